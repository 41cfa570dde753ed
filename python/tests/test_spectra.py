"""Reflectances → XYZ, xy, CIELAB and fits: against colour-science 0.4.7 and the CLI."""

import warnings

import colour
import numpy as np
import pytest

import specpoly
from conftest import table

warnings.filterwarnings("ignore")

NM = np.arange(380, 781)


def linear_1nm(wl, values):
    """Linear interpolant at 1 nm over 380-780 nm holding the end values (the library's rule
    for data that stop short, CIE 015:2018)."""
    return np.array([np.interp(NM, wl, v) for v in np.atleast_2d(values)])


def colour_cmfs(observer):
    """colour-science's table of a CIE observer at 1 nm over 380-780 nm; the CIE 2015 tables
    (from 390 nm) are zero below their first row, as the CIE leaves them undefined there."""
    name = {
        "1931": "CIE 1931 2 Degree Standard Observer",
        "1964": "CIE 1964 10 Degree Standard Observer",
        "2015-2": "CIE 2015 2 Degree Standard Observer",
        "2015-10": "CIE 2015 10 Degree Standard Observer",
    }[observer]
    t = colour.MSDS_CMFS[name]
    v = np.array([np.interp(NM, t.wavelengths, t.values[:, i], left=0, right=0) for i in range(3)])
    return colour.MultiSpectralDistributions(v.T, NM, labels=t.labels)


def colour_xyz(values_1nm, light_1nm, observer):
    """colour-science's integration (CIE 015:2018 eq. 7.1, k = 100 / Σ S ȳ) at 1 nm."""
    cmfs = colour_cmfs(observer)
    light = colour.SpectralDistribution(light_1nm, NM)
    return np.array(
        [
            colour.sd_to_XYZ(
                colour.SpectralDistribution(v, NM), cmfs, light, method="Integration"
            )
            for v in values_1nm
        ]
    )


@pytest.mark.parametrize(
    "light,observer", [("D65", "1931"), ("FL11", "1964"), ("A", "1931")]
)
def test_exact_xyz_is_colour_sciences_integration(colorchecker, light, observer):
    _, wl, r = colorchecker
    _, lwl, lv = table(f"data/illuminants/{light}.csv")
    want = colour_xyz(linear_1nm(wl, r), linear_1nm(lwl, lv[0])[0], observer)
    got = specpoly.sd_to_XYZ(r, wl, illuminant=light, observer=observer, repr="exact")
    assert got.shape == (24, 3)
    np.testing.assert_allclose(got, want, rtol=2e-6, atol=1e-6)


def test_poly_colours_are_within_the_fits_error_of_colour_science(colorchecker):
    _, wl, r = colorchecker
    _, lwl, lv = table("data/illuminants/D65.csv")
    light = linear_1nm(lwl, lv[0])[0]
    want = colour_xyz(linear_1nm(wl, r), light, "1931")
    white = colour_xyz(np.ones((1, NM.size)), light, "1931")[0]
    got = specpoly.sd_to_Lab(r, wl, illuminant="D65", observer="1931")
    d = colour.delta_E(got, colour.XYZ_to_Lab(want / 100, colour.XYZ_to_xy(white / 100)))
    # the 8-span cubic fit of the ColorChecker (docs/accuracy.md): well below 0.5 ΔE00
    assert d.max() < 0.5, d.max()


def test_xyz_xy_lab_equal_the_clis(colorchecker, cli):
    names, wl, r = colorchecker
    rows = cli.json("xyz", "colorchecker#*", "--illuminant", "FL11", "--observer", "1964")
    assert [row["name"] for row in rows] == ["colorchecker#" + n for n in names]
    want = np.array([[row[k] for k in ("X", "Y", "Z")] for row in rows])
    kw = dict(illuminant="FL11", observer="1964")
    # the CLI prints 6 decimals: equal to 1e-6 relative, or to its last printed digit
    np.testing.assert_allclose(specpoly.sd_to_XYZ(r, wl, **kw), want, rtol=1e-6, atol=5e-7)
    xy = np.array([[row["x"], row["y"]] for row in rows])
    np.testing.assert_allclose(specpoly.sd_to_xy(r, wl, **kw), xy, rtol=1e-6, atol=5e-7)
    # CIELAB: the batch's matrix and the CLI's per-spectrum path differ by f32 rounding, which
    # a* and b* of near-neutral colours magnify (cube roots of ratios): 1e-4 ΔE
    lab = np.array([[row[k] for k in ("L", "a", "b")] for row in rows])
    np.testing.assert_allclose(specpoly.sd_to_Lab(r, wl, **kw), lab, rtol=1e-6, atol=1e-4)


