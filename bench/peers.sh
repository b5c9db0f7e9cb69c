#!/bin/sh
# peers.sh - CSF side by side with SciPy's solve_ivp (see README.md, "Peers:
# SciPy's solve_ivp"). Run by `make peers` in bench/ (`make bench-peers` at
# the top); not part of `make bench` or `make check`.
#
# The problems: the work-precision problems wp/*.csf (exact answers, error
# by wp/err.awk and the problem's awk) and the n-body scene of gen_nbody.sh
# (error: the worst absolute position error against a reference run,
# peers_nbody.awk). Each is run by csfvm under every method at every
# tolerance (csfvm --method M --tol T --stats) and by peers.py (SciPy's
# solve_ivp, methods RK45 DOP853 Radau BDF LSODA, rtol = atol = T), each run
# its own process, timed whole by bin/timeit. One row per run goes to
# $OUT/peers.csv:
#   problem,program,method,tol,error,evaluations,integration_seconds,process_seconds,jacobian_evaluations
# the runs left out to $OUT/peers-skipped.csv, and the summary (the fastest
# run of each program reaching each accuracy, and their ratio) to
# $OUT/peers.txt, which also replaces the part of $README between the
# peers:begin and peers:end markers.
#
#   BUILD       directory holding csfc and csfvm              (default ../build)
#   BIN         directory holding timeit                      (default bin)
#   OUT         where the results go                          (default results)
#   README      file whose peers section is rewritten (default README.md;
#               empty: leave it alone)
#   PYTHON      a python3 with numpy and scipy (default: python3 if it has
#               them, else /usr/bin/python3, Debian's: python3-scipy)
#   PEERS_PROBLEMS  (default: harmonic kepler_e05 kepler_e09 linear_drag
#               stiff nbody64); nbodyN is gen_nbody.sh's scene of N bodies
#   PEERS_NB_TILL, PEERS_NB_BY  the n-body run's end and output step (2, 0.05)
#   PEERS_CSF_METHODS  csfvm's methods (default: every method `csfvm --help`
#               lists, except the fixed-step ones, which take no tolerance)
#   PEERS_SCIPY_METHODS  (default: RK45 DOP853 Radau BDF LSODA)
#   PEERS_TOLS  tolerances, loosest first (default 1e-3 ... 1e-13)
#   PEERS_LEVELS  the accuracies of the summary (default 1e-4 ... 1e-10)
#   PEERS_NB_LEVEL  the accuracy of the n-body evaluations target (1e-6)
#   PEERS_LIMIT wall seconds a single process may take (`timeout`); a run
#               that hits it, or whose predicted time exceeds it, stops that
#               problem/program/method (default 10)
#   PEERS_BUDGET  seconds all the runs of one problem/program/method may
#               take together (default 30)
#   PEERS_REPS  runs whose integration takes under PEERS_SHORT seconds
#               (default 0.2) are repeated, PEERS_REPS runs in all (default
#               3), and the median of each time kept
#
# Times: process_seconds is the whole process, from fork to exit (bin/timeit:
# csfvm's start-up and loading of the bytecode; python's start-up and
# imports), integration_seconds the program's own (csfvm --stats: the
# integration and the output; peers.py: solve_ivp and writing the rows).
# csfc's compile of each model is timed once and shown in the summary.
# Needs POSIX sh, awk, sort, timeout (coreutils), python3 with numpy and scipy.
set -eu

BUILD=${BUILD:-../build}
case $BUILD in ..//*) BUILD=${BUILD#..} ;; esac
BIN=${BIN:-bin}
OUT=${OUT:-results}
README=${README-README.md}
PEERS_PROBLEMS=${PEERS_PROBLEMS:-harmonic kepler_e05 kepler_e09 linear_drag stiff nbody64}
PEERS_NB_TILL=${PEERS_NB_TILL:-2}
PEERS_NB_BY=${PEERS_NB_BY:-0.05}
PEERS_SCIPY_METHODS=${PEERS_SCIPY_METHODS:-RK45 DOP853 Radau BDF LSODA}
PEERS_TOLS=${PEERS_TOLS:-1e-3 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10 1e-11 1e-12 1e-13}
PEERS_LEVELS=${PEERS_LEVELS:-1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10}
PEERS_NB_LEVEL=${PEERS_NB_LEVEL:-1e-6}
PEERS_LIMIT=${PEERS_LIMIT:-10}
PEERS_BUDGET=${PEERS_BUDGET:-30}
PEERS_REPS=${PEERS_REPS:-3}
PEERS_SHORT=${PEERS_SHORT:-0.2}

