# tests/sweep/launch.awk - every row of a run of launch.csf (or of a sweep of
# it, the swept values first) against the exact motion with linear drag:
#   pos(t) = pos0 + v_inf t + (V0 - v_inf) (1 - e^{-k t}) / k,  v_inf = g / k
# -v lead=N: N leading swept columns, theta and v0 first (lead=0: theta and v0 from
# -v theta= -v v0=); -v x0= -v z0=: the initial position. Within 1e-6
# absolutely or relatively; exits 1 naming the first row that misses.
BEGIN { FS = ","; k = 0.1 / 0.5; gz = -9.80665; if (x0 == "") x0 = 0; if (z0 == "") z0 = 0; bad = 0 }
NR == 1 { next }
{
	if (lead >= 2) { theta = $1; v0 = $2 }
	t = $(lead + 1); x = $(lead + 2); y = $(lead + 3); z = $(lead + 4)
	vx = v0 * cos(theta); vz = v0 * sin(theta); vinf = gz / k; e = (1 - exp(-k * t)) / k
	ex = x0 + vx * e; ez = z0 + vinf * t + (vz - vinf) * e
	if (!near(x, ex) || !near(z, ez) || y != 0) { printf "row %d (theta %s, v0 %s, t %s): (%s, %s) expected (%.17g, %.17g)\n", NR, theta, v0, t, x, z, ex, ez; bad = 1; exit 1 }
	rows++
}
END { if (!bad && rows == 0) { print "no rows"; exit 1 } if (!bad && rows != expect && expect != "") { printf "%d rows, expected %d\n", rows, expect; exit 1 } }
function near(a, b) { d = a - b; if (d < 0) d = -d; return d <= 1e-6 || d <= 1e-6 * (b < 0 ? -b : b) }
