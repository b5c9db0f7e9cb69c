"""Result.plot with matplotlib (skipped where python3-matplotlib is not installed): a line per column
against t, the run's own doubles; one panel per unit, the unit on its axis; a vector or a property of
several objects as its columns."""
import pytest

from conftest import same_bits, top

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")


def lines(ax):
    return {l.get_label(): l for l in ax.get_lines()}


def test_plot_columns(csf):
    import matplotlib.pyplot as plt
    r = csf.compile(top("examples", "projectile.csf")).run()
    fig = r.plot()
    try:
        axes = fig.get_axes()
        assert [a.get_ylabel() for a in axes] == ["[m]", "[m/s]"] and axes[-1].get_xlabel() == "t [s]"
        for a, names in zip(axes, (("ball.pos.x", "ball.pos.y", "ball.pos.z"), ("ball.v.x", "ball.v.y", "ball.v.z"))):
            got = lines(a)
            assert sorted(got) == sorted(names)
            for n in names:
                x, y = got[n].get_data()
                assert same_bits(x, r.t) and same_bits(y, r[n])
    finally:
        plt.close(fig)
    # a vector, and a property of several objects, as their columns, on an axes of one's own
    fig, ax = plt.subplots()
    try:
        r.plot(["ball.v"], ax=ax)
        assert sorted(lines(ax)) == ["ball.v.x", "ball.v.y", "ball.v.z"]
        assert same_bits(lines(ax)["ball.v.z"].get_ydata(), r["ball.v"][:, 2])
    finally:
        plt.close(fig)
    two = csf.compile(source="object a: vector pos = (1, 0, 0) m\nobject b: vector pos = (0, 2, 0) m\n"
                             "rule: pos' = (0, 0, 1) m/s\ninc t till 1 s by 0.5 s watch pos\n").run()
    fig = two.plot(["pos"])
    try:
        got = lines(fig.get_axes()[0])
        assert sorted(got) == ["a.pos.x", "a.pos.y", "a.pos.z", "b.pos.x", "b.pos.y", "b.pos.z"]
        assert same_bits(got["b.pos.y"].get_ydata(), [2.0, 2.0, 2.0])
        assert same_bits(got["b.pos.z"].get_ydata(), two["pos"][:, 1, 2])
    finally:
        plt.close(fig)
