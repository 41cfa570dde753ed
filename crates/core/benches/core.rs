//! Multiply (+ reduce) and →XYZ for every representation, side by side in one run
//! (`cargo bench -p specpoly-core --bench core`). Figures: docs/performance.md.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use specpoly_core::{
    DefaultSpectrum, Illuminant, Observer, PaperSpectrum, Rgb, Sampled, Shade, Tabulated,
};

fn reflectances() -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let w: Vec<f32> = (0..41).map(|i| 380.0 + 10.0 * i as f32).collect();
    let a = w
        .iter()
        .map(|x| 0.1 + 0.7 / (1.0 + ((600.0 - x) / 20.0).exp()))
        .collect();
    let b = w
        .iter()
        .map(|x| 0.2 + 0.6 * (-((x - 470.0) / 60.0).powi(2)).exp())
        .collect();
    (w, a, b)
}

fn bench_one<T: Shade>(c: &mut Criterion, name: &str) {
    let (w, a, b) = reflectances();
    let light = T::light(Observer::Cie1964, &Illuminant::FL11.tabulated());
    let x = T::from_reflectance(&Tabulated::new(&w, &a).unwrap(), &light).unwrap();
    let y = T::from_reflectance(&Tabulated::new(&w, &b).unwrap(), &light).unwrap();
    c.bench_with_input(BenchmarkId::new("multiply", name), &(x, y), |bn, (x, y)| {
        bn.iter(|| black_box(x).mul(black_box(y)))
    });
    c.bench_with_input(BenchmarkId::new("to_xyz", name), &x, |bn, x| {
        bn.iter(|| black_box(x).xyz(black_box(&light)))
    });
}

fn all(c: &mut Criterion) {
    bench_one::<Rgb>(c, "rgb");
    bench_one::<PaperSpectrum>(c, "paper 2x3");
    bench_one::<DefaultSpectrum>(c, "default 8x3");
    bench_one::<Sampled<16>>(c, "sampled 16");
    bench_one::<Sampled<41>>(c, "sampled 41");
    bench_one::<Sampled<81>>(c, "sampled 81");
}

criterion_group!(benches, all);
criterion_main!(benches);
