#!/bin/sh
# tests/h5/sweep.sh CSFC CSFVM DIR BUILD - a sweep to one HDF5 file (--sweep ... -o SWEEP.h5):
#  - a projectile over its launch angle and speed that lands (stop when) or
#    fails an assertion (launch.csf), 9 variants and 600 (blocks of them),
#    with -j 1 and -j 2: exit status and diagnostics those of the sweep to
#    CSV, --dump's CSV its bytes; the two files the same bytes but for the
#    command line;
#  - read by sweep.py (SKIP without python3-h5py): every dataset with a
#    leading axis of variants, the swept values on it, NaN past a variant's
#    rows; each variant's rows against the closed form, and bit for bit its
#    -D run's CSV, its exit status the run's; -j 1 and -j 2 the same data;
#  - a generated program's file (csfc --emit-c) and csfvm-mpi's (where
#    BUILD/csfvm-mpi and mpirun are) the same;
#  - an interrupted sweep's file readable, the variants not run with status
#    -1 and no rows, every swept value set;
#  - --sweep-summary, --out-dir and --sweep-binary with -o SWEEP.h5, a path
#    that cannot be made, a write that fails (a file size limit): exit 2
#    with a message.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3 B=$4
HERE=$(dirname "$0")
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
if "$PY" -c 'import h5py' 2>/dev/null; then H5PY=1; else
	H5PY=0
	echo "SKIP: h5 sweep: reading the files with h5py: no python3-h5py (make deps installs it)"
fi

# a sweep to one file: launch.csf over theta and v0, 9 variants (sweep.py: each against its -D run)
# and 600 (blocks of variants); exit status and diagnostics as the CSV's, --dump its bytes
(cd "$HERE" && "$CSFC" launch.csf -o "$T/l.csfb") || { echo "FAIL: launch.csf does not compile"; exit 1; }
# sweeps NAME THETA V0: NAME.csv and its diagnostics; NAME1.h5 (-j 1) and NAME2.h5 (-j 2), each the same
sweeps() {
	m=$1 th=$2 v=$3
	"$CSFVM" --sweep "theta=$th deg" --sweep "v0=$v m/s" "$T/l.csfb" >"$T/$m.csv" 2>"$T/$m.err"
	st=$?
	for j in 1 2; do
		"$CSFVM" --sweep "theta=$th deg" --sweep "v0=$v m/s" -j $j -o "$T/$m$j.h5" "$T/l.csfb" >"$T/$m.out" 2>"$T/$m$j.err"
		sj=$?
		if [ $st -eq 1 ] && [ $sj -eq 1 ] && [ ! -s "$T/$m.out" ] && cmp -s "$T/$m.err" "$T/$m$j.err"; then ok
		else bad "sweep $th, $v -j $j -o $m$j.h5: exit $sj (to CSV: $st), $(head -n 1 "$T/$m$j.err")"; fi
		if "$CSFVM" --dump "$T/$m$j.h5" 2>&1 | cmp -s - "$T/$m.csv"; then ok
		else bad "sweep $th, $v: --dump $m$j.h5 is not the sweep's CSV"; fi
	done
	# the two files differ in their command lines' two digits alone ("-j 1 -o NAME1.h5", "-j 2 -o NAME2.h5")
	n=$(cmp -l "$T/${m}1.h5" "$T/${m}2.h5" | wc -l)
	if [ "$n" -eq 2 ]; then ok; else bad "sweep $th, $v: -j 1 and -j 2 write files that differ in $n bytes, not 2"; fi
}
sweeps sw 15:75:3 10:30:3
sweeps big 15:75:30 10:30:20
if [ $H5PY -eq 1 ]; then
	if "$PY" "$HERE/sweep.py" "$T/sw1.h5" "$T/sw2.h5" "$CSFVM" "$T/l.csfb" >"$T/sw.py" 2>&1; then ok
	else bad "sweep -o sw.h5: $(head -n 3 "$T/sw.py" | tr '\n' ' ')"; fi
	if "$PY" "$HERE/sweep.py" "$T/big1.h5" "$T/big2.h5" >"$T/big.py" 2>&1; then ok
	else bad "sweep of 600 variants -o big.h5: $(head -n 3 "$T/big.py" | tr '\n' ' ')"; fi
fi
# a generated program's sweep: the same file
if (cd "$HERE" && timeout 120 "$CSFC" --emit-c launch.csf -o "$T/l.exe") 2>"$T/ec.err"; then
	timeout 60 "$T/l.exe" --sweep 'theta=15:75:3 deg' --sweep 'v0=10:30:3 m/s' -o "$T/swc.h5" >"$T/c.out" 2>"$T/c.err"
	st=$?
	if [ $st -eq 1 ] && [ ! -s "$T/c.out" ] && "$CSFVM" --dump "$T/swc.h5" | cmp -s - "$T/sw.csv"; then ok
	else bad "generated program of launch.csf --sweep -o swc.h5: exit $st, $(head -n 1 "$T/c.err")"; fi
	if [ $H5PY -eq 1 ]; then
		if "$PY" "$HERE/sweep.py" "$T/sw1.h5" "$T/swc.h5" >"$T/swc.py" 2>&1; then ok
		else bad "generated program's sweep -o swc.h5: $(head -n 3 "$T/swc.py" | tr '\n' ' ')"; fi
	fi
