//! Time per frame of the paper's Example 1 and Example 2 in each mode, side by side in one run
//! (docs/performance.md, "Renderer"). `cargo bench -p specpoly --bench render`.
//!
//! - `frame-1thread/*`: 256 × 256, one ray per pixel, on a one-thread pool, so the ratios between
//!   modes are not disturbed by other work on the machine;
//! - `example2-512/*`: the full 512 × 512 Example 2 on every core.
//!
//! Each iteration is a whole frame: converting the scene's spectra, precomputing the lights and
//! tracing every pixel.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use specpoly::render;
use specpoly::repr::Repr;
use std::time::Duration;

fn modes() -> Vec<(&'static str, Repr)> {
    ["rgb", "paper", "poly", "sampled:16", "sampled:81"]
        .into_iter()
        .map(|m| (m, m.parse().unwrap()))
        .collect()
}

fn frames(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("frame-1thread");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for scene_name in ["example1", "example2"] {
        let mut scene = render::load(scene_name).unwrap();
        scene.render.width = 256;
        scene.render.height = 256;
        scene.render.samples = 1;
        for (name, mode) in modes() {
            g.bench_function(BenchmarkId::new(scene_name, name), |b| {
                b.iter(|| pool.install(|| render::render(&scene, mode, None).unwrap()))
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("example2-512");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(6));
    let mut scene = render::load("example2").unwrap();
    scene.render.width = 512;
    scene.render.height = 512;
    for (name, mode) in modes() {
        if name == "sampled:16" {
            continue;
        }
        g.bench_function(name, |b| {
            b.iter(|| render::render(&scene, mode, None).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
