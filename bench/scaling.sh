#!/bin/sh
# scaling.sh - how csfc and csfvm grow with the number of objects (README.md,
# "Scaling"); run by `make` in bench/ after run.sh. Environment as run.sh:
# BUILD (csfc, csfvm), BIN (nbody, timeit), OUT (results), README.
#
#   gen_scene.sh N, N = 1e3, 1e4, 1e5: csfc seconds and peak memory, bytecode
#     bytes, code words (rhs + out + jac), csfvm start-up (the model with till 0);
#   gen_nbody.sh N, N = 128, 512, 2048: csfc seconds, code words, bytecode
#     bytes, and the time per pair of one right-hand side evaluation of csfvm
#     beside nbody.c (the same arithmetic): (run - start-up) / (evaluations
#     N (N - 1)), evaluations from nbody --stats (both take the same steps);
#   gen_cloth.sh 30 30 (neighbour rules, each one loop): csfc, csfc --emit-c + cc, the lines of
#     generated code, and the time per evaluation of csfvm, of the generated program and of
#     cloth.c (the same operations, hand-written), with the generated program's ratio to cloth.c;
#   an array of ARR_N (1e6) projectiles (tests/arrays/gen_projectiles.sh): csfc's seconds and
#     peak memory as compiled (two members watched, the others left out) and with --keep-all,
#     the bytecode's bytes, csfvm's start-up (--keep-all, till 0), and one evaluation of the
#     right-hand side by the VM beside projectiles.c's loop over the same arrays (medians of
#     ARR_REPS, and whether the derivatives are the same bits);
#   the same array of 1e4 and 1e5 members with their momentum, a sum over them, watched: csfc's
#     seconds and peak memory;
#   a galaxy of GAL_N (1e5) stars read from a data file, softened gravity (gen_galaxy.sh):
#     csfc --emit-c's seconds and peak memory, and one evaluation (N (N - 1) pairs) of the
#     generated code beside galaxy.c's hand-written loop over the same arrays, each timed over
#     the first GAL_ROWS stars and scaled to N (medians of GAL_REPS; whether the same bits).
# Each run once: the sizes are exact, the times are for orders of magnitude.
set -eu
BUILD=${BUILD:-../build}
BIN=${BIN:-bin}
OUT=${OUT:-results}
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
README=${README-README.md}
ARR_N=${ARR_N:-1000000}
ARR_REPS=${ARR_REPS:-11}
GAL_N=${GAL_N:-100000}
GAL_ROWS=${GAL_ROWS:-1000}
GAL_REPS=${GAL_REPS:-3}
CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
TMP=$OUT/scaling.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
say() { printf '%s\n' "$*" >&2; }
# run OUT CMD... : "wall_seconds peak_KiB" of one run
run() { "$BIN/timeit" "$@" | awk '{ print $1, $4 }'; }
words() { "$CSFC" --dump-bytecode "$1" -o "$TMP/w.csfb" | awk '/^section/ { gsub(/[()]/, ""); n += $3 } END { print n }'; }
TAB=$TMP/table.md
{
	echo "| scene | N | csfc s | csfc peak MiB | bytecode bytes | code words | csfvm start-up s |"
	echo "|---|---:|---:|---:|---:|---:|---:|"
} > "$TAB"
for n in 1000 10000 100000; do
	sh ./gen_scene.sh "$n" "$TMP/s$n.csf"
	set -- $(run /dev/null "$CSFC" "$TMP/s$n.csf" -o "$TMP/s$n.csfb")
	cs=$1 mem=$2
	sed 's/^inc t till 1 by/inc t till 0 by/' "$TMP/s$n.csf" > "$TMP/s$n.0.csf"
	"$CSFC" "$TMP/s$n.0.csf" -o "$TMP/s$n.0.csfb"
	set -- $(run /dev/null "$CSFVM" "$TMP/s$n.0.csfb")
	echo "| gen_scene.sh | $n | $cs | $((mem / 1024)) | $(wc -c < "$TMP/s$n.csfb" | tr -d ' ') | $(words "$TMP/s$n.csf") | $1 |" >> "$TAB"
	say "scaling: gen_scene $n: csfc $cs s"
