"""Sweeps: csfvm --sweep as a child process. 100 variants equal 100 -D runs (csfvm's and Python's),
jobs=1 equals jobs=2, and every row is within 1e-9 of the closed form."""
import math

import numpy as np
import pytest

from conftest import csfc, csfvm, near, parse_csv, same_bits, top

LAUNCH = "tests/sweep/launch.csf"


def launch_exact(theta, v0, t):
    """tests/sweep/launch.csf: pos(t) = v_inf t + (V0 - v_inf)(1 - e^{-kt})/k, v_inf = g/k, k = b/m."""
    k, gz = 0.1 / 0.5, -9.80665
    vinf = gz / k
    e = (1 - np.exp(-k * t)) / k
    return np.stack([v0 * np.cos(theta) * e, 0 * t, vinf * t + (v0 * np.sin(theta) - vinf) * e], axis=1)


@pytest.fixture(scope="module")
def launch():
    import csf
    return csf.compile(top(LAUNCH))


def test_hundred_variants(csf, launch, tmp_path):
    pytest.importorskip("pandas")
    df = launch.sweep({"theta": csf.grid(0, 90, 10, "deg"), "v0": csf.grid(5, 50, 10, "m/s")}, jobs=2)
    assert list(df.columns) == ["theta", "v0", "t", "ball.pos.x", "ball.pos.y", "ball.pos.z"]
    assert df.attrs["units"] == {"theta": "", "v0": "m/s", "t": "s", "ball.pos.x": "m", "ball.pos.y": "m",
                                 "ball.pos.z": "m"}
    assert len(df) == 100 * 21
    # the whole table: csfvm --sweep's CSV, read with float()
    b = csfc(top(LAUNCH), str(tmp_path / "l.csfb"))
    st, out, err = csfvm("--sweep", "theta=0:90:10 deg", "--sweep", "v0=5:50:10 m/s", b)
    assert st == 0, err
    assert same_bits(df.to_numpy(), parse_csv(out)[1])
    data = df.to_numpy()
    for i, (theta, v0) in enumerate(data[::21, :2]):
        rows = data[21 * i:21 * (i + 1), 2:]
        # the same as csfvm -D NAME=PRINTED, and as a run from Python with those values
        st, out, err = csfvm("-D", "theta=%r" % theta, "-D", "v0=%r" % v0, b)
        assert st == 0, err
        assert same_bits(rows, parse_csv(out)[1]), (theta, v0)
        assert same_bits(rows, launch.run(params={"theta": theta, "v0": v0}).data)
        assert near(rows[:, 1:], launch_exact(theta, v0, rows[:, 0]))
    assert data[-1, 0] == math.pi / 2 and data[-1, 1] == 50


def test_jobs_1_equals_jobs_2(csf, launch):
    axes = {"theta": csf.grid(0, 90, 13, "deg"), "v0": csf.grid(5, 50, 11)}
    a = launch.sweep(axes, jobs=1, as_frame=False)
    b = launch.sweep(axes, jobs=2, as_frame=False)
    assert list(a) == list(b)
    for k in a:
        assert same_bits(a[k], b[k])
    assert len(a["t"]) == 13 * 11 * 21


