#!/bin/sh
# stiff.sh - the stiff reference problems of issue 26 at the defaults
# (--method auto) against the stiff methods chosen by hand: van der Pol's
# oscillator (mu = 1000, to 2000 s), Robertson's kinetics (to 1e11 s), the
# Oregonator (to 360) and HIRES (to 321.8122), the models in stiff/ and their
# reference values (the IVP Test Set's) below. Each run once per repetition
# under csfvm --stats: right-hand side and Jacobian evaluations, the run's
# seconds from --stats (the integration, not the process), the best of REPS;
# the largest error over the components of the last row (each the smaller of
# absolute and relative, as --compare-methods measures); and for the
# defaults, evaluations and time over those of the best method by hand (the
# one of bsimp and msbdf with fewer evaluations). The target: every default
# run within 1e-6 of the reference, exit 0, within 3 times the evaluations
# and the time of the best by hand.
# Writes $OUT/stiff.csv and $OUT/stiff.txt, and the stiff section of $README.
#   BUILD (../build), OUT (results), README (README.md; empty: leave it alone), REPS (3)
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
OUT=${OUT:-results}
README=${README-README.md}
REPS=${REPS:-3}
TMP=$OUT/scratch.tmp CSV=$OUT/stiff.csv
mkdir -p "$TMP" # and $OUT
echo "problem,method,exit,steps,rhs,jac,seconds,error" > "$CSV"

. ./stiff_lib.sh

for p in vdp robertson oregonator hires; do
	"$BUILD/csfc" "stiff/$p.csf" -o "$TMP/$p.csfb"
	for m in default bsimp msbdf; do
		if [ $m = default ]; then r=$(stiff_run $p "$TMP/$p.csfb"); else r=$(stiff_run $p "$TMP/$p.csfb" --method $m); fi
		echo "$p,$m,$r" >> "$CSV"
	done
done

awk -F, 'NR > 1 { k = $1; S[k, $2] = $0; st[k, $2] = $3; f[k, $2] = $5; j[k, $2] = $6; s[k, $2] = $7; e[k, $2] = $8
	if (!(k in seen)) { seen[k] = 1; order[++n] = k } }
	END {
		print "| problem | at the defaults (auto): evaluations (Jacobians), ms, error, exit | bsimp | msbdf | defaults / best by hand: evaluations, time |"
		print "|---|---|---|---|---|"
		ok = 1
		for (i = 1; i <= n; i++) {
			k = order[i]; b = f[k, "bsimp"] <= f[k, "msbdf"] ? "bsimp" : "msbdf"
			re = f[k, "default"] / f[k, b]; rt = s[k, "default"] / s[k, b]
			if (st[k, "default"] != 0 || e[k, "default"] > 1e-6 || re > 3 || rt > 3) ok = 0
			line = "| " k
			split("default bsimp msbdf", ms, " ")
			for (q = 1; q <= 3; q++) { m = ms[q]
				line = line sprintf(" | %d (%d), %.2f, %s, %d", f[k, m], j[k, m], 1000 * s[k, m], e[k, m], st[k, m]) }
			print line sprintf(" | %.2f (%s), %.2f |", re, b, rt)
		}
		print ""
		print (ok ? "Every default run within 1e-6, exit 0, within 3 times the evaluations and time of the best by hand." \
		          : "NOT MET: a default run misses 1e-6, exits non-zero, or costs more than 3 times the best by hand.")
	}' "$CSV" > "$OUT/stiff.txt"
cat "$OUT/stiff.txt"
sh ./readme_section.sh "$README" stiff "$OUT/stiff.txt"
rm -rf "$TMP"
