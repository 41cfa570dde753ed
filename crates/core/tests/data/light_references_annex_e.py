"""ANSI/IES TM-30-20 Annex E design-intent priority levels for core/tests/tm30_design_intents.rs,
by luxpy 1.12.5 (K. A. G. Smet, GPL-3.0; luxpy.color.cri.iestm30.metrics.
tm30_metrics_to_annexE_recommendations and its table _IES_TM30_ANNEX_E_TABLE).

Run from the repository root, after light_references.py (luxpy 1.12.5 needs numpy < 2.3, so it
has a virtual environment of its own):
    python3 -m venv venv_luxpy && venv_luxpy/bin/pip install luxpy==1.12.5 "numpy<2.3" matplotlib
    venv_luxpy/bin/python crates/core/tests/data/light_references_annex_e.py
It reads light_references.csv beside itself (colour-science 0.4.7's Rf, Rg, Rf,h1 and Rcs,h1 of
118 lights) and writes light_references_annex_e.csv: per light the Preference, Vividness and
Fidelity priority levels luxpy assigns to those figures (P1-P3 or P-, V1-V3 or V-, F1-F3 or F-).
Only luxpy's table and its classification are used here, not its colour-rendering computation,
so the levels test the table and the rule, on figures made independently of this project.
"""

import os

import numpy as np
from luxpy.color.cri.iestm30.metrics import tm30_metrics_to_annexE_recommendations

HERE = os.path.dirname(os.path.abspath(__file__))

with open(os.path.join(HERE, "light_references.csv")) as f:
    lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
head = lines[0].split(",")
rows = [l.split(",") for l in lines[1:]]
col = {h: i for i, h in enumerate(head)}
names = [r[0] for r in rows]
value = lambda k: np.array([float(r[col[k]]) for r in rows])
levels = tm30_metrics_to_annexE_recommendations(
    Rf=value("rf"), Rg=value("rg"), Rcsh1=value("rcs_h1"), Rfh1=value("rf_h1")
)
with open(os.path.join(HERE, "light_references_annex_e.csv"), "w") as f:
    f.write("# luxpy 1.12.5 on colour-science 0.4.7's figures; made by light_references_annex_e.py\n")
    f.write("name,preference,vividness,fidelity\n")
    for i, n in enumerate(names):
        f.write(",".join([n] + [str(levels[k][i]) for k in range(3)]) + "\n")
print(len(names), "lights")
