#!/bin/sh
# tests/arrays/check.sh CSFC CSFVM DIR - object arrays (DECISIONS §11), against exact answers:
#  - N projectiles with linear drag in an array (N = 100000; 10000 under the sanitizers), each
#    launched at its own v0 = (3 + i/1000, 1, 10 - i/2000) m/s (gen_projectiles.sh): ten sampled
#    members at every row against the closed form to 1e-9 m, both as compiled (the unwatched
#    members left out) and with --keep-all (every member integrated);
#  - the --keep-all bytecode holds nothing per member but its values and its name;
#  - --explain says the members left out between two watched ones in one line, and each property
#    of the array's members in one line of its parameters (first and last values, or the one);
#  - the same array read from a data file gives the same output, byte for byte, and the same
#    scene written object by object (2000 objects) the same rows;
#  - `watch p.pos` names every member's columns p[k].pos.x [m] ..., and -D sets one member;
#  - a ring of 1000 masses and springs (ring.csf, neighbour rules `for node[i], node[i+1]` and a
#    sum) oscillates in its normal mode at the exact frequency, to 1e-9 m, its momentum (a sum)
#    stays 0 to 1e-12 and its assertion on the summed mass holds.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
D=$(dirname "$0")
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { if "$@"; then ok; else bad "$*"; fi; }
comp() { # comp NAME SCENE [CSFC OPTIONS]: $T/NAME.csfb, csfc's words in $T/NAME.err
	n=$1 f=$2
	shift 2
	"$CSFC" "$@" "$f" -o "$T/$n.csfb" 2>"$T/$n.err" && return 0
	bad "$n: does not compile: $(head -n 1 "$T/$n.err")"
	return 1
}
N=100000
[ -n "$CSF_SAN" ] && N=10000
S="0 7 99 1234 2500 4321 5000 7777 9998 $((N - 1))"
W=$(for k in $S; do printf 'p[%d].pos, ' "$k"; done | sed 's/, $//')

# the closed form of linear drag (tau = m/k = 10 s) for the members in S, at every row
closed() { # closed CSV
	awk -F, -v s="$S" 'function abs(x) { return x < 0 ? -x : x }
		BEGIN { n = split(s, id, " ") }
		NR > 1 { tau = 10; g = 9.80665; e = 1 - exp(-$1 / tau)
			for (j = 1; j <= n; j++) {
				i = id[j]; c = 2 + 3 * (j - 1)
				x = (3 + i / 1000) * tau * e; y = tau * e; z = tau * ((10 - i / 2000) + g * tau) * e - g * tau * $1
				if (abs($c - x) > 1e-9 || abs($(c + 1) - y) > 1e-9 || abs($(c + 2) - z) > 1e-9) {
					printf "FAIL: p[%d] at t=%s: (%.17g, %.17g, %.17g), not (%.17g, %.17g, %.17g)\n", i, $1, $c, $(c + 1), $(c + 2), x, y, z
					exit 1 }
			}
			rows++ }
		END { exit rows != 41 }' "$1"
}

sh "$D/gen_projectiles.sh" $N array "$W" >"$T/pa.csf"
if comp pa "$T/pa.csf"; then
	check grep -q "and $((N - 13)) more objects from 'p\[" "$T/pa.err"
	"$CSFVM" "$T/pa.csfb" >"$T/pa.csv" && check closed "$T/pa.csv"
	check test "$(head -n 1 "$T/pa.csv" | cut -d, -f2)" = "p[0].pos.x [m]"
	# --explain: the members left out between two watched ones as one line
	"$CSFC" --explain "$T/pa.csf" 2>/dev/null >"$T/pa.explain"
	check grep -q '^objects p\[1\] \.\. p\[6\] (6 members): left out: nothing watched' "$T/pa.explain"
	# the ten members kept, alone or in runs of consecutive ones
	check test "$(awk '/left out/ { next } /^object p/ { n++ } /^objects p/ && match($0, /\([0-9]+ members\)/) { n += substr($0, RSTART + 1, RLENGTH - 10) } END { print n }' "$T/pa.explain")" -eq 10
