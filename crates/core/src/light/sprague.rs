//! Sprague (1880) interpolation of 5 nm data to 1 nm, as CIE 167:2005 recommends for spectral
//! data (and colour-science uses for CIE 13.3: it takes 5 nm lights and the 5 nm test colour
//! samples to 1 nm this way before summing).
//!
//! Two points are added at each end, `y₋₂ = Σ cⱼ yⱼ / 209` with the CIE 167 boundary
//! coefficients `(884, −1960, 3033, −2648, 1080, −180)` and `(508, −540, 488, −367, 144, −24)`
//! (mirrored at the long end); between `yᵢ` and `yᵢ₊₁` the quintic
//! `a₀ + a₁X + … + a₅X⁵` in `X = (λ − λᵢ)/5 nm` through the six points `p₀…p₅ = yᵢ₋₂…yᵢ₊₃` has
//! `a₀ = p₂`, `a₁ = (2p₀ − 16p₁ + 16p₃ − 2p₄)/24`, `a₂ = (−p₀ + 16p₁ − 30p₂ + 16p₃ − p₄)/24`,
//! `a₃ = (−9p₀ + 39p₁ − 70p₂ + 66p₃ − 33p₄ + 7p₅)/24`,
//! `a₄ = (13p₀ − 64p₁ + 126p₂ − 124p₃ + 61p₄ − 12p₅)/24`,
//! `a₅ = (−5p₀ + 25p₁ − 50p₂ + 50p₃ − 25p₄ + 5p₅)/24`.

const LEFT: [[f64; 6]; 2] = [
    [884.0, -1960.0, 3033.0, -2648.0, 1080.0, -180.0],
    [508.0, -540.0, 488.0, -367.0, 144.0, -24.0],
];

/// The 401 values at 1 nm over 380–780 nm of 81 values at 5 nm over the same range.
pub fn to_1nm(y5: &[f64; 81]) -> [f64; 401] {
    let mut p = [0.0f64; 85];
    for (d, s) in p[2..83].iter_mut().zip(y5) {
        *d = *s;
    }
    let dot = |c: &[f64; 6], v: [f64; 6]| c.iter().zip(v).map(|(a, b)| a * b).sum::<f64>() / 209.0;
    let head: [f64; 6] = core::array::from_fn(|j| p[2 + j]);
    let tail: [f64; 6] = core::array::from_fn(|j| p[82 - j]);
    p[0] = dot(&LEFT[0], head);
    p[1] = dot(&LEFT[1], head);
    p[84] = dot(&LEFT[0], tail);
    p[83] = dot(&LEFT[1], tail);
    let mut out = [0.0f64; 401];
    for (k, o) in out.iter_mut().enumerate() {
        if k % 5 == 0 {
            *o = y5[k / 5];
            continue;
        }
        let i = (k / 5).min(79);
        let x = (k - 5 * i) as f64 / 5.0;
        let q = &p[i..i + 6];
        let a = [
            q[2],
            (2.0 * q[0] - 16.0 * q[1] + 16.0 * q[3] - 2.0 * q[4]) / 24.0,
            (-q[0] + 16.0 * q[1] - 30.0 * q[2] + 16.0 * q[3] - q[4]) / 24.0,
            (-9.0 * q[0] + 39.0 * q[1] - 70.0 * q[2] + 66.0 * q[3] - 33.0 * q[4] + 7.0 * q[5])
                / 24.0,
            (13.0 * q[0] - 64.0 * q[1] + 126.0 * q[2] - 124.0 * q[3] + 61.0 * q[4] - 12.0 * q[5])
                / 24.0,
            (-5.0 * q[0] + 25.0 * q[1] - 50.0 * q[2] + 50.0 * q[3] - 25.0 * q[4] + 5.0 * q[5])
                / 24.0,
        ];
        *o = a.iter().rev().fold(0.0, |acc, c| acc * x + c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside (390–770 nm, six real points) Sprague's interpolant reproduces polynomials up to
    /// degree 5; in the end intervals the CIE 167 boundary points govern, checked against
    /// colour-science 0.4.7's `SpragueInterpolator` on the same cubic.
    #[test]
    fn keeps_a_cubic_and_matches_colour_science_at_the_ends() {
        let f = |nm: f64| {
            let t = (nm - 580.0) / 200.0;
            0.5 + 0.3 * t - 0.2 * t * t + 0.1 * t * t * t
        };
        let y5: [f64; 81] = core::array::from_fn(|i| f(380.0 + 5.0 * i as f64));
        let y1 = to_1nm(&y5);
        for (k, v) in y1.iter().enumerate() {
            if k % 5 == 0 {
                assert_eq!(*v, y5[k / 5]);
            }
            if (10..=390).contains(&k) {
                let nm = 380.0 + k as f64;
                assert!((v - f(nm)).abs() < 1e-12, "{nm}: {v} vs {}", f(nm));
            }
        }
        let colour_science = [
            (1, -0.095037433433014),
            (2, -0.090080210765550),
            (3, -0.085135202930622),
            (4, -0.080210240430622),
            (396, 0.696041398325359),
            (397, 0.697026760825359),
            (398, 0.698015958133971),
            (399, 0.699007475538278),
        ];
        for (k, want) in colour_science {
            assert!(
                (y1[k] - want).abs() < 1e-12,
                "{}: {} vs {want}",
                380 + k,
                y1[k]
            );
        }
    }
}
