#!/bin/sh
# tests/view/check.sh CSFC CSFVM CSFVIEW DIR - csfview(1).
#
# Always: the page of examples/bouncing_ball.csf is self-contained (nothing
# it loads from elsewhere), carries the CSV's rows exactly and the scene's
# floor; --svg names the axes with their units; --png is a PNG; --term draws
# text; a plain CSV without units; a run that failed an assertion (--log)
# and ended before its till (--scene) is noted; a 1e6-row CSV is decimated
# to every 100th row, said so, in a few seconds; --decimated (an input that is
# already every K-th row of a run) said so; bad usage is exit 2, a file
# that is no CSV exit 1. What joins objects, in the page's CSF_META: the
# pendulum's rod from bob to pivot (an anchor at the origin), a string of
# 1 m, a scene's rod (a global in cm), string (written backwards), springs
# (by number; one named twice) and fixed objects, the
# spring of examples/spring.csf to an object the CSV has no pos of; the
# rectangles the planes are drawn as, against the box of the motion worked
# out by hand (the bouncing ball's floor; the table that ends at its edge).
# In node, where it is installed, else a SKIP line (tests/view/drawn.js runs
# the page with a stub DOM and renderer): the rod's ends at the exact
# pendulum's position; the string slack (dashed) just before it goes taut
# at t = sqrt(1.6 m / g) and taut (solid, its length L) just after; the
# spring a zigzag from the exact position to the scene's fixed anchor; the
# planes drawn at the size CSF_META gives.
# In headless Chromium, where it is installed (make deps-chromium), else a
# SKIP line: the pages of the bouncing ball and Newton's cradle load with no
# console error; the screenshot has drawn pixels in the 3-D view and in the
# plots; at t = 1.3548 s (#t=1.3548) the page shows the ball on the floor,
# at t = 0.2 s above it at 1 - g t^2/2; the cradle's last ball at
# x = 0.6 + (t - 0.105) m; the page of a plain CSV shows its plot; the page
# of the 1e6-row run says it is decimated; the string's page loads with no
# console error and its legend says slack at t = 0.2 s, taut at t = 1 s.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 CSFVIEW=$3 T=$4
HERE=$(cd "$(dirname "$0")" && pwd)
TOP=$(cd "$HERE/../.." && pwd)
LIMIT=${CSF_TEST_LIMIT:-300}
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: view: $*"; }

run() { # MODEL [FILE]: compile and run FILE (examples/MODEL.csf) into $T/MODEL.csv
	"$CSFC" "${2:-$TOP/examples/$1.csf}" -o "$T/$1.csfb" 2>"$T/err" && "$CSFVM" "$T/$1.csfb" >"$T/$1.csv" 2>>"$T/err"
}

# the CSV inside a page (between <script id="csv" ...> and </script>)
page_csv() {
	awk '/^<script id="csv" type="text\/csv">$/ { on = 1; next } on && /^<\/script>$/ { exit } on' "$1"
}

# 1. the page: self-contained, the CSV's rows, the scene's floor, the title
if run bouncing_ball && "$CSFVIEW" --scene "$TOP/examples/bouncing_ball.csf" -o "$T/ball.html" "$T/bouncing_ball.csv" 2>"$T/err"; then
	# (an inline data: URI, as dygraphs has for an icon, is no other file)
	refs=$( (grep -Eio '<script[^>]* src=[^>]*|<link[^>]*|<img[^>]*|<iframe|@import|sourceMappingURL[^ ]*|[^-]src="[^"]*' "$T/ball.html"
		grep -o 'url([^)]*' "$T/ball.html") | grep -v 'src="data:' | head -n 3)
	if [ -n "$refs" ]; then bad "the page refers to another file: $refs"; else ok; fi
	page_csv "$T/ball.html" >"$T/ball.page.csv"
	if cmp -s "$T/ball.page.csv" "$T/bouncing_ball.csv"; then ok; else bad "the page's data differ from the CSV: $(cmp "$T/ball.page.csv" "$T/bouncing_ball.csv" 2>&1)"; fi
	if grep -q 'planes: \[{name:"floor",point:\[0,0,0\],normal:\[0,0,1\]' "$T/ball.html" && grep -q '<h1 id="title">bouncing_ball</h1>' "$T/ball.html" &&
		grep -q 'rows: 3001, stride: 1, till: 3,' "$T/ball.html"; then ok
	else bad "the page lacks the floor, the title or the facts: $(grep -o 'var CSF_META.*' "$T/ball.html")"; fi
	# the same page from standard input, as in csfvm m.csfb | csfview -o page.html
	if "$CSFVIEW" --scene "$TOP/examples/bouncing_ball.csf" -o "$T/ball2.html" <"$T/bouncing_ball.csv" && cmp -s "$T/ball.html" "$T/ball2.html"; then ok
	else bad "the page from standard input differs from the page of the file"; fi
