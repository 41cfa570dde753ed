"""Bad input: a clear Python exception, never a crash or a silent wrong answer."""

import numpy as np
import pytest

import specpoly

WL = np.arange(380, 781, 10.0)
R = np.full((2, WL.size), 0.5)


@pytest.mark.parametrize(
    "values,wl,exc,msg",
    [
        (np.zeros((2, 3, WL.size)), WL, ValueError, "1-D or 2-D"),
        (R[:, :-1], WL, ValueError, "40 samples per spectrum but 41 wavelengths"),
        (R, WL.reshape(1, -1), ValueError, "wavelengths: expected a 1-D array"),
        (np.where(np.arange(WL.size) == 5, np.nan, R), WL, ValueError, r"values\[0, 5\] is not finite"),
        (R, np.where(np.arange(WL.size) == 2, np.inf, WL), ValueError, r"wavelengths\[2\] is not finite"),
        (R.astype(str), WL, TypeError, "got dtype <U"),
        (R.astype(complex), WL, TypeError, "got dtype complex128"),
        ([["a"] * WL.size], WL, TypeError, "values"),
        (R, WL[::-1], specpoly.SpecpolyError, "increasing"),
        (100 * R, WL, specpoly.SpecpolyError, "scale=0.01"),
        (-R, WL, specpoly.SpecpolyError, "negative"),
    ],
)
def test_bad_spectra(values, wl, exc, msg):
    with pytest.raises(exc, match=msg):
        specpoly.sd_to_XYZ(values, wl)


def test_bad_names():
    with pytest.raises(specpoly.SpecpolyError, match="D66"):
        specpoly.sd_to_XYZ(R, WL, illuminant="D66")
    with pytest.raises(ValueError, match="unknown observer `1930`"):
        specpoly.sd_to_XYZ(R, WL, observer="1930")
    with pytest.raises(specpoly.SpecpolyError, match="poly:9x9|representation"):
        specpoly.sd_to_XYZ(R, WL, repr="poly:9x9")
    with pytest.raises(TypeError, match="illuminant"):
        specpoly.sd_to_XYZ(R, WL, illuminant=65)
    with pytest.raises(specpoly.SpecpolyError, match="fit"):
        specpoly.sd_fit(R, WL, repr="rgb")
    with pytest.raises(ValueError, match="no spectra"):
        specpoly.sd_to_XYZ(np.zeros((0, WL.size)), WL, product=True)


def test_library_errors_are_value_errors():
    assert issubclass(specpoly.SpecpolyError, ValueError)


def test_bad_displays(tmp_path):
    with pytest.raises(specpoly.SpecpolyError):
        specpoly.DisplayModel.open(tmp_path / "missing.toml")
    bad = tmp_path / "bad.ti3"
    bad.write_text("not a ti3\n")
    with pytest.raises(specpoly.SpecpolyError, match="bad.ti3"):
        specpoly.DisplayModel.fit_ti3(bad)
    d = specpoly.DisplayModel.open("sRGB")
    with pytest.raises(ValueError, match=r"expected shape \(n, 3\)"):
        d.predict(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="not finite"):
        d.inverse([[1.0, np.nan, 2.0]])
    with pytest.raises(ValueError, match="needs a calibration"):
        d.write_icc(tmp_path / "x.icc")
    with pytest.raises(ValueError, match="LUT format"):
        d.write_lut3d(tmp_path / "x.txt")
    assert not (tmp_path / "x.icc").exists()


def test_light_batch_errors():
    with pytest.raises(ValueError, match="one light"):
        specpoly.tm30(R, WL)
    with pytest.raises(TypeError):
        specpoly.light_metrics(R.astype(object), WL)
