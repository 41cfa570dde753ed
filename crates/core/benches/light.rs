//! Light metrics and LED mixing (`cargo bench -p specpoly-core --bench light`).
//! Figures: docs/leds.md.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use specpoly_core::light::{
    cct::{cct_duv, Cct},
    cri::cri,
    mix::{solve_mix, Objective, Target},
    tm30::tm30,
    Samples, Source,
};
use specpoly_core::Tabulated;

fn channels() -> Vec<Source> {
    let text = include_str!("../../../data/leds/rgbwa.csv");
    let rows: Vec<Vec<f32>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let nm: Vec<f32> = rows.iter().map(|r| r[0]).collect();
    (1..6)
        .map(|c| {
            let v: Vec<f32> = rows.iter().map(|r| r[c]).collect();
            Source::new(&Tabulated::new(&nm, &v).unwrap()).unwrap()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let ch = channels();
    let tcs = Samples::cie13_3();
    let ces = Samples::cie224();
    let d = [0.3, 0.5, 0.2, 1.0, 0.4];
    let parts: Vec<(f64, &Source)> = d.iter().copied().zip(&ch).collect();
    let light = Source::mix(&parts).unwrap();
    let uv = light.uv();
    c.bench_function("source mix (5 channels)", |b| {
        b.iter(|| Source::mix(black_box(&parts)).unwrap())
    });
    c.bench_function("cct_duv", |b| b.iter(|| cct_duv(black_box(uv)).unwrap()));
    c.bench_function("cri (Ra, 14 TCS)", |b| {
        b.iter(|| cri(black_box(&light), &tcs).unwrap())
    });
    c.bench_function("tm30 (Rf, Rg, 99 CES)", |b| {
        b.iter(|| tm30(black_box(&light), &ces).unwrap())
    });
    let t = Target::Cct(Cct {
        cct: 4000.0,
        duv: 0.0,
    });
    c.bench_function("solve_mix rgbwa 4000 K efficacy", |b| {
        b.iter(|| solve_mix(black_box(&ch), t, 0.8, Objective::Efficacy).unwrap())
    });
    let mut g = c.benchmark_group("slow");
    g.sample_size(10);
    g.bench_function("solve_mix rgbwa 4000 K rf", |b| {
        b.iter(|| solve_mix(black_box(&ch), t, 0.8, Objective::Rf(&ces)).unwrap())
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
