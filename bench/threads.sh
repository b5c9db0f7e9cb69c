#!/bin/sh
# threads.sh - what --threads N gains on the large n-body scene of run.sh
# (NB2_N bodies under pairwise gravity, rk8pd, till NB2_TILL by NB_BY): csfvm
# and the csfc --emit-c program (CFLAGS=EMITC_CFLAGS) with 1 and 2 threads,
# and 4 and 8 where the machine has that many processors, REPS runs each,
# interleaved in rotating order; every output must be the one-thread run's,
# byte for byte. The machine's load (/proc/loadavg) before and after says
# what the threads competed with. Target: 2 threads at least 1.8 times as
# fast as 1, for both programs.
# Writes $OUT/threads.csv and $OUT/threads.txt, and the threads section of $README.
#   BUILD (../build), BIN (bin), OUT (results), README (README.md; empty: leave it alone),
#   REPS (5), NB2_N (2048), NB2_TILL (0.02), NB_BY (0.01), EMITC_CFLAGS (-O2)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
BIN=${BIN:-bin}
OUT=${OUT:-results}
README=${README-README.md}
REPS=${REPS:-5}
NB2_N=${NB2_N:-2048} NB2_TILL=${NB2_TILL:-0.02} NB_BY=${NB_BY:-0.01}
EMITC_CFLAGS=${EMITC_CFLAGS:--O2}
TMP=$OUT/threads.tmp
rm -rf "$TMP"
mkdir -p "$TMP" "$BIN"
CSV=$OUT/threads.csv
NCPU=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
COUNTS=1
for n in 2 4 8; do [ "$n" -le "$NCPU" ] || [ "$n" = 2 ] && COUNTS="$COUNTS $n"; done
load() { cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo n/a; }

sh ./gen_nbody.sh "$NB2_N" "$NB2_TILL" "$NB_BY" "$TMP/nb.csf" /dev/null
"$BUILD/csfc" "$TMP/nb.csf" -o "$TMP/nb.csfb"
CC="${CC:-cc}" CFLAGS="$EMITC_CFLAGS" "$BUILD/csfc" --emit-c "$TMP/nb.csf" -o "$BIN/threads_gen"
echo "threads: $NB2_N bodies, till $NB2_TILL by $NB_BY, $REPS run(s) of each of csfvm and emit-c with $COUNTS threads" >&2

# run PROG N OUTFILE : one timed run, its wall seconds
run() {
	case $1 in
	csfvm) "$BIN/timeit" "$3" "$BUILD/csfvm" --method rk8pd --threads "$2" "$TMP/nb.csfb" ;;
	emit-c) "$BIN/timeit" "$3" "$BIN/threads_gen" --method rk8pd --threads "$2" ;;
	esac | awk '{ print $1 }'
}

LOAD0=$(load)
echo "program,threads,seconds" > "$CSV"
progs=
for p in csfvm emit-c; do for n in $COUNTS; do progs="$progs $p:$n"; done; done
run csfvm 1 "$TMP/ref.csv" > /dev/null
r=1
while [ "$r" -le "$REPS" ]; do
	order=$(echo $progs | awk -v r="$r" '{ for (k = 0; k < NF; k++) printf "%s ", $((k + r - 1) % NF + 1) }')
	for pn in $order; do
		s=$(run "${pn%:*}" "${pn#*:}" "$TMP/out.csv")
		cmp -s "$TMP/out.csv" "$TMP/ref.csv" ||
			{ echo "threads.sh: ${pn%:*} --threads ${pn#*:} printed other bytes than csfvm --threads 1" >&2; exit 1; }
		echo "${pn%:*},${pn#*:},$s" >> "$CSV"
		echo "  run $r ${pn%:*} --threads ${pn#*:}: $s s" >&2
	done
	r=$((r + 1))
done
LOAD1=$(load)

sort -t, -k1,1 -k2,2n -k3,3g "$CSV" | awk -F, -v n="$NB2_N" -v till="$NB2_TILL" -v by="$NB_BY" -v reps="$REPS" \
	-v l0="$LOAD0" -v l1="$LOAD1" -v cpus="$NCPU" '
$1 != "program" { k = $1 SUBSEP $2; t[k, ++c[k]] = $3; if (!(k in seen)) { seen[k] = 1; key[++nk] = k } }
END {
	printf "`--threads N` on %d bodies under pairwise gravity (rk8pd, till %s by %s): median wall time of %d runs each, the programs interleaved; every output byte-identical to `csfvm --threads 1`'"'"'s. %d processors; load average (1, 5, 15 min) %s before, %s after.\n\n", n, till, by, reps, cpus, l0, l1
	print "| program | threads | seconds | speed-up over 1 thread | target |"
	print "|---|---:|---:|---:|---|"
	for (i = 1; i <= nk; i++) {
		k = key[i]; m = c[k]
		med[k] = m % 2 ? t[k, (m + 1) / 2] : (t[k, m / 2] + t[k, m / 2 + 1]) / 2
		split(k, a, SUBSEP)
		one = med[a[1] SUBSEP 1]
		sp = med[k] > 0 ? one / med[k] : 0
		tg = a[2] == 2 ? (sp >= 1.8 ? ">= 1.8: met" : ">= 1.8: **missed**") : ""
		printf "| %s | %d | %.3f | %.2f | %s |\n", a[1] == "emit-c" ? "emit-c" : "csfvm", a[2], med[k], sp, tg
	}
}' > "$OUT/threads.txt"
cat "$OUT/threads.txt"
sh ./readme_section.sh "$README" threads "$OUT/threads.txt"
