"""Models: compiled by csfc (a child process), loaded and run by libcsf (csf-python(7))."""
import ctypes
import errno
import numbers
import os
import re
import signal
import subprocess
import threading
import warnings
from typing import NamedTuple, Optional, Tuple, Union

import numpy as np

from . import _lib
from ._errors import (BytecodeError, CompileError, CompileWarning, Interrupted, OptionError, ParameterError,
                      RunError, RunWarning)
from ._result import Result, Stats


class Diagnostic(NamedTuple):
    """One of csfc's messages: `file:line:column: severity: message` (file, line and column None
    for a message about no place in the source, as `csfc: error: too many errors`)."""
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    severity: str
    message: str

    def __str__(self):
        if self.file is None:
            return "%s: %s" % (self.severity, self.message)
        return "%s:%d:%d: %s: %s" % (self.file, self.line, self.column, self.severity, self.message)


class Column(NamedTuple):
    """An output column: its name as the CSV header gives it without the unit (`ball.pos.x`), its
    unit ("" when none), and, for a component of a watched vector, the vector (`ball.pos`) and the
    component (0, 1, 2); else None and None."""
    name: str
    unit: str
    vector: Optional[str]
    component: Optional[int]


class Parameter(NamedTuple):
    """A value `csfc --explain` lists and -D sets: a global (`g`) or OBJECT.PROP (`ball.v`), its
    initial value (a float, or a tuple of 3 for a vector) in the model's units, its unit ("" when
    dimensionless), why it cannot be set ("" when it can), and whether its dimension is known."""
    name: str
    value: Union[float, Tuple[float, float, float]]
    unit: str
    why: str
    known: bool

    @property
    def settable(self):
        return not self.why


class _Table(list):
    """A list of Column or Parameter that is also indexed by name."""

    def __init__(self, items):
        super().__init__(items)
        self._by = {x.name: x for x in items}

    def __getitem__(self, key):
        if isinstance(key, str):
            return self._by[key]
        return super().__getitem__(key)

    def __contains__(self, key):
        return key in self._by if isinstance(key, str) else super().__contains__(key)

    def names(self):
        return [x.name for x in self]


_DIAG = re.compile(r"^(.*?):(\d+):(\d+): (error|warning): (.*)$")
_TOOL = re.compile(r"^csfc: (?:(error|warning): )?(.*)$")


def parse_diagnostics(text):
    """csfc's stderr as a list of Diagnostic (the quoted source lines and carets left out)."""
    out = []
    for line in text.splitlines():
        m = _DIAG.match(line)
        if m:
            out.append(Diagnostic(m.group(1), int(m.group(2)), int(m.group(3)), m.group(4), m.group(5)))
            continue
        m = _TOOL.match(line)
        if m:
            out.append(Diagnostic(None, None, None, m.group(1) or "error", m.group(2)))
    return out


def _num(x):
    """A number as -D reads it back to the same double."""
    if isinstance(x, bool):
        raise TypeError("csf: a parameter's value is a number, not %r" % (x,))
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, numbers.Real):
        return repr(float(x))
    raise TypeError("csf: a parameter's value is a number, a vector of 3, a string or (value, unit), not %r" % (x,))


def format_value(v):
    """A parameter's value as -D's text: "(3, 0, 4) m/s" as it is; 20 or 0.5; (200, "g/s");
    (3, 0, 4) or a numpy array of 3; ((3, 0, 4), "m/s")."""
    if isinstance(v, str):
        return v
    if isinstance(v, tuple) and len(v) == 2 and isinstance(v[1], str):
        return "%s %s" % (format_value(v[0]), v[1])
    if isinstance(v, (tuple, list, np.ndarray)):
        if len(v) != 3:
            raise ValueError("csf: a vector has 3 components, not %d: %r" % (len(v), v))
        return "(%s)" % ", ".join(_num(x) for x in v)
    return _num(v)


def assignments(params):
    """NAME=VALUE strings (-D's) of a dict, of (name, value) pairs, or of such strings themselves."""
    if params is None:
        return []
    items = params.items() if hasattr(params, "items") else params
    return [x if isinstance(x, str) else "%s=%s" % (x[0], format_value(x[1])) for x in items]


