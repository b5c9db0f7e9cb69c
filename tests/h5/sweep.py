"""tests/h5/sweep.py SW1.h5 SW2.h5 [CSFVM MODEL.csfb]: reads with h5py the files of
a sweep of tests/h5/launch.csf over theta and v0 (csfvm --sweep ... -o SWEEP.h5,
with -j 1 and -j 2) and checks:
- the layout: the swept values theta and v0 datasets (variants,) with their
  units, on the dimension scale variant (the run numbers 1, 2, ...); rows and
  status (variants,); t (variants, rows), ball.pos and ball.v (variants, rows,
  3) on the scales variant, row and xyz; the root's attribute swept; xarray
  (where installed) gives theta and v0 as coordinates of variant;
- every variant's rows against the closed form within 1e-9 (m, m/s), NaN
  past its rows; a variant that ends with status 0 landed (its last row at
  z = 0 within 1e-9, before till), one with status 1 failed its assertion
  x < 40 m: its last row before x reaches 40, the next output time past it;
- SW2's datasets are SW1's, bit for bit, and its attributes but the command line;
- with CSFVM and MODEL: each variant's rows and exit status are, bit for bit,
  those of csfvm -D theta=VALUE -D v0=VALUE MODEL, its CSV read by float().
Prints one line per failure; exit status 1 after one."""
import math
import struct
import subprocess
import sys

import h5py

fails = []
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
n = a["variant"].shape[0]


def bits(x):
    return struct.pack("<d", x)


def want(name, shape, dims, unit=None):
    d = a.get(name)
    if d is None:
        fails.append(f"no dataset {name}")
        return
    got = [x.keys() for x in d.dims]
    if d.shape != shape or got != [[x] for x in dims]:
        fails.append(f"{name}: shape {d.shape}, scales {got}; want {shape}, {dims}")
    if unit is not None and d.attrs.get("unit") != unit:
        fails.append(f"{name}: unit {d.attrs.get('unit')!r}, not {unit!r}")


rows = a["row"].shape[0]
if list(a.attrs["swept"]) != ["theta", "v0"]:
    fails.append(f"attribute swept: {list(a.attrs['swept'])}")
if list(a.attrs["columns"][:3]) != ["theta", "v0 [m/s]", "t"]:
    fails.append(f"attribute columns: {list(a.attrs['columns'][:3])}")
want("theta", (n,), ["variant"], "")
want("v0", (n,), ["variant"], "m/s")
want("rows", (n,), ["variant"])
want("status", (n,), ["variant"])
want("t", (n, rows), ["variant", "row"], "s")
want("ball.pos", (n, rows, 3), ["variant", "row", "xyz"], "m")
want("ball.v", (n, rows, 3), ["variant", "row", "xyz"], "m/s")
if list(a["variant"][:]) != list(range(1, n + 1)) or list(a["row"][:]) != list(range(rows)):
    fails.append(f"variant {a['variant'][:5]}..., row {a['row'][:5]}...")
if fails:
    print(*("FAIL: " + x for x in fails), sep="\n")
    sys.exit(1)

theta, v0, nrows, status = a["theta"][:], a["v0"][:], a["rows"][:], a["status"][:]
t, pos, vel = a["t"][()], a["ball.pos"][()], a["ball.v"][()]
if max(nrows) != rows:
    fails.append(f"rows {list(nrows)}: the row axis is {rows} long")
# the closed form: k = b/m = 0.2 /s, v_inf = g/k
k, g = 0.2, -9.80665
vinf = g / k


def exact(i, tt):
    V = (v0[i] * math.cos(theta[i]), v0[i] * math.sin(theta[i]))
    e = math.exp(-k * tt)
    x = V[0] * (1 - e) / k
    z = vinf * tt + (V[1] - vinf) * (1 - e) / k
    return (x, 0.0, z), (V[0] * e, 0.0, vinf + (V[1] - vinf) * e)


for i in range(n):
    r = int(nrows[i])
    where = f"variant {i + 1} (theta {theta[i]!r}, v0 {v0[i]!r})"
    if r < 1 or status[i] not in (0, 1):
        fails.append(f"{where}: {r} rows, status {status[i]}")
        continue
    for j in range(r):
        p, v = exact(i, t[i, j])
        if any(abs(pos[i, j, c] - p[c]) > 1e-9 or abs(vel[i, j, c] - v[c]) > 1e-9 for c in range(3)):
            fails.append(f"{where}, row {j}, t {t[i, j]!r}: pos {list(pos[i, j])}, v {list(vel[i, j])}; exact {p}, {v}")
            break
    pad = [t[i, r:], pos[i, r:], vel[i, r:]]
    if not all(math.isnan(x) for q in pad for x in q.flat):
        fails.append(f"{where}: not NaN past its {r} rows")
    if status[i] == 0 and not (abs(pos[i, r - 1, 2]) <= 1e-9 and 0 < t[i, r - 1] < 8):
        fails.append(f"{where}: status 0, but its last row, t {t[i, r - 1]!r}, is not the landing (z {pos[i, r - 1, 2]!r})")
    if status[i] == 1 and not (pos[i, r - 1, 0] < 40 <= exact(i, t[i, r - 1] + 0.1)[0][0]):
        fails.append(f"{where}: status 1, but x {pos[i, r - 1, 0]!r} at its last row, t {t[i, r - 1]!r}")
    if len(fails) > 3:
        break

# SW2: the same data
if sorted(a) != sorted(b):
    fails.append(f"{sys.argv[2]}: datasets {sorted(b)}, not {sorted(a)}")
for name in a:
    if name in b and a[name][()].tobytes() != b[name][()].tobytes():
        fails.append(f"{sys.argv[2]}: dataset {name} differs")
for name in set(a.attrs) | set(b.attrs):
    if name != "command_line" and str(a.attrs.get(name)) != str(b.attrs.get(name)):
        fails.append(f"{sys.argv[2]}: attribute {name} differs")

# each variant, bit for bit, its -D run's CSV
if len(sys.argv) > 4:
    csfvm, model = sys.argv[3:5]
    for i in range(n):
        run = subprocess.run([csfvm, "-D", f"theta={theta[i]!r}", "-D", f"v0={v0[i]!r}", model], capture_output=True,
                             text=True)
        lines = run.stdout.splitlines()[1:]
        csv = [[float(x) for x in line.split(",")] for line in lines]
        mine = [[t[i, j]] + list(pos[i, j]) + list(vel[i, j]) for j in range(int(nrows[i]))]
        if run.returncode != status[i] or len(csv) != len(mine) or any(
                bits(x) != bits(y) for u, w in zip(csv, mine) for x, y in zip(u, w)):
            fails.append(f"variant {i + 1}: not the rows (or status {run.returncode}) of its -D run")

try:
    import xarray

    ds = xarray.open_dataset(sys.argv[1], engine="h5netcdf")
    if ds["ball.pos"].dims != ("variant", "row", "xyz") or ds["theta"].dims != ("variant",) or \
            not {"theta", "v0", "t", "variant", "row"} <= set(ds.coords):
        fails.append(f"xarray: coordinates {list(ds.coords)}, ball.pos on {ds['ball.pos'].dims}")
    elif not (ds["ball.pos"].isel(variant=n - 1)["v0"] == v0[n - 1]):
        fails.append("xarray: the last variant's v0")
except ImportError:
    pass
for x in fails[:5]:
    print("FAIL:", x)
sys.exit(1 if fails else 0)
