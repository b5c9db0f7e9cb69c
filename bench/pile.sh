#!/bin/sh
# pile.sh - a pile of balls settling in a 2-D box under gravity, in Box2D and
# in csfvm. For each N of PILE_N: gen_pile.sh N 0.5 0.3 3 0.01 (N balls of
# 1 kg, radius 0.05 m, restitution 0.5, mu_s 0.3, mu_k 0.24, dropped from a
# lattice 0.12 m apart into a box W = ceil(sqrt(N)) balls wide, for 3 s);
# box2d_pile.cpp runs the same scene in Box2D 2.4 at 240 Hz (8/3 iterations)
# and prints its stepping time, the worst overlap at the end and the largest
# speed at the end; csfvm --stats runs the compiled scene under
# timeout -s KILL $PILE_LIMIT: its exit status, the last t it wrote, events,
# right-hand side evaluations, its seconds (--stats; empty if killed), the
# worst overlap of its last row (pairs of balls and ball and wall, as
# box2d_pile.cpp), and, when it failed, the first line of its stderr that
# begins with error (else its first line; commas and bars become ; and /).
# Writes $OUT/pile.csv and $OUT/pile.txt, and the pile section of $README.
#   BUILD (../build), BIN (bin), CXX (g++), OUT (results), README (README.md;
#   empty: leave it alone), PILE_N ("16 64 256 1024"), PILE_LIMIT (120)
# Needs libbox2d-dev (make deps-box2d at the top).
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
BIN=${BIN:-bin}
CXX=${CXX:-g++}
OUT=${OUT:-results}
README=${README-README.md}
PILE_N=${PILE_N:-16 64 256 1024}
PILE_LIMIT=${PILE_LIMIT:-120}
CR=0.5 MU=0.3 TILL=3 BY=0.01
TMP=$OUT/pile.tmp CSV=$OUT/pile.csv
mkdir -p "$TMP" "$BIN"

$CXX -std=c++17 -Wall -Wextra -O2 box2d_pile.cpp -o "$BIN/box2d_pile" -lbox2d

echo "n,box2d_seconds,box2d_overlap_m,box2d_speed_m_s,csf_exit,csf_t,csf_events,csf_evaluations,csf_seconds,csf_overlap_m,csf_message" > "$CSV"
for n in $PILE_N; do
	b2=$("$BIN/box2d_pile" "$n" $CR $MU $TILL)
	sh ./gen_pile.sh "$n" $CR $MU $TILL $BY "$TMP/pile.csf"
	"$BUILD/csfc" "$TMP/pile.csf" -o "$TMP/pile.csfb"
	st=0
	timeout -s KILL "$PILE_LIMIT" "$BUILD/csfvm" --stats "$TMP/pile.csfb" >"$TMP/run.csv" 2>"$TMP/run.err" || st=$?
	stats=$(awk -F'[ ,;()]+' '/^stats: method/ { for (i = 1; i <= NF; i++) { if ($(i + 1) == "events") e = $i
		if ($(i + 1) == "right-hand") f = $i; if ($i ~ /^[0-9.]+$/) last = $i }
		print e "," f "," last }' "$TMP/run.err")
	[ -n "$stats" ] || stats=",,"
	# the last complete row: t, then x, y, z of each ball
	last=$(awk -F, -v n="$n" 'NR > 1 && NF == 1 + 3 * n { row = $0 } END { print row }' "$TMP/run.csv")
	t=${last%%,*}
	ov=$(echo "$last" | awk -F, -v n="$n" -v w="$(awk -v n="$n" 'BEGIN { w = int(sqrt(n)); if (w * w < n) w++; print w }')" '
		function max(a, b) { return a > b ? a : b }
		NF > 1 { r = 0.05; x1 = w * 0.12 + 0.1; m = 0
			for (i = 0; i < n; i++) { x[i] = $(2 + 3 * i); z[i] = $(4 + 3 * i)
				m = max(m, r - z[i]); m = max(m, r - x[i]); m = max(m, r - (x1 - x[i])) }
			for (i = 0; i < n; i++) for (j = i + 1; j < n; j++)
				m = max(m, 2 * r - sqrt((x[i] - x[j]) ^ 2 + (z[i] - z[j]) ^ 2))
			printf "%.3g", m }')
	msg=
	if [ "$st" -ne 0 ]; then
		msg=$(grep '^error' "$TMP/run.err" | head -n 1 | tr -d '\r' | tr ',|' ';/')
		[ -n "$msg" ] || msg=$(grep -v '^stats:' "$TMP/run.err" | head -n 1 | tr -d '\r' | tr ',|' ';/')
		[ -n "$msg" ] || msg="killed after $PILE_LIMIT s (no message)"
	fi
	echo "$b2,$st,$t,$stats,$ov,$msg" >> "$CSV"
	echo "N=$n: box2d $b2; csfvm exit $st, t $t, $stats, overlap $ov${msg:+, $msg}" >&2
done

awk -F, -v till=$TILL 'NR > 1 { rows++; n[rows] = $1; line = sprintf("| %d | %.3f s, %s m, %s m/s | %d | %s | %s | %s | %s | %s |", \
		$1, $2, $3, $4, $5, $6 == "" ? "-" : $6, $7 == "" ? "-" : $7, $9 == "" ? "-" : sprintf("%.3f s", $9), $10 == "" ? "-" : $10 " m", $11 == "" ? "-" : $11)
		l[rows] = line; if ($5 == 0 && $6 + 0 >= till) ok = ok (ok == "" ? "" : ", ") $1; else bad = bad (bad == "" ? "" : ", ") $1
		if ($3 + 0 > b2o) b2o = $3 + 0; if ($4 + 0 > b2v) b2v = $4 + 0; if ($11 ~ /masses less different/) hint = 1 }
	END {
		print "| N | Box2D: time, worst overlap, residual speed | CSF exit | CSF t reached (s) | CSF events | CSF time | CSF worst overlap at t reached | CSF message |"
		print "|---|---|---|---|---|---|---|---|"
		for (i = 1; i <= rows; i++) print l[i]
		print ""
		printf "Box2D reached %s s at every N, with overlaps up to %g m at the end (its linear slop is 0.005 m) and %s. csfvm %s.%s\n", \
			till, b2o, b2v == 0 ? "every ball at rest (asleep)" : sprintf("speeds up to %g m/s", b2v), bad == "" ? "reached " till " s with exit 0 at every N" : (ok == "" ? "did not reach " till " s with exit 0 at any N" : "reached " till " s with exit 0 at N = " ok " and did not at N = " bad), \
			hint ? " Every ball has the same mass, so the hint of the error message (light bodies between heavy ones) does not fit these piles." : ""
	}' "$CSV" > "$OUT/pile.txt"
cat "$OUT/pile.txt"
sh ./readme_section.sh "$README" pile "$OUT/pile.txt"
rm -rf "$TMP"
