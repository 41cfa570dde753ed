//! The standard's computation ([`Spd`], [`cri_spd`], [`tm30_spd`]) against colour-science 0.4.7
//! on 118 lights no one here wrote: every spectrum of colour-science's `SDS_ILLUMINANTS` and
//! `SDS_LIGHT_SOURCES` tabulated at 1 or 5 nm over 380–780 nm (CIE A–E, D, FL, FL3.x, HP and LED
//! series, measured lamps of the NIST and Philips/Luxeon sets) and 11 mixes of `data/leds/` at
//! 1 nm. `data/light_references.csv` (CCT, Duv, Ra, R1–R14, Rf, Rg, hue bins) and
//! `data/light_references_spd.csv` (the spectra at their own sampling) are made by
//! `data/light_references.py`; `data/light_references_r15.csv` (R15, colour-science's "CIE 2024"
//! sample set) by `data/light_references_r15.py`.

use crate::common::light_data::csv;
use specpoly_core::light::{cri::cri_spd, tm30::tm30_spd, Spd};
use specpoly_core::Tabulated;

/// The tolerances of the parity requirement, and why the references can differ at all:
/// colour-science finds the CCT by Ohno (2013) (its cascade is exact to ≈ 0.02 %, we find the
/// minimum distance directly); CIE 13.3 in colour-science uses Robertson (1968) for the CCT,
/// Sprague-interpolates the light to 1 nm over 360–780 nm and rounds the daylight `M₁`, `M₂` to
/// 3 decimals.
struct Tol {
    cct_rel: f64,
    duv: f64,
    ri: f64,
    rf: f64,
    rg: f64,
    rf_h: f64,
    rcs_h: f64,
    rhs_h: f64,
}

const TOL: Tol = Tol {
    cct_rel: 5e-4,
    duv: 2e-5,
    ri: 0.1,
    rf: 0.05,
    rg: 0.05,
    rf_h: 0.1,
    rcs_h: 0.005,
    rhs_h: 0.005,
};

/// Lights whose Ra and Rᵢ are not compared: FL3.10's CCT is 5000.1 K here and 4999.5 K by
/// colour-science's Robertson (1968) and Ohno (2013) estimates, so CIE 13.3 takes daylight as
/// the reference here and a Planckian radiator there (Rᵢ differ by up to 3.3, R9 by 1.3).
const RI_OUTLIERS: [&str; 1] = ["FL3.10"];

const NAMES: [&str; 9] = [
    "CCT (relative)",
    "Duv",
    "Ra and R1-R14",
    "Rf",
    "Rg",
    "Rf,hj",
    "Rcs,hj",
    "Rhs,hj",
    "R15",
];

#[test]
fn agrees_with_colour_science_on_118_lights() {
    let (_, spds) = csv(include_str!("data/light_references_spd.csv"));
    let (head, refs) = csv(include_str!("data/light_references.csv"));
    assert_eq!(head.len(), 1 + 3 + 14 + 2 + 48);
    assert_eq!(refs.len(), 118);
    let (head, r15) = csv(include_str!("data/light_references_r15.csv"));
    assert_eq!(head, ["name", "r15"]);
    assert_eq!(r15.len(), 118);
    let tol = [
        TOL.cct_rel,
        TOL.duv,
        TOL.ri,
        TOL.rf,
        TOL.rg,
        TOL.rf_h,
        TOL.rcs_h,
        TOL.rhs_h,
        TOL.ri,
    ];
    let mut worst: [(f64, String); 9] = Default::default();
    let (mut five, mut one) = (0, 0);
    for ((s, r), r15) in spds.iter().zip(&refs).zip(&r15) {
        assert_eq!((&s[0], &s[0]), (&r[0], &r15[0]));
        let start: f32 = s[1].parse().unwrap();
        let step: f32 = s[2].parse().unwrap();
        let v: Vec<f32> = s[3..].iter().map(|x| x.parse().unwrap()).collect();
        let nm: Vec<f32> = (0..v.len()).map(|i| start + step * i as f32).collect();
        let spd = Spd::new(&Tabulated::new(&nm, &v).unwrap()).unwrap();
        assert_eq!(spd.step() as f32, step, "{}", s[0]);
        if step == 5.0 {
            five += 1
        } else {
            one += 1
        }
        let want: Vec<f64> = r[1..].iter().map(|x| x.parse().unwrap()).collect();
        let c = cri_spd(&spd).unwrap();
        let t = tm30_spd(&spd).unwrap();
        let mut diff = |k: usize, d: f64| {
            if d.abs() > worst[k].0 {
                worst[k] = (d.abs(), r[0].clone());
            }
        };
        diff(0, (t.cct.cct - want[0]) / want[0]);
        diff(1, t.cct.duv - want[1]);
        if RI_OUTLIERS.contains(&r[0].as_str()) {
            // the reason: the two CCTs lie on either side of CIE 13.3's 5000 K switch
            assert!(want[0] < 5000.0 && c.cct.cct >= 5000.0, "{}", r[0]);
            println!("{} (outlier): R9 {:+.3}", r[0], c.r[8] - want[11]);
        } else {
            diff(2, c.ra - want[2]);
            for i in 0..14 {
                diff(2, c.r[i] - want[3 + i]);
            }
            diff(8, c.r15 - r15[1].parse::<f64>().unwrap());
        }
        diff(3, t.rf - want[17]);
        diff(4, t.rg - want[18]);
        for j in 0..16 {
            diff(5, t.rf_h[j] - want[19 + j]);
            diff(6, t.rcs_h[j] - want[35 + j]);
            diff(7, t.rhs_h[j] - want[51 + j]);
        }
        // the CRI (on the 1 nm interpolant) and TM-30 find nearly the same CCT
        assert!((c.cct.cct - t.cct.cct).abs() < 1e-3 * t.cct.cct);
    }
    assert_eq!((five, one), (107, 11));
    let mut failed = vec![];
    for k in 0..9 {
        println!("{:16} worst {:.3e} ({})", NAMES[k], worst[k].0, worst[k].1);
        if worst[k].0 > tol[k] {
            failed.push(format!("{}: {} > {}", NAMES[k], worst[k].0, tol[k]));
        }
    }
    assert!(failed.is_empty(), "{failed:?}");
}
