#!/bin/sh
# tests/piles/jam.sh CSFC CSFVM DIR ["X CR" ...] - a ball dropped onto two jammed between
# the walls of a box (issue 28): the lower balls (2 kg, radius 0.1 m) stand
# on the floor at x = 0.1 and 0.3 m, each touching the other and its wall
# (the box 0.4 m wide); the top ball (0.5 kg, radius 0.08 m) falls from
# (X, 0, 0.45) m onto them. Everything rough (mu_s 0.4, mu_k 0.3) with
# restitution CR. Twelve cases: X in 0.2 0.205 0.21 0.22 0.24 0.26, CR in 0
# and 0.3; each runs 2 s (rows every 0.05 s, or every BY s where a case
# names it) under the default method.
#
# The checks, from physics alone: exit 0; no overlap beyond 1e-9 m; the
# energy (kinetic and potential) never grows between rows beyond 1e-9 of
# it (impacts and friction only take energy away); at the end (restitution
# 0.3 ends its bounces within 0.7 s: every pair's bounces shrink by 0.3)
# every ball at rest (speed below 1e-9 m/s) with its contact forces
# FN + Ff balancing its weight to 1e-9 of the whole weight.
#
# The jam is statically indeterminate (the lower balls' squeeze between the
# walls is not determined, and with it their sliding friction). All 12
# pass, and make check runs them (tests/run.sh, jam_now). Before a step's
# crossings were located in the order of their estimates (csf(5), events),
# X = 0.2 with restitution 0.3 stopped at t = 0.405 s: an impact within
# the jam (5 contacts, the row's nearly redundant) found no impulses that
# push and leave no pair closing, directly or by 1000 sweeps; on another
# path it does not come. Before slips stopped by their
# cluster's impulses (csf(5), Rest), it ended with the top ball creeping up
# at 9e-9 m/s, its contacts with the lower balls opening at 7e-9 m/s while
# they stayed in contact (above the 1e-9 m/s the check allows at rest); and
# since then X = 0.22 with restitution 0.3 needs auto's return to dop853
# where bsimp's step collapses (csfvm(1)). Before the forces were chosen to
# push only (csf(5), "Normal forces only push"), 7 of the 12 passed: a
# sliding pair whose normal force came out negative was solved again with
# its friction turned, which then pushed along its slip (a lower ball rose,
# gaining energy); and X = 0.22 with restitution 0.3 needed the last
# resort there, the pairs that press chosen without the sliding pairs'
# friction, which locks them (a lower ball wedged by friction 9.4e-8 m above
# the floor at the top of a bounce).
# With events a step is at most the rows' spacing long (csfvm(1)), so
# another spacing takes another path, and the jam at restitution 0.3 fails
# on some of them (JAM_SPACINGS, below; make check-piles runs them: X in
# 0.2 0.21 0.22 0.24 0.26, rows every 0.2, 0.7, 1 and 2 ms). At a6bccf2,
# 14 of those 20 failed. Eight gained energy (2.7e-9 to 1.9e-7 of it
# between two rows: a lower ball wedged 2.6e-7 m above the floor, rising,
# was held up by the sliding friction of contacts whose least-norm forces
# pulled, -32.7 N; settle's passes went round between lift-off and contact
# until their bound, and the step began with the pull, whose guard,
# negative from the start, no event reports); three stopped as X = 0.2
# did; three did not finish in 60 s. At 51e9dac (a pair that pulls again
# after lifting off at an instant stops the slides beside it, csf(5),
# "Normal forces only push"; a crossing after a false alarm of the
# interpolant in the same step is located, where the top ball went 1.1e-5
# m into a lower one with no impact), 6 failed: four impulse errors, and
# two gained 1.3e-9 and 1.8e-9 of the energy, the work of a squeeze of
# 1.6e7 N on a ball stuck in the wedge through normal velocities of 1e-12
# m/s. With crossings located earliest first 6 failed, each stopping with
# the impulse error above (the impulses of the row jammed between the
# walls, its contacts redundant to 1e-7 rad, left a pair closing at
# 3.2e-12 m/s, above the 2.9e-12 that counts, and their active sets went
# round); with impulses by Goldfarb and Idnani's dual method, one: X = 0.22
# every 1 ms gained 3.4e-7 of the energy, a lower ball 3e-7 m up in the
# wedge rising at 5.2e-7 m/s on the friction of least-norm forces that
# pulled (-32.7 N). It passes since a stopped slide is held by a stopping
# neighbour's impulses as a sticking pair is (csf(5), Rest); that alone
# left X = 0.22 every 0.2 ms gaining 1.1e-9, which holding sticking pairs
# at a slip of zero (csf(5), "Contacts held") took away. All 20 pass, and
# make check runs them.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
pass=0 fail=0
jam() { # X CR [BY]
	by=${3:-0.05} f=$T/jam_$1_$2_$by
	{
		echo "using mechanics/mass_point"
		printf 'object lo1: mass_point\nobject lo1: m = 2 kg\nobject lo1: radius = 0.1 m\nobject lo1: pos = (0.1, 0, 0.1) m\n'
		printf 'object lo2: mass_point\nobject lo2: m = 2 kg\nobject lo2: radius = 0.1 m\nobject lo2: pos = (0.3, 0, 0.1) m\n'
		printf 'object top: mass_point\nobject top: m = 0.5 kg\nobject top: radius = 0.08 m\nobject top: pos = (%s, 0, 0.45) m\n' "$1"
		printf 'object floor: plane\nobject wl: plane\nobject wl: normal = (1, 0, 0)\n'
		printf 'object wr: plane\nobject wr: point = (0.4, 0, 0) m\nobject wr: normal = (-1, 0, 0)\n'
		for o in lo1 lo2 top floor wl wr; do
			printf 'object %s: mu_s = 0.4\nobject %s: mu_k = 0.3\nobject %s: cr = %s\n' "$o" "$o" "$o" "$2"
		done
		echo "using mechanics/rules"
		echo "rule F: W = g.mul(m)"
		echo "inc t till 2 s by $by s watch pos, v, FN, Ff"
	} >"$f.csf"
	label="jam X=$1 cr=$2 by=$by"
	if ! timeout -k 10 60 "$CSFC" "$f.csf" -o "$f.csfb" 2>"$f.err"; then
		fail=$((fail + 1)); echo "FAIL: $label: csfc: $(head -n 1 "$f.err")"; return
	fi
	timeout -k 10 60 "$CSFVM" "$f.csfb" >"$f.csv" 2>"$f.err"
	st=$?
	if [ $st -ne 0 ]; then
		fail=$((fail + 1))
		echo "FAIL: $label: csfvm exit $st after $(($(wc -l <"$f.csv") - 1)) rows: $(grep -v '^warning' "$f.err" | head -n 1 | cut -c1-160)"
		return
	fi
	if awk -F, -v name="$label" '
	function dist(i, j) { return sqrt((x[i] - x[j]) ^ 2 + (z[i] - z[j]) ^ 2) }
	NR == 1 { for (k = 1; k <= NF; k++) col[$k] = k; next }
	{
		g = 9.80665; m[1] = 2; m[2] = 2; m[3] = 0.5; r[1] = 0.1; r[2] = 0.1; r[3] = 0.08
		split("lo1 lo2 top", nm, " ")
		e = 0
		for (i = 1; i <= 3; i++) {
			x[i] = $col[nm[i] ".pos.x [m]"]; z[i] = $col[nm[i] ".pos.z [m]"]
			vx = $col[nm[i] ".v.x [m/s]"]; vz = $col[nm[i] ".v.z [m/s]"]
			v[i] = sqrt(vx * vx + vz * vz)
			e += 0.5 * m[i] * (vx * vx + vz * vz) + m[i] * g * z[i]
			fz[i] = $col[nm[i] ".FN.z [N]"] + $col[nm[i] ".Ff.z [N]"]
			fx[i] = $col[nm[i] ".FN.x [N]"] + $col[nm[i] ".Ff.x [N]"]
			if (r[i] - z[i] > 1e-9 || r[i] - x[i] > 1e-9 || r[i] - (0.4 - x[i]) > 1e-9) {
				printf "%s: t = %s: %s overlaps a wall or the floor\n", name, $1, nm[i]; bad = 1; exit 1
			}
		}
		for (i = 1; i <= 3; i++)
			for (j = i + 1; j <= 3; j++)
				if (r[i] + r[j] - dist(i, j) > 1e-9) {
					printf "%s: t = %s: %s and %s overlap by %.3g m\n", name, $1, nm[i], nm[j], r[i] + r[j] - dist(i, j); bad = 1; exit 1
				}
		if (NR > 2 && e - e0 > 1e-9 * e0) {
			printf "%s: t = %s: the energy grows from %.17g J to %.17g J (%.2g of it)\n", name, $1, e0, e, (e - e0) / e0; bad = 1; exit 1
		}
		e0 = e
	}
	END {
		if (bad) exit 1
		for (i = 1; i <= 3; i++) {
			if (v[i] > 1e-9) { printf "%s: at the end %s moves at %.3g m/s\n", name, nm[i], v[i]; exit 1 }
			if (fz[i] - m[i] * g > 1e-9 * 4.5 * g || fz[i] - m[i] * g < -1e-9 * 4.5 * g || fx[i] > 1e-9 * 4.5 * g || fx[i] < -1e-9 * 4.5 * g) {
				printf "%s: at the end the forces on %s do not balance its weight: (%.17g, %.17g) N\n", name, nm[i], fx[i], fz[i] - m[i] * g; exit 1
			}
		}
	}' "$f.csv" >"$f.chk" 2>&1; then
		pass=$((pass + 1))
	else
		fail=$((fail + 1)); echo "FAIL: $(head -n 1 "$f.chk")"
	fi
}
if [ $# -gt 3 ]; then # the cases named, each "X CR" or "X CR BY"
	shift 3
	for c in "$@"; do jam $c; done
else
	for x in 0.2 0.205 0.21 0.22 0.24 0.26; do
		for cr in 0 0.3; do jam "$x" "$cr"; done
	done
	for by in $JAM_SPACINGS; do
		for x in 0.2 0.21 0.22 0.24 0.26; do jam "$x" 0.3 "$by"; done
	done
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
