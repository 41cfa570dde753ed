"""Type stubs of specpoly (shapes in the docstrings: n spectra or triples, k wavelengths)."""

from os import PathLike
from typing import Dict, List, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

Float = NDArray[np.float64]
Light = Union[str, Tuple[ArrayLike, ArrayLike], None]
Path = Union[str, "PathLike[str]"]

class SpecpolyError(ValueError):
    """An error of the specpoly library, with its one-line message."""

def sd_to_XYZ(
    values: ArrayLike,
    wavelengths: ArrayLike,
    illuminant: Light = None,
    observer: str = "1964",
    repr: str = "poly",
    scale: float = 1.0,
    product: bool = False,
) -> Float:
    """CIE XYZ of reflectances (n, k) or (k,) on `wavelengths` (k,) nm under `illuminant`
    (a built-in name, default D65, a FILE.csv#COLUMN or a tuple (wavelengths, values)) and
    `observer` (as the CLI's --observer: "1964"/"10", the default, "1931"/"2", "2015-2",
    "2015-10", "cie2006:age=A,field=F" for CIE 170-1 at age 20-80 and field 2-10 degrees, or
    a CSV file of three sensitivities), in representation `repr` ("poly", "paper",
    "poly:SxD", "sampled:N", "hero:4", "rgb", "exact"); the white has Y = 100. Returns
    (n, 3), or (3,) for one spectrum or with `product=True` (the product of all rows).
    A 2-D float64/float32 batch on one grid is computed as one (3, k) matrix product (the
    grid's matrix is built once and kept; equal to the per-spectrum colours to f32 rounding)."""

def sd_to_xy(
    values: ArrayLike,
    wavelengths: ArrayLike,
    illuminant: Light = None,
    observer: str = "1964",
    repr: str = "poly",
    scale: float = 1.0,
    product: bool = False,
) -> Float:
    """CIE xy chromaticity: (n, 2) or (2,)."""

def sd_to_Lab(
    values: ArrayLike,
    wavelengths: ArrayLike,
    illuminant: Light = None,
    observer: str = "1964",
    repr: str = "poly",
    scale: float = 1.0,
    product: bool = False,
) -> Float:
    """CIELAB against the light's exact white: (n, 3) or (3,)."""

def white_XYZ(illuminant: Light = None, observer: str = "1964") -> Float:
    """XYZ of the light's white (perfect reflector, Y = 100) under `observer` (any of
    `sd_to_XYZ`'s): (3,)."""

def illuminants() -> List[str]:
    """The built-in illuminants' names."""

def sd_fit(
    values: ArrayLike,
    wavelengths: ArrayLike,
    repr: str = "poly",
    illuminant: Light = None,
    observer: str = "1964",
    scale: float = 1.0,
) -> Dict[str, Union[Float, float]]:
    """Piecewise-polynomial fit: {"coefficients": (n, spans, coeffs), "breaks": (spans + 1,),
    "rms": (n, spans), "max": (n, spans), "delta_E00": (n,)} (batch axis dropped for (k,))."""

def light_metrics(
    values: ArrayLike,
    wavelengths: ArrayLike,
    extrapolate: bool = False,
    observer: Optional[str] = None,
) -> Dict[str, Union[Float, float]]:
    """`specpoly light --json` for SPDs (n, k) or (k,): {"XYZ": (n, 3), "xy": (n, 2),
    "uv_prime": (n, 2), "CCT", "Duv", "Ra", "R9", "Rf", "Rg": (n,)}; NaN where undefined.
    With `observer` (any of `sd_to_XYZ`'s; `light --observer`) also the light's colour under
    it: "observer_XYZ" (n, 3), "observer_xy", "observer_uv_prime" (n, 2)."""

def CCT_Duv(values: ArrayLike, wavelengths: ArrayLike, extrapolate: bool = False) -> Float:
    """CCT (K) and Duv: (n, 2) or (2,)."""

def colour_rendering_index(
    values: ArrayLike, wavelengths: ArrayLike, extrapolate: bool = False
) -> Tuple[Union[Float, float], Float]:
    """CIE 13.3 (Ra (n,), Ri (n, 14)), unrounded."""

def colour_fidelity_index(
    values: ArrayLike, wavelengths: ArrayLike, extrapolate: bool = False
) -> Tuple[Union[Float, float], Union[Float, float]]:
    """CIE 224:2017 Rf and TM-30 Rg: (n,) each, or floats for one light; unrounded (TM-30
    alone: faster than `light_metrics`, which also computes CIE 13.3 and rounds as the CLI)."""

def tm30(
    values: ArrayLike, wavelengths: ArrayLike, extrapolate: bool = False
) -> Dict[str, object]:
    """TM-30-20 in full for one light (k,): Rf, Rg, CCT, Duv, Rf_hj, Rcs_hj (percent),
    Rhs_hj (16,), test_ab, reference_ab (16, 2), Rf_ces, bin_of_ces (99,), design_intents."""

class DisplayModel:
    """A display's model: device RGB (0-1) <-> CIE XYZ."""

    @staticmethod
    def open(spec: Path) -> "DisplayModel":
        """A calibration file, an ICC display profile, a display TOML or "sRGB"."""
    @staticmethod
    def fit_ti3(
        path: Path,
        transfer: str = "table",
        matrix: str = "least-squares",
        table_points: int = 64,
        interaction: str = "auto",
        hold_out: bool = False,
        keep_outliers: bool = False,
    ) -> "DisplayModel":
        """Fits a model to a CGATS .ti3 as `specpoly calibrate fit` does."""
    @property
    def name(self) -> str: ...
    @property
    def white(self) -> Float:
        """XYZ of device white: (3,)."""
    @property
    def has_interaction(self) -> bool: ...
    @property
    def fit_delta_e00(self) -> Tuple[float, float, float]:
        """The fit's ΔE00 (mean, p95, max)."""
    def predict(self, rgb: ArrayLike) -> Float:
        """XYZ of device RGB: (n, 3) or (3,)."""
    def inverse(self, xyz: ArrayLike) -> Float:
        """Device RGB of XYZ: (n, 3) or (3,)."""
    def save(self, path: Path) -> None:
        """Writes the calibration file (TOML)."""
    def write_icc(
        self,
        path: Path,
        version: int = 2,
        tables: Optional[bool] = None,
        description: Optional[str] = None,
    ) -> None:
        """Writes an ICC display profile (v2.4 or v4.4)."""
    def write_lut3d(
        self,
        path: Path,
        source: str = "srgb",
        size: int = 33,
        white: str = "adapt",
        gamut: str = "clip",
        exact_nodes: bool = False,
    ) -> None:
        """Writes a 3D LUT (.cube, .3dl, .3dlut by extension)."""
