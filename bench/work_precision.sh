#!/bin/sh
# work_precision.sh - the work-precision benchmark (see README.md, "Work
# precision"). Run by `make work-precision` (and `make`, all) in bench/.
#
# Every problem wp/NAME.csf has an exact answer; wp/err.awk with wp/NAME.awk
# (wp/kepler.awk for both Kepler orbits) measures a run's worst error against
# it. Every problem is run under every method at every tolerance with
# csfvm --method M --tol T --stats; one row per run goes to
# $OUT/work-precision.csv (problem,method,tol,error,seconds,rhs_evals), the
# runs left out to $OUT/work-precision-skipped.csv, the plot to
# $OUT/work-precision.svg and the summary to $OUT/work-precision.txt, which
# also replaces the part of $README between the wp:begin and wp:end markers.
#
#   BUILD       directory holding csfc and csfvm              (default ../build)
#   OUT         where the results go                          (default results)
#   README      file whose work-precision section is rewritten (default
#               README.md; empty: leave it alone)
#   WP_PROBLEMS problems, names of wp/*.csf  (default: harmonic kepler_e05
#               kepler_e09 linear_drag stiff)
#   WP_METHODS  methods (default: all but verlet, which takes no tolerance)
#   WP_TOLS     tolerances, loosest first (default 1e-3 ... 1e-12)
#   WP_LIMIT    wall seconds a single run may take: csfvm runs under
#               `timeout WP_LIMIT`; a run that hits it stops that
#               problem/method, and so does a predicted run time above it
#               (default 10)
#   WP_BUDGET   seconds all the runs of one problem/method may take together;
#               the next tolerance is skipped when it would go over (default 20)
#   WP_REPS     runs shorter than WP_SHORT seconds are repeated, WP_REPS runs
#               in all, and the median time kept (default 3; WP_SHORT 0.2)
#
# The seconds are csfvm's own (--stats: the integration, without loading the
# bytecode and starting the process); rhs_evals are its right-hand side
# evaluations (the implicit methods' Jacobian evaluations come on top; their
# time is in the seconds). Needs POSIX sh, awk, sort, gnuplot and, for the
# per-run limit, timeout (coreutils; without it runs are not limited).
set -eu

BUILD=${BUILD:-../build}
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
OUT=${OUT:-results}
README=${README-README.md}
WP_PROBLEMS=${WP_PROBLEMS:-harmonic kepler_e05 kepler_e09 linear_drag stiff}
WP_METHODS=${WP_METHODS:-dop853 dopri5 rk8pd rk2 rk4 rkf45 rkck msadams rk1imp rk2imp rk4imp bsimp msbdf}
WP_TOLS=${WP_TOLS:-1e-3 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10 1e-11 1e-12}
WP_LIMIT=${WP_LIMIT:-10}
WP_BUDGET=${WP_BUDGET:-20}
WP_REPS=${WP_REPS:-3}
WP_SHORT=${WP_SHORT:-0.2}

CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
WP=wp
say() { printf '%s\n' "$*" >&2; }
for p in "$CSFC" "$CSFVM"; do
	[ -x "$p" ] || { say "work_precision.sh: $p is missing: build it first (make from the top)"; exit 2; }
done
command -v gnuplot > /dev/null 2>&1 ||
	{ say "work_precision.sh: gnuplot is missing (Debian: apt-get install gnuplot-nox)"; exit 2; }
if command -v timeout > /dev/null 2>&1; then TIMEOUT="timeout $WP_LIMIT"; else
	TIMEOUT=; say "work_precision.sh: no timeout(1): runs are not limited to $WP_LIMIT s"; fi
case $WP_REPS in '' | *[!0-9]* | 0) say "work_precision.sh: WP_REPS must be a positive integer"; exit 2 ;; esac

TMP=$OUT/wp.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
CSV=$TMP/work-precision.csv
SKIP=$TMP/work-precision-skipped.csv
echo "problem,method,tol,error,seconds,rhs_evals" > "$CSV"
echo "problem,method,tol,reason" > "$SKIP"
START=$(date +%s)

# errof PROBLEM OUTFILE : the worst error of a run (err.awk), or nothing.
errof() {
	case $1 in
	kepler_e05) awk -F, -v ecc=0.5 -f "$WP/err.awk" -f "$WP/kepler.awk" "$2" ;;
	kepler_e09) awk -F, -v ecc=0.9 -f "$WP/err.awk" -f "$WP/kepler.awk" "$2" ;;
	*) awk -F, -f "$WP/err.awk" -f "$WP/$1.awk" "$2" ;;
	esac
}

