//! Fitting Cowan's model (Cowan 1983; the paper's §7.3) to display measurements.
//!
//! The model: `XYZ(r, g, b) = M · (t_R(r), t_G(g), t_B(b)) + K`, with `K` the black (XYZ at
//! device 0, 0, 0), the columns `P_i` of `M` the primaries at full drive minus black, and
//! `t_i` each channel's transfer curve from device value to linear light (`t_i(0) = 0`,
//! `t_i(1) = 1`).
//!
//! 1. Repeated device values are averaged. `K` is the mean of the `(0, 0, 0)` patches; `P_i`
//!    the mean of the full-drive single-channel patches minus `K`.
//! 2. Each channel's ramp (patches where the other two channels are 0) gives
//!    `t_i(v) = ((XYZ(v) − K) · P_i) / |P_i|²`, the least-squares scale of `P_i` that best
//!    explains the ramp patch (Cowan's scalar-channel assumption: the primary's chromaticity
//!    does not change with drive once black is removed).
//! 3. The table: the ramp interpolated with a monotone cubic (Fritsch & Carlson 1980) and
//!    resampled at `n ≤ 64` evenly spaced device values (what `specpoly-core` tabulates),
//!    forced non-decreasing. The gamma: the exponent of `v^γ` nearest the ramp in least squares.
//! 4. Optionally (`MatrixFit::LeastSquares`) `M` is re-fitted by linear least squares over all
//!    fit patches, given their linearised drive and `K`: `M = argmin Σ w ‖XYZ − K − M·t‖²`,
//!    each tristimulus value `v` weighted by `((v/v_white) + 0.01)^(−4/3) / v_white²` (the
//!    square of CIELAB's slope, so errors count about as ΔE counts them). With the table
//!    transfer, the tables are then re-fitted over all fit patches given `M` (the model is
//!    linear in the table values), with `t(0) = 0`, a light second-difference penalty and
//!    monotonicity, and `M` again given the tables, three rounds: a shaper/matrix fit like
//!    ArgyllCMS's `colprof -as`. It absorbs the channel interaction of LCDs that the pure
//!    full-drive matrix misses; see docs/calibration.md for the figures.
//! 5. Additivity (Cowan's other assumption): the measured white against
//!    `XYZ(R) + XYZ(G) + XYZ(B) − 2·K`, as ΔE00 (CIELAB relative to the measured white) and as
//!    the luminance difference in percent.

use super::file::{
    Calibration, CalibrationData, FitReport, Primaries, Primary, Provenance, TransferCurves,
    TransferKind, FORMAT, VERSION,
};
use super::verify;
use crate::error::{CliError, Result};
use crate::measurement::Measurement;
use crate::stats::Stats;

/// How the matrix `M` is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum MatrixFit {
    /// Cowan: the full-drive primaries minus black.
    Cowan,
    /// Weighted linear least squares over every fit patch (needs mixtures among them).
    #[default]
    #[value(name = "least-squares")]
    LeastSquares,
}

/// Fit options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// The transfer curve the model uses (both are always fitted and stored).
    pub transfer: TransferKind,
    /// How the matrix is found.
    pub matrix: MatrixFit,
    /// Points of each transfer table (2–64).
    pub table_points: usize,
    /// Whether the measurements are in cd/m² (else relative, white `Y = 100`).
    pub absolute: bool,
    /// With a table transfer and the least-squares matrix: rounds of re-fitting the tables
    /// over every fit patch given the matrix, then the matrix given the tables.
    pub iterations: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            transfer: TransferKind::Table,
            matrix: MatrixFit::LeastSquares,
            table_points: specpoly_core::display::TABLE_MAX,
            absolute: true,
            iterations: 3,
        }
    }
}

/// Splits measurements for a hold-out check: every ramp patch (black, white, single-channel
/// steps) and every other remaining patch to the fit, the rest to verification, in order.
pub fn hold_out(meas: Vec<Measurement>) -> (Vec<Measurement>, Vec<Measurement>) {
    let (mut fit, mut verify) = (Vec::new(), Vec::new());
    let mut k = 0;
    for m in meas {
        if is_ramp(&m) {
            fit.push(m);
        } else {
            if k % 2 == 0 {
                fit.push(m)
            } else {
                verify.push(m)
            }
            k += 1;
        }
    }
    (fit, verify)
}

