//! Reading the light tests' reference tables (`crates/core/tests/data/`, `data/leds/`): CSV with `#`
//! comment lines, and spectral tables of a wavelength column and named value columns. Include
//! it with `#[path = "common/light_data.rs"] mod light_data;`.
#![allow(dead_code)]

/// The header and the rows of a CSV text (comment and blank lines skipped, fields trimmed).
pub fn csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.trim().to_string()).collect())
        .collect();
    (head, rows)
}

/// A spectral table: the wavelengths (first column) and every other column by its name.
pub fn table(text: &str) -> (Vec<f32>, Vec<(String, Vec<f32>)>) {
    let (head, rows) = csv(text);
    let nm = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    let cols = (1..head.len())
        .map(|c| {
            (
                head[c].clone(),
                rows.iter().map(|r| r[c].parse().unwrap()).collect(),
            )
        })
        .collect();
    (nm, cols)
}

/// The lamps' SPDs at 5 nm (`data/light_spds_5nm.csv`).
pub fn lamp_spds() -> (Vec<f32>, Vec<(String, Vec<f32>)>) {
    table(include_str!("../data/light_spds_5nm.csv"))
}
