#!/bin/sh
# tests/longrun/estimate.sh CSFC CSFVM DIR - --estimate-error and --accuracy
# against exact solutions (exact.py): the harmonic oscillator (osc.csf), a
# Kepler orbit of eccentricity 0.5 (kepler.csf) and a projectile with linear
# drag (projectile.csf).
#  - --estimate-error on each scene with several methods at --tol 1e-7 and
#    1e-9: the estimate within a factor 3 of the true global error (the
#    largest difference from the exact solution over every row and column);
#    where the true error is at rounding's level (below 1e-12), the estimate
#    must be too;
#  - --accuracy 1e-6 with every method: exit 0 and a true error of at most
#    1e-6, or exit 1 saying why it cannot be met;
#  - the per-column lines, --stats's line, and the rows identical to a run
#    without --estimate-error.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
HERE=$(dirname "$0")
PY=/usr/bin/python3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
if ! "$PY" -c 'import numpy' 2>/dev/null; then echo "SKIP: numpy is missing"; echo "0 passed, 0 failed"; exit 0; fi
for s in osc kepler projectile; do
	"$CSFC" "$HERE/$s.csf" -o "$T/$s.csfb" || { echo "FAIL: $s.csf does not compile"; exit 1; }
done
# ratio TRUE EST: within a factor 3, or both at rounding's level
within() { awk -v a="$1" -v b="$2" 'BEGIN { if (b == "none") exit 1; if (a < 1e-12) exit !(b < 1e-11); exit !(b <= 3 * a && a <= 3 * b) }'; }
for s in osc kepler projectile; do
	for m in auto rk8pd rkf45 msadams msbdf rk4imp bsimp; do
		for tol in 1e-7 1e-9; do
			if ! timeout -s KILL 120 "$CSFVM" --method "$m" --tol "$tol" --estimate-error --stats "$T/$s.csfb" >"$T/e.csv" 2>"$T/e.err"; then
				bad "$s --method $m --tol $tol --estimate-error: $(grep -v '^stats' "$T/e.err" | head -n 1)"
				continue
			fi
			r=$("$PY" "$HERE/exact.py" "$s" "$T/e.csv" "$T/e.err")
			if within $r; then ok; else bad "$s --method $m --tol $tol: the true error and the estimate: $r"; fi
		done
	done
	# the rows are those of the run without the estimate; a line per column, and the one of --stats
	"$CSFVM" "$T/$s.csfb" >"$T/plain.csv"
	"$CSFVM" --estimate-error "$T/$s.csfb" >"$T/e.csv" 2>"$T/e.err"
	cols=$(head -n 1 "$T/plain.csv" | tr ',' '\n' | tail -n +2 | wc -l)
	if cmp -s "$T/plain.csv" "$T/e.csv" && [ "$(grep -c '^error estimate: .*: [-+.0-9e]* at t=' "$T/e.err")" -eq "$cols" ] &&
		! grep -q '^stats' "$T/e.err"; then ok
	else bad "$s --estimate-error: other rows, or not one line per column ($cols): $(head -n 2 "$T/e.err")"; fi
	# --accuracy 1e-6 with every method but the implicit ones of order 1 and 2 (rk1imp, rk2imp: a
	# million steps or more, minutes): met (exit 0, the true error at most 1e-6), or exit 1 and why;
	# verlet runs no scene with drag (exit 2, as without --accuracy)
	for m in auto dop853 dopri5 rk8pd rkf45 rkck rk2 rk4 msadams msbdf rk4imp bsimp verlet; do
		timeout -s KILL 100 "$CSFVM" --method "$m" --accuracy 1e-6 --stats "$T/$s.csfb" >"$T/a.csv" 2>"$T/a.err"
		st=$?
		if [ $st -eq 0 ]; then
			r=$("$PY" "$HERE/exact.py" "$s" "$T/a.csv" "$T/a.err")
			if awk -v a="${r% *}" 'BEGIN { exit !(a <= 1e-6) }' && grep -q '^accuracy: 1e-06 met at --' "$T/a.err"; then ok
			else bad "$s --method $m --accuracy 1e-6: exit 0 but the true error and the estimate are $r"; fi
		elif [ $st -eq 1 ] && grep -q '^error: --accuracy 1e-06 cannot be met: the estimate at ' "$T/a.err"; then
			echo "note: $s --method $m: $(grep '^error: --accuracy' "$T/a.err")"
			ok
		elif [ $st -eq 2 ] && [ $m = verlet ] && [ $s = projectile ] && grep -q '^error: verlet needs' "$T/a.err"; then ok
		else bad "$s --method $m --accuracy 1e-6: exit $st: $(grep -v '^stats' "$T/a.err" | head -n 1)"; fi
	done
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
