//! RGB → smooth reflectance, for assets that only have an RGB colour.
//!
//! Three smooth basis functions that sum to one at every wavelength (a partition of unity):
//!
//! `b_blue(λ) = 1 − σ((λ − 490)/w)`, `b_red(λ) = σ((λ − 590)/w)`, `b_green = 1 − b_blue − b_red`,
//!
//! with `σ` the logistic function and `w = 15 nm`. For a linear-sRGB colour `c` (D65 white), the
//! reflectance is `r(λ) = Σⱼ aⱼ bⱼ(λ)` with the weights `a = M⁻¹ · XYZ(c)`, where `Mᵢⱼ` is the
//! XYZ of `bⱼ` under D65 (CIE 1931, 1 nm sums) — so `r` has exactly the colour `c` under D65.
//! Because the basis sums to one, grey `(g, g, g)` becomes the flat reflectance `g` (to the
//! 0.1 % by which the D65 table's white and the sRGB white point differ). Saturated colours
//! outside what the basis can reach with weights in `[0, 1]` are clipped to `[0, 1]` per
//! wavelength and lose some chroma. (A smooth-basis variant of Smits, "An RGB-to-spectrum
//! conversion for reflectances", J. Graphics Tools 4(4), 1999, with three smooth bands in place
//! of his ten-bin spectra.)

use specpoly_core::{exact_xyz, Display, Illuminant, Mat3, Observer};

/// Wavelengths of the upsampled tables: 380, 385, …, 780 nm.
pub fn wavelengths() -> Vec<f32> {
    (0..81).map(|i| 380.0 + 5.0 * i as f32).collect()
}

fn basis(nm: f64) -> [f64; 3] {
    let sig = |x: f64| 1.0 / (1.0 + (-x).exp());
    const W: f64 = 15.0;
    let blue = 1.0 - sig((nm - 490.0) / W);
    let red = sig((nm - 590.0) / W);
    [red, 1.0 - blue - red, blue]
}

/// The reflectance (at [`wavelengths`]) whose colour under D65 is the linear-sRGB `rgb`.
pub fn rgb_to_reflectance(rgb: [f32; 3]) -> Vec<f32> {
    let d65 = Illuminant::D65.tabulated();
    let mut m = [[0.0f32; 3]; 3];
    for j in 0..3 {
        let (xyz, _) = exact_xyz(Observer::Cie1931, &d65, |nm| basis(nm)[j]);
        for i in 0..3 {
            m[i][j] = xyz[i] as f32;
        }
    }
    let target = Display::srgb().rgb_to_xyz().apply(rgb).map(|v| v * 100.0);
    let a = Mat3(m).inverse().unwrap_or(Mat3::IDENTITY).apply(target);
    wavelengths()
        .iter()
        .map(|&nm| {
            let b = basis(nm as f64);
            let v = a[0] as f64 * b[0] + a[1] as f64 * b[1] + a[2] as f64 * b[2];
            v.clamp(0.0, 1.0) as f32
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::Tabulated;

    #[test]
    fn grey_is_flat_and_colours_round_trip() {
        let g = rgb_to_reflectance([0.5, 0.5, 0.5]);
        assert!(g.iter().all(|v| (v - 0.5).abs() < 0.01), "{g:?}");
        let w = wavelengths();
        let c = [0.4f32, 0.25, 0.1];
        let r = rgb_to_reflectance(c);
        let t = Tabulated::new(&w, &r).unwrap();
        let (xyz, _) = exact_xyz(Observer::Cie1931, &Illuminant::D65.tabulated(), |nm| {
            t.at(nm)
        });
        let xyz = [
            xyz[0] as f32 / 100.0,
            xyz[1] as f32 / 100.0,
            xyz[2] as f32 / 100.0,
        ];
        let back = Display::srgb().xyz_to_rgb().apply(xyz);
        for k in 0..3 {
            assert!((back[k] - c[k]).abs() < 0.01, "{back:?} vs {c:?}");
        }
    }
}
