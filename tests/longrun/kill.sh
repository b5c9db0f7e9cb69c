#!/bin/sh
# tests/longrun/kill.sh CSFVM DIR NAME MODEL.csfb [OPTION...] - the kill test
# of --checkpoint and --resume: the run of MODEL with OPTIONs, uninterrupted,
# then ten runs with --checkpoint every 5 ms of wall time (or 1/20 of the
# uninterrupted run's, if shorter), each killed by
# SIGKILL at an instant drawn from a fixed seed (between 5 % and 95 % of
# the checkpointing run's duration), resumed with --resume >> the same file
# (the second of each pair of instants killed again, at another instant,
# and resumed once more), and the output compared byte for byte with the
# uninterrupted run's. A kill before the first checkpoint leaves none: the
# run starts again from scratch, as a user would.
# Prints one line per failure and, last, "N passed, N failed".
VM=$1 T=$2 NAME=$3 M=$4
shift 4
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $NAME: $*"; }
F=$T/$NAME.full P=$T/$NAME.part C=$T/$NAME.ck
now_ms() { date +%s%3N; }
a=$(now_ms)
timeout -s KILL 300 "$VM" "$@" ${M:+"$M"} >"$F" 2>"$T/$NAME.err" || { bad "the uninterrupted run: $(head -n 1 "$T/$NAME.err")"; echo "$pass passed, $fail failed"; exit 1; }
# checkpoints every 5 ms of wall time, or every 1/20 of the uninterrupted run (start-up included)
# when that is shorter (at least 0.5 ms): a run of 22 ms, most of it start-up, wrote none at 5 ms
CK=$(awk -v w="$(( $(now_ms) - a ))" 'BEGIN { e = w / 20 / 1000; if (e > 0.005) e = 0.005; if (e < 0.0005) e = 0.0005; printf "%.4f", e }')
rm -f "$C"
a=$(now_ms)
timeout -s KILL 300 "$VM" --checkpoint "$C" --checkpoint-every "$CK" "$@" ${M:+"$M"} >"$P" 2>"$T/$NAME.err"
w=$(( $(now_ms) - a ))
if cmp -s "$F" "$P"; then ok; else bad "a run with --checkpoint differs from one without"; fi
[ -s "$C" ] || bad "no checkpoint after a run of $w ms"
seed=20261126
for i in 1 2 3 4 5 6 7 8 9 10; do
	seed=$(( (seed * 16807) % 2147483647 ))
	d=$(( w * 5 / 100 + seed % (w * 90 / 100 + 1) ))
	rm -f "$C" "$C.tmp"
	timeout -s KILL "$(awk -v d="$d" 'BEGIN { printf "%.3f", d / 1000 }')" \
		"$VM" --checkpoint "$C" --checkpoint-every "$CK" "$@" ${M:+"$M"} >"$P" 2>"$T/$NAME.err"
	how="killed at $d ms of $w"
	if [ $((i % 2)) -eq 0 ] && [ -f "$C" ]; then
		seed=$(( (seed * 16807) % 2147483647 ))
		d2=$(( 1 + seed % (w / 2 + 1) ))
		timeout -s KILL "$(awk -v d="$d2" 'BEGIN { printf "%.3f", d / 1000 }')" \
			"$VM" --resume "$C" "$@" ${M:+"$M"} >>"$P" 2>"$T/$NAME.err"
		how="$how, resumed and killed again at $d2 ms"
	fi
	if [ -f "$C" ]; then
		timeout -s KILL 300 "$VM" --resume "$C" "$@" ${M:+"$M"} >>"$P" 2>"$T/$NAME.err"
	else
		how="$how (before the first checkpoint: run again)"
		timeout -s KILL 300 "$VM" "$@" ${M:+"$M"} >"$P" 2>"$T/$NAME.err"
	fi
	st=$?
	if [ $st -ne 0 ]; then bad "$how: the resumed run's exit status $st: $(head -n 1 "$T/$NAME.err")"
	elif cmp -s "$F" "$P"; then ok
	else bad "$how: the output differs from the uninterrupted run's: $(cmp "$F" "$P" 2>&1 | head -n 1)"; fi
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
