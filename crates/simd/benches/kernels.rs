//! The shading kernels per call, every path side by side in one run
//! (`cargo bench -p specpoly-simd --bench kernels`; figures and method: docs/performance.md,
//! "Kernels at the floor").
//!
//! What is measured is the kernel, not the harness: each sample runs the kernel over a batch of
//! [`BATCH`] different inputs, writing into a preallocated output slice, and the batch time is
//! divided by [`BATCH`] (`iter_custom`), so criterion's figures are nanoseconds per call. Only
//! the slices' addresses pass through `black_box`, once per batch: no per-call read-back of a
//! 128-byte result, no per-call barrier. Inputs and outputs (≤ 62 KiB) stay in L1/L2.
//!
//! On a loaded machine criterion's medians swing 2–3×: run with `--sample-size 1000
//! --measurement-time 4` and take the 5th percentile of the per-sample means
//! (`target/criterion/*/*/new/sample.json`, `times[i] / iters[i]`), as docs/performance.md does.
//!
//! Paths, per representation:
//! - `naive`: a plain scalar reference — the product span by span (`Cheb::mul_truncated`),
//!   XYZ as one running sum per axis (no lanes);
//! - `portable`: the core's kernel as built for the x86-64 baseline (SSE2), inlined in the loop;
//! - `runtime`: [`Wide`]'s per-call choice, as the ray tracer calls it (a cached flag, then the
//!   AVX2 + FMA kernel as a call; for sampled-81's product, the portable product inlined);
//! - `avx2-loop`: the AVX2 + FMA kernel inlined into an AVX2 loop (one check per batch).
//!
//! A third group times the renderer's most frequent pair, `xyz(a·b, L)`: portable, as two
//! run-time calls, and as one fused call ([`Shade::mul_xyz`]).

use criterion::{black_box, criterion_group, criterion_main, Bencher, BenchmarkId, Criterion};
use specpoly_core::{
    DefaultSpectrum, Illuminant, Layout, Moments, Observer, PaperSpectrum, Sampled, SampledLight,
    Shade, Spectrum, Tabulated, Xyz,
};
use specpoly_simd::{Avx2Fma, Kernels, Wide};
use std::time::{Duration, Instant};

/// Calls per batch.
const BATCH: usize = 64;

/// `2 · BATCH` smooth reflectances (a sigmoid edge plus a Gaussian bump, varied), at 5 nm.
fn inputs<T: Shade>(light: &T::Light) -> (Vec<T>, Vec<T>) {
    let nm: Vec<f32> = (0..81).map(|i| 380.0 + 5.0 * i as f32).collect();
    let one = |i: usize| {
        let edge = 400.0 + (i * 37 % 360) as f32;
        let width = 8.0 + (i * 13 % 40) as f32;
        let bump = 380.0 + (i * 53 % 400) as f32;
        let v: Vec<f32> = nm
            .iter()
            .map(|x| {
                0.05 + 0.6 / (1.0 + ((edge - x) / width).exp())
                    + 0.3 * (-((x - bump) / 40.0).powi(2)).exp()
            })
            .collect();
        T::from_reflectance(&Tabulated::new(&nm, &v).unwrap(), light).unwrap()
    };
    (
        (0..BATCH).map(one).collect(),
        (BATCH..2 * BATCH).map(one).collect(),
    )
}

/// Times `batch` (one pass over [`BATCH`] inputs) and reports nanoseconds per call.
fn per_call(b: &mut Bencher, mut batch: impl FnMut()) {
    b.iter_custom(|iters| {
        let start = Instant::now();
        for _ in 0..iters {
            batch();
        }
        start.elapsed() / BATCH as u32
    });
}

fn naive_mul<const S: usize, const C: usize, L: Layout<S>>(
    a: &Spectrum<S, C, L>,
    b: &Spectrum<S, C, L>,
) -> Spectrum<S, C, L> {
    Spectrum::from_spans(core::array::from_fn(|s| {
        a.span(s).mul_truncated(&b.span(s))
    }))
}

fn naive_xyz<const S: usize, const C: usize, L: Layout<S>>(
    a: &Spectrum<S, C, L>,
    light: &Moments<S, C, L>,
) -> Xyz {
    let c = a.coefficients();
    let m = light.moments();
    let mut out = [0.0f32; 3];
    for axis in 0..3 {
        for k in 0..C {
            for s in 0..S {
                out[axis] += m[axis][k][s] * c[k][s];
            }
        }
    }
    Xyz::from_array(out)
}

fn naive_mul_sampled<const N: usize>(a: &Sampled<N>, b: &Sampled<N>) -> Sampled<N> {
    let mut r = [0.0f32; N];
    for i in 0..N {
        r[i] = a.0[i] * b.0[i];
    }
    Sampled(r)
}

