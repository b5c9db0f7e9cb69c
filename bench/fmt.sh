#!/bin/sh
# fmt.sh - the cost of a CSV cell: csf_fmt_double (runtime/run/fmt.c) beside
# the loop it replaced (%.15g, %.16g, %.17g and strtod: tests/fmt_ref.h), in
# ns per value on five kinds of values (the median of FMT_REPS timings of 1e6
# values; the old loop on 1e5), then FMT_COUNT doubles (half random 64-bit
# patterns, half the other kinds) compared with the old loop one by one
# (bin/fmt, from fmt.c). Exits 1 on a mismatch, which names the value's bits.
# Writes $OUT/fmt.txt and the fmt section of $README (only when all matched).
#   BIN (bin), OUT (results), README (README.md; empty: leave it alone),
#   FMT_COUNT (1e8: some minutes), FMT_REPS (5)
set -eu
cd "$(dirname "$0")"
BIN=${BIN:-bin}
OUT=${OUT:-results}
README=${README-README.md}
FMT_COUNT=${FMT_COUNT:-1e8}
FMT_REPS=${FMT_REPS:-5}
mkdir -p "$OUT"
st=0
"$BIN/fmt" "$FMT_COUNT" "$FMT_REPS" >"$OUT/fmt.txt" || st=$?
{
	echo
	echo "Machine: $(uname -m), $(nproc) cores ($(grep -m 1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //')), shared; $(cc --version | head -n 1)."
} >>"$OUT/fmt.txt"
cat "$OUT/fmt.txt"
[ $st -eq 0 ] && sh ./readme_section.sh "$README" fmt "$OUT/fmt.txt"
exit $st