/// Whether a patch is one the pure Cowan model is built from: black, white, or a
/// single-channel ramp step.
pub fn is_ramp(m: &Measurement) -> bool {
    let zeros = m.device.iter().filter(|v| **v <= 1e-9).count();
    zeros >= 2 || m.device.iter().all(|v| *v >= 1.0 - 1e-9)
}

/// Averages repeated device values (device values equal to 1e-6).
fn groups(meas: &[Measurement]) -> Vec<Measurement> {
    let key = |m: &Measurement| m.device.map(|v| (v * 1e6).round() as i64);
    let mut keys: Vec<([i64; 3], [f64; 3], usize)> = Vec::new();
    let mut index = std::collections::HashMap::new();
    for m in meas {
        let k = key(m);
        let i = *index.entry(k).or_insert_with(|| {
            keys.push((k, [0.0; 3], 0));
            keys.len() - 1
        });
        for c in 0..3 {
            keys[i].1[c] += m.xyz[c];
        }
        keys[i].2 += 1;
    }
    keys.into_iter()
        .map(|(k, s, n)| Measurement {
            device: k.map(|v| v as f64 / 1e6),
            xyz: s.map(|v| v / n as f64),
        })
        .collect()
}

fn find(g: &[Measurement], dev: [f64; 3]) -> Option<[f64; 3]> {
    g.iter()
        .find(|m| (0..3).all(|c| (m.device[c] - dev[c]).abs() < 1e-9))
        .map(|m| m.xyz)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Monotone piecewise-cubic interpolation (Fritsch & Carlson 1980) through `(x, y)`, `x`
/// strictly increasing, evaluated at `t`.
pub fn pchip(x: &[f64], y: &[f64], t: f64) -> f64 {
    let n = x.len();
    if n == 1 {
        return y[0];
    }
    let t = t.clamp(x[0], x[n - 1]);
    let k = x.partition_point(|v| *v <= t).clamp(1, n - 1) - 1;
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let slope = |i: usize| -> f64 {
        if i == 0 {
            d[0]
        } else if i == n - 1 {
            d[n - 2]
        } else if d[i - 1] * d[i] <= 0.0 {
            0.0
        } else {
            let w1 = 2.0 * h[i] + h[i - 1];
            let w2 = h[i] + 2.0 * h[i - 1];
            (w1 + w2) / (w1 / d[i - 1] + w2 / d[i])
        }
    };
    let (m0, m1) = (slope(k), slope(k + 1));
    let s = (t - x[k]) / h[k];
    let (s2, s3) = (s * s, s * s * s);
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    h00 * y[k] + h10 * h[k] * m0 + h01 * y[k + 1] + h11 * h[k] * m1
}

/// The exponent of `v^γ` nearest the points in least squares (golden-section search on
/// `γ ∈ [0.3, 6]`).
fn fit_gamma(v: &[f64], l: &[f64]) -> f64 {
    let cost = |g: f64| -> f64 { v.iter().zip(l).map(|(v, l)| (v.powf(g) - l).powi(2)).sum() };
    let (mut a, mut b) = (0.3f64, 6.0f64);
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if cost(c) < cost(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

/// Solves the 3×3 system `A x = b` (f64, [`specpoly_core::solve`]); `None` if singular.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    specpoly_core::solve::solve(a.as_flattened_mut(), &mut b).ok()?;
    Some(b)
}

/// Fits the model to measurements (device values 0–1, XYZ in cd/m² or relative — say which in
/// `opts.absolute`). Needs black `(0,0,0)` and the three full-drive primaries; the ramps
/// give the curves. The returned calibration's provenance is empty except for the patch
/// counts; the caller fills in the source.
pub fn fit(meas: &[Measurement], opts: &FitOptions) -> Result<Calibration> {
    check_input(meas, opts)?;
    let g = groups(meas);
    let (black, p) = primaries(&g)?;
    let (tables, gamma) = curves(&g, black, p, opts.table_points);
    let white = find(&g, [1.0; 3]);
    let model = Model {
        opts,
        black,
        white,
        gamma,
    };
    let mut cal = model.calibration(p, &tables, "cowan")?;
    if opts.matrix == MatrixFit::LeastSquares {
        cal = model.least_squares(&cal, &g, p, tables)?;
    }
    let residual = Stats::of(&verify::delta_e(&cal, meas));
    let (additivity_delta_e00, additivity_luminance_percent) = match white {
        Some(w) => {
            let pred = model.white_of(p);
            (
                Some(verify::delta_e00(pred, w, w)),
                Some((pred[1] / w[1] - 1.0) * 100.0),
            )
        }
        None => (None, None),
    };
    let (report, prov) = cal.report_mut();
    report.residual = residual;
    report.additivity_delta_e00 = additivity_delta_e00;
    report.additivity_luminance_percent = additivity_luminance_percent;
    prov.patches_fit = meas.len();
    prov.patches_total = meas.len();
    prov.created = super::file::now_utc();
    Ok(cal)
}

/// A usage error for a bad table size, a data error for a measurement that is not finite.
fn check_input(meas: &[Measurement], opts: &FitOptions) -> Result<()> {
    if !(2..=specpoly_core::display::TABLE_MAX).contains(&opts.table_points) {
        return Err(CliError::usage(format!(
            "table points {} must be 2–{}",
            opts.table_points,
            specpoly_core::display::TABLE_MAX
        )));
    }
    if let Some(i) = meas
        .iter()
        .position(|m| m.device.iter().chain(&m.xyz).any(|v| !v.is_finite()))
    {
        return Err(CliError::data(format!(
            "measurement {} is not finite",
            i + 1
        )));
    }
    Ok(())
}

/// Black and the three primaries' XYZ at full drive minus black (Cowan 1983), from the
/// grouped patches.
fn primaries(g: &[Measurement]) -> Result<([f64; 3], [[f64; 3]; 3])> {
    let black = find(g, [0.0; 3]).ok_or_else(|| {
        CliError::data("no black patch (device 0 0 0): Cowan's model needs the black level")
    })?;
    let names = ["red", "green", "blue"];
    let mut p = [[0.0; 3]; 3];
    for c in 0..3 {
        let mut dev = [0.0; 3];
        dev[c] = 1.0;
        let full = find(g, dev).ok_or_else(|| {
            CliError::data(format!(
                "no full-drive {} patch (device {} {} {})",
                names[c], dev[0], dev[1], dev[2]
            ))
        })?;
        p[c] = sub(full, black);
        if p[c][1] <= 0.0 || p[c].iter().sum::<f64>() <= 0.0 {
            return Err(CliError::data(format!(
                "the full-drive {} patch is not brighter than black",
                names[c]
            )));
        }
    }
    Ok((black, p))
}

/// Each channel's transfer table (`n` points, monotone, 0 and 1 at the ends: PCHIP through the
/// ramp's linear light along its primary) and its best pure power law.
fn curves(
    g: &[Measurement],
    black: [f64; 3],
    p: [[f64; 3]; 3],
    n: usize,
) -> ([Vec<f64>; 3], [f64; 3]) {
    let mut tables: [Vec<f64>; 3] = Default::default();
    let mut gamma = [0.0; 3];
    for c in 0..3 {
        let mut pts: Vec<(f64, f64)> = g
            .iter()
            .filter(|m| (0..3).all(|k| k == c || m.device[k] <= 1e-9))
            .map(|m| (m.device[c], dot(sub(m.xyz, black), p[c]) / dot(p[c], p[c])))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (x, y): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
        let mut t: Vec<f64> = (0..n)
            .map(|i| pchip(&x, &y, i as f64 / (n - 1) as f64))
            .collect();
        t[0] = 0.0;
        t[n - 1] = 1.0;
        for i in 1..n {
            t[i] = t[i].clamp(t[i - 1], 1.0);
        }
        tables[c] = t;
        let inner: Vec<usize> = (0..x.len())
            .filter(|i| x[*i] > 0.0 && x[*i] < 1.0)
            .collect();
        gamma[c] = if inner.is_empty() {
            1.0
        } else {
            fit_gamma(
                &inner.iter().map(|i| x[*i]).collect::<Vec<_>>(),
                &inner.iter().map(|i| y[*i]).collect::<Vec<_>>(),
            )
        };
    }
    (tables, gamma)
}

/// What every candidate calibration of one fit shares: options, black, the measured white
/// and the power-law gammas.
struct Model<'a> {
    opts: &'a FitOptions,
    black: [f64; 3],
    white: Option<[f64; 3]>,
    gamma: [f64; 3],
}

impl Model<'_> {
    /// The white the model predicts for primaries `p`: their sum plus black.
    fn white_of(&self, p: [[f64; 3]; 3]) -> [f64; 3] {
        [0, 1, 2].map(|r| p[0][r] + p[1][r] + p[2][r] + self.black[r])
    }

    /// The calibration with primaries `p` (as XYZ) and curves `tables`, its matrix found by
    /// `matrix`.
    fn calibration(
        &self,
        p: [[f64; 3]; 3],
        tables: &[Vec<f64>; 3],
        matrix: &str,
    ) -> Result<Calibration> {
        let prim = p.map(Primary::from_xyz);
        Calibration::new(CalibrationData {
            format: FORMAT.into(),
            version: VERSION,
            units: if self.opts.absolute {
                "cd/m2"
            } else {
                "relative"
            }
            .into(),
            black: self.black,
            white: self.white.unwrap_or(self.white_of(p)),
            primaries: Primaries {
                red: prim[0],
                green: prim[1],
                blue: prim[2],
            },
            transfer: TransferCurves {
                kind: self.opts.transfer,
                gamma: self.gamma,
                red: tables[0].clone(),
                green: tables[1].clone(),
                blue: tables[2].clone(),
            },
            fit: FitReport {
                matrix: matrix.into(),
                ..Default::default()
            },
            provenance: Provenance::default(),
        })
    }

    /// The weighted least-squares matrix over every patch, starting from `cowan`'s curves;
    /// with tabulated curves, alternately refits the tables given the matrix and the matrix
    /// given the tables (a shaper/matrix fit), `opts.iterations` times.
    fn least_squares(
        &self,
        cowan: &Calibration,
        g: &[Measurement],
        p: [[f64; 3]; 3],
        mut tables: [Vec<f64>; 3],
    ) -> Result<Calibration> {
        let no_span =
            || CliError::data("least-squares matrix: the fit patches do not span three channels");
        let wxyz = self.white.unwrap_or(self.white_of(p));
        let lsq = lsq_matrix(cowan, g, self.black, wxyz).ok_or_else(no_span)?;
        let mut cal = self.calibration(lsq, &tables, "least-squares")?;
        if self.opts.transfer == TransferKind::Table {
            let mut m = lsq;
            for _ in 0..self.opts.iterations {
                let Some(t) = refit_tables(g, m, self.black, wxyz, self.opts.table_points) else {
                    break;
                };
                tables = t.0;
                m = t.1;
                cal = self.calibration(m, &tables, "least-squares")?;
                m = lsq_matrix(&cal, g, self.black, wxyz).ok_or_else(no_span)?;
                cal = self.calibration(m, &tables, "least-squares")?;
            }
        }
        Ok(cal)
    }
}

