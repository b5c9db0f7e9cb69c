# cyclotron.awk - checks cyclotron.csf's output, converted to SI by to_si.awk,
# against the circle: every position within 1e-6 of the radius, velocity
# within 1e-6 of v0, force within 1e-6 of q v0 B; B and q exact to 1e-15.
function abs(x) { return x < 0 ? -x : x }
function cmp(name, got, want, scale,   d) {
	d = abs(got - want) / scale
	if (d > tol) { printf "row %d (t=%s): %s = %.17g, exact %.17g\n", NR, $1, name, got, want; failed = 1; exit 1 }
}
BEGIN { FS = ","; tol = 1e-6; q = 1.602176634e-19; m = 1.67262192369e-27; B = 1.5; v0 = 1e6; w = q * B / m; r = v0 / w }
NR == 1 {
	if ($0 != "t,p.pos.x,p.pos.y,p.pos.z,p.v.x,p.v.y,p.v.z,p.FB.x,p.FB.y,p.FB.z,p.B.x,p.B.y,p.B.z,p.q") {
		print "header: " $0; failed = 1; exit 1
	}
	next
}
{
	n++; t = $1; c = cos(w * t); s = sin(w * t)
	if (abs(t - (NR - 2) * 1e-9) > 1e-15 * t) { printf "row %d: t = %s\n", NR, t; failed = 1; exit 1 }
	cmp("x", $2, r * s, r); cmp("y", $3, r * (c - 1), r); cmp("z", $4, 0, r)
	cmp("v.x", $5, v0 * c, v0); cmp("v.y", $6, -v0 * s, v0); cmp("v.z", $7, 0, v0)
	cmp("FB.x", $8, -q * v0 * B * s, q * v0 * B); cmp("FB.y", $9, -q * v0 * B * c, q * v0 * B)
	cmp("B.z", $13, B, B * 1e-9); cmp("q", $14, q, q * 1e-9)
}
END { if (failed) exit 1; if (n != 201) { printf "expected 201 rows, got %d\n", n; exit 1 } }
