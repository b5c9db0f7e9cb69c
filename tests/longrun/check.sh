#!/bin/sh
# tests/longrun/check.sh CSFC CSFVM DIR BUILD - long runs: checkpoints and the run record.
#  - kill tests (kill.sh): ten SIGKILLs at instants from a fixed seed, each
#    run resumed with --resume and compared byte for byte with the
#    uninterrupted run: a Kepler orbit (auto, rk8pd), the bouncing
#    ball (impacts, Zeno's accumulation, rest), a pile of 9 balls
#    (contacts), a string going slack and taut (a one-sided constraint),
#    the ball with --every 7 and rk8pd, a sweep of 30 variants (serial and -j 2: a checkpoint
#    after a variant written holds how many are), and a generated program
#    (csfc --emit-c) of the ball; a
#    checkpoint of csfvm resumed by the generated program;
#  - SIGTERM ends the run after its row with a checkpoint (exit 143), resumed exactly;
#  - a checkpoint at a row where an impact is pending, with more pairs in contact than at the
#    start (land.csf), resumed exactly;
#  - refusals, exit 2 with the reason: a sweep's --out-dir, --compare-methods, -o FILE.h5,
#    a multistep method; another model's checkpoint, other options, an
#    output shorter than the checkpoint's rows, a damaged checkpoint; into
#    an empty file (> instead of >>) the rows after the checkpoint's;
#  - --record FILE.json: every field, the bytecode's FNV-1a hash computed
#    here, the -D values, the exit status of a run that failed; -o FILE.h5
#    holds the same fields as attributes (h5py; SKIP without it).
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3 B=$4
# the processes killed with SIGKILL are csfvm itself: tests/run.sh's CSFVM is a wrapper that execs
# timeout, and SIGKILL to timeout leaves its csfvm running on, writing into the output that the
# resumed run writes (once a resumed output went on past the uninterrupted run's last row)
KVM=$CSFVM
[ -n "$B" ] && [ -x "$B/csfvm" ] && KVM=$B/csfvm
HERE=$(dirname "$0")
PY=/usr/bin/python3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# the ball under --checkpoint into $T/c, killed with SIGKILL after its first checkpoint; its rows in $T/part.csv
killed_after_checkpoint() {
	rm -f "$T/c"
	"$KVM" --checkpoint "$T/c" --checkpoint-every 0.005 "$T/ball.csfb" >"$T/part.csv" &
	pid=$!
	n=0
	while [ ! -f "$T/c" ] && [ $n -lt 3000 ]; do sleep 0.01; n=$((n + 1)); done
	kill -KILL $pid 2>/dev/null
	wait $pid
}
# kill.sh's tally into ours
kills() {
	sh "$HERE/kill.sh" "$@" >"$T/kill.out" 2>&1
	grep '^FAIL' "$T/kill.out"
	set -- $(tail -n 1 "$T/kill.out")
	pass=$((pass + ${1:-0})) fail=$((fail + ${3:-1}))
}
"$CSFC" "$HERE/orbit.csf" -o "$T/orbit.csfb" && "$CSFC" "$HERE/ball.csf" -o "$T/ball.csfb" &&
	sh "$HERE/../../bench/gen_pile.sh" 9 0.5 0.3 2 0.001 "$T/pile.csf" 'pos, v' && "$CSFC" "$T/pile.csf" -o "$T/pile.csfb" &&
	"$CSFC" --emit-c "$HERE/ball.csf" -o "$T/ball-exe" || { echo "FAIL: the test scenes do not compile"; exit 1; }

kills "$KVM" "$T" orbit "$T/orbit.csfb"
kills "$KVM" "$T" orbit-rk8pd "$T/orbit.csfb" --method rk8pd
kills "$KVM" "$T" ball "$T/ball.csfb"
kills "$KVM" "$T" pile "$T/pile.csfb"
# a string (a one-sided constraint) going slack and snapping taut; --every with another method
"$CSFC" "$HERE/string.csf" -o "$T/string.csfb" || bad "string.csf does not compile"
kills "$KVM" "$T" string "$T/string.csfb"
kills "$KVM" "$T" ball-every "$T/ball.csfb" --every 7 --method rk8pd
# a sweep: a checkpoint after a variant written holds how many are (serial, and -j 2)
"$CSFC" "$HERE/../../examples/bouncing_ball.csf" -o "$T/bb.csfb"
kills "$KVM" "$T" sweep "$T/bb.csfb" --sweep 'ball.cr=0.1:0.8:30'
kills "$KVM" "$T" sweep-j2 "$T/bb.csfb" -j 2 --sweep 'ball.cr=0.1:0.8:30'
# a generated program: its own kill test; a checkpoint of csfvm goes on in it (the same bytecode)
kills "$T/ball-exe" "$T" ball-exe ""
"$CSFVM" "$T/ball.csfb" >"$T/full.csv"
killed_after_checkpoint
if [ -f "$T/c" ] && "$T/ball-exe" --resume "$T/c" >>"$T/part.csv" 2>"$T/err" && cmp -s "$T/full.csv" "$T/part.csv"; then ok
else bad "csfvm's checkpoint resumed by the generated program: $(head -n 1 "$T/err") $(cmp "$T/full.csv" "$T/part.csv" 2>&1)"; fi

