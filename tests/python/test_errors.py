"""Errors: each a Python exception with the command line's message."""
import os

import numpy as np
import pytest

from conftest import CSFC, csfc, csfvm, parse_csv, run, same_bits, top


def test_compile_error(csf):
    # csfc's whole message, and each diagnostic's place
    path = top("tests/diag/cancels.csf")
    with pytest.raises(csf.CompileError) as e:
        csf.compile(path)
    st, _, err = run([CSFC, path, "-o", os.devnull])
    assert st == 1 and e.value.status == 1
    assert str(e.value) == err.rstrip("\n")
    want = open(top("tests/diag/cancels.err")).read().splitlines()[0]  # cancels.csf:2:7: error: ...
    d = e.value.diagnostics[0]
    assert (os.path.basename(d.file), d.line, d.column, d.severity) == ("cancels.csf", 2, 7, "error")
    assert want == "cancels.csf:%d:%d: error: %s" % (d.line, d.column, d.message)


def test_compile_error_from_source(csf):
    src = "object p: x = 1 m\nrule: y = p.x + 1 s\ninc t till 1 by 0.5 watch p.x\n"
    with pytest.raises(csf.CompileError) as e:
        csf.compile(source=src)
    st, _, err = run([CSFC, "-", "-o", os.devnull], input=src.encode())
    assert str(e.value) == err.rstrip("\n")
    assert e.value.diagnostics == [csf.Diagnostic("<stdin>", 2, 19, "error", "cannot add x (m) and 1 s")]


def test_compile_warning(csf):
    src = "object p: x = 1 m\nobject p: k = 2\ninc t till 1 by 0.5 watch p.x\n"
    with pytest.warns(csf.CompileWarning):
        m = csf.compile(source=src)
    assert m.warnings and m.warnings[0].severity == "warning"
    with pytest.raises(csf.CompileError):
        csf.compile(source=src, werror=True)


@pytest.mark.parametrize("name", ["assert_fail", "nonfinite"])
def test_run_failure(csf, tmp_path, monkeypatch, name):
    # a failed assertion, a non-finite value: RunError, csfvm's message, the rows before it
    src = top("tests/runtime/%s.csf" % name)
    monkeypatch.chdir(top("tests/runtime"))
    m = csf.compile(name + ".csf")
    with pytest.raises(csf.RunError) as e:
        m.run()
    b = csfc(os.path.basename(src), str(tmp_path / "r.csfb"), cwd=top("tests/runtime"))
    st, out, err = csfvm(b)
    expect = dict(l.split(" ", 1) for l in open(src[:-4] + ".expect").read().splitlines())
    assert st == e.value.status == int(expect["exit"])
    assert str(e.value) == err.strip()
    assert expect["stderr"] in str(e.value)
    assert len(e.value.result) == int(expect["rows"])
    assert same_bits(e.value.result.data, parse_csv(out)[1])


@pytest.mark.parametrize("assign", [
    "ball.k=3",                 # unknown property
    "bal.v=(1, 2, 3) m/s",      # unknown object, with a suggestion
    "ball.b=3 m",               # wrong dimension
    "ball.v=3 m/s",             # a scalar for a vector
    "ball.a=(0, 0, 0) m/s^2",   # computed by a rule
    "ball.b=fast",              # not a value
])
def test_parameter_errors(csf, tmp_path, assign):
    m = csf.compile(top("examples/projectile.csf"))
    name, _, value = assign.partition("=")
    with pytest.raises(csf.ParameterError) as e:
        m.run(params={name: value})
    assert isinstance(e.value, ValueError)
    b = csfc(top("examples/projectile.csf"), str(tmp_path / "p.csfb"))
    st, out, err = csfvm("-D", assign, b)
    assert st == 2 and out == ""
    assert "csfvm: " + str(e.value) == err.strip()


def test_parameter_messages():
    import csf
    m = csf.compile(top("examples/projectile.csf"))
    with pytest.raises(csf.ParameterError, match=r"wrong dimension: ball.b is in kg/s, '3 m' is not"):
        m.run(params={"ball.b": (3, "m")})
    with pytest.raises(csf.ParameterError, match=r"did you mean 'ball'\?"):
        m.run(params={"bal.v": (1, 2, 3)})


@pytest.mark.parametrize("kw,args", [
    ({"tol": 1e-30}, ["--tol", "1e-30"]),
    ({"method": "nosuch"}, ["--method", "nosuch"]),
    ({"atol": -1}, ["--atol", "-1"]),
])
def test_option_errors(csf, tmp_path, kw, args):
    m = csf.compile(top("examples/projectile.csf"))
    with pytest.raises(csf.OptionError) as e:
        m.run(**kw)
    b = csfc(top("examples/projectile.csf"), str(tmp_path / "p.csfb"))
    st, out, err = csfvm(*args, b)
    assert st == 2 and err.startswith(csfvm.__globals__["CSFVM"] + ": ")  # (csfvm's argv[0])
    assert str(e.value) == err.strip().split(": ", 1)[1]


def test_options_not_of_a_run(csf):
    m = csf.compile(top("examples/projectile.csf"))
    for opt in (["--sweep", "ball.m=1:2:3"], ["--compare-methods"], ["-j", "2"], ["model.csfb"], ["--help"]):
        with pytest.raises(csf.OptionError):
            m.run(options=opt)


def test_hostile_bytes(csf):
    # every truncation and every byte inverted of a small model, and noise: an exception, never a crash
    good = csf.compile(top("tests/runtime/nonfinite.csf")).bytecode
    ref = csf.load(good)
    bad = [b"", b"\0", b"CSFB", os.urandom(4096), good + b"x", good[:-1] + bytes([good[-1] ^ 1])]
    bad += [good[:n] for n in range(0, len(good), 7)]
    bad += [good[:i] + bytes([good[i] ^ 0xFF]) + good[i + 1:] for i in range(len(good))]
    for b in bad:
        with pytest.raises(csf.BytecodeError):
            csf.load(b)
    # the good program still runs as it did, and so does another
    with pytest.raises(csf.RunError) as e:
        ref.run()
    assert len(e.value.result) == 2
    assert len(csf.compile(top("examples/projectile.csf")).run()) == 21
