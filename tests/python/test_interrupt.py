"""Stopping a run: Ctrl-C (SIGINT), csf.interrupt() from another thread, a progress callback. The
run ends after its current row and keeps the rows before: each the same as the whole run's."""
import os
import signal
import threading
import time

import numpy as np
import pytest

from conftest import same_bits

LONG = "object p: x = 1\nobject p: v = 0\nrule: x' = v\nrule: v' = -x\ninc t till 1e6 by 0.1 watch x, v\n"


@pytest.fixture(scope="module")
def long_model():
    import csf
    return csf.compile(source=LONG)


def reference(m, n):
    """The first n rows of the run, from a run that ends there (a progress callback that stops it)."""
    return m.run(progress=lambda t, rows: rows >= n, progress_interval=0).data


def test_sigint_keeps_the_rows(csf, long_model):
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt) as e:
        long_model.run()
    assert time.monotonic() - t0 < 5
    assert isinstance(e.value, csf.Interrupted)
    r = e.value.result
    assert 0 < len(r) < 10000001 and r.status == 130
    assert same_bits(r.data, reference(long_model, len(r)))
    # Python's handler is back: the next Ctrl-C is a KeyboardInterrupt as always
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)
    # and a run after it is whole
    assert len(csf.compile(source=LONG.replace("till 1e6", "till 1")).run()) == 11


def test_interrupt_from_a_thread(csf, long_model):
    timer = threading.Timer(0.2, csf.interrupt)
    timer.start()
    with pytest.raises(csf.Interrupted) as e:
        long_model.run()
    r = e.value.result
    assert len(r) > 0 and same_bits(r.data, reference(long_model, len(r)))


def test_progress_callback(csf):
    m = csf.compile(source=LONG.replace("till 1e6", "till 100"))
    seen = []
    r = m.run(progress=lambda t, rows: seen.append((t, rows)), progress_interval=0)
    assert len(r) == 1001 and not r.stopped
    assert seen[0] == (0.0, 1) and seen[-1] == (100.0, 1001) and len(seen) == 1001
    r2 = m.run(progress=lambda t, rows: t >= 50, progress_interval=0)
    assert r2.stopped and len(r2) == 501 and same_bits(r2.data, r.data[:501])

    def boom(t, rows):
        raise ValueError("from the callback")
    with pytest.raises(ValueError, match="from the callback"):
        m.run(progress=boom, progress_interval=0)


def test_sweep_interrupted(csf):
    # csfvm --sweep in the child ends after the rows in progress; the whole rows before are kept
    m = csf.compile(source=LONG.replace("till 1e6", "till 2000"))
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(csf.Interrupted) as e:
        m.sweep({"p.x": csf.grid(1, 2, 200)}, jobs=1, as_frame=False)
    table = e.value.result
    n = len(table["t"])
    assert 0 < n < 200 * 20001
    first = m.run().data
    k = min(n, 20001)
    assert same_bits(np.stack([table["t"], table["p.x"], table["p.v"]], axis=1)[:k], first[:k])
