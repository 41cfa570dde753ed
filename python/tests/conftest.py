"""Shared data for the tests: the repository's spectra, and the CLI whose output the package
must reproduce (``SPECPOLY_CLI``, default ``target/debug/specpoly``, which ``./test.sh``'s
build makes)."""

import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def table(rel):
    """A spectral CSV of the repository: (names, wavelengths (k,), values (n, k))."""
    with open(ROOT / rel, newline="") as f:
        rows = list(csv.reader(f))
    names = rows[0][1:]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    return names, data[:, 0], data[:, 1:].T.copy()


@pytest.fixture(scope="session")
def colorchecker():
    return table("data/reflectances/colorchecker_babelcolor_average.csv")


@pytest.fixture(scope="session")
def leds():
    return table("data/leds/rgbwa.csv")


@pytest.fixture(scope="session")
def cli():
    exe = Path(os.environ.get("SPECPOLY_CLI", ROOT / "target" / "debug" / "specpoly"))
    if not exe.is_file():
        raise RuntimeError(
            f"{exe}: the CLI is needed to compare against (cargo build -p specpoly, or set SPECPOLY_CLI)"
        )

    def run(*args, stdin=None):
        out = subprocess.run(
            [str(exe), *args], input=stdin, capture_output=True, text=True, check=True, cwd=ROOT
        )
        return out.stdout

    run.json = lambda *args: json.loads(run(*args, "--json"))
    return run