# SIGTERM: the run ends after its row with a checkpoint (none was due), resumed exactly (an orbit
# of 300000 light rows: the row is reached well within the watchdog's 500 ms)
sed 's/^inc t till 125 /inc t till 3000 /' "$HERE/orbit.csf" >"$T/long.csf" && "$CSFC" "$T/long.csf" -o "$T/long.csfb"
rm -f "$T/c"
: >"$T/part.csv" # there before the loop below reads its size (the shell may not have opened it yet)
"$CSFVM" --checkpoint "$T/c" --checkpoint-every 1000 "$T/long.csfb" >"$T/part.csv" 2>"$T/err" &
pid=$!
n=0 # SIGTERM once some rows are out
while [ "$(wc -c <"$T/part.csv")" -lt 200000 ] && [ $n -lt 3000 ]; do sleep 0.01; n=$((n + 1)); done
kill -TERM $pid
wait $pid
st=$?
"$CSFVM" "$T/long.csfb" >"$T/full.csv"
if [ $st -eq 143 ] && [ ! -f "$T/c" ] && cmp -s "$T/full.csv" "$T/part.csv"; then ok # (the signal came after the last row)
elif [ $st -eq 143 ] && [ -f "$T/c" ] && "$CSFVM" --resume "$T/c" "$T/long.csfb" >>"$T/part.csv" 2>"$T/err" &&
	cmp -s "$T/full.csv" "$T/part.csv"; then ok
else bad "SIGTERM with --checkpoint: exit $st (143 expected), checkpoint $(ls "$T/c" 2>&1), $(head -n 1 "$T/err")"; fi

