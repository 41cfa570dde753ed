//! Fitting the display model to measurements: Cowan's model (Cowan 1983; the paper's §7.3)
//! as the base, per-channel curves fitted jointly with a 3 × 4 matrix (black flare, as Day,
//! Taplin & Berns 2004 fit LCDs), and a channel-interaction lattice kept only when it lowers
//! the cross-validated error ([`lattice`], [`select`]); bad readings are found and dropped
//! ([`robust`]).
//!
//! The model: `XYZ(r, g, b) = M · (t_R(r), t_G(g), t_B(b)) + K + L(r, g, b)`, with `K` the
//! black (XYZ at device 0, 0, 0; with the least-squares fit, the fitted flare), the columns
//! `P_i` of `M` the primaries at full drive minus black, `t_i` each channel's transfer curve
//! from device value to linear light (`t_i(0) = 0`, `t_i(1) = 1`), and `L` the optional
//! interaction lattice.
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
//!    `MatrixFit::Cowan` stops here (primaries outside the chromaticity triangle are projected
//!    onto it and reported).
//! 4. `MatrixFit::LeastSquares` (the default) alternates, `opts.iterations` rounds:
//!    `[M | K]` by weighted linear least squares over all fit patches given the curves and
//!    `L` (each tristimulus value `v` weighted by `((v/v_white) + 0.01)^(−4/3) / v_white²`,
//!    the square of CIELAB's slope, so errors count about as ΔE counts them; a primary that
//!    would leave the triangle `x ≥ 0, y > 0, x + y ≤ 1` has the offending coefficient held
//!    at the boundary and its row re-solved); with table curves, the 3 × 63 table values given
//!    `M`, `K` and `L` (linear in them: `t(0) = 0`, a light second-difference penalty,
//!    monotone, rescaled so `t(1) = 1`); then `L` given the rest. A shaper/matrix fit like
//!    ArgyllCMS's `colprof -as`, plus the lattice.
//! 5. Which lattice (none, 2, 5, 7 or 9 nodes a side) is chosen by 5-fold cross-validation on
//!    the fit patches ([`select`]); then patches far off the fitted model are dropped as bad
//!    readings and the choice and fit repeated ([`robust`]).
//! 6. Additivity (Cowan's other assumption): the measured white against
//!    `XYZ(R) + XYZ(G) + XYZ(B) − 2·K`, as ΔE00 (CIELAB relative to the measured white) and as
//!    the luminance difference in percent.

pub use specpoly_display::lattice;
pub mod locus;
pub mod provenance;
pub mod robust;
pub mod select;

use crate::error::{Error, Result};
use crate::readings::check_readings;
use crate::verify;
use specpoly_display::calibration::{
    Calibration, CalibrationData, FitReport, Primaries, Primary, Provenance, TransferCurves,
    TransferKind, FORMAT, VERSION,
};
use specpoly_formats::measurement::Measurement;
use specpoly_formats::stats::Stats;

/// How the matrix `M` is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MatrixFit {
    /// Cowan: the full-drive primaries minus black.
    Cowan,
    /// Weighted linear least squares over every fit patch (needs mixtures among them).
    #[default]
    LeastSquares,
}

/// Whether the fit adds a channel-interaction lattice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum InteractionChoice {
    /// Chosen by cross-validation among none and lattices of 2, 5, 7 and 9 nodes a side.
    #[default]
    Auto,
    /// The matrix model alone.
    None,
    /// A lattice of this many nodes a side (2–[`lattice::MAX_GRID`]).
    Grid(usize),
}

impl std::str::FromStr for InteractionChoice {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "none" => Ok(Self::None),
            n => match n.parse::<usize>() {
                Ok(g) if (2..=lattice::MAX_GRID).contains(&g) => Ok(Self::Grid(g)),
                _ => Err(format!(
                    "`{n}` is not auto, none or a lattice size 2–{}",
                    lattice::MAX_GRID
                )),
            },
        }
    }
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
    /// With the least-squares matrix: rounds of fitting `[M | K]`, the tables and the lattice
    /// in turn.
    pub iterations: usize,
    /// The interaction lattice (least-squares matrix only).
    pub interaction: InteractionChoice,
    /// Whether bad readings are found and dropped (least-squares matrix only).
    pub robust: bool,
    /// The observer the measurements' XYZ are under (an instrument's: CIE 1931; another when
    /// they were computed from spectra, `spectral_display::xyz_under`): the primaries are kept
    /// inside its spectral locus.
    pub observer: specpoly_core::Observer,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            transfer: TransferKind::Table,
            matrix: MatrixFit::LeastSquares,
            table_points: specpoly_core::display::TABLE_MAX,
            absolute: true,
            iterations: 4,
            interaction: InteractionChoice::Auto,
            robust: true,
            observer: specpoly_core::Observer::Cie1931,
        }
    }
}

