#!/bin/sh
# gen_cloth.sh W H CSF_OUT - a cloth of W x H masses written with neighbour rules
# (csf(5), OBJECTS, "Object arrays"): the members come from a data file
# (CSF_OUT with .csv for .csf; columns pos, home, m, link and hang), each joined by a
# spring of rest length 0.05 m (K = 200 N/m) to the next in its row
# (node[i], node[i+1], times link: 0 at the end of a row, so rows do not
# join end to start) and to the one in the next row (node[i], node[i+W]),
# under gravity, its first row held by stiff springs to where it starts
# (hang = 1 in that row). Four neighbour rules, each one loop over its
# bindings, whatever W and H.
set -eu
if [ $# -ne 3 ]; then
	echo "usage: $0 W H CSF_OUT" >&2
	exit 2
fi
w=$1 h=$2 out=$3
data=${out%.csf}.csv
awk -v w="$w" -v h="$h" 'BEGIN {
	print "pos.x [m],pos.y [m],pos.z [m],home.x [m],home.y [m],home.z [m],m [kg],link,hang"
	for (j = 0; j < w * h; j++) {
		x = (j % w) * 0.05; y = int(j / w) * 0.05
		printf "%.17g,%.17g,0,%.17g,%.17g,0,0.01,%d,%d\n", x, y, x, y, (j % w == w - 1) ? 0 : 1, j < w ? 1 : 0
	}
}' > "$data"
cat > "$out" <<CSF
# A $w x $h cloth (bench/gen_cloth.sh): springs to the next in a row and in a column.
global K = 200 N/m
global s = 0.05 m
global H = 1e4 N/m
using mechanics/mass_point
object node[]: from "$(basename "$data")"
object node[i]: mass_point
rule F for node[i], node[i+1]: R = link * K * (node[i+1].pos - node[i].pos).unit() * ((node[i+1].pos - node[i].pos).mag() - s)
rule F for node[i+1], node[i]: L = link\$1 * K * (node[i].pos - node[i+1].pos).unit() * ((node[i].pos - node[i+1].pos).mag() - s)
rule F for node[i], node[i+$w]: U = K * (node[i+$w].pos - node[i].pos).unit() * ((node[i+$w].pos - node[i].pos).mag() - s)
rule F for node[i+$w], node[i]: D = K * (node[i].pos - node[i+$w].pos).unit() * ((node[i].pos - node[i+$w].pos).mag() - s)
rule F: W = g.mul(m)
rule F: Hold = hang * H * (home - pos)
using mechanics/rules
inc t till 0.1 s by 0.01 s watch node[0].pos, node[$((w * h - 1))].pos
CSF
