//! ICC display profiles as `--display` (`render`, `xyz`) and `--calibration` (`led`), through
//! the one loader (`calibrate::file::load_display`): our own profiles give the calibration's
//! device values back (within [`RGB`]; a table-only profile read through Little CMS's
//! transform within [`RGB_TABLES`]); a profile ArgyllCMS's `colprof` makes from the same .ti3
//! predicts its patches within a mean ΔE00 of [`ARGYLL_DE`] (an independent model of the same
//! display); broken and non-display profiles are one-line errors.

use crate::common::cli;

use crate::common::displays;
use cli::{output as specpoly, s};

use specpoly_calibrate::fit::{fit, FitOptions, InteractionChoice};
use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_display::calibration::Calibration;
use specpoly_display::icc::{self, IccOptions, IccVersion};
use specpoly_display::spec::DisplaySpec;
use specpoly_formats::cgats::read_ti3;
use std::path::Path;
use std::process::Command;

/// Device values from our profile against those from the calibration itself.
const RGB: f64 = 2e-3;
/// The same through a profile with only `A2B0`/`B2A0` tables (sampled by Little CMS).
const RGB_TABLES: f64 = 5e-3;
/// Mean ΔE00 over the .ti3's patches of the display read from an ArgyllCMS profile.
const ARGYLL_DE: f64 = 1.0;

/// The matrix model (what a `Display` and a matrix/TRC profile hold).
fn acer() -> Calibration {
    let t = read_ti3(specpoly_spectra::data::ACER_TI3, "acer.ti3").unwrap();
    let opts = FitOptions {
        interaction: InteractionChoice::None,
        ..FitOptions::default()
    };
    fit(&t.best_units().0, &opts).unwrap()
}

/// `xyz … --display D --json`: the device values of each colour.
fn rgb_of(display: &Path) -> Vec<[f64; 3]> {
    let o = specpoly(&["xyz", "colorchecker#*", "--display", s(display), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let a = r["rgb"].as_array().expect("rgb");
            [0, 1, 2].map(|k| a[k].as_f64().unwrap())
        })
        .collect()
}

/// The largest difference of any component between `got` and `want`.
fn max_difference(got: &[[f64; 3]], want: &[[f64; 3]]) -> f64 {
    got.iter()
        .zip(want)
        .flat_map(|(g, w)| (0..3).map(move |k| (g[k] - w[k]).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn our_profiles_give_the_calibrations_device_values() {
    let dir = tempfile::tempdir().unwrap();
    let cal = acer();
    let toml = dir.path().join("acer.toml");
    cal.save(&toml).unwrap();
    let want = rgb_of(&toml);
    assert_eq!(want.len(), 24);
    for version in [IccVersion::V2, IccVersion::V4] {
        let p = dir.path().join(format!("acer-{version:?}.icc"));
        let b = icc::build(
            &cal,
            "acer",
            &IccOptions {
                version,
                tables: false,
            },
        )
        .unwrap();
        std::fs::write(&p, b).unwrap();
        let worst = max_difference(&rgb_of(&p), &want);
        eprintln!("{version:?}: max |ΔRGB| {worst:.2e}");
        assert!(worst < RGB, "{version:?}: {worst}");
        // the LED controller's lines come from the same loader
        let lines =
            specpoly_led::lines::calibration(&DisplaySpec::open_measured(&p).unwrap()).unwrap();
        assert_eq!(lines.len(), 4, "{lines:?}");
    }
    // a LUT profile: the same with tables, its colorant and curve tags renamed away
    let mut b = icc::build(
        &cal,
        "acer tables",
        &IccOptions {
            version: IccVersion::V2,
            tables: true,
        },
    )
    .unwrap();
    displays::tables_only(&mut b);
    let p = dir.path().join("tables.icc");
    std::fs::write(&p, b).unwrap();
    let worst = max_difference(&rgb_of(&p), &want);
    eprintln!("tables only: max |ΔRGB| {worst:.2e}");
    assert!(worst < RGB_TABLES, "{worst}");
}

#[test]
fn argyll_profiles_describe_the_display() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("acer.ti3"),
        specpoly_spectra::data::ACER_TI3,
    )
    .unwrap();
    let t = read_ti3(specpoly_spectra::data::ACER_TI3, "acer.ti3").unwrap();
    let (meas, _) = t.best_units();
    {
        let name = "shaper";
        let a = ["-ql", "-as", "-O", name, "acer"];
        let o = Command::new("colprof")
            .args(a)
            .current_dir(dir.path())
            .output()
            .expect("colprof (test.sh installs ArgyllCMS)");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let d = DisplaySpec::open_measured(&dir.path().join(name))
            .unwrap()
            .display();
        let w = d.white().to_array().map(|v| v as f64);
        let des: Vec<f64> = meas
            .iter()
            .map(|m| {
                let p = d
                    .device_to_xyz(m.device.map(|v| v as f32))
                    .to_array()
                    .map(|v| v as f64);
                delta_e00(p, m.xyz, w)
            })
            .collect();
        let mean = des.iter().sum::<f64>() / des.len() as f64;
        eprintln!(
            "{name}: white Y {:.2} cd/m² (measured {:.2}); mean ΔE00 {mean:.3} over {} patches",
            w[1],
            t.white_cdm2.unwrap()[1],
            des.len()
        );
        assert!((w[1] / t.white_cdm2.unwrap()[1] - 1.0).abs() < 0.01);
        assert!(mean < ARGYLL_DE, "{name}: {mean}");
        // and render takes it, embedding the profile as it is
        let out = dir.path().join(format!("{name}.png"));
        let o = specpoly(&[
            "render",
            "example1",
            "--size",
            "32x24",
            "--display",
            s(&dir.path().join(name)),
            "-o",
            s(&out),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let dec = png::Decoder::new(std::fs::File::open(&out).unwrap());
        let r = dec.read_info().unwrap();
        let icc = r.info().icc_profile.as_ref().expect("iCCP").to_vec();
        assert_eq!(icc, std::fs::read(dir.path().join(name)).unwrap());
    }
}

#[test]
fn broken_and_non_display_profiles_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let good = icc::build(&acer(), "acer", &IccOptions::default()).unwrap();
    let mut printer = good.clone();
    printer[12..16].copy_from_slice(b"prtr");
    let mut cmyk = good.clone();
    cmyk[16..20].copy_from_slice(b"CMYK");
    let mut short = good.clone();
    short.truncate(good.len() - 40);
    let mut garbage = good.clone();
    for b in garbage[128..].iter_mut() {
        *b = 0xA5;
    }
    for (name, bytes, want) in [
        ("printer", printer, "not a display"),
        ("cmyk", cmyk, "not RGB"),
        ("short", short, "broken ICC profile"),
        ("garbage", garbage, "broken ICC profile"),
    ] {
        let p = dir.path().join(format!("{name}.icc"));
        std::fs::write(&p, bytes).unwrap();
        for args in [
            vec!["xyz", "colorchecker#red", "--display", s(&p)],
            vec![
                "render",
                "example1",
                "--size",
                "8x8",
                "--display",
                s(&p),
                "-o",
                s(&dir.path().join("x.png")),
            ],
        ] {
            let o = specpoly(&args);
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(1), "{name} {args:?}: {err}");
            assert_eq!(err.trim_end().lines().count(), 1, "{name}: {err}");
            assert!(err.contains(want), "{name}: {err}");
        }
        assert!(!dir.path().join("x.png").exists());
    }
}
