//! Observers given as data: `--observer` values and sensitivity CSV files. A good file is read
//! onto the 1 nm grid exactly (the CIE 1931 table as a CSV is the built-in observer to the bit);
//! every bad one is refused with one line naming the file.

use specpoly_core::Observer;
use specpoly_spectra::observer::{from_csv_text, parse};

fn cie1931_csv() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/cmf/cie1931_2deg_1nm.csv"
    ))
    .unwrap()
}

#[test]
fn a_csv_of_the_1931_table_is_the_builtin_observer() {
    let t = from_csv_text(&cie1931_csv(), "cie1931.csv").unwrap();
    assert_eq!(t.values(), Observer::Cie1931.table());
    assert_eq!(t.name(), "file:cie1931.csv");
}

#[test]
fn a_coarse_camera_table_is_interpolated_and_zero_outside_its_data() {
    let csv = "wavelength_nm,r,g,b\n400,0,0.1,0.8\n500,0.1,0.6,0.4\n600,0.9,0.3,0\n700,0.2,0,0\n";
    let t = from_csv_text(csv, "camera.csv").unwrap();
    let v = t.values();
    assert_eq!(v[19], [0.0; 3]); // 399 nm: outside the data
    assert_eq!(v[20], [0.0, 0.1, 0.8]);
    assert!((v[170][0] - 0.5).abs() < 1e-6); // 550 nm, halfway
    assert_eq!(v[321], [0.0; 3]); // 701 nm
}

#[test]
fn bad_sensitivity_files_are_refused_in_one_line() {
    let cases: [(&str, &str); 7] = [
        (
            "wavelength_nm,x,y,z\n400,0,1,1\n550,-0.1,1,1\n700,1,1,1\n",
            "negative",
        ),
        (
            "wavelength_nm,x,y,z\n400,0,1,1\n550,,1,1\n700,1,1,1\n",
            "empty cell",
        ),
        (
            "wavelength_nm,x,y,z\n400,0,1,1\n700,1,1,1\n550,1,1,1\n",
            "wavelength",
        ),
        (
            "wavelength_nm,x,y,z\n450,0,1,1\n550,1,1,1\n650,1,1,1\n",
            "400-700",
        ),
        ("wavelength_nm,x,y\n400,0,1\n700,1,1\n", "3"),
        (
            "wavelength_nm,x,y,z\n400,0,1,0\n700,1,1,0\n",
            "zero everywhere",
        ),
        (
            "wavelength_nm,x,y,z\n400,0,1,1\n550,nan,1,1\n700,1,1,1\n",
            "file.csv",
        ),
    ];
    for (csv, says) in cases {
        let e = from_csv_text(csv, "file.csv").unwrap_err().to_string();
        assert!(e.contains(says), "{e}");
        assert!(e.contains("file.csv"), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }
}

#[test]
fn observer_values_parse() {
    assert_eq!(parse("2015-10").unwrap(), Observer::Cie2015_10);
    assert_eq!(parse("10").unwrap(), Observer::Cie1964);
    let a = parse("cie2006:age=50,field=4").unwrap();
    assert_eq!(a.name(), "cie2006:age=50,field=4");
    // the same observer asked twice is kept once
    let b = parse("cie2006:field=4,age=50").unwrap();
    match (a, b) {
        (Observer::Table(x), Observer::Table(y)) => assert!(std::ptr::eq(x, y)),
        _ => panic!("not runtime tables"),
    }
    let e = parse("cie2006:age=85,field=4").unwrap_err().to_string();
    assert!(e.contains("age 85 outside"), "{e}");
    let e = parse("no-such-observer.csv").unwrap_err().to_string();
    assert!(e.starts_with("unknown observer"), "{e}");
}