/// Fits on `fit_set` and verifies on `verify_set` (may be empty), recording both in the
/// report and the provenance's patch counts.
pub fn fit_and_verify(
    fit_set: &[Measurement],
    verify_set: &[Measurement],
    opts: &FitOptions,
) -> Result<Calibration> {
    let mut cal = fit(fit_set, opts)?;
    let v = if verify_set.is_empty() {
        None
    } else {
        Some(Stats::of(&verify::delta_e(&cal, verify_set)))
    };
    let (report, prov) = cal.report_mut();
    report.verification = v;
    prov.patches_verify = verify_set.len();
    prov.patches_total = fit_set.len() + verify_set.len();
    Ok(cal)
}

/// The weight of a squared error in tristimulus value `v` (the white's is `w`): CIELAB's
/// `f(t) = t^(1/3)` has slope `t^(−2/3) / 3`, so an error `dv` moves L*, a*, b* by about
/// `(v/w)^(−2/3) dv / w`; its square is the weight (floored at 1 % of white, near CIELAB's
/// linear toe).
fn weight(v: f64, w: f64) -> f64 {
    ((v / w).max(0.0) + 0.01).powf(-4.0 / 3.0) / (w * w)
}

/// Weighted least-squares `M` given the calibration's curves and black.
fn lsq_matrix(
    cal: &Calibration,
    g: &[Measurement],
    black: [f64; 3],
    white: [f64; 3],
) -> Option<[[f64; 3]; 3]> {
    // one weighted least-squares problem per row r of M (X, Y, Z)
    let mut a = [[[0.0; 3]; 3]; 3];
    let mut b = [[0.0; 3]; 3];
    for m in g {
        let t = cal.linearise(m.device);
        let y = sub(m.xyz, black);
        for r in 0..3 {
            let w = weight(m.xyz[r], white[r]);
            for i in 0..3 {
                for j in 0..3 {
                    a[r][i][j] += w * t[i] * t[j];
                }
                b[r][i] += w * t[i] * y[r];
            }
        }
    }
    let rows: Option<Vec<[f64; 3]>> = (0..3).map(|r| solve3(a[r], b[r])).collect();
    let rows = rows?;
    Some([0, 1, 2].map(|c| [rows[0][c], rows[1][c], rows[2][c]]))
}