CSFC=$BUILD/csfc
CSFVM=$BUILD/csfvm
TIMEIT=$BIN/timeit
WP=wp
say() { printf '%s\n' "$*" >&2; }
for p in "$CSFC" "$CSFVM" "$TIMEIT"; do
	[ -x "$p" ] || { say "peers.sh: $p is missing: build it first (make bench-peers from the top)"; exit 2; }
done
case $PEERS_REPS in '' | *[!0-9]* | 0) say "peers.sh: PEERS_REPS must be a positive integer"; exit 2 ;; esac
if command -v timeout > /dev/null 2>&1; then TIMEOUT="timeout $PEERS_LIMIT"; else
	TIMEOUT=; say "peers.sh: no timeout(1): runs are not limited to $PEERS_LIMIT s"; fi

if [ -z "${PYTHON:-}" ]; then
	for c in python3 /usr/bin/python3; do
		if "$c" -c 'import numpy, scipy.integrate' > /dev/null 2>&1; then PYTHON=$c; break; fi
	done
fi
if [ -z "${PYTHON:-}" ] || ! "$PYTHON" -c 'import numpy, scipy.integrate' > /dev/null 2>&1; then
	say "peers.sh: no python3 with numpy and scipy (Debian: apt-get install python3-scipy, or make deps-peers)"
	exit 2
fi

# csfvm's methods, from its --help: the names after the "--method NAME" option's
# labels ("ODE stepper:", "implicit, ...:"), without parenthesised remarks and
# without the fixed-step group (it takes no tolerance).
if [ -z "${PEERS_CSF_METHODS:-}" ]; then
	PEERS_CSF_METHODS=$("$CSFVM" --help 2>&1 | awk '
		/^ *--method/ { on = 1; sub(/^ *--method *NAME */, ""); s = $0; next }
		on && /^ *--/ { on = 0 }
		on { s = s " " $0 }
		END {
			n = split(s, seg, ";")
			for (k = 1; k <= n; k++) {
				if (seg[k] ~ /fixed/) continue
				g = seg[k]; gsub(/\([^)]*\)/, "", g); sub(/.*:/, "", g)
				m = split(g, w, /[ ,]+/)
				for (i = 1; i <= m; i++) if (w[i] ~ /^[a-z][a-z0-9_-]*$/) out = out (out == "" ? "" : " ") w[i]
			}
			print out
		}')
	# keep only names csfvm accepts, where its message for an unknown method lists them
	known=$("$CSFVM" --method '?' /dev/null 2>&1 | sed -n 's/.*unknown method.*(one of: \([^)]*\)).*/\1/p' || true)
	if [ -n "$known" ]; then
		PEERS_CSF_METHODS=$(echo "$PEERS_CSF_METHODS" | awk -v k="$known" '{
			n = split(k, a, " "); for (i = 1; i <= n; i++) ok[a[i]] = 1
			for (i = 1; i <= NF; i++) if ($i in ok) out = out (out == "" ? "" : " ") $i
			print out }')
	fi
	[ -n "$PEERS_CSF_METHODS" ] || { say "peers.sh: could not read the methods from csfvm --help: set PEERS_CSF_METHODS"; exit 2; }
fi
say "peers: csfvm methods: $PEERS_CSF_METHODS; SciPy methods: $PEERS_SCIPY_METHODS; python: $PYTHON"

TMP=$OUT/peers.tmp
rm -rf "$TMP"
mkdir -p "$TMP"
CSV=$TMP/peers.csv
SKIP=$TMP/peers-skipped.csv
INFO=$TMP/info.txt
echo "problem,program,method,tol,error,evaluations,integration_seconds,process_seconds,jacobian_evaluations" > "$CSV"
echo "problem,program,method,tol,reason" > "$SKIP"
: > "$INFO"
START=$(date +%s)

