#!/bin/sh
# csfview - see a CSF run: one self-contained HTML page (a 3-D animation of
# every watched pos and a plot of every column against t, grouped by unit),
# static plots with gnuplot (SVG, PNG) and a text plot for the terminal.
#
#   csfview [-o PAGE.html] [--svg FILE.svg] [--png FILE.png] [--term]
#           [--scene MODEL.csf] [--title TEXT] [--note TEXT] [--log FILE]
#           [--plane X,Y,Z,NX,NY,NZ]... [--radius OBJECT=R]... [--max-rows N]
#           [--decimated ROWS,K] [--record RUN.json] [CSV | RUN.h5]
#
# Design: a POSIX shell script over installed pieces. The CSV (a file, or
# standard input copied to a temporary file; an HDF5 file of csfvm -o RUN.h5
# becomes the run's CSV by csfvm --dump) is read twice by awk: once to
# count the rows, to find the constant columns and the range of every pos
# column, once to keep every k-th row (k = ceil(rows / --max-rows); the last
# row always) for display (an input that is already every K-th row of a run
# of ROWS, --decimated ROWS,K as the Python package writes a big run, is
# said to be so: its rows are then every k*K-th of the run's). The page is the template viewer/view.html with
# its marker lines replaced by the files they name: Debian's three.js and
# dygraphs (libjs-three, libjs-dygraphs), the decimated CSV as the text of a
# <script type=text/csv>, the scene's facts as a small JavaScript object
# (CSF_META), and viewer/view.js. Nothing on the page refers to another
# file. The static plots are a gnuplot script written by awk from the
# header. What the CSV cannot say (planes, radii of objects whose radius was
# not watched, the scene's end time, its fixed objects and the rods, strings
# and springs between objects) comes from the scene's source (--scene) or
# from flags; csfvm's stderr (--log) says whether the run ended early. The
# geometry the page needs from the whole run, the box of every centre and
# the rectangle each plane is drawn as, is worked out here too, so that the
# page's numbers can be checked as text.
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
               [--plane X,Y,Z,NX,NY,NZ]... [--radius OBJECT=R]... [--max-rows N]
               [--decimated ROWS,K] [--record RUN.json] [CSV | RUN.h5]
