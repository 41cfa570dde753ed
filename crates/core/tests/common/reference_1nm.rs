//! The independent 1 nm reference's data: the project's CSV files in `data/` read directly (no
//! library code), linearly interpolated to 1 nm over 380–780 nm with the end values held. Shared
//! by the reference tests of several crates: `core`'s test binary has it as `common`, the
//! others include it with `#[path = "../../core/tests/common/reference_1nm.rs"] mod
//! reference_1nm;` in their `tests/main.rs`.
#![allow(dead_code)]

/// The header and numeric rows of `data/PATH` (blank and `#` lines skipped).
pub fn read(path: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let p = format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{p}: {e}"));
    let mut lines = text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.trim().parse().unwrap()).collect())
        .collect();
    (head, rows)
}

/// `(wavelengths, values)` of column `j` of rows read by [`read`].
pub fn column_at(rows: &[Vec<f64>], j: usize) -> (Vec<f64>, Vec<f64>) {
    (
        rows.iter().map(|r| r[0]).collect(),
        rows.iter().map(|r| r[j]).collect(),
    )
}

/// `(wavelengths, values)` of the column called `name` in `data/PATH`.
pub fn column(path: &str, name: &str) -> (Vec<f64>, Vec<f64>) {
    let (head, rows) = read(path);
    let j = head
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("{path}: no column {name}"));
    column_at(&rows, j)
}

/// The linear interpolant of `(x, y)` at `nm`, end values held beyond the table.
pub fn interp(x: &[f64], y: &[f64], nm: f64) -> f64 {
    if nm <= x[0] {
        return y[0];
    }
    if nm >= x[x.len() - 1] {
        return y[y.len() - 1];
    }
    let i = x.iter().position(|v| *v > nm).unwrap();
    y[i - 1] + (y[i] - y[i - 1]) * (nm - x[i - 1]) / (x[i] - x[i - 1])
}

/// [`interp`] at 380, 381, …, 780 nm.
pub fn to_1nm(x: &[f64], y: &[f64]) -> Vec<f64> {
    (380..=780).map(|nm| interp(x, y, nm as f64)).collect()
}

/// The colour-matching functions of `data/cmf/FILE` (a 1 nm table) at 380–780 nm.
pub fn cmf_1nm(file: &str) -> Vec<[f64; 3]> {
    let (_, rows) = read(&format!("cmf/{file}"));
    (380..=780)
        .map(|nm| {
            let r = rows.iter().find(|r| r[0] as i32 == nm).unwrap();
            [r[1], r[2], r[3]]
        })
        .collect()
}

/// The illuminant `data/illuminants/NAME.csv` at 1 nm.
pub fn light_1nm(name: &str) -> Vec<f64> {
    let (_, rows) = read(&format!("illuminants/{name}.csv"));
    let (x, y) = column_at(&rows, 1);
    to_1nm(&x, &y)
}