@pytest.mark.parametrize("repr_", ["paper", "poly:4x5", "sampled:16", "rgb", "exact"])
def test_every_representation_equals_the_cli(colorchecker, cli, repr_):
    _, wl, r = colorchecker
    rows = cli.json("xyz", "colorchecker#*", "--repr", repr_)
    want = np.array([[row[k] for k in ("X", "Y", "Z")] for row in rows])
    np.testing.assert_allclose(
        specpoly.sd_to_XYZ(r, wl, repr=repr_), want, rtol=1e-6, atol=5e-7
    )


def test_product_equals_the_clis(colorchecker, cli):
    names, wl, r = colorchecker
    i, j = names.index("red"), names.index("blue")
    row = cli.json("xyz", "colorchecker#red", "colorchecker#blue", "--product")[0]
    got = specpoly.sd_to_XYZ(r[[i, j]], wl, product=True)
    assert got.shape == (3,)
    np.testing.assert_allclose(got, [row["X"], row["Y"], row["Z"]], rtol=1e-6, atol=5e-7)


def test_shapes_dtypes_and_light_arrays(colorchecker):
    _, wl, r = colorchecker
    batch = specpoly.sd_to_XYZ(r, wl)
    assert batch.dtype == np.float64
    # one spectrum takes the per-spectrum path, the batch the grid's matrix: f32 rounding apart
    np.testing.assert_allclose(specpoly.sd_to_XYZ(r[3], wl), batch[3], rtol=0, atol=1e-5)
    np.testing.assert_array_equal(specpoly.sd_to_XYZ(r.astype(np.float32), wl), batch)
    # a non-contiguous view reads the same numbers
    np.testing.assert_array_equal(specpoly.sd_to_XYZ(np.asfortranarray(r), wl), batch)
    _, lwl, lv = table("data/illuminants/FL11.csv")
    np.testing.assert_array_equal(
        specpoly.sd_to_XYZ(r, wl, illuminant=(lwl, lv[0])),
        specpoly.sd_to_XYZ(r, wl, illuminant="FL11"),
    )
    assert specpoly.sd_to_XYZ(np.zeros((0, wl.size)), wl).shape == (0, 3)
    np.testing.assert_allclose(specpoly.white_XYZ("D65")[1], 100.0, rtol=1e-9)
    assert "D65" in specpoly.illuminants()


def test_percent_data_with_scale(colorchecker):
    _, wl, r = colorchecker
    np.testing.assert_allclose(
        specpoly.sd_to_XYZ(100 * r, wl, scale=0.01), specpoly.sd_to_XYZ(r, wl), rtol=1e-6
    )


def test_fit_reproduces_the_data_by_numpys_chebyshev_series(colorchecker):
    _, wl, r = colorchecker
    f = specpoly.sd_fit(r, wl)
    c, breaks = f["coefficients"], f["breaks"]
    assert c.shape == (24, 8, 4) and f["rms"].shape == (24, 8)
    np.testing.assert_allclose(breaks, np.linspace(380, 780, 9))
    # evaluate each span's series at its samples (t in [-1, 1]) and compare with the data
    for s in range(8):
        a, b = breaks[s], breaks[s + 1]
        inside = (wl >= a) & (wl <= b)
        t = 2 * (wl[inside] - a) / (b - a) - 1
        for i in range(24):
            fitted = np.polynomial.chebyshev.chebval(t, c[i, s])
            err = np.abs(fitted - r[i, inside]).max()
            assert err <= f["max"][i, s] + 1e-5
    assert np.all(f["delta_E00"] < 0.5)


def mixtures(colorchecker, n, seed=3):
    """n reflectances at 5 nm over 380-780 nm: random mixtures of ColorChecker patches."""
    _, wl, r = colorchecker
    grid = np.arange(380, 781, 5.0)
    cc = np.array([np.interp(grid, wl, v) for v in r])
    w = np.random.default_rng(seed).dirichlet(np.ones(len(cc)) * 0.3, size=n)
    return grid, w @ cc