fi
if comp pak "$T/pa.csf" --keep-all; then
	"$CSFVM" "$T/pak.csfb" >"$T/pak.csv" && check closed "$T/pak.csv"
	# --explain's parameters: a line per property of the array, not per member; v0 first and last
	"$CSFC" --explain --keep-all "$T/pa.csf" 2>/dev/null >"$T/pak.explain"
	check grep -qxF "  p[0..$((N - 1))].m = 0.5 kg ($N members, the same)" "$T/pak.explain"
	check awk -v n=$N 'function abs(x) { return x < 0 ? -x : x }
		index($0, "  p[0.." n - 1 "].v = (3, 1, 10) .. (") == 1 && index($0, ") m/s (" n " members, each its own)") {
			split(substr($0, index($0, ".. (") + 4), v, /[,)] */)
			ok = abs(v[1] - (3 + (n - 1) / 1000)) < 1e-12 && v[2] == 1 && abs(v[3] - (10 - (n - 1) / 2000)) < 1e-12 }
		END { exit !ok }' "$T/pak.explain"
	check test "$(sed -n '/^parameters/,$p' "$T/pak.explain" | grep -c '^  p\[')" -lt 20
	# the bytecode: per member only its own values (v, three doubles: 24 bytes) and its name
	# ("p[K]" and a NUL); its entries in the tables of properties, targets and state are
	# progressions (csf(5)), a few hundred bytes whatever N: under 64 KiB beside the members' share
	check awk -v n=$N -v size="$(wc -c <"$T/pak.csfb")" 'BEGIN {
		for (i = 0; i < n; i++) own += 24 + length("p[" i "]") + 1
		exit !(size > own && size - own < 65536) }'
fi
# from a data file: the same output, byte for byte
sh "$D/gen_projectiles.sh" $N data "$W" "$T/proj.csv" >"$T/pd.csf"
if comp pd "$T/pd.csf" && [ -f "$T/pa.csv" ]; then
	"$CSFVM" "$T/pd.csfb" >"$T/pd.csv" && check cmp -s "$T/pa.csv" "$T/pd.csv"
fi
# written out object by object: the same rows
W2="p[0].pos, p[7].pos, p[1999].pos"
sh "$D/gen_projectiles.sh" 2000 array "$W2" >"$T/qa.csf"
sh "$D/gen_projectiles.sh" 2000 list "$W2" >"$T/ql.csf"
if comp qa "$T/qa.csf" && comp ql "$T/ql.csf"; then
	"$CSFVM" "$T/qa.csfb" | tail -n +2 >"$T/qa.csv" && "$CSFVM" "$T/ql.csfb" | tail -n +2 >"$T/ql.csv" &&
		check cmp -s "$T/qa.csv" "$T/ql.csv"
	check test "$(wc -l <"$T/qa.csv")" = 41
fi
# every member watched, and -D on one
sh "$D/gen_projectiles.sh" 4 array "p.pos" >"$T/p4.csf"
if comp p4 "$T/p4.csf"; then
	check test "$("$CSFVM" "$T/p4.csfb" | head -n 1)" = "t,p[0].pos.x [m],p[0].pos.y [m],p[0].pos.z [m],p[1].pos.x [m],p[1].pos.y [m],p[1].pos.z [m],p[2].pos.x [m],p[2].pos.y [m],p[2].pos.z [m],p[3].pos.x [m],p[3].pos.y [m],p[3].pos.z [m]"
	# p[3] launched at rest falls as z = -g tau^2 (e^(-t/tau) - 1 + t/tau); x = y = 0
	"$CSFVM" -D 'p[3].v=(0,0,0) m/s' "$T/p4.csfb" >"$T/p4.csv" &&
		check awk -F, 'function abs(x) { return x < 0 ? -x : x }
			NR > 1 { z = -9.80665 * 100 * (exp(-$1 / 10) - 1 + $1 / 10)
				if ($11 != 0 || $12 != 0 || abs($13 - z) > 1e-9) exit 1; n++ }
			END { exit n != 41 }' "$T/p4.csv"