else
	bad "bouncing_ball: $(head -n 2 "$T/err")"
fi

# 2. static plots: the axes and their units in the SVG; a PNG; text
if "$CSFVIEW" --svg "$T/ball.svg" --png "$T/ball.png" "$T/bouncing_ball.csv" 2>"$T/err" &&
	grep -q '<svg' "$T/ball.svg" && grep -q '>t \[s\]<' "$T/ball.svg" && grep -q '>\[m\]<' "$T/ball.svg" &&
	grep -q '>\[m/s\]<' "$T/ball.svg" && grep -q '>ball.pos.z<' "$T/ball.svg" && grep -q '>ball.v.z<' "$T/ball.svg" &&
	! grep -q '>ball.pos.x<' "$T/ball.svg"; then ok
else bad "--svg: the axis labels t [s], [m], [m/s] or the series: $(head -n 2 "$T/err")"; fi
if [ "$(od -An -c -N4 "$T/ball.png" 2>/dev/null | tr -d ' ')" = '211PNG' ]; then ok; else bad "--png: not a PNG"; fi
if COLUMNS=90 "$CSFVIEW" --term "$T/bouncing_ball.csv" >"$T/term" 2>"$T/err" && [ "$(wc -l <"$T/term")" -ge 40 ] &&
	grep -q '\[m\]' "$T/term" && grep -q 't \[s\]' "$T/term" && grep -q 'ball.pos.z \*' "$T/term"; then ok
else bad "--term: $(head -n 2 "$T/err" "$T/term")"; fi

# 3. a plain CSV: no units, its own first column
printf 'time,x,y\n0,1,5\n1,2,4\n2,4,3\n' >"$T/plain.csv"
if "$CSFVIEW" -o "$T/plain.html" --svg "$T/plain.svg" "$T/plain.csv" 2>"$T/err" && grep -q '>time<' "$T/plain.svg" &&
	grep -q '>(no unit)<' "$T/plain.svg" && [ "$(page_csv "$T/plain.html")" = "$(cat "$T/plain.csv")" ]; then ok
else bad "a plain CSV: $(head -n 2 "$T/err")"; fi

# 4. a run that ended early: the assertion from csfvm's stderr, the end before till
m=$TOP/tests/runtime/assert_fail.csf
"$CSFC" "$m" -o "$T/af.csfb" 2>"$T/err"
"$CSFVM" "$T/af.csfb" 2>"$T/af.log" | "$CSFVIEW" --scene "$m" --log "$T/af.log" -o "$T/af.html" 2>>"$T/err"
if grep -q '<div id="note">.*assert_fail.csf:8: assertion failed at t=1.5: pos.z &gt; 0 m (object ball)$' "$T/af.html" &&
	grep -q "^The run ended at t = 1.4, before the end of the scene at t = 3.</div>" "$T/af.html"; then ok
