"""N-channel LED mixing: duties equal to the CLI's `mix --json` for the same channels and
target, and the mixed spectrum (duties @ channels) integrated by colour-science 0.4.7 lands
on the target."""

import warnings

import colour
import numpy as np
import pytest

import specpoly

warnings.filterwarnings("ignore")


def channel_csv(path, names, wl, v):
    """The channels as a spectral CSV (wavelength, one column per channel), exact floats."""
    lines = ["wavelength," + ",".join(names)]
    lines += [",".join(repr(float(x)) for x in (w, *col)) for w, col in zip(wl, v.T)]
    path.write_text("\n".join(lines) + "\n")


def xy_by_colour(wl, spd):
    sd = colour.SpectralDistribution(dict(zip(wl, spd)))
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    return colour.XYZ_to_xy(colour.sd_to_XYZ(sd, cmfs, method="Integration"))


@pytest.mark.parametrize(
    "pick, target, cli_target, optimize",
    [
        (["red", "green", "blue"], (0.3127, 0.329), "xy:0.3127,0.329", "rf"),
        (["red", "green", "blue", "amber"], 3000.0, "cct:3000,duv:0", "power"),
    ],
)
def test_mix_equals_the_clis_and_hits_the_target(leds, cli, tmp_path, pick, target, cli_target, optimize):
    names, wl, v = leds
    ch = v[[names.index(n) for n in pick]]
    csv = tmp_path / "channels.csv"
    channel_csv(csv, pick, wl, ch)
    args = [a for n in pick for a in ("--channel", f"{n}={csv}#{n}")]
    want = cli.json("mix", *args, "--target", cli_target, "--optimize", optimize)
    got = specpoly.mix(ch, wl, target, optimize=optimize, names=pick)
    assert got["channels"] == want["channels"] == pick
    np.testing.assert_array_equal(got["duties"], want["duties"])
    for k, j in [("x", "x"), ("y", "y"), ("CCT", "cct"), ("Duv", "duv"), ("Ra", "ra"), ("Rf", "rf")]:
        np.testing.assert_array_equal(got[k], np.nan if want[j] is None else want[j], err_msg=k)
    assert got["efficacy"] == want["efficacy"]
    # independent check: colour-science's xy of the mixed light is the target's
    xy = xy_by_colour(wl, got["duties"] @ ch)
    want_xy = target if isinstance(target, tuple) else colour.UCS_uv_to_xy(colour.temperature.CCT_to_uv_Ohno2013(np.array([3000.0, 0.0])))
    np.testing.assert_allclose(xy, want_xy, atol=2e-4)


def test_mix_limits_and_bad_input(leds):
    names, wl, v = leds
    ch = v[[names.index(n) for n in ["red", "green", "blue"]]]
    r = specpoly.mix(ch, wl, "cct:4000", minimum={"ra": 99.0})
    assert r["limits"][0]["metric"] == "ra" and r["limits"][0]["met"] is False
    with pytest.raises(ValueError, match="3 to 6 channels"):
        specpoly.mix(ch[:2], wl, (0.3127, 0.329))
    with pytest.raises(ValueError, match="target"):
        specpoly.mix(ch, wl, "xyz:1,2")
    with pytest.raises(ValueError, match="luminance"):
        specpoly.mix(ch, wl, 3000.0, luminance=0.0)
    with pytest.raises(ValueError, match="optimize"):
        specpoly.mix(ch, wl, 3000.0, optimize="lumens")
