"""tests/longrun/exact.py SCENE RUN.csv ERR.txt - the true global error of a run
of osc, kepler or projectile (the scenes beside this file) against its exact
solution, and the run's --estimate-error: prints "TRUE EST" (the largest
absolute difference from the exact solution over every row and watched
column, and the estimate --stats reported)."""
import sys, re
import numpy as np

scene, csv, errf = sys.argv[1:4]
d = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)
t = d[:, 0]
if scene == "osc":  # x = A cos(w t), v = -A w sin(w t), A = 0.1 m, w = 8 rad/s
    exact = np.zeros((len(t), 6))
    exact[:, 0] = 0.1 * np.cos(8 * t)
    exact[:, 3] = -0.8 * np.sin(8 * t)
elif scene == "projectile":  # linear drag: k = b/m = 0.2 /s, v_inf = (0, 0, -m g/b)
    k, g = 0.2, 9.80665
    vinf = np.array([0, 0, -g / k])
    v0 = np.array([3.0, 0, 4.0])
    e = np.exp(-k * t)[:, None]
    pos = vinf * t[:, None] + (v0 - vinf) * (1 - e) / k
    v = vinf + (v0 - vinf) * e
    exact = np.hstack([pos, v])
elif scene == "kepler":  # star (M = 1) and planet (m = 0.001), e = 0.5, a = 1, G = 1, from periapsis
    M, m, ecc, a = 1.0, 0.001, 0.5, 1.0
    mu = M + m
    n = np.sqrt(mu / a**3)
    E = n * t
    for _ in range(60):  # Newton on Kepler's equation E - e sin E = n t
        E = E - (E - ecc * np.sin(E) - n * t) / (1 - ecc * np.cos(E))
    b = a * np.sqrt(1 - ecc**2)
    r = np.stack([a * (np.cos(E) - ecc), b * np.sin(E), 0 * t], axis=1)
    Ed = n / (1 - ecc * np.cos(E))
    rv = np.stack([-a * np.sin(E) * Ed, b * np.cos(E) * Ed, 0 * t], axis=1)
    # the columns: star.pos, planet.pos, star.v, planet.v (watch pos, v: pos of every object, then v)
    exact = np.hstack([-m / mu * r, M / mu * r, -m / mu * rv, M / mu * rv])
else:
    sys.exit("unknown scene " + scene)
true = np.max(np.abs(d[:, 1:] - exact))
est = None
for line in open(errf):
    mm = re.match(r"stats: error estimate: (\S+) ", line)
    if mm:
        est = float(mm.group(1))
print(true, est if est is not None else "none")
