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
#   NB2_N, NB2_TILL, NB2_BY  the large n-body run (must differ from NB_N)
#                                                      (default 2048, 0.02, 0.01)
#   CH_N, CH_TILL, CH_BY  the spring-chain run: masses, end time, output step
#                                                      (default 100, 50, 0.01)
#   EMITC_CFLAGS  CFLAGS for the C compiler csfc --emit-c runs (default -O2;
#            csfc adds -ffp-contract=off)
#   EMITC_FAST_CFLAGS  CFLAGS of the informational second build of each n-body
#            emit-c program (default -O3 -march=native -fno-math-errno)
#   NBODY_FAST_CFLAGS  what bin/nbody_fast was built with, for the summary only
#            (default -O3 -march=native -fno-math-errno -ffp-contract=off)
#
# Everything else it generates goes to $OUT/scratch.tmp (ignored by git).
# Only POSIX sh, awk, sort, cmp and the two helper programs are needed
# (and size(1) from binutils, if present, for the code and data sizes).
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
NB2_N=${NB2_N:-2048}
NB2_TILL=${NB2_TILL:-0.02}
NB2_BY=${NB2_BY:-0.01}
CH_N=${CH_N:-100}
CH_TILL=${CH_TILL:-50}
CH_BY=${CH_BY:-0.01}
EMITC_CFLAGS=${EMITC_CFLAGS:--O2}
EMITC_FAST_CFLAGS=${EMITC_FAST_CFLAGS:--O3 -march=native -fno-math-errno}
NBODY_FAST_CFLAGS=${NBODY_FAST_CFLAGS:--O3 -march=native -fno-math-errno -ffp-contract=off}
SIZE_N=16 # bodies of the small model whose executable is compared with NB2_N's

# The hand-written programs integrate as csfvm's rk8pd does (ref.h): GSL's rk8pd,
# steps of at most by ending on every output time. csfvm and the emit-c
# programs run that method, so that all compute the same numbers.
METHOD="--method rk8pd"

CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
for p in "$CSFC" "$CSFVM" "$BIN/nbody" "$BIN/nbody_pow" "$BIN/nbody_fast" "$BIN/chain" "$BIN/timeit"; do
	[ -x "$p" ] || { echo "run.sh: $p is missing: build it first (make bench from the top)" >&2; exit 2; }
done
case $REPS in '' | *[!0-9]* | 0) echo "run.sh: REPS must be a positive integer" >&2; exit 2 ;; esac
[ "$NB_N" != "$NB2_N" ] || { echo "run.sh: NB2_N must differ from NB_N" >&2; exit 2; }
TMP=$OUT/scratch.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
# what else the processors were doing: the load average (1, 5, 15 min) at the start and at the end
LOAD0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo n/a)
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

# interleaved BENCHMARK RUN PROGRAM... : REPS rounds of one timed run of each
# PROGRAM (RUN PROGRAM OUTFILE prints its wall seconds), in rotating order so
# that no program always runs first or last; each run's output must be its
# first run's ($TMP/BENCHMARK.PROGRAM.csv); the times go to the CSV.
interleaved() {
	ib=$1
	irun=$2
	shift 2
	ir=1
	while [ "$ir" -le "$REPS" ]; do
		order=$(echo "$*" | awk -v r="$ir" '{ for (k = 0; k < NF; k++) printf "%s ", $((k + r - 1) % NF + 1) }')
		for prog in $order; do
			s=$("$irun" "$prog" "$TMP/$ib.run.csv")
			cmp -s "$TMP/$ib.run.csv" "$TMP/$ib.$prog.csv" ||
				{ say "run.sh: a timed run of $prog printed something else than its first run"; exit 1; }
			record "$ib" "$prog" "$s" "$(rows "$TMP/$ib.run.csv")"
			say "  run $ir $prog: $s s"
		done
		ir=$((ir + 1))
	done
}

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

# ---- 2. NB_N and NB2_N bodies under pairwise gravity: csfvm, the emit-c program, nbody.c ----

