#!/bin/sh
# tests/warn/check.sh CSFC CSFVM DIR - csfc catches a user's mistakes and follows Unix conventions:
#  - each tests/warn/X.csf compiles with exit 0 and writes the warnings of X.warn
#    (file:line:col: warning: ...), exactly those; -Werror makes them errors (exit 1,
#    "[-Werror]"); -w silences them;
#  - misspelt names and units draw "did you mean 'NAME'?";
#  - a tab in indentation is one error, with no cascade after it;
#  - - is standard input and output; --opt=value; watch of a vector's component.
# Prints one line per failure and, last, "N passed, N failed".
CSFC=$1 CSFVM=$2 T=$3
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
for m in tests/warn/*.csf; do
	f=$(basename "$m" .csf)
	(cd tests/warn && "$CSFC" "$f.csf" -o "$T/w.csfb") > /dev/null 2> "$T/w.err"; st=$?
	grep "warning:" "$T/w.err" > "$T/w.got"
	if [ $st -eq 0 ] && cmp -s "$T/w.got" "tests/warn/$f.warn" && [ -s "$T/w.csfb" ]; then ok
	else bad "$f: exit $st, $(head -n 1 "$T/w.err")"; fi
	(cd tests/warn && "$CSFC" -Werror "$f.csf" -o "$T/w.csfb") > /dev/null 2> "$T/w.err"; st=$?
	if [ $st -eq 1 ] && grep -q "error: .* \[-Werror\]$" "$T/w.err"; then ok; else bad "$f -Werror: exit $st"; fi
	(cd tests/warn && "$CSFC" -w "$f.csf" -o "$T/w.csfb") > /dev/null 2> "$T/w.err"; st=$?
	if [ $st -eq 0 ] && [ ! -s "$T/w.err" ]; then ok; else bad "$f -w: exit $st, $(head -n 1 "$T/w.err")"; fi
done
# a clean model has no warnings
"$CSFC" examples/projectile.csf -o "$T/w.csfb" 2> "$T/w.err"
if [ ! -s "$T/w.err" ]; then ok; else bad "examples/projectile.csf warns: $(head -n 1 "$T/w.err")"; fi
# ... nor a conditional force without 'for', needed for the block though not for the floor it also applies to
"$CSFC" tests/e2e/push_friction.csf -o "$T/w.csfb" 2> "$T/w.err"
if [ ! -s "$T/w.err" ]; then ok; else bad "tests/e2e/push_friction.csf warns: $(head -n 1 "$T/w.err")"; fi

# errors with suggestions
expect_error() { # NAME TEXT LINE: compiling TEXT is exit 1 with LINE on stderr, and no other error
	printf '%b' "$2" > "$T/$1.csf"
	(cd "$T" && "$CSFC" "$1.csf" -o "$T/w.csfb") > /dev/null 2> "$T/w.err"; st=$?
	if [ $st -eq 1 ] && grep -Fxq -- "$3" "$T/w.err" && [ "$(grep -c ': error: ' "$T/w.err")" -eq 1 ]; then ok
	else bad "$1: exit $st, $(grep ': error: ' "$T/w.err" | head -n 2)"; fi
}
expect_error mass 'using mechanics/mass_point\nobject ball: mass_point\nusing mechanics/rules\nrule F: W = g.mul(mass)\ninc t till 1 s by 0.1 s watch pos\n' \
	"mass.csf:4:19: error: unknown name 'mass' in rule \"W = g.mul(mass)\" for object ball; did you mean 'm'?"
expect_error mps 'object ball: v = (3, 0, 4) mps\ninc t till 1 s by 0.1 s watch v\n' \
	"mps.csf:1:28: error: unknown unit 'mps'; did you mean 'm/s'?"
expect_error kmph 'object car: v = 50 kmph\ninc t till 1 s by 0.1 s watch v\n' \
	"kmph.csf:1:20: error: unknown unit 'kmph'; did you mean 'km/h'?"
expect_error byneg 'object b: x = 1\ninc t till 1 s by -0.1 s watch x\n' \
	"byneg.csf:2:19: error: 'by' must be a positive time"
expect_error byzero 'object b: x = 1\ninc t till 1 s by 0 s watch x\n' \
	"byzero.csf:2:21: error: 'by' must be a positive time"
expect_error tabs 'def k:\n    m = 1 kg\n\t  x = 2 m\nobject b: k\nrule: y = m\ninc t till 1 s by 0.1 s watch y\n' \
	"tabs.csf:3:1: error: tabs are not allowed in indentation; indent with spaces"

# - as standard input and output; --opt=value
if "$CSFC" --units=mks - -o - < tests/stability/oscillator.csf 2> "$T/w.err" | "$CSFVM" - > "$T/w1.csv" &&
	"$CSFC" tests/stability/oscillator.csf -o "$T/w.csfb" && "$CSFVM" "$T/w.csfb" > "$T/w2.csv" && cmp -s "$T/w1.csv" "$T/w2.csv"
then ok; else bad "csfc - -o - | csfvm -: $(head -n 1 "$T/w.err")"; fi
"$CSFC" - < tests/stability/oscillator.csf > /dev/null 2> "$T/w.err"; st=$?
if [ $st -eq 2 ] && grep -q "name the output with -o" "$T/w.err"; then ok; else bad "csfc - without -o: exit $st"; fi
printf 'object b: x = 1\ninc t till 1 s by 0.1 s watch y\n' | "$CSFC" - -o "$T/w.csfb" 2> "$T/w.err"; st=$?
if [ $st -eq 1 ] && grep -q "^<stdin>:2:" "$T/w.err"; then ok; else bad "an error on standard input: $(head -n 1 "$T/w.err")"; fi

# watch a component: the columns of the whole vector, one of them
printf 'using mechanics/mass_point\nobject bob: mass_point\nobject bob: v = (1, 2, 3) m/s\nusing mechanics/rules\nrule F: W = g.mul(m)\ninc t till 1 s by 0.25 s watch bob.pos.x, v.z, bob.pos\n' > "$T/wc.csf"
if "$CSFC" "$T/wc.csf" -o "$T/wc.csfb" && "$CSFVM" "$T/wc.csfb" > "$T/wc.csv" &&
	head -n 1 "$T/wc.csv" | grep -qx 't,bob.pos.x \[m\],bob.v.z \[m/s\],bob.pos.x \[m\],bob.pos.y \[m\],bob.pos.z \[m\]' &&
	awk -F, 'function abs(x) { return x < 0 ? -x : x } NR > 1 && ($2 != $4 || abs($3 - (3 - 9.80665 * $1)) > 1e-12) { bad = 1 } END { exit bad || NR != 6 }' "$T/wc.csv"
then ok; else bad "watch bob.pos.x, v.z: $(head -n 2 "$T/wc.csv")"; fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
