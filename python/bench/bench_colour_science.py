"""specpoly against colour-science 0.4.7 on the same batches; prints a Markdown table.

Run (from the repository root, with the package and colour-science installed):
    python python/bench/bench_colour_science.py [--lights N] [--colour-lights M]

1. 10 000 reflectances × one light → XYZ (CIE 1931, D65, 5 nm data): specpoly's `sd_to_XYZ`
   (poly, the default, and `exact`, the 1 nm sum) on the batch (one shared grid: the grid's
   (3, k) matrix, built on the first call and kept, then one pass over the rows), its first
   call (which builds the matrix: k conversions), and one spectrum at a time (the
   per-spectrum path: each spectrum fitted by 8 cubic spans, then three dot products; timed
   on the same number of spectra as colour-science's loop and scaled), against
   colour-science's `sd_to_XYZ` called per spectrum (ASTM E308, its default) and its
   vectorised `msds_to_XYZ` (integration over an (n, k) array), and NumPy's bare product
   `values @ W` with a (k, 3) matrix (the floor of any method that reads the array).
2. Rf (and Rg) of N lights: `colour_fidelity_index` (TM-30 alone), and `light_metrics`
   (everything `light --json` prints), against colour-science's `colour_fidelity_index`
   (ANSI/IES TM-30-18) per light, timed on M lights and scaled to N.
3. Display predict of 10⁶ RGB triples: `DisplayModel.predict` (sRGB, and a model fitted from a
   .ti3 with its interaction lattice) against colour-science's `sRGB_to_XYZ`.
Best of 3 runs each (15 for the batch XYZ calls of a few milliseconds, 1 for the
colour-science loops). NumPy's BLAS threads (OPENBLAS_NUM_THREADS) change colour-science's
vectorised figures a lot on a loaded machine: run it both ways.
"""

import argparse
import os
import time
import warnings

import colour
import numpy as np

import specpoly

warnings.filterwarnings("ignore")
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def best(f, runs=3):
    t = []
    for _ in range(runs):
        s = time.perf_counter()
        f()
        t.append(time.perf_counter() - s)
    return min(t)


def reflectances(n, rng):
    """n smooth reflectances at 5 nm over 380-780 nm: random mixtures of ColorChecker patches."""
    raw = np.loadtxt(
        os.path.join(ROOT, "data/reflectances/colorchecker_babelcolor_average.csv"),
        delimiter=",",
        skiprows=1,
    )
    wl = np.arange(380, 781, 5.0)
    cc = np.array([np.interp(wl, raw[:, 0], raw[:, i]) for i in range(1, raw.shape[1])])
    w = rng.dirichlet(np.ones(len(cc)) * 0.3, size=n)
    return wl, np.clip(w @ cc, 0, 1)


