#!/bin/sh
# gen_projectiles.sh N FORM WATCH - N projectiles with linear drag (m 0.5 kg, k 0.05 kg/s) launched
# from the origin at v0 = (3 + i/1000, 1, 10 - i/2000) m/s, i = 0 .. N-1, as FORM:
#   array: an object array whose members' velocities are a formula of i;
#   data:  the same array read from the data file proj.csv (written next to stdout's file, $4);
#   list:  the objects written out one by one, named p0 .. p{N-1}.
# WATCH: the watch list (members as p[K] in every form; the list form writes pK).
N=$1 FORM=$2 WATCH=$3 DATA=$4
echo "# $N projectiles with linear drag ($FORM)"
echo "using mechanics/mass_point"
case $FORM in
array)
	echo "object p[0..$((N - 1))]: mass_point"
	echo "object p[i]: m = 0.5 kg"
	echo "object p[i]: k = 0.05 kg/s"
	echo "object p[i]: v = (3 + i/1000, 1, 10 - i/2000) m/s" ;;
data)
	awk -v n="$N" 'BEGIN { print "v.x [m/s],v.y [m/s],v.z [m/s],m [kg],k [kg/s]"
		for (i = 0; i < n; i++) printf "%.17g,1,%.17g,0.5,0.05\n", 3 + i / 1000, 10 - i / 2000 }' >"$DATA"
	echo "object p[]: from \"$(basename "$DATA")\""
	echo "object p[i]: mass_point" ;;
list)
	awk -v n="$N" 'BEGIN { for (i = 0; i < n; i++) {
		printf "object p%d: mass_point\nobject p%d: m = 0.5 kg\nobject p%d: k = 0.05 kg/s\n", i, i, i
		printf "object p%d: v = (%.17g, 1, %.17g) m/s\n", i, 3 + i / 1000, 10 - i / 2000 } }'
	WATCH=$(echo "$WATCH" | sed 's/p\[\([0-9]*\)\]/p\1/g') ;;
esac
echo "rule F: W = g.mul(m)"
echo "rule F: D = v.mul(-k)"
echo "using mechanics/rules"
echo "inc t till 4 s by 0.1 s watch $WATCH"
