//! `calibrate simulate | ccss | ccmx | match`: two simulated displays (QD-OLED and WLED)
//! matched under the CIE 2015 10° observer end within Δu′v′ 0.0005 of each other under it
//! after the 16-bit video LUT, checked by an independent f64 1 nm sum over the CSV tables in
//! `data/cmf/` and the `.cal` as written; bad spectral input is a one-line error and writes
//! nothing.

use crate::common::cli;
use crate::reference_1nm;
use specpoly_calibrate::sim::SimModel;

/// `KM · Σ s·cmf` with the CSV's columns (1 nm from 380 nm), f64.
fn xyz(table: &[Vec<f64>], s: &[f64]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for row in table {
        let i = row[0] as usize;
        if !(380..=780).contains(&i) {
            continue;
        }
        for k in 0..3 {
            out[k] += s[i - 380] * row[k + 1];
        }
    }
    out.map(|v| v * 683.002)
}

fn uv(x: [f64; 3]) -> [f64; 2] {
    let d = x[0] + 15.0 * x[1] + 3.0 * x[2];
    [4.0 * x[0] / d, 9.0 * x[1] / d]
}

#[test]
fn qdoled_and_wled_matched_under_cie_2015_10_agree_within_0_0005_and_keep_their_1931_mismatch() {
    let dir = tempfile::tempdir().unwrap();
    let r = cli::run_in(
        dir.path(),
        &[
            "calibrate",
            "match",
            "--a",
            "sim:qdoled",
            "--b",
            "sim:wled",
            "--observer",
            "2015-10",
            "-o",
            "b.cal",
            "--figure",
            "match.svg",
            "--json",
        ],
    );
    let (code, out, err) = r.parts();
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let row = |name: &str| {
        j["mismatch"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["observer"] == name)
            .unwrap()
            .clone()
    };
    assert!(
        row("2015-10")["delta_uv"].as_f64().unwrap() <= 5e-4,
        "{out}"
    );
    // the 1931 mismatch they keep
    assert!(row("1931")["delta_uv"].as_f64().unwrap() > 2e-3, "{out}");
    assert!(std::fs::read_to_string(dir.path().join("match.svg"))
        .unwrap()
        .contains("<svg"));
    // independently: B's white from the .cal's full-input entries, both whites summed at 1 nm
    // over the CIE 2015 10° CSV
    let cal = std::fs::read_to_string(dir.path().join("b.cal")).unwrap();
    let rows: Vec<Vec<f64>> = cal
        .lines()
        .skip_while(|l| l.trim() != "BEGIN_DATA")
        .skip(1)
        .take_while(|l| l.trim() != "END_DATA")
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 256);
    let last = rows.last().unwrap();
    assert_eq!(last[0], 1.0);
    for v in &last[1..] {
        let q = v * 65535.0;
        assert!((q - q.round()).abs() < 1e-3, "16-bit entries: {v}");
    }
    let (_, table) = reference_1nm::read("cmf/cie2015_10deg_1nm.csv");
    let a = SimModel::parse("qdoled").unwrap();
    let b = SimModel::parse("wled").unwrap();
    let wa = xyz(&table, &a.spectrum([1.0; 3]));
    // wled's transfer curve is a 2.2 power law: the LUT's output drives it
    let light: Vec<f64> = last[1..].iter().map(|v| v.powf(2.2)).collect();
    let sb: Vec<f64> = (0..401)
        .map(|i| (0..3).map(|c| light[c] * b.spectra[c][i]).sum::<f64>() + b.offset_spectrum[i])
        .collect();
    let wb = xyz(&table, &sb);
    let (p, q) = (uv(wa), uv(wb));
    let d = (p[0] - q[0]).hypot(p[1] - q[1]);
    assert!(d <= 5e-4, "Δu′v′ {d}");
}