else bad "the note of a run that ended early: $(grep -A 2 'id="note"' "$T/af.html" | head -n 3) $(head -n 1 "$T/err")"; fi
if "$CSFVIEW" --note 'stopped by hand' -o "$T/n.html" "$T/plain.csv" && grep -q '<div id="note">stopped by hand</div>' "$T/n.html"; then ok
else bad "--note"; fi

# 5. 1e6 rows: every 100th shown (and the last), said so, quickly
awk 'BEGIN { print "t,p.pos.x [m],p.pos.y [m],p.pos.z [m],p.v.x [m/s]"
	for (i = 0; i <= 1000000; i++) printf "%.5f,%.6f,%.6f,0,%.6f\n", i * 1e-5, cos(i * 1e-4), sin(i * 1e-4), -sin(i * 1e-4) }' >"$T/big.csv"
start=$(date +%s)
if "$CSFVIEW" -o "$T/big.html" "$T/big.csv" 2>"$T/err"; then
	secs=$(($(date +%s) - start))
	rows=$(page_csv "$T/big.html" | wc -l)
	if grep -q 'rows: 1000001, stride: 100,' "$T/big.html" && [ "$rows" -eq 10002 ] &&
		[ "$(page_csv "$T/big.html" | tail -n 1)" = "$(tail -n 1 "$T/big.csv")" ] && [ "$secs" -le 20 ]; then ok
	else bad "1e6 rows: $rows lines in the page (want 10002), $secs s, $(grep -o 'var CSF_META = {[^}]*' "$T/big.html")"; fi
else
	bad "1e6 rows: $(head -n 1 "$T/err")"
fi

# 5a. --decimated ROWS,K: the big CSV's every 1000th row and last, said to be of 1000001 rows; decimated
#     again to every 10th of those (--max-rows 100): every 10000th of the run; a count that does not fit, exit 2
awk -F, 'NR == 1 || (NR - 2) % 1000 == 0' "$T/big.csv" >"$T/pre.csv"
if "$CSFVIEW" --decimated 1000001,1000 -o "$T/pre.html" "$T/pre.csv" 2>"$T/err" &&
	grep -q 'rows: 1000001, stride: 1000,' "$T/pre.html" && page_csv "$T/pre.html" | cmp -s - "$T/pre.csv" &&
	"$CSFVIEW" --decimated=1000001,1000 --max-rows 100 -o "$T/pre.html" "$T/pre.csv" 2>"$T/err" &&
	grep -q 'rows: 1000001, stride: 10000,' "$T/pre.html" && [ "$(page_csv "$T/pre.html" | wc -l)" -eq 102 ]; then ok
else bad "--decimated: $(head -n 1 "$T/err") $(grep -o 'var CSF_META = {[^}]*' "$T/pre.html")"; fi
"$CSFVIEW" --decimated 1000001,999 -o "$T/x.html" "$T/pre.csv" 2>"$T/err"; st=$?
if [ $st -eq 2 ] && grep -q 'every 999th row and the last of 1000001 rows are 1003 rows, the input has 1001' "$T/err"; then ok
else bad "--decimated that does not fit the input: exit $st, $(head -n 1 "$T/err")"; fi

# 6. bad usage is exit 2; what is not a CSV, exit 1
u=0
"$CSFVIEW" --no-such-flag "$T/plain.csv" >/dev/null 2>&1; [ $? -eq 2 ] || { u=1; bad "an unknown flag: not exit 2"; }
"$CSFVIEW" -o "$T/x.html" "$T/does-not-exist.csv" 2>/dev/null; [ $? -eq 2 ] || { u=1; bad "a missing CSV: not exit 2"; }
"$CSFVIEW" --plane 1,2 -o "$T/x.html" "$T/plain.csv" 2>/dev/null; [ $? -eq 2 ] || { u=1; bad "--plane 1,2: not exit 2"; }
printf 't,x\n0,1\n1\n' | "$CSFVIEW" -o "$T/x.html" 2>"$T/err"; st=$?
[ $st -eq 1 ] && grep -q 'line 3 has 1 fields' "$T/err" || { u=1; bad "a short row: exit $st, $(head -n 1 "$T/err")"; }
: | "$CSFVIEW" -o "$T/x.html" 2>/dev/null; [ $? -eq 1 ] || { u=1; bad "empty input: not exit 1"; }
[ $u -eq 0 ] && ok

