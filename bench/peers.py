#!/usr/bin/env python3
"""peers.py - the SciPy side of the peers benchmark (see README.md, "Peers:
SciPy's solve_ivp"; run by peers.sh, one process a run).

    python3 peers.py run PROBLEM METHOD TOL [IC_FILE TILL BY]

integrates PROBLEM (harmonic, kepler_e05, kepler_e09, linear_drag, stiff:
the ODEs of wp/*.csf; nbody: the scene of gen_nbody.sh, whose IC_FILE
(N, then "m x y z vx vy vz" a body), TILL and BY follow) with
scipy.integrate.solve_ivp(method=METHOD, rtol=TOL, atol=TOL,
t_eval=the output times k*by) and writes on standard output the CSV csfvm
writes for the same model: the same header (names and units), one row per
output time, the watched values as the shortest repr of each double, so that
wp/err.awk and the problem's awk (or peers_nbody.awk) measure its error
exactly as they measure csfvm's. On standard error, one line:

    peers: method M, nfev N, njev J, nlu L, status S, T s

T is the wall time of solve_ivp plus writing the rows (what csfvm --stats
times: the integration and the output, not start-up or loading).

The right-hand sides are numpy, written as a SciPy user would write them for
speed: a matrix product for the linear problems, the two-body force on
slices for Kepler, the pairwise force over (N, N, 3) arrays (einsum, matmul)
for the n-body scene. The implicit methods and LSODA get the exact Jacobian
(as csfvm's implicit methods do), not finite differences. No max_step:
solve_ivp steps freely and interpolates at t_eval (csfvm caps its step at
by). Needs python3, numpy and scipy only (Debian: python3-scipy).
"""
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

G = 6.673e-11  # GSL_CONST_MKSA_GRAVITATIONAL_CONSTANT, the runtime's G
METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")
USES_JAC = ("Radau", "BDF", "LSODA")


def cols(objs, props, units):
    """csfvm's header names: obj.prop.x [unit], ... in watch order."""
    out = []
    for o in objs:
        for p, u in zip(props, units):
            out += ["%s.%s.%s [%s]" % (o, p, c, u) for c in "xyz"]
    return out


def harmonic():
    # bob: m = 2 kg, k = 18 N/m, pos' = v, v' = -(k/m) pos; y = (pos, v)
    w2 = 18.0 / 2.0
    A = np.zeros((6, 6))
    A[0:3, 3:6] = np.eye(3)
    A[3:6, 0:3] = -w2 * np.eye(3)
    y0 = np.array([1.0, 0.0, -0.5, 0.0, 3.0, 1.5])
    by = np.pi / 6
    return dict(header=cols(["bob"], ["pos", "v"], ["m", "m/s"]), y0=y0,
                fun=lambda t, y: A @ y, jac=lambda t, y: A,
                t_eval=np.arange(41) * by, order=list(range(6)))


def kepler(rp, vrel2):
    # A and B, G m_A = 3, G m_B = 1 m^3/s^2, periapsis rp, relative speed
    # sqrt(vrel2) there (the decimals of kepler_e05.csf and kepler_e09.csf);
    # y = (pos_A, pos_B, v_A, v_B)
    gma, gmb = 3.0, 1.0
    vrel = np.sqrt(vrel2)
    y0 = np.array([-0.25 * rp, 0, 0, 0.75 * rp, 0, 0,
                   0, -vrel / 4, 0, 0, 3 * vrel / 4, 0])
    eye3 = np.eye(3)

    def fun(t, y):
        d = y[3:6] - y[0:3]
        r2 = d @ d
        s = d / (r2 * np.sqrt(r2))
        return np.concatenate((y[6:12], gmb * s, -gma * s))

    def jac(t, y):
        d = y[3:6] - y[0:3]
        r2 = d @ d
        r = np.sqrt(r2)
        K = eye3 / (r2 * r) - 3.0 * np.outer(d, d) / (r2 * r2 * r)
        J = np.zeros((12, 12))
        J[0:6, 6:12] = np.eye(6)
        J[6:9, 0:3], J[6:9, 3:6] = -gmb * K, gmb * K
        J[9:12, 0:3], J[9:12, 3:6] = gma * K, -gma * K
        return J

    by = np.pi / 10
    # csfvm's columns: A.pos, B.pos, A.v, B.v (the watch list pos, v, by object)
    header = cols(["A", "B"], ["pos"], ["m"]) + cols(["A", "B"], ["v"], ["m/s"])
    return dict(header=header, y0=y0, fun=fun, jac=jac,
                t_eval=np.arange(101) * by, order=list(range(12)))


def linear_drag():
    # ball: m = 2 kg, b = 0.5 kg/s, g = (0, -9.81, 0); v' = g - (b/m) v
    k = 0.5 / 2.0
    A = np.zeros((6, 6))
    A[0:3, 3:6] = np.eye(3)
    A[3:6, 3:6] = -k * np.eye(3)
    c = np.array([0, 0, 0, 0, -9.81, 0])
    y0 = np.array([0.0, 50.0, 0.0, 10.0, 0.0, 0.0])
    return dict(header=cols(["ball"], ["pos", "v"], ["m", "m/s"]), y0=y0,
                fun=lambda t, y: A @ y + c, jac=lambda t, y: A,
                t_eval=np.arange(21) * 1.0, order=list(range(6)))