#[test]
fn bad_spectral_input_is_one_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = cli::run_in(
        dir.path(),
        &[
            "calibrate",
            "simulate",
            "--display",
            "sim:wled",
            "-o",
            "good.ti3",
        ],
    )
    .parts();
    assert_eq!(code, 0, "{err}");
    let good = std::fs::read_to_string(dir.path().join("good.ti3")).unwrap();
    let first_row = good
        .lines()
        .skip_while(|l| *l != "BEGIN_DATA")
        .nth(1)
        .unwrap()
        .to_string();
    let mut nan_row: Vec<&str> = first_row.split_whitespace().collect();
    nan_row[100] = "NaN";
    let cases = [
        (
            "bands.ti3",
            good.replace("SPECTRAL_BANDS \"401\"", "SPECTRAL_BANDS \"400\""),
            "SPECTRAL_BANDS is 400 but the data format has 401 spectral fields",
        ),
        (
            "start.ti3",
            good.replace(
                "SPECTRAL_START_NM \"380.000000\"",
                "SPECTRAL_START_NM \"38O\"",
            ),
            "SPECTRAL_START_NM `38O` is not a number",
        ),
        (
            "nan.ti3",
            good.replacen(&first_row, &nan_row.join(" "), 1),
            "`NaN` is not a number",
        ),
        (
            "field.ti3",
            good.replacen(" SPEC_500 ", " SPEC_900 ", 1),
            "no field SPEC_500",
        ),
    ];
    for (name, text, want) in cases {
        std::fs::write(dir.path().join(name), text).unwrap();
        for args in [
            vec!["calibrate", "ccss", "--ti3", name, "-o", "out.ccss"],
            vec![
                "calibrate",
                "fit",
                "--ti3",
                name,
                "--observer",
                "2015-10",
                "-o",
                "out.toml",
            ],
            vec![
                "calibrate",
                "match",
                "--a",
                "sim:qdoled",
                "--b",
                name,
                "-o",
                "out.cal",
                "--figure",
                "out.svg",
            ],
        ] {
            let (code, out, err) = cli::run_in(dir.path(), &args).parts();
            assert_eq!(code, 1, "{args:?}: {out}{err}");
            let e = err.trim();
            assert_eq!(e.lines().count(), 1, "{e}");
            assert!(e.contains(name) && e.contains(want), "{name}: {e}");
            for f in ["out.ccss", "out.cal", "out.svg", "out.toml"] {
                assert!(!dir.path().join(f).exists(), "{name}: {f} written");
            }
        }
    }
}

/// The fields and rows of a CGATS table's data (fields named by `BEGIN_DATA_FORMAT`).
fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let fields: Vec<String> = text
        .lines()
        .skip_while(|l| l.trim() != "BEGIN_DATA_FORMAT")
        .skip(1)
        .take_while(|l| l.trim() != "END_DATA_FORMAT")
        .flat_map(|l| l.split_whitespace().map(String::from).collect::<Vec<_>>())
        .collect();
    let rows = text
        .lines()
        .skip_while(|l| l.trim() != "BEGIN_DATA")
        .skip(1)
        .take_while(|l| l.trim() != "END_DATA")
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    (fields, rows)
}

/// Column `name` of each row.
fn col(fields: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let j = fields.iter().position(|f| f == name).unwrap();
    rows.iter().map(|r| r[j]).collect()
}

/// Each row's spectrum in W (the file's SPEC_380…SPEC_780 are mW·sr⁻¹·m⁻²·nm⁻¹).
fn spectra(fields: &[String], rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let js: Vec<usize> = (380..=780)
        .map(|nm| {
            fields
                .iter()
                .position(|f| *f == format!("SPEC_{nm}"))
                .unwrap()
        })
        .collect();
    rows.iter()
        .map(|r| js.iter().map(|j| r[*j] / 1000.0).collect())
        .collect()
}

