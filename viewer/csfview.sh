#!/bin/sh
# csfview - see a CSF run: one self-contained HTML page (a 3-D animation of
# every watched pos and a plot of every column against t, grouped by unit),
# static plots with gnuplot (SVG, PNG) and a text plot for the terminal.
#
#   csfview [-o PAGE.html] [--svg FILE.svg] [--png FILE.png] [--term]
#           [--scene MODEL.csf] [--title TEXT] [--note TEXT] [--log FILE]
#           [--plane X,Y,Z,NX,NY,NZ]... [--radius OBJECT=R]... [--max-rows N] [CSV]
#
# Design: a POSIX shell script over installed pieces. The CSV (a file, or
# standard input copied to a temporary file) is read twice by awk: once to
# count the rows and to find the constant columns, once to keep every k-th
# row (k = ceil(rows / --max-rows); the last row always) for display. The
# page is the template viewer/view.html with its marker lines replaced by the
# files they name: Debian's three.js and dygraphs (libjs-three,
# libjs-dygraphs), the decimated CSV as the text of a <script type=text/csv>,
# the scene's facts as a small JavaScript object, and viewer/view.js. Nothing
# on the page refers to another file. The static plots are a gnuplot script
# written by awk from the header. What the CSV cannot say (planes, radii of
# objects whose radius was not watched, the scene's end time) comes from the
# scene's source (--scene) or from flags; csfvm's stderr (--log) says whether
# the run ended early.
#
# Exit status: 0, 1 (the input is not a CSV csfview can read), 2 (bad usage,
# an unreadable or unwritable file, a missing package).
set -eu

# the viewer's files: CSF_VIEW_DIR, else ../share/csf/viewer beside this
# script (an installed copy, wherever it was moved), else where make said
VIEWDIR=${CSF_VIEW_DIR:-}
if [ -z "$VIEWDIR" ]; then
	VIEWDIR=$(dirname "$0")/../share/csf/viewer
	[ -r "$VIEWDIR/view.js" ] || VIEWDIR='@VIEWDIR@'
fi
JSDIR=${CSF_JS_DIR:-/usr/share/javascript}

usage() {
	cat >&2 <<'EOF'
usage: csfview [-o PAGE.html] [--svg FILE.svg] [--png FILE.png] [--term]
               [--scene MODEL.csf] [--title TEXT] [--note TEXT] [--log FILE]
               [--plane X,Y,Z,NX,NY,NZ]... [--radius OBJECT=R]... [--max-rows N] [CSV]
Reads a run's CSV (standard input when no CSV or -) and writes an HTML page
(to PAGE.html, or to standard output when no other output is asked for).
See csfview(1).
EOF
	exit 2
}
die() {
	echo "csfview: $*" >&2
	exit 2
}

out=
svg=
png=
term=0
scene=
title=
note=
log=
planes=
radii=
maxrows=10000
csv=
while [ $# -gt 0 ]; do
	opt=$1
	case $opt in
	--*=*) val=${opt#*=}; opt=${opt%%=*}; shift; set -- "$opt" "$val" "$@" ;;
	esac
	case $1 in
	-h | --help) usage ;;
	--term) term=1; shift; continue ;;
	-o | --output | --svg | --png | --scene | --title | --note | --log | --plane | --radius | --max-rows)
		[ $# -ge 2 ] || die "$1 needs a value"
		case $1 in
		-o | --output) out=$2 ;;
		--svg) svg=$2 ;;
		--png) png=$2 ;;
		--scene) scene=$2 ;;
		--title) title=$2 ;;
		--note) note=$2 ;;
		--log) log=$2 ;;
		--plane)
			echo "$2" | grep -Eq '^ *[-+.0-9eE]+( *, *[-+.0-9eE]+){5} *$' ||
				die "--plane $2: give X,Y,Z,NX,NY,NZ (a point in metres and a normal)"
			planes="$planes$2;" ;;
		--radius)
			echo "$2" | grep -Eq '^[A-Za-z_][A-Za-z0-9_.]*=[-+.0-9eE]+$' || die "--radius $2: give OBJECT=R (metres)"
			radii="$radii$2;" ;;
		--max-rows)
			echo "$2" | grep -Eq '^[0-9]+$' && [ "$2" -ge 2 ] || die "--max-rows $2: give a whole number of at least 2"
			maxrows=$2 ;;
		esac
		shift 2 ;;
	-) [ -z "$csv" ] || usage; csv=-; shift ;;
	-*) echo "csfview: unknown option $1" >&2; usage ;;
	*) [ -z "$csv" ] || usage; csv=$1; shift ;;
	esac
done
[ -n "$out$svg$png" ] || [ $term -eq 1 ] || out=-
if [ "$out" = - ] && [ -t 1 ]; then
	die "the page would go to a terminal: give -o PAGE.html (or redirect standard output)"
