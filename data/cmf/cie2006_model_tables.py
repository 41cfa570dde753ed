"""Writes data/cmf/cie2006_model_0_1nm.csv: the CIE 170-1:2006 physiological observer's input
tables at 0.1 nm over 390-780 nm, as CIE TC1-97 tabulates them and luxpy 1.12.5 ships them
(luxpy/toolboxes/indvcmf/data/cietc197_absorbances0_1nm.dat, cietc197_docul2.dat).

Columns:
  l_log_abs, m_log_abs, s_log_abs  log10 of the L, M, S photopigments' relative absorbance
                                   (CIE 170-1 Table 6.6 via TC1-97); s is empty past 615 nm,
                                   where CIE 170-1 leaves the S cone undefined (zero)
  lens_aging, lens_fixed           optical density of the ocular media at 32 years, split into
                                   the part that scales with age and the part that does not
                                   (CIE 170-1 eq. 6.9, Pokorny et al. 1987): lens_fixed is the
                                   5 nm table of TC1-97 (390-455 nm, zero beyond), interpolated
                                   by the cubic spline TC1-97 uses; lens_aging = total - fixed
  macular_rel                      macular pigment optical density relative to its peak
                                   (the 2° table / 0.35, CIE 170-1 Table 6.4)

Run with luxpy's environment: /work/venv_luxpy/bin/python data/cmf/cie2006_model_tables.py
"""
import os
import numpy as np
from scipy import interpolate
import luxpy.toolboxes.indvcmf as ind

src = os.path.join(os.path.dirname(ind.__file__), "data")
raw = np.genfromtxt(os.path.join(src, "cietc197_absorbances0_1nm.dat"), delimiter=",")
raw = raw[raw[:, 0] <= 780.0 + 1e-9]
wl = raw[:, 0]
d2 = np.genfromtxt(os.path.join(src, "cietc197_docul2.dat"), delimiter=",")
d2 = np.vstack((d2, np.c_[np.arange(460, 835, 5), np.zeros(75)]))
fixed = interpolate.InterpolatedUnivariateSpline(d2[:, 0], d2[:, 1])(wl)
aging = raw[:, 5] - fixed
macular = raw[:, 6] / 0.35

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cie2006_model_0_1nm.csv")
with open(out, "w") as f:
    f.write("wavelength_nm,l_log_abs,m_log_abs,s_log_abs,lens_aging,lens_fixed,macular_rel\n")
    for i in range(len(wl)):
        s = "" if np.isnan(raw[i, 4]) else "%.13g" % raw[i, 4]
        f.write("%.1f,%.13g,%.13g,%s,%.10g,%.10g,%.10g\n"
                % (wl[i], raw[i, 2], raw[i, 3], s, aging[i], fixed[i], macular[i]))
print("wrote", out, len(wl), "rows")