fn naive_xyz_sampled<const N: usize>(a: &Sampled<N>, light: &SampledLight<N>) -> Xyz {
    let w = light.weights();
    let mut out = [0.0f32; 3];
    for axis in 0..3 {
        for i in 0..N {
            out[axis] += w[axis][i] * a.0[i];
        }
    }
    Xyz::from_array(out)
}

fn bench_repr<T: Kernels>(
    c: &mut Criterion,
    name: &str,
    naive_mul: fn(&T, &T) -> T,
    naive_xyz: fn(&T, &T::Light) -> Xyz,
) {
    let light = T::light(Observer::Cie1964, &Illuminant::FL11.tabulated());
    let (a, b) = inputs::<T>(&light);
    let wa: Vec<Wide<T>> = a.iter().copied().map(Wide).collect();
    let wb: Vec<Wide<T>> = b.iter().copied().map(Wide).collect();
    let zero = T::constant(0.0, &light);
    let mut out = vec![zero; BATCH];
    let mut wout = vec![Wide(zero); BATCH];
    let mut xyz = vec![Xyz::default(); BATCH];
    let avx2 = Avx2Fma::detect();

    let mut g = c.benchmark_group("multiply");
    g.bench_function(BenchmarkId::new(name, "naive"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&a, &b));
            for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
                *o = naive_mul(x, y);
            }
            black_box(&mut out);
        })
    });
    g.bench_function(BenchmarkId::new(name, "portable"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&a, &b));
            for ((o, x), y) in out.iter_mut().zip(a).zip(b) {
                *o = x.mul(y);
            }
            black_box(&mut out);
        })
    });
    g.bench_function(BenchmarkId::new(name, "runtime"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&wa, &wb));
            for ((o, x), y) in wout.iter_mut().zip(a).zip(b) {
                *o = x.mul(y);
            }
            black_box(&mut wout);
        })
    });
    if let Some(k) = avx2 {
        g.bench_function(BenchmarkId::new(name, "avx2-loop"), |bn| {
            per_call(bn, || {
                let (a, b) = black_box((&a, &b));
                T::mul_each(k, a, b, &mut out);
                black_box(&mut out);
            })
        });
    }
    g.finish();

    let mut g = c.benchmark_group("to_xyz");
    g.bench_function(BenchmarkId::new(name, "naive"), |bn| {
        per_call(bn, || {
            let a = black_box(&a);
            for (o, x) in xyz.iter_mut().zip(a) {
                *o = naive_xyz(x, &light);
            }
            black_box(&mut xyz);
        })
    });
    g.bench_function(BenchmarkId::new(name, "portable"), |bn| {
        per_call(bn, || {
            let a = black_box(&a);
            for (o, x) in xyz.iter_mut().zip(a) {
                *o = x.xyz(&light);
            }
            black_box(&mut xyz);
        })
    });
    g.bench_function(BenchmarkId::new(name, "runtime"), |bn| {
        per_call(bn, || {
            let a = black_box(&wa);
            for (o, x) in xyz.iter_mut().zip(a) {
                *o = x.xyz(&light);
            }
            black_box(&mut xyz);
        })
    });
    if let Some(k) = avx2 {
        g.bench_function(BenchmarkId::new(name, "avx2-loop"), |bn| {
            per_call(bn, || {
                let a = black_box(&a);
                T::xyz_each(k, a, &light, &mut xyz);
                black_box(&mut xyz);
            })
        });
    }
    g.finish();

    // the renderer's most frequent pair, `xyz(T·D, L)`: two calls, or one (`mul_xyz`)
    let mut g = c.benchmark_group("multiply_to_xyz");
    g.bench_function(BenchmarkId::new(name, "portable"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&a, &b));
            for ((o, x), y) in xyz.iter_mut().zip(a).zip(b) {
                *o = x.mul(y).xyz(&light);
            }
            black_box(&mut xyz);
        })
    });
    g.bench_function(BenchmarkId::new(name, "runtime, two calls"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&wa, &wb));
            for ((o, x), y) in xyz.iter_mut().zip(a).zip(b) {
                *o = x.mul(y).xyz(&light);
            }
            black_box(&mut xyz);
        })
    });
    g.bench_function(BenchmarkId::new(name, "runtime, fused"), |bn| {
        per_call(bn, || {
            let (a, b) = black_box((&wa, &wb));
            for ((o, x), y) in xyz.iter_mut().zip(a).zip(b) {
                *o = x.mul_xyz(y, &light);
            }
            black_box(&mut xyz);
        })
    });
    g.finish();
}

fn all(c: &mut Criterion) {
    bench_repr::<DefaultSpectrum>(c, "default 8x3", naive_mul, naive_xyz);
    bench_repr::<PaperSpectrum>(c, "paper 2x3", naive_mul, naive_xyz);
    bench_repr::<Sampled<81>>(c, "sampled 81", naive_mul_sampled, naive_xyz_sampled);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(60)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = all
}
criterion_main!(benches);
