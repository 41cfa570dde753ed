"""Reference light metrics for core/tests/light_references.rs, computed with colour-science 0.4.7.

Run from the repository root:
    python3 -m venv venv && venv/bin/pip install colour-science==0.4.7
    venv/bin/python crates/core/tests/data/light_references.py
It writes, beside itself:
  light_references_spd.csv  one light per row: name, first wavelength (nm), step (nm), then the
                            relative spectral power over 380-780 nm at that step. The lights:
                            every spectrum of colour.SDS_ILLUMINANTS and colour.SDS_LIGHT_SOURCES
                            tabulated at 1 or 5 nm over 380-780 nm (CIE A-E, D, FL, FL3.x, HP, LED
                            series; ISO 7589 ones stop at 690 nm and are left out; the
                            measured lamps of the NIST/Ohno and Luxeon sets), trimmed to 380-780
                            nm, and mixes of the project's LED channels (data/leds, 1 nm) named
                            SET:d1/d2/...; lights farther than |Duv| 0.05 from the Planckian
                            locus (no CCT) are left out. Values are written with 7 significant
                            digits and reloaded before computing, so both sides see the same
                            numbers.
  light_references.csv      per light: CCT and Duv (Ohno 2013, as CIE 224:2017 specifies),
                            CIE 13.3 Ra and R1-R14, CIE 224:2017 Rf, ANSI/IES TM-30-18 Rg and the
                            16 hue bins' Rf,hj, Rcs,hj (a fraction, not %) and Rhs,hj.
  light_references_tm30.csv per light: the 99 colour evaluation samples' fidelities Rf,CESi
                            (colour-science's R_s), each sample's hue bin (1-16, by its hue under
                            the reference) and the hue bins' mean CAM02-UCS a', b' under the test
                            light and under the reference (averages_test, averages_reference):
                            what the colour vector graphic is drawn from.
Licence: colour-science is BSD-3-Clause; its spectral data are the CIE's, ISO's and the cited
authors' published tables (see colour.SDS_ILLUMINANTS / SDS_LIGHT_SOURCES documentation).
"""

import os
import warnings

import numpy as np
import colour
from colour.quality import tm3018

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..", "..")

lights = {}
for dataset in (colour.SDS_ILLUMINANTS, colour.SDS_LIGHT_SOURCES):
    for name, sd in dataset.items():
        s = sd.shape
        if s.start > 380 or s.end < 780 or s.interval not in (1, 5) or (380 - s.start) % s.interval:
            continue
        step = int(s.interval)
        nm = np.arange(380, 781, step)
        lights[name] = (step, np.array([sd[w] for w in nm]))


def led_mix(name):
    s, duties = name.split(":")
    d = np.array([float(v) for v in duties.split("/")])
    raw = np.loadtxt(os.path.join(ROOT, "data/leds/%s.csv" % s), delimiter=",", skiprows=1)
    sel = (raw[:, 0] >= 380) & (raw[:, 0] <= 780)
    assert np.all(np.diff(raw[sel, 0]) == 1)
    return (1, raw[sel, 1:] @ d)


for m in [
    "rgb:1/0.52/0.05", "rgb:1/0.73/0.17", "rgb:1/0.8/0.26", "rgbwa:0/0/0/1/0",
    "rgbwa:0.2/0.1/0.1/1/0.3", "rgbwa:0.05/0.2/0.05/0.8/0.6", "rgbwa:0.3/0.5/0.2/1/0.4",
    "tunable_white:1/0/0", "tunable_white:0/1/0", "tunable_white:0.5/0.5/0",
    "tunable_white:1/0.2/0.3",
]:
    lights[m] = led_mix(m)

rows = []
spd_rows = []
tm30_rows = []
for name, (step, v) in lights.items():
    assert "," not in name
    text = ["%.7g" % x for x in v / v.max()]
    values = np.array([float(t) for t in text])
    sd = colour.SpectralDistribution(values, np.arange(380, 781, step), name=name)
    tm = tm3018.colour_fidelity_index_ANSIIESTM3018(sd, additional_data=True)
    if abs(tm.D_uv) > 0.05:
        print("left out (|Duv| > 0.05):", name, tm.D_uv)
        continue
    cri = colour.quality.colour_rendering_index(sd, additional_data=True)
    ri = [cri.Q_as[i].Q_a for i in range(1, 15)]
    rows.append(
        [name]
        + ["%.4f" % tm.CCT, "%.8f" % tm.D_uv, "%.5f" % cri.Q_a]
        + ["%.5f" % r for r in ri]
        + ["%.5f" % tm.R_f, "%.5f" % tm.R_g]
        + ["%.5f" % r for r in tm.R_fs]
        + ["%.6f" % (r / 100) for r in tm.R_cs]
        + ["%.6f" % r for r in tm.R_hs]
    )
    spd_rows.append([name, "380", str(step)] + text)
    tm30_rows.append(
        [name]
        + ["%.5f" % r for r in tm.R_s]
        + ["%d" % (b + 1) for b in tm.bins]
        + ["%.6f" % v for v in tm.averages_test.ravel()]
        + ["%.6f" % v for v in tm.averages_reference.ravel()]
    )

with open(os.path.join(HERE, "light_references_spd.csv"), "w") as f:
    f.write("# colour-science 0.4.7 datasets and data/leds mixes; made by light_references.py\n")
    f.write("name,start_nm,step_nm,values...\n")
    for r in spd_rows:
        f.write(",".join(r) + "\n")
with open(os.path.join(HERE, "light_references.csv"), "w") as f:
    f.write("# colour-science 0.4.7; made by light_references.py beside this file\n")
    head = ["name", "cct", "duv", "ra"] + ["r%d" % i for i in range(1, 15)] + ["rf", "rg"]
    head += ["rf_h%d" % i for i in range(1, 17)] + ["rcs_h%d" % i for i in range(1, 17)]
    head += ["rhs_h%d" % i for i in range(1, 17)]
    f.write(",".join(head) + "\n")
    for r in rows:
        f.write(",".join(r) + "\n")
with open(os.path.join(HERE, "light_references_tm30.csv"), "w") as f:
    f.write("# colour-science 0.4.7; made by light_references.py beside this file\n")
    head = ["name"] + ["rf_ces%d" % i for i in range(1, 100)]
    head += ["bin_ces%d" % i for i in range(1, 100)]
    head += ["%s_h%d" % (c, j) for j in range(1, 17) for c in ("test_a", "test_b")]
    head += ["%s_h%d" % (c, j) for j in range(1, 17) for c in ("ref_a", "ref_b")]
    f.write(",".join(head) + "\n")
    for r in tm30_rows:
        f.write(",".join(r) + "\n")
print(len(rows), "lights")
