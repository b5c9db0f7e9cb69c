"""The projectile with drag, the oscillator and the Kepler orbit through Python: every value the
same double as csfvm's CSV parsed with float(), and within 1e-9 of the closed forms."""
import math

import numpy as np
import pytest

from conftest import csfc, csfvm, near, parse_csv, same_bits, top

G0 = -9.80665


def projectile(t, m, b, v0):
    k = b / m
    vinf = np.array([0.0, 0.0, m * G0 / b])
    ek = np.exp(-k * t)[:, None]
    v0 = np.asarray(v0, dtype=float)
    return vinf * t[:, None] + (v0 - vinf) * (1 - ek) / k, vinf + (v0 - vinf) * ek


def against_csfvm(csf, tmp_path, model, args=(), params=None, **run):
    m = csf.compile(top(model))
    r = m.run(params=params, **run)
    b = csfc(top(model), str(tmp_path / "m.csfb"))
    defs = []
    for a in __import__("csf._model", fromlist=["x"]).assignments(params):
        defs += ["-D", a]
    st, out, err = csfvm(*args, *defs, b)
    assert st == 0, err
    header, rows = parse_csv(out)
    assert header == ["t"] + ["%s [%s]" % (c.name, c.unit) if c.unit else c.name for c in m.columns]
    assert same_bits(r.data, rows)
    return m, r


def test_projectile(csf, tmp_path):
    m, r = against_csfvm(csf, tmp_path, "examples/projectile.csf")
    assert len(r) == 21 and r.t[3] == 0.30000000000000004
    pos, v = projectile(r.t, 0.5, 0.1, (3, 0, 4))
    assert near(r["ball.pos"], pos) and near(r["ball.v"], v)
    assert r["ball.pos"].shape == (21, 3) and r["pos"].shape == (21, 1, 3)
    assert r.units["ball.pos"] == "m" and r.units["ball.v.z"] == "m/s" and r.units["t"] == "s"
    assert r.stats.steps > 0 and r.stats.rhs > r.stats.steps and r.stats.seconds >= 0


def test_projectile_parameters(csf, tmp_path):
    # -D's path: a vector with its unit, a scalar in g/s (0.2 kg/s), the method and tolerance
    params = {"ball.v": "(3, 0, 4) m/s", "ball.b": (200, "g/s"), "ball.m": 0.75}
    m, r = against_csfvm(csf, tmp_path, "examples/projectile.csf", ("--method", "dop853", "--tol", "1e-10"),
                         params, method="dop853", tol=1e-10)
    pos, v = projectile(r.t, 0.75, 0.2, (3, 0, 4))
    assert near(r["ball.pos"], pos) and near(r["ball.v"], v)
    # the same as -D's strings, as pairs, and with numpy's numbers
    import numpy
    for p in (["ball.v=(3, 0, 4) m/s", "ball.b=200 g/s", "ball.m=0.75"],
              [("ball.v", numpy.array([3.0, 0, 4])), ("ball.b", (numpy.float64(0.2), "kg/s")), ("ball.m", 0.75)]):
        assert same_bits(m.run(params=p, method="dop853", tol=1e-10).data, r.data)


def test_oscillator(csf, tmp_path):
    m, r = against_csfvm(csf, tmp_path, "examples/spring.csf")
    w = math.sqrt(4 / 0.25)
    A, v0, p0 = np.array([0.1, 0, 0]), np.array([0.2, 0.4, 0]), np.array([0, 0, 1])
    c, s = np.cos(w * r.t)[:, None], np.sin(w * r.t)[:, None]
    assert near(r["bob.pos"], p0 + A * c + v0 / w * s)
    assert near(r["bob.v"], -A * w * s + v0 * c)
    assert len(r) == 61


def kepler(t, e=0.5, a=1.0, M=1.0, mp=0.001):
    mu = M + mp
    n = math.sqrt(mu / a ** 3)
    E = n * t
    for _ in range(50):  # Newton on E - e sin E = n t
        E = E - (E - e * np.sin(E) - n * t) / (1 - e * np.cos(E))
    q = math.sqrt(1 - e * e)
    r = np.stack([a * (np.cos(E) - e), a * q * np.sin(E), 0 * E], axis=1)
    rd = np.stack([-a * np.sin(E), a * q * np.cos(E), 0 * E], axis=1) * (n / (1 - e * np.cos(E)))[:, None]
    return -mp / mu * r, M / mu * r, -mp / mu * rd, M / mu * rd


