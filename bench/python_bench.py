#!/usr/bin/python3
"""python_bench.py - the Python side of python.sh (bench/README.md, "Python"); run with the package
of BUILD/python on sys.path. One CSV line per measurement on standard output: case,what,value.

    python_bench.py sweep LAUNCH.csf VARIANTS_THETA VARIANTS_V0 JOBS REPS CSFVM OUTFILE
        m.sweep(...) of the launch scene (the model compiled before), and in turn CSFVM --sweep alone
        writing its CSV to OUTFILE (a child process, as a shell starts it): the median and the least
        wall seconds of each; m.sweep with compiling; the sweep's rows and their largest error from
        the closed form.
    python_bench.py run MODEL.csfb REPS
        m.run() of a model (loaded before) and r["pos"], after one run to warm up: the median wall
        seconds.
    python_bench.py scipy VARIANTS_THETA VARIANTS_V0 RTOL REPS
        the same sweep with scipy.integrate.solve_ivp (DOP853, rtol = atol = RTOL, t_eval the rows),
        one call a variant, as a user would write it: the median seconds, evaluations and the largest
        error from the closed form.
"""
import statistics
import sys
import time

import numpy as np

import csf

K, GZ = 0.1 / 0.5, -9.80665


def exact(theta, v0, t):
    vinf = GZ / K
    e = (1 - np.exp(-K * t)) / K
    return v0 * np.cos(theta) * e, vinf * t + (v0 * np.sin(theta) - vinf) * e


def median_time(f, reps):
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def sweep(path, nth, nv, jobs, reps, csfvm, outfile):
    import subprocess
    axes = {"theta": csf.grid(0, 90, nth, "deg"), "v0": csf.grid(5, 50, nv)}
    m = csf.compile(path)
    m.save(outfile + ".csfb")
    alone = [csfvm, "--sweep", "theta=0:90:%ddeg" % nth, "--sweep", "v0=5:50:%d" % nv, "-j", str(jobs), outfile + ".csfb"]
    m.sweep(axes, jobs=jobs)  # warm: the page cache, the allocator
    tp, tc = [], []
    for _ in range(reps):  # in turn, so that the machine's load weighs on both alike
        with open(outfile, "wb") as f:
            t0 = time.perf_counter()
            subprocess.run(alone, stdout=f, check=True)
            tc.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        m.sweep(axes, jobs=jobs)
        tp.append(time.perf_counter() - t0)
    print("sweep,csfvm,%.6f" % statistics.median(tc))
    print("sweep,csfvm_least,%.6f" % min(tc))
    print("sweep,call,%.6f" % statistics.median(tp))
    print("sweep,call_least,%.6f" % min(tp))
    print("sweep,compile_and_call,%.6f" % median_time(lambda: csf.compile(path).sweep(axes, jobs=jobs), reps))
    df = m.sweep(axes, jobs=jobs)
    x, z = exact(df["theta"].to_numpy(), df["v0"].to_numpy(), df["t"].to_numpy())
    err = max(np.max(np.abs(df["ball.pos.x"].to_numpy() - x)), np.max(np.abs(df["ball.pos.z"].to_numpy() - z)))
    print("sweep,rows,%d" % len(df))
    print("sweep,max_error,%.3g" % err)
    # the evaluations of the right-hand side, every variant run alone (--stats's count)
    first = df[df["t"] == 0]
    nrhs = sum(m.run(params={"theta": th, "v0": v}).stats.rhs for th, v in zip(first["theta"], first["v0"]))
    print("sweep,rhs,%d" % nrhs)


def run(path, reps):
    m = csf.load(path)

    def one():
        r = m.run()
        return r["pos"]
    one()
    print("run,call,%.6f" % median_time(one, reps))


def scipy_sweep(nth, nv, rtol, reps):
    from scipy.integrate import solve_ivp
    thetas = [0 + (np.pi / 2 - 0) * (i / (nth - 1)) for i in range(nth)]
    v0s = [5 + 45 * (i / (nv - 1)) for i in range(nv)]
    t_eval = np.arange(21) * 0.1
    g = np.array([0.0, 0.0, GZ])
    stats = {}

    def rhs(t, y, V0):
        v = V0 + y[3:]
        return np.concatenate([v, g - v * K])

    def all_variants():
        err, nfev = 0.0, 0
        for th in thetas:
            for v0 in v0s:
                V0 = np.array([v0 * np.cos(th), 0.0, v0 * np.sin(th)])
                s = solve_ivp(rhs, (0, 2), np.zeros(6), method="DOP853", rtol=rtol, atol=rtol, t_eval=t_eval,
                              args=(V0,))
                x, z = exact(th, v0, s.t)
                err = max(err, np.max(np.abs(s.y[0] - x)), np.max(np.abs(s.y[2] - z)))
                nfev += s.nfev
        stats["err"], stats["nfev"] = err, nfev
    print("scipy,call,%.6f" % median_time(all_variants, reps))
    print("scipy,nfev,%d" % stats["nfev"])
    print("scipy,max_error,%.3g" % stats["err"])


if __name__ == "__main__":
    what = sys.argv[1]
    if what == "sweep":
        sweep(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6]), sys.argv[7],
              sys.argv[8])
    elif what == "run":
        run(sys.argv[2], int(sys.argv[3]))
    elif what == "scipy":
        scipy_sweep(int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5]))
