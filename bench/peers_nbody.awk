# peers_nbody.awk - the error measure of the peers benchmark's n-body scene:
#   awk -F, -v ref=REF.csv -f peers_nbody.awk out.csv
# prints one number, the worst absolute position error, over every output row
# and every watched body's position components (columns named *.pos.*),
# of out.csv against the reference run REF.csv (csfvm --method rk8pd
# --tol 1e-13 on the same model). The columns are matched by name; exits 1,
# saying why on standard error, when a column is missing, the number of rows
# differs, or a row's time is not the reference's.
function abs(x) { return x < 0 ? -x : x }
BEGIN {
	if (ref == "") { print "peers_nbody.awk: needs -v ref=REF.csv" > "/dev/stderr"; bad = 1; exit 1 }
	while ((getline line < ref) > 0) {
		nf = split(line, f, ",")
		if (++nr == 1) {
			for (i = 1; i <= nf; i++) { h = f[i]; sub(/ *\[.*$/, "", h); rc[h] = i }
			continue
		}
		for (i = 1; i <= nf; i++) R[nr - 1, i] = f[i]
	}
	close(ref)
	rrows = nr - 1
	if (rrows < 1) { print "peers_nbody.awk: " ref ": no rows" > "/dev/stderr"; bad = 1; exit 1 }
	maxerr = 0
}
NR == 1 {
	for (i = 1; i <= NF; i++) {
		h = $i; sub(/ *\[.*$/, "", h)
		if (h ~ /\.pos\./) {
			if (!(h in rc)) { print "peers_nbody.awk: column " h " not in the reference" > "/dev/stderr"; bad = 1; exit 1 }
			np++; oc[np] = i; refc[np] = rc[h]
		}
	}
	if (!np) { print "peers_nbody.awk: no position columns" > "/dev/stderr"; bad = 1; exit 1 }
	next
}
{
	n++
	if (n > rrows || abs($1 - R[n, 1]) > 1e-9 * (1 + abs(R[n, 1]))) {
		printf "peers_nbody.awk: row %d: t = %s, reference t = %s\n", n, $1, R[n, 1] > "/dev/stderr"; bad = 1; exit 1
	}
	for (k = 1; k <= np; k++) {
		d = abs($(oc[k]) - R[n, refc[k]])
		if (d > maxerr || d != d) maxerr = d
	}
}
END {
	if (bad) exit 1
	if (n != rrows) { printf "peers_nbody.awk: expected %d data rows, got %d\n", rrows, n > "/dev/stderr"; exit 1 }
	printf "%.3e\n", maxerr
}
