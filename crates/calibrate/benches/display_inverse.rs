//! The full display model's inverse (`DisplayModel::inverse`, behind `Calibration::inverse`,
//! `render --display` and `xyz --display`): time per colour over the 13³ device grid of
//! `crates/calibrate/tests/display_inverse.rs` (dense near black), the prediction of each grid colour
//! inverted, on the shipped displays fitted with the default model (docs/calibration.md, "The
//! full model's inverse"). `cargo bench -p specpoly --bench display_inverse`.
//!
//! Each iteration inverts all 2 197 colours; the figure per colour is the time / 2 197.

#[path = "../tests/common/displays.rs"]
mod displays;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use specpoly_core::Xyz;
use std::time::Duration;

/// Grid points per side, as in the round-trip test.
const GRID: usize = 13;

const DISPLAYS: [(&str, &str); 3] = [
    ("acer", "acer-xb271hu-unit1_dispread_2068.ti3"),
    ("lenovo", "lenovo-thinkpad-x61_825.ti3"),
    ("surface", "microsoft-surface-pro-2017_825.ti3"),
];

fn inverse(c: &mut Criterion) {
    let mut g = c.benchmark_group("inverse");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for (label, file) in DISPLAYS {
        let cal = displays::fitted(file);
        let model = cal.model();
        let wanted: Vec<Xyz> = (0..GRID * GRID * GRID)
            .map(|i| {
                let rgb = [i / (GRID * GRID), i / GRID % GRID, i % GRID]
                    .map(|v| (v as f32 / (GRID - 1) as f32).powf(1.5));
                model.device_to_xyz(rgb)
            })
            .collect();
        g.throughput(Throughput::Elements(wanted.len() as u64));
        g.bench_with_input(BenchmarkId::from_parameter(label), &wanted, |b, w| {
            b.iter(|| {
                for x in w {
                    black_box(model.inverse(black_box(*x)));
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, inverse);
criterion_main!(benches);
