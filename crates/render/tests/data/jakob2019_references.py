"""Reference reflectances for the RGB -> spectrum upsampling (render/tests/upsample.rs), computed
with colour-science 0.4.7's independent implementation of Jakob and Hanika 2019.

Run from the repository root:
    python3 -m venv venv && venv/bin/pip install colour-science==0.4.7
    venv/bin/python crates/render/tests/data/jakob2019_references.py
It writes jakob2019_references.csv beside itself: per linear-sRGB colour, the reflectance of
colour.recovery.find_coefficients_Jakob2019 (CIE 1931 2-degree CMFs and CIE D65 on the
380-780 nm, 1 nm grid the renderer integrates on; max_error 1e-4 ΔE76, continuation from
grey in 8 steps as the renderer does) at 380, 390, ..., 780 nm.
Licence: colour-science is BSD-3-Clause.
"""
import os
import numpy as np
import colour
from colour.recovery import find_coefficients_Jakob2019, sd_Jakob2019
from colour.recovery.jakob2019 import dimensionalise_coefficients

shape = colour.SpectralShape(380, 780, 1)
cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
d65 = colour.SDS_ILLUMINANTS["D65"].copy().align(shape)
srgb = colour.RGB_COLOURSPACES["sRGB"]
white = colour.sd_to_XYZ(colour.sd_ones(shape), cmfs, d65, method="Integration") / 100
COLOURS = [
    (0.5, 0.5, 0.5), (0.8, 0.0, 0.0), (0.4, 0.25, 0.1), (0.1, 0.2, 0.6), (0.05, 0.9, 0.1),
    (1.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.2, 0.6, 0.6), (0.9, 0.5, 0.7), (0.02, 0.01, 0.03),
]
rows = []
for rgb in COLOURS:
    c = np.zeros(3)
    for s in np.arange(1, 9) / 8:
        target = colour.RGB_to_XYZ(0.5 + s * (np.array(rgb) - 0.5), srgb, apply_cctf_decoding=False)
        # to the 1 nm D65 table's white, channel by channel (as the renderer does)
        target = target * white / colour.RGB_to_XYZ(np.ones(3), srgb, apply_cctf_decoding=False)
        c, err = find_coefficients_Jakob2019(target, cmfs, d65, c, max_error=1e-4,
                                             dimensionalise=False)
    sd = sd_Jakob2019(dimensionalise_coefficients(c, shape), colour.SpectralShape(380, 780, 10))
    rows.append(list(rgb) + [err] + list(sd.values))
here = os.path.dirname(os.path.abspath(__file__))
with open(os.path.join(here, "jakob2019_references.csv"), "w") as f:
    f.write("# colour-science " + colour.__version__ + ", find_coefficients_Jakob2019\n")
    f.write("r,g,b,delta_e76," + ",".join(f"{w}" for w in range(380, 781, 10)) + "\n")
    for r in rows:
        f.write(",".join(f"{v:.7g}" for v in r) + "\n")
