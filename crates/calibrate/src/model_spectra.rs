//! Built-in model spectra of display primaries (`sim:qdoled`, `sim:wled`, `sim:broadband`),
//! 1 nm over 380–780 nm, relative (the simulated display scales them to its white).
//!
//! Physically plausible shapes, not measurements of a product; each is a sum of Gaussian
//! bands `exp(−½((λ − c)/σ)²)` with `σ = FWHM / 2.3548`, peaks and widths as the literature
//! reports for the technology:
//!
//! - **`qdoled`** — a blue OLED emitter with quantum-dot colour converters (Samsung
//!   QD-OLED): blue 455 nm (FWHM 20 nm), green 531 nm (FWHM 24 nm), red 630 nm (FWHM 27 nm),
//!   each converter passing 1 % of the blue; the narrowest primaries here (a Rec. 2020-wide
//!   gamut).
//! - **`wled`** — an LCD backlit by white LEDs: an InGaN blue die at 447 nm (FWHM 20 nm) and a
//!   broad YAG:Ce phosphor (peak 555 nm, FWHM 115 nm, 0.6 of the blue peak), seen through the
//!   LCD's three absorption colour filters. A filter's transmittance is
//!   `0.01 + 0.89·s((λ − lo)/w)·s((hi − λ)/w)` with `s` the logistic function: blue lo 380,
//!   hi 505, w 9 nm; green lo 475, hi 595, w 9 nm; red lo 585, hi 900, w 8 nm (the sRGB-class
//!   office monitor; its green and red share the phosphor's broad band).
//! - **`broadband`** — wide primaries like an early CCFL-lit or a projector lamp's: red 615 nm
//!   (FWHM 90 nm), green 540 nm (FWHM 95 nm), blue 455 nm (FWHM 60 nm).
//!
//! Sources for the peaks and widths: Kim et al., "Quantum-dot OLED", SID Digest 2022
//! (QD-OLED: blue 450–460 nm, QD FWHM 20–30 nm); Schubert, *Light-Emitting Diodes*, 2nd ed.
//! (2006), §21 (InGaN 445–455 nm, YAG:Ce 550–560 nm, FWHM ≈ 110–120 nm); Yang & Wu, *Fundamentals
//! of Liquid Crystal Devices*, 2nd ed. (2014), §13 (colour-filter pass bands).

/// The built-in spectra's names.
pub const NAMES: [&str; 3] = ["qdoled", "wled", "broadband"];

/// 380..=780 nm at 1 nm.
pub fn wavelengths() -> Vec<f32> {
    (380..=780).map(|n| n as f32).collect()
}

fn gauss(nm: f64, centre: f64, fwhm: f64) -> f64 {
    let s = fwhm / (8.0 * std::f64::consts::LN_2).sqrt();
    (-0.5 * ((nm - centre) / s).powi(2)).exp()
}

fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + (-x).exp())
}

fn filter(nm: f64, lo: f64, hi: f64, w: f64) -> f64 {
    0.01 + 0.89 * logistic((nm - lo) / w) * logistic((hi - nm) / w)
}

/// The `[red, green, blue]` spectra of built-in `name` at [`wavelengths`], or `None`.
pub fn primaries(name: &str) -> Option<[Vec<f32>; 3]> {
    let f: fn(f64) -> [f64; 3] = match name {
        "qdoled" => |nm| {
            let blue = gauss(nm, 455.0, 20.0);
            [
                gauss(nm, 630.0, 27.0) + 0.01 * blue,
                gauss(nm, 531.0, 24.0) + 0.01 * blue,
                blue,
            ]
        },
        "wled" => |nm| {
            let backlight = gauss(nm, 447.0, 20.0) + 0.6 * gauss(nm, 555.0, 115.0);
            [
                backlight * filter(nm, 585.0, 900.0, 8.0),
                backlight * filter(nm, 475.0, 595.0, 9.0),
                backlight * filter(nm, 380.0, 505.0, 9.0),
            ]
        },
        "broadband" => |nm| {
            [
                gauss(nm, 615.0, 90.0),
                gauss(nm, 540.0, 95.0),
                gauss(nm, 455.0, 60.0),
            ]
        },
        _ => return None,
    };
    let mut out = [Vec::new(), Vec::new(), Vec::new()];
    for nm in 380..=780 {
        let v = f(nm as f64);
        for k in 0..3 {
            out[k].push(v[k] as f32);
        }
    }
    Some(out)
}
