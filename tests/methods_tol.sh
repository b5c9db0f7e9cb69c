#!/bin/sh
# tests/methods_tol.sh - every method of csfvm (as its "unknown method"
# message lists them) at every tolerance 1e-3 ... 1e-12 on the harmonic
# oscillator of tests/methods_tol.csf. Each run must exit 0 within its
# timeout, write all 1001 rows at t = k * 10 ms, and stay within
#
#   err <= 3.3 N tol A
#
# of the exact solution, where err is the worst, over the rows, of
# |x - A cos(8t)|, |v/8 + A sin(8t)| and the y and z components (which stay
# 0), N the accepted steps (--stats), A = 0.1 m. Why: GSL accepts a step when
# its error estimate is at most 1.1 tol (|y_i| + scale_i) in every component;
# the scales are A for pos (its initial magnitude) and 1 m/s for v, so a
# step errs by at most 2.2 tol A in x and 1.1 tol (8A + 1 m/s)/8 = 2.475 tol A
# in v/8, together sqrt(2.2^2 + 2.475^2) = 3.3 tol A in the norm
# |(x, v/8)|, which the oscillator's flow (a rotation of (x, v/8)) keeps;
# the global error is then at most the sum of the N local ones. Measured:
# at most 1.4 N tol A (msbdf), and at tight tolerances far below (rk8pd
# 7e-16 against a bound of 3.3e-10 at 1e-12). The check itself is shown to
# fail on a wrong answer: rk8pd's output against w = 8 (1 + 1e-6).
#
# verlet takes fixed steps h derived from tol (csf_ode_fixed_step), with no
# error estimate; its error, A w^3 T h^2 / 24, is within the same bound with
# room to spare. rk1imp (implicit Euler, order 1) needs steps of about
# sqrt(tol) / 8 s: 2e5 steps at 1e-7, 6e6 (11 s) at 1e-10, 6e7 at 1e-12; it
# is run down to 1e-7 only, to keep this test fast.
#
# Run from the top of the tree; CSF_BUILD names the build directory (default
# build). One line per run; exits 1 after "FAIL: ..." lines if any failed.
set -u
B=$(cd "${CSF_BUILD:-build}" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail=0
bad() { fail=1; echo "FAIL: $*"; }

# awk -F, -v method=M -v tol=TOL -v steps=N -v w=W "$check" out.csv: prints the run's line;
# exits 1 on unexpected columns, a missing or misplaced row, or an error above the bound
# shellcheck disable=SC2016 # an awk program
check='
function abs(x) { return x < 0 ? -x : x }
function worse(d) { if (abs(d) > err) err = abs(d) }
BEGIN { A = 0.1; by = 0.01; rows = 1001; bound = 3.3 * steps * tol * A }
NR == 1 { if ($2 !~ /^bob\.pos\.x/ || $5 !~ /^bob\.v\.x/) { print "columns: " $0; bad = 1; exit 1 } next }
{
	n++; t = $1
	if (abs(t - (n - 1) * by) > 1e-12) { printf "row %d: t = %s, expected %.17g\n", n, t, (n - 1) * by; bad = 1; exit 1 }
	worse($2 - A * cos(w * t)); worse($5 / w + A * sin(w * t))
	worse($3); worse($4); worse($6); worse($7)
}
END {
	if (bad) exit 1
	if (n != rows) { printf "%d rows, expected %d\n", n, rows; exit 1 }
	printf "%-8s %-6s %8d steps  err %.2e  bound %.2e\n", method, tol, steps, err, bound
	exit !(err <= bound)
}'

if ! "$B/csfc" tests/methods_tol.csf -o "$T/o.csfb" 2>"$T/err"; then
	echo "FAIL: tests/methods_tol.csf does not compile: $(head -n 1 "$T/err")"
	exit 1
fi
methods=$("$B/csfvm" --method '' "$T/o.csfb" 2>&1 | sed -n 's/.*(one of: \(.*\))$/\1/p')
[ -n "$methods" ] || bad "no method list from csfvm --method ''"
for m in $methods; do
	for e in 3 4 5 6 7 8 9 10 11 12; do
		[ "$m" = rk1imp ] && [ "$e" -gt 7 ] && continue
		tol=1e-$e
		timeout 10 "$B/csfvm" --stats --method "$m" --tol "$tol" "$T/o.csfb" >"$T/out.csv" 2>"$T/err"
		st=$?
		if [ $st -ne 0 ]; then
			bad "$m --tol $tol: exit status $st: $(head -n 1 "$T/err")"
			continue
		fi
		# accepted steps: "stats: method M, S steps (R rejected), ..."
		steps=$(sed -n 's/^stats: .*, \([0-9]*\) steps (\([0-9]*\) rejected).*/\1 - \2/p' "$T/err")
		steps=$((${steps:-0}))
		if awk -F, -v method="$m" -v tol="$tol" -v steps="$steps" -v w=8 "$check" "$T/out.csv" >"$T/chk" 2>&1; then
			cat "$T/chk"
		else
			bad "$m --tol $tol: $(cat "$T/chk")"
		fi
	done
done

# the check fails on a wrong answer: rk8pd's run at 1e-12 against w off by 1e-6
# (a phase error of 8e-5 rad at t = 10 s, 8e-6 m; the bound is 3.3e-10 m)
"$B/csfvm" --method rk8pd --tol 1e-12 "$T/o.csfb" >"$T/out.csv" 2>"$T/err" || bad "rk8pd: $(head -n 1 "$T/err")"
if awk -F, -v method=wrong -v tol=1e-12 -v steps=1000 -v w=8.000008 "$check" "$T/out.csv" >"$T/chk" 2>&1; then
	bad "the check accepts a wrong answer: $(cat "$T/chk")"
fi
exit $fail