def test_lists_and_grids_in_any_order(csf, launch, tmp_path):
    # a list after a grid: the variants in the axes' order, the last fastest, as csfvm's --sweep does
    df = launch.sweep({"theta": csf.grid(0, 90, 3, "deg"), "v0": [5, (36, "km/h"), "20 m/s"]}, jobs=2,
                      as_frame=False)
    b = csfc(top(LAUNCH), str(tmp_path / "l.csfb"))
    st, out, err = csfvm("--sweep", "theta=0:90:3 deg", "--sweep", "v0=5:20:3", b)
    header, rows = parse_csv(out)
    want = rows.copy()
    want[:, 1] = np.repeat(np.tile([5.0, 10.0, 20.0], 3), 21)  # 36 km/h = 10 m/s exactly
    got = np.stack([df[k] for k in df], axis=1)
    assert same_bits(got[:, :2], want[:, :2])
    for i in range(9):
        theta, v0 = got[21 * i, :2]
        assert same_bits(got[21 * i:21 * (i + 1), 2:], launch.run(params={"theta": theta, "v0": v0}).data)
    # a list of angles with units before a grid: one --sweep-file, then the grid
    df2 = launch.sweep({"theta": [(30, "deg"), "45 deg"], "v0": csf.grid(10, 20, 2)}, as_frame=False)
    t30, t45 = launch.parse_value("theta", "30 deg"), launch.parse_value("theta", "45 deg")
    assert same_bits(df2["theta"][::21], [t30, t30, t45, t45])
    assert abs(t30 - math.pi / 6) < 1e-15
    assert list(df2["v0"][::21]) == [10, 20, 10, 20]


def test_fixed_parameters_options_and_summary(csf, launch, tmp_path):
    df = launch.sweep({"v0": csf.grid(5, 50, 4)}, params={"theta": (30, "deg"), "ball.b": (200, "g/s")},
                      method="rk8pd", tol=1e-11, summary="max(ball.pos.z), final(ball.pos.x)", as_frame=False)
    b = csfc(top(LAUNCH), str(tmp_path / "l.csfb"))
    st, out, err = csfvm("-D", "theta=30 deg", "-D", "ball.b=200 g/s", "--method", "rk8pd", "--tol", "1e-11",
                         "--sweep", "v0=5:50:4", "--sweep-summary", "max(ball.pos.z), final(ball.pos.x)", b)
    header, rows = parse_csv(out)
    assert list(df) == ["v0", "max(ball.pos.z)", "final(ball.pos.x)"]
    assert same_bits(np.stack([df[k] for k in df], axis=1), rows)


def test_sweep_errors(csf, launch, tmp_path):
    b = csfc(top(LAUNCH), str(tmp_path / "l.csfb"))
    with pytest.raises(csf.ParameterError) as e:
        launch.sweep({"thetta": [1, 2]})
    st, _, err = csfvm("-D", "thetta=1", b)
    assert "csfvm: " + str(e.value) == err.strip()
    with pytest.raises(csf.ParameterError) as e:
        launch.sweep({"v0": csf.grid(1, 2, 3, "kg")})
    assert "wrong dimension: v0 is in m/s" in str(e.value)
    with pytest.raises(csf.ParameterError, match="a sweep varies a scalar"):
        launch.sweep({"ball.pos": [(0, 0, 1)]})
    with pytest.raises(csf.OptionError, match="unknown method 'nosuch'"):
        launch.sweep({"v0": [1, 2]}, method="nosuch")


def test_failing_variant(csf, tmp_path):
    # a variant whose assertion fails: the sweep goes on; RunError with the whole table and csfvm's message
    src = top("tests/runtime/assert_fail.csf")
    m = csf.compile(src)
    with pytest.raises(csf.RunError) as e:
        m.sweep({"ball.pos.z": [20, 10, 30]}, as_frame=False)
    b = csfc(src, str(tmp_path / "a.csfb"))
    st, out, err = csfvm("--sweep-file", write(tmp_path / "f.csv", "ball.pos.z\n20\n10\n30\n"), b)
    assert st == 1 and e.value.status == 1
    assert str(e.value) == err.strip()
    header, rows = parse_csv(out)
    table = e.value.result
    assert list(table) == ["ball.pos.z (swept)", "t", "ball.pos.x", "ball.pos.y", "ball.pos.z"]
    assert same_bits(np.stack([table[k] for k in table], axis=1), rows)
    # each variant's rows while the ball is above the floor (it lands at sqrt(2 z / g))
    assert len(rows) == sum(math.floor(math.sqrt(2 * z / 9.80665) / 0.1) + 1 for z in (20, 10, 30)) == 61


def write(path, text):
    path.write_text(text)
    return str(path)