# errof PROBLEM OUTFILE : the worst error of a run, or nothing (exit 1).
errof() {
	case $1 in
	kepler_e05) awk -F, -v ecc=0.5 -f "$WP/err.awk" -f "$WP/kepler.awk" "$2" ;;
	kepler_e09) awk -F, -v ecc=0.9 -f "$WP/err.awk" -f "$WP/kepler.awk" "$2" ;;
	nbody*) awk -F, -v ref="$TMP/$1.ref.csv" -f peers_nbody.awk "$2" ;;
	*) awk -F, -f "$WP/err.awk" -f "$WP/$1.awk" "$2" ;;
	esac
}

# stat FIELD FILE : from the stats line of csfvm (stats: ...) or peers.py
# (peers: ...): seconds, rhs or jac evaluations.
stat() {
	awk -v f="$1" '/^(stats|peers):/ {
		if (f == "seconds") v = $(NF - 1)
		else for (i = 2; i <= NF; i++) {
			w = $i; sub(/,$/, "", w)
			if (f == "rhs" && (w == "right-hand" && i > 1)) v = $(i - 1)
			if (f == "rhs" && w == "nfev") { v = $(i + 1); sub(/,$/, "", v) }
			if (f == "jac" && w == "Jacobian") v = $(i - 1)
			if (f == "jac" && w == "njev") { v = $(i + 1); sub(/,$/, "", v) }
		}
	} END { if (v == "") exit 1; print v }' "$2"
}

# median of a list of numbers
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# skip PROBLEM PROGRAM METHOD TOL REASON
skip() { echo "$1,$2,$3,$4,$5" >> "$SKIP"; }

# runonce PROGRAM PROBLEM METHOD TOL : one timed process; output in $TMP/run.csv,
# stats in $TMP/run.err, timeit's line in $TMP/run.time; returns its status.
runonce() {
	if [ "$1" = csf ]; then
		# shellcheck disable=SC2086 # TIMEOUT is a command and its argument, or nothing
		$TIMEOUT "$TIMEIT" "$TMP/run.csv" "$CSFVM" --method "$3" --tol "$4" --stats "$TMP/$2.csfb" \
			> "$TMP/run.time" 2> "$TMP/run.err"
	else
		case $2 in
		nbody*)
			# shellcheck disable=SC2086
			$TIMEOUT "$TIMEIT" "$TMP/run.csv" "$PYTHON" peers.py run nbody "$3" "$4" "$TMP/$2.ic" \
				"$PEERS_NB_TILL" "$PEERS_NB_BY" > "$TMP/run.time" 2> "$TMP/run.err" ;;
		*)
			# shellcheck disable=SC2086
			$TIMEOUT "$TIMEIT" "$TMP/run.csv" "$PYTHON" peers.py run "$2" "$3" "$4" \
				> "$TMP/run.time" 2> "$TMP/run.err" ;;
		esac
	fi
}

# ---- the models, their compile times, the n-body reference ----