# stat FIELD FILE : seconds or rhs evaluations from csfvm's --stats line.
stat() {
	awk -v f="$1" '/^stats:/ { if (f == "seconds") v = $(NF - 1)
		else for (i = 2; i <= NF; i++) if ($i == "right-hand") v = $(i - 1) }
		END { if (v == "") exit 1; print v }' "$2"
}

# skip PROBLEM METHOD TOL REASON
skip() { echo "$1,$2,$3,$4" >> "$SKIP"; }

# Check the exact answers first: the error of a tight run must be small.
for p in $WP_PROBLEMS; do
	[ -f "$WP/$p.csf" ] || { say "work_precision.sh: no problem $WP/$p.csf"; exit 2; }
	"$CSFC" "$WP/$p.csf" -o "$TMP/$p.csfb"
	"$CSFVM" --tol 1e-12 --method "$( [ "$p" = stiff ] && echo msbdf || echo rk8pd)" "$TMP/$p.csfb" > "$TMP/check.csv"
	e=$(errof "$p" "$TMP/check.csv") || { say "work_precision.sh: $p: the error measure failed"; exit 1; }
	awk -v e="$e" 'BEGIN { exit !(e < 1e-7) }' ||
		{ say "work_precision.sh: $p: error $e at tol 1e-12: the exact answer or the model is wrong"; exit 1; }
done

nruns=0
for p in $WP_PROBLEMS; do
	for m in $WP_METHODS; do
		stop='' s1='' s2='' cum=0
		for tol in $WP_TOLS; do
			if [ -n "$stop" ]; then skip "$p" "$m" "$tol" "$stop"; continue; fi
			# Predict this run's time from the last two: the last one times their
			# ratio (at least 1, at most 10); skip if it exceeds the limit or the budget.
			pred=$(awk -v a="${s2:-}" -v b="${s1:-}" 'BEGIN { if (b == "") { print 0; exit }
				r = (a != "" && a >= 0.01) ? b / a : 1; if (r < 1) r = 1; if (r > 10) r = 10; printf "%.6g\n", b * r }')
			why=$(awk -v p="$pred" -v c="$cum" -v l="$WP_LIMIT" -v g="$WP_BUDGET" 'BEGIN {
				if (p > l) printf "predicted %.3g s > limit %s s", p, l
				else if (c + p > g) printf "predicted %.3g s would take the total over the budget %s s", p, g }')
			if [ -n "$why" ]; then stop=$why; skip "$p" "$m" "$tol" "$stop"; continue; fi
			secs='' rc=0
			r=1
			while [ "$r" -le "$WP_REPS" ]; do
				rc=0
				# shellcheck disable=SC2086 # TIMEOUT is a command and its argument, or nothing
				$TIMEOUT "$CSFVM" --method "$m" --tol "$tol" --stats "$TMP/$p.csfb" > "$TMP/run.csv" 2> "$TMP/run.err" || rc=$?
				[ "$rc" -eq 0 ] || break
				s=$(stat seconds "$TMP/run.err")
				secs="$secs $s"
				nruns=$((nruns + 1))
				if [ "$r" -eq 1 ]; then
					cp "$TMP/run.csv" "$TMP/first.csv"
					awk -v s="$s" -v t="$WP_SHORT" 'BEGIN { exit !(s >= t) }' && break
				fi
				r=$((r + 1))
			done
			if [ "$rc" -eq 124 ]; then
				stop="timed out (over $WP_LIMIT s)"
				skip "$p" "$m" "$tol" "$stop"
				continue
			elif [ "$rc" -ne 0 ]; then
				msg=$(grep -v '^stats:' "$TMP/run.err" | head -n 1 | sed 's/^[^:]*: //; s/,/;/g' | cut -c1-200)
				skip "$p" "$m" "$tol" "csfvm failed (exit $rc: $msg)"
				continue
			fi
			# shellcheck disable=SC2086 # a list of numbers
			s=$(printf '%s\n' $secs | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
			n=$(stat rhs "$TMP/run.err")
			if ! e=$(errof "$p" "$TMP/first.csv" 2> "$TMP/err.msg"); then
				skip "$p" "$m" "$tol" "no error measure ($(head -n 1 "$TMP/err.msg"))"
				continue
			fi
			echo "$p,$m,$tol,$e,$s,$n" >> "$CSV"
			s2=$s1 s1=$s
			# shellcheck disable=SC2086 # a list of numbers
			cum=$(awk -v c="$cum" -v s="$s" -v k="$(echo $secs | wc -w)" 'BEGIN { print c + s * k }')
		done
		say "$p $m: total $cum s${stop:+; stopped: $stop}"
	done
done
END=$(date +%s)

mkdir -p "$OUT"
cp "$CSV" "$OUT/work-precision.csv"
cp "$SKIP" "$OUT/work-precision-skipped.csv"

# ---- the plot: error against csfvm's seconds, one panel a problem, one line a method ----

for p in $WP_PROBLEMS; do
	for m in $WP_METHODS; do
		awk -F, -v p="$p" -v m="$m" 'NR > 1 && $1 == p && $2 == m {
			s = $5 < 1e-6 ? 1e-6 : $5; e = $4 < 1e-17 ? 1e-17 : $4; print s, e, $3 }' "$CSV" > "$TMP/plot_${p}_$m.dat"
	done
