#!/bin/sh
# run.sh - the CSF benchmarks (see README.md). Run by `make` in bench/.
#
#   BUILD    directory holding csfc and csfvm          (default ../build)
#   BIN      directory holding nbody and timeit        (default bin)
#   OUT      where results.csv and summary.txt go      (default results)
#   README   file whose results section is rewritten   (default README.md;
#            empty: leave it alone)
#   REPS     repetitions of every timed run            (default 5)
#   SCENE_N  objects in the compile-time scene         (default 1000)
#   NB_N, NB_TILL, NB_BY  the n-body run: bodies, end time and output step
#                                                      (default 128, 3, 0.01)
#   CH_N, CH_TILL, CH_BY  the spring-chain run: masses, end time, output step
#                                                      (default 100, 50, 0.01)
#   EMITC_CFLAGS  CFLAGS for the C compiler csfc --emit-c runs (default -O2;
#            csfc adds -ffp-contract=off)
#
# Everything else it generates goes to $OUT/scratch.tmp (ignored by git).
# Only POSIX sh, awk, sort, cmp and the two helper programs are needed.
set -eu

BUILD=${BUILD:-../build}
BIN=${BIN:-bin}
OUT=${OUT:-results}
# The top Makefile passes BUILD=../$(BUILD): undo that for an absolute BUILD.
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
README=${README-README.md}
REPS=${REPS:-5}
SCENE_N=${SCENE_N:-1000}
NB_N=${NB_N:-128}
NB_TILL=${NB_TILL:-3}
NB_BY=${NB_BY:-0.01}
CH_N=${CH_N:-100}
CH_TILL=${CH_TILL:-50}
CH_BY=${CH_BY:-0.01}
EMITC_CFLAGS=${EMITC_CFLAGS:--O2}

CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
for p in "$CSFC" "$CSFVM" "$BIN/nbody" "$BIN/nbody_pow" "$BIN/chain" "$BIN/timeit"; do
	[ -x "$p" ] || { echo "run.sh: $p is missing: build it first (make bench from the top)" >&2; exit 2; }
done
case $REPS in '' | *[!0-9]* | 0) echo "run.sh: REPS must be a positive integer" >&2; exit 2 ;; esac

TMP=$OUT/scratch.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
CSV=$TMP/results.csv
echo "benchmark,program,seconds,steps,seconds_per_step" > "$CSV"

say() { printf '%s\n' "$*" >&2; }

# timed OUTFILE CMD... : run CMD once under timeit, print its wall seconds.
timed() {
	tout=$1
	shift
	line=$("$BIN/timeit" "$tout" "$@") || { say "run.sh: failed: $*"; exit 1; }
	echo "$line" | awk '{ print $1 }'
}

# record BENCHMARK PROGRAM SECONDS STEPS
record() {
	awk -v b="$1" -v p="$2" -v s="$3" -v n="$4" 'BEGIN { printf "%s,%s,%s,%d,%.9g\n", b, p, s, n, s / n }' >> "$CSV"
}

# median BENCHMARK PROGRAM COLUMN : median of that column over the repetitions.
median() {
	awk -F, -v b="$1" -v p="$2" -v c="$3" 'NR > 1 && $1 == b && $2 == p { print $c }' "$CSV" | sort -n |
		awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2];
			else printf "%.9g\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# rows FILE : data rows of a CSV output after the header and the t=0 row, i.e. output steps.
rows() { awk 'END { print NR - 2 }' "$1"; }

# ---- 1. compile time of a SCENE_N-object scene ----

SCENE=$TMP/scene$SCENE_N.csf
sh ./gen_scene.sh "$SCENE_N" "$SCENE"
say "compile: $SCENE_N mass points ($(wc -l < "$SCENE" | tr -d ' ') lines), $REPS run(s) of csfc"
"$CSFC" "$SCENE" -o "$TMP/scene.csfb" # warm-up, and the model must compile
"$CSFVM" "$TMP/scene.csfb" > "$TMP/scene.out" || { say "run.sh: the compiled scene does not run"; exit 1; }
SCENE_BYTES=$(wc -c < "$TMP/scene.csfb" | tr -d ' ')
SCENE_INSNS=$("$CSFC" --dump-bytecode "$SCENE" -o "$TMP/scene.csfb" | awk '/^ +[0-9]+ +[A-Z]/ { n++ } END { print n + 0 }')
i=1
while [ "$i" -le "$REPS" ]; do
	s=$(timed /dev/null "$CSFC" "$SCENE" -o "$TMP/scene.csfb")
	record "compile_scene$SCENE_N" csfc "$s" 1
	i=$((i + 1))