for p in $PEERS_PROBLEMS; do
	case $p in
	nbody*)
		n=${p#nbody}
		case $n in '' | *[!0-9]*) say "peers.sh: $p: nbodyN needs a number of bodies"; exit 2 ;; esac
		sh ./gen_nbody.sh "$n" "$PEERS_NB_TILL" "$PEERS_NB_BY" "$TMP/$p.csf" "$TMP/$p.ic"
		;;
	*)
		[ -f "$WP/$p.csf" ] || { say "peers.sh: no problem $WP/$p.csf"; exit 2; }
		cp "$WP/$p.csf" "$TMP/$p.csf"
		;;
	esac
	cs=$("$TIMEIT" /dev/null "$CSFC" "$TMP/$p.csf" -o "$TMP/$p.csfb" | awk '{ print $1 }')
	[ -s "$TMP/$p.csfb" ] || { say "peers.sh: $p does not compile"; exit 1; }
	echo "compile $p $cs" >> "$INFO"
	case $p in
	nbody*)
		# the reference: csfvm rk8pd at 1e-13, checked against SciPy's DOP853 at 1e-13
		"$CSFVM" --method rk8pd --tol 1e-13 "$TMP/$p.csfb" > "$TMP/$p.ref.csv"
		"$PYTHON" peers.py run nbody DOP853 1e-13 "$TMP/$p.ic" "$PEERS_NB_TILL" "$PEERS_NB_BY" \
			> "$TMP/$p.dop.csv" 2> /dev/null
		d=$(errof "$p" "$TMP/$p.dop.csv") || { say "peers.sh: $p: the error measure failed"; exit 1; }
		echo "refcheck $p $d" >> "$INFO"
		awk -v e="$d" 'BEGIN { exit !(e < 1e-9) }' ||
			{ say "peers.sh: $p: the reference and SciPy's DOP853 at 1e-13 differ by $d: the models differ"; exit 1; }
		;;
	*)
		# the exact answers and both programs' models: a tight run of each must be close
		"$CSFVM" --tol 1e-12 --method "$( [ "$p" = stiff ] && echo msbdf || echo rk8pd)" "$TMP/$p.csfb" > "$TMP/check.csv"
		e=$(errof "$p" "$TMP/check.csv") || { say "peers.sh: $p: the error measure failed"; exit 1; }
		"$PYTHON" peers.py run "$p" "$( [ "$p" = stiff ] && echo Radau || echo DOP853)" 1e-12 > "$TMP/check.csv" 2> /dev/null
		e2=$(errof "$p" "$TMP/check.csv") || { say "peers.sh: $p: the error measure failed on peers.py's output"; exit 1; }
		awk -v e="$e" -v f="$e2" 'BEGIN { exit !(e < 1e-6 && f < 1e-6) }' ||
			{ say "peers.sh: $p: error $e (csfvm) and $e2 (SciPy) at tol 1e-12: the exact answer or a model is wrong"; exit 1; }
		;;
	esac
done

# SciPy's fixed cost: python3 importing numpy and scipy.integrate, nothing else
st=''
for r in 1 2 3; do st="$st $("$TIMEIT" /dev/null "$PYTHON" -c 'import numpy, scipy.integrate' | awk '{ print $1 }')"; done
# shellcheck disable=SC2086 # a list of numbers
echo "pystart $(median $st)" >> "$INFO"

# ---- the runs ----

nproc=0
for p in $PEERS_PROBLEMS; do
	for prog in csf scipy; do
		if [ "$prog" = csf ]; then methods=$PEERS_CSF_METHODS; else methods=$PEERS_SCIPY_METHODS; fi
		for m in $methods; do
			stop='' s1='' s2='' cum=0
			for tol in $PEERS_TOLS; do
				if [ -n "$stop" ]; then skip "$p" "$prog" "$m" "$tol" "$stop"; continue; fi
				# Predict this run's process time from the last two: the last one times
				# their ratio (at least 1, at most 10); skip above the limit or the budget.
				pred=$(awk -v a="${s2:-}" -v b="${s1:-}" 'BEGIN { if (b == "") { print 0; exit }
					r = (a != "" && a >= 0.01) ? b / a : 1; if (r < 1) r = 1; if (r > 10) r = 10; printf "%.6g\n", b * r }')
				why=$(awk -v p="$pred" -v c="$cum" -v l="$PEERS_LIMIT" -v g="$PEERS_BUDGET" 'BEGIN {
					if (p > l) printf "predicted %.3g s > limit %s s", p, l
					else if (c + p > g) printf "predicted %.3g s would take the total over the budget %s s", p, g }')
				if [ -n "$why" ]; then stop=$why; skip "$p" "$prog" "$m" "$tol" "$stop"; continue; fi
				ps='' is='' rc=0 r=1
				while [ "$r" -le "$PEERS_REPS" ]; do
					rc=0
					runonce "$prog" "$p" "$m" "$tol" || rc=$?
					nproc=$((nproc + 1))
					[ "$rc" -eq 0 ] || break
					pt=$(awk '{ print $1 }' "$TMP/run.time")
					it=$(stat seconds "$TMP/run.err") || { rc=1; break; }
					ps="$ps $pt" is="$is $it"
					cum=$(awk -v c="$cum" -v s="$pt" 'BEGIN { print c + s }')
					if [ "$r" -eq 1 ]; then
						cp "$TMP/run.csv" "$TMP/first.csv"
						cp "$TMP/run.err" "$TMP/first.err"
						awk -v s="$it" -v t="$PEERS_SHORT" 'BEGIN { exit !(s >= t) }' && break
					fi
					r=$((r + 1))
				done
				if [ "$rc" -eq 124 ]; then
					stop="timed out (over $PEERS_LIMIT s)"
					cum=$(awk -v c="$cum" -v s="$PEERS_LIMIT" 'BEGIN { print c + s }')
					skip "$p" "$prog" "$m" "$tol" "$stop"
					continue
				elif [ "$rc" -ne 0 ]; then
					msg=$(grep -v -e '^stats:' -e '^peers:' -e '^warning:' "$TMP/run.err" | tail -n 1 | sed 's/^[^:]*: //; s/,/;/g' | cut -c1-200)
					skip "$p" "$prog" "$m" "$tol" "failed (exit $rc: $msg)"
					continue
				fi
				# shellcheck disable=SC2086 # lists of numbers
				pt=$(median $ps) it=$(median $is)
				n=$(stat rhs "$TMP/first.err") || n=''
				j=$(stat jac "$TMP/first.err") || j=''
				if ! e=$(errof "$p" "$TMP/first.csv" 2> "$TMP/err.msg"); then
					skip "$p" "$prog" "$m" "$tol" "no error measure ($(head -n 1 "$TMP/err.msg" | sed 's/,/;/g'))"
					continue
				fi
				echo "$p,$prog,$m,$tol,$e,$n,$it,$pt,$j" >> "$CSV"
				s2=$s1 s1=$pt
			done
			say "$p $prog $m: total $cum s${stop:+; stopped: $stop}"
		done
	done
