"""R15 (the Japanese skin sample TCS15 of JIS Z 8726:1990, computed by the CIE 13.3-1995 rule) of
the 118 lights of light_references_spd.csv, by two tools, for core/tests/light_references.rs.

Run from the repository root, after light_references.py:
    venv/bin/python crates/core/tests/data/light_references_r15.py colour
        colour-science 0.4.7: colour_rendering_index(sd, method="CIE 2024") (TCS01-TCS15, its
        CIE 2024 sample set; R15 is Q_as[15]); writes light_references_r15.csv
    venv_luxpy/bin/python crates/core/tests/data/light_references_r15.py luxpy
        luxpy 1.12.5 (needs numpy < 2.3: its own venv): spd_to_cri(spd, cri_type="ciera-15",
        out="Rfi")[14] (luxpy's JIS-Z-8726-R15.dat sample; the light interpolated to 1 nm first,
        its default); writes light_references_r15_luxpy.csv
Each CSV: name, r15. Nothing here is tuned to this project.
"""

import os
import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
tool = sys.argv[1] if len(sys.argv) > 1 else "colour"

rows = []
with open(os.path.join(HERE, "light_references_spd.csv")) as f:
    for line in f:
        if line.startswith("#") or line.startswith("name,"):
            continue
        c = line.strip().split(",")
        start, step = int(c[1]), int(c[2])
        v = np.array([float(x) for x in c[3:]])
        rows.append((c[0], start, step, v))

if tool == "colour":
    import colour

    version, out = "colour-science " + colour.__version__, "light_references_r15.csv"

    def r15(start, step, v):
        nm = np.arange(start, start + step * len(v), step)
        sd = colour.SpectralDistribution(dict(zip(nm, v)))
        cri = colour.colour_rendering_index(sd, additional_data=True, method="CIE 2024")
        return cri.Q_as[15].Q_a

elif tool == "luxpy":
    import luxpy as lx

    version, out = "luxpy " + lx.__version__, "light_references_r15_luxpy.csv"

    def r15(start, step, v):
        nm = np.arange(start, start + step * len(v), step)
        rfi = lx.cri.spd_to_cri(np.vstack((nm, v)), cri_type="ciera-15", out="Rfi")
        return float(np.ravel(rfi[14])[0])

else:
    sys.exit("usage: light_references_r15.py colour|luxpy")

with open(os.path.join(HERE, out), "w") as f:
    f.write("# %s; made by light_references_r15.py beside this file\n" % version)
    f.write("name,r15\n")
    for n, start, step, v in rows:
        f.write("%s,%.6f\n" % (n, r15(start, step, v)))
print(len(rows), "lights,", version)