# emitc NAME MODEL [CFLAGS] : build MODEL with csfc --emit-c into $BIN/NAME
# (translation and C compilation, timed once), print the wall seconds.
# CFLAGS defaults to EMITC_CFLAGS.
emitc() {
	rm -f "$BIN/$1"
	timed /dev/null env CC="${CC:-cc}" CFLAGS="${3:-$EMITC_CFLAGS}" "$CSFC" --emit-c "$2" -o "$BIN/$1"
}

# exesize FILE : "BYTES TEXT RODATA", the file's size and the sizes of its .text
# (code) and .rodata (read-only data) sections, "n/a" for these without size(1).
exesize() {
	b=$(wc -c < "$1" | tr -d ' ')
	if command -v size > /dev/null 2>&1 && size -A "$1" > "$TMP/size.txt" 2> /dev/null; then
		awk -v b="$b" '$1 == ".text" { t = $2 } $1 == ".rodata" { r = $2 }
			END { print b, (t == "" ? "n/a" : t), (r == "" ? "n/a" : r) }' "$TMP/size.txt"
	else
		echo "$b n/a n/a"
	fi
}

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

# same A B : "yes" if the two outputs are byte-identical, else "no (max |difference| X)".
same() {
	if cmp -s "$1" "$2"; then
		echo yes
	else
		d=$(maxdiff "$1" "$2")
		echo "no (max |difference| ${d% *})"
	fi
}

# nbrun PROGRAM OUTFILE [TILL] : one timed run of the current n-body scene ($NB),
# prints the wall seconds. emit-c is the model built by csfc --emit-c with
# EMITC_CFLAGS, emit-c-fast the same with EMITC_FAST_CFLAGS (the same till: no
# start-up variant). nbody.c-pow is nbody.c with pow(r, 3.0) for the VM's
# (r*r)*r (as the VM computed r^3 before integer powers): informational, not the
# VM's arithmetic. nbody.c-fast is nbody.c built with NBODY_FAST_CFLAGS.
nbrun() {
	# shellcheck disable=SC2086 # WATCH is a list of numbers
	case $1 in
	csfvm) timed "$2" "$CSFVM" $METHOD "$TMP/$NB${3:+.$3}.csfb" ;;
	emit-c) timed "$2" "$BIN/$NBGEN" $METHOD ;;
	emit-c-fast) timed "$2" "$BIN/${NBGEN}_fast" $METHOD ;;
	nbody.c) timed "$2" "$BIN/nbody" "$NBIC" "${3:-$NBTILL}" "$NBBY" $WATCH ;;
	nbody.c-pow) timed "$2" "$BIN/nbody_pow" "$NBIC" "${3:-$NBTILL}" "$NBBY" $WATCH ;;
	nbody.c-fast) timed "$2" "$BIN/nbody_fast" "$NBIC" "${3:-$NBTILL}" "$NBBY" $WATCH ;;
	esac
}