done
# shellcheck disable=SC2086 # a list of names
np=$(echo $WP_PROBLEMS | wc -w)
cols=3
rows=$(((np + 1 + cols - 1) / cols))
{
	echo "set terminal svg size $((cols * 520)),$((rows * 430)) dynamic enhanced font 'sans,11' background '#ffffff'"
	echo "set output '$OUT/work-precision.svg'"
	echo "set multiplot layout $rows,$cols title 'CSF work-precision: worst error against csfvm seconds (--stats), tolerances 1e-3 to 1e-12'"
	echo "set logscale xy; set format x '10^{%T}'; set format y '10^{%T}'; set grid"
	echo "set xlabel 'seconds'; set ylabel 'worst error (min of abs., rel.)'"
	echo "unset key"
	# a colour a method (in WP_METHODS order; cycled past 12), dashed lines for the implicit ones
	set -- '#9400d3' '#009e73' '#56b4e9' '#e69f00' '#b8a000' '#0072b2' '#e51e10' '#000000' '#cc79a7' '#8b4513' '#808080' '#2ca02c'
	i=0
	for m in $WP_METHODS; do
		i=$((i + 1))
		case $m in rk1imp | rk2imp | rk4imp | bsimp | msbdf) dt=2 ;; *) dt=1 ;; esac
		lc=''
		eval "lc=\${$(((i - 1) % 12 + 1))}"
		echo "set style line $i lc rgb '$lc' lw 1.5 pt $(((i - 1) % 13 + 1)) ps 0.6 dt $dt"
	done
	for p in $WP_PROBLEMS; do
		echo "set title '$p' noenhanced"
		printf 'plot'
		i=0 sep=
		for m in $WP_METHODS; do
			i=$((i + 1))
			if [ -s "$TMP/plot_${p}_$m.dat" ]; then
				printf "%s '%s' using 1:2 with linespoints ls %d title '%s'" "$sep" "$TMP/plot_${p}_$m.dat" "$i" "$m"
				sep=','
			fi
		done
		[ -n "$sep" ] || printf " NaN notitle"
		echo
	done
	# the last panel holds the key only
	echo "unset title; unset xlabel; unset ylabel; unset grid; unset tics; unset border; unset logscale"
	echo "set xrange [0:1]; set yrange [0:1]"
	echo "set key center center box title 'method (dashed: implicit)' noenhanced"
	printf 'plot'
	i=0 sep=
	for m in $WP_METHODS; do
		i=$((i + 1))
		printf "%s NaN with linespoints ls %d title '%s'" "$sep" "$i" "$m"
		sep=','
	done
	echo
	echo "unset multiplot"
} > "$TMP/work-precision.gp"
gnuplot "$TMP/work-precision.gp"

# ---- the summary ----

# The cheapest run (by seconds, ties by rhs_evals) reaching each accuracy level,
# with the cheapest run of another method for comparison; then, for the default,
# every method's loosest tolerance that meets 1e-6 on all the smooth problems.
cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
gsl=$(pkg-config --modversion gsl 2>/dev/null || echo "?")
awk -F, -v problems="$WP_PROBLEMS" -v methods="$WP_METHODS" -v tols="$WP_TOLS" -v skipfile="$SKIP" \
	-v date="$(date -u '+%Y-%m-%d %H:%M UTC')" -v host="$(uname -sm)" -v cpu="${cpu:-unknown}" -v ncpu="$ncpu" -v gsl="$gsl" \
	-v wall="$((END - START))" -v nruns="$nruns" -v limit="$WP_LIMIT" -v budget="$WP_BUDGET" -v reps="$WP_REPS" -v short="$WP_SHORT" '
function better(i, j) { return j == 0 || S[i] < S[j] || (S[i] == S[j] && N[i] < N[j]) }
function run(i) { return sprintf("%s %s | %.3g | %.2e | %d", M[i], T[i], E[i], S[i], N[i]) }
NR > 1 { n++; P[n] = $1; M[n] = $2; T[n] = $3; E[n] = $4 + 0; S[n] = $5 + 0; N[n] = $6 + 0
	key[$1, $2, $3] = n; tot[$1] += S[n] }
