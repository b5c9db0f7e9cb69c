"""The exceptions and warnings of the csf package (csf-python(7), ERRORS)."""


class CSFError(Exception):
    """The base of csf's own errors (not of csf.Interrupted, a KeyboardInterrupt)."""


class CompileError(CSFError):
    """csfc refused the model: str() is csfc's whole message, .diagnostics its errors and
    warnings (csf.Diagnostic: file, line, column, severity, message), .status csfc's exit status."""

    def __init__(self, text, diagnostics, status):
        super().__init__(text)
        self.text = text
        self.diagnostics = diagnostics
        self.status = status


class BytecodeError(CSFError, ValueError):
    """Bytes that are not a valid CSF program (the loader's reason, as csfvm gives it)."""


class ParameterError(CSFError, ValueError):
    """A parameter csfvm's -D would refuse: an unknown name, a wrong dimension, a value that cannot
    be read or cannot be overridden. str() is csfvm's message without "csfvm: "."""


class OptionError(CSFError, ValueError):
    """A run option csfvm would refuse (--tol 1e-30, an unknown method): csfvm's message."""


class RunError(CSFError):
    """The run failed (csfvm's exit status 1 or 2): a failed assertion, a non-finite value, an
    integrator that gave up. str() is csfvm's diagnostics; .result holds the rows written before
    the failure (a csf.Result, or a sweep's table), .status the exit status."""

    def __init__(self, message, result=None, status=1):
        super().__init__(message)
        self.message = message
        self.result = result
        self.status = status


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) ended a run after its current row: .result holds the rows before it.
    A KeyboardInterrupt, so that it stops a loop of runs as Ctrl-C does."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class CompileWarning(UserWarning):
    """A warning of csfc (file:line:col: warning: ...)."""


class RunWarning(UserWarning):
    """A warning csfvm wrote during a run that succeeded."""

for _c in (CSFError, CompileError, BytecodeError, ParameterError, OptionError, RunError, Interrupted, CompileWarning,
           RunWarning):
    _c.__module__ = "csf"  # as the package names them: csf.RunError
