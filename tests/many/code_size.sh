#!/bin/sh
# tests/many/code_size.sh CSFC DIR CODE_WORDS - the code grows with the scene's text, not
# with its number of objects: every rule is compiled once per shape of object,
# as a loop. The code sections (rhs, out, jac) of bench/gen_scene.sh 10 and of
# gen_scene.sh N have the same number of words, and those of bench/gen_nbody.sh
# 16 and 2048 (pairwise gravity: a loop over pairs); only the data grows.
# A deterministic size, not a time. The sizes are those csfc --dump-bytecode
# heads its sections with, read from the compiled file by CODE_WORDS
# (build/code-words, tests/code_words.c): the listing of the large scene takes
# a minute (five minutes under the sanitizers), its object table listed
# property by property. Prints "N passed, N failed".
CSFC=$1 T=$2 CW=$3
N=${CODE_SIZE_N:-100000}
pass=0 fail=0
sections() { "$CSFC" "$1" -o "$T/cs.csfb" 2>"$T/cs.err" && "$CW" "$T/cs.csfb" 2>>"$T/cs.err" | grep '^section' | tr '\n' ' '; }
check() { # what, small model, large model
	a=$(sections "$2") b=$(sections "$3")
	if [ -n "$a" ] && [ "$a" = "$b" ]; then pass=$((pass + 1)); else
		echo "FAIL: $1: code of the small scene [$a], of the large one [$b] $(head -n 1 "$T/cs.err")"; fail=$((fail + 1))
	fi
}
B=$(dirname "$0")/../../bench
rm -f "$T"/scene10.csf "$T"/sceneN.csf "$T"/nb16.csf "$T"/nb2048.csf
sh "$B/gen_scene.sh" 10 "$T/scene10.csf" && sh "$B/gen_scene.sh" "$N" "$T/sceneN.csf" &&
	sh "$B/gen_nbody.sh" 16 1 0.1 "$T/nb16.csf" "$T/nb16.ic" && sh "$B/gen_nbody.sh" 2048 1 0.1 "$T/nb2048.csf" "$T/nb2048.ic" ||
	{ echo "FAIL: the generators failed"; echo "0 passed, 1 failed"; exit 1; }
check "gen_scene.sh 10 and $N" "$T/scene10.csf" "$T/sceneN.csf"
check "gen_nbody.sh 16 and 2048" "$T/nb16.csf" "$T/nb2048.csf"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
