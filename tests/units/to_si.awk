# to_si.awk - converts a csfvm CSV to SI using the units in its header
# ("ball.pos.x [cm]", "bob.a.z [ft/s^2]", "x [kg*m/(s^2)]", "F [dyn]"): the
# base units of the three systems and the derived units they print by name.
function base(u) {
	if (u == "m" || u == "kg" || u == "s" || u == "A") return 1
	if (u == "N" || u == "J" || u == "W" || u == "Pa" || u == "C" || u == "V" || u == "T") return 1
	if (u == "ohm" || u == "S" || u == "F" || u == "H" || u == "Wb") return 1
	if (u == "cm") return 0.01
	if (u == "g") return 0.001
	if (u == "ft") return 0.3048
	if (u == "lb") return 0.45359237
	if (u == "dyn") return 1e-5
	if (u == "erg") return 1e-7
	if (u == "pdl") return 0.138254954376
	print "to_si.awk: unknown unit " u > "/dev/stderr"
	exit 2
}
function product(s,    n, parts, i, f, e, p) {
	gsub(/[()]/, "", s)
	n = split(s, parts, "*")
	f = 1
	for (i = 1; i <= n; i++) {
		if (parts[i] == "1" || parts[i] == "") continue
		e = 1
		p = index(parts[i], "^")
		if (p) { e = substr(parts[i], p + 1) + 0; parts[i] = substr(parts[i], 1, p - 1) }
		f *= base(parts[i]) ^ e
	}
	return f
}
function factor(h,    u, p) {
	if (!match(h, /\[[^]]*\]/)) return 1
	u = substr(h, RSTART + 1, RLENGTH - 2)
	p = index(u, "/")
	if (!p) return product(u)
	return product(substr(u, 1, p - 1)) / product(substr(u, p + 1))
}
BEGIN { FS = OFS = "," }
NR == 1 { for (i = 1; i <= NF; i++) { f[i] = factor($i); sub(/ \[.*/, "", $i) } print; next }
{ for (i = 1; i <= NF; i++) $i = sprintf("%.17g", $i * f[i]); print }
