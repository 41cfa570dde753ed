//! Moments: `Moments::xyz` of a polynomial spectrum equals an independent f64 1 nm sum of that
//! polynomial times the light (read here from data/illuminants, linearly interpolated) and the
//! observer (read here from data/cmf), normalised to Y = 100 for the perfect white.

use specpoly_core::{DefaultSpectrum, Illuminant, Moments, Observer, Tabulated};

fn csv(path: &str) -> Vec<Vec<f64>> {
    std::fs::read_to_string(format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR")))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.trim().parse().unwrap()).collect())
        .collect()
}

fn interp(rows: &[Vec<f64>], nm: f64) -> f64 {
    let i = rows.iter().position(|r| r[0] >= nm).unwrap();
    if rows[i][0] == nm || i == 0 {
        return rows[i][1];
    }
    let (a, b) = (&rows[i - 1], &rows[i]);
    a[1] + (b[1] - a[1]) * (nm - a[0]) / (b[0] - a[0])
}

#[test]
fn moments_equal_the_1nm_sum_of_the_polynomial() {
    let cmf = csv("cmf/cie1964_10deg_1nm.csv");
    for (ill, file) in [
        (Illuminant::D65, "D65"),
        (Illuminant::FL11, "FL11"),
        (Illuminant::A, "A"),
    ] {
        let light = csv(&format!("illuminants/{file}.csv"));
        // a wiggly test spectrum
        let w: Vec<f32> = (0..41).map(|i| 380.0 + 10.0 * i as f32).collect();
        let v: Vec<f32> = w
            .iter()
            .map(|x| 0.5 + 0.4 * ((x - 380.0) / 37.0).sin())
            .collect();
        let t = Tabulated::new(&w, &v).unwrap();
        let p = DefaultSpectrum::fit(&t).unwrap();
        let m = Moments::new(Observer::Cie1964, &ill.tabulated());
        let got = m.xyz(&p);

        let (mut xyz, mut wy) = ([0.0f64; 3], 0.0);
        for nm in 380..=780 {
            let row = cmf.iter().find(|r| r[0] as i32 == nm).unwrap();
            let s = interp(&light, nm as f64);
            let r = p.eval(nm as f32) as f64;
            for k in 0..3 {
                xyz[k] += r * s * row[k + 1];
            }
            wy += s * row[2];
        }
        let want = xyz.map(|v| v * 100.0 / wy);
        for (g, w) in got.to_array().iter().zip(want) {
            assert!(
                (*g as f64 - w).abs() < 2e-4 * w.max(1.0),
                "{file}: {got:?} vs {want:?}"
            );
        }
        assert!((m.white().y - 100.0).abs() < 1e-4);
    }
}