/// Every how many patches [`hold_out`] holds one out: 5, so the fit sees 4/5 of them.
pub const HOLD_OUT_EVERY: usize = 5;

/// Splits measurements for a hold-out check: every ramp patch (black, white, single-channel
/// steps) to the fit; of the remaining patches, every [`HOLD_OUT_EVERY`]-th (the 5th, 10th, …)
/// to verification and the others to the fit, in order.
pub fn hold_out(meas: Vec<Measurement>) -> (Vec<Measurement>, Vec<Measurement>) {
    let (f, v) = hold_out_indices(&meas);
    (
        f.iter().map(|i| meas[*i]).collect(),
        v.iter().map(|i| meas[*i]).collect(),
    )
}

/// [`hold_out`]'s split as positions in `meas`: (fit, verification).
pub fn hold_out_indices(meas: &[Measurement]) -> (Vec<usize>, Vec<usize>) {
    let (mut fit, mut verify) = (Vec::new(), Vec::new());
    let mut k = 0;
    for (i, m) in meas.iter().enumerate() {
        if is_ramp(m) {
            fit.push(i);
        } else {
            k += 1;
            if k % HOLD_OUT_EVERY == 0 {
                verify.push(i)
            } else {
                fit.push(i)
            }
        }
    }
    (fit, verify)
}