def run_options(method=None, tol=None, atol=None, hmax=None, fixed=False, step=None, every=None, stats=False,
                options=()):
    """csfvm's options for these arguments (None: csfvm's default)."""
    a = []
    if method is not None:
        a += ["--method", str(method)]
    for flag, v in (("--tol", tol), ("--atol", atol), ("--hmax", hmax), ("--step", step)):
        if v is not None:
            a += [flag, _num(v)]
    if every is not None:
        a += ["--every", str(int(every))]
    if fixed:
        a.append("--fixed")
    if stats:
        a.append("--stats")
    return a + [str(x) for x in options]


def _catch_sigint():
    """Whether a run should catch Ctrl-C itself: in the main thread, where Ctrl-C raises KeyboardInterrupt."""
    return (threading.current_thread() is threading.main_thread() and
            signal.getsignal(signal.SIGINT) is signal.default_int_handler)


def _diag_lines(text, stats):
    return [l for l in text.splitlines() if stats or not l.startswith("stats: ")]


class Model:
    """A compiled model (csf.compile, csf.load): its bytecode, columns and parameters; run() runs it
    in this process through libcsf, sweep() runs csfvm --sweep as a child process."""

    def __init__(self, bytecode, *, path=None, source=None, units=None, diagnostics=()):
        lib = _lib.lib()
        bytecode = bytes(bytecode)
        err = ctypes.create_string_buffer(1024)
        h = lib.csf_api_load(bytecode, len(bytecode), err, len(err))
        if not h:
            raise BytecodeError("invalid bytecode: " + err.value.decode("utf-8", "replace"))
        self._lib, self._h = lib, h
        self.bytecode = bytecode
        self.path = path
        self.source = source
        self.units = units
        self.diagnostics = list(diagnostics)
        self.warnings = [d for d in self.diagnostics if d.severity == "warning"]
        self.till = lib.csf_api_till(h)
        self.by = lib.csf_api_by(h)
        cols = []
        for i in range(lib.csf_api_ncols(h)):
            name = lib.csf_api_col_name(h, i).decode()
            comp = lib.csf_api_col_component(h, i)
            cols.append(Column(name, lib.csf_api_col_unit(h, i).decode(), name[:-2] if comp >= 0 else None,
                               comp if comp >= 0 else None))
        self.columns = _Table(cols)
        pars = []
        v = (ctypes.c_double * 3)()
        for i in range(lib.csf_api_nparams(h)):
            n = lib.csf_api_param_value(h, i, v)
            pars.append(Parameter(lib.csf_api_param_name(h, i).decode(), v[0] if n == 1 else tuple(v[:3]),
                                  lib.csf_api_param_unit(h, i).decode(), lib.csf_api_param_why(h, i).decode(),
                                  bool(lib.csf_api_param_known(h, i))))
        self.parameters = _Table(pars)
        self._index = None

    def __del__(self):
        h, self._h = getattr(self, "_h", None), None
        if h:
            self._lib.csf_api_free(h)

    def __repr__(self):
        return "<csf.Model %s: %d columns, %d parameters, till %g by %g>" % (
            self.path or "(source)", len(self.columns), len(self.parameters), self.till, self.by)

    def save(self, path):
        """Writes the bytecode (a .csfb file csfvm runs)."""
        with open(path, "wb") as f:
            f.write(self.bytecode)

    def parse_value(self, name, value):
        """A parameter's value (as run's params take it) in the model's units: a float, or a tuple of
        3. Raises csf.ParameterError with -D's message."""
        v = (ctypes.c_double * 3)()
        err = ctypes.create_string_buffer(1024)
        assign = "%s=%s" % (name, format_value(value))
        n = self._lib.csf_api_param_parse(self._h, assign.encode(), v, err, len(err))
        if n < 0:
            raise ParameterError(err.value.decode("utf-8", "replace"))
        return v[0] if n == 1 else tuple(v[:3])

    def run(self, params=None, *, method=None, tol=None, atol=None, hmax=None, fixed=False, step=None, every=None,
            stats=False, options=(), progress=None, progress_interval=0.5, warn=True):
        """Runs the model in this process: a csf.Result (csf-python(7), Model.run)."""
        lib, h = self._lib, self._h
        args = run_options(method, tol, atol, hmax, fixed, step, every, stats, options)
        r = lib.csf_api_run_new(h)
        if not r:
            raise MemoryError("csf: out of memory")
        state = {"stop": False, "exc": None}
        try:
            argv = (ctypes.c_char_p * max(len(args), 1))(*[a.encode() for a in args])
            if lib.csf_api_run_options(r, len(args), argv):
                raise OptionError(lib.csf_api_run_error(r).decode("utf-8", "replace"))
            for a in assignments(params):
                if lib.csf_api_run_set(r, a.encode()):
                    raise ParameterError(lib.csf_api_run_error(r).decode("utf-8", "replace"))
            nmax = lib.csf_api_run_rows(r)
            data = np.empty((nmax, len(self.columns) + 1))
            cb = None
            if progress is not None:
                def cb_py(ctx, t, n):
                    try:
                        if progress(t, n):
                            state["stop"] = True
                            return 1
                        return 0
                    except BaseException as e:  # raised again after the run
                        state["exc"] = e
                        return 1
                cb = _lib.PROGRESS_FN(cb_py)
                lib.csf_api_run_progress(r, cb, None, float(progress_interval))
            flags = _lib.CATCH_SIGINT if _catch_sigint() else 0
            st = lib.csf_api_run_exec(r, data.ctypes.data_as(_lib.c_double_p), nmax, flags)
            n = lib.csf_api_run_nrows(r)
            diag = lib.csf_api_run_diagnostics(r).decode("utf-8", "replace")
            st_ = Stats(lib.csf_api_run_steps(r), lib.csf_api_run_rhs(r), lib.csf_api_run_seconds(r))
        finally:
            lib.csf_api_run_free(r)
        res = Result(self, data[:n], diag, st_, st)
        if state["exc"] is not None:
            raise state["exc"]
        if st == 0 or (st == 130 and state["stop"]):
            res.stopped = st == 130
            if warn:
                for line in _diag_lines(diag, False):
                    warnings.warn(RunWarning(line), stacklevel=2)
            return res
        if st == 130:
            raise Interrupted("csf: run interrupted after %d rows (the result is the exception's .result)" % n, res)
        raise RunError("\n".join(_diag_lines(diag, False)) or "csf: the run failed (status %d)" % st, res, st)

    def sweep(self, axes, params=None, *, jobs=None, summary=None, as_frame=None, timeout=None, **opts):
        """Runs csfvm --sweep as a child: a pandas DataFrame (csf-python(7), Model.sweep)."""
        from ._sweep import sweep
        return sweep(self, axes, params=params, jobs=jobs, summary=summary, as_frame=as_frame, timeout=timeout, **opts)