def test_a_batch_on_one_grid_is_colour_sciences_and_the_per_spectrum_colour(colorchecker):
    # 40 spectra on 81 wavelengths: the grid's matrix (n >= k/4)
    wl, r = mixtures(colorchecker, 40)
    _, lwl, lv = table("data/illuminants/A.csv")
    cmfs = colour_cmfs("1931")
    want = colour.msds_to_XYZ(
        linear_1nm(wl, r), cmfs, colour.SpectralDistribution(linear_1nm(lwl, lv[0])[0], NM),
        method="Integration", shape=colour.SpectralShape(380, 780, 1),
    )
    got = specpoly.sd_to_XYZ(r, wl, illuminant="A", observer="1931", repr="exact")
    np.testing.assert_allclose(got, want, rtol=2e-6, atol=1e-6)
    for repr_ in ("poly", "exact", "rgb"):
        batch = specpoly.sd_to_XYZ(r, wl, repr=repr_)
        one = np.array([specpoly.sd_to_XYZ(v, wl, repr=repr_) for v in r[:6]])
        np.testing.assert_allclose(batch[:6], one, rtol=0, atol=1e-5)
        # float32 values, a strided view and percent data with scale read the same numbers
        np.testing.assert_array_equal(specpoly.sd_to_XYZ(r.astype(np.float32), wl, repr=repr_),
                                      specpoly.sd_to_XYZ(r.astype(np.float32).astype(float), wl, repr=repr_))
        np.testing.assert_array_equal(specpoly.sd_to_XYZ(np.asfortranarray(r), wl, repr=repr_), batch)
    np.testing.assert_allclose(specpoly.sd_to_XYZ(100 * r, wl, scale=0.01), specpoly.sd_to_XYZ(r, wl), rtol=1e-6)
    lab = specpoly.sd_to_Lab(r, wl)
    np.testing.assert_allclose(lab, colour.XYZ_to_Lab(specpoly.sd_to_XYZ(r, wl) / 100,
                               colour.XYZ_to_xy(specpoly.white_XYZ() / 100)), atol=1e-9)


@pytest.mark.parametrize(
    "row,col,value,exc,msg",
    [
        (13, 5, np.nan, ValueError, r"values\[13, 5\] is not finite"),
        (7, 60, 50.0, specpoly.SpecpolyError, r"values\[7\].*scale=0.01"),
        (31, 2, -0.5, specpoly.SpecpolyError, r"values\[31\].*negative"),
    ],
)
def test_bad_rows_of_a_batch_are_named(colorchecker, row, col, value, exc, msg):
    wl, r = mixtures(colorchecker, 40)
    r[row, col] = value
    with pytest.raises(exc, match=msg):
        specpoly.sd_to_XYZ(r, wl)


@pytest.mark.parametrize("observer", ["2015-2", "2015-10"])
def test_cie_2015_observers_are_colour_sciences(colorchecker, observer):
    _, wl, r = colorchecker
    _, lwl, lv = table("data/illuminants/D65.csv")
    want = colour_xyz(linear_1nm(wl, r), linear_1nm(lwl, lv[0])[0], observer)
    got = specpoly.sd_to_XYZ(r, wl, observer=observer, repr="exact")
    np.testing.assert_allclose(got, want, rtol=2e-6, atol=1e-6)
    np.testing.assert_allclose(specpoly.white_XYZ(observer=observer)[1], 100.0, rtol=1e-9)


CAMERA = "wavelength_nm,r,g,b\n400,0,0.1,0.8\n500,0.1,0.6,0.4\n600,0.9,0.3,0\n700,0.2,0,0\n"


def test_observers_as_data_equal_the_clis(colorchecker, cli, tmp_path):
    _, wl, r = colorchecker
    camera = tmp_path / "camera.csv"
    camera.write_text(CAMERA)
    for observer in ["2015-10", "cie2006:age=70,field=4", str(camera)]:
        rows = cli.json("xyz", "colorchecker#*", "--illuminant", "FL11", "--observer", observer)
        want = np.array([[row[k] for k in ("X", "Y", "Z")] for row in rows])
        got = specpoly.sd_to_XYZ(r, wl, illuminant="FL11", observer=observer)
        np.testing.assert_allclose(got, want, rtol=1e-6, atol=5e-7, err_msg=observer)
        lab = np.array([[row[k] for k in ("L", "a", "b")] for row in rows])
        got = specpoly.sd_to_Lab(r, wl, illuminant="FL11", observer=observer)
        np.testing.assert_allclose(got, lab, rtol=1e-6, atol=1e-4, err_msg=observer)
    fit = specpoly.sd_fit(r[:2], wl, observer="cie2006:age=70,field=4")
    assert np.all(fit["delta_E00"] < 0.5)


def test_bad_observers_are_one_line_value_errors(tmp_path):
    wl = np.arange(380, 781, 10.0)
    r = np.full(wl.size, 0.5)
    negative = tmp_path / "negative.csv"
    negative.write_text(CAMERA.replace("0.9,0.3,0", "0.9,-0.3,0"))
    for observer, msg in [
        ("1930", "unknown observer `1930`"),
        ("cie2006:age=90,field=4", "age"),
        ("cie2006:age=40", "field"),
        (str(tmp_path / "missing.csv"), "unknown observer"),
        (str(negative), "negative.csv: negative sensitivity -0.3"),
    ]:
        for f in (lambda: specpoly.sd_to_XYZ(r, wl, observer=observer),
                  lambda: specpoly.white_XYZ(observer=observer)):
            with pytest.raises(ValueError, match=msg) as e:
                f()
            assert "\n" not in str(e.value), observer