fi
# the ring in its normal mode: x_j(t) = j s + A cos(2 pi k j/N) cos(w t), w = 40 sin(pi/10)
if comp ring "$D/ring.csf"; then
	check test ! -s "$T/ring.err"
	"$CSFVM" --tol 1e-12 "$T/ring.csfb" >"$T/ring.csv"
	check test $? = 0
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		BEGIN { pi = atan2(0, -1); w = 40 * sin(pi / 10); split("0 1 3 998 999", j, " ") }
		NR > 1 { for (k = 1; k <= 5; k++) {
				x = j[k] * 0.01 + 0.001 * cos(2 * pi * 100 * j[k] / 1000) * cos(w * $1)
				if (abs($(k + 1) - x) > 1e-9) { printf "FAIL: node[%d] at t=%s: %.17g, not %.17g\n", j[k], $1, $(k + 1), x; exit 1 } }
			if (abs($7) > 1e-12 || $8 != 0 || $9 != 0) { printf "FAIL: momentum %s at t=%s\n", $7, $1; exit 1 }
			n++ }
		END { exit n != 21 }' "$T/ring.csv"
fi
# one member's own value after every member's: osc[3] and osc[4] take theirs, the rest 0.25 kg;
# each on a spring of 1 N/m from x = 1 m: x = cos(t sqrt(k/m)); the other order is an error
cat >"$T/own.csf" <<'EOS'
using mechanics/mass_point
global k = 1 N/m
object osc[0..4]: mass_point
object osc[i]: m = 0.25 kg
object osc[i]: pos = (1, 0, 0.1 * i) m
object osc[3]: m = 1 kg
object osc[4]: m = 4 kg
using mechanics/rules
rule F: S = pos.mul(-k)
inc t till 2 s by 0.1 s watch osc.pos
EOS
if comp own "$T/own.csf"; then
	"$CSFVM" "$T/own.csfb" >"$T/own.csv"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { n++; split("4 4 4 1 0.25", w2, " ")
			for (j = 0; j < 5; j++) if (abs($(2 + 3 * j) - cos($1 * sqrt(w2[j + 1]))) > 1e-9) exit 1 }
		END { exit n != 21 }' "$T/own.csv"
fi
printf 'using mechanics/mass_point\nobject p[0..2]: mass_point\nobject p[1]: m = 2 kg\nobject p[i]: m = 1 kg\n' >"$T/own2.csf"
"$CSFC" "$T/own2.csf" -o "$T/own2.csfb" 2>"$T/own2.err"
check test $? -eq 1
check grep -q "own2.csf:4:14: error: property 'm' of object 'p\[1\]' is already defined" "$T/own2.err"
check grep -q "one member's own value comes after the value every member takes" "$T/own2.err"

