#!/bin/sh
# tests/piles/mixed.sh CSFC CSFVM DIR - random piles of rough balls of mixed
# sizes and masses (tests/piles/mixed/*.csf), each against check.awk: no
# overlap beyond 1e-9 m, no energy gained between rows beyond 1e-9 of it,
# and from t = 1.5 s every ball at rest with FN + Ff its weight. Each
# stopped at an instant with 3 contacts that "contradict each other"
# (pile136 once a sliding pair at rest stuck as the modes stand) until such
# a cluster stopped its slides by an impulse of friction (csf(5),
# mechanics/rules). The box's width, the balls' masses and radii and mu_s
# are read from the scene. Every process has a time limit.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
HERE=$(dirname "$0")
pass=0 fail=0
for f in "$HERE"/mixed/*.csf; do
	s=$(basename "$f" .csf)
	if ! timeout -k 10 60 "$CSFC" "$f" -o "$T/$s.csfb" 2>"$T/$s.err" ||
		! timeout -k 10 120 "$CSFVM" "$T/$s.csfb" >"$T/$s.csv" 2>"$T/$s.err"; then
		fail=$((fail + 1)); echo "FAIL: $s: $(grep -v '^warning' "$T/$s.err" | head -n 1 | cut -c1-200)"; continue
	fi
	xw=$(sed -n 's/^object wr: point = (\([0-9.]*\), 0, 0) m$/\1/p' "$f")
	mu=$(sed -n 's/^object b0: mu_s = \([0-9.]*\)$/\1/p' "$f")
	balls=$(awk '/: m = .* kg$/ { sub(/:$/, "", $2); m[$2] = $5 } /: radius = .* m$/ { sub(/:$/, "", $2); r[$2] = $5 }
		END { for (b in m) printf "%s:%s:%s ", b, m[b], r[b] }' "$f")
	if awk -v name="$s" -v xw="$xw" -v mu="$mu" -v balls="$balls" -v rest=1.5 -v rows=401 -f "$HERE/check.awk" "$T/$s.csv" >"$T/$s.chk" 2>&1; then
		pass=$((pass + 1))
	else
		fail=$((fail + 1)); echo "FAIL: $(head -n 1 "$T/$s.chk")"
	fi
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
