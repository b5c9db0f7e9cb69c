"""tests/h5/read.py RUN.h5 RUN.csv [ROWS]: reads a file of csfvm -o RUN.h5 with
h5py and checks it against the CSV the same run wrote (csfvm >RUN.csv):
every value equals the CSV's number read by float(), bit for bit; each
dataset's unit is the CSV header's; a vector is one dataset (rows, 3); a
property watched for several objects is one dataset (rows, objects) or
(rows, objects, 3), its objects' names (each once, in an order of the
objects) the dimension scale of its axis 1 (objects, objects_PROP, ...), its
attribute columns each one's first column of the property in the CSV; the
root's attributes name the model, the method, the version, the
header. With ROWS, the CSV must have that many rows. With xarray and
h5netcdf installed, xarray reads the file too, with t, xyz and the objects
as its coordinates. Prints one line per failure; exit status 1 after one."""
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


# the values, as the header groups its columns: NAME.x, NAME.y, NAME.z [UNIT] one vector, but for
# OBJECT.x, OBJECT.y, OBJECT.z, scalars (NAME without a dot: a vector only as a global, 2-D in the file)
def vector_global(name):
    return any(re.fullmatch(re.escape(name) + r"( \(\d+\))?", n) and f[n].ndim == 2 and "columns" not in f[n].attrs
               for n in f)


vals = []  # [first column, NAME, width, unit]
i = 1
while i < len(head):
    m = [re.fullmatch(r"(.+)\.([xyz])(?: \[(.*)\])?", h) for h in head[i:i + 3]]
    vec = len(m) == 3 and all(m) and [x.group(2) for x in m] == ["x", "y", "z"] and \
        len({(x.group(1), x.group(3)) for x in m}) == 1 and ("." in m[0].group(1) or vector_global(m[0].group(1)))
    if vec:
        vals.append([i, m[0].group(1), 3, m[0].group(3) or ""])
        i += 3
    else:
        name, _, unit = head[i].partition(" [")
        vals.append([i, name, 1, unit[:-1]])
        i += 1

# a property (one width, one unit) of two objects or more: one dataset of each object's first value
props = {}
for v in vals:
    if "." in v[1]:
        obj, prop = v[1].split(".", 1)
        props.setdefault((prop, v[2], v[3]), {}).setdefault(obj, v)
lead = {}  # id of a property's first value: (PROP, its values)
inside = set()
for (prop, _, _), objs in props.items():
    if len(objs) > 1:
        group = sorted(objs.values())
        lead[id(group[0])] = (prop, group)
        inside.update(id(v) for v in group[1:])
# the datasets in creation order: t, xyz, the scales of objects, the values; a name taken before is
# NAME (2), NAME (3), ...
taken = set()


def take(name):
    n, k = name, 2
    while n in taken:
        n, k = f"{name} ({k})", k + 1
    taken.add(n)
    return n


take("t")
if any(v[2] == 3 for v in vals):
    take("xyz")
scales = {}  # the objects' names: the scale's name
for v in vals:
    if id(v) in lead:
        prop, group = lead[id(v)]
        objs = frozenset(g[1].split(".", 1)[0] for g in group)
        if objs not in scales:
            scales[objs] = take("objects" if not scales else f"objects_{prop}")
sets = []  # (dataset, {object: its first column} or None, [first column of each, as in the file], width, unit)
for v in vals:
    if id(v) in inside:
        continue
    if id(v) in lead:
        prop, group = lead[id(v)]
        sets.append((take(prop), {g[1].split(".", 1)[0]: g[0] for g in group}, [], v[2], v[3]))
    else:
        sets.append((take(v[1]), None, [v[0]], v[2], v[3]))
t = f["t"]
if t.shape != (len(rows),) or t.attrs["unit"] != "s":
    fails.append(f"t: shape {t.shape} for {len(rows)} rows, unit {t.attrs.get('unit')}")
names = [n for n in f if isinstance(f[n], h5py.Dataset) and f[n].dtype == "<f8"]
if sorted(names) != sorted(["t"] + [s[0] for s in sets]):
    fails.append(f"datasets {sorted(names)}, not {sorted(['t'] + [s[0] for s in sets])}")
for name, objs, first, width, unit in sets:
    d = f.get(name)
    if d is None:
        fails.append(f"no dataset {name!r}")
        continue
    want = (len(rows),) + ((len(objs),) if objs else ()) + ((3,) if width == 3 else ())
    if d.shape != want or d.dtype != "<f8":
        fails.append(f"{name}: shape {d.shape}, type {d.dtype}; want {want}, float64")
    if d.attrs["unit"] != unit:
        fails.append(f"{name}: unit {d.attrs['unit']!r}, the header's {unit!r}")
    if objs:
        sc = d.dims[1].keys()
        scale = scales[frozenset(objs)]
        names = [s.decode() for s in f[sc[0]][:]] if len(sc) == 1 else []
        if len(sc) != 1 or sc[0] != scale or sorted(names) != sorted(objs):
            fails.append(f"{name}: objects' scale {sc} of {names[:4]}..., not {scale!r} of {sorted(objs)[:4]}...")
            continue
        first[:] = [objs[n] for n in names]
        if list(d.attrs.get("columns", [])) != first:
            fails.append(f"{name}: attribute columns {list(d.attrs.get('columns', []))[:4]}..., not {first[:4]}...")
    elif "columns" in d.attrs:
        fails.append(f"{name}: an attribute columns")
if fails:
    print("FAIL:", *fails[:5], sep="\n  ")
    sys.exit(1)
# each column's values: (dataset's values, object, component)
data = [(t[:], None, None)] * len(head)
for name, objs, first, width, _ in sets:
    a = f[name][()]
    for j, c in enumerate(first):
        for k in range(width):
            data[c + k] = (a, j if objs else None, k if width == 3 else None)
for r, row in enumerate(rows):
    for c, v in enumerate(row):
        a, j, k = data[c]
        x = a[(r,) + ((j,) if j is not None else ()) + ((k,) if k is not None else ())]
        if bits(float(x)) != bits(v):
            fails.append(f"row {r + 1}, column {head[c]}: {x!r} in the file, {v!r} in the CSV")
            break
    if len(fails) > 3:
        break
try:
    import xarray

    ds = xarray.open_dataset(h5, engine="h5netcdf")
    want = ["t"] + (["xyz"] if any(s[3] == 3 for s in sets) else []) + list(scales.values())
    vec = [s for s in sets if s[3] == 3]
    if list(ds.coords) != want:
        fails.append(f"xarray: coordinates {list(ds.coords)}, not {want}")
    elif vec and ds[vec[0][0]].dims != ("t",) + ((scales[frozenset(vec[0][1])],) if vec[0][1] else ()) + ("xyz",):
        fails.append(f"xarray: {vec[0][0]}: dimensions {ds[vec[0][0]].dims}")
    elif not (ds["t"].values == t[:]).all():
        fails.append("xarray: t differs")
    for objs, n in scales.items():
        if [str(x) for x in ds[n].values] != [x.decode() for x in f[n][:]]:
            fails.append(f"xarray: {n}: {list(ds[n].values)[:4]}...")
except ImportError:
    pass
for x in fails:
    print("FAIL:", x)
sys.exit(1 if fails else 0)
