#!/bin/sh
# tests/h5/check.sh CSFC CSFVM DIR BUILD - HDF5 output (-o RUN.h5) and --dump:
#  - a run with -o RUN.h5 and --dump RUN.h5 writes the CSV of the run
#    byte for byte (vectors, scalars named OBJECT.x, a column watched
#    twice, a global vector named xyz, a run that fails an assertion,
#    --every; properties watched for several objects, alone (watch pos, v;
#    watch q.v, b.v) and among values watched for one object, globals and
#    values watched twice: groups.csf);
#    -o RUN.csv writes the bytes of standard output;
#  - read with h5py (tests/h5/read.py; SKIP without python3-h5py): every
#    value the CSV's number read by float(), bit for bit; the units; a
#    vector a dataset of shape (rows, 3); a property of several objects one
#    dataset (rows, objects) or (rows, objects, 3), the objects in their
#    definition order its dimension scale, its attribute columns; the
#    root's attributes; a run that fails an assertion keeps its 15 rows;
#    xarray's variables, dimensions and coordinates for groups.csf;
#  - -o to a path that cannot be made, and a write that fails (a file size
#    limit): exit 2 with a message (a sweep's file: tests/h5/sweep.sh);
#  - a run ended by SIGINT, and one killed, leave a file --dump reads;
#  - a generated program (csfc --emit-c) writes the same file (projectile.csf, groups.csf);
#  - csfview shows RUN.h5 as it shows the CSV (BUILD/csfview).
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3 B=$4
HERE=$(dirname "$0")
TOP=$(cd "$HERE/../.." && pwd)
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
if "$PY" -c 'import h5py' 2>/dev/null; then H5PY=1; else
	H5PY=0
	echo "SKIP: h5: reading the files with h5py: no python3-h5py (make deps installs it)"
fi

(cd "$TOP/examples" && "$CSFC" projectile.csf -o "$T/p.csfb") && "$CSFC" "$HERE/scalars.csf" -o "$T/s.csfb" &&
	"$CSFC" "$TOP/tests/runtime/assert_fail.csf" -o "$T/a.csfb" && "$CSFC" "$HERE/groups.csf" -o "$T/g.csfb" &&
	sed 's/ watch .*/ watch pos, v/' "$HERE/groups.csf" >"$T/gp.csf" && "$CSFC" "$T/gp.csf" -o "$T/gp.csfb" 2>"$T/gp.warn" &&
	sed 's/ watch .*/ watch q.v, b.v/' "$HERE/groups.csf" >"$T/gi.csf" && "$CSFC" "$T/gi.csf" -o "$T/gi.csfb" 2>"$T/gi.warn" ||
	{ echo "FAIL: the test scenes do not compile"; exit 1; }

# run MODEL STATUS [ROWS] [OPTION...]: -o RUN.h5 as the CSV: --dump's bytes, h5py's values; -o RUN.csv
run() {
	m=$1 want=$2 rows=$3
	shift 3
	"$CSFVM" "$@" "$T/$m.csfb" >"$T/$m.csv" 2>"$T/$m.err"
	st=$?
	"$CSFVM" "$@" -o "$T/$m.h5" "$T/$m.csfb" >"$T/$m.out" 2>"$T/$m.h5err"
	sh5=$?
	if [ $st -ne "$want" ] || [ $sh5 -ne $st ] || [ -s "$T/$m.out" ] || ! cmp -s "$T/$m.err" "$T/$m.h5err"; then
		bad "$m $*: exit $st, with -o $m.h5 $sh5, $(head -c 80 "$T/$m.out") $(head -n 1 "$T/$m.h5err")"
		return
	fi
	if "$CSFVM" --dump "$T/$m.h5" >"$T/$m.dump" 2>"$T/$m.derr" && cmp -s "$T/$m.csv" "$T/$m.dump"; then ok
	else bad "$m $*: --dump $m.h5 is not the CSV: $(cmp "$T/$m.csv" "$T/$m.dump" 2>&1) $(head -n 1 "$T/$m.derr")"; fi
	"$CSFVM" "$@" -o "$T/$m.o.csv" "$T/$m.csfb" >"$T/$m.out" 2>/dev/null
	if cmp -s "$T/$m.o.csv" "$T/$m.csv" && [ ! -s "$T/$m.out" ]; then ok; else bad "$m $*: -o $m.o.csv is not the CSV"; fi
	[ $H5PY -eq 1 ] || return
	if "$PY" "$HERE/read.py" "$T/$m.h5" "$T/$m.csv" $rows >"$T/$m.py" 2>&1; then ok
	else bad "$m $*: h5py: $(head -n 3 "$T/$m.py" | tr '\n' ' ')"; fi
}
run p 0 21 -D ball.m=0.25 --method rk8pd --tol 1e-9
run s 0 5
run a 1 15
cp "$T/p.csfb" "$T/e.csfb"
run e 0 5 --every 5
run g 0 9
run gp 0 9
run gi 0 9 --method rk4