def lights(n, rng):
    """n white LED mixes at 1 nm (data/leds/rgbwa.csv, random duties near white)."""
    raw = np.loadtxt(os.path.join(ROOT, "data/leds/rgbwa.csv"), delimiter=",", skiprows=1)
    d = np.column_stack(
        [rng.uniform(0, 0.2, n), rng.uniform(0, 0.2, n), rng.uniform(0, 0.1, n), np.ones(n), rng.uniform(0, 0.5, n)]
    )
    return raw[:, 0], d @ raw[:, 1:].T


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--reflectances", type=int, default=10_000)
    ap.add_argument("--colour-loop", type=int, default=1_000, help="spectra timed in colour's per-spectrum loop")
    ap.add_argument("--lights", type=int, default=1_000)
    ap.add_argument("--colour-lights", type=int, default=20)
    ap.add_argument("--rgb", type=int, default=1_000_000)
    a = ap.parse_args()
    rng = np.random.default_rng(1)
    rows = []

    wl, r = reflectances(a.reflectances, rng)
    s = time.perf_counter()
    specpoly.sd_to_XYZ(r, wl, observer="1931")
    t_first = time.perf_counter() - s
    # milliseconds each on a shared machine: best of 15
    t_poly = best(lambda: specpoly.sd_to_XYZ(r, wl, observer="1931"), runs=15)
    t_exact = best(lambda: specpoly.sd_to_XYZ(r, wl, observer="1931", repr="exact"), runs=15)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    d65 = colour.SDS_ILLUMINANTS["D65"]
    shape = colour.SpectralShape(380, 780, 5)
    t_vec = best(lambda: colour.msds_to_XYZ(r, cmfs, d65, method="Integration", shape=shape), runs=15)
    w = rng.random((len(wl), 3))
    t_np = best(lambda: r @ w, runs=15)
    m = a.colour_loop
    t_one = best(lambda: [specpoly.sd_to_XYZ(v, wl, observer="1931") for v in r[:m]], runs=1) * a.reflectances / m
    sds = [colour.SpectralDistribution(v, wl) for v in r[:m]]
    t_loop = best(lambda: [colour.sd_to_XYZ(sd, cmfs, d65) for sd in sds], runs=1) * a.reflectances / m
    n = a.reflectances
    rows += [
        (f"{n} reflectances → XYZ", "sd_to_XYZ (poly) on the batch", t_poly, "msds_to_XYZ vectorised (integration)", t_vec),
        ("", "sd_to_XYZ (exact, 1 nm) on the batch", t_exact, "msds_to_XYZ vectorised (integration)", t_vec),
        ("", "sd_to_XYZ (poly), first call (builds W)", t_first, "msds_to_XYZ vectorised (integration)", t_vec),
        ("", "sd_to_XYZ (poly) on the batch", t_poly, "sd_to_XYZ per spectrum (ASTM E308)", t_loop),
        ("", "sd_to_XYZ (poly) per spectrum", t_one, "sd_to_XYZ per spectrum (ASTM E308)", t_loop),
        ("", "sd_to_XYZ (poly) on the batch", t_poly, "NumPy `values @ W` alone", t_np),
    ]

    lwl, lv = lights(a.lights, rng)
    t_rf = best(lambda: specpoly.colour_fidelity_index(lv, lwl))
    t_all = best(lambda: specpoly.light_metrics(lv, lwl))
    k = a.colour_lights
    lsds = [colour.SpectralDistribution(v, lwl) for v in lv[:k]]
    t_crf = best(lambda: [colour.colour_fidelity_index(sd, method="ANSI/IES TM-30-18") for sd in lsds], runs=1) * a.lights / k
    rows += [
        (f"Rf of {a.lights} lights", "colour_fidelity_index (Rf, Rg)", t_rf, f"colour_fidelity_index per light (timed on {k})", t_crf),
        ("", "light_metrics (XYZ, CCT, Ra, R9, Rf, Rg, checks)", t_all, "colour_fidelity_index per light", t_crf),
    ]

    rgb = rng.random((a.rgb, 3))
    srgb = specpoly.DisplayModel.open("sRGB")
    t_s = best(lambda: srgb.predict(rgb))
    t_cs = best(lambda: colour.sRGB_to_XYZ(rgb))
    acer = specpoly.DisplayModel.fit_ti3(os.path.join(ROOT, "data/ti3/acer-xb271hu-unit1_dispread_2068.ti3"))
    t_a = best(lambda: acer.predict(rgb))
    rows += [
        (f"predict {a.rgb:.0e} RGB", "DisplayModel('sRGB').predict", t_s, "sRGB_to_XYZ", t_cs),
        ("", "fitted .ti3 model (lattice: %s).predict" % acer.has_interaction, t_a, "sRGB_to_XYZ", t_cs),
    ]

    print(
        f"CPU cores: {os.cpu_count()}, load average {os.getloadavg()[0]:.1f}; "
        f"numpy {np.__version__}, colour-science {colour.__version__}\n"
    )
    print("| batch | specpoly | s | colour-science | s | speed-up |")
    print("| --- | --- | ---: | --- | ---: | ---: |")
    for b, sn, st, cn, ct in rows:
        print(f"| {b} | {sn} | {st:.4f} | {cn} | {ct:.4f} | {ct / st:.1f}× |")


if __name__ == "__main__":
    main()
