# err.awk - the error measure of the work-precision benchmark, shared by every
# problem: awk -F, -f err.awk -f NAME.awk out.csv prints one number, the worst
# error over all output rows (t included) and all watched values, each value's
# error being min(absolute, relative) against the exact answer:
#   d = |got - exact|,  err = min(d, d/|exact|)  (err = d where exact = 0),
# the measure of tests/e2e/*.check. NAME.awk defines setup() (constants, the
# columns, by and the expected number of rows) and row(t) (calls cmp(got, exact)
# for every watched value of the current row). Exits 1, printing why on
# standard error, when a column is missing or the number of rows is wrong
# (a run that stopped early).
function abs(x) { return x < 0 ? -x : x }
function cmp(got, want,   d, r) {
	d = abs(got - want); r = want != 0 ? d / abs(want) : d
	if (r < d) d = r
	if (d > maxerr || d != d) maxerr = d
}
function col(name) {
	if (!(name in c)) { printf "missing column %s\n", name > "/dev/stderr"; bad = 1; exit 1 }
	return c[name]
}
NR == 1 {
	for (i = 1; i <= NF; i++) { h = $i; sub(/ *\[.*$/, "", h); c[h] = i }
	maxerr = 0; setup(); next
}
{ n++; cmp($1, (NR - 2) * by); row($1 + 0) }
END {
	if (bad) exit 1
	if (n != rows) { printf "expected %d data rows, got %d\n", rows, n > "/dev/stderr"; exit 1 }
	printf "%.3e\n", maxerr
}
