#!/bin/sh
# bench/sweep.sh - a sweep of SWEEP_N x SWEEP_N (default 100 x 100 = 1e4)
# variants of a projectile with drag (tests/sweep/launch.csf: the launch
# angle from 0 to 90 deg and the speed from 5 to 50 m/s, 21 rows each):
# variants per second with -j 1, with -j 2 (and the ratio), and under
# mpirun -np 2 (BUILD/csfvm-mpi, where Open MPI is installed). The three
# outputs must be the same bytes. Writes OUT/sweep.csv and OUT/sweep.txt,
# and the sweep section of README.
set -eu
BUILD=${BUILD:-../build} OUT=${OUT:-results} README=${README:-} N=${SWEEP_N:-100}
mkdir -p "$OUT"
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$BUILD/csfc" ../tests/sweep/launch.csf -o "$T/launch.csfb"
SW="--sweep theta=0:90:${N}deg --sweep v0=5:50:$N"
variants=$((N * N))
now() { date +%s.%N; }
# run LABEL COMMAND...: the seconds it takes, the output in $T/LABEL.csv
run() {
	label=$1
	shift
	t0=$(now)
	timeout 3600 "$@" >"$T/$label.csv"
	t1=$(now)
	awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }'
}
# shellcheck disable=SC2086 # SW holds the sweep options
s1=$(run j1 "$BUILD/csfvm" $SW -j 1 "$T/launch.csfb")
# shellcheck disable=SC2086
s2=$(run j2 "$BUILD/csfvm" $SW -j 2 "$T/launch.csfb")
cmp -s "$T/j1.csv" "$T/j2.csv" || { echo "sweep.sh: -j 1 and -j 2 differ" >&2; exit 1; }
rows=$(($(wc -l <"$T/j1.csv") - 1))
sm=""
if [ -x "$BUILD/csfvm-mpi" ] && command -v mpirun >/dev/null 2>&1; then
	# shellcheck disable=SC2086
	sm=$(run mpi mpirun --allow-run-as-root --oversubscribe -np 2 "$BUILD/csfvm-mpi" $SW "$T/launch.csfb")
	cmp -s "$T/j1.csv" "$T/mpi.csv" || { echo "sweep.sh: mpirun -np 2 differs from -j 1" >&2; exit 1; }
fi
{
	echo "mode,variants,rows,seconds,variants_per_second"
	echo "j1,$variants,$rows,$s1,$(awk -v n=$variants -v s="$s1" 'BEGIN { printf "%.0f", n / s }')"
	echo "j2,$variants,$rows,$s2,$(awk -v n=$variants -v s="$s2" 'BEGIN { printf "%.0f", n / s }')"
	[ -z "$sm" ] || echo "mpi2,$variants,$rows,$sm,$(awk -v n=$variants -v s="$sm" 'BEGIN { printf "%.0f", n / s }')"
} >"$OUT/sweep.csv"
{
	echo "A sweep of $variants variants of a projectile with drag (tests/sweep/launch.csf; $rows CSV rows in all),"
	echo "on $(nproc) CPUs ($(date -u +%Y-%m-%d)); the outputs are byte-identical:"
	echo
	echo "| run | seconds | variants/s | speed-up |"
	echo "|---|---|---|---|"
	awk -F, -v s1="$s1" 'NR > 1 { name = $1 == "j1" ? "csfvm -j 1" : $1 == "j2" ? "csfvm -j 2" : "mpirun -np 2 csfvm-mpi"
		printf "| %s | %s | %s | %.2f |\n", name, $4, $5, s1 / $4 }' "$OUT/sweep.csv"
	[ -n "$sm" ] || { echo; echo "(mpirun -np 2: not run, Open MPI is not installed: make deps-mpi)"; }
} >"$OUT/sweep.txt"
cat "$OUT/sweep.txt"
[ -z "$README" ] || sh ./readme_section.sh "$README" sweep "$OUT/sweep.txt"
