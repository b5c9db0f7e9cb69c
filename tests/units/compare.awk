# compare.awk - A.csv B.csv: same header, every value equal to 1e-12 relative
# to the largest magnitude in its column (so zeros compare sensibly).
BEGIN { FS = "," }
NR == FNR { n = FNR; for (i = 1; i <= NF; i++) { a[FNR, i] = $i; v = $i + 0; if (v < 0) v = -v; if (FNR > 1 && v > s[i]) s[i] = v } w = NF; next }
FNR == 1 { if (NF != w) bad = "header"; next }
{
	for (i = 1; i <= NF; i++) {
		d = $i - a[FNR, i]; if (d < 0) d = -d
		if (d > 1e-12 * s[i] && d > 0) { printf "row %d column %d: %s vs %s\n", FNR, i, a[FNR, i], $i; exit 1 }
	}
	m = FNR
}
END { if (bad || m != n) { print "shape differs"; exit 1 } }