def _program_args(units, include, keep_all, werror, nowarn, max_rows):
    a = [_lib.program("csfc")]
    if units:
        a += ["--units", units]
    for d in include:
        a += ["-I", os.fspath(d)]
    if keep_all:
        a.append("--keep-all")
    if werror:
        a.append("-Werror")
    if nowarn:
        a.append("-w")
    if max_rows is not None:
        a += ["--max-rows", _num(max_rows)]
    return a


def compile(path_or_source=None, *, source=None, units=None, include=(), keep_all=False, werror=False,
            nowarn=False, max_rows=None):
    """Compiles a model with csfc: a path to a .csf file, or its text (source=, or a string with a
    line break). Raises csf.CompileError with csfc's diagnostics; warnings become CompileWarnings."""
    path = None
    if source is None:
        if path_or_source is None:
            raise TypeError("csf.compile: give a path or source=TEXT")
        s = os.fspath(path_or_source)
        if os.path.exists(s):
            path = s
        elif isinstance(s, str) and "\n" in s:
            source = s
        else:
            raise FileNotFoundError(errno.ENOENT, "no such model", s)
    args = _program_args(units, include, keep_all, werror, nowarn, max_rows)
    args += [path if source is None else "-", "-o", "-"]
    p = subprocess.run(args, input=None if source is None else source.encode(), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    text = p.stderr.decode("utf-8", "replace")
    diags = parse_diagnostics(text)
    if p.returncode != 0:
        raise CompileError(text.rstrip("\n"), diags, p.returncode)
    m = Model(p.stdout, path=path, source=source, units=units or "mks", diagnostics=diags)
    for d in m.warnings:
        warnings.warn(CompileWarning(str(d)), stacklevel=2)
    return m


def load(path_or_bytes):
    """A model from a .csfb file (a path) or from its bytes. Raises csf.BytecodeError."""
    if isinstance(path_or_bytes, (bytes, bytearray, memoryview)):
        return Model(path_or_bytes)
    with open(path_or_bytes, "rb") as f:
        return Model(f.read(), path=os.fspath(path_or_bytes))


def interrupt():
    """Ends every run in progress in this process after its current row (as Ctrl-C does)."""
    _lib.lib().csf_api_interrupt()
