#!/bin/sh
# guard.sh - what the stability guard costs (csfvm(1), STABILITY) on the
# benchmarks' scenes: each runs once under csfvm --stats, which times the
# guard's looks (its Jacobian-vector products, the stability polynomial, the
# stiffness ratio --stats asks for) inside the run, so the share is a ratio
# of two times of one process, not of two runs on a busy machine.
# Scenes: the n-body runs of run.sh (NB_N, NB2_N bodies) and its chain, under
# rk8pd (as run.sh times them) and the default (dop853: auto is dop853 alone past 200
# state variables); the chain with fixed
# rk4 steps and with verlet (a look every 2 / (h rho) steps); the gas of
# gas.sh (contacts: products by differences of the right-hand side).
# Writes $OUT/guard.csv and $OUT/guard.txt, and the guard section of $README.
#   BUILD (../build), OUT (results), README (README.md; empty: leave it alone),
#   NB_N (128), NB_TILL (3), NB2_N (2048), NB2_TILL (0.02), NB_BY (0.01),
#   CH_N (100), CH_TILL (50), CH_BY (0.01), GAS_N (1000), GAS_TILL (0.5)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
OUT=${OUT:-results}
README=${README-README.md}
NB_N=${NB_N:-128} NB_TILL=${NB_TILL:-3} NB2_N=${NB2_N:-2048} NB2_TILL=${NB2_TILL:-0.02} NB_BY=${NB_BY:-0.01}
CH_N=${CH_N:-100} CH_TILL=${CH_TILL:-50} CH_BY=${CH_BY:-0.01} GAS_N=${GAS_N:-1000} GAS_TILL=${GAS_TILL:-0.5}
mkdir -p "$OUT"
TMP=$OUT/scratch.tmp
mkdir -p "$TMP"
CSV=$OUT/guard.csv
echo "scene,method,run_seconds,guard_seconds,share,looks,products,steps" > "$CSV"

# one SCENE LABEL ARGS... : csfvm --stats ARGS on $TMP/SCENE.csfb, one CSV row
one() {
	scene=$1 label=$2
	shift 2
	timeout 600 "$BUILD/csfvm" --stats "$@" "$TMP/$scene.csfb" >/dev/null 2>"$TMP/guard.err" || true
	awk -F'[ ,;()]+' -v s="$scene" -v m="$label" '
		/^stats: method/ { for (i = 1; i <= NF; i++) { if ($(i + 1) == "steps") st = $i; if ($i ~ /^[0-9.]+$/) last = $i }; run = last }
		/^stats: stability:/ { for (i = 1; i <= NF; i++) { if ($(i + 1) == "looks") lk = $i; if ($(i + 1) == "Jacobian-vector") pr = $i; if ($i ~ /^[0-9.]+$/) last = $i }; g = last }
		/^stats: stability: not looked at/ { g = 0; lk = 0; pr = 0 }
		END { if (run == "") { print "guard.sh: " s " " m ": no stats" > "/dev/stderr"; exit 1 }
		      printf "%s,%s,%s,%s,%.4f,%d,%d,%d\n", s, m, run, g, g / run, lk, pr, st }' "$TMP/guard.err" >> "$CSV"
}

sh ./gen_nbody.sh "$NB_N" "$NB_TILL" "$NB_BY" "$TMP/g_nb1.csf" /dev/null
sh ./gen_nbody.sh "$NB2_N" "$NB2_TILL" "$NB_BY" "$TMP/g_nb2.csf" /dev/null
sh ./gen_chain.sh "$CH_N" "$CH_TILL" "$CH_BY" "$TMP/g_chain.csf" /dev/null
sh ./gen_gas.sh "$GAS_N" "$GAS_TILL" 0.01 "$TMP/g_gas.csf"
for s in g_nb1 g_nb2 g_chain g_gas; do "$BUILD/csfc" "$TMP/$s.csf" -o "$TMP/$s.csfb"; done
echo "guard: $NB_N and $NB2_N bodies, chain of $CH_N, gas of $GAS_N" >&2
one g_nb1 rk8pd --method rk8pd
one g_nb1 dop853
one g_nb2 rk8pd --method rk8pd
one g_chain rk8pd --method rk8pd
one g_chain dop853
one g_chain "rk4 --fixed --step 0.001" --method rk4 --fixed --step 0.001
one g_chain verlet --method verlet
one g_gas dop853

awk -F, -v nb1="$NB_N" -v nb2="$NB2_N" -v ch="$CH_N" -v gas="$GAS_N" -v t1="$NB_TILL" -v t2="$NB2_TILL" -v tc="$CH_TILL" -v tg="$GAS_TILL" '
BEGIN {
	name["g_nb1"] = nb1 "-body gravity, till " t1; name["g_nb2"] = nb2 "-body gravity, till " t2
	name["g_chain"] = "chain of " ch " masses, till " tc; name["g_gas"] = "gas of " gas " balls, till " tg
	print "The stability guard on the benchmark scenes (one run each under csfvm --stats, which times the guard inside the run; target: under 5 % of the run):\n"
	print "| scene | method | run (s) | guard (s) | share | looks | J v products | steps |"
	print "|---|---|---:|---:|---:|---:|---:|---:|"
}
NR > 1 {
	printf "| %s | %s | %.3f | %.4f | %.1f %% | %d | %d | %d |\n", name[$1], $2, $3, $4, 100 * $5, $6, $7, $8
	if ($5 > worst) worst = $5
}
END { printf "\nLargest share: %.1f %% (%s).\n", 100 * worst, worst < 0.05 ? "target met" : "**target missed**" }' "$CSV" > "$OUT/guard.txt"
cat "$OUT/guard.txt"
sh ./readme_section.sh "$README" guard "$OUT/guard.txt"
