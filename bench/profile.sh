#!/bin/sh
# profile.sh - where csfvm's time goes on the n-body benchmark (make profile).
#
# Writes $OUT/profile.txt: the VM instruction mix of one right-hand side
# evaluation (from csfc --dump-bytecode), then flat profiles of csfvm and of
# nbody.c on a short run and of csfc compiling the 1000-object scene, by
# `perf record` if perf works here, else by valgrind --tool=callgrind
# (slower: a shorter run; PROFILER=callgrind forces it), else the mix alone.
set -eu
BUILD=${BUILD:-../build}
# The top Makefile passes BUILD=../$(BUILD): undo that for an absolute BUILD.
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
BIN=${BIN:-bin}
OUT=${OUT:-results}
NB_N=${NB_N:-128}
TMP=$OUT/profile.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
REPORT=$OUT/profile.txt

prof_run() { # NAME CMD... : profile CMD into the report
	name=$1
	shift
	if [ "$TOOL" = perf ]; then
		perf record -q -o "$TMP/$name.perf" "$@" > /dev/null 2> "$TMP/$name.err"
		perf report -i "$TMP/$name.perf" --stdio --no-children --sort dso,symbol 2> /dev/null |
			awk '/^ +[0-9.]+%/ && n < 8 { printf "  %8s  %-20s %s\n", $1, $2, $4; n++ }'
	else
		valgrind --tool=callgrind --callgrind-out-file="$TMP/$name.cg" "$@" > /dev/null 2> "$TMP/$name.err"
		callgrind_annotate "$TMP/$name.cg" 2> /dev/null | awk '/^-+$/ { d++ } d >= 3 && NF && n < 10 { print; n++ }'
	fi
}

TOOL=none
if [ "${PROFILER:-}" = callgrind ]; then
	TOOL=callgrind
	TILL=0.05
elif command -v perf > /dev/null 2>&1 && perf record -q -o "$TMP/probe.perf" true > /dev/null 2>&1; then
	TOOL=perf
	TILL=3
elif command -v valgrind > /dev/null 2>&1; then
	TOOL=callgrind
	TILL=0.05
fi
sh ./gen_nbody.sh "$NB_N" "${TILL:-0.05}" 0.01 "$TMP/nb.csf" "$TMP/nb.ic"
"$BUILD/csfc" --dump-bytecode "$TMP/nb.csf" -o "$TMP/nb.csfb" > "$TMP/nb.lst"
WATCH=$(awk '/^inc / { for (i = 1; i <= NF; i++) if ($i ~ /^p[0-9]+\.pos/) { sub(/^p/, "", $i); sub(/\..*/, "", $i); printf "%s ", $i } }' "$TMP/nb.csf")
{
	echo "csfvm profile, $NB_N-body gravity ($(date -u '+%Y-%m-%d %H:%M UTC'))"
	echo
	echo "VM instructions executed per right-hand side evaluation (section rhs; each weighed by the"
	echo "counts of the loops around it):"
	awk '/^section rhs/ { on = 1; w = 1; d = 0; next } /^section/ { on = 0 }
		on && /^ +[0-9]+ +[A-Z]/ {
			op = $2; c[op] += w; n += w; words++
			if (op == "LOOP") { st[++d] = w; w *= $4 }
			else if (op == "NEXT") w = st[d--]
		}
		END {
			for (k in c) printf "  %-8s %10d  %5.1f%%\n", k, c[k], 100 * c[k] / n
			printf "  %-8s %10d  (%d instructions of code)\n", "total", n, words > "/dev/stderr"
		}' "$TMP/nb.lst" 2> "$TMP/mix.total" | sort -k2,2nr -k1,1
	cat "$TMP/mix.total"
	echo "(instructions as the bytecode counts them: csfvm dispatches those of an innermost loop it runs a block"
	echo "at a time, such as the pair loop, once a block of up to 64 iterations: csfvm(1), DESCRIPTION)"
	echo
	if [ "$TOOL" = none ]; then
		echo "(neither perf nor valgrind works here: no sampled profile)"
	else
		echo "$TOOL, csfvm, till ${TILL} by 0.01:"
		prof_run csfvm "$BUILD/csfvm" "$TMP/nb.csfb"
		if [ "$TOOL" = perf ]; then
			for sym in exec run_blocked; do
				echo
				echo "perf, csfvm: the samples of $sym by source line, the instruction each is (exec: the dispatch loop,"
				echo "an opcodes.def line its case, operands loaded and stored; run_blocked: a loop a block of 64 at a"
				echo "time, vm.c the loop over the block, csf_ops.h the arithmetic)"
				perf annotate -i "$TMP/csfvm.perf" --stdio -l -s "$sym" 2> /dev/null |
					awk '/^Sorted summary/ { on = 1; next } on && /^ *$/ && n { exit }
						on && /^ +[0-9.]+ +[a-z_]+\.[a-z]+:[0-9]+/ && n < 14 {
							split($2, a, ":"); f = "../runtime/" a[1]; text = ""
							for (i = 1; (getline l < f) > 0; i++) if (i == a[2]) { text = l; break }
							close(f); gsub(/^[ \t]+|[ \t]+$/, "", text)
							printf "  %7s%%  %-16s %.70s\n", $1, $2, text; n++ }'
			done
		fi
		echo
		echo "$TOOL, nbody.c, same run:"
		# shellcheck disable=SC2086
		prof_run nbody "$BIN/nbody" "$TMP/nb.ic" "$TILL" 0.01 $WATCH
		echo
		echo "$TOOL, csfc on the 1000-mass-point scene:"
		sh ./gen_scene.sh 1000 "$TMP/scene.csf"
		prof_run csfc "$BUILD/csfc" "$TMP/scene.csf" -o "$TMP/scene.csfb"
	fi
} > "$REPORT"
cat "$REPORT"