else
	bad "csfc --emit-c launch.csf: $(head -n 1 "$T/ec.err")"
fi
# csfvm-mpi: rank 0 writes the file, the other ranks send it their variants' rows
if [ -x "$B/csfvm-mpi" ] && command -v mpirun >/dev/null 2>&1; then
	ASAN_OPTIONS=detect_leaks=0 timeout 120 mpirun --allow-run-as-root --oversubscribe -np 3 "$B/csfvm-mpi" \
		--sweep 'theta=15:75:30 deg' --sweep 'v0=10:30:20 m/s' -o "$T/mpi.h5" "$T/l.csfb" >"$T/mpi.out" 2>"$T/mpi.err"
	if [ ! -s "$T/mpi.out" ] && "$CSFVM" --dump "$T/mpi.h5" | cmp -s - "$T/big.csv"; then ok
	else bad "mpirun csfvm-mpi --sweep -o SWEEP.h5: $(grep -v assertion "$T/mpi.err" | head -n 1)"; fi
fi
# an interrupted sweep: the variants it ran (status 0, or 130 for those SIGINT ended), then -1 (never run,
# no rows), every swept value set; --dump reads it
printf 'global k = 1 1/s\nobject p: x = 1\nrule: x'"'"' = -k * x\ninc t till 10 s by 1 s watch x\n' >"$T/decay.csf"
"$CSFC" "$T/decay.csf" -o "$T/decay.csfb"
timeout -s INT 1 "$B/csfvm" --method rk4 --step 1e-5 --sweep 'k=1:2:200 1/s' -j 2 -o "$T/int.h5" "$T/decay.csfb" 2>"$T/int.err"
if "$CSFVM" --dump "$T/int.h5" >"$T/int.csv" 2>>"$T/int.err"; then ok
else bad "an interrupted sweep: --dump: $(head -n 1 "$T/int.err")"; fi
if [ $H5PY -eq 1 ]; then
	if "$PY" - "$T/int.h5" >"$T/int.py" 2>&1 <<'EOF'; then ok; else bad "an interrupted sweep: $(tail -n 1 "$T/int.py")"; fi
import sys, h5py
f = h5py.File(sys.argv[1], "r")
st, rows, k = list(f["status"][:]), list(f["rows"][:]), list(f["k"][:])
ran = st.index(-1) if -1 in st else len(st)
assert 0 < ran < 200 and st[ran:] == [-1] * (200 - ran) and rows[ran:] == [0] * (200 - ran), (st, rows)
assert set(st[:ran]) <= {0, 130} and all(r == 11 for r, s in zip(rows, st) if s == 0), (st, rows)
assert k == [1 + j / 199 for j in range(199)] + [2], k[:3]
EOF
fi

# errors: options that write other things, a path that cannot be made, a write that fails
for o in "--sweep-summary max(ball.pos.z)" "--out-dir $T/sw.d" --sweep-binary; do
	# shellcheck disable=SC2086 # $o: an option and its argument
	"$CSFVM" --sweep 'v0=10:20:2 m/s' $o -o "$T/sw.h5" "$T/l.csfb" 2>"$T/e.err"
	st=$?
	if [ $st -eq 2 ] && grep -q "^csfvm: ${o%% *} writes .*; -o FILE.h5 " "$T/e.err" && [ ! -e "$T/sw.h5" ] && [ ! -e "$T/sw.d" ]; then ok
	else bad "--sweep $o -o FILE.h5: exit $st, $(head -n 1 "$T/e.err")"; fi
done
"$CSFVM" --sweep 'v0=10:20:2 m/s' -o "$T/no/such/dir/s.h5" "$T/l.csfb" >"$T/e.out" 2>"$T/e.err"
st=$?
if [ $st -eq 2 ] && grep -q "^csfvm: cannot create $T/no/such/dir/s.h5: No such file or directory" "$T/e.err" && [ ! -s "$T/e.out" ]; then ok
else bad "--sweep -o to a path that cannot be made: exit $st, $(head -n 1 "$T/e.err")"; fi
# (no leak check: HDF5 1.10 does not free the buffer of a chunk whose write failed)
(trap '' XFSZ; ulimit -f 200; ASAN_OPTIONS=detect_leaks=0 exec "$CSFVM" --sweep 'theta=15:75:30 deg' --sweep 'v0=10:30:20 m/s' \
	-o "$T/big.h5" "$T/l.csfb") 2>"$T/e.err"
st=$?
if [ $st -eq 2 ] && [ "$(grep -c "^error: cannot write output: File too large" "$T/e.err")" -eq 1 ]; then ok
else bad "--sweep -o SWEEP.h5 past the file size limit: exit $st, $(grep -v assertion "$T/e.err" | head -n 1)"; fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
