"""tests/python: the Python package csf against known answers (run by tests/run.sh, job python).

The package and libcsf are those of the build directory $CSF_BUILD (default build): its python/
directory goes first on sys.path. Every child process has a time limit ($CSF_TEST_LIMIT, 300 s).
"""
import os
import subprocess
import sys

import numpy as np
import pytest

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.abspath(os.environ.get("CSF_BUILD", os.path.join(TOP, "build")))
sys.path.insert(0, os.path.join(BUILD, "python"))
CSFC = os.path.join(BUILD, "csfc")
CSFVM = os.path.join(BUILD, "csfvm")
LIMIT = float(os.environ.get("CSF_TEST_LIMIT", "300"))


def top(*path):
    return os.path.join(TOP, *path)


def run(args, **kw):
    """A child process under the time limit: (status, stdout, stderr) as text."""
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=LIMIT, **kw)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def csfc(src, out, *opts, cwd=None):
    st, _, err = run([CSFC, *opts, src, "-o", out], cwd=cwd)
    assert st == 0, err
    return out


def csfvm(*args, cwd=None):
    return run([CSFVM, *args], cwd=cwd)


def parse_csv(text):
    """csfvm's CSV: the header's cells and the rows, each value read by float()."""
    lines = text.splitlines()
    rows = [[float(x) for x in line.split(",")] for line in lines[1:]]
    return lines[0].split(","), np.array(rows, dtype=np.float64).reshape(len(rows), -1)


def same_bits(a, b):
    """The same doubles, bit for bit (-0 and 0 differ)."""
    a, b = np.ascontiguousarray(a, dtype=np.float64), np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and bool((a.view(np.int64) == b.view(np.int64)).all())


def near(got, want, tol=1e-9):
    """Within tol absolutely or relatively, every value."""
    d = np.abs(np.asarray(got) - np.asarray(want))
    return bool((d <= tol * np.maximum(1.0, np.abs(want))).all())


@pytest.fixture
def csf():
    import csf as m
    return m
