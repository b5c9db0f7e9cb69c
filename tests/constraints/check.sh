#!/bin/sh
# tests/constraints/check.sh CSFC CSFVM DIR - constraints (rules with attribute C) against
# what must hold exactly:
#  - the double pendulum on rods (double_pendulum.csf) and the same pendulum in angles
#    (double_pendulum_angles.csf): every position to 1e-8 over 3 s; the rods' lengths to 1e-10
#    and the energy within 1e-9 of its start over 100 s;
#  - a square frame with both diagonals (a redundant rod) swinging from a pivot (frame.csf):
#    every rod's length to 1e-10 and the energy to 1e-9 over 20 s;
#  - a chain of 20 rods between two anchors, damped, settles into the discrete catenary
#    (gen_chain.sh, catenary.awk): every link's length to 1e-10 at every row, every joint
#    within 1e-8 m of the catenary's at the end.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
D=$(dirname "$0")
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
run() { # run NAME SCENE [CSFVM OPTIONS]: $T/NAME.csv
	n=$1 f=$2
	shift 2
	if "$CSFC" "$f" -o "$T/$n.csfb" 2>"$T/$n.err" && "$CSFVM" "$@" "$T/$n.csfb" >"$T/$n.csv" 2>>"$T/$n.err"; then return 0; fi
	bad "$n: $(head -n 2 "$T/$n.err" | tr '\n' ' ')"
	return 1
}

# the double pendulum, both ways, to 3 s
if sed 's/till 100 s by 0.5 s/till 3 s by 0.1 s/' "$D/double_pendulum.csf" >"$T/dp3.csf" && run dp3 "$T/dp3.csf" &&
	sed 's/by 0.5 s/by 0.1 s/' "$D/double_pendulum_angles.csf" >"$T/dpa.csf" && run dpa "$T/dpa.csf"; then
	if paste -d, "$T/dp3.csv" "$T/dpa.csv" | awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR == 1 { for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i } next }
		{ w["a.pos.x"] = "p.x1"; w["a.pos.z"] = "p.z1"; w["b.pos.x"] = "p.x2"; w["b.pos.z"] = "p.z2"
		  for (k in w) if (abs($c[k] - $c[w[k]]) > 1e-8) {
			printf "FAIL: double pendulum at t=%s: %s = %.17g on rods, %.17g in angles\n", $1, k, $c[k], $c[w[k]]; exit 1 }
		  n++ }
		END { if (n != 31) { print "FAIL: double pendulum: " n " rows"; exit 1 } }'; then ok; else fail=$((fail + 1)); fi
fi

# energy: E = sum m v^2/2 + m g z, and the rods, at every row
energy() { # energy NAME MASSES(name=kg,...) RODS(a-b=L,...; "pivot" at PX,PZ)
	awk -F, -v masses="$2" -v rods="$3" -v name="$1" 'function abs(x) { return x < 0 ? -x : x }
	BEGIN { nm = split(masses, M, ","); for (i = 1; i <= nm; i++) { split(M[i], q, "="); mass[q[1]] = q[2] }
		nr = split(rods, R, ",") }
	NR == 1 { for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i } next }
	{ E = 0
	  for (b in mass) E += mass[b] * (($c[b ".v.x"] ^ 2 + $c[b ".v.y"] ^ 2 + $c[b ".v.z"] ^ 2) / 2 + 9.80665 * $c[b ".pos.z"])
	  if (NR == 2) { E0 = E; S = 0; for (b in mass) S += mass[b] * 9.80665 * (abs($c[b ".pos.z"]) + 1) }
	  if (abs(E - E0) > 1e-9 * S) { printf "FAIL: %s at t=%s: energy %.17g, at the start %.17g\n", name, $1, E, E0; exit 1 }
	  for (i = 1; i <= nr; i++) {
		split(R[i], q, "="); split(q[1], ab, "-")
		ax = $c[ab[1] ".pos.x"]; ay = $c[ab[1] ".pos.y"]; az = $c[ab[1] ".pos.z"]
		bx = $c[ab[2] ".pos.x"]; by = $c[ab[2] ".pos.y"]; bz = $c[ab[2] ".pos.z"]
		d = sqrt((ax - bx) ^ 2 + (ay - by) ^ 2 + (az - bz) ^ 2)
		if (abs(d - q[2]) > 1e-10 * q[2]) { printf "FAIL: %s at t=%s: rod %s of length %.17g\n", name, $1, q[1], d; exit 1 }
	  } }' "$T/$1.csv"
}
if run dp "$D/double_pendulum.csf" && energy dp "a=1,b=2" "a-pivot=1,b-a=0.7"; then ok; else fail=$((fail + 1)); fi
if run frame "$D/frame.csf" && energy frame "p1=0.25,p2=0.25,p3=0.25,p4=0.25" \
	"p1-pivot=0.5,p1-p2=0.3,p2-p3=0.3,p3-p4=0.3,p4-p1=0.3,p1-p3=0.4242640687119285,p2-p4=0.4242640687119285"; then ok
else fail=$((fail + 1)); fi

# the chain of 20 rods settles into the catenary
sh "$D/gen_chain.sh" 20 3 0.2 0.2 60 1 >"$T/chain.csf"
if run chain "$T/chain.csf" && awk -F, -v n=20 -v span=3 -v L=0.2 -v m=0.1 -v tol=1e-8 -f "$D/catenary.awk" "$T/chain.csv"; then ok
else fail=$((fail + 1)); fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
