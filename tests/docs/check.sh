#!/bin/sh
# tests/docs/check.sh CSFC CSFVM DIR - the README's example is the program's:
#  - the scene shown under "An example" is examples/projectile.csf without its
#    comment lines;
#  - the output shown after "$ csfvm projectile.csfb" is what csfvm prints:
#    the lines shown before "..." are the first lines of the output, the line
#    after it the last, byte for byte.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# the first fenced block after the heading "## An example"
awk '/^## An example/ { on = 1 } on && /^```$/ { if (in_block) exit; in_block = 1; next } in_block { print }' README.md >"$T/shown.csf"
grep -v '^#' examples/projectile.csf >"$T/source.csf"
if cmp -s "$T/shown.csf" "$T/source.csf"; then ok
else bad "README's example scene differs from examples/projectile.csf: $(diff "$T/shown.csf" "$T/source.csf" | head -n 3 | tr '\n' ' ')"; fi
# the lines after "$ csfvm projectile.csfb" up to the end of the block
awk '/^\$ csfvm projectile.csfb$/ { on = 1; next } on && /^```$/ { exit } on { print }' README.md >"$T/shown.csv"
if ! "$CSFC" examples/projectile.csf -o "$T/p.csfb" 2>"$T/err" || ! "$CSFVM" "$T/p.csfb" >"$T/out.csv" 2>>"$T/err"; then
	bad "README's example does not run: $(head -n 1 "$T/err")"
else
	head_n=$(awk '/^\.\.\.$/ { exit } { n++ } END { print n + 0 }' "$T/shown.csv")
	tail_n=$(awk '/^\.\.\.$/ { after = 1; next } after { n++ } END { print n + 0 }' "$T/shown.csv")
	{ head -n "$head_n" "$T/out.csv"; [ "$tail_n" -gt 0 ] && echo "..." && tail -n "$tail_n" "$T/out.csv"; } >"$T/real.csv"
	if [ "$head_n" -gt 2 ] && cmp -s "$T/shown.csv" "$T/real.csv"; then ok
	else bad "README's example output is not what csfvm prints: $(diff "$T/shown.csv" "$T/real.csv" | head -n 3 | tr '\n' ' ')"; fi
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