done

# ---- 2. NB_N bodies under pairwise gravity: csfvm against nbody.c ----

NB=nbody$NB_N
NBCSF=$TMP/$NB.csf
NBIC=$TMP/$NB.ic
sh ./gen_nbody.sh "$NB_N" "$NB_TILL" "$NB_BY" "$NBCSF" "$NBIC"
# the bodies the model watches (p0 and three more), in its order
WATCH=$(awk '/^inc / { for (i = 1; i <= NF; i++) if ($i ~ /^p[0-9]+\.pos/) { sub(/^p/, "", $i); sub(/\..*/, "", $i); printf "%s ", $i } }' "$NBCSF")
say "n-body: $NB_N bodies, till $NB_TILL by $NB_BY; compiling ($REPS run(s) of csfc)"
"$CSFC" --dump-bytecode "$NBCSF" -o "$TMP/$NB.csfb" > "$TMP/$NB.lst"
NB_INSNS=$(awk '/^section rhs/ { on = 1; next } /^section/ { on = 0 } on && /^ +[0-9]+ +[A-Z]/ { n++ } END { print n + 0 }' "$TMP/$NB.lst")
i=1
while [ "$i" -le "$REPS" ]; do
	s=$(timed /dev/null "$CSFC" "$NBCSF" -o "$TMP/$NB.csfb")
	record "compile_$NB" csfc "$s" 1
	i=$((i + 1))
done

# emitc NAME MODEL : build MODEL with csfc --emit-c into $BIN/NAME (translation
# and C compilation, timed once: it is slow), print the wall seconds.
emitc() {
	rm -f "$BIN/$1"
	timed /dev/null env CC="${CC:-cc}" CFLAGS="$EMITC_CFLAGS" "$CSFC" --emit-c "$2" -o "$BIN/$1"
}
say "n-body: csfc --emit-c (CFLAGS=$EMITC_CFLAGS), once: the generated C is large"
NBGEN=${NB}_gen
s=$(emitc "$NBGEN" "$NBCSF")
record "emitc_$NB" "csfc --emit-c + cc $EMITC_CFLAGS" "$s" 1
NBGEN_BYTES=$(wc -c < "$BIN/$NBGEN" | tr -d ' ')
say "  built $BIN/$NBGEN ($NBGEN_BYTES bytes) in $s s"

# maxdiff A B : "ABS REL", the largest absolute and relative difference between
# two CSV outputs value by value, or "mismatch" if their shapes or headers differ.
maxdiff() {
	awk -F, 'NR == FNR { if (FNR == 1) h = $0; for (i = 1; i <= NF; i++) v[FNR, i] = $i; nf[FNR] = NF; n = FNR; next }
	FNR == 1 { if ($0 != h) bad = 1; next }
	{ m++; if (NF != nf[FNR]) bad = 1
	  for (i = 2; i <= NF; i++) { a = v[FNR, i] + 0; b = $i + 0; d = a - b; if (d < 0) d = -d
		s = a < 0 ? -a : a; if ((b < 0 ? -b : b) > s) s = (b < 0 ? -b : b)
		if (d > da) da = d; if (s > 0 && d / s > dr) dr = d / s } }
	END { if (bad || m != n - 1) print "mismatch"; else printf "%.3g %.3g\n", da + 0, dr + 0 }' "$1" "$2"
}

# nbrun PROGRAM OUTFILE [TILL] : one timed n-body run, prints the wall seconds.
# emit-c is the model built by csfc --emit-c (the same till: no start-up variant).
# nbody.c-pow is nbody.c with pow(r, 3.0) for the VM's (r*r)*r (as the VM computed r^3
# before integer powers): informational, not the VM's arithmetic.
nbrun() {
	# shellcheck disable=SC2086 # WATCH is a list of numbers
	case $1 in
	csfvm) timed "$2" "$CSFVM" "$TMP/$NB${3:+.$3}.csfb" ;;
	emit-c) timed "$2" "$BIN/$NBGEN" ;;
	nbody.c) timed "$2" "$BIN/nbody" "$NBIC" "${3:-$NB_TILL}" "$NB_BY" $WATCH ;;
	nbody.c-pow) timed "$2" "$BIN/nbody_pow" "$NBIC" "${3:-$NB_TILL}" "$NB_BY" $WATCH ;;
	esac
}
PROGS="csfvm emit-c nbody.c nbody.c-pow"

