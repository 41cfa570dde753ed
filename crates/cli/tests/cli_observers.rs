//! `--observer` end to end: a sensitivity CSV holding the CIE 1931 table gives the built-in
//! observer's numbers; bad CSVs and ages outside the CIE 2006 model are refused with one line,
//! a non-zero exit and nothing written; `light --observer` reports the light under it.

use crate::common::cli::specpoly;

fn xyz(observer: &str) -> serde_json::Value {
    let (code, out, err) = specpoly(&[
        "xyz",
        "colorchecker#red",
        "colorchecker#blue",
        "--repr",
        "exact",
        "--json",
        "--observer",
        observer,
    ]);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn a_csv_of_the_1931_table_is_the_1931_observer() {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/cmf/cie1931_2deg_1nm.csv"
    );
    assert_eq!(xyz(file), xyz("1931"));
    // and the observers differ from each other
    assert_ne!(xyz("2015-10"), xyz("1964"));
    assert_ne!(xyz("cie2006:age=70,field=4"), xyz("2015-10"));
}

#[test]
fn bad_observers_are_refused_in_one_line_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "negative.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n550,-0.1,1,1\n700,1,1,1\n",
        ),
        (
            "missing.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n550,,1,1\n700,1,1,1\n",
        ),
        (
            "order.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n700,1,1,1\n550,1,1,1\n",
        ),
        (
            "short.csv",
            "wavelength_nm,x,y,z\n450,0,1,1\n550,1,1,1\n650,1,1,1\n",
        ),
    ];
    let mut observers: Vec<String> = cases
        .iter()
        .map(|(name, text)| {
            let p = dir.path().join(name);
            std::fs::write(&p, text).unwrap();
            p.display().to_string()
        })
        .collect();
    observers.push("cie2006:age=85,field=4".into());
    observers.push("cie2006:age=30,field=12".into());
    observers.push("2016".into());
    for o in &observers {
        let png = dir.path().join("out.png");
        for args in [
            vec!["xyz", "colorchecker#red", "--observer", o],
            vec!["light", "D65", "--observer", o],
            vec!["render", "example1", "--size", "8x8", "--observer", o, "-o"],
        ] {
            let mut args: Vec<&str> = args;
            if args[0] == "render" {
                args.push(png.to_str().unwrap());
            }
            let (code, out, err) = specpoly(&args);
            assert_ne!(code, 0, "{args:?}");
            assert!(out.is_empty(), "{args:?}: {out}");
            assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
            assert!(!png.exists(), "{args:?}");
        }
    }
}

#[test]
fn light_reports_its_colour_under_the_observer() {
    let (code, out, err) = specpoly(&["light", "FL11", "--json", "--observer", "1931"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in ["X", "Y", "Z", "x", "y", "u_prime", "v_prime"] {
        let (a, b) = (v[k].as_f64().unwrap(), v["observer"][k].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-6 * a.abs().max(1.0), "{k}: {a} {b}");
    }
    let (code, out, _) = specpoly(&["light", "FL11", "--json", "--observer", "2015-10"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["observer"]["name"], "2015-10");
    assert!((v["observer"]["x"].as_f64().unwrap() - v["x"].as_f64().unwrap()).abs() > 1e-3);
}
