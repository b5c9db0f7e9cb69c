#!/bin/sh
# constraints.sh - the cost of constraints (rules with attribute C): chains of
# N rods (tests/constraints/gen_chain.sh: N - 1 beads of 0.1 kg between two
# anchors, damped, from a V) for N of CON_N, each beside the same chain with
# a stiff spring (k = CON_K N/m) in place of every rod, at equal evaluations
# (--method rk4 --fixed --step CON_STEP for CON_TILL s: the same count of
# right-hand side evaluations for both); then both chains of 20 links
# settling for 60 s under the default method, against the discrete
# catenary (tests/constraints/catenary.awk): evaluations and the worst
# joint's distance from it; and a cloth of CON_CLOTH x CON_CLOTH beads joined
# by rods to their neighbours (loops of rods), hung by two corners.
# Reports time per evaluation and its growth with N, the ratio rods/springs,
# and the ratio of evaluations at the accuracy the springs reach.
# Writes $OUT/constraints.csv and $OUT/constraints.txt, and the constraints
# section of $README.
#   BUILD (../build), OUT (results), README (README.md; empty: leave it alone),
#   CON_N ("100 1000 10000"), CON_K (1e6), CON_TILL (0.05), CON_STEP (1e-4), CON_CLOTH (30)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
OUT=${OUT:-results}
README=${README-README.md}
CON_N=${CON_N:-100 1000 10000}
CON_K=${CON_K:-1e6}
CON_TILL=${CON_TILL:-0.05}
CON_STEP=${CON_STEP:-1e-4}
CON_CLOTH=${CON_CLOTH:-30}
TMP=$OUT/constraints.tmp CSV=$OUT/constraints.csv TXT=$OUT/constraints.txt
mkdir -p "$TMP"
GEN=../tests/constraints/gen_chain.sh
export CSF_STDLIB="${CSF_STDLIB:-$(cd .. && pwd)/stdlib}"

# springs in place of the rods of a chain from gen_chain.sh: the same scene, each rod a Hooke
# spring, a force rule for each end that is a bead (Sl: its link to the left, Sr: to the right)
springs() {
	awk -v k="$CON_K" '
	function spring(a, b, name) {
		printf "rule F for %s, %s: %s = (pos$1 - pos).mul(k * ((pos$1 - pos).mag - L) / (pos$1 - pos).mag)\n", a, b, name
	}
	/^global L = / { print "global k = " k " N/m" }
	/^rule C for / { split($0, w, /[ ,:]+/); a = w[4]; b = w[5]
		if (b == "left") spring(a, b, "Sl")
		else if (b == "right") spring(a, b, "Sr")
		else { spring(a, b, "Sl"); spring(b, a, "Sr") }
		next }
	{ print }' "$1"
}
# stats NAME: evaluations and seconds from csfvm --stats (stderr in $TMP/NAME.err)
stats() { awk -F'[ ,;()]+' '/^stats: method/ { for (i = 1; i <= NF; i++) { if ($(i + 1) == "right-hand") f = $i
	if ($i ~ /^[0-9.]+$/) last = $i } print f "," last }' "$TMP/$1.err"; }
run() { # run NAME SCENE OPTIONS...
	rn=$1 rf=$2
	shift 2
	"$BUILD/csfc" "$rf" -o "$TMP/$rn.csfb" 2>"$TMP/$rn.cerr" && "$BUILD/csfvm" --stats "$@" "$TMP/$rn.csfb" >"$TMP/$rn.csv" 2>"$TMP/$rn.err" || true
}

echo "scene,n,evaluations,seconds,us_per_evaluation" >"$CSV"
for n in $CON_N; do
	sh "$GEN" "$n" "$(awk -v n="$n" 'BEGIN { print n * 0.15 }')" 0.2 0.2 "$CON_TILL" "$CON_TILL" >"$TMP/rods$n.csf"
	springs "$TMP/rods$n.csf" >"$TMP/springs$n.csf"
	for s in rods springs; do
		run "$s$n" "$TMP/$s$n.csf" --method rk4 --fixed --step "$CON_STEP"
		echo "$s,$n,$(stats "$s$n")" | awk -F, '{ printf "%s,%s,%s,%s,%.3f\n", $1, $2, $3, $4, ($3 > 0) ? 1e6 * $4 / $3 : 0 }' >>"$CSV"
	done
