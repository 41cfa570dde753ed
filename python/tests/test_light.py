"""Light metrics: equal to the CLI's `light --json`, and against colour-science 0.4.7 within
the tolerances of the core's own parity tests (crates/core/tests/light_references.rs)."""

import json
import warnings

import colour
import numpy as np
import pytest
from colour.quality import tm3018

import specpoly

warnings.filterwarnings("ignore")

KEYS = {"CCT": "cct", "Duv": "duv", "Ra": "ra", "R9": "r9", "Rf": "rf", "Rg": "rg"}


def test_metrics_equal_the_clis(leds, cli):
    names, wl, v = leds
    rows = [json.loads(line) for line in cli("light", "data/leds/rgbwa.csv#*", "--json").splitlines()]
    assert [r["name"] for r in rows] == ["data/leds/rgbwa.csv#" + n for n in names]
    m = specpoly.light_metrics(v, wl)
    np.testing.assert_array_equal(m["XYZ"], [[r["X"], r["Y"], r["Z"]] for r in rows])
    np.testing.assert_array_equal(m["xy"], [[r["x"], r["y"]] for r in rows])
    np.testing.assert_array_equal(m["uv_prime"], [[r["u_prime"], r["v_prime"]] for r in rows])
    for k, j in KEYS.items():
        want = np.array([np.nan if r[j] is None else r[j] for r in rows])
        np.testing.assert_array_equal(m[k], want, err_msg=k)
    # red, green, blue and amber LEDs are far from the Planckian locus: no CCT, no indices
    assert np.isnan(m["Rf"][0]) and not np.isnan(m["Rf"][names.index("white")])


def test_observer_colours_equal_the_clis(leds, cli):
    names, wl, v = leds
    for observer in ["2015-10", "cie2006:age=60,field=4"]:
        out = cli("light", "data/leds/rgbwa.csv#*", "--observer", observer, "--json")
        rows = [json.loads(line)["observer"] for line in out.splitlines()]
        m = specpoly.light_metrics(v, wl, observer=observer)
        np.testing.assert_array_equal(m["observer_XYZ"], [[r["X"], r["Y"], r["Z"]] for r in rows])
        np.testing.assert_array_equal(m["observer_xy"], [[r["x"], r["y"]] for r in rows])
        np.testing.assert_array_equal(m["observer_uv_prime"], [[r["u_prime"], r["v_prime"]] for r in rows])
    assert "observer_XYZ" not in specpoly.light_metrics(v, wl)
    with pytest.raises(ValueError, match="unknown observer `2016`"):
        specpoly.light_metrics(v, wl, observer="2016")


def test_one_light_and_tm30_equal_the_clis(leds, cli):
    names, wl, v = leds
    white = v[names.index("white")]
    row = cli.json("light", "data/leds/rgbwa.csv#white")
    m = specpoly.light_metrics(white, wl)
    assert m["XYZ"].shape == (3,) and isinstance(m["Rf"], float)
    assert (m["CCT"], m["Rf"], m["Rg"], m["Ra"]) == (row["cct"], row["rf"], row["rg"], row["ra"])
    t = json.loads(cli("light", "data/leds/rgbwa.csv#white", "--tm30", "--json"))["tm30"]
    got = specpoly.tm30(white, wl)
    assert (got["Rf"], got["Rg"], got["CCT"]) == (t["rf"], t["rg"], t["cct"])
    np.testing.assert_array_equal(got["Rf_hj"], [b["rf"] for b in t["bins"]])
    np.testing.assert_array_equal(got["Rcs_hj"], [b["rcs_percent"] for b in t["bins"]])
    np.testing.assert_array_equal(got["Rf_ces"], [c["rf"] for c in t["ces"]])
    assert got["design_intents"] == t["design_intents"]


@pytest.mark.parametrize("name", ["FL2", "FL11", "A", "LED-B3"])
def test_metrics_agree_with_colour_science(name):
    # as crates/core/tests/data/light_references.py: the data over 380-780 nm, a new
    # distribution with colour-science's default interpolation and extrapolation
    full = colour.SDS_ILLUMINANTS[name]
    wl = np.arange(380, 781, full.shape.interval)
    v = full[wl]
    sd = colour.SpectralDistribution(v, wl)
    m = specpoly.light_metrics(v, wl)
    tm = tm3018.colour_fidelity_index_ANSIIESTM3018(sd, additional_data=True)
    np.testing.assert_allclose(m["CCT"], tm.CCT, rtol=5e-4)
    assert abs(m["Duv"] - tm.D_uv) < 2e-5
    assert abs(m["Rf"] - tm.R_f) < 0.05 and abs(m["Rg"] - tm.R_g) < 0.05
    t = specpoly.tm30(v, wl)
    np.testing.assert_allclose(t["Rf_hj"], tm.R_fs, atol=0.1)
    np.testing.assert_allclose(t["Rcs_hj"], tm.R_cs, atol=0.5)  # both in percent
    np.testing.assert_allclose(t["Rhs_hj"], tm.R_hs, atol=0.005)
    cri = colour.colour_rendering_index(sd, additional_data=True)
    ra, ri = specpoly.colour_rendering_index(v, wl)
    assert abs(ra - cri.Q_a) < 0.1
    np.testing.assert_allclose(ri, [cri.Q_as[i].Q_a for i in sorted(cri.Q_as)], atol=0.1)


def test_batch_helpers(leds):
    names, wl, v = leds
    cd = specpoly.CCT_Duv(v, wl)
    assert cd.shape == (5, 2)
    rf, rg = specpoly.colour_fidelity_index(v, wl)
    m = specpoly.light_metrics(v, wl)
    np.testing.assert_array_equal(cd[:, 0], m["CCT"])
    # unrounded; light_metrics rounds to the CLI's 6 decimals
    np.testing.assert_allclose(rf, m["Rf"], rtol=0, atol=5e-7)
    np.testing.assert_allclose(rg, m["Rg"], rtol=0, atol=5e-7)
    assert np.isnan(rf[0]) and not np.isnan(rf[names.index("white")])
    assert isinstance(specpoly.colour_fidelity_index(v[names.index("white")], wl)[0], float)
    ra, ri = specpoly.colour_rendering_index(v, wl)
    assert ri.shape == (5, 14)
    w = names.index("white")
    assert abs(ra[w] - m["Ra"][w]) < 1e-6 and abs(ri[w, 8] - m["R9"][w]) < 1e-6


def test_short_lights_need_extrapolate(leds):
    _, wl, v = leds
    keep = (wl >= 400) & (wl <= 700)
    with pytest.raises(specpoly.SpecpolyError, match="380"):
        specpoly.light_metrics(v[3, keep], wl[keep])
    m = specpoly.light_metrics(v[3, keep], wl[keep], extrapolate=True)
    assert np.isfinite(m["CCT"])
