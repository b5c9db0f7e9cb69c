#!/bin/sh
# tests/docs/check.sh CSFC CSFVM DIR - the README's example is the program's, and csf(5) the format's:
#  - the scene shown under "An example" is examples/projectile.csf without its
#    comment lines;
#  - the output shown after "$ csfvm projectile.csfb" is what csfvm prints:
#    the lines shown before "..." are the first lines of the output, the line
#    after it the last, byte for byte.
#  - csf(5) lists the bytecode payload's fields as the table csf_fields in
#    runtime/prog/fields.c does (the one source): the same names, in the same order.
#  - no man page holds a control character other than a tab (a font change
#    written \f in a script that printed it came out as a form feed, which
#    troff drops: "3\fIi\fR" showed as "3Ii R").
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
# the payload's fields: the table's names, a code section's three after "sections"
F=runtime/prog/fields.c
{
	sed -n '/^const csf_field csf_fields\[\] = {/,/^};/p' "$F" |
		sed -n 's/.*\.name = "\([a-z]*\)".*/\1/p; s/^[[:blank:]][A-Z0-9_]*("\([a-z]*\)".*/\1/p; s/^[[:blank:]]SECTION(.*/sections/p' | uniq
	sed -n '/^#define SECTION(/,/[^\\]$/p' "$F" | sed -n 's/.*SEC_[A-Z0-9]*("\([a-z]*\)".*/\1/p'
} >"$T/table"
# csf(5): the name after each .TP of the payload's list, and the three of its "sections" entry
awk '/^\.SS Bytecode/ { on = 1 } on && /^An instruction is/ { exit } !on { next }
	/^\.TP/ { tp = 1; next } /^\.B [a-z]+$/ && (tp || sec) { print $2; if ($2 == "sections") sec = 1 } { tp = 0 }' \
	man/csf.5 | sed -n '/^strings$/,$p' >"$T/man"
if [ "$(wc -l <"$T/table")" -gt 20 ] && cmp -s "$T/table" "$T/man"; then ok
else bad "csf(5) does not list the bytecode fields of $F in order: $(diff "$T/table" "$T/man" | head -n 4 | tr '\n' ' ')"; fi
# the man pages: no control character but a tab (and the newlines)
ctl=$(LC_ALL=C grep -n "$(printf '[\001-\010\013-\037\177]')" man/*.[1-9] | head -n 3 | cut -c1-80)
if [ -z "$ctl" ]; then ok; else bad "a control character in a man page: $(echo "$ctl" | cat -v | tr '\n' ' ')"; fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