# Agreement (and warm-up): one untimed run of each, compared value by value.
"$CSFVM" "$TMP/$NB.csfb" > "$TMP/$NB.csfvm.csv"
# shellcheck disable=SC2086
"$BIN/nbody" --stats "$NBIC" "$NB_TILL" "$NB_BY" $WATCH > "$TMP/$NB.nbody.c.csv" 2> "$TMP/$NB.stats"
# shellcheck disable=SC2086
"$BIN/nbody_pow" "$NBIC" "$NB_TILL" "$NB_BY" $WATCH > "$TMP/$NB.nbody.c-pow.csv"
"$BIN/$NBGEN" > "$TMP/$NB.emit-c.csv"
cmp -s "$TMP/$NB.csfvm.csv" "$TMP/$NB.emit-c.csv" ||
	{ say "run.sh: the csfc --emit-c program's output differs from csfvm's ($TMP/$NB.emit-c.csv, $TMP/$NB.csfvm.csv)"; exit 1; }
say "agreement: csfc --emit-c program and csfvm outputs byte-identical: yes"
cat "$TMP/$NB.stats" >&2
EVALS=$(awk '{ print $2 }' "$TMP/$NB.stats")
CLOSEST=$(awk '{ print $(NF - 1) }' "$TMP/$NB.stats")
if cmp -s "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c.csv"; then IDENTICAL=yes; else IDENTICAL=no; fi
DIFF=$(maxdiff "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c.csv")
POWDIFF=$(maxdiff "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c-pow.csv")
for d in "$DIFF" "$POWDIFF"; do
	[ "$d" != mismatch ] || { say "run.sh: csfvm and nbody printed tables of different shapes"; exit 1; }
done
MAXABS=${DIFF% *}
MAXREL=${DIFF#* }
say "agreement: identical output: $IDENTICAL; max |csfvm - nbody.c| = $MAXABS, max relative = $MAXREL"
say "           (nbody.c-pow, pow(r, 3.0) for (r*r)*r: max |csfvm - nbody.c-pow| = ${POWDIFF% *})"

# Start-up: the same model with till 0 (csfvm: load, decode and verify the bytecode).
sh ./gen_nbody.sh "$NB_N" 0 "$NB_BY" "$TMP/$NB.0.csf" "$TMP/$NB.0.ic"
"$CSFC" "$TMP/$NB.0.csf" -o "$TMP/$NB.0.csfb"

say "n-body: $REPS run(s) of each program, interleaved"
i=1
while [ "$i" -le "$REPS" ]; do
	# rotate the order, so that no program always runs first or last
	order=$(echo "$PROGS" | awk -v r="$i" '{ for (k = 0; k < NF; k++) printf "%s ", $((k + r - 1) % NF + 1) }')
	for prog in $order; do
		s=$(nbrun "$prog" "$TMP/$NB.run.csv")
		cmp -s "$TMP/$NB.run.csv" "$TMP/$NB.$prog.csv" ||
			{ say "run.sh: a timed run of $prog printed something else than its first run"; exit 1; }
		record "$NB" "$prog" "$s" "$(rows "$TMP/$NB.run.csv")"
		say "  run $i $prog: $s s"
	done
	for prog in csfvm nbody.c; do
		s=$(nbrun "$prog" /dev/null 0)
		record "startup_$NB" "$prog" "$s" 1
	done
	i=$((i + 1))
done

# ---- 3. a chain of CH_N masses and springs: csfvm, the emit-c program, chain.c ----

CH=chain$CH_N
CHCSF=$TMP/$CH.csf
CHIC=$TMP/$CH.ic
sh ./gen_chain.sh "$CH_N" "$CH_TILL" "$CH_BY" "$CHCSF" "$CHIC"
CHWATCH=$(awk '/^inc / { for (i = 1; i <= NF; i++) if ($i ~ /^p[0-9]+\.pos/) { sub(/^p/, "", $i); sub(/\..*/, "", $i); printf "%s ", $i } }' "$CHCSF")
say "chain: $CH_N masses, till $CH_TILL by $CH_BY; csfc, then csfc --emit-c (CFLAGS=$EMITC_CFLAGS) once"
"$CSFC" --dump-bytecode "$CHCSF" -o "$TMP/$CH.csfb" > "$TMP/$CH.lst"
CH_INSNS=$(awk '/^section rhs/ { on = 1; next } /^section/ { on = 0 } on && /^ +[0-9]+ +[A-Z]/ { n++ } END { print n + 0 }' "$TMP/$CH.lst")
CHGEN=${CH}_gen
s=$(emitc "$CHGEN" "$CHCSF")
record "emitc_$CH" "csfc --emit-c + cc $EMITC_CFLAGS" "$s" 1

chrun() { # PROGRAM OUTFILE : one timed chain run, prints the wall seconds
	# shellcheck disable=SC2086 # CHWATCH is a list of numbers
	case $1 in
	csfvm) timed "$2" "$CSFVM" "$TMP/$CH.csfb" ;;
	emit-c) timed "$2" "$BIN/$CHGEN" ;;
	chain.c) timed "$2" "$BIN/chain" "$CHIC" "$CH_TILL" "$CH_BY" $CHWATCH ;;
	esac
}
CHPROGS="csfvm emit-c chain.c"

