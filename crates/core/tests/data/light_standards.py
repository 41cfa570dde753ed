"""Reference figures for core/tests/light_standards.rs: peak wavelength, FWHM, dominant wavelength
and excitation purity, computed with colour-science 0.4.7 and SciPy (not with this project).

Run from the repository root, after light_references.py:
    venv/bin/python crates/core/tests/data/light_standards.py
It reads light_references_spd.csv (the 118 lights of light_references.py) and writes, beside itself:
  light_standards_spd.csv  coloured lights, same layout (name, first nm, step nm, values 380-780 nm):
                           every channel of data/leds (narrow-band and phosphor LEDs, 1 nm), three
                           purple mixes of its red and blue (rgb:R/0/B, duties), Gaussian
                           bands of known FWHM (colour.sd_gaussian, method "FWHM") and Ohno (2005)
                           single-LED models (colour.sd_single_led), at 1 nm; values with 7
                           significant digits, reloaded before computing.
  light_standards.csv      per light (both files): peak wavelength (nm, the largest tabulated
                           value: numpy.argmax), FWHM (nm: scipy.signal.peak_widths at half the
                           peak's height, with the bases at the ends of 380-780 nm so that the
                           height is exactly half the maximum; linear interpolation between
                           samples; empty when the spectrum does not fall below half on both
                           sides), dominant wavelength (nm; negative: the complementary wavelength
                           of a purple) and excitation purity, by colour.dominant_wavelength and
                           colour.excitation_purity against the equal-energy stimulus E
                           (x = y = 1/3) with the CIE 1931 2-degree observer restricted to 380-780 nm
                           (the range every metric here sums over; colour-science's default locus
                           runs 360-830 nm). colour-science returns the dominant wavelength of the
                           spectral-locus node (1 nm) closest to the intersection, an integer.
Licence: colour-science is BSD-3-Clause, SciPy BSD-3-Clause.
"""

import os
import warnings

import numpy as np
import colour
from scipy.signal import peak_widths

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..", "..")


def read_spds(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("name,"):
                continue
            c = line.strip().split(",")
            out.append((c[0], int(c[1]), int(c[2]), np.array([float(v) for v in c[3:]])))
    return out


extra = []
for s in ("rgb", "rgbwa", "tunable_white"):
    raw = np.loadtxt(os.path.join(ROOT, "data/leds/%s.csv" % s), delimiter=",", skiprows=1)
    with open(os.path.join(ROOT, "data/leds/%s.csv" % s)) as f:
        names = f.readline().strip().split(",")[1:]
    sel = (raw[:, 0] >= 380) & (raw[:, 0] <= 780)
    for j, n in enumerate(names):
        extra.append(("%s#%s" % (s, n), 380, 1, raw[sel, 1 + j]))
    if s == "rgb":
        # purples: red and blue together have a complementary wavelength
        for r, b in ((1, 1), (1, 3), (3, 1)):
            extra.append(("rgb:%d/0/%d" % (r, b), 380, 1, r * raw[sel, 1] + b * raw[sel, 3]))
shape = colour.SpectralShape(380, 780, 1)
for mu, fwhm in ((450, 20), (530, 35), (590, 15), (630, 18), (405, 12), (700, 40), (560, 90)):
    sd = colour.sd_gaussian(mu, fwhm, shape, method="FWHM")
    extra.append(("gaussian:%d/%d" % (mu, fwhm), 380, 1, sd.values))
for peak, half in ((460, 25), (525, 30), (615, 20)):
    sd = colour.sd_single_led(peak, shape, half_spectral_width=half)
    extra.append(("ohno2005:%d/%d" % (peak, half), 380, 1, sd.values))

with open(os.path.join(HERE, "light_standards_spd.csv"), "w") as f:
    f.write("# data/leds channels and colour-science 0.4.7 model bands; made by light_standards.py\n")
    f.write("name,start_nm,step_nm,values...\n")
    for n, start, step, v in extra:
        f.write(",".join([n, str(start), str(step)] + ["%.7g" % x for x in v]) + "\n")

lights = read_spds(os.path.join(HERE, "light_references_spd.csv")) + read_spds(
    os.path.join(HERE, "light_standards_spd.csv")
)

cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().trim(shape)
E = np.array([1 / 3, 1 / 3])

with open(os.path.join(HERE, "light_standards.csv"), "w") as f:
    f.write("# colour-science 0.4.7 and SciPy 1.17; made by light_standards.py beside this file\n")
    f.write("name,peak_nm,fwhm_nm,dominant_nm,purity\n")
    for n, start, step, v in lights:
        nm = np.arange(start, start + step * len(v), step)
        i = int(np.argmax(v))
        half = v[i] / 2
        fwhm = ""
        if v[: i + 1].min() < half and v[i:].min() < half:
            w, _, _, _ = peak_widths(v, [i], rel_height=0.5, prominence_data=(np.array([v[i]]), np.array([0]), np.array([len(v) - 1])))
            fwhm = "%.6f" % (w[0] * step)
        sd = colour.SpectralDistribution(dict(zip(nm, v)))
        xyz = colour.sd_to_XYZ(sd, cmfs, method="Integration")
        xy = colour.XYZ_to_xy(xyz)
        wl, _, _ = colour.dominant_wavelength(xy, E, cmfs)
        pe = colour.excitation_purity(xy, E, cmfs)
        f.write("%s,%.1f,%s,%.1f,%.8f\n" % (n, nm[i], fwhm, float(wl), float(pe)))
print(len(lights), "lights")