# nbscene N TILL BY MAIN : the n-body scene of N bodies, till TILL by BY: the
# emit-c builds (timed once each), the agreement checks, then REPS interleaved
# timed runs of every program and of the start-up (till 0) of csfvm and nbody.c.
# MAIN=1 (the NB_N scene) adds the compile time and nbody.c-pow. Leaves its
# figures in the NB_* variables below; the times go to the CSV as benchmark nbody<N>.
nbscene() {
	NB=nbody$1
	NBTILL=$2
	NBBY=$3
	NBCSF=$TMP/$NB.csf
	NBIC=$TMP/$NB.ic
	NBGEN=${NB}_gen
	sh ./gen_nbody.sh "$1" "$2" "$3" "$NBCSF" "$NBIC"
	# the bodies the model watches (p0 and three more), in its order
	WATCH=$(awk '/^inc / { for (i = 1; i <= NF; i++) if ($i ~ /^p[0-9]+\.pos/) { sub(/^p/, "", $i); sub(/\..*/, "", $i); printf "%s ", $i } }' "$NBCSF")
	"$CSFC" --dump-bytecode "$NBCSF" -o "$TMP/$NB.csfb" > "$TMP/$NB.lst"
	NB_INSNS=$(awk '/^section rhs/ { on = 1; next } /^section/ { on = 0 } on && /^ +[0-9]+ +[A-Z]/ { n++ } END { print n + 0 }' "$TMP/$NB.lst")
	nbprogs="csfvm emit-c nbody.c emit-c-fast nbody.c-fast"
	if [ "$4" = 1 ]; then
		nbprogs="csfvm emit-c nbody.c nbody.c-pow emit-c-fast nbody.c-fast"
		say "n-body: $1 bodies, till $2 by $3; compiling ($REPS run(s) of csfc)"
		i=1
		while [ "$i" -le "$REPS" ]; do
			s=$(timed /dev/null "$CSFC" "$NBCSF" -o "$TMP/$NB.csfb")
			record "compile_$NB" csfc "$s" 1
			i=$((i + 1))
		done
	else
		say "n-body: $1 bodies, till $2 by $3"
	fi

	say "n-body: csfc --emit-c, once with CFLAGS=$EMITC_CFLAGS, once with CFLAGS=$EMITC_FAST_CFLAGS"
	s=$(emitc "$NBGEN" "$NBCSF")
	record "emitc_$NB" "csfc --emit-c + cc $EMITC_CFLAGS" "$s" 1
	NB_SIZE=$(exesize "$BIN/$NBGEN")
	say "  built $BIN/$NBGEN (${NB_SIZE%% *} bytes) in $s s"
	s=$(emitc "${NBGEN}_fast" "$NBCSF" "$EMITC_FAST_CFLAGS")
	record "emitc_fast_$NB" "csfc --emit-c + cc $EMITC_FAST_CFLAGS" "$s" 1
	say "  built $BIN/${NBGEN}_fast in $s s"

	# Agreement (and warm-up): one untimed run of each, compared value by value.
	"$CSFVM" $METHOD "$TMP/$NB.csfb" > "$TMP/$NB.csfvm.csv"
	# shellcheck disable=SC2086
	"$BIN/nbody" --stats "$NBIC" "$NBTILL" "$NBBY" $WATCH > "$TMP/$NB.nbody.c.csv" 2> "$TMP/$NB.stats"
	# shellcheck disable=SC2086
	"$BIN/nbody_fast" "$NBIC" "$NBTILL" "$NBBY" $WATCH > "$TMP/$NB.nbody.c-fast.csv"
	"$BIN/$NBGEN" $METHOD > "$TMP/$NB.emit-c.csv"
	"$BIN/${NBGEN}_fast" $METHOD > "$TMP/$NB.emit-c-fast.csv"
	cmp -s "$TMP/$NB.csfvm.csv" "$TMP/$NB.emit-c.csv" ||
		{ say "run.sh: the csfc --emit-c program's output differs from csfvm's ($TMP/$NB.emit-c.csv, $TMP/$NB.csfvm.csv)"; exit 1; }
	say "agreement: csfc --emit-c program and csfvm outputs byte-identical: yes"
	cat "$TMP/$NB.stats" >&2
	NB_EVALS=$(awk '{ print $2 }' "$TMP/$NB.stats")
	NB_CLOSEST=$(awk '{ print $(NF - 1) }' "$TMP/$NB.stats")
	if cmp -s "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c.csv"; then NB_IDENT=yes; else NB_IDENT=no; fi
	d=$(maxdiff "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c.csv")
	[ "$d" != mismatch ] || { say "run.sh: csfvm and nbody printed tables of different shapes"; exit 1; }
	NB_MAXABS=${d% *}
	NB_MAXREL=${d#* }
	say "agreement: identical output: $NB_IDENT; max |csfvm - nbody.c| = $NB_MAXABS, max relative = $NB_MAXREL"
	NB_GENFAST_SAME=$(same "$TMP/$NB.csfvm.csv" "$TMP/$NB.emit-c-fast.csv")
	NB_CFAST_SAME=$(same "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c-fast.csv")
	say "           (informational: = csfvm: emit-c-fast $NB_GENFAST_SAME, nbody.c-fast $NB_CFAST_SAME)"
	NB_POWDIFF=
	if [ "$4" = 1 ]; then
		# shellcheck disable=SC2086
		"$BIN/nbody_pow" "$NBIC" "$NBTILL" "$NBBY" $WATCH > "$TMP/$NB.nbody.c-pow.csv"
		d=$(maxdiff "$TMP/$NB.csfvm.csv" "$TMP/$NB.nbody.c-pow.csv")
		[ "$d" != mismatch ] || { say "run.sh: csfvm and nbody_pow printed tables of different shapes"; exit 1; }
		NB_POWDIFF=${d% *}
		say "           (nbody.c-pow, pow(r, 3.0) for (r*r)*r: max |csfvm - nbody.c-pow| = $NB_POWDIFF)"
	fi

	# Start-up: the same model with till 0 (csfvm: load, decode and verify the bytecode).
	sh ./gen_nbody.sh "$1" 0 "$3" "$TMP/$NB.0.csf" "$TMP/$NB.0.ic"
	"$CSFC" "$TMP/$NB.0.csf" -o "$TMP/$NB.0.csfb"

	say "n-body: $REPS run(s) of each program, interleaved"
	# shellcheck disable=SC2086 # nbprogs is a list of names
	interleaved "$NB" nbrun $nbprogs
	i=1
	while [ "$i" -le "$REPS" ]; do
		for prog in csfvm nbody.c; do
			s=$(nbrun "$prog" /dev/null 0)
			record "startup_$NB" "$prog" "$s" 1
		done
		i=$((i + 1))
	done
}

nbscene "$NB_N" "$NB_TILL" "$NB_BY" 1
N1_INSNS=$NB_INSNS N1_SIZE=$NB_SIZE N1_EVALS=$NB_EVALS N1_CLOSEST=$NB_CLOSEST N1_IDENT=$NB_IDENT
N1_MAXABS=$NB_MAXABS N1_MAXREL=$NB_MAXREL N1_GENFAST_SAME=$NB_GENFAST_SAME N1_CFAST_SAME=$NB_CFAST_SAME
POWDIFF=$NB_POWDIFF

nbscene "$NB2_N" "$NB2_TILL" "$NB2_BY" 0
N2_INSNS=$NB_INSNS N2_SIZE=$NB_SIZE N2_EVALS=$NB_EVALS N2_CLOSEST=$NB_CLOSEST N2_IDENT=$NB_IDENT
N2_MAXABS=$NB_MAXABS N2_MAXREL=$NB_MAXREL N2_GENFAST_SAME=$NB_GENFAST_SAME N2_CFAST_SAME=$NB_CFAST_SAME

# The executable of a SIZE_N-body model, built as the NB2_N one (not run): its
# size beside NB2_N's shows whether the code grows with the number of objects.
SZ=size$SIZE_N
sh ./gen_nbody.sh "$SIZE_N" "$NB2_TILL" "$NB2_BY" "$TMP/$SZ.csf" "$TMP/$SZ.ic"
say "n-body: $SIZE_N bodies, csfc --emit-c (CFLAGS=$EMITC_CFLAGS) once, for its size"
s=$(emitc "${SZ}_gen" "$TMP/$SZ.csf")
record "emitc_nbody$SIZE_N" "csfc --emit-c + cc $EMITC_CFLAGS" "$s" 1
SZ_SIZE=$(exesize "$BIN/${SZ}_gen")
say "  built $BIN/${SZ}_gen (${SZ_SIZE%% *} bytes) in $s s"

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
	csfvm) timed "$2" "$CSFVM" $METHOD "$TMP/$CH.csfb" ;;
	emit-c) timed "$2" "$BIN/$CHGEN" $METHOD ;;
	chain.c) timed "$2" "$BIN/chain" "$CHIC" "$CH_TILL" "$CH_BY" $CHWATCH ;;
	esac
}
CHPROGS="csfvm emit-c chain.c"

