#!/bin/sh
# tests/contacts/drop.sh CSFC CSFVM DIR - a ball dropped onto a floor or an
# incline, in every placement: the floor at z = 0, 0.7 m, 1e3 m and 1e6 m;
# inclines of 5, 20 and 45 degrees (mu_s 0.5, mu_k 0.4: it sticks on the
# first two, below the friction angle of 26.6 degrees, and slides on the
# third); a point and a sphere of radius 0.1 m; output every 0.1 ms to
# 100 ms. Every row is checked against the exact motion by drop.awk.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
HERE=$(dirname "$0")
pass=0 fail=0
drop() { # theta zf r by(ms) e till
	theta=$1 zf=$2 r=$3 by=$4 e=$5 till=$6
	h0=1 mus=0.5 muk=0.4
	[ "$theta" = 0 ] && mus=0 muk=0
	cat >"$T/drop.csf" <<SCENE
using mechanics/mass_point
object ball: mass_point
object ball: radius = $r m
object ball: cr = $e
object ball: mu_s = $mus
object ball: mu_k = $muk
object ball: pos = (-($r + $h0) * sin($theta deg), 0, $zf + ($r + $h0) * cos($theta deg)) m
object floor: plane
object floor: point = (0, 0, $zf) m
object floor: normal = (-sin($theta deg), 0, cos($theta deg))
using mechanics/rules
rule F: W = g.mul(m)
inc t till $till s by $by ms watch ball.pos, ball.v, ball.FN, ball.Ff
SCENE
	rows=$(awk -v till="$till" -v by="$by" 'BEGIN { printf "%d", till * 1000 / by + 1.5 }')
	if ! "$CSFC" "$T/drop.csf" -o "$T/drop.csfb" 2>"$T/drop.err"; then
		fail=$((fail + 1)); echo "FAIL: drop theta=$theta zf=$zf r=$r by=$by ms: $(head -n 1 "$T/drop.err")"; return
	fi
	if ! timeout 60 "$CSFVM" "$T/drop.csfb" >"$T/drop.out" 2>"$T/drop.err"; then
		fail=$((fail + 1)); echo "FAIL: drop theta=$theta zf=$zf r=$r by=$by ms: csfvm: $(head -n 1 "$T/drop.err")"; return
	fi
	if awk -v theta="$theta" -v zf="$zf" -v r="$r" -v h0=$h0 -v e="$e" -v mus=$mus -v muk=$muk -v by="$(awk -v b="$by" 'BEGIN { print b / 1000 }')" \
		-v rows_expected="$rows" -f "$HERE/drop.awk" "$T/drop.out" >"$T/drop.chk" 2>&1; then
		pass=$((pass + 1)); [ -n "${VERBOSE:-}" ] && cat "$T/drop.chk"
	else
		fail=$((fail + 1)); echo "FAIL: drop: $(head -n 2 "$T/drop.chk")"
	fi
}
for zf in 0 0.7 1e3 1e6; do
	for r in 0 0.1; do
		for by in 0.1 1 2 10 100; do drop 0 $zf $r $by 0.5 2; done
	done
done
for theta in 5 20 45; do
	for zf in 0 0.7; do
		for r in 0 0.1; do
			for by in 1 10; do drop $theta $zf $r $by 0.6 3; done
		done
	done
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
