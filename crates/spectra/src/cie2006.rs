//! The CIE 2006 physiological observer (CIE 170-1:2006) for an age and a field size: cone
//! fundamentals l̄ m̄ s̄ built from the photopigments' absorbance, their optical densities, the
//! macular pigment and the ocular media, and from them x̄ ȳ z̄ by the CIE 170-2:2015 matrices.
//!
//! ## The model (CIE 170-1:2006, §§ 5–6)
//!
//! For age `A` (20–80 years) and field size `f` (2–10°), at each wavelength λ:
//!
//! - peak optical densities of the photopigments, `D_L = D_M = 0.38 + 0.54·e^(−f/1.333)`,
//!   `D_S = 0.30 + 0.45·e^(−f/1.333)`, and of the macular pigment `D_mac = 0.485·e^(−f/6.132)`,
//!   each rounded to 3 decimals as CIE TC1-97's reference code does;
//! - absorptance `αᵢ(λ) = 1 − 10^(−Dᵢ · Aᵢ(λ))` with `Aᵢ` the relative absorbance (tabulated as
//!   `log10 Aᵢ`; the S cone is zero past 615 nm, where CIE 170-1 leaves it undefined);
//! - ocular media density `d_ocul(λ) = d₁(λ)·(1 + 0.02·(A − 32)) + d₂(λ)` up to 60 years and
//!   `d₁(λ)·(1.56 + 0.0667·(A − 60)) + d₂(λ)` beyond (eq. 6.9; `d₁` ages, `d₂` does not);
//! - quantal fundamentals `αᵢ(λ) · 10^(−D_mac·m(λ) − d_ocul(λ))`, `m` the macular density
//!   relative to its peak; energy fundamentals are these times λ, each scaled to peak 1.
//!
//! The tables (`data/cmf/cie2006_model_0_1nm.csv`) are at 0.1 nm over 390–780 nm, as CIE TC1-97
//! tabulates them; the peaks are found on that grid (on a 1 nm grid a peak falls up to 0.5 nm
//! off and the fundamentals would be up to 1.2·10⁻⁴ high), and the 1 nm rows are kept. Below
//! 390 nm the fundamentals are zero, as for the CIE 2015 tables.
//!
//! ## x̄ ȳ z̄
//!
//! CIE 170-2:2015 (also CIE 015:2018, eq. 7.4–7.5) gives the transformation from the energy
//! fundamentals (peak 1) to the cone-fundamental-based x̄ ȳ z̄ for the 2° and 10° observers:
//!
//! ```text
//!  2°:  x̄ = 1.94735469 l̄ − 1.41445123 m̄ + 0.36476327 s̄    10°:  x̄ = 1.93986443 l̄ − 1.34664359 m̄ + 0.43044935 s̄
//!       ȳ = 0.68990272 l̄ + 0.34832189 m̄                            ȳ = 0.69283932 l̄ + 0.34967567 m̄
//!       z̄ = 1.93485343 s̄                                           z̄ = 2.14687945 s̄
//! ```
//!
//! For a field size between, the matrix is interpolated linearly in the field size between
//! these two (as Asano et al. 2016 do with theirs). The matrix is the one of the standard
//! 32-year observer whatever the age: colour matches (metamers) depend on the fundamentals only,
//! and any fixed invertible matrix keeps them; chromaticities and the white's `Y = 100` scale
//! follow this matrix. CIE TC1-97's software instead re-derives a matrix for each age and field
//! (ȳ as that observer's luminous efficiency, x̄ by an optimisation); that procedure is not
//! implemented here, and its x̄ ȳ z̄ differ from ours by up to a few per cent of peak at the
//! ages far from 32 (docs/accuracy.md, "Observers").

use crate::{Error, Result};
use specpoly_core::{observer::CMF_LEN, CmfTable};
use std::sync::OnceLock;

/// The model's input tables at 0.1 nm, 390–780 nm (see data/README.md).
const TABLES: &str = include_str!("../../../data/cmf/cie2006_model_0_1nm.csv");