done
{
	echo
	echo "| scene | N | csfc s | code words | bytecode bytes | csfvm ns/pair | nbody.c ns/pair | csfvm / nbody.c |"
	echo "|---|---:|---:|---:|---:|---:|---:|---:|"
} >> "$TAB"
for n in 128 512 2048; do
	till=$(awk -v n="$n" 'BEGIN { print (n >= 2048 ? 0.02 : n >= 512 ? 0.2 : 2) }')
	sh ./gen_nbody.sh "$n" "$till" 0.01 "$TMP/n$n.csf" "$TMP/n$n.ic"
	sh ./gen_nbody.sh "$n" 0 0.01 "$TMP/n$n.0.csf" "$TMP/n$n.0.ic"
	set -- $(run /dev/null "$CSFC" "$TMP/n$n.csf" -o "$TMP/n$n.csfb")
	cs=$1
	"$CSFC" "$TMP/n$n.0.csf" -o "$TMP/n$n.0.csfb"
	W=$(awk '/^inc / { for (i = 1; i <= NF; i++) if ($i ~ /^p[0-9]+\.pos/) { sub(/^p/, "", $i); sub(/\..*/, "", $i); printf "%s ", $i } }' "$TMP/n$n.csf")
	# shellcheck disable=SC2086
	"$BIN/nbody" --stats "$TMP/n$n.ic" "$till" 0.01 $W > /dev/null 2> "$TMP/n$n.stats"
	ev=$(awk '{ print $2 }' "$TMP/n$n.stats")
	vm=$(run /dev/null "$CSFVM" "$TMP/n$n.csfb" | awk '{ print $1 }')
	vm0=$(run /dev/null "$CSFVM" "$TMP/n$n.0.csfb" | awk '{ print $1 }')
	# shellcheck disable=SC2086
	hc=$(run /dev/null "$BIN/nbody" "$TMP/n$n.ic" "$till" 0.01 $W | awk '{ print $1 }')
	# shellcheck disable=SC2086
	hc0=$(run /dev/null "$BIN/nbody" "$TMP/n$n.ic" 0 0.01 $W | awk '{ print $1 }')
	awk -v n="$n" -v cs="$cs" -v w="$(words "$TMP/n$n.csf")" -v b="$(wc -c < "$TMP/n$n.csfb" | tr -d ' ')" \
	    -v ev="$ev" -v vm="$vm" -v vm0="$vm0" -v hc="$hc" -v hc0="$hc0" 'BEGIN {
		p = ev * n * (n - 1); a = (vm - vm0) / p * 1e9; h = (hc - hc0) / p * 1e9
		printf "| gen_nbody.sh | %d | %s | %d | %d | %.2f | %.2f | %.2f |\n", n, cs, w, b, a, h, a / h }' >> "$TAB"
	say "scaling: gen_nbody $n: $ev evaluations"
