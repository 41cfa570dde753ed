//! CIEDE2000 against the 34 published pairs of Sharma, Wu & Dalal (2005), both orders, and
//! CIELAB + CIEDE2000 cross-checked against the `palette` crate on a grid of colours.

use specpoly_core::{delta_e2000, Lab};

fn rows() -> Vec<[f64; 7]> {
    include_str!("data/sharma_ciede2000.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|c| c.trim().parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4], v[5], v[6]]
        })
        .collect()
}

#[test]
fn all_34_published_pairs() {
    let rows = rows();
    assert_eq!(rows.len(), 34);
    for r in rows {
        let p = Lab {
            l: r[0],
            a: r[1],
            b: r[2],
        };
        let q = Lab {
            l: r[3],
            a: r[4],
            b: r[5],
        };
        let d = delta_e2000(p, q);
        assert!((d - r[6]).abs() < 5e-5, "{r:?}: got {d}");
        let d = delta_e2000(q, p);
        assert!((d - r[6]).abs() < 5e-5, "{r:?} reversed: got {d}");
    }
}

#[test]
fn lab_and_ciede2000_agree_with_palette() {
    use palette::color_difference::Ciede2000;
    use palette::convert::FromColorUnclamped;
    use palette::white_point::D65;
    let white = [95.047, 100.0, 108.883];
    let mut worst: f64 = 0.0;
    for i in 0..6 {
        for j in 0..6 {
            for k in 0..6 {
                let xyz = [
                    5.0 + 15.0 * i as f64,
                    3.0 + 16.0 * j as f64,
                    4.0 + 18.0 * k as f64,
                ];
                let ours = Lab::from_xyz(xyz, white);
                let theirs = palette::Lab::<D65, f64>::from_color_unclamped(
                    palette::Xyz::<D65, f64>::new(xyz[0] / 100.0, xyz[1] / 100.0, xyz[2] / 100.0),
                );
                worst = worst
                    .max((ours.l - theirs.l).abs())
                    .max((ours.a - theirs.a).abs())
                    .max((ours.b - theirs.b).abs());
                let other = Lab {
                    l: ours.l + 3.0,
                    a: ours.a - 2.0,
                    b: ours.b + 5.0,
                };
                let theirs_other = palette::Lab::<D65, f64>::new(other.l, other.a, other.b);
                let d_ours = delta_e2000(ours, other);
                let d_theirs =
                    palette::Lab::<D65, f64>::new(ours.l, ours.a, ours.b).difference(theirs_other);
                assert!((d_ours - d_theirs).abs() < 1e-5, "{d_ours} vs {d_theirs}");
            }
        }
    }
    assert!(worst < 1e-9, "Lab differs from palette by {worst}");
}