def stiff():
    # x'' + 1000001 x' + 1e6 x = 0; y = (x, v)
    J = np.array([[0.0, 1.0], [-1e6, -1000001.0]])
    return dict(header=["p.x [m]", "p.v [m/s]"], y0=np.array([1.0, -1.0]),
                fun=lambda t, y: np.array([y[1], -1000001.0 * y[1] - 1e6 * y[0]]),
                jac=lambda t, y: J, t_eval=np.arange(21) * 0.25, order=[0, 1])


def nbody(icfile, till, by):
    with open(icfile) as f:
        n = int(f.readline())
        ic = np.loadtxt(f, ndmin=2)
    if ic.shape != (n, 7):
        raise SystemExit("peers.py: %s: expected %d bodies of 7 numbers" % (icfile, n))
    gm = G * ic[:, 0]
    n3 = 3 * n
    y0 = np.concatenate((ic[:, 1:4].ravel(), ic[:, 4:7].ravel()))

    def fun(t, y):
        p = y[:n3].reshape(n, 3)
        d = p[np.newaxis, :, :] - p[:, np.newaxis, :]  # d[i, j] = p_j - p_i
        r2 = np.einsum("ijk,ijk->ij", d, d)
        np.fill_diagonal(r2, 1.0)
        w = gm / (r2 * np.sqrt(r2))  # G m_j / r_ij^3
        np.fill_diagonal(w, 0.0)
        a = np.matmul(w[:, np.newaxis, :], d)[:, 0, :]
        return np.concatenate((y[n3:], a.ravel()))

    eye3 = np.eye(3)

    def jac(t, y):
        p = y[:n3].reshape(n, 3)
        d = p[np.newaxis, :, :] - p[:, np.newaxis, :]
        r2 = np.einsum("ijk,ijk->ij", d, d)
        np.fill_diagonal(r2, 1.0)
        r = np.sqrt(r2)
        w3 = gm / (r2 * r)
        w5 = 3.0 * gm / (r2 * r2 * r)
        np.fill_diagonal(w3, 0.0)
        np.fill_diagonal(w5, 0.0)
        # K[i, j] = G m_j (I / r^3 - 3 d d^T / r^5) = d a_i / d p_j, j != i
        K = w3[:, :, None, None] * eye3 - w5[:, :, None, None] * (d[:, :, :, None] * d[:, :, None, :])
        K[np.arange(n), np.arange(n)] = -K.sum(axis=1)
        J = np.zeros((2 * n3, 2 * n3))
        J[:n3, n3:] = np.eye(n3)
        J[n3:, :n3] = K.transpose(0, 2, 1, 3).reshape(n3, n3)
        return J

    rows = int(till / by + 1e-9) + 1
    watch = [0, n // 4 + 1, n // 2 + 6, n - 1]  # gen_nbody.sh's watch list
    header, order = [], []
    for b in watch:
        header += cols(["p%d" % b], ["pos", "v"], ["m", "m/s"])
        order += [3 * b, 3 * b + 1, 3 * b + 2, n3 + 3 * b, n3 + 3 * b + 1, n3 + 3 * b + 2]
    return dict(header=header, y0=y0, fun=fun, jac=jac,
                t_eval=np.arange(rows) * by, order=order)


PROBLEMS = {
    "harmonic": harmonic,
    "kepler_e05": lambda: kepler(0.5, 12.0),
    "kepler_e09": lambda: kepler(0.1, 76.0),
    "linear_drag": linear_drag,
    "stiff": stiff,
}


def run(argv):
    if len(argv) < 3:
        raise SystemExit("usage: peers.py run PROBLEM METHOD TOL [IC_FILE TILL BY]")
    name, method, tol = argv[0], argv[1], float(argv[2])
    if method not in METHODS:
        raise SystemExit("peers.py: unknown method %s (%s)" % (method, " ".join(METHODS)))
    if name == "nbody":
        if len(argv) != 6:
            raise SystemExit("usage: peers.py run nbody METHOD TOL IC_FILE TILL BY")
        prob = nbody(argv[3], float(argv[4]), float(argv[5]))
    elif name in PROBLEMS:
        prob = PROBLEMS[name]()
    else:
        raise SystemExit("peers.py: unknown problem %s" % name)
    t_eval = prob["t_eval"]
    opts = {"jac": prob["jac"]} if method in USES_JAC else {}

    t0 = time.perf_counter()
    sol = solve_ivp(prob["fun"], (0.0, t_eval[-1]), prob["y0"], method=method,
                    t_eval=t_eval, rtol=tol, atol=tol, **opts)
    if sol.status == 0:
        vals = sol.y[prob["order"], :].T
        out = ["t," + ",".join(prob["header"])]
        out += [",".join([repr(float(t))] + [repr(v) for v in row.tolist()])
                for t, row in zip(sol.t.tolist(), vals)]
        sys.stdout.write("\n".join(out) + "\n")
        sys.stdout.flush()
    t1 = time.perf_counter()
    sys.stderr.write("peers: method %s, nfev %d, njev %d, nlu %d, status %d, %.6f s\n"
                     % (method, sol.nfev, sol.njev, sol.nlu, sol.status, t1 - t0))
    if sol.status != 0:
        sys.stderr.write("peers.py: %s %s %g failed: %s\n" % (name, method, tol, sol.message))
        return 1
    return 0


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "run":
        return run(sys.argv[2:])
    raise SystemExit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