# Members share their array's properties (csf(5), OBJECT ARRAYS): six balls b[i] of radius 0.02 + 0.005 i m
# dropped from 0.3 + 0.1 i m onto a floor, restitution 0.5 (b[5] its own 0.9, b[4] its own mass), in
# one shape with an object of their kind (ball, elastic) and a point dropped from b[2]'s place raised
# 1 m (top: it reads b[2]'s value, which then is b[2]'s own). Each against the closed form of its
# bounces (at rest once their times add up), to 1e-9 m; the same scene written object by object gives
# the same rows; -D sets one member's restitution and refuses b[2].pos, folded into top.pos; b[4]
# watched alone (the others left out) follows its closed form too.
cat >"$T/lean.csf" <<'EOS'
using mechanics/mass_point
object floor: plane
object floor: point = (0, 0, 0) m
object floor: normal = (0, 0, 1)
object ball: mass_point
object ball: pos = (-1, 0, 0.5) m
object ball: radius = 0.05 m
object b[0..5]: mass_point
object b[i]: radius = (0.02 + 0.005 * i) m
object b[i]: pos = (0.5 * i, 0, 0.3 + 0.1 * i) m
object b[i]: cr = 0.5
object b[4]: m = 3 kg
object b[5]: cr = 0.9
object top: mass_point
object top: pos = b[2].pos + (0.2, 0, 1) m
rule F: W = g.mul(m)
using mechanics/rules
inc t till 1 s by 0.05 s watch b.pos, ball.pos, top.pos
EOS
{
	sed -n 1,7p "$T/lean.csf"
	for i in 0 1 2 3 4 5; do
		printf 'object b%d: mass_point\nobject b%d: radius = (0.02 + 0.005 * %d) m\n' $i $i $i
		printf 'object b%d: pos = (0.5 * %d, 0, 0.3 + 0.1 * %d) m\nobject b%d: cr = %s\n' $i $i $i $i "$([ $i = 5 ] && echo 0.9 || echo 0.5)"
		[ $i = 4 ] && printf 'object b4: m = 3 kg\n'
	done
	printf 'object top: mass_point\nobject top: pos = b2.pos + (0.2, 0, 1) m\nrule F: W = g.mul(m)\nusing mechanics/rules\n'
	printf 'inc t till 1 s by 0.05 s watch b0.pos, b1.pos, b2.pos, b3.pos, b4.pos, b5.pos, ball.pos, top.pos\n'
} >"$T/leanl.csf"
bounces() { # bounces CSV [CR1 [K]]: every row against the closed forms (b[1]'s restitution CR1, 0.5 if not
	# given); with K, the CSV holds b[K].pos alone
	awk -F, -v cr1="${2:-0.5}" -v only="${3:-}" 'function abs(x) { return x < 0 ? -x : x }
		function zb(t, z0, r, c,   g, t1, v) { # a ball of radius r dropped from z0 at rest, restitution c
			g = 9.80665; t1 = sqrt(2 * (z0 - r) / g)
			if (t <= t1) return z0 - g * t * t / 2
			v = c * g * t1; t -= t1
			if (c < 1 && t >= 2 * v / (g * (1 - c))) return r
			while (t > 2 * v / g) { t -= 2 * v / g; v *= c }
			return r + v * t - g * t * t / 2 }
		NR > 1 { n++
			for (i = only == "" ? 0 : only; i < (only == "" ? 6 : only + 1); i++) {
				z = zb($1, 0.3 + 0.1 * i, 0.02 + 0.005 * i, i == 5 ? 0.9 : i == 1 ? cr1 : 0.5)
				c = only == "" ? 3 * i : 0
				if (abs($(4 + c) - z) > 1e-9 || $(2 + c) != 0.5 * i) { printf "FAIL: b[%d] at t=%s\n", i, $1; exit 1 } }
			if (only == "" && (abs($22 - zb($1, 0.5, 0.05, 1)) > 1e-9 || abs($25 - zb($1, 1.5, 0, 1)) > 1e-9 || $23 != 1.2)) exit 1 }
		END { exit n != 21 }' "$1"
}
if comp lean "$T/lean.csf" && comp leanl "$T/leanl.csf"; then
	"$CSFVM" "$T/lean.csfb" >"$T/lean.csv" && "$CSFVM" "$T/leanl.csfb" >"$T/leanl.csv"
	check bounces "$T/lean.csv"
	tail -n +2 "$T/lean.csv" >"$T/lean.rows" && tail -n +2 "$T/leanl.csv" >"$T/leanl.rows"
	check cmp -s "$T/lean.rows" "$T/leanl.rows"
	"$CSFVM" -D 'b[1].cr=1' "$T/lean.csfb" >"$T/lean1.csv"
	check bounces "$T/lean1.csv" 1
	"$CSFVM" -D 'b[2].pos=(1,0,1) m' "$T/lean.csfb" >/dev/null 2>"$T/lean2.err"
	check test $? -eq 2
	check grep -q "b\[2\].pos cannot be overridden: its value is folded at compile time into the value of top.pos" "$T/lean2.err"
fi
sed 's/ watch b.pos, ball.pos, top.pos/ watch b[4].pos/' "$T/lean.csf" >"$T/lean4.csf"
if comp lean4 "$T/lean4.csf"; then
	"$CSFVM" "$T/lean4.csfb" >"$T/lean4.csv"
	check bounces "$T/lean4.csv" 0.5 4
fi
# a kind's value that reads a member's own (k = 4 m 1/s^2, from each member's mass in a data file):
# x = x0 cos 2t, y = (v0 / 2) sin 2t for q[i] from (i + 1, 0, 0) m at (0, i, 0) m/s
printf 'm [kg],pos.x [m],pos.y [m],pos.z [m]\n1,1,0,0\n2,2,0,0\n4,3,0,0\n' >"$T/q.csv"
cat >"$T/kind.csf" <<'EOS'
def probe:
    m = 1 kg
    k = m * 4 1/s^2
    vector pos = (0, 0, 0) m
    vector v = (0, 0, 0) m/s
