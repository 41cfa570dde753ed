//! Spectral CSV as spreadsheets export it, and CGATS in Latin-1 (issue 10): each file in
//! `crates/cli/tests/data/spreadsheets/` holds the same two spectra as `plain.csv` (written plainly:
//! `,`, decimal points, ASCII), shaped as LibreOffice Calc and Excel write them in a German
//! locale — `;` separators, decimal commas, quoted headers with separators inside, a UTF-8
//! byte-order mark, CRLF, Latin-1 bytes, trailing empty columns and rows, tabs — and must read
//! as the same numbers. Errors name `file:line:column`.

use specpoly_formats::csv::{parse, Table};
use specpoly_formats::read::{decode, text_or_latin1};
use std::path::{Path, PathBuf};
use std::process::Command;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/spreadsheets")
}

fn read(name: &str) -> Table {
    let path = dir().join(name);
    let text = text_or_latin1(&path).unwrap();
    parse(&text, name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn spreadsheet_exports_read_as_the_plain_file() {
    let plain = read("plain.csv");
    assert_eq!(plain.wavelengths.len(), 41);
    for (file, names) in [
        ("libreoffice_de.csv", ["Rot, matt", "Blau"]),
        ("excel_de_utf8.csv", ["Rot, matt", "Blau"]),
        ("excel_de_ansi.csv", ["Rot; matt", "Blau"]),
        ("tab_de.tsv", ["red", "blue"]),
        ("quoted.csv", ["red \"matte\", 2019", "blue"]),
    ] {
        let t = read(file);
        assert_eq!(t.wavelengths, plain.wavelengths, "{file}");
        assert_eq!(t.columns.len(), 2, "{file}: {:?}", t.columns);
        for (k, name) in names.iter().enumerate() {
            assert_eq!(t.columns[k].0, *name, "{file}");
            assert_eq!(t.columns[k].1, plain.columns[k].1, "{file}: {name}");
        }
    }
}

#[test]
fn latin1_headers_decode_and_the_cli_reads_them() {
    let bytes = std::fs::read(dir().join("excel_de_ansi.csv")).unwrap();
    assert!(
        std::str::from_utf8(&bytes).is_err(),
        "the fixture is Latin-1"
    );
    assert!(decode(bytes).starts_with("Wellenlänge;"));
    // the same colour from the Excel export as from the plain file
    let xyz = |spec: String| {
        let out = Command::new(env!("CARGO_BIN_EXE_specpoly"))
            .args(["xyz", &spec, "--json"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v[0]["Y"].as_f64().unwrap()
    };
    let d = dir();
    let excel = xyz(format!(
        "{}#Rot; matt",
        d.join("excel_de_ansi.csv").display()
    ));
    let plain = xyz(format!("{}#red matte", d.join("plain.csv").display()));
    assert_eq!(excel, plain);
}

#[test]
fn errors_name_file_line_and_column() {
    let err = |t: &str| parse(t, "x.csv").unwrap_err().to_string();
    // de_DE: a thousands separator is not a decimal comma
    let e = err("nm;a;b\r\n400;0,1;0,2\r\n410;1.000,5;0,3\r\n");
    assert!(
        e.starts_with("x.csv:3:2: `1.000,5` in column `a` is not a number"),
        "{e}"
    );
    let e = err("nm,a\n400,0.1\n\"410,0.2\n");
    assert!(e.starts_with("x.csv:3:"), "{e}");
    let e = err("nm\ta\tb\n400\t0,1\n");
    assert!(e.starts_with("x.csv:2:"), "{e}");
    assert!(e.contains("2 cells, the header has 3"), "{e}");
    // a comma-separated file keeps `,` as the separator even with `;` in a quoted name
    let t = parse("nm,\"a;b;c\"\n400,0.5\n", "x.csv").unwrap();
    assert_eq!(t.columns[0].0, "a;b;c");
}

#[test]
fn latin1_cgats_reads_with_line_numbers_in_errors() {
    let ti3 = "CTI3\r\nDESCRIPTOR \"Büro-Monitor\"\r\nNUMBER_OF_FIELDS 6\r\nBEGIN_DATA_FORMAT\r\n\
               RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z\r\nEND_DATA_FORMAT\r\nNUMBER_OF_SETS 2\r\n\
               BEGIN_DATA\r\n100 100 100 95.0 100.0 108.0\r\n0 0 0 0.1 0.1 0.1\r\nEND_DATA\r\n";
    let latin1: Vec<u8> = ti3.chars().map(|c| c as u32 as u8).collect();
    assert!(std::str::from_utf8(&latin1).is_err());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("büro.ti3");
    std::fs::write(&path, &latin1).unwrap();
    let t = specpoly_formats::cgats::read_ti3_file(&path).unwrap();
    assert_eq!(t.keyword("DESCRIPTOR"), Some("Büro-Monitor"));
    assert_eq!(t.measurements.len(), 2);
    // every error names its line: a bad number, a missing field, a bad keyword
    let bad = |from: &str, to: &str| {
        let text = ti3.replace(from, to);
        specpoly_formats::cgats::read_ti3(&text, "b.ti3")
            .unwrap_err()
            .to_string()
    };
    assert!(bad("0.1 0.1 0.1", "0.1 x 0.1").starts_with("b.ti3:10:"));
    assert!(bad("XYZ_Z\r\n", "XYZ_W\r\n").starts_with("b.ti3:4:"));
    let e = bad(
        "NUMBER_OF_FIELDS 6",
        "LUMINANCE_XYZ_CDM2 \"1 -2 3\"\r\nNUMBER_OF_FIELDS 6",
    );
    assert!(e.starts_with("b.ti3:3: LUMINANCE_XYZ_CDM2"), "{e}");
}
