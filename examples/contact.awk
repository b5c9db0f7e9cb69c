# Shared by the mechanics examples' checkers (each names it on its first line).
# Columns by name (units stripped); cmp() fails the run on the first value
# that differs from the exact one by more than tol absolutely and relatively
# (tol times tolscale, when awk is given -v tolscale=K: a low-order method).
function abs(x) { return x < 0 ? -x : x }
function cmp(name, got, want,   d, e) {
	d = abs(got - want); e = tol * (tolscale ? tolscale : 1)
	if (d > maxerr) maxerr = d
	if (d > e && d > e * abs(want)) {
		printf "row %d (t=%s): %s = %.17g, exact %.17g, error %.3g\n", NR, $1, name, got, want, d
		failed = 1; exit 1
	}
}
function col(name) { if (!(name in c)) { print "missing column " name; failed = 1; exit 1 } return $c[name] }
function header(   i, h) { for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i } }
function finish(rows) {
	if (failed) exit 1
	if (n != rows) { printf "expected %d data rows, got %d\n", rows, n; exit 1 }
	printf "max_err=%.3g\n", maxerr > "/dev/stderr"
}