"$CSFVM" "$TMP/$CH.csfb" > "$TMP/$CH.csfvm.csv"
"$BIN/$CHGEN" > "$TMP/$CH.emit-c.csv"
# shellcheck disable=SC2086
"$BIN/chain" --stats "$CHIC" "$CH_TILL" "$CH_BY" $CHWATCH > "$TMP/$CH.chain.c.csv" 2> "$TMP/$CH.stats"
cat "$TMP/$CH.stats" >&2
cmp -s "$TMP/$CH.csfvm.csv" "$TMP/$CH.emit-c.csv" ||
	{ say "run.sh: the csfc --emit-c program's output differs from csfvm's ($TMP/$CH.emit-c.csv, $TMP/$CH.csfvm.csv)"; exit 1; }
CHEVALS=$(awk '{ print $2 }' "$TMP/$CH.stats")
CHLINKS=$(awk '{ print $(NF - 3) " to " $(NF - 1) }' "$TMP/$CH.stats")
if cmp -s "$TMP/$CH.csfvm.csv" "$TMP/$CH.chain.c.csv"; then CHIDENT=yes; else CHIDENT=no; fi
CHDIFF=$(maxdiff "$TMP/$CH.csfvm.csv" "$TMP/$CH.chain.c.csv")
[ "$CHDIFF" != mismatch ] || { say "run.sh: csfvm and chain printed tables of different shapes"; exit 1; }
say "agreement: csfvm = emit-c program: yes; csfvm = chain.c: $CHIDENT (max |difference| ${CHDIFF% *})"

say "chain: $REPS run(s) of each program, interleaved"
i=1
while [ "$i" -le "$REPS" ]; do
	order=$(echo "$CHPROGS" | awk -v r="$i" '{ for (k = 0; k < NF; k++) printf "%s ", $((k + r - 1) % NF + 1) }')
	for prog in $order; do
		s=$(chrun "$prog" "$TMP/$CH.run.csv")
		cmp -s "$TMP/$CH.run.csv" "$TMP/$CH.$prog.csv" ||
			{ say "run.sh: a timed run of $prog printed something else than its first run"; exit 1; }
		record "$CH" "$prog" "$s" "$(rows "$TMP/$CH.run.csv")"
		say "  run $i $prog: $s s"
	done
	i=$((i + 1))
done

# ---- 4. results ----

