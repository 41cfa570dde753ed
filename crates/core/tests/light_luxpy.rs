//! A second reference for the base metrics: luxpy 1.12.5 on the 118 lights of
//! `light_references.rs` (`data/light_references_luxpy.py`). luxpy interpolates every light to
//! 1 nm before its sums (a 5 nm light is summed at 5 nm here and in colour-science), finds the
//! CCT by Ohno (2014) and differs from colour-science 0.4.7 itself by up to 0.34 in Ra, 0.89 in
//! R9 and 0.23 in Rg on these lights, so those tolerances are wider than against
//! colour-science; CCT, Duv and Rf are held to the parity requirement.

use crate::common::light_data::csv;
use specpoly_core::light::{cri::cri_spd, tm30::tm30_spd, Spd};
use specpoly_core::Tabulated;

#[test]
fn agrees_with_luxpy_on_118_lights() {
    let (_, spds) = csv(include_str!("data/light_references_spd.csv"));
    let (head, refs) = csv(include_str!("data/light_references_luxpy.csv"));
    assert_eq!(head, ["name", "cct", "duv", "ra", "r9", "rf", "rg"]);
    assert_eq!(refs.len(), 118);
    let (head, r15) = csv(include_str!("data/light_references_r15_luxpy.csv"));
    assert_eq!(head, ["name", "r15"]);
    assert_eq!(r15.len(), 118);
    // CCT relative, Duv, Ra, R9, Rf, Rg. D75's Duv is 2.0e-5 from luxpy's as from
    // colour-science's (the CCT methods; docs/leds.md): at the requirement, rounded up by 5 %
    // (R15 as R9: luxpy's 1 nm interpolation of the light moves the special indices alike)
    let tol = [5e-4, 2.05e-5, 0.4, 1.0, 0.05, 0.3, 1.0];
    let names = ["CCT (relative)", "Duv", "Ra", "R9", "Rf", "Rg", "R15"];
    let mut worst: [(f64, String); 7] = Default::default();
    for ((s, r), r15) in spds.iter().zip(&refs).zip(&r15) {
        assert_eq!((&s[0], &s[0]), (&r[0], &r15[0]));
        let start: f32 = s[1].parse().unwrap();
        let step: f32 = s[2].parse().unwrap();
        let v: Vec<f32> = s[3..].iter().map(|x| x.parse().unwrap()).collect();
        let nm: Vec<f32> = (0..v.len()).map(|i| start + step * i as f32).collect();
        let spd = Spd::new(&Tabulated::new(&nm, &v).unwrap()).unwrap();
        let mut want: Vec<f64> = r[1..].iter().map(|x| x.parse().unwrap()).collect();
        want.push(r15[1].parse().unwrap());
        let (c, t) = (cri_spd(&spd).unwrap(), tm30_spd(&spd).unwrap());
        let got = [t.cct.cct, t.cct.duv, c.ra, c.r[8], t.rf, t.rg, c.r15];
        for k in 0..7 {
            let mut d = got[k] - want[k];
            if k == 0 {
                d /= want[0];
            }
            // FL3.10 is on either side of CIE 13.3's 5000 K switch (light_references.rs)
            if (k == 2 || k == 3 || k == 6) && r[0] == "FL3.10" {
                continue;
            }
            if d.abs() > worst[k].0 {
                worst[k] = (d.abs(), r[0].clone());
            }
        }
    }
    for k in 0..7 {
        println!(
            "luxpy {:14} worst {:.3e} ({})",
            names[k], worst[k].0, worst[k].1
        );
    }
    for k in 0..7 {
        assert!(worst[k].0 <= tol[k], "{}: {:?}", names[k], worst[k]);
    }
}
