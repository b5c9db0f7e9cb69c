"""CSF from Python: compile a model with csfc, run it in this process through libcsf (its rows as
numpy arrays, exact to the bit), and sweep its parameters with csfvm --sweep in a child process.

    import csf
    m = csf.compile("launch.csf")
    r = m.run(params={"v0": (36, "km/h")}, method="dop853", tol=1e-10)
    r.t, r["ball.pos"], r.units, r.to_pandas()
    m.sweep({"theta": csf.grid(0, 90, 19, "deg"), "v0": [5, 10]}, jobs=2)

The manual is csf-python(7).
"""
from ._errors import (BytecodeError, CompileError, CompileWarning, CSFError, Interrupted, OptionError,
                      ParameterError, RunError, RunWarning)
from ._model import Column, Diagnostic, Model, Parameter, compile, interrupt, load
from ._result import Result, Stats
from ._sweep import Grid, grid

__all__ = ["compile", "load", "grid", "interrupt", "Model", "Result", "Stats", "Column", "Parameter", "Diagnostic",
           "Grid", "CSFError", "CompileError", "BytecodeError", "ParameterError", "OptionError", "RunError",
           "Interrupted", "CompileWarning", "RunWarning", "api_version", "runtime_version"]


def api_version():
    """libcsf's ABI version (csf_api_version)."""
    from . import _lib
    return _lib.lib().csf_api_version()


def runtime_version():
    """The runtime's version (csfvm --version)."""
    from . import _lib
    return _lib.lib().csf_api_runtime_version().decode()
