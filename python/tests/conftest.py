"""Shared fixtures: the checkout, the CLI of the same build, and its --json output."""
import os

# OpenBLAS's thread count changes LAPACK's rounding (Kumar's 122.30 rad/s mode moves by
# 1e-11 relative between 1 and 2 threads), and the CLI's sweeps run it single-threaded:
# the library in this process and the CLI runs below both get one thread, so both
# compute with the same arithmetic. Set before numpy or geardyn load OpenBLAS.
os.environ["OPENBLAS_NUM_THREADS"] = "1"

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))  # the package: python/geardyn
BUILD = os.path.abspath(os.path.join(os.path.dirname(HERE), os.environ.get("GEARDYN_BUILD",
                                                                           "../build")))


def example(name):
    return os.path.join(ROOT, "examples", name + ".yaml")


def run_cli(*args):
    """`geardyn ARGS --json` of the same build, parsed (null -> NaN)."""
    out = subprocess.run([os.path.join(BUILD, "geardyn")] + list(args) + ["--json"],
                         cwd=ROOT, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def nums(values):
    """JSON numbers as a float array, null as NaN."""
    return np.array([math.nan if v is None else v for v in values], dtype=float)


def same(a, b):
    """The same doubles as the CLI printed them (NaN equal to NaN). Both call the same
    library function on the same input, so the numbers are identical; what the JSON can
    show of them is cJSON's printing: %.15g when that reads back within one rounding
    unit (|a - b| <= max(|a|, |b|) DBL_EPSILON, cJSON's compare_double), else %.17g.
    That print tolerance is the only one allowed here."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return False
    tol = np.maximum(np.abs(a), np.abs(b)) * np.finfo(float).eps
    ok = (a == b) | (np.abs(a - b) <= tol) | (np.isnan(a) & np.isnan(b))
    return bool(np.all(ok))


@pytest.fixture(scope="session")
def geardyn():
    import geardyn as g
    return g
