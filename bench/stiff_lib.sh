# stiff_lib.sh - what stiff.sh and cvode.sh share (sourced; needs BUILD, REPS, TMP):
# the stiff problems' reference values and one measured csfvm run.

# stiff_ref PROBLEM: the reference values of stiff/PROBLEM.csf at its end time (the IVP Test Set's)
stiff_ref() {
	case $1 in
	vdp) echo "1.706167732170483 -8.928097010247975e-4" ;;
	robertson) echo "2.083340149701255e-8 8.333360770334713e-14 0.9999999791665050" ;;
	oregonator) echo "1.000814870318523 1228.178521549917 132.0554942846706" ;;
	hires) echo "0.7371312573325668e-3 0.1442485726316185e-3 0.5888729740967575e-4 0.1175651343283149e-2" \
		"0.2386356198831331e-2 0.6238968252742796e-2 0.2849998395185769e-2 0.2850001604814231e-2" ;;
	esac
}

# stiff_run PROBLEM CSFB [CSFVM OPTIONS...]: runs csfvm --stats REPS times and prints
# "exit,steps,rhs,jac,seconds,error": the best run's (fewest seconds) counts and time from
# --stats, and the largest error of the last row against stiff_ref (each component's
# smaller of absolute and relative error)
stiff_run() {
	p=$1 csfb=$2
	shift 2
	best=
	for _ in $(seq "$REPS"); do
		st=0
		timeout 600 "$BUILD/csfvm" --stats "$@" "$csfb" >"$TMP/run.csv" 2>"$TMP/run.err" || st=$?
		row=$(awk -F'[ ,;()]+' '/^stats: method/ { for (i = 1; i <= NF; i++) { if ($(i + 1) == "steps") s = $i
			if ($(i + 1) == "right-hand") f = $i; if ($(i + 1) == "Jacobian") j = $i; if ($i ~ /^[0-9.]+$/) last = $i }
			print s "," f "," j "," last }' "$TMP/run.err")
		secs=${row##*,}
		if [ -z "$best" ] || awk -v a="$secs" -v b="${best##*,}" 'BEGIN { exit !(a < b) }'; then best=$row; fi
	done
	err=$(tail -n 1 "$TMP/run.csv" | awk -F, -v ref="$(stiff_ref "$p")" '
		function abs(x) { return x < 0 ? -x : x }
		{ n = split(ref, r, " "); for (i = 1; i <= n; i++) { d = abs($(i + 1) - r[i]); if (r[i] != 0 && d / abs(r[i]) < d) d = d / abs(r[i]); if (d > m) m = d }
		  printf "%.3g", m }')
	echo "$st,$best,$err"
}
