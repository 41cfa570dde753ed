//! `specpoly xyz … --display CAL.toml` on a calibration with channel interaction (the
//! Surface's fit of data/ti3): the device values printed are the full model's inverse, not the
//! matrix model's. Oracle: the full model's forward prediction at the printed values against
//! the colour asked for, in `palette`'s CIEDE2000 (relative to the model's white), for every
//! ColorChecker colour the full model can show (its exact inverse reaches it).

use crate::common::cli;
use crate::common::displays;

use displays::{de00, fitted};

/// The inverse's own tolerance (`DisplayModel::inverse`, ΔE00 0.005) plus the JSON's 10⁻⁶
/// rounding of device values.
const XYZ_DISPLAY_DE: f64 = 0.01;

#[test]
fn xyz_display_uses_the_full_model() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("surface.toml");
    let cal = fitted("microsoft-surface-pro-2017_825.ti3");
    cal.save(&path).unwrap();
    let o = cli::output(&[
        "xyz",
        "colorchecker#*",
        "--display",
        cli::s(&path),
        "--json",
    ]);
    assert!(o.status.success(), "{}", cli::text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let model = cal.model();
    let d = model.display();
    let k = (d.white().y - d.black().y) as f64 / 100.0;
    let white: [f64; 3] = model.white().into();
    let (mut checked, mut worst) = (0, 0.0f64);
    for row in v.as_array().unwrap() {
        let want = ["X", "Y", "Z"].map(|c| row[c].as_f64().unwrap() * k);
        let rgb = [0, 1, 2].map(|i| row["rgb"][i].as_f64().unwrap() as f32);
        let w = specpoly_core::Xyz::new(want[0] as f32, want[1] as f32, want[2] as f32);
        if !model.inverse(w).exact {
            continue;
        }
        let got: [f64; 3] = model.device_to_xyz(rgb).into();
        let de = de00(got, want, white);
        worst = worst.max(de);
        checked += 1;
    }
    assert!(checked >= 12, "{checked} colours in the full model's gamut");
    assert!(worst <= XYZ_DISPLAY_DE, "worst ΔE00 {worst}");
}