# 7. what joins objects, the fixed objects and the planes' rectangles, in CSF_META
meta() { # PAGE: the line of CSF_META
	grep -o 'var CSF_META = .*' "$1"
}
page() { # MODEL FILE: run FILE and write its page $T/MODEL.html
	run "$1" "$2" && "$CSFVIEW" --scene "$2" -o "$T/$1.html" "$T/$1.csv" 2>>"$T/err"
}
has() { # MODEL TEXT...: the page of MODEL has every TEXT in its CSF_META
	m=$1
	shift
	for want in "$@"; do
		meta "$T/$m.html" | grep -qF "$want" || { bad "$m: CSF_META lacks $want: $(meta "$T/$m.html")"; return 1; }
	done
	ok
}
if page pendulum "$TOP/examples/pendulum.csf"; then
	has pendulum 'anchors: [{name:"pivot",pos:[0,0,0]}]' 'links: [{a:"bob",b:"pivot",kind:"rod",length:1,op:"="}]'
else bad "pendulum: $(head -n 2 "$T/err")"; fi
# the scenes are written here, not kept as .csf files (tests/layout/check.sh
# takes the digests of every .csf under tests/)
cat >"$T/string_swing.csf" <<'EOF'
# A ball on a string of 1 m from a pivot at the origin, let go at rest
# 0.6 m beside it, the string slack. It falls freely until the string goes
# taut at z = -0.8 m, at t = sqrt(1.6 m / g) = 0.40393 s; cr 0, so the
# impact is plastic (it keeps the 0.6 g t of its speed across the string)
# and the string stays taut: the ball swings on it, up to z = -0.8 m +
# (0.6 g t)^2 / (2 g) = -0.512 m, below the pivot, where the tension
# m (g cos(angle) + v^2 / L) is still positive.
using mechanics/mass_point
object pivot: anchor
object ball: mass_point
object ball: cr = 0
object ball: pos = (0.6, 0, 0) m
using mechanics/rules
rule F: W = g.mul(m)
rule C for ball, pivot: (pos - pos$1).mag <= 1 m
inc t till 2 s by 0.01 s watch pos
EOF
cat >"$T/links.csf" <<'EOF'
# What csfview reads as links: a rod whose length is a global in cm, a
# string written backwards (a constant >= the distance, so the distance
# <= 50 cm), a spring given by the objects' numbers, a spring
# named twice (b, d and d, b: one link), a constraint on one object (no
# link), and a fixed object that is no anchor (hook: a pos, no kind, no v).
# Objects by number: pivot 0, a 1, b 2, d 3, hook 4.
using mechanics/mass_point
object pivot: anchor
object pivot: pos = (0, 0, 2) m
object a: mass_point
object a: pos = (0, 0, 1) m
object b: mass_point
object b: pos = (0.3, 0, 1) m
object d: mass_point
object d: pos = (1, 0, 1) m
object hook: vector pos = (2, 0, 1) m
global L = 100 cm
global k = 10 N/m
using mechanics/rules
rule F: W = g.mul(m)
rule C for a, pivot: (pos - pos$1).mag = L
rule C for b, a: 50 cm >= (pos$1 - pos).mag
rule F for 3, 4: S1 = (pos$1 - pos).mul(k)
rule F for b, d: S2 = (pos$1 - pos).mul(k)
rule F for d, b: S3 = (pos$1 - pos).mul(k)
rule C for d: pos.y = 0 m
inc t till 1 s by 0.1 s watch pos
EOF
if page string_swing "$T/string_swing.csf"; then
	has string_swing 'links: [{a:"ball",b:"pivot",kind:"string",length:1,op:"<="}]'