Reads a run's CSV, or its HDF5 file (csfvm -o RUN.h5; standard input when
none or -), and writes an HTML page (to PAGE.html, or to standard output
when no other output is asked for).
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
record=
planes=
radii=
maxrows=10000
runrows=
pre=1
csv=
while [ $# -gt 0 ]; do
	opt=$1
	case $opt in
	--*=*) val=${opt#*=}; opt=${opt%%=*}; shift; set -- "$opt" "$val" "$@" ;;
	esac
	case $1 in
	-h | --help) usage ;;
	--term) term=1; shift; continue ;;
	-o | --output | --svg | --png | --scene | --title | --note | --log | --plane | --radius | --max-rows | --decimated | --record)
		[ $# -ge 2 ] || die "$1 needs a value"
		case $1 in
		-o | --output) out=$2 ;;
		--svg) svg=$2 ;;
		--png) png=$2 ;;
		--scene) scene=$2 ;;
		--title) title=$2 ;;
		--note) note=$2 ;;
		--log) log=$2 ;;
		--record) record=$2; [ -r "$record" ] || die "cannot read $record" ;;
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
		--decimated)
			echo "$2" | grep -Eq '^[1-9][0-9]{0,14},[1-9][0-9]{0,14}$' ||
				die "--decimated $2: give ROWS,K (the input is every K-th row and the last of a run of ROWS rows)"
			runrows=${2%,*}
			pre=${2#*,} ;;
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
# an HDF5 file (its first 8 bytes), as csfvm -o RUN.h5 writes one: its CSV, from csfvm --dump
# (the csfvm beside this script, else the one on the PATH)
if [ "$(head -c 8 "$in" | od -An -tx1 | tr -d ' \n')" = 894844460d0a1a0a ]; then
	vm=$(dirname "$0")/csfvm
	[ -x "$vm" ] || vm=csfvm
	"$vm" --dump "$in" >"$T/dump.csv" || { echo "csfview: ${csv:-standard input}: not a file csfvm --dump reads" >&2; exit 1; }
	in=$T/dump.csv
	name=${name%.h5}
	name=${name%.hdf5}
fi
[ -z "$scene" ] || [ -r "$scene" ] || die "cannot read $scene"
[ -z "$log" ] || [ -r "$log" ] || die "cannot read $log"
if [ -n "$scene" ]; then
	name=$(basename "$scene")
	name=${name%.csf}
fi
[ -n "$title" ] || title=$name

# Pass 1: count the rows, check every row has the header's number of fields,
# find the columns that never change and the range of every pos column;
# writes cols.tsv (index, name, unit, constant, first value, and for a pos
# column its least and greatest value) and facts (rows, last t).
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
			if (h ~ /(^|\.)pos\.[xyz]$/) pc[++npc] = i
		}
		next
	}
	{
		sub(/\r$/, "")
		if (NF != nf) { printf "csfview: line %d has %d fields, the header %d\n", NR, NF, nf > "/dev/stderr"; bad = 1; exit 1 }
		if ($1 !~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/) {
			printf "csfview: line %d: the first field is not a number: %s\n", NR, $1 > "/dev/stderr"; bad = 1; exit 1
		}
		if (NR == 2) {
			for (i = 1; i <= NF; i++) first[i] = $i
			for (j = 1; j <= npc; j++) { i = pc[j]; lo[i] = hi[i] = $i + 0 }
		} else {
			for (i = 2; i <= NF; i++) if (const[i] && $i != first[i]) const[i] = 0
			for (j = 1; j <= npc; j++) {
				i = pc[j]
				if ($i + 0 < lo[i]) lo[i] = $i + 0
				if ($i + 0 > hi[i]) hi[i] = $i + 0
			}
		}
		last = $1
	}
	END {
		if (bad) exit 1
		if (NR < 2) { print "csfview: no data rows" > "/dev/stderr"; exit 1 }
		CONVFMT = OFMT = "%.17g"
		for (i = 1; i <= nf; i++)
			printf "%d\t%s\t%s\t%d\t%s\t%s\t%s\n", i, name[i], un[i], (i > 1 && const[i]), first[i], lo[i], hi[i] > cols
		printf "rows=%d\nlast=%s\n", NR - 1, last
	}' "$in" >"$T/facts" || exit 1
rows=$(sed -n 's/^rows=//p' "$T/facts")
last=$(sed -n 's/^last=//p' "$T/facts")
stride=$(((rows - 1 + maxrows - 1) / maxrows))   # at most maxrows intervals
[ "$stride" -ge 1 ] || stride=1
# the run the page speaks of: the input's, or the one it was taken from (--decimated), whose
# every pre-th row and last the input has (checked: as many rows as that leaves)
if [ -n "$runrows" ]; then
	want=$(((runrows - 1 + pre - 1) / pre + 1))
	[ "$rows" -eq "$want" ] ||
		die "--decimated $runrows,$pre: every ${pre}th row and the last of $runrows rows are $want rows, the input has $rows"
else
	runrows=$rows
fi
runstride=$((pre * stride))

