//! Time per frame of the paper's Example 1 and Example 2 in each mode, side by side in one run
//! (docs/performance.md, "Renderer"). `cargo bench -p specpoly --bench render`.
//!
//! - `frame-1thread/*`: 256 × 256, one ray per pixel, on a one-thread pool, so the ratios between
//!   modes are not disturbed by other work on the machine;
//! - `example2-512/*`: the full 512 × 512 Example 2 on every core.
//!
//! Each iteration is a whole frame: converting the scene's spectra, precomputing the lights and
//! tracing every pixel.

#[path = "../tests/common/scenes.rs"]
mod scenes;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use scenes::{camera, environment, ground, material, path_render, sphere_obj};
use specpoly_spectra::repr::Repr;
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
        let mut scene = specpoly_render::load(scene_name).unwrap();
        scene.render.width = 256;
        scene.render.height = 256;
        scene.render.samples = 1;
        for (name, mode) in modes() {
            g.bench_function(BenchmarkId::new(scene_name, name), |b| {
                b.iter(|| pool.install(|| specpoly_render::render(&scene, mode, None).unwrap()))
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("example2-512");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(6));
    let mut scene = specpoly_render::load("example2").unwrap();
    scene.render.width = 512;
    scene.render.height = 512;
    for (name, mode) in modes() {
        if name == "sampled:16" {
            continue;
        }
        g.bench_function(name, |b| {
            b.iter(|| specpoly_render::render(&scene, mode, None).unwrap())
        });
    }
    g.finish();
}

/// A scene of a procedural mesh: a latitude–longitude sphere of 160 × 320 quads (102 080
/// triangles) written as an OBJ file and loaded through the scene file, on a grey floor under
/// a rectangle light and the environment.
fn mesh_scene(dir: &std::path::Path) -> specpoly_render::scene::Scene {
    std::fs::write(
        dir.join("sphere.obj"),
        sphere_obj(160, [0.0, 1.0, 0.0], 1.0),
    )
    .unwrap();
    let toml = [
        path_render(128, 128, 4, 4),
        camera([0.0, 1.5, -4.0], [0.0, 1.0, 0.0]),
        environment("D65", 0.3),
        material("paint", "\"colorchecker#orange\""),
        material("floor", "\"colorchecker#neutral 5\""),
        "[[area_light]]\nspectrum = \"FL11\"\nradiance = 8.0\ncorner = [-1.0, 4.0, -1.0]\n\
         u = [2.0, 0.0, 0.0]\nv = [0.0, 0.0, 2.0]\n"
            .into(),
        "[[mesh]]\nfile = \"sphere.obj\"\nmaterial = \"paint\"\n".into(),
        ground("floor"),
    ]
    .concat();
    let path = dir.join("mesh.toml");
    std::fs::write(&path, toml).unwrap();
    specpoly_render::load(path.to_str().unwrap()).unwrap()
}

/// Rays per second (camera, bounce and shadow rays) of the path tracer, poly mode, on the
/// Cornell box and the 102k-triangle mesh, 1 and 2 threads: printed, then frame times for
/// criterion. Also the path tracer's frame time per mode on the Cornell box.
fn path_tracer(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let mut cornell = specpoly_render::load("cornell").unwrap();
    cornell.render.width = 128;
    cornell.render.height = 128;
    cornell.render.spp = 4;
    let mesh = mesh_scene(dir.path());
    println!("mesh: {} triangles", mesh.triangles.len());
    let mut g = c.benchmark_group("path");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for (name, scene) in [("cornell", &cornell), ("mesh102k", &mesh)] {
            let t0 = std::time::Instant::now();
            let img = pool.install(|| specpoly_render::render(scene, Repr::DEFAULT, None).unwrap());
            let secs = t0.elapsed().as_secs_f64();
            println!(
                "{name}, {threads} thread(s): {} rays in {secs:.3} s: {:.2} Mrays/s",
                img.rays,
                img.rays as f64 / secs / 1e6
            );
            g.bench_function(
                BenchmarkId::new(format!("{name}-{threads}t"), "poly"),
                |b| {
                    b.iter(|| {
                        pool.install(|| {
                            specpoly_render::render(scene, Repr::DEFAULT, None).unwrap()
                        })
                    })
                },
            );
        }
    }
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for (name, mode) in modes() {
        g.bench_function(BenchmarkId::new("cornell-modes-1t", name), |b| {
            b.iter(|| one.install(|| specpoly_render::render(&cornell, mode, None).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, frames, path_tracer);
criterion_main!(benches);
