# awk -F, -f err.awk -f stiff.awk out.csv : exact answer of stiff.csf, x = e^-t, v = -e^-t.
function setup() { by = 0.25; rows = 21; X = col("p.x"); V = col("p.v") }
function row(t) { cmp($X, exp(-t)); cmp($V, -exp(-t)) }
