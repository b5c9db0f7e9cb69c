#!/bin/sh
# tests/layout/check.sh - the compiler's output has not changed.
#
# Moving code between files must not change what csfc produces. For every
# .csf under examples/, stdlib/ and tests/, this compiles it and takes the
# SHA-256 of: the bytecode (.csfb), its warnings, the --dump-bytecode listing,
# the --explain text, the --emit-c source, and for a model that does not compile, its exit status and
# diagnostics. The digests are compared with tests/layout/csfc.sha256.
#
#   sh tests/layout/check.sh BUILD          compare (exit 1 on any difference)
#   sh tests/layout/check.sh BUILD --update rewrite the manifest
#
# The manifest is rewritten only by a commit that means to change what the
# compiler emits, and that commit says so.
set -u
B=$(cd "${1:-build}" && pwd)
MAN=tests/layout/csfc.sha256
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
for m in $(find examples stdlib tests -name '*.csf' | LC_ALL=C sort); do
	d=$(dirname "$m")
	st=0
	timeout 60 "$B/csfc" -I "$d" "$m" -o "$T/m.csfb" >"$T/out" 2>"$T/err" || st=$?
	if [ $st = 0 ]; then
		echo "$m csfb $(sha256sum <"$T/m.csfb" | cut -c1-64)"
		echo "$m warnings $( (cat "$T/out" "$T/err") | sha256sum | cut -c1-64)"
		timeout 60 "$B/csfc" -I "$d" --dump-bytecode "$m" -o "$T/x.csfb" >"$T/dump" 2>&1
		echo "$m dump $(sha256sum <"$T/dump" | cut -c1-64)"
		timeout 60 "$B/csfc" -I "$d" --explain "$m" -o "$T/x.csfb" >"$T/expl" 2>&1
		echo "$m explain $(sha256sum <"$T/expl" | cut -c1-64)"
		timeout 60 "$B/csfc" -I "$d" --emit-c "$m" -o "$T/x.c" >"$T/c.err" 2>&1
		echo "$m emit-c $(cat "$T/x.c" "$T/c.err" | sha256sum | cut -c1-64)"
	else
		echo "$m exit$st $( (cat "$T/out" "$T/err") | sha256sum | cut -c1-64)"
	fi
done >"$T/now"
if [ "${2:-}" = --update ]; then
	cp "$T/now" "$MAN"
	echo "tests/layout: $(wc -l <"$MAN") digests written to $MAN"
	exit 0
fi
if cmp -s "$T/now" "$MAN"; then
	echo "tests/layout: csfc's output unchanged ($(wc -l <"$MAN") digests)"
	exit 0
fi
echo "tests/layout: csfc's output differs from $MAN:"
diff "$MAN" "$T/now" | sed -n 's/^[<>]/  &/p' | head -n 20
exit 1