done
# the cloth of gen_cloth.sh, 30 x 30, written with neighbour rules (each one loop): csfc, and
# csfc --emit-c with cc, in seconds; the lines of C outside the embedded image; the time of one
# right-hand side evaluation of csfvm and of the generated program (run - start-up) / evaluations
{
	echo
	echo "| scene | N | csfc s | csfc --emit-c + cc s | lines of C (code) | evaluations | csfvm us/evaluation | emit-c us/evaluation | cloth.c us/evaluation | emit-c / cloth.c |"
	echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
} >> "$TAB"
sh ./gen_cloth.sh 30 30 "$TMP/cloth.csf"
sed 's/^inc t till 0.1 s/inc t till 0 s/' "$TMP/cloth.csf" > "$TMP/cloth0.csf"
cs=$(run /dev/null "$CSFC" "$TMP/cloth.csf" -o "$TMP/cloth.csfb" | awk '{ print $1 }')
ccs=$(run /dev/null "$CSFC" --emit-c "$TMP/cloth.csf" -o "$TMP/cloth" | awk '{ print $1 }')
"$CSFC" --emit-c "$TMP/cloth.csf" -o "$TMP/cloth.c"
"$CSFC" "$TMP/cloth0.csf" -o "$TMP/cloth0.csfb"
"$CSFC" --emit-c "$TMP/cloth0.csf" -o "$TMP/cloth0"
lines=$(awk '/^static const unsigned char csf_model_image/ { img = 1 } img && /;$/ { img = 0; next } !img { n++ } END { print n }' "$TMP/cloth.c")
ev=$("$CSFVM" --stats "$TMP/cloth.csfb" 2>&1 >/dev/null | sed -n 's/.* \([0-9]*\) right-hand side.*/\1/p')
vm=$(run /dev/null "$CSFVM" "$TMP/cloth.csfb" | awk '{ print $1 }')
vm0=$(run /dev/null "$CSFVM" "$TMP/cloth0.csfb" | awk '{ print $1 }')
ex=$(run /dev/null "$TMP/cloth" | awk '{ print $1 }')
ex0=$(run /dev/null "$TMP/cloth0" | awk '{ print $1 }')
# cloth.c integrates with ref.h's steps, not csfvm's: its own evaluations
hev=$("$BIN/cloth" --stats "$TMP/cloth.csv" 0.1 0.01 30 0 899 2>&1 >/dev/null | awk '{ print $2 }')
hc=$(run /dev/null "$BIN/cloth" "$TMP/cloth.csv" 0.1 0.01 30 0 899 | awk '{ print $1 }')
hc0=$(run /dev/null "$BIN/cloth" "$TMP/cloth.csv" 0 0.01 30 0 899 | awk '{ print $1 }')
awk -v cs="$cs" -v ccs="$ccs" -v lines="$lines" -v ev="$ev" -v vm="$vm" -v vm0="$vm0" -v ex="$ex" -v ex0="$ex0" \
    -v hev="$hev" -v hc="$hc" -v hc0="$hc0" 'BEGIN {
	e = (ex - ex0) / ev * 1e6; h = (hc - hc0) / hev * 1e6
	printf "| gen_cloth.sh 30 30 | 900 | %s | %s | %d | %d | %.1f | %.1f | %.1f | %.2f |\n", cs, ccs, lines, ev, (vm - vm0) / ev * 1e6, e, h, e / h }' >> "$TAB"
say "scaling: cloth 30 x 30: $ev evaluations"
# ARR_N projectiles in an array: csfc as compiled (two members watched) and --keep-all, csfvm's
# start-up, and one evaluation by the VM and by projectiles.c
{
	echo
	echo "| scene | N | csfc s | csfc peak MiB | csfc --keep-all s | --keep-all peak MiB | --keep-all bytecode bytes | csfvm start-up s | VM us/evaluation | projectiles.c us/evaluation | VM / projectiles.c | same bits |"
	echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
} >> "$TAB"
sh ../tests/arrays/gen_projectiles.sh "$ARR_N" array "p[0].pos, p[7].pos" > "$TMP/pa.csf"
sed 's/^inc t till 4 s by/inc t till 0 s by/' "$TMP/pa.csf" > "$TMP/pa0.csf"
set -- $(run /dev/null "$CSFC" "$TMP/pa.csf" -o "$TMP/pa.csfb")
acs=$1 amem=$2
rm -f "$TMP/pa.csfb"
set -- $(run /dev/null "$CSFC" --keep-all "$TMP/pa0.csf" -o "$TMP/pa0.csfb")
aks=$1 akmem=$2
ast=$(run /dev/null "$CSFVM" "$TMP/pa0.csfb" | awk '{ print $1 }')
set -- $("$BIN/projectiles" "$TMP/pa0.csfb" "$ARR_REPS")
awk -v n="$ARR_N" -v cs="$acs" -v mem="$amem" -v ks="$aks" -v kmem="$akmem" -v b="$(wc -c < "$TMP/pa0.csfb" | tr -d ' ')" \
    -v st="$ast" -v vm="$2" -v hc="$3" -v same="$4" 'BEGIN {
	printf "| gen_projectiles.sh array | %d | %s | %d | %s | %d | %d | %s | %.0f | %.0f | %.2f | %s |\n", n, cs, mem / 1024, ks,
	       kmem / 1024, b, st, vm * 1e6, hc * 1e6, vm / hc, same ? "yes" : "no" }' >> "$TAB"
