"""A second reference for the base metrics, by luxpy 1.12.5 (K. A. G. Smet, GPL-3.0): CCT and Duv
(luxpy.xyz_to_cct, its default Ohno 2014 method on the CIE 1931 2-degree observer), CIE 13.3 Ra and
R9 (luxpy.cri.spd_to_ciera; spd_to_cri with cri_type='ciera-14', out='Rfi'), CIE 224:2017 Rf (luxpy.cri.spd_to_cierf)
and TM-30 Rg (spd_to_cri with cri_type='iesrf-tm30-20', out='Rg'), for core/tests/light_luxpy.rs.

Run from the repository root, after light_references.py (luxpy needs numpy < 2.3: its own venv):
    venv_luxpy/bin/python crates/core/tests/data/light_references_luxpy.py
It reads light_references_spd.csv (118 lights, at 1 or 5 nm over 380-780 nm) and writes
light_references_luxpy.csv: name, cct, duv, ra, r9, rf, rg. luxpy interpolates every light to its
own 1 nm wavelength grid before the sums (its defaults); nothing here is tuned to this project.
"""

import os
import warnings

import numpy as np
import luxpy as lx

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))

rows = []
with open(os.path.join(HERE, "light_references_spd.csv")) as f:
    for line in f:
        if line.startswith("#") or line.startswith("name,"):
            continue
        c = line.strip().split(",")
        start, step = int(c[1]), int(c[2])
        v = np.array([float(x) for x in c[3:]])
        nm = np.arange(start, start + step * len(v), step)
        rows.append((c[0], np.vstack((nm, v))))

with open(os.path.join(HERE, "light_references_luxpy.csv"), "w") as f:
    f.write("# luxpy %s; made by light_references_luxpy.py beside this file\n" % lx.__version__)
    f.write("name,cct,duv,ra,r9,rf,rg\n")
    for n, spd in rows:
        xyz = lx.spd_to_xyz(spd, cieobs="1931_2", relative=True)
        cct, duv = lx.xyz_to_cct(xyz, cieobs="1931_2", out="cct,duv")
        ra = lx.cri.spd_to_ciera(spd)
        rfi = lx.cri.spd_to_cri(spd, cri_type="ciera-14", out="Rfi")
        rf = lx.cri.spd_to_cierf(spd, out="Rf")
        rg = lx.cri.spd_to_cri(spd, cri_type="iesrf-tm30-20", out="Rg")
        vals = [float(np.ravel(x)[0]) for x in (cct, duv, ra)] + [float(np.ravel(rfi[8])[0])]
        vals += [float(np.ravel(rf)[0]), float(np.ravel(rg)[0])]
        f.write(",".join([n] + ["%.6f" % x for x in vals]) + "\n")
print(len(rows), "lights")