# the datasets of groups.csf: a property's of several objects, in the objects' definition order
if [ $H5PY -eq 1 ]; then
	if "$PY" - "$T/g.h5" "$T/gp.h5" "$T/gi.h5" >"$T/layout" 2>&1 <<'EOF'; then ok; else bad "groups.csf's datasets: $(tail -n 1 "$T/layout")"; fi
import sys, h5py
g, gp, gi = (h5py.File(x, "r") for x in sys.argv[1:])
def check(f, name, shape, unit, columns, scale, objects):
    d = f[name]
    assert d.shape == shape and d.attrs["unit"] == unit, f"{name}: {d.shape}, {d.attrs['unit']!r}"
    assert list(d.attrs["columns"]) == columns, f"{name}: columns {list(d.attrs['columns'])}"
    assert d.dims[1].keys() == [scale], f"{name}: scale {d.dims[1].keys()}"
    assert [x.decode() for x in f[scale][:]] == objects, f"{scale}: {f[scale][:]}"
check(g, "v", (9, 3, 3), "m/s", [19, 4, 1], "objects", ["a", "b", "q"])
check(g, "pos", (9, 3, 3), "m", [7, 10, 13], "objects", ["a", "b", "q"])
check(g, "pos (2)", (9, 2), "m", [16, 17], "objects_pos", ["d", "r"])
for n, shape in (("a.m", (9,)), ("b.v", (9, 3)), ("q.v", (9, 3)), ("b.pos", (9, 3)), ("k", (9,)), ("g", (9, 3)), ("r.w", (9,))):
    assert g[n].shape == shape and "columns" not in g[n].attrs, n
assert (g["v"][:, 2, :] == g["q.v"][:]).all() and (g["pos"][:, 1, :] == g["b.pos"][:]).all()
check(gp, "pos", (9, 3, 3), "m", [1, 4, 7], "objects", ["a", "b", "q"])
check(gp, "pos (2)", (9, 2), "m", [10, 11], "objects_pos", ["d", "r"])
check(gp, "v", (9, 3, 3), "m/s", [12, 15, 18], "objects", ["a", "b", "q"])
check(gi, "v", (9, 2, 3), "m/s", [4, 1], "objects", ["b", "q"])
assert sorted(gi) == ["objects", "t", "v", "xyz"], sorted(gi)
try:
    import xarray
except ImportError:
    sys.exit(0)
ds = xarray.open_dataset(sys.argv[1], engine="h5netcdf")
assert list(ds.coords) == ["t", "xyz", "objects", "objects_pos"], list(ds.coords)
assert list(ds.data_vars) == ["v", "pos", "pos (2)", "a.m", "b.v", "q.v", "b.pos", "k", "g", "r.w"], list(ds.data_vars)
assert ds["v"].dims == ("t", "objects", "xyz") and ds["pos (2)"].dims == ("t", "objects_pos"), ds["v"].dims
assert (ds["v"].sel(objects="q").values == g["q.v"][:]).all()
EOF
fi

# the root's attributes: what ran
if [ $H5PY -eq 1 ]; then
	v=$("$CSFVM" --version | sed 's/.* //')
	if "$PY" - "$T/p.h5" "$T/p.csfb" "$v" >"$T/attrs" 2>&1 <<'EOF'; then ok; else bad "the root's attributes: $(tail -n 1 "$T/attrs")"; fi
