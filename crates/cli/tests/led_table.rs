//! The drive-correction table (`specpoly_core::drive_table`, `specpoly_led::DriveTable`)
//! that carries the full display model to the LED controller: its interpolation error against
//! the exact inverse (`DisplayModel::inverse`) on the shipped real displays (data/ti3) fitted
//! with the default model. For a dense sample of the controller's matrix-model device values
//! `d` (off the nodes), the full model at the table's corrected values must show the matrix
//! model's colour `f_m(d)` within `TABLE_DE` (and `TABLE_MEAN_DE` on average) wherever the exact inverse reaches it. ΔE00 is
//! `palette`'s CIEDE2000 (CIELAB relative to the full model's white), independent of ours.
//!
//! `cargo test -p specpoly --test led_table -- --ignored --nocapture` prints the table of
//! grid sides against error (docs/calibration.md, "The full model on the controller").

use crate::common::displays;

use displays::{de00, fitted, shipped};
use rayon::prelude::*;
use specpoly_core::drive_table::correction;
use specpoly_core::{Display, DisplayModel};
use specpoly_led::table::{controller_display, DEFAULT_GRID, TABLE_DE, TABLE_MEAN_DE};
use specpoly_led::DriveTable;

/// Sample points per side: `(i + 0.5) / SAMPLE`, between the nodes of every grid tried.
const SAMPLE: usize = 14;

/// Mean and max ΔE00 of the table's colours against the matrix model's, over the sample points
/// the exact inverse reaches (ΔE00 ≤ 0.01); and how many those are.
fn table_error(
    model: &DisplayModel<{ specpoly_core::display_model::FULL }>,
    matrix: &Display,
    table: &DriveTable,
) -> (f64, f64, usize) {
    let white: [f64; 3] = model.white().into();
    let pts: Vec<[f32; 3]> = (0..SAMPLE * SAMPLE * SAMPLE)
        .map(|i| {
            [i / (SAMPLE * SAMPLE), i / SAMPLE % SAMPLE, i % SAMPLE]
                .map(|n| (n as f32 + 0.5) / SAMPLE as f32)
        })
        .collect();
    let errs: Vec<f64> = pts
        .par_iter()
        .filter_map(|d| {
            let want = matrix.device_to_xyz(*d);
            let w: [f64; 3] = want.into();
            let exact = model.inverse(want);
            let reached: [f64; 3] = model.device_to_xyz(exact.device).into();
            if de00(reached, w, white) > 0.01 {
                return None;
            }
            let mut t = table.table().unwrap();
            let c = correction(&mut t, *d);
            let dd = [0, 1, 2].map(|k| (d[k] + c[k]).clamp(0.0, 1.0));
            let got: [f64; 3] = model.device_to_xyz(dd).into();
            Some(de00(got, w, white))
        })
        .collect();
    let n = errs.len();
    let mean = errs.iter().sum::<f64>() / n.max(1) as f64;
    let max = errs.iter().cloned().fold(0.0, f64::max);
    (mean, max, n)
}

#[test]
#[ignore = "prints the grid-side table for docs/calibration.md (≈ 1 min)"]
fn grid_sides_against_the_exact_inverse() {
    for name in shipped() {
        let name = name.as_str();
        let cal = fitted(name);
        let matrix = controller_display(&cal.display()).unwrap();
        let zero = DriveTable {
            grid: 2,
            nodes: vec![[0; 3]; 8],
        };
        let (mean, max, n) = table_error(cal.model(), &matrix, &zero);
        println!("{name} matrix model alone: mean {mean:.4} max {max:.4} over {n}");
        for g in [5, 9, 13, 17] {
            let t = DriveTable::build(cal.model(), &matrix, g);
            let (mean, max, n) = table_error(cal.model(), &matrix, &t);
            println!("{name} grid {g}: mean {mean:.4} max {max:.4} over {n}");
        }
    }
}

/// The default grid's table on the Surface and the Lenovo (the two panels with the strongest
/// interaction) stays within [`TABLE_DE`] of the exact inverse.
#[test]
fn the_default_table_is_within_its_bound() {
    for name in [
        "lenovo-thinkpad-x61_825.ti3",
        "microsoft-surface-pro-2017_825.ti3",
    ] {
        let cal = fitted(name);
        let matrix = controller_display(&cal.display()).unwrap();
        let t = DriveTable::build(cal.model(), &matrix, DEFAULT_GRID);
        let (mean, max, n) = table_error(cal.model(), &matrix, &t);
        assert!(
            n > SAMPLE * SAMPLE * SAMPLE / 2,
            "{name}: {n} sample colours reached"
        );
        assert!(max <= TABLE_DE, "{name}: mean {mean} max {max}");
        assert!(mean <= TABLE_MEAN_DE, "{name}: mean {mean} max {max}");
    }
}