/// Whether a patch is one the model cannot do without: black or a single channel at full
/// drive (the cross-validation keeps them in every fold; they are never dropped as outliers).
pub fn is_anchor(m: &Measurement) -> bool {
    let zeros = m.device.iter().filter(|v| **v <= 1e-9).count();
    let full = m.device.iter().filter(|v| **v >= 1.0 - 1e-9).count();
    zeros == 3 || (zeros == 2 && full == 1) || full == 3
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

/// Fits the model to measurements (device values 0–1, XYZ in cd/m² or relative — say which in
/// `opts.absolute`). Needs black `(0,0,0)` and the three full-drive primaries; the ramps
/// give the curves. The returned calibration's provenance is empty except for the patch
/// counts; the caller fills in the source. Its report says which model was chosen, which
/// patches were dropped and which primaries were constrained.
pub fn fit(meas: &[Measurement], opts: &FitOptions) -> Result<Calibration> {
    check_input(meas, opts)?;
    let (mut cal, set) = if opts.matrix == MatrixFit::Cowan {
        (fit_model(meas, opts, None)?, meas.to_vec())
    } else {
        robust::fit_robust(meas, opts)?
    };
    let g = groups(&set);
    let (black, p) = primaries(&g)?;
    let white = find(&g, [1.0; 3]);
    let residual = Stats::of(&verify::delta_e(&cal, &set));
    let (additivity_delta_e00, additivity_luminance_percent) = match white {
        Some(w) => {
            let pred = [0, 1, 2].map(|r| p[0][r] + p[1][r] + p[2][r] + black[r]);
            (
                Some(specpoly_core::delta_e2000_xyz(pred, w, w)),
                Some((pred[1] / w[1] - 1.0) * 100.0),
            )
        }
        None => (None, None),
    };
    let (report, prov) = cal.report_mut();
    report.residual = residual;
    report.additivity_delta_e00 = additivity_delta_e00;
    report.additivity_luminance_percent = additivity_luminance_percent;
    prov.patches_fit = set.len();
    prov.patches_total = meas.len();
    prov.created = specpoly_display::calibration::now_utc();
    Ok(cal)
}

/// The name of a model in the report: `"shaper-matrix"` or `"shaper-matrix + lattice N"`
/// (`"gamma-matrix"` with power-law curves; `"cowan"` for the pure model).
pub fn model_name(opts: &FitOptions, grid: Option<usize>) -> String {
    let base = match (opts.matrix, opts.transfer) {
        (MatrixFit::Cowan, _) => "cowan",
        (_, TransferKind::Table) => "shaper-matrix",
        (_, TransferKind::Gamma) => "gamma-matrix",
    };
    match grid {
        Some(g) => format!("{base} + lattice {g}"),
        None => base.to_string(),
    }
}

/// Fits one model (`grid`: the interaction lattice's side, if any) to `meas` with no
/// outlier test: the calibration, its report holding the model name and any constrained
/// primaries.
pub fn fit_model(
    meas: &[Measurement],
    opts: &FitOptions,
    grid: Option<usize>,
) -> Result<Calibration> {
    let g = groups(meas);
    let (black, p) = primaries(&g)?;
    let (tables, gamma) = curves(&g, black, p, opts.table_points);
    let white = find(&g, [1.0; 3]);
    let model = Model { opts, white, gamma };
    let mut cal = if opts.matrix == MatrixFit::LeastSquares {
        model.joint(&g, p, black, tables, grid)?
    } else {
        let mut p = p;
        let notes = project_primaries(&mut p);
        let mut cal = model.calibration(p, black, &tables, None, "cowan")?;
        cal.report_mut().0.constrained.splice(0..0, notes);
        cal
    };
    // a lattice whose system could not be solved is left out: name what was fitted
    let fitted = grid.filter(|_| cal.has_interaction());
    cal.report_mut().0.model = model_name(opts, fitted);
    Ok(cal)
}

const NAMES: [&str; 3] = ["red", "green", "blue"];

/// The chromaticity of a primary's XYZ, for messages.
fn xy_of(p: [f64; 3]) -> (f64, f64) {
    let s = p[0] + p[1] + p[2];
    (p[0] / s, p[1] / s)
}

/// Brings measured primaries (columns) into the chromaticity triangle `x ≥ 0`, `y > 0`,
/// `x + y ≤ 1` by setting a negative X or Z to 0 (the nearest point on that edge with the
/// same other components); one sentence per primary moved.
fn project_primaries(p: &mut [[f64; 3]; 3]) -> Vec<String> {
    let mut notes = Vec::new();
    for c in 0..3 {
        if p[c][0] < 0.0 || p[c][2] < 0.0 {
            let (x, y) = xy_of(p[c]);
            p[c][0] = p[c][0].max(0.0);
            p[c][2] = p[c][2].max(0.0);
            let (x2, y2) = xy_of(p[c]);
            notes.push(format!(
                "the {} primary measured at x = {x:.4}, y = {y:.4} (x + y = {:.4}) is outside the chromaticity triangle: moved to x = {x2:.4}, y = {y2:.4}",
                NAMES[c],
                x + y
            ));
        }
    }
    notes
}

/// A usage error for a bad table size, a data error for a measurement that is not finite or
/// beyond [`crate::readings::MAX_READING`] ([`check_readings`]).
fn check_input(meas: &[Measurement], opts: &FitOptions) -> Result<()> {
    if !(2..=specpoly_core::display::TABLE_MAX).contains(&opts.table_points) {
        return Err(Error::TablePoints {
            points: opts.table_points,
            max: specpoly_core::display::TABLE_MAX,
        });
    }
    check_readings(meas)
}

/// Black and the three primaries' XYZ at full drive minus black (Cowan 1983), from the
/// grouped patches.
fn primaries(g: &[Measurement]) -> Result<([f64; 3], [[f64; 3]; 3])> {
    let black = find(g, [0.0; 3]).ok_or(Error::NoBlack)?;
    let names = ["red", "green", "blue"];
    let mut p = [[0.0; 3]; 3];
    for c in 0..3 {
        let mut dev = [0.0; 3];
        dev[c] = 1.0;
        let full = find(g, dev).ok_or(Error::NoFullDrive {
            channel: names[c],
            device: dev,
        })?;
        p[c] = sub(full, black);
        if p[c][1] <= 0.0 || p[c].iter().sum::<f64>() <= 0.0 {
            return Err(Error::DarkPrimary { channel: names[c] });
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
            // max/min rather than clamp: a NaN from degenerate data must not panic
            t[i] = t[i].max(t[i - 1]).min(1.0);
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

/// What every candidate calibration of one fit shares: options, the measured white and the
/// power-law gammas.
struct Model<'a> {
    opts: &'a FitOptions,
    white: Option<[f64; 3]>,
    gamma: [f64; 3],
}

impl Model<'_> {
    /// The calibration with primaries `p` (columns, as XYZ), black `k`, curves `tables` and
    /// lattice `lattice`, its matrix found by `matrix`.
    fn calibration(
        &self,
        p: [[f64; 3]; 3],
        k: [f64; 3],
        tables: &[Vec<f64>; 3],
        lattice: Option<lattice::Lattice>,
        matrix: &str,
    ) -> Result<Calibration> {
        // physically possible primaries: inside the spectral locus
        let mut p = p;
        let locus_notes = locus::constrain(&mut p, self.opts.observer);
        let prim = p.map(Primary::from_xyz);
        let model_white = [0, 1, 2].map(|r| p[0][r] + p[1][r] + p[2][r] + k[r]);
        Ok(Calibration::new(CalibrationData {
            format: FORMAT.into(),
            version: VERSION,
            units: if self.opts.absolute {
                "cd/m2"
            } else {
                "relative"
            }
            .into(),
            black: k,
            white: self.white.unwrap_or(model_white),
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
            interaction: lattice,
            fit: FitReport {
                matrix: matrix.into(),
                constrained: locus_notes,
                ..Default::default()
            },
            provenance: Provenance::default(),
        })?)
    }

    /// Each channel's linear light at `dev` under the current curves.
    fn linear(&self, tables: &[Vec<f64>; 3], dev: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|c| {
            let v = dev[c].clamp(0.0, 1.0);
            match self.opts.transfer {
                TransferKind::Gamma => v.powf(self.gamma[c]),
                TransferKind::Table => {
                    let t = &tables[c];
                    let n = t.len();
                    let x = v * (n - 1) as f64;
                    let i = (x as usize).min(n - 2);
                    let f = x - i as f64;
                    t[i] + (t[i + 1] - t[i]) * f
                }
            }
        })
    }

    /// The joint fit (module docs, step 4): `[M | K]`, the tables and the lattice of side
    /// `grid` in turn, `opts.iterations` rounds, from the ramp curves `tables`.
    fn joint(
        &self,
        g: &[Measurement],
        p: [[f64; 3]; 3],
        black: [f64; 3],
        mut tables: [Vec<f64>; 3],
        grid: Option<usize>,
    ) -> Result<Calibration> {
        let no_span = || Error::NoSpan;
        let wxyz = self
            .white
            .unwrap_or([0, 1, 2].map(|r| p[0][r] + p[1][r] + p[2][r] + black[r]));
        let mut lat: Option<lattice::Lattice> = None;
        let (mut m, mut k) = (p, black);
        let mut notes = Vec::new();
        let mut first_notes: Vec<String> = Vec::new();
        for _ in 0..self.opts.iterations.max(1) {
            // the measurements less the lattice: what the matrix model must explain
            let target: Vec<Measurement> = g
                .iter()
                .map(|x| {
                    let l = lat.as_ref().map_or([0.0; 3], |l| l.eval(x.device));
                    Measurement {
                        device: x.device,
                        xyz: sub(x.xyz, l),
                    }
                })
                .collect();
            let lin: Vec<[f64; 3]> = g.iter().map(|x| self.linear(&tables, x.device)).collect();
            (m, k, notes) = lsq_affine(g, &target, &lin, wxyz).ok_or_else(no_span)?;
            // the first round's unconstrained primaries say best how far out the data put
            // them (later rounds start from curves fitted with the constraint)
            if first_notes.is_empty() {
                first_notes.clone_from(&notes);
            }
            if self.opts.transfer == TransferKind::Table {
                if let Some((t, m2)) = refit_tables(g, &target, m, k, wxyz, self.opts.table_points)
                {
                    tables = t;
                    m = m2;
                }
            }
            if let Some(side) = grid {
                let samples: Vec<lattice::Sample> = g
                    .iter()
                    .map(|x| {
                        let t = self.linear(&tables, x.device);
                        let pred = [0, 1, 2]
                            .map(|r| m[0][r] * t[0] + m[1][r] * t[1] + m[2][r] * t[2] + k[r]);
                        lattice::Sample {
                            device: x.device,
                            residual: sub(x.xyz, pred),
                            weight: [0, 1, 2].map(|r| patch_weight(x, r, wxyz)),
                        }
                    })
                    .collect();
                lat = lattice::fit(side, &samples);
            }
        }
        let mut cal = self.calibration(m, k, &tables, lat, "least-squares")?;
        if !notes.is_empty() {
            cal.report_mut().0.constrained.splice(0..0, first_notes);
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

/// How much more the black and white patches count than the others: the white is the
/// reference of every ΔE and of an ICC profile, the black its other end. With 10 the model's
/// white lands within 0.1 ΔE00 of the measured one on the shipped displays (0.5 with 1), at
/// no cost to the held-out error (docs/calibration.md).
pub const ANCHOR_WEIGHT: f64 = 10.0;

/// The weight of patch `m`'s error in tristimulus component `r` ([`weight`], times
/// [`ANCHOR_WEIGHT`] for black and white).
fn patch_weight(m: &Measurement, r: usize, white: [f64; 3]) -> f64 {
    let d = m.device;
    let anchor = d.iter().all(|v| *v <= 1e-9) || d.iter().all(|v| *v >= 1.0 - 1e-9);
    let w = weight(m.xyz[r], white[r]);
    if anchor {
        w * ANCHOR_WEIGHT
    } else {
        w
    }
}

/// Weighted least-squares `[M | K]` (columns of `M`, then the flare `K`) given each patch's
/// linear light `lin` and the XYZ to explain `target` (weights from the measured `g`). A
/// primary outside the chromaticity triangle (`X < 0`, `Z < 0`: `x < 0`, `x + y > 1`; or
/// `Y ≤ 0`) has that coefficient held at the boundary (0, or 10⁻⁶ of the white's `Y`) and
/// its row re-solved; the sentences say which.
#[allow(clippy::type_complexity)]
fn lsq_affine(
    g: &[Measurement],
    target: &[Measurement],
    lin: &[[f64; 3]],
    white: [f64; 3],
) -> Option<([[f64; 3]; 3], [f64; 3], Vec<String>)> {
    // fixed[r][c]: coefficient of channel c in row r held at a value
    let mut fixed: [[Option<f64>; 3]; 3] = [[None; 3]; 3];
    let mut first: Option<[[f64; 3]; 3]> = None;
    for _ in 0..4 {
        let mut rows = [[0.0; 4]; 3];
        for r in 0..3 {
            let free: Vec<usize> = (0..3).filter(|c| fixed[r][*c].is_none()).collect();
            let u = free.len() + 1;
            let mut a = vec![vec![0.0; u]; u];
            let mut b = vec![0.0; u];
            for ((m, t), l) in g.iter().zip(target).zip(lin) {
                let w = patch_weight(m, r, white);
                let mut y = t.xyz[r];
                for c in 0..3 {
                    if let Some(v) = fixed[r][c] {
                        y -= v * l[c];
                    }
                }
                let mut x: Vec<f64> = free.iter().map(|c| l[*c]).collect();
                x.push(1.0);
                for i in 0..u {
                    b[i] += w * x[i] * y;
                    for j in 0..u {
                        a[i][j] += w * x[i] * x[j];
                    }
                }
            }
            let sol = solve_dense(a, b)?;
            for (i, c) in free.iter().enumerate() {
                rows[r][*c] = sol[i];
            }
            for c in 0..3 {
                if let Some(v) = fixed[r][c] {
                    rows[r][c] = v;
                }
            }
            rows[r][3] = sol[u - 1];
        }
        let m = [0, 1, 2].map(|c| [rows[0][c], rows[1][c], rows[2][c]]);
        let k = [rows[0][3], rows[1][3], rows[2][3]];
        first.get_or_insert(m);
        let mut changed = false;
        for c in 0..3 {
            if m[c][1] <= 0.0 && fixed[1][c].is_none() {
                fixed[1][c] = Some(1e-6 * white[1].abs());
                changed = true;
            }
            for r in [0, 2] {
                if m[c][r] < 0.0 && fixed[r][c].is_none() {
                    fixed[r][c] = Some(0.0);
                    changed = true;
                }
            }
        }
        if !changed {
            let notes = (0..3)
                .filter(|c| (0..3).any(|r| fixed[r][*c].is_some()))
                .map(|c| {
                    let f = first.unwrap_or(m)[c];
                    let (x, y) = xy_of(f);
                    let (x2, y2) = xy_of(m[c]);
                    format!(
                        "the fitted {} primary x = {x:.4}, y = {y:.4} (x + y = {:.4}) is outside the chromaticity triangle: refitted on its edge, x = {x2:.4}, y = {y2:.4}",
                        NAMES[c],
                        x + y
                    )
                })
                .collect();
            return Some((m, k, notes));
        }
    }
    None
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
    target: &[Measurement],
    m: [[f64; 3]; 3],
    black: [f64; 3],
    white: [f64; 3],
    n: usize,
) -> Option<([Vec<f64>; 3], [[f64; 3]; 3])> {
    // unknowns: channel c, node k = 1..n-1 → index c·(n−1) + k − 1
    let u = 3 * (n - 1);
    let mut a = vec![vec![0.0; u]; u];
    let mut b = vec![0.0; u];
    for (p, tp) in g.iter().zip(target) {
        let y = sub(tp.xyz, black);
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
            let w = patch_weight(p, r, white);
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
