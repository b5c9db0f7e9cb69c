"""Sweeps: csfvm --sweep as a child process (no fork in this one), its rows read back as the doubles
themselves (--sweep-binary: the CSV's header line, then the rows as doubles)."""
import ctypes
import itertools
import os
import signal
import subprocess
import tempfile
from typing import NamedTuple, Optional

import numpy as np

from . import _lib
from ._errors import Interrupted, OptionError, ParameterError, RunError
from ._model import _num, assignments, format_value, run_options


class Grid(NamedTuple):
    """count values from start to stop, both included, evenly spaced, in unit (None: the model's
    units): csfvm's --sweep 'NAME=START:STOP:COUNT UNIT'."""
    start: float
    stop: float
    count: int
    unit: Optional[str] = None

    def spec(self, name):
        return "%s=%s:%s:%d%s" % (name, _num(self.start), _num(self.stop), self.count,
                                   " " + self.unit if self.unit else "")

    def values(self, model, name):
        """The values in the model's units, as csfvm computes them."""
        u = " " + self.unit if self.unit else ""
        a = _scalar(model, name, "%s%s" % (_num(self.start), u))
        b = _scalar(model, name, "%s%s" % (_num(self.stop), u))
        n = self.count
        return [b if i == n - 1 and n > 1 else a + (b - a) * (i / (n - 1 if n > 1 else 1)) for i in range(n)]


def grid(start, stop, count, unit=None):
    """An axis of a sweep: count values from start to stop (both included), in unit."""
    count = int(count)
    if not 1 <= count <= 100000000:
        raise ValueError("csf.grid: count must be a whole number from 1 to 1e8, not %r" % (count,))
    return Grid(start, stop, count, unit)


def _scalar(model, name, value):
    v = model.parse_value(name, value)
    if isinstance(v, tuple):
        raise ParameterError("%s is a vector; a sweep varies a scalar (a global the vector is computed from)" % name)
    return v


def _check_options(model, args):
    lib = _lib.lib()
    r = lib.csf_api_run_new(model._h)
    try:
        argv = (ctypes.c_char_p * max(len(args), 1))(*[a.encode() for a in args])
        if lib.csf_api_run_options(r, len(args), argv):
            raise OptionError(lib.csf_api_run_error(r).decode("utf-8", "replace"))
    finally:
        lib.csf_api_run_free(r)


def _table(out):
    """csfvm --sweep-binary's output: the header's names and units, and the rows (whole rows only: an
    interrupted sweep's last may be cut) as a 2-D array."""
    nl = out.find(b"\n")
    if nl < 0:
        return [], [], np.empty((0, 0))
    names, units = [], []
    for cell in out[:nl].decode().split(","):
        name, sep, unit = cell.partition(" [")
        names.append(name)
        units.append(unit[:-1] if sep else "")
    if "t" in names:
        units[names.index("t")] = "s"
        for k in range(names.index("t")):  # a swept value that is also a column: "NAME (swept)"
            if names[k] in names[k + 1:]:
                names[k] += " (swept)"
    width = 8 * len(names)
    body = memoryview(out)[nl + 1:]
    body = body[:len(body) - len(body) % width]
    return names, units, np.frombuffer(body, dtype=np.float64).reshape(-1, len(names)).copy()


def _frame(names, units, data, as_frame):
    if as_frame is None:
        try:
            import pandas  # noqa: F401
            as_frame = True
        except ImportError:
            as_frame = False
    if not as_frame:
        return {n: data[:, k] for k, n in enumerate(names)}
    import pandas as pd
    df = pd.DataFrame(data, columns=names, copy=False)
    df.attrs["units"] = dict(zip(names, units))
    return df


def sweep(model, axes, params=None, *, jobs=None, summary=None, as_frame=None, timeout=None, **opts):
    """csf-python(7), Model.sweep."""
    items = list(axes.items() if hasattr(axes, "items") else axes)
    if not items:
        raise ValueError("csf: a sweep needs at least one axis")
    # the trailing grids are csfvm's --sweep axes; whatever comes before them, one --sweep-file of
    # their product (its rows first, the slowest, as the axes' order asks)
    k = len(items)
    while k > 0 and isinstance(items[k - 1][1], Grid):
        k -= 1
    file_axes, grid_axes = items[:k], items[k:]
    file_values = []
    for name, ax in file_axes:
        vals = ax.values(model, name) if isinstance(ax, Grid) else [_scalar(model, name, format_value(v)) for v in ax]
        if not vals:
            raise ValueError("csf: the sweep's axis %s has no values" % name)
        file_values.append(vals)
    for name, g in grid_axes:
        g.values(model, name)  # checks the name, the unit and the dimension before the child starts
    defs = assignments(params)
    for a in defs:
        name, _, value = a.partition("=")
        model.parse_value(name, value)
    oargs = run_options(**opts)
    _check_options(model, oargs)
    args = [_lib.program("csfvm"), "--sweep-binary"] + oargs
    for a in defs:
        args += ["-D", a]
    for name, g in grid_axes:
        args += ["--sweep", g.spec(name)]
    if summary:
        args += ["--sweep-summary", summary]
    if jobs is not None:
        args += ["-j", str(int(jobs))]
    tmp = None
    try:
        if file_axes:
            fd, tmp = tempfile.mkstemp(prefix="csf-sweep-", suffix=".csv")
            with os.fdopen(fd, "w") as f:
                f.write(",".join(n for n, _ in file_axes) + "\n")
                f.writelines(",".join(map(repr, row)) + "\n" for row in itertools.product(*file_values))
            args += ["--sweep-file", tmp]
        args.append("-")
        p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        try:
            out, err = p.communicate(model.bytecode, timeout=timeout)
        except KeyboardInterrupt:  # csfvm ends after the rows in progress: those before them are kept
            p.send_signal(signal.SIGINT)
            out, err = p.communicate(timeout=10)
            names, units, data = _table(out)
            raise Interrupted("csf: sweep interrupted after %d rows (the exception's .result)" % len(data),
                              _frame(names, units, data, as_frame)) from None
        except BaseException:
            p.kill()
            p.communicate()
            raise
    finally:
        if tmp:
            os.unlink(tmp)
    names, units, data = _table(out)
    table = _frame(names, units, data, as_frame)
    if p.returncode != 0:
        msg = err.decode("utf-8", "replace").rstrip("\n")
        raise RunError(msg or "csf: csfvm --sweep failed (status %d)" % p.returncode, table, p.returncode)
    return table