"$CSFVM" $METHOD "$TMP/$CH.csfb" > "$TMP/$CH.csfvm.csv"
"$BIN/$CHGEN" $METHOD > "$TMP/$CH.emit-c.csv"
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
# shellcheck disable=SC2086 # CHPROGS is a list of names
interleaved "$CH" chrun $CHPROGS

# ---- 4. results ----

mkdir -p "$OUT"
cp "$CSV" "$OUT/results.csv"
NB=nbody$NB_N
NB2=nbody$NB2_N
CH=chain$CH_N
C1=$(median "compile_scene$SCENE_N" csfc 3)
C2=$(median "compile_$NB" csfc 3)
EB="csfc --emit-c + cc $EMITC_CFLAGS"
EF="csfc --emit-c + cc $EMITC_FAST_CFLAGS"
B1=$(median "emitc_$NB" "$EB" 3)
BF1=$(median "emitc_fast_$NB" "$EF" 3)
B2=$(median "emitc_$NB2" "$EB" 3)
BF2=$(median "emitc_fast_$NB2" "$EF" 3)
BS=$(median "emitc_nbody$SIZE_N" "$EB" 3)
BC=$(median "emitc_$CH" "$EB" 3)
# nbtimes BENCHMARK : the medians of csfvm, emit-c, nbody.c, emit-c-fast, nbody.c-fast,
# nbody.c-pow, and of the start-up of csfvm and nbody.c, and the output steps
nbtimes() {
	for p in csfvm emit-c nbody.c emit-c-fast nbody.c-fast nbody.c-pow; do printf '%s ' "$(median "$1" "$p" 3)"; done
	for p in csfvm nbody.c; do printf '%s ' "$(median "startup_$1" "$p" 3)"; done
	awk -F, -v b="$1" 'NR > 1 && $1 == b { print $4; exit }' "$CSV"
}
T1=$(nbtimes "$NB")
T2=$(nbtimes "$NB2")
HV=$(median "$CH" csfvm 3)
HG=$(median "$CH" emit-c 3)
HC=$(median "$CH" chain.c 3)
CHSTEPS=$(awk -F, -v b="$CH" 'NR > 1 && $1 == b { print $4; exit }' "$CSV")

cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
gsl=$(pkg-config --modversion gsl 2>/dev/null || echo "?")
ccv=$(${CC:-cc} --version 2>/dev/null | awk 'NR == 1' || echo "?")

awk -v c1="$C1" -v c2="$C2" -v b1="$B1" -v bf1="$BF1" -v b2="$B2" -v bf2="$BF2" -v bs="$BS" -v bc="$BC" \
	-v t1="$T1" -v t2="$T2" -v sz1="$N1_SIZE" -v sz2="$N2_SIZE" -v szs="$SZ_SIZE" -v sn16="$SIZE_N" \
	-v hv="$HV" -v hg="$HG" -v hc="$HC" -v chsteps="$CHSTEPS" -v chevals="$CHEVALS" -v chinsns="$CH_INSNS" \
	-v chn="$CH_N" -v chtill="$CH_TILL" -v chby="$CH_BY" -v chident="$CHIDENT" -v chdiff="$CHDIFF" -v chlinks="$CHLINKS" \
	-v ecflags="$EMITC_CFLAGS" -v efflags="$EMITC_FAST_CFLAGS" -v nfflags="$NBODY_FAST_CFLAGS" -v powdiff="$POWDIFF" \
	-v n1="$NB_N" -v till1="$NB_TILL" -v by1="$NB_BY" -v insns1="$N1_INSNS" -v evals1="$N1_EVALS" \
	-v ident1="$N1_IDENT" -v maxabs1="$N1_MAXABS" -v maxrel1="$N1_MAXREL" -v closest1="$N1_CLOSEST" \
	-v gfsame1="$N1_GENFAST_SAME" -v cfsame1="$N1_CFAST_SAME" \
	-v n2="$NB2_N" -v till2="$NB2_TILL" -v by2="$NB2_BY" -v insns2="$N2_INSNS" -v evals2="$N2_EVALS" \
	-v ident2="$N2_IDENT" -v maxabs2="$N2_MAXABS" -v maxrel2="$N2_MAXREL" -v closest2="$N2_CLOSEST" \
	-v gfsame2="$N2_GENFAST_SAME" -v cfsame2="$N2_CFAST_SAME" \
	-v reps="$REPS" -v sn="$SCENE_N" -v sbytes="$SCENE_BYTES" -v sinsns="$SCENE_INSNS" \
	-v date="$(date -u '+%Y-%m-%d %H:%M UTC')" -v host="$(uname -sm)" -v cpu="${cpu:-unknown}" -v ncpu="$ncpu" \
	-v gsl="$gsl" -v ccv="$ccv" -v load0="$LOAD0" -v load1="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo n/a)" '
