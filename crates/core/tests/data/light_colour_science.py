"""Reference figures for core/tests/light_colour_science.rs, computed with colour-science 0.4.7.

Run from the repository root:
    pip install colour-science==0.4.7
    python3 core/tests/data/light_colour_science.py
It writes, beside itself:
  light_spds_5nm.csv       CIE F-series FL1-FL12, CIE LED illuminants and the CIE 224 test lamp,
                           380-780 nm @ 5 nm (colour.SDS_ILLUMINANTS; colour's cfi2017 test data)
  light_colour_science.csv x, y (CIE 1931), CCT and Duv (Ohno 2013), Ra and R9 (CIE 13.3), Rf and
                           Rg (ANSI/IES TM-30-18 = CIE 224:2017 + Rg) of those lights, of A, D50,
                           D65, and of LED mixes `SET:d1,d2,...` of data/leds/SET.csv
"""

import os
import warnings

import numpy as np
import colour
from colour.quality import tm3018, cfi2017

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")
SHAPE5 = colour.SpectralShape(380, 780, 5)

# The lamp of the CIE 224:2017 calculator example, as colour-science's own test carries it.
import ast  # noqa: E402

_src = open(os.path.join(os.path.dirname(colour.__file__), "quality/tests/test_cfi2017.py")).read()
DATA_SD_SAMPLE_5NM = next(
    ast.literal_eval(n.value)
    for n in ast.walk(ast.parse(_src))
    if isinstance(n, ast.AnnAssign) and getattr(n.target, "id", "") == "DATA_SD_SAMPLE_5NM"
)

lights = {}
for k in ["FL%d" % i for i in range(1, 13)] + [
    "LED-B1", "LED-B2", "LED-B3", "LED-B4", "LED-B5", "LED-BH1", "LED-RGB1", "LED-V1", "LED-V2",
]:
    lights[k] = colour.SDS_ILLUMINANTS[k].copy().align(SHAPE5)
lights["CIE224-sample"] = colour.SpectralDistribution(DATA_SD_SAMPLE_5NM).align(SHAPE5)

with open(os.path.join(HERE, "light_spds_5nm.csv"), "w") as f:
    f.write("wavelength_nm," + ",".join(lights) + "\n")
    for w in range(380, 781, 5):
        f.write("%d," % w + ",".join("%.6g" % lights[k][w] for k in lights) + "\n")

# reload exactly what was written, so both sides see the same numbers
names = list(lights)
table = {}
for i, k in enumerate(names):
    table[k] = colour.SpectralDistribution(
        np.loadtxt(os.path.join(HERE, "light_spds_5nm.csv"), delimiter=",", skiprows=1)[:, i + 1],
        np.arange(380, 781, 5),
    )
for k in ["A", "D50", "D65"]:
    sd = colour.SpectralDistribution(
        np.loadtxt(os.path.join(ROOT, "data/illuminants/%s.csv" % k), delimiter=",", skiprows=1)[:, 1],
        np.loadtxt(os.path.join(ROOT, "data/illuminants/%s.csv" % k), delimiter=",", skiprows=1)[:, 0],
    )
    table[k] = sd.copy().trim(SHAPE5)


def led_mix(name):
    s, duties = name.split(":")
    d = np.array([float(v) for v in duties.split(",")])
    raw = np.loadtxt(os.path.join(ROOT, "data/leds/%s.csv" % s), delimiter=",", skiprows=1)
    return colour.SpectralDistribution(raw[:, 1:] @ d, raw[:, 0])


MIXES = [
    "rgb:1,0.52,0.05", "rgb:1,0.73,0.17", "rgb:1,0.8,0.26", "rgbwa:0,0,0,1,0", "rgbwa:0.2,0.1,0.1,1,0.3",
    "rgbwa:0.05,0.2,0.05,0.8,0.6", "rgbwa:0.3,0.5,0.2,1,0.4", "tunable_white:1,0,0",
    "tunable_white:0,1,0", "tunable_white:0.5,0.5,0", "tunable_white:1,0.2,0.3",
]
for m in MIXES:
    table[m] = led_mix(m)

with open(os.path.join(HERE, "light_colour_science.csv"), "w") as f:
    f.write("# colour-science 0.4.7; made by light_colour_science.py beside this file\n")
    f.write("name,x,y,cct,duv,ra,r9,rf,rg\n")
    for k, sd in table.items():
        xyz = colour.sd_to_XYZ(sd, method="Integration")
        x, y = colour.XYZ_to_xy(xyz)
        cct, duv = cfi2017.CCT_reference_illuminant(sd)
        cri = colour.quality.colour_rendering_index(sd, additional_data=True)
        tm = tm3018.colour_fidelity_index_ANSIIESTM3018(sd, additional_data=True)
        f.write(
            "%s,%.6f,%.6f,%.3f,%.6f,%.4f,%.4f,%.4f,%.4f\n"
            % (k, x, y, cct, duv, cri.Q_a, cri.Q_as[9].Q_a, tm.R_f, tm.R_g)
        )
