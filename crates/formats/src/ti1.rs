//! ArgyllCMS `.ti1` patch sets (CGATS table `CTI1`): the device values a display
//! measurement shows, as `targen` writes them and `dispread` reads them.
//!
//! A display `.ti1` has the fields `SAMPLE_ID RGB_R RGB_G RGB_B` (device values 0–100; `targen`
//! adds the expected `XYZ_X XYZ_Y XYZ_Z`, which are ignored here) and `COLOR_REP "RGB"`. The
//! writer writes only the RGB fields: `dispread` needs no more (tested against the real
//! binary in crates/cli/tests/calibrate_argyll.rs).

use crate::cgats;
use crate::{Error, Result};

/// The device values (each in `[0, 1]`) of a `.ti1`, in file order. Errors are one line.
pub fn read_ti1(text: &str, source: &str) -> Result<Vec<[f64; 3]>> {
    let tables = cgats::parse(text, source)?;
    let t = &tables[0];
    if t.kind != "CTI1" {
        return Err(Error::Cgats {
            file: source.to_string(),
            line: None,
            why: format!(
                "a `{}` table, not a CTI1 patch set (ArgyllCMS targen's .ti1)",
                t.kind
            ),
        });
    }
    const NEED: [&str; 3] = ["RGB_R", "RGB_G", "RGB_B"];
    let mut col = [0usize; 3];
    for (c, name) in col.iter_mut().zip(NEED) {
        *c = t.field(name).ok_or_else(|| Error::Cgats {
            file: source.to_string(),
            line: None,
            why: format!(
                "no field {name}: a display patch set needs RGB_R RGB_G RGB_B (targen -d3)"
            ),
        })?;
    }
    if t.rows.is_empty() {
        return Err(Error::Cgats {
            file: source.to_string(),
            line: None,
            why: "no patches".into(),
        });
    }
    let mut out = Vec::with_capacity(t.rows.len());
    for (line, row) in &t.rows {
        let mut d = [0.0; 3];
        for k in 0..3 {
            let v = &row[col[k]];
            d[k] = match v.parse::<f64>() {
                Ok(x) if x.is_finite() && (-1e-6..=100.0 + 1e-6).contains(&x) => {
                    (x / 100.0).clamp(0.0, 1.0)
                }
                _ => {
                    return Err(Error::CgatsNumber {
                        file: source.to_string(),
                        line: *line,
                        field: NEED[k].into(),
                        value: v.clone(),
                        range: Some("0–100"),
                    })
                }
            };
        }
        out.push(d);
    }
    Ok(out)
}

/// A `.ti1` of `devices` (each in `[0, 1]`) that `dispread` measures.
pub fn write_ti1(devices: &[[f64; 3]], descriptor: &str) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "CTI1\n");
    let _ = writeln!(s, "DESCRIPTOR \"{}\"", descriptor.replace('"', "'"));
    let _ = writeln!(s, "ORIGINATOR \"specpoly\"");
    let _ = writeln!(s, "COLOR_REP \"RGB\"");
    let _ = writeln!(s, "\nNUMBER_OF_FIELDS 4");
    let _ = writeln!(
        s,
        "BEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B\nEND_DATA_FORMAT\n"
    );
    let _ = writeln!(s, "NUMBER_OF_SETS {}", devices.len());
    let _ = writeln!(s, "BEGIN_DATA");
    for (i, d) in devices.iter().enumerate() {
        let _ = writeln!(
            s,
            "{} {:.5} {:.5} {:.5}",
            i + 1,
            d[0] * 100.0,
            d[1] * 100.0,
            d[2] * 100.0
        );
    }
    let _ = writeln!(s, "END_DATA");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roundtrip_and_refusals() {
        let d = vec![[0.0, 0.5, 1.0], [128.0 / 255.0, 0.0, 0.25]];
        let back = read_ti1(&write_ti1(&d, "x"), "f").unwrap();
        for (a, b) in d.iter().zip(&back) {
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() < 1e-7);
            }
        }
        let ti3 = "CTI3\n\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B\nEND_DATA_FORMAT\nNUMBER_OF_SETS 1\nBEGIN_DATA\n1 0 0 0\nEND_DATA\n";
        assert!(read_ti1(ti3, "f").unwrap_err().to_string().contains("CTI3"));
        let bad = ti3.replace("CTI3", "CTI1").replace("1 0 0 0", "1 0 0 101");
        let e = read_ti1(&bad, "f").unwrap_err().to_string();
        assert!(e.starts_with("f:9: RGB_B `101`"), "{e}");
    }
}
