#!/bin/sh
# tests/contacts/methods.sh CSFC CSFVM DIR [SCENE...] - every scene (or the SCENEs named) of contacts (tests/contacts/scenes) under
# every integration method (the dense dop853 and dopri5 too): the mechanics examples, a ball dropped on a
# resting ball, a ball lifted off the floor, balls dropped on a peg, glancing off one and sliding off
# one, two balls that graze each other within one step, and two balls whose paths turn back within one
# step, 1 um into a roof and a peg (apex_touch). Each run must finish (exit 0, every
# row) and every row must be within 1e-6 of the exact motion (the scene's checker), or 1e-4 for the
# multistep msadams and msbdf, whose accuracy at the default tolerance is
# lower on these scenes (restarted at first order at every event; csf(5),
# EVENTS). rk1imp, of first order, moves impacts by some 1e-5 s, so a row
# next to an impact may show its other side: it must finish with every row
# (the checker's count). verlet must be refused before the run, naming the
# methods that can run contacts.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
shift 3
# shellcheck disable=SC2046 # one scene a word
[ $# -gt 0 ] || set -- $(cat "$(dirname "$0")/scenes")
pass=0 fail=0
for m in "$@"; do
	if ! "$CSFC" "$m.csf" -o "$T/mm.csfb" 2>"$T/mm.err"; then
		fail=$((fail + 1)); echo "FAIL: $m: does not compile: $(head -n 1 "$T/mm.err")"; continue
	fi
	uses=$(sed -n '1s/^# uses: //p' "$m.check")
	for method in dop853 dopri5 rk8pd rk2 rk4 rkf45 rkck rk1imp rk2imp rk4imp bsimp msadams msbdf; do
		scale=1
		case $method in msadams | msbdf) scale=100 ;; esac
		if ! "$CSFVM" --method $method "$T/mm.csfb" >"$T/mm.csv" 2>"$T/mm.err"; then
			fail=$((fail + 1)); echo "FAIL: $m --method $method: $(head -n 1 "$T/mm.err")"; continue
		fi
		if [ $method = rk1imp ]; then
			rows=$(sed -n 's/.*finish(\([0-9]*\)).*/\1/p' "$m.check")
			if [ "$(($(wc -l <"$T/mm.csv") - 1))" = "$rows" ]; then pass=$((pass + 1)); else
				fail=$((fail + 1)); echo "FAIL: $m --method rk1imp: not $rows rows"; fi
		elif awk -F, -v tolscale=$scale -f "$m.check" ${uses:+-f "$(dirname "$m")/$uses"} "$T/mm.csv" >"$T/mm.chk" 2>&1; then
			pass=$((pass + 1))
		else
			fail=$((fail + 1)); echo "FAIL: $m --method $method: $(head -n 1 "$T/mm.chk")"
		fi
	done
	"$CSFVM" --method verlet "$T/mm.csfb" >/dev/null 2>"$T/mm.err"
	st=$?
	if [ $st -eq 2 ] && grep -q "verlet" "$T/mm.err" && grep -q "rk8pd" "$T/mm.err"; then
		pass=$((pass + 1))
	else
		fail=$((fail + 1)); echo "FAIL: $m --method verlet: exit $st, $(head -n 1 "$T/mm.err")"
	fi
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