fi

T=$(mktemp -d "${TMPDIR:-/tmp}/csfview.XXXXXX")
trap 'rm -rf "$T"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

if [ -z "$csv" ] || [ "$csv" = - ]; then
	cat >"$T/in.csv" || die "cannot read standard input"
	in=$T/in.csv
	name=stdin
else
	[ -r "$csv" ] && [ -f "$csv" ] || die "cannot read $csv"
	in=$csv
	name=$(basename "$csv")
	name=${name%.csv}
fi
[ -s "$in" ] || { echo "csfview: ${csv:-standard input}: empty, no CSV header" >&2; exit 1; }
[ -z "$scene" ] || [ -r "$scene" ] || die "cannot read $scene"
[ -z "$log" ] || [ -r "$log" ] || die "cannot read $log"
if [ -n "$scene" ]; then
	name=$(basename "$scene")
	name=${name%.csf}
fi
[ -n "$title" ] || title=$name

# Pass 1: count the rows, check every row has the header's number of fields,
# find the columns that never change; writes cols.tsv (index, name, unit, constant)
# and facts (rows, last t).
awk -F, -v cols="$T/cols.tsv" '
	NR == 1 {
		sub(/\r$/, "")
		nf = NF
		for (i = 1; i <= NF; i++) {
			h = $i
			gsub(/^[ \t"]+|[ \t"]+$/, "", h)
			unit = ""
			if (match(h, / *\[[^]]*\]$/)) {
				unit = substr(h, RSTART, RLENGTH)
				sub(/^ *\[/, "", unit)
				sub(/\]$/, "", unit)
				h = substr(h, 1, RSTART - 1)
			}
			if (i == 1 && h == "t" && unit == "") unit = "s"   # the time csfvm writes, in seconds
			name[i] = h
			un[i] = unit
			const[i] = 1
		}
		next
	}
	{
		sub(/\r$/, "")
		if (NF != nf) { printf "csfview: line %d has %d fields, the header %d\n", NR, NF, nf > "/dev/stderr"; bad = 1; exit 1 }
		if ($1 !~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/) {
			printf "csfview: line %d: the first field is not a number: %s\n", NR, $1 > "/dev/stderr"; bad = 1; exit 1
		}
		if (NR == 2) for (i = 1; i <= NF; i++) first[i] = $i
		else for (i = 2; i <= NF; i++) if (const[i] && $i != first[i]) const[i] = 0
		last = $1
	}
	END {
		if (bad) exit 1
		if (NR < 2) { print "csfview: no data rows" > "/dev/stderr"; exit 1 }
		for (i = 1; i <= nf; i++) printf "%d\t%s\t%s\t%d\n", i, name[i], un[i], (i > 1 && const[i]) > cols
		printf "rows=%d\nlast=%s\n", NR - 1, last
	}' "$in" >"$T/facts" || exit 1
rows=$(sed -n 's/^rows=//p' "$T/facts")
last=$(sed -n 's/^last=//p' "$T/facts")
stride=$(((rows - 1 + maxrows - 1) / maxrows))   # at most maxrows intervals
[ "$stride" -ge 1 ] || stride=1

