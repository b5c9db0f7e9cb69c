#!/bin/sh
# tests/view/check.sh CSFC CSFVM CSFVIEW DIR - csfview(1).
#
# Always: the page of examples/bouncing_ball.csf is self-contained (nothing
# it loads from elsewhere), carries the CSV's rows exactly and the scene's
# floor; --svg names the axes with their units; --png is a PNG; --term draws
# text; a plain CSV without units; a run that failed an assertion (--log)
# and ended before its till (--scene) is noted; a 1e6-row CSV is decimated
# to every 100th row, said so, in a few seconds; bad usage is exit 2, a file
# that is no CSV exit 1.
# In headless Chromium, where it is installed (make deps-chromium), else a
# SKIP line: the pages of the bouncing ball and Newton's cradle load with no
# console error; the screenshot has drawn pixels in the 3-D view and in the
# plots; at t = 1.3548 s (#t=1.3548) the page shows the ball on the floor,
# at t = 0.2 s above it at 1 - g t^2/2; the cradle's last ball at
# x = 0.6 + (t - 0.105) m; the page of a plain CSV shows its plot; the page
# of the 1e6-row run says it is decimated.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 CSFVIEW=$3 T=$4
HERE=$(cd "$(dirname "$0")" && pwd)
TOP=$(cd "$HERE/../.." && pwd)
LIMIT=${CSF_TEST_LIMIT:-300}
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: view: $*"; }

run() { # MODEL: compile and run examples/MODEL.csf into $T/MODEL.csv
	"$CSFC" "$TOP/examples/$1.csf" -o "$T/$1.csfb" 2>"$T/err" && "$CSFVM" "$T/$1.csfb" >"$T/$1.csv" 2>>"$T/err"
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

# 6. bad usage is exit 2; what is not a CSV, exit 1
u=0
"$CSFVIEW" --no-such-flag "$T/plain.csv" >/dev/null 2>&1; [ $? -eq 2 ] || { u=1; bad "an unknown flag: not exit 2"; }
"$CSFVIEW" -o "$T/x.html" "$T/does-not-exist.csv" 2>/dev/null; [ $? -eq 2 ] || { u=1; bad "a missing CSV: not exit 2"; }
"$CSFVIEW" --plane 1,2 -o "$T/x.html" "$T/plain.csv" 2>/dev/null; [ $? -eq 2 ] || { u=1; bad "--plane 1,2: not exit 2"; }
printf 't,x\n0,1\n1\n' | "$CSFVIEW" -o "$T/x.html" 2>"$T/err"; st=$?
[ $st -eq 1 ] && grep -q 'line 3 has 1 fields' "$T/err" || { u=1; bad "a short row: exit $st, $(head -n 1 "$T/err")"; }
: | "$CSFVIEW" -o "$T/x.html" 2>/dev/null; [ $? -eq 1 ] || { u=1; bad "empty input: not exit 1"; }
[ $u -eq 0 ] && ok

# 7. in headless Chromium
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
	probe "$T/big.html" "$T/big.probe.html"
	chrome t=5 "$T/big.probe.html" --dump-dom >"$T/big.dom"
	if grep -q 'id="decimation">Decimated for display: the run has 1000001 rows; every 100th row (and the last) is shown, 10001 rows.<' "$T/big.dom" &&
		[ -z "$(attr data-errors "$T/big.dom")" ]; then ok
	else bad "the 1e6-row page: $(grep -o 'id="decimation">[^<]*' "$T/big.dom") $(attr data-errors "$T/big.dom")"; fi
fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
