#!/bin/sh
# output.sh - what a run's output costs (issue 30's targets):
#  - the cone of influence: OUT_N (20000) independent projectiles with drag watching one
#    (tests/cone/gen_projectiles.sh, 1001 rows) beside the same scene with that projectile
#    alone: compile and run time, and the ratio (target: within 2x);
#  - CSV at scale: OUT_ALL (2000) projectiles watching every position and velocity (1001 rows,
#    12 000 columns): wall time, megabytes written, MB/s (targets: 200 MB/s or more, the run
#    under 0.6 s);
#  - OUT_MP (10000) mass points watching pos (bench/gen_scene.sh's lattice, 1001 rows, 3e7
#    values) to CSV (target: under 6 s) and, where csfvm writes HDF5 (-o FILE.h5), to HDF5
#    (target: under 3 s).
# The runs' output goes to a file on this machine's disk (results/output.tmp). The medians of
# OUT_REPS (7) runs. Writes $OUT/output.csv, $OUT/output.txt and the output section of $README.
#   BUILD (../build), OUT (results), README (README.md; empty: leave it alone)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
OUT=${OUT:-results}
README=${README-README.md}
OUT_N=${OUT_N:-20000}
OUT_ALL=${OUT_ALL:-2000}
OUT_MP=${OUT_MP:-10000}
OUT_REPS=${OUT_REPS:-7}
TMP=$OUT/output.tmp CSV=$OUT/output.csv TXT=$OUT/output.txt
mkdir -p "$TMP"
export CSF_STDLIB="${CSF_STDLIB:-$(cd .. && pwd)/stdlib}"
GEN=../tests/cone/gen_projectiles.sh
[ -x bin/timeit ] || ${CC:-cc} -O2 -o bin/timeit timeit.c

# median WALL of OUT_REPS runs of COMMAND... (stdout to $TMP/out)
median() {
	i=0
	while [ $i -lt "$OUT_REPS" ]; do
		bin/timeit "$TMP/out" "$@" | awk '{ print $1 }'
		i=$((i + 1))
	done | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
echo "case,what,value" > "$CSV"
row() { echo "$1,$2,$3" >> "$CSV"; }

# 1. the cone: N projectiles watching p0, and p0 alone
sh $GEN "$OUT_N" "p0.pos" "till 1000 s by 1 s" > "$TMP/many.csf"
sh $GEN 1 "p0.pos" "till 1000 s by 1 s" > "$TMP/one.csf"
cmany=$(median "$BUILD/csfc" -w "$TMP/many.csf" -o "$TMP/many.csfb")
cone=$(median "$BUILD/csfc" -w "$TMP/one.csf" -o "$TMP/one.csfb")
rmany=$(median "$BUILD/csfvm" "$TMP/many.csfb")
rone=$(median "$BUILD/csfvm" "$TMP/one.csfb")
"$BUILD/csfvm" "$TMP/many.csfb" > "$TMP/a.csv"
"$BUILD/csfvm" "$TMP/one.csfb" > "$TMP/b.csv"
same=$(cmp -s "$TMP/a.csv" "$TMP/b.csv" && echo "byte for byte the same" || echo "DIFFERENT")
row cone compile_many "$cmany"; row cone compile_one "$cone"; row cone run_many "$rmany"; row cone run_one "$rone"

# 2. CSV at scale
sh $GEN "$OUT_ALL" "pos, v" "till 1000 s by 1 s" > "$TMP/all.csf"
"$BUILD/csfc" -w "$TMP/all.csf" -o "$TMP/all.csfb"
rall=$(median "$BUILD/csfvm" "$TMP/all.csfb")
"$BUILD/csfvm" "$TMP/all.csfb" > "$TMP/all.csv"
mball=$(wc -c < "$TMP/all.csv" | awk '{ printf "%.1f", $1 / 1e6 }')
values=$(awk -F, 'NR == 2 { c = NF } END { print (NR - 1) * c }' "$TMP/all.csv")
rm -f "$TMP/all.csv"
row csv run "$rall"; row csv megabytes "$mball"; row csv values "$values"

# 3. 10 000 mass points, pos watched: CSV, and HDF5 where csfvm writes it
sh ./gen_scene.sh "$OUT_MP" | sed 's/^inc t .*/inc t till 1 by 0.001 watch pos/' > "$TMP/mp.csf"
"$BUILD/csfc" -w "$TMP/mp.csf" -o "$TMP/mp.csfb"
rmp=$(median "$BUILD/csfvm" "$TMP/mp.csfb")
"$BUILD/csfvm" "$TMP/mp.csfb" > "$TMP/mp.csv"
mbmp=$(wc -c < "$TMP/mp.csv" | awk '{ printf "%.1f", $1 / 1e6 }')
rm -f "$TMP/mp.csv" "$TMP/out"
row mp csv "$rmp"; row mp megabytes "$mbmp"
h5=""
if "$BUILD/csfvm" -o "$TMP/probe.h5" "$TMP/one.csfb" > /dev/null 2>&1; then
	h5=$(median "$BUILD/csfvm" -o "$TMP/mp.h5" "$TMP/mp.csfb")
	mbh5=$(wc -c < "$TMP/mp.h5" | awk '{ printf "%.1f", $1 / 1e6 }')
	row mp h5 "$h5"; row mp h5_megabytes "$mbh5"
fi
rm -f "$TMP"/*.h5

{
	echo "| case | measured | target |"
	echo "|---|---|---|"
	awk -v a="$rmany" -v b="$rone" -v ca="$cmany" -v cb="$cone" -v n="$OUT_N" -v same="$same" 'BEGIN {
		printf "| %d projectiles watching one, 1001 rows | run %.3f s against %.3f s for that projectile alone: %.2fx (compile %.2f s against %.3f s); its rows %s | within 2x |\n",
			n, a, b, a / b, ca, cb, same }'
	awk -v t="$rall" -v mb="$mball" -v v="$values" -v n="$OUT_ALL" 'BEGIN {
		printf "| %d projectiles watching all, 1001 rows | %.2f s for %s MB of CSV (%d values): %.0f MB/s, %.0f ns a value | 200 MB/s or more, the run under 0.6 s |\n",
			n, t, mb, v, mb / t, t / v * 1e9 }'
	awk -v t="$rmp" -v mb="$mbmp" -v n="$OUT_MP" 'BEGIN {
		printf "| %d mass points watching pos to CSV, 1001 rows | %.2f s (%s MB) | under 6 s |\n", n, t, mb }'
	if [ -n "$h5" ]; then
		awk -v t="$h5" -v mb="$mbh5" -v n="$OUT_MP" 'BEGIN {
			printf "| %d mass points watching pos to HDF5 | %.2f s (%s MB) | under 3 s |\n", n, t, mb }'
	else
		echo "| $OUT_MP mass points watching pos to HDF5 | (this csfvm writes no HDF5) | under 3 s |"
	fi
	echo
	echo "Medians of $OUT_REPS runs, output to a file on local disk; $(nproc) CPUs, $(date -u +%Y-%m-%d)."
} > "$TXT"
cat "$TXT"
sh ./readme_section.sh "$README" output "$TXT"
