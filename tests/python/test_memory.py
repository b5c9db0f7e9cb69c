"""10 000 runs in one process grow its memory by less than 1 MB: libcsf frees everything."""
import gc

import pytest

from conftest import top


def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    pytest.skip("no /proc/self/status")


def test_ten_thousand_runs(csf):
    m = csf.compile(top("examples/projectile.csf"))
    bad = csf.compile(top("tests/runtime/assert_fail.csf"))
    params = {"ball.v": "(3, 0, 4) m/s", "ball.b": (200, "g/s")}

    def one(i):
        if i % 10 == 9:  # failures too: their rows and messages
            try:
                bad.run()
            except csf.RunError:
                pass
        else:
            r = m.run(params=params, tol=1e-10 if i % 2 else None)
            assert len(r) == 21

    for i in range(1000):  # the allocators' pools settle
        one(i)
    gc.collect()
    before = rss_kib()
    for i in range(10000):
        one(i)
    gc.collect()
    grown = rss_kib() - before
    assert grown < 1024, "10 000 runs grew RSS by %d KiB" % grown


def test_models_loaded_and_freed(csf):
    b = csf.compile(top("examples/two_body.csf")).bytecode
    for i in range(500):
        csf.load(b).run()
    gc.collect()
    before = rss_kib()
    for i in range(5000):
        m = csf.load(b)
        assert len(m.columns) == 12
        del m
    gc.collect()
    assert rss_kib() - before < 1024
