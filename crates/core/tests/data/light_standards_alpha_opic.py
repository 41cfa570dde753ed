"""CIE S 026:2018 alpha-opic references for core/tests/light_standards.rs, by luxpy 1.12.5
(K. A. G. Smet, GPL-3.0; luxpy.toolboxes.photbiochem: spd_to_aopicELR, spd_to_aopicDER).

Run from the repository root, after light_standards.py (luxpy 1.12.5 needs numpy < 2.3, so it has
a virtual environment of its own, as for light_references_annex_e.py):
    venv_luxpy/bin/python crates/core/tests/data/light_standards_alpha_opic.py
It reads light_references_spd.csv and light_standards_spd.csv beside itself and writes
light_standards_alpha_opic.csv: per light the alpha-opic efficacy of luminous radiation ELR
(mW/lm: alpha-opic irradiance per lux) and the alpha-opic daylight (D65) efficacy ratio DER of the
five photoreceptors (s-cone, m-cone, l-cone, rhodopic, melanopic), summed on the light's own
grid (force_1nm_sid_spacing=False: a 5 nm light at 5 nm, as this project sums it), and the
melanopic DER with luxpy's default, which first interpolates the light to 1 nm (cubic, CIE 015:2018's
recommendation; der_mel_1nm). luxpy uses its own copy of the action spectra (CIE S 026 Table 2 as
downloaded 2025-06-04, missing values as 0) and takes the illuminance with the CIE 1931 V(lambda)
and Km = 683.002 lm/W.
"""

import os

import numpy as np
import luxpy as lx
from luxpy.toolboxes.photbiochem import spd_to_aopicELR, spd_to_aopicDER

HERE = os.path.dirname(os.path.abspath(__file__))

lights = []
for fname in ("light_references_spd.csv", "light_standards_spd.csv"):
    with open(os.path.join(HERE, fname)) as f:
        for line in f:
            if line.startswith("#") or line.startswith("name,"):
                continue
            c = line.strip().split(",")
            start, step = int(c[1]), int(c[2])
            v = np.array([float(x) for x in c[3:]])
            nm = np.arange(start, start + step * len(v), step)
            lights.append((c[0], np.vstack((nm, v))))

order = [2, 1, 0, 3, 4]  # luxpy: l, m, s, rod, mel -> s, m, l, rod, mel
with open(os.path.join(HERE, "light_standards_alpha_opic.csv"), "w") as f:
    f.write("# luxpy %s (CIE S 026:2018); made by light_standards_alpha_opic.py\n" % lx.__version__)
    f.write("name,elr_sc,elr_mc,elr_lc,elr_rh,elr_mel,der_sc,der_mc,der_lc,der_rh,der_mel,der_mel_1nm\n")
    for n, spd in lights:
        elr = spd_to_aopicELR(spd, force_1nm_sid_spacing=False)[0] * 1000
        der = spd_to_aopicDER(spd, force_1nm_sid_spacing=False)[0]
        der1 = spd_to_aopicDER(spd)[0]
        row = [n] + ["%.7g" % elr[k] for k in order] + ["%.7g" % der[k] for k in order]
        f.write(",".join(row + ["%.7g" % der1[4]]) + "\n")
print(len(lights), "lights")