mkdir -p "$OUT"
cp "$CSV" "$OUT/results.csv"
C1=$(median "compile_scene$SCENE_N" csfc 3)
C2=$(median "compile_$NB" csfc 3)
E1=$(median "emitc_$NB" "csfc --emit-c + cc $EMITC_CFLAGS" 3)
E2=$(median "emitc_$CH" "csfc --emit-c + cc $EMITC_CFLAGS" 3)
VS=$(median "$NB" csfvm 3)
GS=$(median "$NB" emit-c 3)
CS=$(median "$NB" nbody.c 3)
PS=$(median "$NB" nbody.c-pow 3)
V0=$(median "startup_$NB" csfvm 3)
C0=$(median "startup_$NB" nbody.c 3)
HV=$(median "$CH" csfvm 3)
HG=$(median "$CH" emit-c 3)
HC=$(median "$CH" chain.c 3)
STEPS=$(awk -F, -v b="$NB" 'NR > 1 && $1 == b { print $4; exit }' "$CSV")
CHSTEPS=$(awk -F, -v b="$CH" 'NR > 1 && $1 == b { print $4; exit }' "$CSV")
NPAIRS=$((NB_N * (NB_N - 1)))

cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
gsl=$(pkg-config --modversion gsl 2>/dev/null || echo "?")
ccv=$(${CC:-cc} --version 2>/dev/null | awk 'NR == 1' || echo "?")

awk -v c1="$C1" -v c2="$C2" -v e1="$E1" -v e2="$E2" -v vs="$VS" -v gs="$GS" -v cs="$CS" -v ps="$PS" -v v0="$V0" -v c0="$C0" \
	-v hv="$HV" -v hg="$HG" -v hc="$HC" -v chsteps="$CHSTEPS" -v chevals="$CHEVALS" -v chinsns="$CH_INSNS" \
	-v chn="$CH_N" -v chtill="$CH_TILL" -v chby="$CH_BY" -v chident="$CHIDENT" -v chdiff="$CHDIFF" -v chlinks="$CHLINKS" \
	-v ecflags="$EMITC_CFLAGS" -v nbgenbytes="$NBGEN_BYTES" \
	-v powdiff="${POWDIFF% *}" -v steps="$STEPS" -v evals="$EVALS" -v npairs="$NPAIRS" \
	-v reps="$REPS" -v sn="$SCENE_N" -v nb="$NB_N" -v till="$NB_TILL" -v by="$NB_BY" \
	-v sbytes="$SCENE_BYTES" -v sinsns="$SCENE_INSNS" -v nbinsns="$NB_INSNS" \
	-v ident="$IDENTICAL" -v maxabs="$MAXABS" -v maxrel="$MAXREL" -v closest="$CLOSEST" \
	-v date="$(date -u '+%Y-%m-%d %H:%M UTC')" -v host="$(uname -sm)" -v cpu="${cpu:-unknown}" -v ncpu="$ncpu" \
	-v gsl="$gsl" -v ccv="$ccv" '