else bad "string_swing: $(head -n 2 "$T/err")"; fi
if page links "$T/links.csf"; then
	has links 'anchors: [{name:"pivot",pos:[0,0,2]},{name:"hook",pos:[2,0,1]}]' \
		'links: [{a:"a",b:"pivot",kind:"rod",length:1,op:"="},{a:"b",b:"a",kind:"string",length:0.5,op:"<="},{a:"d",b:"hook",kind:"spring",length:null,op:null},{a:"b",b:"d",kind:"spring",length:null,op:null}]}'
else bad "links: $(head -n 2 "$T/err")"; fi
if page spring "$TOP/examples/spring.csf"; then
	if head -n 1 "$T/spring.csv" | grep -q 'anchor\.pos'; then bad "spring: the CSV has the anchor's pos: the test wants one it has not"
	else has spring 'anchors: [{name:"anchor",pos:[0,0,1]}]' 'links: [{a:"bob",b:"anchor",kind:"spring",length:null,op:null}]'; fi
else bad "spring: $(head -n 2 "$T/err")"; fi
# a plane is the box of every centre over the run projected onto it, a
# quarter of the box's longest side beyond it, cut at its edge line
rect() { # PAGE NAME: the centre and size of plane NAME, "x y z w h"
	meta "$1" | sed -n "s/.*{name:\"$2\",[^}]*centre:\[\([^]]*\)\],u:\[[^]]*\],v:\[[^]]*\],size:\[\([^]]*\)\]}.*/\1,\2/p" | tr ',' ' '
}
near() { # GOT WANT...: the numbers agree to 1e-6
	echo "$1 | $2" | awk -F'|' '{ n = split($1, a, " "); if (split($2, b, " ") != n || n == 0) exit 1
		for (i = 1; i <= n; i++) if ((a[i] - b[i])^2 > 1e-12) exit 1 }'
}
# the ball drops from z = 1 m to the floor at z = 0 straight down: a box 1 m
# tall and no wider than a point; the floor 0.5 m square under it
f=$(rect "$T/ball.html" floor)
if near "$f" "0 0 0 0.5 0.5"; then ok; else bad "bouncing_ball: the floor's rectangle is $f, want 0 0 0 0.5 0.5"; fi
# off a table at z = 1 m that ends at x = 1 m at 2 m/s: 1 m to the edge, a
# fall of sqrt(2 m / g) to the floor (cr 0), a slide at mu_k g = 0.2 g to
# rest: x from 0 to X = 1 + 2 sqrt(2/g) + 2^2 / (2 0.2 g) m, z from 0 to 1;
# a margin of X / 4. The table ends at its edge, x = 1; the floor does not.
if page table_edge "$TOP/examples/table_edge.csf"; then
	want=$(awk 'BEGIN { g = 9.80665; X = 1 + 2 * sqrt(2 / g) + 4 / (0.4 * g); m = X / 4
		printf "%.12g 0 1 %.12g %.12g|%.12g 0 0 %.12g %.12g\n", (1 - m) / 2, 1 + m, 2 * m, X / 2, X + 2 * m, 2 * m }')
	tb=$(rect "$T/table_edge.html" table) fl=$(rect "$T/table_edge.html" floor)
	if near "$tb" "${want%|*}" && near "$fl" "${want#*|}"; then ok
	else bad "table_edge: the table's rectangle $tb (want ${want%|*}), the floor's $fl (want ${want#*|})"; fi
else bad "table_edge: $(head -n 2 "$T/err")"; fi

# 8. what the page draws, in node with a stub DOM and renderer
if ! command -v node >/dev/null 2>&1; then
	echo "SKIP: view: what the page draws (tests/view/drawn.js): no node"