object q[]: from "q.csv"
object q[i]: probe
object q[i]: v = (0, i, 0) m/s
rule: v' = pos.mul(-k / m)
rule: pos' = v
inc t till 1 s by 0.25 s watch q.pos, q.k
EOS
if comp kind "$T/kind.csf"; then
	"$CSFVM" --tol 1e-12 "$T/kind.csfb" >"$T/kind.csv"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { n++
			for (i = 0; i < 3; i++)
				if (abs($(2 + 3 * i) - (i + 1) * cos(2 * $1)) > 1e-9 || abs($(3 + 3 * i) - i / 2 * sin(2 * $1)) > 1e-9) exit 1
			if ($11 != 4 || $12 != 8 || $13 != 16) exit 1 }
		END { exit n != 5 }' "$T/kind.csv"
fi
# two arrays and an object of one kind in one shape, on springs of 2 N/m under gravity; the array a
# is named as mass_point's acceleration is: `watch a.pos` is its members' positions. a[i] (1 kg) from
# (i, 0, 0) m at (0, 0, 1 + i) m/s: x = i cos wt, z = -g/2 (1 - cos wt) + (1 + i)/w sin wt, w = sqrt 2;
# b[1] (2 kg) from (0, 1, 1) m at (1, 0, 0) m/s: x = sin t, z = (1 + g) cos t - g
cat >"$T/two.csf" <<'EOS'
using mechanics/mass_point
object a[0..3]: mass_point
object a[i]: pos = (i, 0, 0) m
object a[i]: v = (0, 0, 1 + i) m/s
object c0: mass_point
object c0: pos = (0, 5, 0) m
object b[0..2]: mass_point
object b[j]: pos = (0, j, 1) m
object b[j]: m = (1 + j) kg
object b[1]: v = (1, 0, 0) m/s
rule F: W = g.mul(m)
rule F: S = pos.mul(-2 N/m)
using mechanics/rules
inc t till 1 s by 0.1 s watch a.pos, b.pos, c0.pos
EOS
if comp two "$T/two.csf"; then
	"$CSFVM" --tol 1e-12 "$T/two.csfb" >"$T/two.csv"
	check test "$(head -n 1 "$T/two.csv" | cut -d, -f1-2)" = "t,a[0].pos.x [m]"
	check awk -F, 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { k++; t = $1; w = sqrt(2); g = 9.80665
			for (i = 0; i < 4; i++)
				if (abs($(2 + 3 * i) - i * cos(w * t)) > 1e-9 ||
				    abs($(4 + 3 * i) - (-g / 2 * (1 - cos(w * t)) + (1 + i) / w * sin(w * t))) > 1e-9) exit 1
			if (abs($17 - sin(t)) > 1e-9 || abs($19 - ((1 + g) * cos(t) - g)) > 1e-9) exit 1 }
		END { exit k != 11 }' "$T/two.csv"
fi
# the momentum of N/5 projectiles, a sum over them: P = e^(-t/tau) P0 + M g tau (1 - e^(-t/tau)), to 1e-9
# relative; the members summed keep sharing their array's properties (a sum over 1e4 members took 23 s
# when they were read in N^2 steps)
NS=$((N / 5))
sh "$D/gen_projectiles.sh" "$NS" array "P" |
	sed 's/^using mechanics\/mass_point$/&\nglobal P = (0, 0, 0) kg*m\/s/; s/^using mechanics\/rules$/&\nrule: P = sum(m*v for p)/' >"$T/psum.csf"
if comp psum "$T/psum.csf"; then
	"$CSFVM" --tol 1e-12 "$T/psum.csfb" >"$T/psum.csv"
	check awk -F, -v n="$NS" 'function abs(x) { return x < 0 ? -x : x }
		NR > 1 { k++; e = exp(-$1 / 10); M = 0.5 * n
			px = 0.5 * (3 * n + n * (n - 1) / 2000) * e; py = 0.5 * n * e
			pz = 0.5 * (10 * n - n * (n - 1) / 4000) * e + M * -9.80665 * 10 * (1 - e)
			if (abs($2 - px) > 1e-9 * abs(px) || abs($3 - py) > 1e-9 * py || abs($4 - pz) > 1e-9 * abs(pz)) {
				printf "FAIL: P at t=%s: (%s, %s, %s), not (%.17g, %.17g, %.17g)\n", $1, $2, $3, $4, px, py, pz; exit 1 } }
		END { exit k != 41 }' "$T/psum.csv"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