# The scene's source: planes (object P: plane, with its point, normal and
# edge), radii (of objects and of the kinds they are made of) and the end
# time (inc t till T). Lengths in m, cm, mm, km, ft or in; times in s, ms,
# min or h; a bare number is taken as SI. Writes lines "plane ...", "radius
# NAME R" and "till T" in SI.
if [ -n "$scene" ]; then
	awk '
	function si(num, u, kind) {
		if (u == "") return num
		if (kind == "L" && u in LEN) return num * LEN[u]
		if (kind == "T" && u in TIM) return num * TIM[u]
		return "?"
	}
	function vec(s, u,    a, n) {
		n = split(s, a, /[ ,]+/)
		if (n != 3) return ""
		return si(a[1], u, "L") " " si(a[2], u, "L") " " si(a[3], u, "L")
	}
	BEGIN {
		LEN["m"] = 1; LEN["cm"] = 0.01; LEN["mm"] = 0.001; LEN["km"] = 1000; LEN["ft"] = 0.3048; LEN["in"] = 0.0254
		TIM["s"] = 1; TIM["ms"] = 0.001; TIM["min"] = 60; TIM["h"] = 3600
	}
	{ sub(/#.*/, "") }
	/^def [A-Za-z_][A-Za-z0-9_]*:/ { def = $2; sub(/:.*/, "", def); next }
	def != "" && /^[ \t]/ {
		if (match($0, /^[ \t]+radius *= *[-+.0-9eE]+ *[a-z]*/)) {
			s = substr($0, RSTART, RLENGTH); sub(/^[ \t]+radius *= */, "", s)
			split(s, a, / +/); defr[def] = si(a[1], a[2], "L")
		}
		next
	}
	{ def = "" }
	/^object [A-Za-z_][A-Za-z0-9_]*: *[A-Za-z_][A-Za-z0-9_]* *$/ {
		o = $2; sub(/:$/, "", o); k = $3
		if (o ~ /:/) { split(o, a, ":"); o = a[1]; k = a[2] }
		if (k == "plane") { isplane[o] = 1; order[++np] = o; pt[o] = "0 0 0"; nm[o] = "0 0 1"; ed[o] = "0 0 0" }
		else kind[o] = k
		next
	}
	/^object [A-Za-z_][A-Za-z0-9_]*: *(vector +)?(point|normal|edge) *= *\(/ {
		o = $2; sub(/:.*/, "", o)
		p = $0; sub(/^[^:]*: *(vector +)?/, "", p); prop = p; sub(/ *=.*/, "", prop)
		inner = p; sub(/^[^(]*\(/, "", inner); u = inner; sub(/\).*/, "", inner); sub(/^[^)]*\) */, "", u); sub(/ .*/, "", u)
		v = vec(inner, prop == "normal" ? "" : u)
		if (v != "" && v !~ /\?/) { if (prop == "point") pt[o] = v; else if (prop == "normal") nm[o] = v; else ed[o] = v }
		next
	}
	/^object [A-Za-z_][A-Za-z0-9_]*: *radius *= *[-+.0-9eE]+/ {
		o = $2; sub(/:.*/, "", o)
		s = $0; sub(/^[^=]*= */, "", s); split(s, a, / +/); r = si(a[1], a[2], "L")
		if (r != "?") objr[o] = r
		next
	}
	/^inc t till / { s = $0; sub(/^inc t till +/, "", s); split(s, a, / +/); u = a[2] == "by" || a[2] == "watch" ? "" : a[2]; till = si(a[1], u, "T") }
	END {
		for (i = 1; i <= np; i++) { o = order[i]; print "plane", o, pt[o], nm[o], ed[o] }
		for (o in kind) if (!(o in objr) && kind[o] in defr) objr[o] = defr[kind[o]]
		for (o in objr) print "radius", o, objr[o]
		if (till != "" && till != "?") print "till", till
	}' "$scene" >"$T/scene"
else
	: >"$T/scene"
fi
for p in $(echo "$planes" | tr -d ' ' | tr ';' ' '); do
	echo "plane - $(echo "$p" | tr ',' ' ') 0 0 0" >>"$T/scene"
done
for r in $(echo "$radii" | tr ';' ' '); do
	echo "radius ${r%%=*} ${r#*=}" >>"$T/scene"
done

# Did the run end early? --note, the errors in csfvm's stderr (--log), and
# the last row before the scene's till.
till=$(sed -n 's/^till //p' "$T/scene")
{
	[ -z "$note" ] || printf '%s\n' "$note"
	[ -z "$log" ] || grep -E 'error|assertion failed|warning' "$log" | head -n 5 || true
	if [ -n "$till" ] && awk -v l="$last" -v t="$till" 'BEGIN { exit !(l + 1e-9 * (t < 0 ? -t : t) < t) }'; then
		awk -v l="$last" -v t="$till" 'BEGIN { printf "The run ended at t = %.10g, before the end of the scene at t = %.10g.\n", l, t }'
	fi
} >"$T/note"

# HTML text: & < > " escaped
esc() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g'; }

page() {
	for f in "$JSDIR/three/three.min.js" "$JSDIR/three/examples/js/controls/OrbitControls.js" \
		"$JSDIR/dygraphs/dygraph.min.js" "$JSDIR/dygraphs/dygraph.min.css"; do
		[ -r "$f" ] || die "$f is missing: install libjs-three and libjs-dygraphs (make deps)"
	done
	[ -r "$VIEWDIR/view.html" ] && [ -r "$VIEWDIR/view.js" ] || die "the viewer's files are missing in $VIEWDIR"
	# the facts for view.js
	awk -v rows="$rows" -v stride="$stride" '
		$1 == "plane" { pl = pl sprintf("%s{name:\"%s\",point:[%s,%s,%s],normal:[%s,%s,%s],edge:[%s,%s,%s]}", pl == "" ? "" : ",", $2, $3, $4, $5, $6, $7, $8, $9, $10, $11) }
		$1 == "radius" { ra = ra sprintf("%s\"%s\":%s", ra == "" ? "" : ",", $2, $3) }
		$1 == "till" { till = $2 }
		END {
			printf "var CSF_META = {rows: %d, stride: %d, till: %s, planes: [%s], radii: {%s}};\n", rows, stride, till == "" ? "null" : till, pl, ra
		}' "$T/scene" >"$T/meta.js"
	# every stride-th row and the last; "<" written as \x3c (view.js reads it back)
	awk -v k="$stride" '
		{ sub(/\r$/, "") }
		NR == 1 { gsub(/</, "\\x3c"); print; next }
		(NR - 2) % k == 0 { print; printed = NR; next }
		{ keep = $0 }
		END { if (printed != NR && NR > 1) print keep }' "$in" >"$T/data.csv"
	TITLE=$(printf '%s' "$title" | esc) NOTE=$(esc <"$T/note") awk \
		-v css="$JSDIR/dygraphs/dygraph.min.css" -v three="$JSDIR/three/three.min.js" \
		-v orbit="$JSDIR/three/examples/js/controls/OrbitControls.js" -v dygraph="$JSDIR/dygraphs/dygraph.min.js" \
		-v meta="$T/meta.js" -v data="$T/data.csv" -v view="$VIEWDIR/view.js" '
		function put(f,    l) {
			while ((getline l < f) > 0) if (l !~ /sourceMappingURL=/) print l
			close(f)
		}
		function subst(s, key, val,    i) {
			while ((i = index(s, key)) > 0) s = substr(s, 1, i - 1) val substr(s, i + length(key))
			return s
		}
		/^<!--@DYGRAPH_CSS@-->$/ { put(css); next }
		/^<!--@THREE@-->$/ { put(three); put(orbit); next }
		/^<!--@DYGRAPH@-->$/ { put(dygraph); next }
		/^<!--@META@-->$/ { put(meta); next }
		/^<!--@DATA@-->$/ { put(data); next }
		/^<!--@VIEW@-->$/ { put(view); next }
		{ print subst(subst($0, "@TITLE@", ENVIRON["TITLE"]), "@NOTE@", ENVIRON["NOTE"]) }' "$VIEWDIR/view.html"
}

if [ -n "$out" ]; then
	if [ "$out" = - ]; then
		page
	else
		page >"$T/page.html" && cat "$T/page.html" >"$out" 2>/dev/null || die "cannot write $out"
	fi
fi

# The static plots: one panel per unit of the columns that change, against
# the first column; gnuplot reads every stride-th row of the CSV.
gp() { # TERMINAL-LINE OUTPUT
	command -v gnuplot >/dev/null 2>&1 || die "gnuplot is missing: install gnuplot-nox (make deps)"
	awk -F'\t' -v term="$1" -v out="$2" -v csv="$in" -v k="$stride" -v rows="$rows" -v title="$title" -v notefile="$T/note" '
		NR == 1 { xcol = 1; xlabel = $3 == "" ? $2 : $2 " [" $3 "]"; next }
		$4 == 1 { nconst++; next }
		{
			if (!($3 in seen)) { seen[$3] = ++ng; unit[ng] = $3 }
			g = seen[$3]
			list[g] = list[g] (list[g] == "" ? "" : ", ") sprintf("\"%s\" using 1:%d every %d with lines title \"%s\"", q(csv), $1, k, q($2))
		}
		function q(s) { gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s); return s }
		END {
			if (ng == 0) { print "csfview: no column changes: nothing to plot" > "/dev/stderr"; exit 1 }
			print "set terminal " term
			if (out != "") print "set output \"" q(out) "\""
			print "set datafile separator \",\""
			print "set termoption noenhanced"
			print "set key outside right top"
			print "set grid"
			t = title
			if ((getline l < notefile) > 0) t = t " - " l
			if (k > 1) t = t sprintf(" (every %dth of %d rows)", k, rows)
			printf "set multiplot layout %d,1 title \"%s\"\n", ng, q(t)
			for (g = 1; g <= ng; g++) {
				printf "set xlabel \"%s\"\n", g == ng ? q(xlabel) : ""
				printf "set ylabel \"%s\"\n", unit[g] == "" ? "(no unit)" : "[" q(unit[g]) "]"
				print "plot " list[g]
			}
			print "unset multiplot"
		}' "$T/cols.tsv" >"$T/plot.gp" || exit 1
	gnuplot "$T/plot.gp" 2>"$T/gp.err" || { cat "$T/gp.err" >&2; die "gnuplot failed"; }
}
npanels=$(awk -F'\t' 'NR > 1 && $4 == 0 && !($3 in s) { s[$3]; n++ } END { print n + 0 }' "$T/cols.tsv")
height=$((npanels * 260 + 40))
if [ -n "$svg" ]; then
	gp "svg size 900,$height dynamic background rgb 'white'" "$T/out.svg"
	cat "$T/out.svg" >"$svg" 2>/dev/null || die "cannot write $svg"
fi
if [ -n "$png" ]; then
	gp "pngcairo size 900,$height" "$T/out.png"
	cat "$T/out.png" >"$png" 2>/dev/null || die "cannot write $png"
fi
if [ $term -eq 1 ]; then
	w=${COLUMNS:-100}
	gp "dumb size $w,$((npanels * 22 + 2))" ""
fi
exit 0