else
	drawn() { # MODEL SECONDS: the things the page of MODEL draws at that time, in $T/MODEL.drawn
		node "$HERE/drawn.js" "$T/$1.html" "$2" >"$T/$1.drawn" 2>"$T/err" || { bad "$1 in node: $(head -n 2 "$T/err")"; return 1; }
	}
	line() { # MODEL PREFIX: the drawn line that starts with PREFIX, without it
		sed -n "s/^$2 //p" "$T/$1.drawn" | head -n 1
	}
	# the pendulum at t = 0.5 s: theta = 0.84004966 (examples/pendulum.csf)
	if drawn pendulum 0.5; then
		want=$(awk 'BEGIN { th = 0.84004966; printf "shown 2 %.9f 0 %.9f 0 0 0\n", sin(th), -cos(th) }')
		got=$(line pendulum 'link rod bob pivot')
		if near "$got" "$want" && line pendulum 'fixed pivot' | grep -q '^0 0 0 OctahedronBufferGeometry '; then ok
		else bad "pendulum at t = 0.5 s: the rod is ($got), want ($want); the pivot $(line pendulum 'fixed pivot')"; fi
	fi
	# the string: slack at t = 0.4 s, taut from t = sqrt(1.6 / g) = 0.40393 s
	if drawn string_swing 0.4; then
		s=$(line string_swing 'link string ball pivot' | cut -d' ' -f1) d=$(line string_swing 'link string ball pivot slack' | cut -d' ' -f1)
		if [ "$s $d" = "hidden shown" ] && grep -q '^legend string ball pivot slack string ball.pivot, slack$' "$T/string_swing.drawn"; then ok
		else bad "the string at t = 0.4 s: solid $s, dashed $d, want it slack: $(grep legend "$T/string_swing.drawn")"; fi
	fi
	if drawn string_swing 0.41; then
		got=$(line string_swing 'link string ball pivot')
		d=$(line string_swing 'link string ball pivot slack' | cut -d' ' -f1)
		if echo "$got" | awk -v d="$d" '{ l = sqrt(($3 - $6)^2 + ($4 - $7)^2 + ($5 - $8)^2); exit !($1 == "shown" && d == "hidden" && (l - 1)^2 < 1e-12) }' &&
			grep -q '^legend string ball pivot taut ' "$T/string_swing.drawn"; then ok
		else bad "the string at t = 0.41 s: ($got), dashed $d, want it taut and 1 m long"; fi
	fi
	# the spring at t = 0.5 s: bob at (0.00385019, 0.09092974, 1) m (examples/spring.csf),
	# the anchor at (0, 0, 1) m from the scene; between them corners on alternate sides
	if drawn spring 0.5; then
		got=$(line spring 'link spring bob anchor')
		if echo "$got" | awk '{ if ($1 != "shown" || $2 != 20) exit 1
				if (($3 - 0.00385019)^2 + ($4 - 0.09092974)^2 + ($5 - 1)^2 > 1e-14 || $60^2 + $61^2 + ($62 - 1)^2 > 1e-14) exit 1
				ax = $60 - $3; ay = $61 - $4
				for (j = 3; j <= 18; j++) {
					s = ax * ($(3 * j + 1) - $4) - ay * ($(3 * j) - $3)
					if (j > 3 && (s * prev >= 0 || (s + prev)^2 > 1e-12 * s^2)) exit 1
					prev = s
				} }' && line spring 'fixed anchor' | grep -q '^0 0 1 '; then ok
		else bad "the spring at t = 0.5 s: ($got); the anchor $(line spring 'fixed anchor')"; fi
	fi
	# the planes at the size CSF_META gives
	if drawn table_edge 1; then
		got="$(line table_edge 'plane table' | cut -d' ' -f1,2) $(line table_edge 'plane floor' | cut -d' ' -f1,2)"
		if near "$got" "$(echo "$tb $fl" | cut -d' ' -f4,5,9,10)"; then ok
		else bad "table_edge: the planes drawn are $got (width, height), CSF_META says $tb, $fl"; fi
	fi
fi