done
END=$(date +%s)

mkdir -p "$OUT"
cp "$CSV" "$OUT/peers.csv"
cp "$SKIP" "$OUT/peers-skipped.csv"

# ---- the summary ----

cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
ncpu=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo "?")
pyver=$("$PYTHON" -c 'import sys, numpy, scipy; print("Python %d.%d.%d, numpy %s, SciPy %s" % (sys.version_info[:3] + (numpy.__version__, scipy.__version__)))')
gsl=$(pkg-config --modversion gsl 2>/dev/null || echo "?")
awk -F, -v problems="$PEERS_PROBLEMS" -v levels="$PEERS_LEVELS" -v nblevel="$PEERS_NB_LEVEL" \
	-v skipfile="$SKIP" -v infofile="$INFO" -v tols="$PEERS_TOLS" \
	-v csfmethods="$PEERS_CSF_METHODS" -v scipymethods="$PEERS_SCIPY_METHODS" \
	-v date="$(date -u '+%Y-%m-%d %H:%M UTC')" -v host="$(uname -sm)" -v cpu="${cpu:-unknown}" -v ncpu="$ncpu" \
	-v gsl="$gsl" -v pyver="$pyver" -v wall="$((END - START))" -v nproc="$nproc" -v limit="$PEERS_LIMIT" \
	-v budget="$PEERS_BUDGET" -v reps="$PEERS_REPS" -v short="$PEERS_SHORT" -v nbtill="$PEERS_NB_TILL" -v nbby="$PEERS_NB_BY" '
