"""Display models: fitted from a .ti3 as the CLI fits them, predict equal to
`calibrate predict`, inverse, ICC and 3D LUT files; sRGB against colour-science 0.4.7."""

import warnings

import colour
import numpy as np
import pytest

import specpoly
from conftest import ROOT

warnings.filterwarnings("ignore")

TI3 = ROOT / "data" / "ti3" / "acer-xb271hu-unit1_dispread_2068.ti3"


@pytest.fixture(scope="module")
def acer():
    # a 5-node interaction lattice: the lattice without the cross-validation that picks it
    return specpoly.DisplayModel.fit_ti3(TI3, interaction="5")


def grid(n):
    g = np.linspace(0, 1, n)
    return np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)


def test_srgb_is_colour_sciences_srgb():
    d = specpoly.DisplayModel.open("sRGB")
    rgb = grid(5)
    want = colour.sRGB_to_XYZ(rgb, apply_cctf_decoding=True)  # white Y = 1
    np.testing.assert_allclose(d.predict(rgb), want, rtol=2e-4, atol=5e-5)


def test_predict_equals_the_clis(acer, cli, tmp_path):
    cal = tmp_path / "acer.toml"
    acer.save(cal)
    rgb = grid(4)
    text = "\n".join(" ".join(f"{c:.17g}" for c in t) for t in rgb)
    out = cli("calibrate", "predict", "--calibration", str(cal), stdin=text)
    want = np.array([[float(x) for x in line.split()] for line in out.splitlines()])
    np.testing.assert_allclose(acer.predict(rgb), want, rtol=1e-6, atol=5e-7)
    # the same model as the CLI's own fit of the same file
    cli("calibrate", "fit", "--ti3", str(TI3), "--interaction", "5", "-o", str(tmp_path / "cli.toml"))
    theirs = specpoly.DisplayModel.open(tmp_path / "cli.toml")
    np.testing.assert_array_equal(theirs.predict(rgb), acer.predict(rgb))


def test_inverse_round_trips(acer):
    rgb = grid(6) * 0.9 + 0.05
    back = acer.inverse(acer.predict(rgb))
    np.testing.assert_allclose(back, rgb, atol=2e-3)
    assert acer.predict(rgb[0]).shape == (3,)
    assert acer.fit_delta_e00[0] < 1.0 and acer.has_interaction


def test_icc_and_lut3d_files(acer, cli, tmp_path):
    icc = tmp_path / "acer.icc"
    acer.write_icc(icc, tables=False)  # matrix/TRC: the tables take seconds to sample
    assert icc.read_bytes()[36:40] == b"acsp"
    profile = specpoly.DisplayModel.open(icc)
    rgb = grid(3)
    # the profile read back (absolute, D50-adapted and back) against the model: ΔE00 by
    # colour-science relative to each one's white
    lab = lambda d: colour.XYZ_to_Lab(d.predict(rgb) / d.white[1], colour.XYZ_to_xy(d.white))
    assert colour.delta_E(lab(profile), lab(acer)).max() < 1.0
    cube = tmp_path / "acer.cube"
    acer.write_lut3d(cube, size=5)
    nodes = [l for l in cube.read_text().splitlines() if l[:1].isdigit() or l[:1] == "-"]
    assert len(nodes) == 5**3
    cal = tmp_path / "acer.toml"
    acer.save(cal)
    cli("calibrate", "lut3d", str(cal), "-o", str(tmp_path / "cli.cube"), "--size", "5")
    theirs = [l for l in (tmp_path / "cli.cube").read_text().splitlines() if l[:1].isdigit() or l[:1] == "-"]
    assert nodes == theirs
