#!/bin/sh
# python.sh - CSF from Python (issue 31's targets; the package csf, csf-python(7)):
#  - a sweep of PY_THETA x PY_V0 (40 x 25 = 1000) variants of the projectile with drag
#    (tests/sweep/launch.csf, 21 rows each) from Python, m.sweep(..., jobs=PY_JOBS), beside
#    csfvm --sweep alone writing its CSV to a file (target: within 1.2x);
#  - a run of PY_N (10 000) mass points watching pos (bench/gen_scene.sh's lattice, 1001 rows,
#    3e7 values) from Python, m.run() and r["pos"], beside the run itself writing no text
#    (bin/runonly, linked with libcsfrt.a: csf_run_sink without CSV, with a row sink that keeps
#    nothing, and without one, the rows' values never read; target: within 1.1x);
#  - SciPy's solve_ivp (DOP853, one call a variant) on the same sweep, where python3-scipy is
#    installed (make deps-peers at the top), at PY_RTOL (1e-12) for rtol and atol.
# Medians of PY_REPS (5) runs (the sweeps: PY_SWEEP_REPS (21), the 10 000-object runs: PY_RUN_REPS
# (11), one at a time in turn, and their least too: this machine's neighbours make single runs vary
# by 30 %), Debian's
# /usr/bin/python3 (PYTHON), the package of BUILD/python.
# Writes $OUT/python.csv, $OUT/python.txt and the python section of $README.
#   BUILD (../build), OUT (results), README (README.md; empty: leave it alone)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
OUT=${OUT:-results}
README=${README-README.md}
PYTHON=${PYTHON:-/usr/bin/python3}
PY_THETA=${PY_THETA:-40} PY_V0=${PY_V0:-25} PY_JOBS=${PY_JOBS:-2} PY_N=${PY_N:-10000} PY_REPS=${PY_REPS:-5}
PY_RTOL=${PY_RTOL:-1e-12} PY_RUN_REPS=${PY_RUN_REPS:-11} PY_SWEEP_REPS=${PY_SWEEP_REPS:-21}
TMP=$OUT/python.tmp CSV=$OUT/python.csv TXT=$OUT/python.txt
mkdir -p "$TMP"
export CSF_STDLIB="${CSF_STDLIB:-$(cd .. && pwd)/stdlib}"
export PYTHONPATH="$(cd "$BUILD" && pwd)/python" PYTHONDONTWRITEBYTECODE=1
if ! "$PYTHON" -c 'import csf, numpy, pandas' 2>/dev/null; then
	echo "python.sh: $PYTHON cannot import csf, numpy and pandas (make python; make deps)" >&2
	exit 1
fi
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
least() { sort -g | head -n 1; }
echo "case,what,value" >"$CSV"

# 1. the sweep from Python, and csfvm alone in turn (python_bench.py)
variants=$((PY_THETA * PY_V0))
"$PYTHON" python_bench.py sweep ../tests/sweep/launch.csf "$PY_THETA" "$PY_V0" "$PY_JOBS" "$PY_SWEEP_REPS" \
	"$(cd "$BUILD" && pwd)/csfvm" "$TMP/sweep.csv" >>"$CSV"

# 2. PY_N mass points: the run itself, then from Python
sh ./gen_scene.sh "$PY_N" | sed 's/^inc t .*/inc t till 1 by 0.001 watch pos/' >"$TMP/mp.csf"
"$BUILD/csfc" -w "$TMP/mp.csf" -o "$TMP/mp.csfb"
# (each alternately, so that the machine's load weighs on both alike)
i=0
while [ $i -lt "$PY_RUN_REPS" ]; do
	bin/runonly "$TMP/mp.csfb" 1 sink >>"$TMP/sink"
	bin/runonly "$TMP/mp.csfb" 1 >>"$TMP/none"
	"$PYTHON" python_bench.py run "$TMP/mp.csfb" 1 | sed -n 's/^run,call,//p' >>"$TMP/py"
	i=$((i + 1))