function verdict(x, target, below) { return (below ? x <= target : x >= target) ? "target met" : "**target missed**" }
# nb(K, T): split the nbtimes figures T into the arrays of scene K
function nb(k, t,   a) {
	split(t, a, " ")
	vs[k] = a[1]; gs[k] = a[2]; cs[k] = a[3]; gf[k] = a[4]; cf[k] = a[5]; ps[k] = a[6]; v0[k] = a[7]; c0[k] = a[8]; steps[k] = a[9]
}
function ns(x, k) { return x / evals[k] / npairs[k] * 1e9 }
function runrow(k, prog, x) {
	printf "| %d-body gravity, till %s by %s | %s | %.3f | %d | %.3e |\n", n[k], till[k], by[k], prog, x, steps[k], x / steps[k]
}
function buildrow(what, prog, x) { printf "| build, %s | %s | %.3f | 1 | %.3f |\n", what, prog, x, x }
function sizerow(label, bt, sz,   a) {
	split(sz, a, " ")
	printf "| %s | %s | %s | %s | %s |\n", label, bt, a[1], a[2], a[3]
}
function ratio(a, b) { return (a ~ /^[0-9]/ && b ~ /^[0-9]/ && b > 0) ? sprintf("%.2f", a / b) : "n/a" }
BEGIN {
	nb(1, t1); nb(2, t2)
	n[1] = n1; till[1] = till1; by[1] = by1; evals[1] = evals1; insns[1] = insns1; npairs[1] = n1 * (n1 - 1)
	n[2] = n2; till[2] = till2; by[2] = by2; evals[2] = evals2; insns[2] = insns2; npairs[2] = n2 * (n2 - 1)
	gfsame[1] = gfsame1; cfsame[1] = cfsame1; gfsame[2] = gfsame2; cfsame[2] = cfsame2
	printf "CSF benchmarks, %s, %s, %s (%s CPUs), GSL %s, %s; load average (1, 5, 15 min) %s at the start, %s at the end\n\n", date, host, cpu, ncpu, gsl, ccv, load0, load1
	printf "Median wall time of %d run(s) each (the --emit-c builds: 1 run each); the programs of each scene ran interleaved, in rotating order. emit-c is the program `csfc --emit-c` builds (CFLAGS=%s, plus -ffp-contract=off). Informational: emit-c-fast is the same program built with CFLAGS=%s (plus -ffp-contract=off), nbody.c-fast is nbody.c built with %s (`bin/nbody_fast`).\n\n", reps, ecflags, efflags, nfflags
	printf "| benchmark | program | seconds | steps | seconds/step |\n"
	printf "|---|---|---:|---:|---:|\n"
	printf "| compile, %d mass points (%d instructions, %d bytes of bytecode) | csfc | %.3f | 1 | %.3f |\n", sn, sinsns, sbytes, c1, c1
	printf "| compile, %d-body gravity (%d rule instances) | csfc | %.3f | 1 | %.3f |\n", n1, npairs[1], c2, c2
	buildrow(sprintf("%d-body gravity (for the size of its executable)", sn16), "csfc --emit-c + cc", bs)
	buildrow(sprintf("%d-body gravity (%d VM instructions)", n1, insns[1]), "csfc --emit-c + cc", b1)
	buildrow(sprintf("%d-body gravity", n1), "csfc --emit-c + cc, emit-c-fast", bf1)
	buildrow(sprintf("%d-body gravity (%d VM instructions)", n2, insns[2]), "csfc --emit-c + cc", b2)
	buildrow(sprintf("%d-body gravity", n2), "csfc --emit-c + cc, emit-c-fast", bf2)
	buildrow(sprintf("chain of %d masses (%d VM instructions)", chn, chinsns), "csfc --emit-c + cc", bc)
	for (k = 1; k <= 2; k++) {
		runrow(k, "csfvm", vs[k]); runrow(k, "emit-c", gs[k]); runrow(k, "nbody.c", cs[k])
		if (k == 1) runrow(k, "nbody.c-pow (pow(r, 3.0), informational)", ps[k])
		runrow(k, "emit-c-fast (informational)", gf[k]); runrow(k, "nbody.c-fast (informational)", cf[k])
		printf "| %d-body start-up only (till 0) | csfvm | %.3f | 1 | %.3f |\n", n[k], v0[k], v0[k]
		printf "| %d-body start-up only (till 0) | nbody.c | %.3f | 1 | %.3f |\n", n[k], c0[k], c0[k]
	}
	printf "| chain of %d masses, till %s by %s | csfvm | %.3f | %d | %.3e |\n", chn, chtill, chby, hv, chsteps, hv / chsteps
	printf "| chain of %d masses, till %s by %s | emit-c | %.3f | %d | %.3e |\n", chn, chtill, chby, hg, chsteps, hg / chsteps
	printf "| chain of %d masses, till %s by %s | chain.c | %.3f | %d | %.3e |\n\n", chn, chtill, chby, hc, chsteps, hc / chsteps

	printf "Ratios of the median times (targets: csfvm / hand-written C at most 3, per pair on the n-body scenes and per evaluation on the chain; emit-c / hand-written C at most 1.25):\n\n"
	printf "| scene | csfvm / hand-written C | emit-c / hand-written C | csfvm / emit-c |\n"
	printf "|---|---:|---:|---:|\n"
	for (k = 1; k <= 2; k++)
		printf "| %d-body gravity | %.2f (%s) | %.2f (%s) | %.2f |\n", n[k], vs[k] / cs[k], verdict(vs[k] / cs[k], 3, 1), \
			gs[k] / cs[k], verdict(gs[k] / cs[k], 1.25, 1), vs[k] / gs[k]
	printf "| chain of %d masses | %.2f (%s) | %.2f (%s) | %.2f |\n\n", chn, hv / hc, verdict(hv / hc, 3, 1), hg / hc, \
		verdict(hg / hc, 1.25, 1), hv / hg

	split(szs, s0, " "); split(sz2, s2, " ")
	printf "The executables `csfc --emit-c` builds (CFLAGS=%s), the time to build them (translation and cc) and their sizes in bytes (targets: the %d-body build under 5 s; its code about the size of the %d-body program'"'"'s, at most 1.1 times: the code grows with the text of the scene, not with its number of objects; the file and the read-only data, which hold the model image, are shown beside):\n\n", ecflags, n2, sn16
	printf "| bodies | build (s) | executable | code (.text) | read-only data (.rodata) |\n"
	printf "|---:|---:|---:|---:|---:|\n"
	sizerow(sn16, sprintf("%.3f", bs), szs)
	sizerow(n1, sprintf("%.3f", b1), sz1)
	sizerow(n2, sprintf("%.3f (%s)", b2, verdict(b2, 5, 1)), sz2)
	r = ratio(s2[2], s0[2])
	printf "| %d / %d | | %s | %s | %s |\n\n", n2, sn16, ratio(s2[1], s0[1]), r == "n/a" ? "n/a (no size(1))" : r " (" verdict(r + 0, 1.1, 1) ")", ratio(s2[3], s0[3])

	printf "Per pair (a right-hand side evaluation over N*(N-1) pairs; each run'"'"'s wall time, start-up included, over its evaluations, from `nbody --stats`), in ns; informational: the -fast builds, and whether their outputs are still byte-identical to csfvm'"'"'s:\n\n"
	printf "| bodies | evaluations | csfvm | emit-c | nbody.c | emit-c-fast | nbody.c-fast | emit-c-fast / nbody.c-fast | emit-c-fast = csfvm | nbody.c-fast = csfvm |\n"
	printf "|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n"
	for (k = 1; k <= 2; k++)
		printf "| %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s |\n", n[k], evals[k], ns(vs[k], k), ns(gs[k], k), ns(cs[k], k), \
			ns(gf[k], k), ns(cf[k], k), gf[k] / cf[k], gfsame[k], cfsame[k]
	printf "\n"
	for (k = 1; k <= 2; k++)
		printf "- %d-body gravity, csfvm / nbody.c without start-up (each run minus its till-0 run): %.2f; start-up %.3f s (csfvm) and %.3f s (nbody.c) of %.3f and %.3f\n", \
			n[k], (vs[k] - v0[k]) / (cs[k] - c0[k]), v0[k], c0[k], vs[k], cs[k]
	printf "- what pow would cost: nbody.c-pow is nbody.c with pow(r, 3.0) for (r*r)*r (r^3 as csfvm computed it before integer powers; not the same arithmetic)\n"
	printf "  - nbody.c-pow / nbody.c without start-up (each minus the till-0 run of nbody.c): %.2f; pow takes %.1f ns a pair more than (r*r)*r; csfvm / nbody.c-pow: %.2f\n", \
		(ps[1] - c0[1]) / (cs[1] - c0[1]), ns(ps[1] - cs[1], 1), vs[1] / ps[1]
	for (k = 1; k <= 2; k++)
		printf "- per right-hand side evaluation, %d bodies (%d in the run, %d pairs and %d VM instructions each): csfvm %.0f us, emit-c %.0f us, nbody.c %.0f us\n", \
			n[k], evals[k], npairs[k], insns[k], vs[k] / evals[k] * 1e6, gs[k] / evals[k] * 1e6, cs[k] / evals[k] * 1e6
	printf "- per right-hand side evaluation of the chain (%d in the run, %d VM instructions each): csfvm %.1f us, emit-c %.1f us, chain.c %.1f us\n", \
		chevals, chinsns, hv / chevals * 1e6, hg / chevals * 1e6, hc / chevals * 1e6
	printf "- agreement: emit-c and csfvm outputs byte-identical on the three scenes: yes (checked; the run fails otherwise)\n"
	printf "- agreement: csfvm and nbody.c outputs byte-identical: %s at %d bodies, %s at %d; max |csfvm - nbody.c| = %s (relative %s) and %s (relative %s);\n", \
		ident1, n1, ident2, n2, maxabs1, maxrel1, maxabs2, maxrel2
	printf "  max |csfvm - nbody.c-pow| = %s\n", powdiff
	printf "- agreement: csfvm and chain.c outputs byte-identical: %s; max |csfvm - chain.c| = %s (relative %s)\n", \
		chident, substr(chdiff, 1, index(chdiff, " ") - 1), substr(chdiff, index(chdiff, " ") + 1)
	printf "- closest approach of two bodies at the output times: %s m (%d bodies), %s m (%d bodies); chain links between %s m at the output times\n", \
		closest1, n1, closest2, n2, chlinks
}' > "$OUT/summary.txt"
cat "$OUT/summary.txt"

sh ./readme_section.sh "$README" results "$OUT/summary.txt"
