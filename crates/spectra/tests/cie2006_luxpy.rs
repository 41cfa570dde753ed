//! The CIE 2006 physiological observer (CIE 170-1) against luxpy 1.12.5, an independent
//! implementation (tables made offline by tests/data/cie2006_references.py): the cone
//! fundamentals for ages 20–80 and fields 2–10° within 1e-4 of their peak (1), and x̄ ȳ z̄ at 32
//! years, 2° and 10°, within 1e-4 of the largest value; the fundamentals at 32 years also equal
//! the published CIE 2006 tables (data/cmf), and x̄ ȳ z̄ the CIE 2015 tables, within 3e-4 (one
//! wavelength, 552 nm, where those tables and the TC1-97 data differ).

use specpoly_spectra::cie2006;

/// `(kind, age, field) → 1 nm rows from 390 nm`.
fn luxpy() -> Vec<(String, f64, f64, Vec<[f64; 3]>)> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/cie2006_luxpy.csv"
    ))
    .unwrap();
    let mut out: Vec<(String, f64, f64, Vec<[f64; 3]>)> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let (kind, age, field) = (c[0], c[1].parse().unwrap(), c[2].parse().unwrap());
        let v = [3, 4, 5, 6].map(|k| c[k].parse::<f64>().unwrap());
        let new = out
            .last()
            .is_none_or(|l| l.0 != kind || l.1 != age || l.2 != field);
        if new {
            assert_eq!(v[0], 390.0);
            out.push((kind.to_string(), age, field, Vec::new()));
        }
        out.last_mut().unwrap().3.push([v[1], v[2], v[3]]);
    }
    out
}

/// Largest |ours − theirs| over 390–780 nm, relative to the largest reference value.
fn deviation(ours: &[[f64; 3]; 401], theirs: &[[f64; 3]]) -> f64 {
    assert_eq!(theirs.len(), 391);
    let peak = theirs.iter().flatten().fold(0.0f64, |a, b| a.max(*b));
    let mut worst = 0.0f64;
    for (i, t) in theirs.iter().enumerate() {
        for k in 0..3 {
            worst = worst.max((ours[i + 10][k] - t[k]).abs() / peak);
        }
    }
    worst
}

#[test]
fn fundamentals_equal_luxpy_for_ages_20_to_80_and_fields_2_to_10() {
    let cases = luxpy();
    let mut n = 0;
    for (kind, age, field, rows) in cases.iter().filter(|c| c.0 == "lms") {
        let ours = cie2006::lms(*age, *field).unwrap();
        let d = deviation(&ours, rows);
        eprintln!("lms age {age} field {field}: {d:.1e} of peak");
        assert!(d < 1e-4, "{kind} age {age} field {field}: {d:e}");
        n += 1;
    }
    assert!(n >= 10);
    // below 390 nm the model is zero, as the CIE 2015 tables
    assert_eq!(cie2006::lms(32.0, 2.0).unwrap()[9], [0.0; 3]);
}

#[test]
fn xyz_at_32_years_2_and_10_degrees_equal_luxpy() {
    for (_, age, field, rows) in luxpy().iter().filter(|c| c.0 == "xyz") {
        let ours = cie2006::xyz(*age, *field).unwrap();
        let d = deviation(&ours, rows);
        eprintln!("xyz age {age} field {field}: {d:.1e} of peak");
        assert!(d < 1e-4, "xyz age {age} field {field}: {d:e}");
    }
}

fn table(file: &str) -> Vec<[f64; 3]> {
    std::fs::read_to_string(format!(
        "{}/../../data/cmf/{file}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .lines()
    .skip(1)
    .map(|l| {
        let c: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(c.len(), 4);
        [c[1], c[2], c[3]]
    })
    .collect()
}

#[test]
fn the_32_year_observer_is_the_published_cie_2006_and_2015_one() {
    for (field, lms_file, xyz_file) in [
        (2.0, "cie2006_lms_2deg_1nm.csv", "cie2015_2deg_1nm.csv"),
        (10.0, "cie2006_lms_10deg_1nm.csv", "cie2015_10deg_1nm.csv"),
    ] {
        let d = deviation(&cie2006::lms(32.0, field).unwrap(), &table(lms_file));
        eprintln!("lms 32 years {field}° vs CIE 2006 table: {d:.1e}");
        // the published 1 nm tables and the TC1-97 data behind luxpy differ by 2.7e-4 at one
        // wavelength, 552 nm (l̄ and m̄, 2°; 7e-5 at 10°); luxpy and we agree there to 5e-7
        assert!(d < 3e-4, "lms {field}°: {d:e}");
        let d = deviation(&cie2006::xyz(32.0, field).unwrap(), &table(xyz_file));
        eprintln!("xyz 32 years {field}° vs CIE 2015 table: {d:.1e}");
        assert!(d < 3e-4, "xyz {field}°: {d:e}");
    }
}

#[test]
fn ages_and_fields_outside_the_model_are_refused() {
    for (age, field) in [
        (19.0, 2.0),
        (81.0, 2.0),
        (32.0, 1.0),
        (32.0, 11.0),
        (f64::NAN, 2.0),
    ] {
        let e = cie2006::lms(age, field).unwrap_err().to_string();
        assert!(e.contains("outside"), "{e}");
        assert!(!e.contains('\n'));
    }
    for bad in [
        "age=32",
        "age=x,field=2",
        "age=32,field=2,lens=1",
        "32,2",
        "age=90,field=2",
    ] {
        assert!(cie2006::parse_params(bad, bad).is_err(), "{bad}");
    }
    assert_eq!(
        cie2006::parse_params("", "field=4, age=32").unwrap(),
        (32.0, 4.0)
    );
}
