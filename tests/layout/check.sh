#!/bin/sh
# tests/layout/check.sh - the compiler's output has not changed.
#
# Moving code between files must not change what csfc produces. For every
# .csf under examples/, stdlib/ and tests/, this compiles it and takes the
# SHA-256 of: the bytecode (.csfb), its warnings, the --dump-bytecode listing,
# the --explain text, the --emit-c source, and for a model that does not compile, its exit status and
# diagnostics. The digests are compared with tests/layout/csfc.sha256.
# csfc is given the standard library as the relative path stdlib
# (CSF_STDLIB), which it writes where it names one of its files, so that
# every checkout gives the same digests. The files are compiled nproc at a time.
#
#   sh tests/layout/check.sh BUILD          compare (exit 1 on any difference)
#   sh tests/layout/check.sh BUILD --update rewrite the manifest
#
# The manifest is rewritten only by a commit that means to change what the
# compiler emits, and that commit says so.
set -u
MAN=tests/layout/csfc.sha256
CSF_STDLIB=stdlib
export CSF_STDLIB
digest() { sha256sum | cut -c1-64; }
if [ "${1:-}" = --one ]; then
	# check.sh --one BUILD DIR MODEL: the digests of MODEL, in DIR/MODEL's number
	B=$2 T=$3/$4
	m=$(sed -n "$4p" "$3/list")
	mkdir -p "$T"
	d=$(dirname "$m")
	st=0
	timeout 60 "$B/csfc" -I "$d" "$m" -o "$T/m.csfb" >"$T/out" 2>"$T/err" || st=$?
	if [ $st = 0 ]; then
		echo "$m csfb $(digest <"$T/m.csfb")"
		echo "$m warnings $( (cat "$T/out" "$T/err") | digest)"
		timeout 60 "$B/csfc" -I "$d" --dump-bytecode "$m" -o "$T/x.csfb" >"$T/dump" 2>&1
		echo "$m dump $(digest <"$T/dump")"
		timeout 60 "$B/csfc" -I "$d" --explain "$m" -o "$T/x.csfb" >"$T/expl" 2>&1
		echo "$m explain $(digest <"$T/expl")"
		timeout 60 "$B/csfc" -I "$d" --emit-c "$m" -o "$T/x.c" >"$T/c.err" 2>&1
		echo "$m emit-c $(cat "$T/x.c" "$T/c.err" | digest)"
	else
		echo "$m exit$st $( (cat "$T/out" "$T/err") | digest)"
	fi >"$T/digests"
	exit 0
fi
B=$(cd "${1:-build}" && pwd)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
find examples stdlib tests -name '*.csf' | LC_ALL=C sort >"$T/list"
n=$(wc -l <"$T/list")
awk -v n="$n" 'BEGIN { for (i = 1; i <= n; i++) print i }' |
	xargs -P "$(nproc 2>/dev/null || echo 2)" -n 1 sh "$0" --one "$B" "$T"
i=1
while [ $i -le "$n" ]; do
	cat "$T/$i/digests" 2>/dev/null || echo "$(sed -n "${i}p" "$T/list") not checked"
	i=$((i + 1))
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
