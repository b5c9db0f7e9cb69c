#!/bin/sh
# tests/piles/piles.sh CSFC CSFVM DIR [CASE...] - piles of balls (issue 28):
# each CASE, "N CR MU METHOD", is bench/gen_pile.sh's scene of N balls of
# restitution CR and friction mu_s = MU (mu_k = 0.8 MU) dropped into a 2-D
# box, run to 3 s with rows every 0.01 s under csfvm --method METHOD
# ("default": no --method, auto at its defaults; any other METHOD runs at
# --tol 1e-12, since at their default 1e-10 positions are good to only
# about 1e-8 m, csf(5), coarser than the 1e-9 checks; METHOD@TOL at --tol
# TOL), watching pos, v, FN
# and Ff. The run must end with exit 0 within PILES_LIMIT seconds (120) and every row must pass
# check.awk: no overlap, the energy never grows (and with CR = 1 and MU = 0
# stays E_0), forces consistent with the contacts, and, where the pile must
# be at rest by then, every ball at rest in equilibrium from t = 2.5 s.
#
# Without CASEs: N in 3 16 64 (or in $PILE_N), CR in 0 0.5 0.9 1, MU in 0
# 0.3, METHOD in default, rkf45 and msbdf (72 cases, at most 2 minutes each).
#
# When rest is required (rest_from below). A ball dropped onto the floor
# from rest at height h (of its centre) lands at t0 = sqrt(2 (h - r)/g) and
# its bounces end at tz = t0 (1 + e)/(1 - e) (csf(5), Rest). tz from the
# highest start, 0.1 + 0.12 (rows - 1) m, is 0.19, 0.29 and 0.43 s for
# N = 3, 16 and 64 at e = 0; 0.56, 0.87 and 1.28 s at e = 0.5; 3.5, 5.5 and
# 8.1 s at e = 0.9 (1.9 s even from the lowest row). So at e = 0.9 nothing
# need be at rest by 3 s, and no rest is required; at e <= 0.5 the vertical
# bounces are done well before 2.5 s. Horizontally, friction (MU > 0) stops
# a sliding ball in finite time; without friction a ball rattling between
# walls or balls with room to move loses a factor e of its speed at each hit
# while the time between hits grows by 1/e, so it never stops at e > 0:
# rest is required for MU = 0 only at e = 0, where each hit is plastic. The
# rule: rest from 2.5 s when tz <= 2.5 s and (MU > 0 or CR = 0). This is a
# bound for one ball, not a proof for a pile (a ball can land on one still
# bouncing); Box2D settles the same piles (with rolling) within 1.4 s
# (bench/README.md). With CR = 1: energy conserved when MU = 0, no rest.
#
# Every process has a time limit: TERM after its seconds, KILL 10 s later (TERM
# first, so that a csfvm behind tests/run.sh's timeout wrapper dies with it).
#
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
shift 3
LIMIT=${PILES_LIMIT:-120}
HERE=$(dirname "$0")
GEN=$HERE/../../bench/gen_pile.sh
TILL=3 BY=0.01 REST=2.5
pass=0 fail=0
# rest_from N CR MU: REST when the pile must be at rest by then, else nothing
rest_from() {
	awk -v n="$1" -v e="$2" -v mu="$3" -v rest=$REST 'BEGIN {
		w = int(sqrt(n)); if (w * w < n) w++
		rows = int((n + w - 1) / w); h = 0.1 + 0.12 * (rows - 1)
		if (e + 0 >= 1) exit
		tz = sqrt(2 * (h - 0.05) / 9.80665) * (1 + e) / (1 - e)
		if (tz <= rest && (mu + 0 > 0 || e + 0 == 0)) print rest
	}'
}
pile() { # N CR MU METHOD
	n=$1 cr=$2 mu=$3 method=$4
	label="pile N=$n cr=$cr mu=$mu method=$method"
	f=$T/pile_${n}_${cr}_${mu}_$method
	sh "$GEN" "$n" "$cr" "$mu" $TILL $BY "$f.csf" "pos, v, FN, Ff"
	if ! timeout -k 10 120 "$CSFC" "$f.csf" -o "$f.csfb" 2>"$f.err"; then
		fail=$((fail + 1)); echo "FAIL: $label: csfc: $(head -n 1 "$f.err")"; return
	fi
	margs=
	case $method in
	default) ;;
	*@*) margs="--method ${method%@*} --tol ${method#*@}" ;; # METHOD@TOL: at that tolerance
	*) margs="--method $method --tol 1e-12" ;;
	esac
	# shellcheck disable=SC2086 # margs holds csfvm options
	timeout -k 10 "$LIMIT" "$CSFVM" $margs "$f.csfb" >"$f.csv" 2>"$f.err"
	st=$?
	if [ $st -ne 0 ]; then
		fail=$((fail + 1))
		msg=$(grep -v '^warning' "$f.err" | head -n 1 | cut -c1-200)
		case $st in 124 | 137) msg="did not finish in $LIMIT s" ;; esac
		echo "FAIL: $label: csfvm exit $st after $(($(wc -l <"$f.csv") - 1)) rows: $msg"
		return
	fi
	xw=$(awk -v n="$n" 'BEGIN { w = int(sqrt(n)); if (w * w < n) w++; printf "%.15g", w * 0.12 + 0.1 }')
	rest=$(rest_from "$n" "$cr" "$mu")
	conserve=
	[ "$cr" = 1 ] && [ "$mu" = 0 ] && conserve=1
	rows=$(awk -v till=$TILL -v by=$BY 'BEGIN { printf "%d", till / by + 1.5 }')
	if timeout -k 10 120 awk -v xw="$xw" -v mu="$mu" -v rest="$rest" -v conserve="$conserve" -v by=$BY -v rows="$rows" \
		-v name="$label${rest:+ rest=$rest}${conserve:+ conserve}" -f "$HERE/check.awk" "$f.csv" >"$f.chk" 2>&1; then
		pass=$((pass + 1)); [ -n "${VERBOSE:-}" ] && cat "$f.chk"
	else
		fail=$((fail + 1)); echo "FAIL: $(head -n 1 "$f.chk")"
	fi
}
if [ $# -gt 0 ]; then
	for c in "$@"; do
		# shellcheck disable=SC2086 # a case is four words
		pile $c
	done
else
	for n in ${PILE_N:-3 16 64}; do
		for cr in 0 0.5 0.9 1; do
			for mu in 0 0.3; do
				for method in default rkf45 msbdf; do pile "$n" "$cr" "$mu" "$method"; done
			done
		done
	done
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