/// `calibrate simulate --observer 2015-10` writes XYZ fields that are the 1 nm sums of its own
/// spectral fields over the CIE 2015 10° CSV (measured: within 1e-6 cd/m² at 6 printed
/// decimals); `calibrate fit --observer 2015-10` on the CIE 1931 file fits the display under
/// that observer: its white is the white patch's 1 nm sum under it. `--observer 1931` gives
/// back the file's own XYZ.
#[test]
fn simulate_and_fit_compute_xyz_under_the_observer() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let (code, out, err) = cli::run_in(dir.path(), args).parts();
        assert_eq!(code, 0, "{args:?}: {err}");
        out
    };
    run(&[
        "calibrate",
        "simulate",
        "--display",
        "sim:qdoled",
        "--observer",
        "2015-10",
        "-o",
        "q10.ti3",
    ]);
    run(&[
        "calibrate",
        "simulate",
        "--display",
        "sim:qdoled",
        "-o",
        "q.ti3",
    ]);
    let (_, cmf10) = reference_1nm::read("cmf/cie2015_10deg_1nm.csv");
    let text = std::fs::read_to_string(dir.path().join("q10.ti3")).unwrap();
    let (f, rows) = table(&text);
    let s = spectra(&f, &rows);
    let got: Vec<Vec<f64>> = ["XYZ_X", "XYZ_Y", "XYZ_Z"]
        .iter()
        .map(|k| col(&f, &rows, k))
        .collect();
    let mut worst = 0.0f64;
    for (i, si) in s.iter().enumerate() {
        let want = xyz(&cmf10, si);
        for k in 0..3 {
            worst = worst.max((got[k][i] - want[k]).abs());
        }
    }
    eprintln!("simulate --observer 2015-10: largest |ΔXYZ| {worst:.2e} cd/m²");
    assert!(worst < 1e-5, "largest |ΔXYZ| {worst} cd/m²");
    // the fit under 2015-10 from the CIE 1931 file
    let (f1, rows1) = table(&std::fs::read_to_string(dir.path().join("q.ti3")).unwrap());
    let white = (0..rows1.len())
        .find(|i| {
            ["RGB_R", "RGB_G", "RGB_B"]
                .iter()
                .all(|k| col(&f1, &rows1, k)[*i] == 100.0)
        })
        .unwrap();
    let want = xyz(&cmf10, &spectra(&f1, &rows1)[white]);
    let show = |toml: &str| -> serde_json::Value {
        serde_json::from_str(&run(&["calibrate", "show", toml, "--json"])).unwrap()
    };
    run(&[
        "calibrate",
        "fit",
        "--ti3",
        "q.ti3",
        "--observer",
        "2015-10",
        "-o",
        "c10.toml",
    ]);
    let w = &show("c10.toml")["white"];
    let sum = want.iter().sum::<f64>();
    for (k, v) in [("x", want[0] / sum), ("y", want[1] / sum)] {
        eprintln!(
            "fit --observer 2015-10: white {k} off by {:.2e}",
            w[k].as_f64().unwrap() - v
        );
        assert!((w[k].as_f64().unwrap() - v).abs() < 1e-6, "{k}: {w} vs {v}");
    }
    assert!(
        (w["Y"].as_f64().unwrap() - want[1]).abs() < 1e-4 * want[1],
        "{w}"
    );
    run(&[
        "calibrate",
        "fit",
        "--ti3",
        "q.ti3",
        "--observer",
        "1931",
        "-o",
        "c2.toml",
    ]);
    run(&["calibrate", "fit", "--ti3", "q.ti3", "-o", "c.toml"]);
    let (a, b) = (show("c2.toml"), show("c.toml"));
    for k in ["X", "Y", "Z"] {
        let (p, q) = (
            a["white"][k].as_f64().unwrap(),
            b["white"][k].as_f64().unwrap(),
        );
        assert!((p - q).abs() < 1e-6 * q, "{k}: {p} vs {q}");
    }
    // no spectra to compute another observer's XYZ from; a colorimeter takes 1931 only
    run(&[
        "calibrate",
        "simulate",
        "--display",
        "sim:wled",
        "--instrument",
        "colorimeter",
        "-o",
        "col.ti3",
    ]);
    for (args, want_code) in [
        (
            vec![
                "calibrate",
                "fit",
                "--ti3",
                "col.ti3",
                "--observer",
                "2015-10",
                "-o",
                "x.toml",
            ],
            1,
        ),
        (
            vec![
                "calibrate",
                "simulate",
                "--display",
                "sim:wled",
                "--instrument",
                "colorimeter",
                "--observer",
                "2015-10",
                "-o",
                "x.ti3",
            ],
            2,
        ),
    ] {
        let (code, out, err) = cli::run_in(dir.path(), &args).parts();
        assert_eq!(code, want_code, "{args:?}: {out}{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(!dir.path().join("x.toml").exists() && !dir.path().join("x.ti3").exists());
    }
}