# fastest run of program g on problem p reaching accuracy lv, by time column c
# (IS: integration, PS: process), ties by evaluations
function fastest(p, g, lv, c,   i, b) {
	b = 0
	for (i = 1; i <= n; i++) if (P[i] == p && G[i] == g && E[i] <= lv + 0 &&
		(b == 0 || T(i, c) < T(b, c) || (T(i, c) == T(b, c) && N[i] < N[b]))) b = i
	return b
}
function cheapest(p, g, lv,   i, b) {
	b = 0
	for (i = 1; i <= n; i++) if (P[i] == p && G[i] == g && E[i] <= lv + 0 &&
		(b == 0 || N[i] < N[b] || (N[i] == N[b] && PS[i] < PS[b]))) b = i
	return b
}
function T(i, c) { return c == "IS" ? IS[i] : PS[i] }
function desc(i, c) { return i ? sprintf("%s %s | %.3g | %.3g", M[i], TL[i], E[i], T(i, c)) : "none | | " }
function jacs(i) { return J[i] != "" && J[i] + 0 > 0 ? sprintf(" (+%d Jacobian)", J[i]) : "" }
function verdict(b, c, ratio) {
	if (!b && !c) return "n/a (neither reaches it)"
	if (!b) return "target missed (CSF does not reach it)"
	if (!c) return "target met (SciPy does not reach it)"
	return ratio > 1 ? "target met" : "target missed"
}
function table(c, title,   a, l, b, d, ratio, s) {
	printf "%s\n\n", title
	printf "| problem | accuracy | CSF: method tol | error | seconds | SciPy: method tol | error | seconds | SciPy / CSF | |\n"
	printf "|---|---|---|---:|---:|---|---:|---:|---:|---|\n"
	for (a = 1; a <= np; a++) for (l = 1; l <= nl; l++) {
		b = fastest(pr[a], "csf", lv[l], c); d = fastest(pr[a], "scipy", lv[l], c)
		ratio = (b && d) ? T(d, c) / T(b, c) : 0
		s = verdict(b, d, ratio)
		printf "| %s | %s | %s | %s | %s | %s |\n", pr[a], lv[l], desc(b, c), desc(d, c), (b && d) ? sprintf("%.2f", ratio) : "", s
		cnt[c, s ~ /met/ ? "met" : s ~ /missed/ ? "missed" : "na"]++
		if (s ~ /missed/) miss[c] = miss[c] sprintf("%s%s at %s", miss[c] == "" ? "" : ", ", pr[a], lv[l])
	}
	printf "\n"
}
NR > 1 { n++; P[n] = $1; G[n] = $2; M[n] = $3; TL[n] = $4; E[n] = $5 + 0; N[n] = $6 + 0; IS[n] = $7 + 0; PS[n] = $8 + 0; J[n] = $9
	runs[$2]++ }
