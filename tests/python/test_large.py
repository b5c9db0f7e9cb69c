"""A run whose array libcsf faults in on a helper thread while the run writes its rows (4 MiB or more:
runtime/api/api.c, prefault_pages): 1000 projectiles with linear drag watching pos, 1001 rows of 3001
doubles (24 MB, twelve of the helper's 2 MiB calls, the array not page-aligned). Every value the same
double as csfvm's CSV parsed with float(), within 1e-9 of the closed form; a run stopped after its
first row, the helper still at work, keeps that row."""
import numpy as np

from conftest import csfc, csfvm, near, parse_csv, same_bits

N = 1000
# m 0.5 kg, k 0.05 kg/s (rate 0.1 /s), from the origin at v0 = (3 + i/1000, 1, 10 - i/2000) m/s
SOURCE = """using mechanics/mass_point
object p[0..%d]: mass_point
object p[i]: m = 0.5 kg
object p[i]: k = 0.05 kg/s
object p[i]: v = (3 + i/1000, 1, 10 - i/2000) m/s
rule F: W = g.mul(m)
rule F: D = v.mul(-k)
using mechanics/rules
inc t till 2 s by 0.002 s watch pos
""" % (N - 1)


def exact_pos(t):
    """pos(t) = vinf t + (v0 - vinf) (1 - e^(-rate t)) / rate for every projectile: rows x N x 3."""
    rate, vinf = 0.1, np.array([0.0, 0.0, -9.80665 / 0.1])
    i = np.arange(N)
    v0 = np.stack([3 + i / 1000, np.ones(N), 10 - i / 2000], axis=1)
    e = ((1 - np.exp(-rate * t)) / rate)[:, None, None]
    return vinf * t[:, None, None] + (v0 - vinf) * e


def test_large_array_as_the_csv(csf, tmp_path):
    src = tmp_path / "many.csf"
    src.write_text(SOURCE)
    m = csf.compile(str(src))
    r = m.run()
    assert r.data.nbytes >= 4 << 20 and r.data.ctypes.data % 4096 != 0
    assert r["pos"].shape == (1001, N, 3) and r.objects("pos")[:2] == ["p[0]", "p[1]"]
    st, out, err = csfvm(csfc(str(src), str(tmp_path / "many.csfb")))
    assert st == 0, err
    header, rows = parse_csv(out)
    assert len(header) == 1 + 3 * N
    assert same_bits(r.data, rows)
    assert near(r["pos"], exact_pos(r.t))
    # stopped after its first row: that row, as the CSV's
    s = m.run(progress=lambda t, n: True, progress_interval=0)
    assert s.stopped and len(s) == 1 and same_bits(s.data, rows[:1])