# 9. in headless Chromium
# CSF_TEST_CHROMIUM names the browser (empty: none, the test is skipped)
CHROMIUM=${CSF_TEST_CHROMIUM-$(command -v chromium || command -v chromium-browser || true)}
if [ -z "$CHROMIUM" ]; then
	echo "SKIP: view: the browser test of csfview's page: no chromium (make deps-chromium installs it)"
elif ! command -v python3 >/dev/null 2>&1; then
	echo "SKIP: view: the browser test of csfview's page: no python3 to read the screenshot"
else
	# the page as the test loads it: console errors and the boxes' places written into <html>
	probe() { # PAGE OUT
		sed '/^<head>$/a\
<script>(function () { var errs = [], html = document.documentElement; function note(s) { errs.push(s); html.setAttribute("data-errors", errs.join(" | ")); } var e = console.error; console.error = function () { note([].join.call(arguments, " ")); e.apply(console, arguments); }; window.addEventListener("error", function (ev) { note("uncaught: " + ev.message); }); window.addEventListener("load", function () { [["view3d", "#view3d canvas"], ["plots", "#plots"]].forEach(function (box) { var el = document.querySelector(box[1]); var b = el ? el.getBoundingClientRect() : { left: 0, top: 0, right: 0, bottom: 0 }; html.setAttribute("data-" + box[0], [b.left, b.top, b.right, b.bottom].map(Math.round).join(" ")); }); }); })();</script>' "$1" >"$2"
	}
	chrome() { # URL-FRAGMENT PAGE ARGS...: run headless Chromium on PAGE#FRAGMENT
		frag=$1 page=$2
		shift 2
		timeout "$LIMIT" "$CHROMIUM" --headless --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader \
			--hide-scrollbars --window-size=1280,900 --virtual-time-budget=5000 --user-data-dir="$T/chromium" \
			--no-first-run --enable-logging=stderr --v=0 "$@" "file://$page#$frag" 2>"$T/chromium.log"
	}
	attr() { # NAME FILE: the value of <html NAME="...">
		sed -n "s/.*<html[^>]* $1=\"\([^\"]*\)\".*/\1/p" "$2" | head -n 1
	}
	# pixels that are not the background in a box of the screenshot
	drawn() { # BOX(x0 y0 x1 y1) COLOUR
		# shellcheck disable=SC2086 # the box is four numbers
		python3 "$HERE/pixels.py" "$T/shot.png" $1 "$2"
	}
	browse() { # NAME PAGE FRAGMENT: load, check errors and pixels; leaves the DOM in $T/NAME.dom
		probe "$2" "$T/$1.probe.html"
		chrome "$3" "$T/$1.probe.html" --dump-dom >"$T/$1.dom"
		if ! grep -q '<canvas' "$T/$1.dom"; then bad "$1: no page in Chromium: $(grep -v dbus "$T/chromium.log" | head -n 2)"; return 1; fi
		errs=$(attr data-errors "$T/$1.dom")
		unc=$(grep -a 'CONSOLE' "$T/chromium.log" | grep -a 'Uncaught' | head -n 1)
		if [ -n "$errs$unc" ]; then bad "$1: console errors: $errs $unc"; else ok; fi
		grep -q '<div id="view3d"><canvas' "$T/$1.dom" || bad "$1: no 3-D view (no WebGL?): $(grep -o '<div id="nowebgl">[^<]*' "$T/$1.dom" | tail -n 1)"
		rm -f "$T/shot.png"
		chrome "$3" "$T/$1.probe.html" --screenshot="$T/shot.png" >/dev/null
		v=$(drawn "$(attr data-view3d "$T/$1.dom")" f4f6f8)
		p=$(drawn "$(attr data-plots "$T/$1.dom")" ffffff)
		if [ "${v:-0}" -gt 300 ] && [ "${p:-0}" -gt 3000 ]; then ok
		else bad "$1: the screenshot: ${v:-?} drawn pixels in the 3-D view (box $(attr data-view3d "$T/$1.dom")), ${p:-?} in the plots"; fi
		cp "$T/shot.png" "$T/$1.png"
	}
	# the position the page shows: OBJECT's data-pos in DOM
	shown() { # DOM OBJECT
		sed -n "s/.*<tr id=\"obj-$2\" data-pos=\"\([^\"]*\)\".*/\1/p" "$1" | head -n 1
	}
	if browse ball "$T/ball.html" t=1.3548; then
		pos=$(shown "$T/ball.dom" ball)
		t=$(sed -n 's/.*<span id="time" data-t="\([^"]*\)".*/\1/p' "$T/ball.dom")
		if [ "$t" = 1.3548 ] && echo "$pos" | awk '{ exit !($1 == 0 && $2 == 0 && $3 < 1e-3 && $3 > -1e-3) }'; then ok
		else bad "ball at t = 1.3548 s: shown t = $t, pos = ($pos), not on the floor"; fi
		probe "$T/ball.html" "$T/ball.probe.html"
		chrome t=0.2 "$T/ball.probe.html" --dump-dom >"$T/ball02.dom"
		pos=$(shown "$T/ball02.dom" ball)
		if echo "$pos" | awk '{ z = 1 - 9.80665 * 0.2 * 0.2 / 2; d = $3 - z; exit !(d < 1e-4 && d > -1e-4) }'; then ok
		else bad "ball at t = 0.2 s: shown pos = ($pos), want z = 0.8038670"; fi
	fi
	if run newtons_cradle && "$CSFVIEW" --scene "$TOP/examples/newtons_cradle.csf" -o "$T/cradle.html" "$T/newtons_cradle.csv" 2>"$T/err" &&
		browse cradle "$T/cradle.html" t=0.5; then
		p1=$(shown "$T/cradle.dom" b1) p5=$(shown "$T/cradle.dom" b5)
		if echo "$p1 $p5" | awk '{ exit !(($1 + 0.2)^2 < 1e-12 && ($4 - 0.995)^2 < 1e-12) }'; then ok
		else bad "cradle at t = 0.5 s: b1 at ($p1), b5 at ($p5); want x = -0.2 and 0.995 m"; fi
	fi
	# a plain CSV: no objects to animate, its plot, no error
	probe "$T/plain.html" "$T/plain.probe.html"
	chrome t=1 "$T/plain.probe.html" --dump-dom >"$T/plain.dom"
	if grep -q '<div id="view3d"><div id="nowebgl">No pos was watched' "$T/plain.dom" && grep -q '<div class="graph"' "$T/plain.dom" &&
		[ -z "$(attr data-errors "$T/plain.dom")" ]; then ok
	else bad "the page of a plain CSV: $(attr data-errors "$T/plain.dom")"; fi
	if [ -f "$T/string_swing.html" ] && browse string "$T/string_swing.html" t=0.2; then
		probe "$T/string_swing.html" "$T/string.probe.html"
		chrome t=1 "$T/string.probe.html" --dump-dom >"$T/string1.dom"
		if grep -q '<span data-link="string ball pivot" data-state="slack">' "$T/string.dom" &&
			grep -q '<span data-link="string ball pivot" data-state="taut">' "$T/string1.dom"; then ok
		else bad "the string's legend at t = 0.2 s and 1 s: $(grep -o '<span data-link[^>]*>' "$T/string.dom" "$T/string1.dom")"; fi
	fi
	probe "$T/big.html" "$T/big.probe.html"
	chrome t=5 "$T/big.probe.html" --dump-dom >"$T/big.dom"
	if grep -q 'id="decimation">Decimated for display: the run has 1000001 rows; every 100th row (and the last) is shown, 10001 rows.<' "$T/big.dom" &&
		[ -z "$(attr data-errors "$T/big.dom")" ]; then ok
	else bad "the 1e6-row page: $(grep -o 'id="decimation">[^<]*' "$T/big.dom") $(attr data-errors "$T/big.dom")"; fi
fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