END {
	np = split(problems, pr, " "); nl = split(levels, lv, " ")
	while ((getline line < infofile) > 0) {
		split(line, f, " ")
		if (f[1] == "compile") comp[f[2]] = f[3]
		if (f[1] == "refcheck") refd[f[2]] = f[3]
		if (f[1] == "pystart") pystart = f[2]
	}
	printf "CSF and SciPy'"'"'s solve_ivp, %s, %s, %s (%s CPUs); GSL %s; %s\n\n", date, host, cpu, ncpu, gsl, pyver
	printf "%d measured runs (%d csfvm, %d solve_ivp; %d processes, runs whose integration took under %s s repeated %d times and the median of each time kept) in %d s of wall time; per-process limit %s s, per problem/program/method budget %s s. Tolerances %s; csfvm methods: %s; SciPy methods: %s (rtol = atol = tol; the implicit ones and LSODA with the exact Jacobian).\n\n", \
		n, runs["csf"], runs["scipy"], nproc, short, reps, wall, limit, budget, tols, csfmethods, scipymethods
	table("PS", "**Whole process** (fork to exit: csfvm with its start-up and loading; python3 with its start-up and imports of numpy and scipy). The fastest run of each program whose worst error is within each accuracy, and SciPy / CSF (> 1: CSF ahead; the target is CSF ahead everywhere):")
	table("IS", "**Integration only** (csfvm --stats: the integration and output; peers.py: solve_ivp and writing the rows). The fastest of each by this time, which may be another run:")
	printf "Fixed costs, not in the integration times: python3 importing numpy and scipy.integrate and doing nothing else takes %.3f s (median of 3 processes); csfc compiles each model once (not in the times above):", pystart
	for (a = 1; a <= np; a++) printf " %s %.3f s%s", pr[a], comp[pr[a]], a < np ? "," : ".\n"
	# the n-body scenes: evaluations
	for (a = 1; a <= np; a++) if (pr[a] ~ /^nbody/) {
		p = pr[a]
		printf "\n**%s** (gen_nbody.sh %s %s %s: rows every %s s over %s s; error: worst absolute position error of the watched bodies over all rows against csfvm rk8pd at tol 1e-13, which SciPy'"'"'s DOP853 at rtol = atol = 1e-13 matches within %s m). Right-hand side evaluations of the cheapest run of each program reaching each accuracy (Jacobian evaluations beside; target at %s: CSF at most 1.5 times SciPy'"'"'s):\n\n", \
			p, substr(p, 6), nbtill, nbby, nbby, nbtill, refd[p], nblevel
		printf "| accuracy | CSF: method tol | error | evaluations | SciPy: method tol | error | evaluations | CSF / SciPy | |\n"
		printf "|---|---|---:|---:|---|---:|---:|---:|---|\n"
		for (l = 1; l <= nl; l++) {
			b = cheapest(p, "csf", lv[l]); d = cheapest(p, "scipy", lv[l])
			ratio = (b && d && N[d] > 0) ? N[b] / N[d] : 0
			if (lv[l] + 0 == nblevel + 0) {
				s = !b ? "target missed (CSF does not reach it)" : !d ? "target met (SciPy does not reach it)" : ratio <= 1.5 ? "target met" : "target missed"
				nbverdict[p] = s; nbratio[p] = ratio
			} else s = ""
			printf "| %s | %s | %s | %s | %s |\n", lv[l], \
				b ? sprintf("%s %s | %.3g | %d%s", M[b], TL[b], E[b], N[b], jacs(b)) : "none | |", \
				d ? sprintf("%s %s | %.3g | %d%s", M[d], TL[d], E[d], N[d], jacs(d)) : "none | |", \
				(b && d) ? sprintf("%.2f", ratio) : "", s
		}
	}
	printf "\nTargets: whole process, CSF ahead: %d met, %d missed, %d with neither reaching the accuracy", cnt["PS", "met"], cnt["PS", "missed"], cnt["PS", "na"]
	printf "%s. Integration only (for comparison): %d met, %d missed%s.", miss["PS"] != "" ? " (missed: " miss["PS"] ")" : "", cnt["IS", "met"], cnt["IS", "missed"], miss["IS"] != "" ? " (missed: " miss["IS"] ")" : ""
	for (a = 1; a <= np; a++) if (pr[a] in nbverdict)
		printf " %s evaluations at %s, CSF at most 1.5 times SciPy: %s (%.2f).", pr[a], nblevel, nbverdict[pr[a]], nbratio[pr[a]]
	printf "\n"
	# best error reached by each program on each problem
	printf "\nBest error reached on each problem (any method and tolerance): "
	for (a = 1; a <= np; a++) {
		bc = ""; bs = ""
		for (i = 1; i <= n; i++) if (P[i] == pr[a]) {
			if (G[i] == "csf" && (bc == "" || E[i] < bc)) bc = E[i]
			if (G[i] == "scipy" && (bs == "" || E[i] < bs)) bs = E[i]
		}
		printf "%s CSF %s, SciPy %s%s", pr[a], bc == "" ? "none" : sprintf("%.3g", bc), bs == "" ? "none" : sprintf("%.3g", bs), a < np ? "; " : ".\n"
	}
	# the runs left out, one line per problem/program/method and reason
	while ((getline line < skipfile) > 0) {
		if (++sl == 1) continue
		split(line, f, ","); k2 = f[1] " " (f[2] == "csf" ? "csfvm" : "SciPy") " " f[3] SUBSEP f[5]
		if (!(k2 in first)) { first[k2] = f[4]; ord[++no] = k2 } last[k2] = f[4]
	}
	if (no) {
		printf "\nLeft out (peers-skipped.csv has every tolerance and reason):\n\n"
		for (k = 1; k <= no; k++) { split(ord[k], g, SUBSEP); printf "- %s: tol %s%s: %s\n", g[1], first[ord[k]], \
			last[ord[k]] != first[ord[k]] ? " to " last[ord[k]] : "", g[2] }
	}
}' "$CSV" > "$OUT/peers.txt"
cat "$OUT/peers.txt"

sh ./readme_section.sh "$README" peers "$OUT/peers.txt"
say "peers: $nproc processes in $((END - START)) s; $OUT/peers.csv, $OUT/peers.txt"
