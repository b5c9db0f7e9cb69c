"""libcsf through ctypes (runtime/api/csf_api.h), and where csfc, csfvm and csfview are.

The library is found, in this order: $CSF_LIBCSF; the path make wrote into _paths.py (the build
directory, or the installed lib directory); libcsf.so.1 next to this package; the system's
linker path (ctypes.util.find_library). Its csf_api_version must be API_VERSION.
"""
import ctypes
import ctypes.util
import os
import shutil
import threading

API_VERSION = 1

try:
    from . import _paths
except ImportError:  # the source tree, not a build: the environment or the system must say
    _paths = None

_lock = threading.Lock()
_lib = None
_lib_path = None

c_void_p, c_char_p, c_size_t, c_int, c_double = (ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t,
                                                  ctypes.c_int, ctypes.c_double)
c_double_p = ctypes.POINTER(c_double)
PROGRESS_FN = ctypes.CFUNCTYPE(c_int, c_void_p, c_double, c_size_t)
CATCH_SIGINT = 1

# name: (result type, argument types)
_PROTOS = {
    "csf_api_version": (c_int, []),
    "csf_api_runtime_version": (c_char_p, []),
    "csf_api_load": (c_void_p, [c_char_p, c_size_t, c_char_p, c_size_t]),
    "csf_api_free": (None, [c_void_p]),
    "csf_api_till": (c_double, [c_void_p]),
    "csf_api_by": (c_double, [c_void_p]),
    "csf_api_ncols": (c_size_t, [c_void_p]),
    "csf_api_col_name": (c_char_p, [c_void_p, c_size_t]),
    "csf_api_col_unit": (c_char_p, [c_void_p, c_size_t]),
    "csf_api_col_component": (c_int, [c_void_p, c_size_t]),
    "csf_api_nparams": (c_size_t, [c_void_p]),
    "csf_api_param_name": (c_char_p, [c_void_p, c_size_t]),
    "csf_api_param_unit": (c_char_p, [c_void_p, c_size_t]),
    "csf_api_param_why": (c_char_p, [c_void_p, c_size_t]),
    "csf_api_param_known": (c_int, [c_void_p, c_size_t]),
    "csf_api_param_value": (c_int, [c_void_p, c_size_t, c_double_p]),
    "csf_api_param_parse": (c_int, [c_void_p, c_char_p, c_double_p, c_char_p, c_size_t]),
    "csf_api_run_new": (c_void_p, [c_void_p]),
    "csf_api_run_free": (None, [c_void_p]),
    "csf_api_run_set": (c_int, [c_void_p, c_char_p]),
    "csf_api_run_options": (c_int, [c_void_p, c_int, ctypes.POINTER(c_char_p)]),
    "csf_api_run_error": (c_char_p, [c_void_p]),
    "csf_api_run_rows": (c_size_t, [c_void_p]),
    "csf_api_run_exec": (c_int, [c_void_p, c_double_p, c_size_t, ctypes.c_uint]),
    "csf_api_run_nrows": (c_size_t, [c_void_p]),
    "csf_api_run_diagnostics": (c_char_p, [c_void_p]),
    "csf_api_run_steps": (ctypes.c_ulong, [c_void_p]),
    "csf_api_run_rhs": (ctypes.c_ulong, [c_void_p]),
    "csf_api_run_seconds": (c_double, [c_void_p]),
    "csf_api_run_progress": (None, [c_void_p, PROGRESS_FN, c_void_p, c_double]),
    "csf_api_interrupt": (None, []),
}


def _candidates():
    env = os.environ.get("CSF_LIBCSF")
    if env:
        yield env
        return
    if _paths is not None:
        yield _paths.LIBCSF
    yield os.path.join(os.path.dirname(os.path.abspath(__file__)), "libcsf.so.1")
    found = ctypes.util.find_library("csf")
    if found:
        yield found


def lib():
    """The loaded library (loaded on first use), its functions typed."""
    global _lib, _lib_path
    if _lib is not None:
        return _lib
    with _lock:
        if _lib is not None:
            return _lib
        tried = []
        for path in _candidates():
            if os.sep in path and not os.path.exists(path):
                tried.append(path + " (missing)")
                continue
            try:
                handle = ctypes.CDLL(path)
            except OSError as e:
                tried.append("%s (%s)" % (path, e))
                continue
            version = handle.csf_api_version()
            if version != API_VERSION:
                tried.append("%s (API version %d, this package needs %d)" % (path, version, API_VERSION))
                continue
            for name, (res, args) in _PROTOS.items():
                f = getattr(handle, name)
                f.restype = res
                f.argtypes = args
            _lib, _lib_path = handle, path
            return _lib
        raise ImportError("csf: cannot load libcsf (set CSF_LIBCSF to its path): tried " +
                          ("; ".join(tried) or "nothing"))


def lib_path():
    """The path libcsf was loaded from."""
    lib()
    return _lib_path


def program(name):
    """The path of csfc, csfvm or csfview: $CSF_CSFC, $CSF_CSFVM, $CSF_CSFVIEW; the directory make wrote into _paths.py;
    next to libcsf (a build directory) or in ../bin from it (an installation); else PATH."""
    env = os.environ.get("CSF_" + name.upper())
    if env:
        return env
    dirs = []
    if _paths is not None:
        dirs.append(_paths.BINDIR)
    try:
        libdir = os.path.dirname(os.path.realpath(lib_path()))
        dirs += [libdir, os.path.normpath(os.path.join(libdir, os.pardir, "bin"))]
    except ImportError:
        pass
    for d in dirs:
        p = os.path.join(d, name)
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    p = shutil.which(name)
    if p:
        return p
    raise FileNotFoundError("csf: cannot find %s (set CSF_%s to its path, or put it on PATH)" % (name, name.upper()))
