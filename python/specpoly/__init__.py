"""specpoly: spectral colour with piecewise polynomials, over NumPy arrays.

Batch first: spectra are rows of a 2-D array ``(n, k)`` sampled at ``wavelengths`` (``(k,)``,
nm, strictly increasing); a 1-D ``(k,)`` array is one spectrum and drops the batch axis of
the result. Arrays of float64, float32 or integers are accepted; results are new float64
arrays. Errors of the library are :class:`SpecpolyError` (a ``ValueError``) with its one-line
message; arrays of the wrong shape or with NaN are ``ValueError``, of the wrong dtype
``TypeError``.

Spectra (``specpoly xyz``, ``specpoly fit``)
    :func:`sd_to_XYZ`, :func:`sd_to_xy`, :func:`sd_to_Lab`, :func:`white_XYZ`, :func:`sd_fit`
Light (``specpoly light``)
    :func:`light_metrics`, :func:`CCT_Duv`, :func:`colour_rendering_index`,
    :func:`colour_fidelity_index`, :func:`tm30`
Displays (``specpoly calibrate``)
    :class:`DisplayModel` (``fit_ti3``, ``open``, ``predict``, ``inverse``, ``save``,
    ``write_icc``, ``write_lut3d``)
"""

from __future__ import annotations

import numpy as np

from ._specpoly import (
    DisplayModel,
    SpecpolyError,
    colour_fidelity_index,
    colour_rendering_index,
    illuminants,
    light_metrics,
    sd_fit,
    sd_to_Lab,
    sd_to_XYZ,
    sd_to_xy,
    tm30,
    white_XYZ,
)

__all__ = [
    "CCT_Duv",
    "DisplayModel",
    "SpecpolyError",
    "colour_fidelity_index",
    "colour_rendering_index",
    "illuminants",
    "light_metrics",
    "sd_fit",
    "sd_to_Lab",
    "sd_to_XYZ",
    "sd_to_xy",
    "tm30",
    "white_XYZ",
]


def CCT_Duv(values, wavelengths, extrapolate=False):
    """CCT (K) and Duv of SPDs: (n, 2), or (2,) for one light; NaN farther than 0.05 Duv
    from the Planckian locus (``light_metrics``'s ``CCT`` and ``Duv``)."""
    m = light_metrics(values, wavelengths, extrapolate)
    return np.stack([np.asarray(m["CCT"]), np.asarray(m["Duv"])], axis=-1)