/// Solves a dense system (rows of `a`) with the core's Gaussian elimination
/// ([`specpoly_core::solve`]); `None` if singular or not finite.
fn solve_dense(a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    specpoly_core::solve::solve(&mut a.concat(), &mut b).ok()?;
    b.iter().all(|v| v.is_finite()).then_some(b)
}

/// Given `M` (as columns: `m[channel][xyz]`), the `n`-point tables that minimise the weighted squared XYZ error over all
/// patches (the model is linear in the table values through linear interpolation), with
/// `t(0) = 0` and a small second-difference penalty for nodes few patches touch; then each
/// table is made non-decreasing and scaled so `t(1) = 1`, the scale moving into `M`'s column.
#[allow(clippy::type_complexity)]
fn refit_tables(
    g: &[Measurement],
    m: [[f64; 3]; 3],
    black: [f64; 3],
    white: [f64; 3],
    n: usize,
) -> Option<([Vec<f64>; 3], [[f64; 3]; 3])> {
    // unknowns: channel c, node k = 1..n-1 → index c·(n−1) + k − 1
    let u = 3 * (n - 1);
    let mut a = vec![vec![0.0; u]; u];
    let mut b = vec![0.0; u];
    for p in g {
        let y = sub(p.xyz, black);
        // interpolation weights
        let mut idx: Vec<(usize, usize, f64)> = Vec::with_capacity(6);
        for c in 0..3 {
            let x = p.device[c].clamp(0.0, 1.0) * (n - 1) as f64;
            let j = (x as usize).min(n - 2);
            let f = x - j as f64;
            for (k, wt) in [(j, 1.0 - f), (j + 1, f)] {
                if k > 0 && wt != 0.0 {
                    idx.push((c, c * (n - 1) + k - 1, wt));
                }
            }
        }
        for r in 0..3 {
            let w = weight(p.xyz[r], white[r]);
            for &(c1, i1, w1) in &idx {
                let g1 = m[c1][r] * w1;
                b[i1] += w * g1 * y[r];
                for &(c2, i2, w2) in &idx {
                    a[i1][i2] += w * g1 * m[c2][r] * w2;
                }
            }
        }
    }
    // smoothness: λ Σ (τ_{k−1} − 2τ_k + τ_{k+1})², scaled to the data's size
    let trace: f64 = (0..u).map(|i| a[i][i]).sum::<f64>() / u as f64;
    let lambda = 1e-2 * trace;
    for c in 0..3 {
        for k in 1..n - 1 {
            let terms = [(k - 1, 1.0), (k, -2.0), (k + 1, 1.0)];
            for &(k1, w1) in &terms {
                for &(k2, w2) in &terms {
                    if k1 > 0 && k2 > 0 {
                        a[c * (n - 1) + k1 - 1][c * (n - 1) + k2 - 1] += lambda * w1 * w2;
                    }
                }
            }
        }
    }
    let x = solve_dense(a, b)?;
    let mut tables: [Vec<f64>; 3] = Default::default();
    let mut m2 = m;
    for c in 0..3 {
        let mut t = vec![0.0; n];
        for k in 1..n {
            t[k] = x[c * (n - 1) + k - 1].max(t[k - 1]);
        }
        let s = t[n - 1];
        if s.is_nan() || s <= 0.0 {
            return None;
        }
        for v in &mut t {
            *v /= s;
        }
        for r in 0..3 {
            m2[c][r] *= s;
        }
        tables[c] = t;
    }
    Some((tables, m2))
}
