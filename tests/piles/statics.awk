# tests/piles/statics.awk EXPECT CSV - a scene at rest, every row against the
# exact answer (statics.sh writes EXPECT).
#
# EXPECT has one check a line, fields separated by ";":
#   LABEL;OP;VALUE;SCALE;C1 COL1 C2 COL2 ...
# the linear combination C1 COL1 + C2 COL2 + ... of the named columns (their
# names without " [unit]") must be, at every row, within tol SCALE of VALUE
# (OP eq), at least VALUE - tol SCALE (ge) or at most VALUE + tol SCALE (le).
# Besides, every NAME.v.* column must be within tol m/s of 0 and every
# NAME.a.* column within tol g of 0 (nothing moves). The first miss stops
# the check with exit 1 and one line: the scene (-v name), the row, the
# check's label, the value and what it should be. -v tol (default 1e-9),
# rows (the number of data rows, when given).
function abs(x) { return x < 0 ? -x : x }
function fail(msg) {
	printf "%s: row %d, t = %s: %s\n", name, FNR - 1, $1, msg
	failed = 1
	exit 1
}
BEGIN { if (tol == "") tol = 1e-9; g = 9.80665; ne = 0 }
FNR == NR {
	if ($0 ~ /^[ \t]*(#|$)/) next
	ne++
	if (split($0, fld, ";") != 5) { printf "%s: statics.awk: bad check: %s\n", name, $0; failed = 2; exit 2 }
	lab[ne] = fld[1]; op[ne] = fld[2]; val[ne] = fld[3] + 0; sc[ne] = fld[4] + 0
	nt[ne] = split(fld[5], w, " ") / 2
	for (k = 1; k <= nt[ne]; k++) { coef[ne, k] = w[2 * k - 1] + 0; cname[ne, k] = w[2 * k] }
	next
}
FNR == 1 {
	FS = ","; $0 = $0
	for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i; if (h ~ /\.v\.[xyz]$/) vcol[i] = h; if (h ~ /\.a\.[xyz]$/) acol[i] = h }
	for (e = 1; e <= ne; e++)
		for (k = 1; k <= nt[e]; k++) {
			if (!(cname[e, k] in c)) { printf "%s: statics.awk: no column %s for %s\n", name, cname[e, k], lab[e]; failed = 2; exit 2 }
			ci[e, k] = c[cname[e, k]]
		}
	next
}
{
	for (i in vcol) if (abs($i) > tol) fail(sprintf("%s = %.17g m/s, expected 0", vcol[i], $i))
	for (i in acol) if (abs($i) > tol * g) fail(sprintf("%s = %.17g m/s^2, expected 0", acol[i], $i))
	for (e = 1; e <= ne; e++) {
		x = 0
		for (k = 1; k <= nt[e]; k++) x += coef[e, k] * $ci[e, k]
		d = tol * sc[e]
		if (op[e] == "eq" && abs(x - val[e]) > d || op[e] == "ge" && x < val[e] - d || op[e] == "le" && x > val[e] + d)
			fail(sprintf("%s = %.17g, expected %s%.17g (to %.3g)", lab[e], x, op[e] == "eq" ? "" : op[e] == "ge" ? ">= " : "<= ", val[e], d))
	}
}
END {
	if (failed) exit failed
	if (FNR < 2) { printf "%s: no data rows\n", name; exit 1 }
	if (rows != "" && FNR - 1 != rows) { printf "%s: %d data rows, expected %d\n", name, FNR - 1, rows; exit 1 }
	printf "%s: %d rows, %d checks a row\n", name, FNR - 1, ne
}