# a checkpoint of a row at which an impact is pending (a ball lands at exactly t = 0.5 s), with
# more pairs in contact than the start had candidates (20 balls at rest): the resumed run takes the
# impact first; its clusters' work had been sized for the start's pairs (a heap overflow, found by
# ASan here, a crash in a pile of 64 balls). Both runs stop at the assertion at t = 1 (exit 1).
"$CSFC" "$HERE/land.csf" -o "$T/land.csfb" || bad "land.csf does not compile"
"$CSFVM" "$T/land.csfb" >"$T/full.csv" 2>/dev/null
rm -f "$T/c"
"$CSFVM" --checkpoint "$T/c" --checkpoint-every 0 "$T/land.csfb" >"$T/part.csv" 2>/dev/null
"$CSFVM" --resume "$T/c" "$T/land.csfb" >>"$T/part.csv" 2>"$T/err"
st=$?
# the row at 0.5: top at the floor (z = 0.05 m) at v = -g t = -4.903325 m/s, the impact not yet taken
if [ $st -eq 1 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q 'assertion failed at t=1' "$T/err" &&
	cmp -s "$T/full.csv" "$T/part.csv" && awk -F, 'NR == 3 && $1 == 0.5 && ($10 - 0.05)^2 < 1e-24 && ($13 + 4.903325)^2 < 1e-24 { ok = 1 }
	END { exit !ok }' "$T/full.csv"; then ok
else bad "a checkpoint with an impact pending and 20 pairs in contact, resumed: exit $st, $(head -n 1 "$T/err"), $(cmp "$T/full.csv" "$T/part.csv" 2>&1)"; fi

# refusals
refuse() { # WHAT PATTERN COMMAND...: exit 2 and PATTERN on stderr
	what=$1 pat=$2
	shift 2
	"$@" >"$T/out" 2>"$T/err"
	st=$?
	if [ $st -eq 2 ] && grep -q -- "$pat" "$T/err"; then ok; else bad "$what: exit $st, $(head -n 1 "$T/err")"; fi
}
refuse "a sweep's --out-dir" "not --out-dir's files" "$CSFVM" --checkpoint "$T/c2" --out-dir "$T/od" --sweep 'ball.cr=0.1:0.5:3' "$T/ball.csfb"
refuse "--compare-methods" "compare-methods runs a table" "$CSFVM" --checkpoint "$T/c2" --compare-methods "$T/ball.csfb"
refuse "-o FILE.h5" "-o FILE.h5 is written whole" "$CSFVM" --checkpoint "$T/c2" -o "$T/x.h5" "$T/ball.csfb"
refuse "msbdf" "msbdf keeps a history of past steps" "$CSFVM" --method msbdf --checkpoint "$T/c2" "$T/orbit.csfb"
killed_after_checkpoint
refuse "another model" "belongs to another model" "$CSFVM" --resume "$T/c" "$T/orbit.csfb"
refuse "other options" "written by a run with other options" "$CSFVM" --resume "$T/c" --tol 1e-9 "$T/ball.csfb"
refuse "other -D" "written by a run with other options" "$CSFVM" --resume "$T/c" -D ball.cr=0.4 "$T/ball.csfb"
printf 't\n' >"$T/short.csv"
refuse "an output shorter than the checkpoint's" "the output has 2 bytes, fewer than" sh -c '"$1" --resume "$2" "$3" >>"$4"' sh "$CSFVM" "$T/c" "$T/ball.csfb" "$T/short.csv"
# > instead of >>: the rows after the checkpoint's, which complete the first run's output cut there
"$CSFVM" "$T/ball.csfb" >"$T/full.csv"
if "$CSFVM" --resume "$T/c" "$T/ball.csfb" >"$T/rest.csv" 2>"$T/err" && grep -q '^warning: --resume: the output is empty' "$T/err" &&
	off=$(sed -n 's/.*first run.s \([0-9]*\) bytes up to.*/\1/p' "$T/err") && [ -n "$off" ] &&
	{ head -c "$off" "$T/part.csv"; cat "$T/rest.csv"; } | cmp -s - "$T/full.csv"; then ok
else bad "--resume into an empty file: $(head -n 1 "$T/err")"; fi
head -c 100 "$T/c" >"$T/cut"
refuse "a damaged checkpoint" "cut short or damaged" "$CSFVM" --resume "$T/cut" "$T/ball.csfb"
refuse "no checkpoint" "cannot read" "$CSFVM" --resume "$T/none" "$T/ball.csfb"
refuse "--checkpoint-every -1" "needs a number of seconds" "$CSFVM" --checkpoint "$T/c" --checkpoint-every -1 "$T/ball.csfb"

# --record: the fields, the hash of the bytecode's bytes, -D, the exit status of a failed run
if "$CSFVM" --record "$T/r.json" --stats -D ball.cr=0.25 "$T/ball.csfb" >"$T/r.csv" 2>"$T/err" &&
	"$PY" - "$T/r.json" "$T/ball.csfb" "$T/r.csv" 0 <<'PY' 2>"$T/err"
import json, sys
r = json.load(open(sys.argv[1]))
h = 14695981039346656037
for b in open(sys.argv[2], "rb").read():
    h = ((h ^ b) * 1099511628211) % 2**64
want = ["csf_version", "bytecode_hash", "source", "units", "method", "tolerance", "atol", "fixed", "step", "hmax",
        "every", "defines", "command_line", "host", "start", "end", "steps", "rejected_steps", "rhs_evaluations",
        "jacobian_evaluations", "events", "rows", "seconds", "exit_status"]
missing = [k for k in want if k not in r]
assert not missing, missing
assert r["bytecode_hash"] == "%016x" % h, (r["bytecode_hash"], "%016x" % h)
assert r["units"] == "mks" and r["method"] == "auto" and r["tolerance"] == 1e-12, r
assert r["defines"] == ["ball.cr=0.25"], r["defines"]
assert r["exit_status"] == int(sys.argv[4]), r["exit_status"]
assert r["rows"] == sum(1 for _ in open(sys.argv[3])) - 1, r["rows"]
assert r["source"].endswith("ball.csf") and "--record" in r["command_line"], r
assert r["start"] <= r["end"] and r["start"].endswith("Z"), r
assert r["steps"] > 0 and r["rhs_evaluations"] > r["steps"] and r["events"] > 0, r
PY
then ok; else bad "--record: $(tail -n 1 "$T/err")"; fi
printf 'using mechanics/mass_point\nobject b: mass_point\nobject b: v = (1, 0, 0) m/s\nusing mechanics/rules\nassert b.pos.x < 0.5 m\ninc t till 1 s by 0.1 s watch b.pos\n' >"$T/fails.csf"
"$CSFC" "$T/fails.csf" -o "$T/fails.csfb"
"$CSFVM" --record "$T/f.json" "$T/fails.csfb" >/dev/null 2>&1
st=$?
if [ $st -eq 1 ] && grep -q '"exit_status": 1$' "$T/f.json"; then ok; else bad "--record of a failed run: exit $st, $(grep exit_status "$T/f.json")"; fi
if "$PY" -c 'import h5py' 2>/dev/null; then
	if "$CSFVM" -o "$T/r.h5" --record "$T/r2.json" "$T/ball.csfb" 2>"$T/err" && "$PY" - "$T/r.h5" "$T/r2.json" <<'PY' 2>"$T/err"
import h5py, json, sys
f = h5py.File(sys.argv[1], "r")
r = json.load(open(sys.argv[2]))
for k, v in r.items():
    a = f.attrs[k]
    if isinstance(v, list):
        assert [x.decode() if isinstance(x, bytes) else x for x in a] == v, (k, a, v)
    elif isinstance(v, str):
        assert (a.decode() if isinstance(a, bytes) else a) == v, (k, a, v)
    else:
        assert float(a) == float(v), (k, a, v)
PY
	then ok; else bad "-o FILE.h5's record: $(tail -n 1 "$T/err")"; fi
else
	echo "SKIP: h5py is missing (the record in -o FILE.h5 is not read back)"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