done
# the same accuracy: the chain of 20 settling into the catenary
sh "$GEN" 20 3 0.2 0.2 60 1 >"$TMP/rods20.csf"
springs "$TMP/rods20.csf" >"$TMP/springs20.csf"
for s in rods springs; do
	run "${s}20" "$TMP/${s}20.csf"
	e=$(awk -F, -v n=20 -v span=3 -v L=0.2 -v m=0.1 -v tol=1 -v springs=$([ $s = springs ] && echo 1 || echo 0) \
		-f ../tests/constraints/catenary.awk "$TMP/${s}20.csv" 2>&1 |
		sed -n 's/.*worst joint \([0-9.e+-]*\) m.*/\1/p')
	echo "${s}_catenary,20,$(stats "${s}20"),$e" >>"$CSV"
done
# a cloth of rods, its two top corners held by rails (three constraints each)
awk -v n="$CON_CLOTH" 'BEGIN {
	print "using mechanics/mass_point"
	for (i = 0; i < n; i++) for (j = 0; j < n; j++)
		printf "object c%d_%d: mass_point\nobject c%d_%d: m = 0.01 kg\nobject c%d_%d: pos = (%.17g, %.17g, 0) m\n", i, j, i, j, i, j, j * 0.1, i * 0.1
	print "using mechanics/rules"
	print "rule F: W = g.mul(m)"
	for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
		if (j + 1 < n) printf "rule C for c%d_%d, c%d_%d: (pos - pos$1).mag = 0.1 m\n", i, j + 1, i, j
		if (i + 1 < n) printf "rule C for c%d_%d, c%d_%d: (pos - pos$1).mag = 0.1 m\n", i + 1, j, i, j
	}
	for (k = 0; k < 2; k++) {
		c = k ? n - 1 : 0
		printf "rule C for c0_%d: pos.x = %.17g m\nrule C for c0_%d: pos.y = 0 m\nrule C for c0_%d: pos.z = 0 m\n", c, c * 0.1, c, c
	}
	printf "inc t till %s s by %s s watch c%d_%d.pos\n", 0.01, 0.01, n - 1, n - 1
}' >"$TMP/cloth.csf"
run cloth "$TMP/cloth.csf" --method rk4 --fixed --step "$CON_STEP"
echo "cloth,$((CON_CLOTH * CON_CLOTH)),$(stats cloth)" | awk -F, '{ printf "%s,%s,%s,%s,%.3f\n", $1, $2, $3, $4, ($3 > 0) ? 1e6 * $4 / $3 : 0 }' >>"$CSV"

awk -F, -v k="$CON_K" -v step="$CON_STEP" -v till="$CON_TILL" -v cloth="$CON_CLOTH" '
	NR == 1 { next }
	$1 == "rods" || $1 == "springs" { us[$1, $2] = $5; if ($1 == "rods") ns[++nn] = $2 }
	$1 ~ /_catenary$/ { sub(/_catenary$/, "", $1); ev[$1] = $3; err[$1] = $5; secs[$1] = $4 }
	$1 == "cloth" { cus = $5; cn = $2 }
	END {
		print "| chain of N rods | rods: us per evaluation | growth from the N before | springs (k = " k " N/m): us per evaluation | rods / springs |"
		print "|---|---|---|---|---|"
		for (i = 1; i <= nn; i++) {
			n = ns[i]
			printf "| %d | %.2f | %s | %.2f | %.2f |\n", n, us["rods", n], (i > 1) ? sprintf("%.2f for %.0fx the links", us["rods", n] / us["rods", ns[i - 1]], n / ns[i - 1]) : "-", us["springs", n], us["rods", n] / us["springs", n]
		}
		printf "\nEach for %s s by rk4 with a fixed step of %s s (the same evaluations for both). A cloth of %d x %d beads joined by rods to their neighbours (%d rods, loops), its top corners on rails: %.2f us per evaluation.\n\n", till, step, cloth, cloth, 2 * cloth * (cloth - 1), cus
		closer = (err["rods"] > 0) ? sprintf("%.2g times", err["springs"] / err["rods"]) : "infinitely"
		printf "A chain of 20 settling for 60 s (the default method) into the discrete catenary: rods, %d evaluations, worst joint %s m from the catenary; springs of %s N/m, %d evaluations, worst joint %s m (their stretch). The rods take %.1fx fewer evaluations and are %s closer.\n", ev["rods"], err["rods"], k, ev["springs"], err["springs"], ev["springs"] / ev["rods"], closer
	}' "$CSV" >"$TXT"
cat "$TXT"
sh ./readme_section.sh "$README" constraints "$TXT"
rm -rf "$TMP"