# The scene's source: planes (object P: plane, with its point, normal and
# edge), radii (of objects and of the kinds they are made of), the end time
# (inc t till T), the fixed objects (object P: anchor, at its pos or the
# anchor's (0, 0, 0) m; or an object with a pos, no kind and no v) and what
# joins two objects: rule C for A, B: with = (a rod) or <= / >= (a string),
# its length when the equation is (pos - pos$1).mag against a length, and
# rule F for A, B: (a spring). Objects in for are names or numbers (from 0
# in the order of their first line). Lengths in m, cm, mm, km, ft or in;
# times in s, ms, min or h; a bare number is taken as SI. Writes lines
# "plane NAME POINT NORMAL EDGE", "radius NAME R", "till T", "anchor NAME
# [X Y Z]" and "link A B rod|string|spring LENGTH|- OP|-" in SI.
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
	# the vector of "... = (X, Y, Z) UNIT" (no unit when bare), or "" when
	# it is not three numbers in a length unit
	function vecof(s, bare,    inner, u, v) {
		inner = s; sub(/^[^(]*\(/, "", inner); u = inner; sub(/\).*/, "", inner)
		sub(/^[^)]*\) */, "", u); sub(/ .*/, "", u)
		v = vec(inner, bare ? "" : u)
		return v ~ /\?/ ? "" : v
	}
	# an object of a for list: a name, or a number in the order of definition
	function obj(s) {
		if (s !~ /^[0-9]+$/) return s
		return (s + 0) in byindex ? byindex[s + 0] : ""
	}
	# (pos - pos$1).mag between the rule objects a and b, spaces removed
	function isdist(x, a, b) {
		return x == "(pos-pos$1).mag" || x == "(pos$1-pos).mag" || x == "(pos$0-pos$1).mag" ||
			x == "(pos$1-pos$0).mag" || x == "(" a ".pos-" b ".pos).mag" || x == "(" b ".pos-" a ".pos).mag"
	}
	# a length: a number with a length unit, or a global that is one; "-" if not
	function metres(x,    n) {
		if (x in glob) return glob[x]
		if (!match(x, /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?/)) return "-"
		n = substr(x, 1, RLENGTH)
		x = substr(x, RLENGTH + 1)
		return x in LEN ? n * LEN[x] : "-"
	}
	BEGIN {
		CONVFMT = OFMT = "%.15g"
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
	/^object [A-Za-z_][A-Za-z0-9_]*:/ {
		o = $2; sub(/:.*/, "", o)
		if (!(o in number)) { number[o] = nobj; byindex[nobj++] = o }
	}
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
		v = vecof(p, prop == "normal")
		if (v != "") { if (prop == "point") pt[o] = v; else if (prop == "normal") nm[o] = v; else ed[o] = v }
		next
	}
	/^object [A-Za-z_][A-Za-z0-9_]*: *(vector +)?pos *=/ { o = $2; sub(/:.*/, "", o); pos[o] = vecof($0, 0); next }
	/^object [A-Za-z_][A-Za-z0-9_]*: *(vector +)?v *=/ { o = $2; sub(/:.*/, "", o); hasv[o] = 1; next }
	/^object [A-Za-z_][A-Za-z0-9_]*: *radius *= *[-+.0-9eE]+/ {
		o = $2; sub(/:.*/, "", o)
		s = $0; sub(/^[^=]*= */, "", s); split(s, a, / +/); r = si(a[1], a[2], "L")
		if (r != "?") objr[o] = r
		next
	}
	/^global [A-Za-z_][A-Za-z0-9_]* *= *[-+.0-9eE]+ *[a-z]* *$/ {
		s = $0; sub(/^global +/, "", s); g = s; sub(/ *=.*/, "", g); sub(/^[^=]*= */, "", s)
		split(s, a, / +/)
		if (a[2] in LEN) glob[g] = si(a[1], a[2], "L")
		next
	}
	/^rule [CF] +for +[^:]+:/ {
		s = $0; sub(/^rule +/, "", s); at = substr(s, 1, 1); sub(/^[CF] +for +/, "", s)
		i = index(s, ":"); list = substr(s, 1, i - 1); body = substr(s, i + 1)
		gsub(/[ \t]/, "", list)
		if (split(list, a, ",") == 2) { ++nr; ra[nr] = a[1]; rb[nr] = a[2]; rat[nr] = at; rbody[nr] = body }
		next
	}
	/^inc t till / { s = $0; sub(/^inc t till +/, "", s); split(s, a, / +/); u = a[2] == "by" || a[2] == "watch" ? "" : a[2]; till = si(a[1], u, "T") }
	END {
		for (i = 1; i <= np; i++) { o = order[i]; print "plane", o, pt[o], nm[o], ed[o] }
		for (o in kind) if (!(o in objr) && kind[o] in defr) objr[o] = defr[kind[o]]
		for (o in objr) print "radius", o, objr[o]
		if (till != "" && till != "?") print "till", till
		for (i = 0; i < nobj; i++) {
			o = byindex[i]
			if ((o in kind) ? kind[o] == "anchor" : !(o in isplane) && (o in pos) && !(o in hasv))
				print "anchor", o, (o in pos) ? pos[o] : "0 0 0"
		}
		for (i = 1; i <= nr; i++) {
			oa = obj(ra[i]); ob = obj(rb[i])
			if (oa == "" || ob == "" || oa == ob) continue
			len = "-"; op = "-"; k = "spring"
			if (rat[i] == "C") {
				e = rbody[i]; gsub(/[ \t]/, "", e)
				op = index(e, "<=") ? "<=" : index(e, ">=") ? ">=" : "="
				j = index(e, op); lhs = substr(e, 1, j - 1); rhs = substr(e, j + length(op))
				k = op == "=" ? "rod" : "string"
				if (isdist(lhs, oa, ob)) len = metres(rhs)
				else if (isdist(rhs, oa, ob)) { len = metres(lhs); op = op == "<=" ? ">=" : op == ">=" ? "<=" : op }
			}
			key = k SUBSEP (oa < ob ? oa SUBSEP ob : ob SUBSEP oa)
			if (key in seen) continue
			seen[key] = 1
			print "link", oa, ob, k, len, op
		}
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

# The run record (csfvm --record RUN.json, one field a line): a table of its fields, HTML-escaped
: >"$T/record.html"
if [ -n "$record" ]; then
	grep -q '"bytecode_hash"' "$record" || die "$record is not a run record of csfvm --record"
	sed -n 's/^  "\([a-z_]*\)": \(.*\)$/\1	\2/p' "$record" | sed 's/,$//' | esc | awk -F'\t' '
		BEGIN { print "<table>" }
		{ v = $2; if (v ~ /^&quot;.*&quot;$/) v = substr(v, 7, length(v) - 12); print "<tr><td>" $1 "</td><td>" v "</td></tr>" }
		END { print "</table>" }' >"$T/record.html"
fi

page() {
	for f in "$JSDIR/three/three.min.js" "$JSDIR/three/examples/js/controls/OrbitControls.js" \
		"$JSDIR/dygraphs/dygraph.min.js" "$JSDIR/dygraphs/dygraph.min.css"; do
		[ -r "$f" ] || die "$f is missing: install libjs-three and libjs-dygraphs (make deps)"
	done
	[ -r "$VIEWDIR/view.html" ] && [ -r "$VIEWDIR/view.js" ] || die "the viewer's files are missing in $VIEWDIR"
	# the facts for view.js, in metres: the planes, each with the rectangle
	# it is drawn as; the radii (a NAME.radius column's first value, else the
	# scene's); the box of every object's centre over the run (the CSV's pos
	# columns, the fixed objects' scene positions); the fixed objects; the links
	awk -F'\t' -v rows="$runrows" -v stride="$runstride" '
		function factor(u) { return u in LEN ? LEN[u] : 1 }
		function js(a, b, c) { return "[" a "," b "," c "]" }
		function dot(a, b) { return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] }
		function unit(a,    l) { l = sqrt(dot(a, a)); if (l > 0) { a[1] /= l; a[2] /= l; a[3] /= l }; return l }
		function grow(k, c0, c1, r) {
			if (!nbox || c0 < lo[k]) lo[k] = c0
			if (!nbox || c1 > hi[k]) hi[k] = c1
			if (!nbox || c0 - r < elo[k]) elo[k] = c0 - r
			if (!nbox || c1 + r > ehi[k]) ehi[k] = c1 + r
		}
		function radius(o) { return o in colr ? colr[o] : o in sr ? sr[o] : 0 }
		# plane i drawn as a rectangle: the box grown by its radii, projected
		# onto the plane, a margin of a quarter of the box on every side, cut
		# at the edge line; its centre, sides u and v and size
		function rect(i,    P, N, E, U, V, A, d, k, c, cu, cv, u0, u1, v0, v1, m, ue, ext, mid) {
			split(ppt[i], P, " "); split(pnm[i], N, " "); split(ped[i], E, " ")
			if (unit(N) == 0) { N[1] = 0; N[2] = 0; N[3] = 1 }
			d = dot(E, N)
			for (k = 1; k <= 3; k++) U[k] = E[k] - d * N[k]
			if (unit(U) == 0) {
				A[1] = N[1] < 0.9 && N[1] > -0.9; A[2] = !A[1]; A[3] = 0
				d = dot(A, N)
				for (k = 1; k <= 3; k++) U[k] = A[k] - d * N[k]
				unit(U)
			}
			V[1] = N[2] * U[3] - N[3] * U[2]; V[2] = N[3] * U[1] - N[1] * U[3]; V[3] = N[1] * U[2] - N[2] * U[1]
			ext = 0
			for (k = 1; k <= 3; k++) if (ehi[k] - elo[k] > ext) ext = ehi[k] - elo[k]
			m = (ext > 0 ? ext : 1) / 4
			for (c = 0; c < 8; c++) {
				for (k = 1; k <= 3; k++) A[k] = (int(c / 2 ^ (k - 1)) % 2 ? ehi[k] : elo[k]) - P[k]
				cu = dot(A, U); cv = dot(A, V)
				if (!c || cu < u0) u0 = cu
				if (!c || cu > u1) u1 = cu
				if (!c || cv < v0) v0 = cv
				if (!c || cv > v1) v1 = cv
			}
			u0 -= m; u1 += m; v0 -= m; v1 += m
			if (dot(E, E) > 0) {
				ue = dot(E, U)
				if (u1 > ue) u1 = ue
				if (u0 > u1 - m) u0 = u1 - m
			}
			for (k = 1; k <= 3; k++) mid[k] = P[k] + U[k] * (u0 + u1) / 2 + V[k] * (v0 + v1) / 2
			return sprintf(",centre:%s,u:%s,v:%s,size:[%s,%s]", js(mid[1], mid[2], mid[3]), js(U[1], U[2], U[3]),
				js(V[1], V[2], V[3]), u1 - u0, v1 - v0)
		}
		BEGIN {
			CONVFMT = OFMT = "%.15g"
			LEN["m"] = 1; LEN["cm"] = 0.01; LEN["mm"] = 0.001; LEN["km"] = 1000; LEN["ft"] = 0.3048; LEN["in"] = 0.0254
		}
		# cols.tsv: index, name, unit, constant, first, least, greatest
		FNR == NR && $2 ~ /(^|\.)pos\.[xyz]$/ {
			o = $2; sub(/\.?pos\.[xyz]$/, "", o)
			if (o == "") o = "pos"
			k = index("xyz", substr($2, length($2)))
			clo[o, k] = $6 * factor($3); chi[o, k] = $7 * factor($3)
			if (++naxes[o] == 3) csvobj[++ncsv] = o
			next
		}
		FNR == NR && $2 ~ /\.radius$/ { o = $2; sub(/\.radius$/, "", o); colr[o] = $5 * factor($3); next }
		FNR == NR && $2 ~ /\.(normal|point|edge)\.[xyz]$/ {
			o = $2; sub(/\.(normal|point|edge)\.[xyz]$/, "", o)
			p = $2; sub(/\.[xyz]$/, "", p); sub(/^.*\./, "", p)
			k = index("xyz", substr($2, length($2)))
			val[o, p, k] = $5 * (p == "normal" ? 1 : factor($3))
			if (++cn[o, p] == 3 && p == "normal") csvplane[++ncp] = o
			next
		}
		FNR == NR { next }
		# the scene: see above
		{ n = split($0, w, " ") }
		w[1] == "plane" { np++; pname[np] = w[2]; ppt[np] = w[3] " " w[4] " " w[5]; pnm[np] = w[6] " " w[7] " " w[8]; ped[np] = w[9] " " w[10] " " w[11]; byplane[w[2]] = np }
		w[1] == "radius" { sr[w[2]] = w[3] }
		w[1] == "till" { till = w[2] }
		w[1] == "anchor" { anchor[++na] = w[2]; if (n == 5) apos[w[2]] = w[3] " " w[4] " " w[5] }
		w[1] == "link" { li = li sprintf("%s{a:\"%s\",b:\"%s\",kind:\"%s\",length:%s,op:%s}", li == "" ? "" : ",", w[2], w[3], w[4],
			w[5] == "-" ? "null" : w[5], w[6] == "-" ? "null" : "\"" w[6] "\"") }
		END {
			for (i = 1; i <= ncsv; i++) {
				o = csvobj[i]
				for (k = 1; k <= 3; k++) grow(k, clo[o, k], chi[o, k], radius(o))
				nbox++
			}
			for (i = 1; i <= na; i++) {
				o = anchor[i]
				an = an sprintf("%s{name:\"%s\",pos:%s}", an == "" ? "" : ",", o, o in apos ? "[" apos[o] "]" : "null")
				if (naxes[o] == 3 || !(o in apos)) continue
				split(apos[o], A, " ")
				for (k = 1; k <= 3; k++) grow(k, A[k], A[k], radius(o))
				nbox++
			}
			gsub(/ /, ",", an)
			# a watched plane is drawn where its columns say
			for (i = 1; i <= ncp; i++) {
				o = csvplane[i]
				j = o in byplane ? byplane[o] : ++np
				pname[j] = o
				pnm[j] = val[o, "normal", 1] " " val[o, "normal", 2] " " val[o, "normal", 3]
				ppt[j] = cn[o, "point"] == 3 ? val[o, "point", 1] " " val[o, "point", 2] " " val[o, "point", 3] : "0 0 0"
				ped[j] = cn[o, "edge"] == 3 ? val[o, "edge", 1] " " val[o, "edge", 2] " " val[o, "edge", 3] : "0 0 0"
			}
			for (i = 1; i <= np; i++) {
				pl = pl sprintf("%s{name:\"%s\",point:[%s],normal:[%s],edge:[%s]%s}", pl == "" ? "" : ",", pname[i],
					ppt[i], pnm[i], ped[i], nbox ? rect(i) : "")
			}
			gsub(/ /, ",", pl)
			for (o in sr) if (!(o in colr)) colr[o] = sr[o]
			for (o in colr) ra = ra sprintf("%s\"%s\":%s", ra == "" ? "" : ",", o, colr[o])
			printf "var CSF_META = {rows: %d, stride: %d, till: %s, planes: [%s], radii: {%s}, box: %s, anchors: [%s], links: [%s]};\n",
				rows, stride, till == "" ? "null" : till, pl, ra,
				nbox ? "{lo:" js(lo[1], lo[2], lo[3]) ",hi:" js(hi[1], hi[2], hi[3]) "}" : "null", an, li
		}' "$T/cols.tsv" "$T/scene" >"$T/meta.js"
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
		-v meta="$T/meta.js" -v data="$T/data.csv" -v view="$VIEWDIR/view.js" -v record="$T/record.html" '
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
		/^<!--@RECORD@-->$/ { put(record); next }
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
	awk -F'\t' -v term="$1" -v out="$2" -v csv="$in" -v k="$stride" -v rows="$runrows" -v kk="$runstride" -v title="$title" \
		-v notefile="$T/note" '
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
			if (kk > 1) t = t sprintf(" (every %dth of %d rows)", kk, rows)
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