import sys, h5py
h5, csfb, version = sys.argv[1:]
a = h5py.File(h5, "r").attrs
want = {"model": "projectile.csf", "method": "rk8pd", "tolerance": 1e-9, "defines": ["ball.m=0.25"], "till": 2.0,
        "by": 0.1, "csf_version": version}
for k, v in want.items():
    got = list(a[k]) if k == "defines" else a[k]
    if got != v:
        sys.exit(f"{k}: {got!r}, not {v!r}")
if not a["command_line"].endswith(f" -D ball.m=0.25 --method rk8pd --tol 1e-9 -o {h5} {csfb}"):
    sys.exit(f"command_line: {a['command_line']!r}")
EOF
fi

# errors: a path that cannot be made, a write that fails, --dump of what is not such a file
"$CSFVM" -o "$T/no/such/dir/r.h5" "$T/p.csfb" >"$T/e.out" 2>"$T/e.err"
st=$?
if [ $st -eq 2 ] && grep -q "^csfvm: cannot create $T/no/such/dir/r.h5: No such file or directory" "$T/e.err" && [ ! -s "$T/e.out" ]; then ok
else bad "-o to a path that cannot be made: exit $st, $(head -n 1 "$T/e.err")"; fi
printf 'object p: x = 1\nrule: x'"'"' = 1\ninc t till 100000 by 1 watch x\n' >"$T/long.csf"
"$CSFC" "$T/long.csf" -o "$T/long.csfb"
(trap '' XFSZ; ulimit -f 200; exec "$CSFVM" -o "$T/big.h5" "$T/long.csfb") 2>"$T/e.err"
st=$?
if [ $st -eq 2 ] && grep -q "^error: cannot write output: File too large" "$T/e.err"; then ok
else bad "-o RUN.h5 past the file size limit: exit $st, $(head -n 1 "$T/e.err")"; fi
if "$CSFVM" --sweep 'ball.m=1:2:2 kg' -o "$T/sw.csv" "$T/p.csfb" && "$CSFVM" --sweep 'ball.m=1:2:2 kg' "$T/p.csfb" | cmp -s - "$T/sw.csv"; then ok
else bad "--sweep -o FILE.csv is not the sweep's standard output"; fi
"$CSFVM" --dump "$T/p.csv" >"$T/e.out" 2>"$T/e.err"
st=$?
if [ $st -eq 2 ] && grep -q "^csfvm: cannot read $T/p.csv: " "$T/e.err" && [ ! -s "$T/e.out" ]; then ok
else bad "--dump of a CSV: exit $st, $(head -n 1 "$T/e.err")"; fi

# csfvm-mpi: rank 0 alone makes the file of -o (where Open MPI is installed; tests/sweep/ says SKIP
# otherwise); ranks that all made it would find it locked
if [ -x "$B/csfvm-mpi" ] && command -v mpirun >/dev/null 2>&1; then
	if ASAN_OPTIONS=detect_leaks=0 timeout 120 mpirun --allow-run-as-root --oversubscribe -np 3 "$B/csfvm-mpi" \
		-o "$T/mpi.h5" "$T/s.csfb" >"$T/mpi.out" 2>"$T/mpi.err" && [ ! -s "$T/mpi.out" ] &&
		"$CSFVM" --dump "$T/mpi.h5" | cmp -s - "$T/s.csv"; then ok
	else bad "mpirun csfvm-mpi -o RUN.h5: $(head -n 1 "$T/mpi.err")"; fi
fi