done
for f in sink none py; do echo "run,$f,$(median <"$TMP/$f")"; echo "run,${f}_least,$(least <"$TMP/$f")"; done >>"$CSV"

# 3. SciPy's solve_ivp on the sweep
scipy=""
if "$PYTHON" -c 'import scipy' 2>/dev/null; then
	scipy=$("$PYTHON" -c 'import scipy; print(scipy.__version__)')
	"$PYTHON" python_bench.py scipy "$PY_THETA" "$PY_V0" "$PY_RTOL" "$(( (PY_REPS + 1) / 2 ))" >>"$CSV"
fi
rm -rf "$TMP"

v() { awk -F, -v c="$1" -v w="$2" '$1 == c && $2 == w { print $3 }' "$CSV"; }
{
	echo "| case | measured | target |"
	echo "|---|---|---|"
	awk -v a="$(v sweep csfvm)" -v p="$(v sweep call)" -v al="$(v sweep csfvm_least)" -v pl="$(v sweep call_least)" \
		-v c="$(v sweep compile_and_call)" -v n="$variants" -v j="$PY_JOBS" -v rows="$(v sweep rows)" \
		-v e="$(v sweep max_error)" 'BEGIN {
		printf "| a sweep of %d variants of the projectile (%d rows), -j %d | m.sweep() %.3f s against csfvm --sweep alone %.3f s (CSV to a file): %.2fx (the least of each: %.3f s against %.3f s, %.2fx); with csf.compile, %.3f s; largest error from the closed form %s m | within 1.2x |\n",
			n, rows, j, p, a, p / a, pl, al, pl / al, c, e }'
	awk -v r="$(v run sink)" -v r0="$(v run none)" -v p="$(v run py)" -v rl="$(v run sink_least)" \
		-v r0l="$(v run none_least)" -v pl="$(v run py_least)" -v n="$PY_N" 'BEGIN {
		printf "| %d mass points watching pos, 1001 rows | m.run() and r[\"pos\"] (1001 x %d x 3 doubles, fresh memory) %.3f s against the run itself writing no text, its rows handed to a sink that keeps nothing, %.3f s: %.2fx (the least of each: %.3f s against %.3f s, %.2fx); against the run whose rows are never read, %.3f s: %.2fx (least %.3f s, %.2fx) | within 1.1x |\n",
			n, n, p, r, p / r, pl, rl, pl / rl, r0, p / r0, r0l, pl / r0l }'
	if [ -n "$scipy" ]; then
		awk -v s="$(v scipy call)" -v p="$(v sweep call)" -v n="$variants" -v f="$(v scipy nfev)" -v e="$(v scipy max_error)" \
			-v cf="$(v sweep rhs)" -v ce="$(v sweep max_error)" -v ver="$scipy" -v tol="$PY_RTOL" 'BEGIN {
			printf "| SciPy %s solve_ivp (DOP853, rtol = atol = %s) on the same %d variants, one call each | %.3f s, %.1fx m.sweep(); %d evaluations (CSF: %d); largest error %s m (CSF: %s m) | (for comparison) |\n",
				ver, tol, n, s, s / p, f, cf, e, ce }'
	else
		echo "| SciPy solve_ivp on the same sweep | (not run: python3-scipy is not installed; make deps-peers) | (for comparison) |"
	fi
	echo
	echo "Medians of $PY_SWEEP_REPS sweeps and $PY_RUN_REPS runs of the $PY_N mass points, each in turn with its baseline ($PY_REPS for m.sweep with csf.compile, $(( (PY_REPS + 1) / 2 )) for SciPy), $("$PYTHON" -c 'import sys; print("Python %d.%d.%d" % sys.version_info[:3])'), numpy $("$PYTHON" -c 'import numpy; print(numpy.__version__)'); $(nproc) CPUs, $(date -u +%Y-%m-%d)."
} >"$TXT"
cat "$TXT"
sh ./readme_section.sh "$README" python "$TXT"
