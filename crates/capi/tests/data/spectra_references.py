"""Reference XYZ for the C library's spectra functions (tests/spectra.rs, tests/c_program.rs),
computed with colour-science 0.4.7.

Run from the repository root:
    pip install colour-science==0.4.7
    python3 crates/capi/tests/data/spectra_references.py
It writes, beside itself and in tests/c/:
  spectra_samples.csv    three ColorChecker reflectances (colour.SDS_COLOURCHECKERS['BabelColor
                         Average']: dark skin, blue sky, red), 380-730 nm @ 10 nm, 6 digits
  ../c/spectra_samples.h the same numbers as C arrays, for the C program
  spectra_references.csv CIE XYZ (perfect white Y = 100) of each reflectance r, and of r*r (an
                         inter-reflection), under A, D65 and FL11 for the CIE 1931 and 1964
                         observers and the CIE 2015 2 and 10 degree ones (zero below 390 nm): colour.sd_to_XYZ (method 'Integration') of the samples'
                         linear interpolant at 1 nm over 380-780 nm with the end values held
                         (the data stop at 730 nm), the light's 5 nm table (data/illuminants)
                         linearly interpolated to 1 nm, colour's CIE 1931/1964/2015 tables at
                         1 nm.
The library's XYZ is that of an 8-span cubic fit of the samples, so the two differ by the fit's
error (the test's tolerance says by how much).
"""

import os
import warnings

import numpy as np
import colour

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..", "..")
PATCHES = ["dark skin", "blue sky", "red"]
NM = np.arange(380, 781, 1.0)

cc = colour.SDS_COLOURCHECKERS["BabelColor Average"]
with open(os.path.join(HERE, "spectra_samples.csv"), "w") as f:
    f.write("wavelength_nm," + ",".join(p.replace(" ", "_") for p in PATCHES) + "\n")
    wl = cc[PATCHES[0]].wavelengths
    for i, w in enumerate(wl):
        f.write("%d," % w + ",".join("%.6g" % cc[p].values[i] for p in PATCHES) + "\n")

# reload exactly what was written, so both sides see the same numbers
t = np.loadtxt(os.path.join(HERE, "spectra_samples.csv"), delimiter=",", skiprows=1)
wl, samples = t[:, 0], {p: t[:, i + 1] for i, p in enumerate(PATCHES)}

with open(os.path.join(HERE, "..", "c", "spectra_samples.h"), "w") as f:
    f.write("/* ColorChecker reflectances (BabelColor Average, colour-science 0.4.7): written by\n"
            " * tests/data/spectra_references.py with tests/data/spectra_samples.csv; do not edit. */\n")
    f.write("#define SAMPLES %d\n" % len(wl))
    f.write("static const float SAMPLE_NM[SAMPLES] = {%s};\n" % ", ".join("%.1ff" % w for w in wl))
    f.write("static const float SAMPLE_VALUE[%d][SAMPLES] = {\n" % len(PATCHES))
    for p in PATCHES:
        f.write("    {%s}, /* %s */\n" % (", ".join("%sf" % ("%.6g" % v if "." in "%.6g" % v or "e" in "%.6g" % v else "%.6g.0" % v) for v in samples[p]), p))
    f.write("};\n")

OBSERVERS = {"1931": "CIE 1931 2 Degree Standard Observer", "1964": "CIE 1964 10 Degree Standard Observer",
             "2015-2": "CIE 2015 2 Degree Standard Observer", "2015-10": "CIE 2015 10 Degree Standard Observer"}
shape = colour.SpectralShape(380, 780, 1)
rows = []
for light in ["A", "D65", "FL11"]:
    d = np.loadtxt(os.path.join(ROOT, "data/illuminants/%s.csv" % light), delimiter=",", skiprows=1)
    s = colour.SpectralDistribution(np.interp(NM, d[:, 0], d[:, 1]), NM)
    for o, name in OBSERVERS.items():
        cmfs = colour.MSDS_CMFS[name].copy().align(shape)
        # the CIE 2015 observers start at 390 nm: zero below, as the project's tables are
        # (align would hold the 390 nm values)
        start = colour.MSDS_CMFS[name].wavelengths[0]
        cmfs[NM[NM < start]] = 0.0
        for p in PATCHES:
            r = np.interp(NM, wl, samples[p])
            for what, v in [("r", r), ("r2", r * r)]:
                xyz = colour.sd_to_XYZ(colour.SpectralDistribution(v, NM), cmfs, s, method="Integration")
                rows.append((p.replace(" ", "_"), what, light, o, xyz))

with open(os.path.join(HERE, "spectra_references.csv"), "w") as f:
    f.write("patch,spectrum,illuminant,observer,X,Y,Z\n")
    for p, what, light, o, xyz in rows:
        f.write("%s,%s,%s,%s,%.6f,%.6f,%.6f\n" % (p, what, light, o, *xyz))
