#!/bin/sh
# tests/unix/check.sh CSFC CSFVM DIR - csfvm follows Unix conventions:
#  - SIGINT and SIGTERM end a run after the current row: every row whole, the
#    --stats line written, exit 130 and 143;
#  - a reader that goes away (csfvm | head -1) ends the run quietly, by SIGPIPE
#    or with exit 0, nothing on stderr; a full disk (/dev/full) is still exit 2
#    with a message;
#  - the same for wide rows (180 columns), which a second thread formats and writes: every row
#    whole after SIGINT and SIGTERM, a closed pipe quiet, a full disk exit 2, and the text byte for
#    byte that of CSF_ROW_THREAD=0 (rows written by the run itself), also with --every and when an
#    assertion halts the run (exit 1 after every row before it);
#  - "-" is standard input; --opt=value as well as --opt value;
#  - source given to csfvm draws a hint to compile it first;
#  - the progress line only when asked for (stderr is not a terminal here) and
#    erased at the end.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
# an oscillator (x = 0.1 cos 8t) run for long enough to be interrupted: 5e6 rows
M=$T/unix_long
sed 's/^inc t till .*/inc t till 5000 s by 1 ms watch bob.pos, bob.v/' tests/stability/oscillator.csf > "$M.csf"
"$CSFC" "$M.csf" -o "$M.csfb" || bad "the long oscillator does not compile"

# whole rows: 7 fields each (t and two vectors), and the last row's t on the grid
whole() { awk -F, 'NR > 1 && NF != 7 { bad = 1 } NR > 1 { n++ } END { exit bad || n < 2 }' "$1"; }
for sig in INT TERM; do
	"$CSFVM" --stats "$M.csfb" > "$T/unix.csv" 2> "$T/unix.err" &
	pid=$!
	sleep 1
	kill -$sig $pid
	wait $pid
	st=$?
	want=130; [ $sig = TERM ] && want=143
	if [ $st -eq $want ] && whole "$T/unix.csv" && grep -q "^stats: method" "$T/unix.err"; then ok
	else bad "SIG$sig: exit $st (want $want), $(tail -c 100 "$T/unix.csv" | tail -n 1), $(head -n 1 "$T/unix.err")"; fi
done

# a closed pipe: quiet, exit 0 or by SIGPIPE (141)
st=$( ( "$CSFVM" "$M.csfb" 2> "$T/unix.err"; echo $? > "$T/unix.st" ) | head -n 1 > /dev/null; cat "$T/unix.st")
if { [ "$st" -eq 0 ] || [ "$st" -eq 141 ]; } && [ ! -s "$T/unix.err" ]; then ok; else bad "| head -1: exit $st, $(cat "$T/unix.err")"; fi
# a full disk: exit 2 and the reason
if [ -w /dev/full ]; then
	"$CSFVM" "$M.csfb" > /dev/full 2> "$T/unix.err"; st=$?
	if [ $st -eq 2 ] && grep -q "cannot write output: No space left on device" "$T/unix.err"; then ok
	else bad "> /dev/full: exit $st, $(cat "$T/unix.err")"; fi
fi

# wide rows: 30 oscillators (x = 0.1 cos 8t each), pos and v watched: 180 columns
W=$T/unix_wide
{ echo "using mechanics/mass_point"; echo "global k = 16 N/m"
  i=0; while [ $i -lt 30 ]; do
	echo "object b$i: mass_point"; echo "object b$i: m = 0.25 kg"; echo "object b$i: pos = (0.1, 0, $i) m"; i=$((i + 1)); done
  echo "rule F: S = (pos - (0, 0, pos.z)).mul(-k)"; echo "using mechanics/rules"
  echo "assert t < 4000 s"; echo "inc t till 5000 s by 1 ms watch pos, v"; } > "$W.csf"
"$CSFC" "$W.csf" -o "$W.csfb" || bad "the wide oscillators do not compile"
wide() { awk -F, 'NR > 1 && NF != 181 { bad = 1 } NR > 1 { n++ } END { exit bad || n < 2 }' "$1"; }
for sig in INT TERM; do
	"$CSFVM" --stats "$W.csfb" > "$T/wide.csv" 2> "$T/wide.err" &
	pid=$!
	sleep 1
	kill -$sig $pid
	wait $pid
	st=$?
	want=130; [ $sig = TERM ] && want=143
	if [ $st -eq $want ] && wide "$T/wide.csv" && grep -q "^stats: method" "$T/wide.err"; then ok
	else bad "wide rows, SIG$sig: exit $st (want $want), $(tail -c 100 "$T/wide.csv" | tail -n 1), $(head -n 1 "$T/wide.err")"; fi