END {
	np = split(problems, pr, " "); nm = split(methods, me, " "); nt = split(tols, to, " ")
	nl = split("1e-3 1e-6 1e-9", lv, " ")
	printf "CSF work-precision, %s, %s, %s (%s CPUs), GSL %s\n\n", date, host, cpu, ncpu, gsl
	printf "%d measured runs (%d csfvm processes, runs under %s s repeated %d times, median kept) in %d s of wall time; per-run limit %s s, per problem/method budget %s s.\n\n", \
		n, nruns, short, reps, wall, limit, budget
	printf "Cheapest run reaching each accuracy (worst error over all output rows and watched values, min of absolute and relative; by csfvm seconds, ties by right-hand side evaluations), and the cheapest run of any other method:\n\n"
	printf "| problem | accuracy | cheapest: method tol | error | seconds | rhs evals | next other method: method tol | error | seconds | rhs evals |\n"
	printf "|---|---|---|---:|---:|---:|---|---:|---:|---:|\n"
	for (a = 1; a <= np; a++) for (l = 1; l <= nl; l++) {
		b = 0; c = 0
		for (i = 1; i <= n; i++) if (P[i] == pr[a] && E[i] <= lv[l] + 0 && better(i, b)) b = i
		if (b) for (i = 1; i <= n; i++) if (P[i] == pr[a] && M[i] != M[b] && E[i] <= lv[l] + 0 && better(i, c)) c = i
		printf "| %s | %s | %s | %s |\n", pr[a], lv[l], b ? run(b) : "none | | |", c ? run(c) : "none | | |"
	}
	printf "\nDefault method and tolerance: for each method, the loosest tolerance at which every smooth problem (all but stiff) is within 1e-6, and the seconds and right-hand side evaluations of those runs summed over the smooth problems:\n\n"
	printf "| method | loosest tol meeting 1e-6 | seconds (sum) | rhs evals (sum) | worst error | at tol 1e-10: seconds | worst error |\n"
	printf "|---|---|---:|---:|---:|---:|---:|\n"
	best = ""
	for (k = 1; k <= nm; k++) {
		m = me[k]; found = ""
		for (t = 1; t <= nt && found == ""; t++) {
			ok = 1; ss = 0; nn = 0; ww = 0; cnt = 0
			for (a = 1; a <= np; a++) {
				if (pr[a] == "stiff") continue
				cnt++; i = key[pr[a], m, to[t]]
				if (!i || E[i] > 1e-6) { ok = 0; break }
				ss += S[i]; nn += N[i]; if (E[i] > ww) ww = E[i]
			}
			if (ok && cnt) { found = to[t]; fs = ss; fn = nn; fw = ww }
		}
		ss = 0; ww = 0; ok = 1
		for (a = 1; a <= np; a++) { if (pr[a] == "stiff") continue; i = key[pr[a], m, "1e-10"]
			if (!i) { ok = 0; break } ss += S[i]; if (E[i] > ww) ww = E[i] }
		at10 = ok ? sprintf("%.2e | %.3g", ss, ww) : "(not run) |"
		if (found == "") printf "| %s | none | | | | %s |\n", m, at10
		else {
			printf "| %s | %s | %.2e | %d | %.3g | %s |\n", m, found, fs, fn, fw, at10
			if (best == "" || fs < bs || (fs == bs && fn < bn)) { best = m " at tol " found; bs = fs; bn = fn }
		}
		if (m == "rk8pd") { r10 = at10; r10ok = ok }
	}
	if (best != "") printf "\nCheapest setting within 1e-6 on every smooth problem: **%s** (%.2e s, %d rhs evaluations over the smooth problems).\n", best, bs, bn
	# the runs left out, one line per problem/method
	while ((getline line < skipfile) > 0) {
		if (++sl == 1) continue
		split(line, f, ","); k2 = f[1] " " f[2] SUBSEP f[4]
		if (!(k2 in first)) { first[k2] = f[3]; ord[++no] = k2 } last[k2] = f[3]
	}
	if (no) {
		printf "\nLeft out (see work-precision-skipped.csv for every tolerance and reason):\n\n"
		for (k = 1; k <= no; k++) { split(ord[k], g, SUBSEP); printf "- %s: tol %s%s: %s\n", g[1], first[ord[k]], \
			last[ord[k]] != first[ord[k]] ? " to " last[ord[k]] : "", g[2] }
	}
	printf "\nSeconds spent in csfvm runs per problem (sum of the recorded medians):"
	for (a = 1; a <= np; a++) printf " %s %.2f%s", pr[a], tot[pr[a]], a < np ? "," : "\n"
}' "$CSV" > "$OUT/work-precision.txt"
cat "$OUT/work-precision.txt"

sh ./readme_section.sh "$README" wp "$OUT/work-precision.txt"
say "work-precision: $nruns csfvm runs in $((END - START)) s; $OUT/work-precision.csv, $OUT/work-precision.svg"
