//! California Title 24 Joint Appendix JA8 ("Qualification requirements for high luminous
//! efficacy light sources"): the colour limits of its Table JA-8.
//!
//! | clause | limit | edition |
//! |---|---|---|
//! | Colour Rendering Index (CIE 13.3 Ra) | ≥ 90 | JA8-2016, -2019, -2022 |
//! | Colour Rendering R9 | ≥ 50 | same |
//! | Correlated colour temperature | ≤ 4000 K | JA8-2019 on (2016: ≤ 3000 K except some LED products) |
//! | Duv | −0.0033 to +0.0033 | JA8-2016 Table JA-8 |
//!
//! Source: Table JA-8 ("Data reporting") of the 2016 and 2019 Reference Appendices, as
//! published on the California Energy Commission's Energy Code Ace site; the 2022 edition's
//! marking (JA8-2022) keeps Ra ≥ 90, R9 ≥ 50 and CCT ≤ 4000 K per the CEC's compliance
//! manual summaries. The Duv limit is the 2016 table's; the 2019 table read here lists no Duv
//! limit, so it is reported as its own clause and a light can be judged with or without it.
//! Limits are inclusive and compared with the computed figures unrounded.

use super::LightError;

/// Least CIE 13.3 Ra.
pub const RA_MIN: f64 = 90.0;
/// Least R9.
pub const R9_MIN: f64 = 50.0;
/// Greatest CCT, K.
pub const CCT_MAX: f64 = 4000.0;
/// Greatest |Duv| (JA8-2016).
pub const DUV_MAX: f64 = 0.0033;

/// The clauses: key and text with the limit.
pub const CLAUSES: [(&str, &str); 4] = [
    ("ra", "CRI Ra >= 90 (Table JA-8)"),
    ("r9", "R9 >= 50 (Table JA-8)"),
    ("cct", "CCT <= 4000 K (Table JA-8, 2019 on)"),
    ("duv", "Duv within +-0.0033 (Table JA-8, 2016)"),
];

/// One clause's figure, limit and verdict.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clause {
    /// Short key: `ra`, `r9`, `cct`, `duv`.
    pub key: &'static str,
    /// What it is, with the limit.
    pub text: &'static str,
    /// The light's figure.
    pub value: f64,
    /// Whether it meets the limit.
    pub pass: bool,
}

/// JA8's colour clauses for a light's Ra, R9, CCT and Duv.
pub fn ja8(ra: f64, r9: f64, cct: f64, duv: f64) -> Result<[Clause; 4], LightError> {
    if ![ra, r9, cct, duv].iter().all(|v| v.is_finite()) {
        return Err(LightError::BadTarget);
    }
    let value = [ra, r9, cct, duv];
    let pass = [
        ra >= RA_MIN,
        r9 >= R9_MIN,
        cct <= CCT_MAX,
        duv.abs() <= DUV_MAX,
    ];
    Ok(core::array::from_fn(|i| Clause {
        key: CLAUSES[i].0,
        text: CLAUSES[i].1,
        value: value[i],
        pass: pass[i],
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_inclusive() {
        let c = ja8(90.0, 50.0, 4000.0, -0.0033).unwrap();
        assert!(c.iter().all(|c| c.pass));
        let c = ja8(89.99, 49.99, 4000.01, 0.00331).unwrap();
        assert!(c.iter().all(|c| !c.pass));
        assert!(ja8(f64::NAN, 50.0, 3000.0, 0.0).is_err());
    }
}
