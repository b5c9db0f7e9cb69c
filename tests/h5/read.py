"""tests/h5/read.py RUN.h5 RUN.csv [ROWS]: reads a file of csfvm -o RUN.h5 with
h5py and checks it against the CSV the same run wrote (csfvm >RUN.csv):
every value equals the CSV's number read by float(), bit for bit; each
dataset's unit is the CSV header's; a vector is one dataset (rows, 3); the
root's attributes name the model, the method, the version, the header.
With ROWS, the CSV must have that many rows. With xarray and h5netcdf
installed, xarray reads the file too, with t and xyz as its coordinates.
Prints one line per failure; exit status 1 after one."""
import re
import struct
import sys

import h5py

h5, csv = sys.argv[1], sys.argv[2]
fails = []


def bits(x):
    return struct.pack("<d", x)


with open(csv) as f:
    head = f.readline().rstrip("\n").split(",")
    rows = [[float(v) for v in line.rstrip("\n").split(",")] for line in f]
if len(sys.argv) > 3 and len(rows) != int(sys.argv[3]):
    fails.append(f"{csv}: {len(rows)} rows, not {sys.argv[3]}")

f = h5py.File(h5, "r")
if list(f.attrs["columns"]) != head:
    fails.append(f"attribute columns {list(f.attrs['columns'])[:4]}... is not the header {head[:4]}...")
for a in ("model", "method", "tolerance", "defines", "command_line", "csf_version", "till", "by"):
    if a not in f.attrs:
        fails.append(f"no root attribute {a}")
# the datasets, as the header groups its columns: NAME.x, NAME.y, NAME.z [UNIT] one vector, but for
# OBJECT.x, OBJECT.y, OBJECT.z, scalars (NAME without a dot: a vector only as a global, 2-D in the file)
def vector_global(name):
    return any(re.fullmatch(re.escape(name) + r"( \(\d+\))?", n) and f[n].ndim == 2 for n in f)


cols = []  # (name, component or None, unit)
i = 1
while i < len(head):
    m = [re.fullmatch(r"(.+)\.([xyz])(?: \[(.*)\])?", h) for h in head[i:i + 3]]
    vec = len(m) == 3 and all(m) and [x.group(2) for x in m] == ["x", "y", "z"] and \
        len({(x.group(1), x.group(3)) for x in m}) == 1 and ("." in m[0].group(1) or vector_global(m[0].group(1)))
    if vec:
        cols += [(m[0].group(1), k, m[0].group(3) or "") for k in range(3)]
        i += 3
    else:
        name, _, unit = head[i].partition(" [")
        cols.append((name, None, unit[:-1]))
        i += 1
# a name taken before is NAME (2), NAME (3), ...: t, xyz (the scale of the vectors, when one is watched)
taken = {"t": 1, "xyz": int(any(k is not None for _, k, _ in cols))}
mapped = []
last = None
for name, k, unit in cols:
    if k is None or k == 0:
        n = taken.get(name, 0) + 1
        taken[name] = n
        last = name if n == 1 else f"{name} ({n})"
    mapped.append((last, k, unit))
t = f["t"]
if t.shape != (len(rows),) or t.attrs["unit"] != "s":
    fails.append(f"t: shape {t.shape} for {len(rows)} rows, unit {t.attrs.get('unit')}")
for name, k, unit in mapped:
    d = f.get(name)
    if d is None:
        fails.append(f"no dataset {name!r}")
        continue
    want = (len(rows), 3) if k is not None else (len(rows),)
    if d.shape != want or d.dtype != "<f8":
        fails.append(f"{name}: shape {d.shape}, type {d.dtype}; want {want}, float64")
    if d.attrs["unit"] != unit:
        fails.append(f"{name}: unit {d.attrs['unit']!r}, the header's {unit!r}")
if fails:
    print("FAIL:", *fails[:5], sep="\n  ")
    sys.exit(1)
data = [t[:]] + [f[name][:, k] if k is not None else f[name][:] for name, k, _ in mapped]
for r, row in enumerate(rows):
    for c, v in enumerate(row):
        if bits(float(data[c][r])) != bits(v):
            fails.append(f"row {r + 1}, column {head[c]}: {data[c][r]!r} in the file, {v!r} in the CSV")
            break
    if len(fails) > 3:
        break
try:
    import xarray

    ds = xarray.open_dataset(h5, engine="h5netcdf")
    vec = [n for n, k, _ in mapped if k is not None]
    if list(ds.coords) != ["t", "xyz"][: 2 if vec else 1] or (vec and ds[vec[0]].dims != ("t", "xyz")):
        fails.append(f"xarray: coordinates {list(ds.coords)}")
    elif not (ds["t"].values == t[:]).all():
        fails.append("xarray: t differs")
except ImportError:
    pass
for x in fails:
    print("FAIL:", x)
sys.exit(1 if fails else 0)
