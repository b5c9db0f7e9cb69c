#!/bin/sh
# gas.sh - the contact benchmark (see README.md, "Contacts: a dilute gas").
# Run by `make` and `make gas` in bench/.
#
#   BUILD     directory holding csfc and csfvm            (default ../build)
#   BIN       directory holding timeit                    (default bin)
#   OUT       where gas.csv and gas.txt go                (default results)
#   README    file whose gas section is rewritten         (default README.md;
#             empty: leave it alone)
#   GAS_N     the numbers of balls                        (default "500 1000 2000 4000")
#   GAS_TILL  the end time of each run, one per N         (default "1 0.5 0.2 0.08")
#   GAS_BY    the output step                             (default 0.01)
#
# For each N: gen_gas.sh writes the scene (N elastic balls in a box of six
# planes), csfc compiles it (timed), and one run of csfvm --stats gives the
# steps, right-hand side evaluations, events, the contact routine's
# candidate pairs and the run's seconds (the integration: not the start-up).
# Each run's events are its sample: the ends are chosen for some 50 to 300
# collisions a run, in a few seconds. Then per right-hand side evaluation,
# events per simulated second, per event, and the log-log slope of each
# column from the first N to the last.
set -eu

BUILD=${BUILD:-../build}
BIN=${BIN:-bin}
OUT=${OUT:-results}
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
README=${README-README.md}
GAS_N=${GAS_N:-500 1000 2000 4000}
GAS_TILL=${GAS_TILL:-1 0.5 0.2 0.08}
GAS_BY=${GAS_BY:-0.01}

CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
for p in "$CSFC" "$CSFVM" "$BIN/timeit"; do
	[ -x "$p" ] || { echo "gas.sh: $p is missing: build it first (make bench from the top)" >&2; exit 2; }
done

TMP=$OUT/gas.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
say() { printf '%s\n' "$*" >&2; }

CSV=$TMP/gas.csv
echo "n,till,compile_s,bytes,steps,evals,events,candidates,seconds" > "$CSV"
# shellcheck disable=SC2086 # GAS_TILL is a list of numbers
set -- $GAS_TILL
for n in $GAS_N; do
	till=${1:-0.1}
	[ $# -gt 0 ] && shift
	sh ./gen_gas.sh "$n" "$till" "$GAS_BY" "$TMP/gas$n.csf"
	cs=$("$BIN/timeit" /dev/null "$CSFC" "$TMP/gas$n.csf" -o "$TMP/gas$n.csfb" | awk '{ print $1 }')
	[ -s "$TMP/gas$n.csfb" ] || { say "gas.sh: the gas of $n balls does not compile"; exit 1; }
	"$CSFVM" --stats "$TMP/gas$n.csfb" > /dev/null 2> "$TMP/gas$n.stats" ||
		{ say "gas.sh: the gas of $n balls does not run: $(head -n 1 "$TMP/gas$n.stats")"; exit 1; }
	line=$(sed -n 's/^stats: .*, \([0-9]*\) steps (.*), \([0-9]*\) right-hand side .*, \([0-9]*\) events, \([0-9.]*\) contact pairs .*, \([0-9.]*\) s$/\1,\2,\3,\4,\5/p' "$TMP/gas$n.stats")
	[ -n "$line" ] || { say "gas.sh: no stats line for the gas of $n balls"; exit 1; }
	echo "$n,$till,$cs,$(wc -c < "$TMP/gas$n.csfb" | tr -d ' '),$line" >> "$CSV"
	say "gas: $n balls, till $till s: $(cat "$TMP/gas$n.stats")"
done

mkdir -p "$OUT"
cp "$CSV" "$OUT/gas.csv"
cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
awk -F, -v by="$GAS_BY" -v date="$(date -u '+%Y-%m-%d %H:%M UTC')" -v host="$(uname -sm)" -v cpu="${cpu:-unknown}" '
NR == 1 { next }
{ k++; n[k] = $1; till[k] = $2; comp[k] = $3; bytes[k] = $4; steps[k] = $5; ev[k] = $6; evs[k] = $7; cand[k] = $8; sec[k] = $9 }
function slope(a, b) { return (a > 0 && b > 0 && n[k] != n[1]) ? sprintf("%.2f", log(b / a) / log(n[k] / n[1])) : "-" }
END {
	if (!k) exit
	printf "CSF contact benchmark, %s, %s, %s\n\n", date, host, cpu
	printf "A dilute gas (`gen_gas.sh N`: N elastic balls of radius 0.05 m in a box of six planes, volume fraction about 0.4 %%, no gravity), one run of each, output every %s s, figures from `csfvm --stats` (the run: integration, events and output, not the start-up):\n\n", by
	printf "| balls | till (s) | compile (s) | bytecode (bytes) | steps | RHS evaluations | events | candidate pairs (mean) | run (s) | per RHS evaluation (us) | events per simulated s | per event (ms) | evaluations per event |\n"
	printf "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
	for (i = 1; i <= k; i++) {
		pe[i] = sec[i] / ev[i] * 1e6; eps[i] = evs[i] / till[i]; te[i] = evs[i] ? sec[i] / evs[i] * 1e3 : 0; epe[i] = evs[i] ? ev[i] / evs[i] : 0
		printf "| %d | %s | %.3f | %d | %d | %d | %d | %.1f | %.3f | %.2f | %.0f | %.2f | %.0f |\n", n[i], till[i], comp[i], bytes[i], steps[i], ev[i], evs[i], cand[i], sec[i], pe[i], eps[i], te[i], epe[i]
	}
	printf "| exponent (log-log slope, %d to %d) | | %s | %s | | | | %s | | **%s** | %s | %s | %s |\n", n[1], n[k], slope(comp[1], comp[k]), slope(bytes[1], bytes[k]), \
		slope(cand[1], cand[k]), slope(pe[1], pe[k]), slope(eps[1], eps[k]), slope(te[1], te[k]), slope(epe[1], epe[k])
	x = (pe[1] > 0 && n[k] != n[1]) ? log(pe[k] / pe[1]) / log(n[k] / n[1]) : 0
	printf "\nTime per right-hand side evaluation grows as N^%.2f from %d to %d balls (target: no faster than N^1.3: %s).\n", x, n[1], n[k], x <= 1.3 ? "target met" : "**target missed**"
}' "$CSV" > "$OUT/gas.txt"
cat "$OUT/gas.txt"

sh ./readme_section.sh "$README" gas "$OUT/gas.txt"