rm -f "$TMP/pa0.csfb"
say "scaling: $ARR_N projectiles in an array"
# the same array with its momentum, a sum over its members, watched (the members summed are compiled
# with properties of their own): csfc for 1e4 and 1e5 members
{
	echo
	echo "| scene | N | csfc s | csfc peak MiB |"
	echo "|---|---:|---:|---:|"
} >> "$TAB"
for n in 10000 100000; do
	sh ../tests/arrays/gen_projectiles.sh "$n" array "P, p[0].pos" |
		sed 's/^using mechanics\/mass_point$/&\nglobal P = (0, 0, 0) kg*m\/s/; s/^using mechanics\/rules$/&\nrule: P = sum(m*v for p)/' > "$TMP/ps.csf"
	set -- $(run /dev/null "$CSFC" "$TMP/ps.csf" -o "$TMP/ps.csfb")
	echo "| gen_projectiles.sh array, P = sum(m*v for p) | $n | $1 | $(($2 / 1024)) |" >> "$TAB"
done
say "scaling: sums over 1e4 and 1e5 members"
# GAL_N stars from a file under softened gravity: csfc --emit-c, and one evaluation of the
# generated code (included by galaxy.c, its loops cut to the first GAL_ROWS stars) beside
# galaxy.c's loop, both scaled to every star
{
	echo
	echo "| scene | N | csfc --emit-c s | csfc peak MiB | pairs per evaluation | emit-c s/evaluation | galaxy.c s/evaluation | emit-c / galaxy.c | same bits |"
	echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
} >> "$TAB"
sh ./gen_galaxy.sh "$GAL_N" 0 "$TMP/galaxy.csv" "$TMP/galaxy.csf"
set -- $(run /dev/null "$CSFC" --emit-c "$TMP/galaxy.csf" -o "$TMP/gal_scene.c")
gcs=$1 gmem=$2
# shellcheck disable=SC2046 # the libraries' flags are words
${CC:-cc} -std=c11 -Wall -Wextra -O2 -ffp-contract=off -I../runtime -I"$TMP" -DGALAXY_C='"gal_scene.c"' \
	-o "$TMP/galaxy" galaxy.c "$BUILD/libcsfrt.a" $(pkg-config --libs gsl) \
	$(pkg-config --libs hdf5-serial 2>/dev/null || echo -lhdf5) -lm
set -- $("$TMP/galaxy" "$TMP/galaxy.csv" "$GAL_REPS" "$GAL_ROWS")
awk -v n="$GAL_N" -v cs="$gcs" -v mem="$gmem" -v e="$2" -v h="$3" -v same="$4" 'BEGIN {
	printf "| gen_galaxy.sh | %d | %s | %d | %.0f | %.4g | %.4g | %.2f | %s |\n", n, cs, mem / 1024, n * (n - 1), e, h, e / h,
	       same ? "yes" : "no" }' >> "$TAB"
rm -f "$TMP/gal_scene.c" "$TMP/galaxy"
say "scaling: a galaxy of $GAL_N stars"
cat "$TAB" >&2
cp "$TAB" "$OUT/scaling.md"
sh ./readme_section.sh "$README" scaling "$TAB"