/// Youngest and oldest age of the model (years).
pub const AGES: (f64, f64) = (20.0, 80.0);
/// Smallest and largest field size (degrees) this implementation takes.
pub const FIELDS: (f64, f64) = (2.0, 10.0);

/// CIE 170-2:2015 fundamentals → XYZ, 2°.
pub const M_2: [[f64; 3]; 3] = [
    [1.947_354_69, -1.414_451_23, 0.364_763_27],
    [0.689_902_72, 0.348_321_89, 0.0],
    [0.0, 0.0, 1.934_853_43],
];
/// CIE 170-2:2015 fundamentals → XYZ, 10°.
pub const M_10: [[f64; 3]; 3] = [
    [1.939_864_43, -1.346_643_59, 0.430_449_35],
    [0.692_839_32, 0.349_675_67, 0.0],
    [0.0, 0.0, 2.146_879_45],
];

/// One row of the model's tables.
struct Row {
    nm: f64,
    /// log10 of the relative absorbance of L, M, S; `None` where undefined (S past 615 nm).
    log_abs: [Option<f64>; 3],
    lens_aging: f64,
    lens_fixed: f64,
    macular: f64,
}

fn tables() -> Result<&'static [Row]> {
    static ROWS: OnceLock<std::result::Result<Vec<Row>, String>> = OnceLock::new();
    ROWS.get_or_init(|| parse(TABLES))
        .as_deref()
        .map_err(|why| Error::Cie2006 {
            spec: "data/cmf/cie2006_model_0_1nm.csv".into(),
            why: why.clone(),
        })
}

fn parse(text: &str) -> std::result::Result<Vec<Row>, String> {
    let mut rows = Vec::with_capacity(3901);
    for (i, line) in text.lines().enumerate().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let num = |k: usize| -> std::result::Result<f64, String> {
            c.get(k)
                .and_then(|s| s.parse::<f64>().ok())
                .ok_or_else(|| format!("line {}: bad cell {}", i + 1, k + 1))
        };
        let opt = |k: usize| -> std::result::Result<Option<f64>, String> {
            match c.get(k) {
                Some(&"") => Ok(None),
                _ => num(k).map(Some),
            }
        };
        rows.push(Row {
            nm: num(0)?,
            log_abs: [opt(1)?, opt(2)?, opt(3)?],
            lens_aging: num(4)?,
            lens_fixed: num(5)?,
            macular: num(6)?,
        });
    }
    // 390.0, 390.1, …, 780.0: the 1 nm rows are every tenth
    let ok = rows.len() == 3901
        && rows
            .iter()
            .enumerate()
            .all(|(i, r)| (r.nm - (390.0 + 0.1 * i as f64)).abs() < 1e-6);
    if ok {
        Ok(rows)
    } else {
        Err("not 390-780 nm at 0.1 nm".into())
    }
}

/// `x` rounded to 3 decimals (CIE TC1-97 rounds the peak densities so).
fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// Checks an age and a field size against the model's range.
fn check(age: f64, field: f64) -> std::result::Result<(), String> {
    if !(age >= AGES.0 && age <= AGES.1) {
        return Err(format!(
            "age {age} outside the model's {}-{} years",
            AGES.0, AGES.1
        ));
    }
    if !(field >= FIELDS.0 && field <= FIELDS.1) {
        return Err(format!(
            "field size {field}° outside {}-{}°",
            FIELDS.0, FIELDS.1
        ));
    }
    Ok(())
}