# a run ended by SIGINT keeps its rows; a killed one leaves the rows of its last block, readable
# (BUILD/csfvm itself: CSFVM may be a script that runs it)
printf 'global k = 1 1/s\nobject p: x = 1\nrule: x'"'"' = -k * x\ninc t till 100 s by 1 s watch x\n' >"$T/slow.csf"
"$CSFC" "$T/slow.csf" -o "$T/slow.csfb"
timeout -s INT 1 "$B/csfvm" --method rk4 --step 1e-6 -o "$T/int.h5" "$T/slow.csfb" 2>"$T/int.err"
"$CSFVM" --dump "$T/int.h5" >"$T/int.csv" 2>>"$T/int.err"
st=$?
n=$(wc -l <"$T/int.csv")
if [ $st -eq 0 ] && [ "$n" -gt 1 ] && [ "$n" -lt 101 ] && [ "$(head -n 2 "$T/int.csv" | tr '\n' ' ')" = "t,p.x 0,1 " ]; then ok
else bad "a run ended by SIGINT: --dump exit $st, $n lines, $(head -n 1 "$T/int.err")"; fi
printf 'object p: x = 1\nrule: x'"'"' = 1\ninc t till 1e7 by 1 watch x\n' >"$T/long7.csf"
"$CSFC" "$T/long7.csf" -o "$T/long7.csfb"
# (killed after 0.3 s, or, on a machine so busy that no block was written by then, 1 s or 3 s)
killed=0
for d in 0.3 1 3; do
	rm -f "$T/kill.h5"
	timeout -s KILL $d "$B/csfvm" -o "$T/kill.h5" "$T/long7.csfb" 2>/dev/null
	if "$CSFVM" --dump "$T/kill.h5" >"$T/kill.csv" 2>"$T/kill.err" &&
		"$CSFVM" "$T/long7.csfb" 2>/dev/null | head -n "$(wc -l <"$T/kill.csv")" | cmp -s - "$T/kill.csv"
	then killed=1; break; fi
done
if [ $killed -eq 1 ]; then ok; else bad "a killed run: --dump: $(head -n 1 "$T/kill.err")"; fi
rm -f "$T/kill.h5"

# a generated program writes the file csfvm writes (but for the command line)
# generated DIR MODEL M [OPTION...]: csfc --emit-c DIR/MODEL's program -o M.c.h5 is M.h5
generated() {
	d=$1 src=$2 m=$3
	shift 3
	if (cd "$d" && timeout 120 "$CSFC" --emit-c "$src" -o "$T/$m.exe") 2>"$T/ec.err"; then
		timeout 60 "$T/$m.exe" "$@" -o "$T/$m.c.h5" >"$T/c.out" 2>&1
		st=$?
		if [ $st -eq 0 ] && [ ! -s "$T/c.out" ] && "$CSFVM" --dump "$T/$m.c.h5" | cmp -s - "$T/$m.csv"; then ok
		else bad "generated program of $src -o $m.c.h5: exit $st, $(head -n 1 "$T/c.out")"; fi
	else
		bad "csfc --emit-c $src: $(head -n 1 "$T/ec.err")"
		return
	fi
	[ $H5PY -eq 1 ] || return
	if "$PY" - "$T/$m.h5" "$T/$m.c.h5" >"$T/same" 2>&1 <<'EOF'; then ok; else bad "generated program of $src: $(head -n 2 "$T/same")"; fi
import sys, h5py
v, c = (h5py.File(x, "r") for x in sys.argv[1:])
assert list(v) == list(c), f"datasets {list(v)} and {list(c)}"
for k in v:
    assert v[k][()].tobytes() == c[k][()].tobytes() and v[k].shape == c[k].shape, k
    for a in ("unit", "columns"):
        assert str(v[k].attrs.get(a)) == str(c[k].attrs.get(a)), f"{k}: {a}"
for k in v.attrs:  # (the run record's command line, start, end and seconds are each run's own)
    if k not in ("command_line", "start", "end", "seconds"):
        assert str(v.attrs[k]) == str(c.attrs[k]), f"attribute {k}: {v.attrs[k]!r} and {c.attrs[k]!r}"
EOF
}
generated "$TOP/examples" projectile.csf p -D ball.m=0.25 --method rk8pd --tol 1e-9
generated . "$HERE/groups.csf" g
# csfview reads RUN.h5 as its CSV: the same page, from a file or standard input
if "$B/csfview" -o "$T/v1.html" "$T/p.csv" 2>"$T/v.err" && "$B/csfview" -o "$T/v2.html" "$T/p.h5" 2>>"$T/v.err" &&
	cmp -s "$T/v1.html" "$T/v2.html" && "$B/csfview" -o "$T/v3.html" <"$T/p.csv" 2>>"$T/v.err" &&
	"$B/csfview" -o "$T/v4.html" <"$T/p.h5" 2>>"$T/v.err" && cmp -s "$T/v3.html" "$T/v4.html"; then ok
else bad "csfview RUN.h5: not the page of its CSV: $(head -n 1 "$T/v.err")"; fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
