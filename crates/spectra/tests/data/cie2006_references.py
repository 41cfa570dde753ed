"""Reference tables for the CIE 2006 physiological observer (CIE 170-1:2006), made offline by
luxpy 1.12.5 (luxpy.toolboxes.indvcmf, its CIE TC1-97 data and model, the defaults), the
independent implementation the tests compare against:

  cie2006_luxpy.csv: kind,age,field,wavelength_nm,v1,v2,v3
    kind lms: the energy cone fundamentals l m s (peak 1), cie2006cmfsEx(out='LMS')
    kind xyz: the cone-fundamental-based x y z, cie2006cmfsEx(out='XYZ') (CIE TC1-97's own
              derivation of the transformation; at 32 years, 2 and 10 degrees it is CIE 170-2's)
  at 1 nm over 390-780 nm.

Run: /work/venv_luxpy/bin/python crates/spectra/tests/data/cie2006_references.py
"""
import os
import warnings
import numpy as np

warnings.filterwarnings("ignore")
import luxpy
from luxpy.toolboxes import indvcmf

LMS_CASES = [(20, 2), (25, 10), (32, 2), (32, 10), (40, 4), (45, 3.5), (60, 6), (61, 8),
             (70, 2.5), (80, 10), (80, 2), (55, 7.3)]
XYZ_CASES = [(32, 2), (32, 10)]

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cie2006_luxpy.csv")
with open(out, "w") as f:
    f.write("# luxpy %s indvcmf.cie2006cmfsEx, wl=[390,830,1], cut at 780 nm\n" % luxpy.__version__)
    f.write("kind,age,field,wavelength_nm,v1,v2,v3\n")
    for kind, cases in (("lms", LMS_CASES), ("xyz", XYZ_CASES)):
        for age, field in cases:
            t = indvcmf.cie2006cmfsEx(age=age, fieldsize=field, wl=[390, 830, 1],
                                      out=kind.upper())
            for j in range(t.shape[1]):
                if t[0, j] > 780:
                    break
                f.write("%s,%g,%g,%d,%.7g,%.7g,%.7g\n"
                        % (kind, age, field, round(t[0, j]), t[1, j], t[2, j], t[3, j]))
print("wrote", out)
