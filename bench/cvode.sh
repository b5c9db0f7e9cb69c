#!/bin/sh
# cvode.sh - SUNDIALS CVODE beside csfvm's stiff methods on the stiff reference
# problems of stiff.sh (stiff/: van der Pol mu = 1000 to 2000 s, Robertson to
# 1e11 s, the Oregonator to 360, HIRES to 321.8122). CVODE (cvode.c: BDF,
# Newton, the dense direct linear solver, the analytic Jacobian, the problems
# written in C from the scenes) against csfvm --method msbdf, --method bsimp and
# the defaults (auto), all at each tolerance of CVODE_TOLS: csfvm --tol TOL, and
# CVODE with relative tolerance TOL and absolute tolerance TOL times csfvm's
# scale of the component (1, or HIRES's y8 at 0.0057: cvode.c). At 1e-10 csfvm
# runs bsimp and msbdf at their default tolerance; auto's dop853 gets 1e-10
# rather than its default 1e-12 (so the auto column at 1e-10 is not stiff.sh's).
# Per run: right-hand side evaluations (CVODE: nfe + nfeLS), Jacobian
# evaluations, steps, the integration's seconds (csfvm: --stats; CVODE:
# clock_gettime around CVode), the best of REPS; the largest error over the
# components at the end (each the smaller of absolute and relative, as
# stiff.sh). Writes $OUT/cvode.csv and $OUT/cvode.txt, and the cvode section
# of $README.
#   BUILD (../build), BIN (bin), CC (cc), OUT (results), README (README.md;
#   empty: leave it alone), REPS (3), CVODE_TOLS ("1e-10 1e-6")
# Needs libsundials-dev (make deps-cvode at the top).
set -eu
cd "$(dirname "$0")"
BUILD=${BUILD:-../build}
BIN=${BIN:-bin}
CC=${CC:-cc}
OUT=${OUT:-results}
README=${README-README.md}
REPS=${REPS:-3}
CVODE_TOLS=${CVODE_TOLS:-1e-10 1e-6}
TMP=$OUT/cvode.tmp CSV=$OUT/cvode.csv
mkdir -p "$TMP" "$BIN"

# SUNDIALS 6 has no pkg-config files in Debian: the libraries by name
$CC -std=c11 -Wall -Wextra -O2 -ffp-contract=off cvode.c -o "$BIN/cvode" \
	-lsundials_cvode -lsundials_nvecserial -lsundials_sunlinsoldense -lsundials_sunmatrixdense -lm

# shellcheck disable=SC2086 # CVODE_TOLS is a list
"$BIN/cvode" "$REPS" $CVODE_TOLS > "$CSV"

. ./stiff_lib.sh

for p in vdp robertson oregonator hires; do
	"$BUILD/csfc" "stiff/$p.csf" -o "$TMP/$p.csfb"
	for tol in $CVODE_TOLS; do
		for m in msbdf bsimp auto; do
			echo "$p,$m,$tol,$(stiff_run $p "$TMP/$p.csfb" --method $m --tol "$tol")" >> "$CSV"
		done
	done
done

awk -F, 'NR > 1 { k = $1 SUBSEP $3; st[k, $2] = $4; n_[k, $2] = $5; f[k, $2] = $6; j[k, $2] = $7; s[k, $2] = $8; e[k, $2] = $9
	if (!(k in seen)) { seen[k] = 1; order[++n] = k } }
	END {
		print "| problem | tol | CVODE: evaluations (Jacobians), ms, error | msbdf | bsimp | auto | better of msbdf and bsimp / CVODE: evaluations, Jacobians, time |"
		print "|---|---|---|---|---|---|---|"
		for (i = 1; i <= n; i++) {
			k = order[i]; split(k, kk, SUBSEP)
			line = "| " kk[1] " | " kk[2]
			split("cvode msbdf bsimp auto", ms, " ")
			for (q = 1; q <= 4; q++) { m = ms[q]
				line = line sprintf(" | %d (%d), %.2f, %s", f[k, m], j[k, m], 1000 * s[k, m], e[k, m])
				if (st[k, m] != 0) line = line sprintf(", exit %d", st[k, m]) }
			b = f[k, "bsimp"] <= f[k, "msbdf"] ? "bsimp" : "msbdf"
			re = f[k, b] / f[k, "cvode"]; rt = s[k, b] / s[k, "cvode"]
			print line sprintf(" | %.2f, %.2f, %.2f (%s) |", re, j[k, b] / j[k, "cvode"], rt, b)
			t = kk[2]; if (!(t in tn)) tord[++ntol] = t
			tn[t]++; if (!(t in elo) || re < elo[t]) elo[t] = re; if (!(t in ehi) || re > ehi[t]) ehi[t] = re
			if (!(t in tlo) || rt < tlo[t]) tlo[t] = rt; if (!(t in thi) || rt > thi[t]) thi[t] = rt
			if (st[k, "cvode"] == 0 && e[k, "cvode"] != "" && e[k, "cvode"] + 0 <= 1e-6) cok[t]++
			if (st[k, b] == 0 && e[k, b] != "" && e[k, b] + 0 <= 1e-6) bok[t]++
		}
		print ""
		for (i = 1; i <= ntol; i++) { t = tord[i]
			printf "At tol %s the better of msbdf and bsimp took %.2f to %.2f times the right-hand side evaluations of CVODE and %.2f to %.2f times its time (CVODE %s); CVODE ended within 1e-6 of the reference on %d of %d problems, the better by hand on %d.%s", \
				t, elo[t], ehi[t], tlo[t], thi[t], (thi[t] < 1 ? "slower on every problem" : (tlo[t] > 1 ? "faster on every problem" : "faster on some, slower on others")), cok[t] + 0, tn[t], bok[t] + 0, i < ntol ? " " : "" }
		print ""
	}' "$CSV" > "$OUT/cvode.txt"
cat "$OUT/cvode.txt"
sh ./readme_section.sh "$README" cvode "$OUT/cvode.txt"
rm -rf "$TMP"