def test_kepler(csf, tmp_path):
    m, r = against_csfvm(csf, tmp_path, "examples/two_body.csf", ("--tol", "1e-14"), tol=1e-14)
    sp, pp, sv, pv = kepler(r.t)
    assert near(r["star.pos"], sp) and near(r["planet.pos"], pp)
    assert near(r["star.v"], sv) and near(r["planet.v"], pv)
    # a property every object has: rows x objects x 3, in the objects' order
    assert r.objects("pos") == ["star", "planet"]
    assert r["pos"].shape == (len(r), 2, 3)
    assert same_bits(r["pos"][:, 1, :], r["planet.pos"]) and same_bits(r["v"][:, 0, :], r["star.v"])
    assert same_bits(r["pos.x"], np.stack([r["star.pos.x"], r["planet.pos.x"]], axis=1))


def test_columns_and_parameters(csf):
    m = csf.compile(top("examples/projectile.csf"))
    assert [c.name for c in m.columns] == ["ball.pos.x", "ball.pos.y", "ball.pos.z", "ball.v.x", "ball.v.y", "ball.v.z"]
    assert m.columns["ball.v.y"] == csf.Column("ball.v.y", "m/s", "ball.v", 1)
    p = m.parameters
    assert p["ball.v"].value == (3.0, 0.0, 4.0) and p["ball.v"].unit == "m/s" and p["ball.v"].settable
    assert p["ball.b"].value == 0.1 and p["ball.b"].unit == "kg/s"
    assert p["g"].value == (0.0, 0.0, G0) and p["g"].unit == "m/s^2"
    assert not p["ball.a"].settable and "a rule computes it" in p["ball.a"].why
    assert m.till == 2 and m.by == 0.1


def test_explain_lists_the_same_parameters(csf, tmp_path):
    # the parameters of csfc --explain, in its order, with their values, units and whether -D sets them
    from conftest import run, CSFC
    st, out, _ = run([CSFC, "--explain", top("examples/projectile.csf"), "-o", str(tmp_path / "p.csfb")])
    lines = out[out.index("parameters (csfvm -D"):].splitlines()[1:]
    m = csf.compile(top("examples/projectile.csf"))
    assert len(lines) == len(m.parameters)
    for line, p in zip(lines, m.parameters):
        name, rest = line.strip().split(" = ", 1)
        if rest.startswith("("):
            inside, rest = rest[1:].split(")", 1)
            value = tuple(float(x) for x in inside.split(","))
        else:
            num, _, rest = rest.partition(" ")
            value, rest = float(num), " " + rest
        unit = rest.split(":")[0].split(" (")[0].strip()
        assert (name, value, unit) == (p.name, p.value, p.unit)
        assert (": cannot be set: " + p.why in line) if p.why else "cannot be set" not in line


def test_units_cgs(csf, tmp_path):
    m = csf.compile(top("examples/projectile.csf"), units="cgs")
    r = m.run()
    assert r.units["ball.pos"] == "cm"
    b = csfc(top("examples/projectile.csf"), str(tmp_path / "c.csfb"), "--units", "cgs")
    st, out, err = csfvm(b)
    assert same_bits(r.data, parse_csv(out)[1])
    pos, _ = projectile(r.t, 0.5, 0.1, (3, 0, 4))
    assert near(r["ball.pos"] / 100, pos)


def test_pandas(csf):
    pd = pytest.importorskip("pandas")
    r = csf.compile(top("examples/projectile.csf")).run()
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == ["t"] + [c.name for c in r.columns]
    assert df.attrs["units"]["ball.pos.z"] == "m" and df.attrs["units"]["t"] == "s"
    assert same_bits(df.to_numpy(), r.data)


def test_source_text_and_load(csf, tmp_path):
    src = open(top("examples/projectile.csf")).read()
    m1 = csf.compile(source=src)
    m2 = csf.compile(src)  # a string with a line break is source text
    m1.save(str(tmp_path / "p.csfb"))
    m3 = csf.load(str(tmp_path / "p.csfb"))
    m4 = csf.load(m1.bytecode)
    ref = csf.compile(top("examples/projectile.csf")).run().data
    for m in (m1, m2, m3, m4):
        assert same_bits(m.run().data, ref)
    with pytest.raises(FileNotFoundError):
        csf.compile(str(tmp_path / "missing.csf"))


def test_every_and_stats_text(csf, tmp_path):
    m = csf.compile(top("examples/spring.csf"))
    r = m.run(every=7, stats=True, method="rk8pd", tol=1e-11)
    b = csfc(top("examples/spring.csf"), str(tmp_path / "s.csfb"))
    st, out, err = csfvm("--every", "7", "--stats", "--method", "rk8pd", "--tol", "1e-11", b)
    assert same_bits(r.data, parse_csv(out)[1])
    assert r.diagnostics.startswith("stats: method rk8pd") and err.startswith("stats: method rk8pd")
