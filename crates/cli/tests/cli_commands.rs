//! `fit`, `plot` and `table1` end to end through the real binary, asserting real numbers.

use crate::common::cli;

use cli::specpoly;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = specpoly(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn fit_reports_coefficients_errors_and_delta_e() {
    let v = json(&["fit", "colorchecker#blue", "colorchecker#foliage", "--json"]);
    let fits = v.as_array().unwrap();
    assert_eq!(fits.len(), 2);
    for f in fits {
        let spans = f["spans"].as_array().unwrap();
        assert_eq!(spans.len(), 8, "default: 8 spans");
        for s in spans {
            assert_eq!(s["coefficients"].as_array().unwrap().len(), 4, "cubic");
            let (rms, max) = (s["rms"].as_f64().unwrap(), s["max"].as_f64().unwrap());
            assert!(rms <= max + 1e-9 && max < 0.02, "{s}");
        }
        assert_eq!(spans[0]["from_nm"].as_f64(), Some(380.0));
        assert_eq!(spans[7]["to_nm"].as_f64(), Some(780.0));
        assert!(f["delta_e00"].as_f64().unwrap() < 0.1, "{f}");
    }
    // the paper's layout: 2 spans split at 550 nm, visibly worse
    let v = json(&["fit", "colorchecker#blue", "--repr", "paper", "--json"]);
    let spans = v[0]["spans"].as_array().unwrap();
    assert_eq!(spans.len(), 2);
    assert_eq!(spans[0]["to_nm"].as_f64(), Some(550.0));
    let de = v[0]["delta_e00"].as_f64().unwrap();
    assert!(de > 0.5, "paper fit of blue ΔE00 {de}");
    // the first coefficient is the span mean of the fitted curve: blue is ~0.04 above 550 nm
    let c0 = spans[1]["coefficients"][0].as_f64().unwrap();
    assert!((0.02..0.08).contains(&c0), "{c0}");
    // poly:4x5 — 4 spans of 6 coefficients; illuminant/observer choices are accepted
    let v = json(&[
        "fit",
        "colorchecker#red",
        "--repr",
        "poly:4x5",
        "--illuminant",
        "FL11",
        "--observer",
        "1931",
        "--json",
    ]);
    assert_eq!(v[0]["spans"].as_array().unwrap().len(), 4);
    assert_eq!(
        v[0]["spans"][0]["coefficients"].as_array().unwrap().len(),
        6
    );
    let (code, out, _) = specpoly(&["fit", "colorchecker#red"]);
    assert_eq!(code, 0);
    assert!(out.contains("ΔE00") && out.contains("380-430"), "{out}");
}

#[test]
fn table1_beside_the_paper() {
    let v = json(&["table1", "--json"]);
    assert_eq!(v["spectrum"], "colorchecker#foliage");
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    let paper = [
        [3.532443e-5, 6.953191e-3, 4.819727e-6],
        [2.381345e-6, 2.124504e-2, 3.651482e-6],
    ];
    for (r, p) in rows.iter().zip(paper) {
        let ours = [
            r["reflectance"].as_f64().unwrap(),
            r["xbar"].as_f64().unwrap(),
            r["reduced"].as_f64().unwrap(),
        ];
        let theirs: Vec<f64> = cli::numbers(&r["paper"]);
        assert_eq!(theirs, p.to_vec());
        // x̄ is the same function in both: with the mean squared error on a 10 nm grid our
        // cubic fit of the CIE 1964 x̄ lands within 10 % of the paper's numbers.
        assert!(
            (ours[1] / p[1] - 1.0).abs() < 0.1,
            "x̄ {} vs {}",
            ours[1],
            p[1]
        );
        // the reduction error is far below the x̄ fit error, as the paper says (§6.2)
        assert!(ours[2] < 0.01 * ours[1], "{ours:?}");
        // ... and below the error of fitting the reflectance itself
        assert!(ours[2] < ours[0], "{ours:?}");
        assert!(ours[0] > 0.0 && ours[0] < 1e-3, "{ours:?}");
    }
    let (code, out, _) = specpoly(&["table1", "colorchecker#blue"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("mean squared error") && out.contains("3.532443e-5"),
        "{out}"
    );
}

#[test]
fn plot_svg_and_png() {
    let d = tempfile::tempdir().unwrap();
    let svg = d.path().join("fig4.svg");
    let (code, _, err) = specpoly(&["plot", "colorchecker#blue", "-o", svg.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    // data points (35 samples 380-730 nm), the 2 span curves, the 550 nm boundary
    assert!(text.matches("<circle").count() >= 35, "the data points");
    assert!(text.matches("<polyline").count() >= 3);
    assert!(text.contains("wavelength (nm)") && text.contains("blue"));

    let png = d.path().join("fig5.png");
    let (code, _, err) = specpoly(&[
        "plot",
        "colorchecker#red",
        "colorchecker#blue",
        "--product",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let dec = png::Decoder::new(std::fs::File::open(&png).unwrap());
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (900, 560));
    let px = &buf[..info.buffer_size()];
    // mostly white background, with the blue exact curve and the red reduced curve drawn
    let white = px.chunks(3).filter(|p| p == &[255, 255, 255]).count();
    assert!(white > 900 * 560 / 2);
    assert!(px.chunks(3).any(|p| p[2] > 150 && p[0] < 80), "blue curve");
    assert!(px.chunks(3).any(|p| p[0] > 180 && p[1] < 80), "red curve");
    assert_eq!(
        std::fs::read_dir(d.path()).unwrap().count(),
        2,
        "no temporary files left"
    );
}