function verdict(x, target, below) { return (below ? x <= target : x >= target) ? "target met" : "**target missed**" }
BEGIN {
	printf "CSF benchmarks, %s, %s, %s (%s CPUs), GSL %s, %s\n\n", date, host, cpu, ncpu, gsl, ccv
	printf "Median wall time of %d run(s) each (the two --emit-c builds: 1 run each); the programs of each scene ran interleaved, in rotating order. emit-c is the program `csfc --emit-c` builds (CFLAGS=%s, plus -ffp-contract=off).\n\n", reps, ecflags
	printf "| benchmark | program | seconds | steps | seconds/step |\n"
	printf "|---|---|---:|---:|---:|\n"
	printf "| compile, %d mass points (%d instructions, %d bytes of bytecode) | csfc | %.3f | 1 | %.3f |\n", sn, sinsns, sbytes, c1, c1
	printf "| compile, %d-body gravity (%d rule instances) | csfc | %.3f | 1 | %.3f |\n", nb, npairs, c2, c2
	printf "| build, %d-body gravity (%d VM instructions; a %d-byte executable) | csfc --emit-c + cc | %.3f | 1 | %.3f |\n", nb, nbinsns, nbgenbytes, e1, e1
	printf "| build, chain of %d masses (%d VM instructions) | csfc --emit-c + cc | %.3f | 1 | %.3f |\n", chn, chinsns, e2, e2
	printf "| %d-body gravity, till %s by %s | csfvm | %.3f | %d | %.3e |\n", nb, till, by, vs, steps, vs / steps
	printf "| %d-body gravity, till %s by %s | emit-c | %.3f | %d | %.3e |\n", nb, till, by, gs, steps, gs / steps
	printf "| %d-body gravity, till %s by %s | nbody.c | %.3f | %d | %.3e |\n", nb, till, by, cs, steps, cs / steps
	printf "| %d-body gravity, till %s by %s | nbody.c-pow (pow(r, 3.0), informational) | %.3f | %d | %.3e |\n", nb, till, by, ps, steps, ps / steps
	printf "| %d-body start-up only (till 0) | csfvm | %.3f | 1 | %.3f |\n", nb, v0, v0
	printf "| %d-body start-up only (till 0) | nbody.c | %.3f | 1 | %.3f |\n", nb, c0, c0
	printf "| chain of %d masses, till %s by %s | csfvm | %.3f | %d | %.3e |\n", chn, chtill, chby, hv, chsteps, hv / chsteps
	printf "| chain of %d masses, till %s by %s | emit-c | %.3f | %d | %.3e |\n", chn, chtill, chby, hg, chsteps, hg / chsteps
	printf "| chain of %d masses, till %s by %s | chain.c | %.3f | %d | %.3e |\n\n", chn, chtill, chby, hc, chsteps, hc / chsteps
	printf "Ratios (targets: emit-c / hand-written C at most 1.25, csfvm / emit-c at most 8):\n\n"
	printf "| scene | csfvm / hand-written C | emit-c / hand-written C | csfvm / emit-c |\n"
	printf "|---|---:|---:|---:|\n"
	printf "| %d-body gravity | %.2f | %.2f (%s) | %.2f (%s) |\n", nb, vs / cs, gs / cs, verdict(gs / cs, 1.25, 1), vs / gs, verdict(vs / gs, 8, 1)
	printf "| chain of %d masses | %.2f | %.2f (%s) | %.2f (%s) |\n\n", chn, hv / hc, hg / hc, verdict(hg / hc, 1.25, 1), hv / hg, verdict(hv / hg, 8, 1)
	printf "- %d-body gravity, csfvm / nbody.c without start-up (each run minus its till-0 run): %.2f\n", nb, (vs - v0) / (cs - c0)
	printf "- what pow would cost: nbody.c-pow is nbody.c with pow(r, 3.0) for (r*r)*r (r^3 as csfvm computed it before integer powers; not the same arithmetic)\n"
	printf "  - nbody.c-pow / nbody.c without start-up (each minus the till-0 run of nbody.c): %.2f; pow takes %.1f ns a pair more than (r*r)*r; csfvm / nbody.c-pow: %.2f\n", \
		(ps - c0) / (cs - c0), (ps - cs) / evals / npairs * 1e9, vs / ps
	printf "- per right-hand side evaluation (%d in the n-body run, %d pairs and %d VM instructions each):\n", evals, npairs, nbinsns
	printf "  csfvm %.0f us, emit-c %.0f us, nbody.c %.0f us, nbody.c-pow %.0f us; per pair %.1f, %.1f, %.1f and %.1f ns\n", \
		vs / evals * 1e6, gs / evals * 1e6, cs / evals * 1e6, ps / evals * 1e6, \
		vs / evals / npairs * 1e9, gs / evals / npairs * 1e9, cs / evals / npairs * 1e9, ps / evals / npairs * 1e9
	printf "- per right-hand side evaluation of the chain (%d in the run, %d VM instructions each): csfvm %.1f us, emit-c %.1f us, chain.c %.1f us\n", \
		chevals, chinsns, hv / chevals * 1e6, hg / chevals * 1e6, hc / chevals * 1e6
	printf "- agreement: emit-c and csfvm outputs byte-identical on both scenes: yes (checked; the run fails otherwise)\n"
	printf "- agreement: csfvm and nbody.c outputs byte-identical: %s; max |csfvm - nbody.c| = %s (relative %s);\n", \
		ident, maxabs, maxrel
	printf "  max |csfvm - nbody.c-pow| = %s\n", powdiff
	printf "- agreement: csfvm and chain.c outputs byte-identical: %s; max |csfvm - chain.c| = %s (relative %s)\n", \
		chident, substr(chdiff, 1, index(chdiff, " ") - 1), substr(chdiff, index(chdiff, " ") + 1)
	printf "- closest approach of two bodies at the output times: %s m; chain links between %s m at the output times\n", closest, chlinks
}' > "$OUT/summary.txt"
cat "$OUT/summary.txt"

sh ./readme_section.sh "$README" results "$OUT/summary.txt"