done
st=$( ( "$CSFVM" "$W.csfb" 2> "$T/wide.err"; echo $? > "$T/wide.st" ) | head -n 1 > /dev/null; cat "$T/wide.st")
if { [ "$st" -eq 0 ] || [ "$st" -eq 141 ]; } && [ ! -s "$T/wide.err" ]; then ok; else bad "wide rows | head -1: exit $st, $(cat "$T/wide.err")"; fi
if [ -w /dev/full ]; then
	"$CSFVM" "$W.csfb" > /dev/full 2> "$T/wide.err"; st=$?
	if [ $st -eq 2 ] && grep -q "cannot write output: No space left on device" "$T/wide.err"; then ok
	else bad "wide rows > /dev/full: exit $st, $(cat "$T/wide.err")"; fi
fi
sed 's/^inc t till 5000 s/inc t till 20 s/' "$W.csf" > "$W.s.csf"
"$CSFC" "$W.s.csf" -o "$W.s.csfb"
for opts in "--fixed --step 0.01" "--every 7"; do
	# shellcheck disable=SC2086 # opts holds options
	"$CSFVM" $opts "$W.s.csfb" > "$T/wide_a.csv" 2>/dev/null
	# shellcheck disable=SC2086
	CSF_ROW_THREAD=0 "$CSFVM" $opts "$W.s.csfb" > "$T/wide_b.csv" 2>/dev/null
	if cmp -s "$T/wide_a.csv" "$T/wide_b.csv" && [ "$(wc -l < "$T/wide_a.csv")" -gt 2800 ]; then ok
	else bad "wide rows ($opts): not those of CSF_ROW_THREAD=0"; fi
done
# an assertion that fails at t = 3001 s: exit 1, every row before it (3001 rows and the header)
sed 's/^inc t till .*/inc t till 5000 s by 1 s watch pos, v/; s/^assert t < 4000 s/assert t < 3000.5 s/' "$W.csf" > "$W.a.csf"
"$CSFC" "$W.a.csf" -o "$W.a.csfb"
"$CSFVM" "$W.a.csfb" > "$T/wide_a.csv" 2>/dev/null; st=$?
CSF_ROW_THREAD=0 "$CSFVM" "$W.a.csfb" > "$T/wide_b.csv" 2>/dev/null
if [ $st -eq 1 ] && cmp -s "$T/wide_a.csv" "$T/wide_b.csv" && [ "$(wc -l < "$T/wide_a.csv")" -eq 3002 ]; then ok
else bad "wide rows, a failed assertion: exit $st, $(wc -l < "$T/wide_a.csv") lines"; fi

# - is standard input; --opt=value
"$CSFC" tests/stability/oscillator.csf -o "$T/unix_osc.csfb"
"$CSFVM" --method rk4 --fixed --step 0.01 "$T/unix_osc.csfb" > "$T/unix_a.csv"
if "$CSFVM" --method=rk4 --fixed --step=0.01 - < "$T/unix_osc.csfb" > "$T/unix_b.csv" && cmp -s "$T/unix_a.csv" "$T/unix_b.csv"
then ok; else bad "--opt=value and - as standard input: not the same output"; fi
"$CSFVM" --tol= "$T/unix_osc.csfb" > /dev/null 2> "$T/unix.err"; st=$?
if [ $st -eq 2 ] && grep -q "tol needs a positive number, not ''" "$T/unix.err"; then ok; else bad "--tol=: exit $st"; fi

# source where bytecode belongs
"$CSFVM" tests/stability/oscillator.csf > /dev/null 2> "$T/unix.err"; st=$?
if [ $st -eq 2 ] && grep -q "^csfvm: hint: tests/stability/oscillator.csf looks like CSF source; compile it with csfc first" "$T/unix.err"
then ok; else bad "csfvm on source: exit $st, $(cat "$T/unix.err")"; fi

# the progress line: none unless asked for; asked for, erased at the end
"$CSFVM" "$M.csfb" > /dev/null 2> "$T/unix.err" & pid=$!; sleep 0.5; kill -INT $pid; wait $pid
if [ ! -s "$T/unix.err" ]; then ok; else bad "progress without a terminal: $(cat -v "$T/unix.err" | head -c 100)"; fi
"$CSFVM" --progress "$M.csfb" > /dev/null 2> "$T/unix.err" & pid=$!; sleep 0.5; kill -INT $pid; wait $pid
if grep -q "t = .* of 5000 s" "$T/unix.err" && [ "$(tail -c 4 "$T/unix.err" | od -An -c | tr -d ' ')" = '\r033[K' ]; then ok
else bad "--progress: $(cat -v "$T/unix.err" | tail -c 100)"; fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