/// The energy cone fundamentals `[l̄, m̄, s̄]` (each peak 1) at 1 nm over 380..=780 nm (zero
/// below 390 nm) for `age` (years, 20–80) and `field` (degrees, 2–10).
pub fn lms(age: f64, field: f64) -> Result<[[f64; 3]; CMF_LEN]> {
    let spec = || format!("cie2006:age={age},field={field}");
    check(age, field).map_err(|why| Error::Cie2006 { spec: spec(), why })?;
    let rows = tables()?;
    let d_mac = round3(0.485 * (-field / 6.132).exp());
    let d_lm = round3(0.38 + 0.54 * (-field / 1.333).exp());
    let d_s = round3(0.30 + 0.45 * (-field / 1.333).exp());
    let peak_density = [d_lm, d_lm, d_s];
    let aging = if age <= 60.0 {
        1.0 + 0.02 * (age - 32.0)
    } else {
        1.56 + 0.0667 * (age - 60.0)
    };
    let energy: Vec<[f64; 3]> = rows
        .iter()
        .map(|r| {
            let filter = 10f64.powf(-d_mac * r.macular - (r.lens_aging * aging + r.lens_fixed));
            let mut e = [0.0; 3];
            for k in 0..3 {
                if let Some(a) = r.log_abs[k] {
                    let alpha = 1.0 - 10f64.powf(-peak_density[k] * 10f64.powf(a));
                    e[k] = alpha * filter * r.nm;
                }
            }
            e
        })
        .collect();
    let mut peak = [0.0f64; 3];
    for e in &energy {
        for k in 0..3 {
            peak[k] = peak[k].max(e[k]);
        }
    }
    let mut out = [[0.0; 3]; CMF_LEN];
    for (i, o) in out.iter_mut().enumerate().skip(10) {
        let e = energy[(i - 10) * 10];
        for k in 0..3 {
            o[k] = e[k] / peak[k];
        }
    }
    Ok(out)
}

/// The CIE 170-2 matrix from fundamentals to x̄ ȳ z̄ for `field` degrees: exact at 2° and 10°,
/// linear in the field size between.
pub fn matrix(field: f64) -> [[f64; 3]; 3] {
    let a = ((10.0 - field) / 8.0).clamp(0.0, 1.0);
    let mut m = [[0.0; 3]; 3];
    for r in 0..3 {
        for c in 0..3 {
            m[r][c] = a * M_2[r][c] + (1.0 - a) * M_10[r][c];
        }
    }
    m
}

/// x̄ ȳ z̄ at 1 nm over 380..=780 nm for `age` and `field`: [`lms`] through [`matrix`].
pub fn xyz(age: f64, field: f64) -> Result<[[f64; 3]; CMF_LEN]> {
    let lms = lms(age, field)?;
    let m = matrix(field);
    let mut out = [[0.0; 3]; CMF_LEN];
    for (o, v) in out.iter_mut().zip(&lms) {
        for r in 0..3 {
            // the matrix's negative x̄ coefficient on m̄ can leave −1e−17-size rounding residue
            o[r] = (m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2]).max(0.0);
        }
    }
    Ok(out)
}

/// Parses `age=A,field=F` (either order, both needed; the part after `cie2006:`).
pub fn parse_params(spec: &str, params: &str) -> Result<(f64, f64)> {
    let bad = |why: String| Error::Cie2006 {
        spec: spec.to_string(),
        why,
    };
    let (mut age, mut field) = (None, None);
    for part in params.split(',') {
        let (k, v) = part
            .split_once('=')
            .ok_or_else(|| bad(format!("`{part}` is not KEY=VALUE (age=A,field=F)")))?;
        let v: f64 = v
            .trim()
            .parse()
            .map_err(|_| bad(format!("`{v}` is not a number")))?;
        match k.trim() {
            "age" => age = Some(v),
            "field" => field = Some(v),
            other => return Err(bad(format!("unknown key `{other}` (age, field)"))),
        }
    }
    match (age, field) {
        (Some(a), Some(f)) => {
            check(a, f).map_err(bad)?;
            Ok((a, f))
        }
        _ => Err(bad("needs both age=A and field=F".into())),
    }
}

/// The CIE 2006 observer for `age` and `field` as a runtime observer table named
/// `cie2006:age=A,field=F` (`crate::observer::parse` keeps it for the process's life).
pub fn table(age: f64, field: f64) -> Result<CmfTable> {
    let name = format!("cie2006:age={age},field={field}");
    let xyz = xyz(age, field)?;
    let mut values = [[0.0f32; 3]; CMF_LEN];
    for (v, x) in values.iter_mut().zip(&xyz) {
        *v = [x[0] as f32, x[1] as f32, x[2] as f32];
    }
    let table = CmfTable::new(&name, values).map_err(|e| Error::Cie2006 {
        spec: name.clone(),
        why: e.to_string(),
    })?;
    Ok(table)
}
