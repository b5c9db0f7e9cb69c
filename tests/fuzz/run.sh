#!/bin/sh
# tests/fuzz/run.sh BUILD SECONDS [RUNS] - runs each fuzz target (BUILD/fuzz-csfc,
# BUILD/fuzz-csfb, BUILD/fuzz-fmt, made by `make fuzz`) with libFuzzer for SECONDS (or RUNS
# executions, if given), one process at a time, at nice 19. Seeds: every
# .csf of examples/, tests/ and stdlib/, the same compiled to .csfb, and the
# regression corpus tests/fuzz/regress/ (fuzz-fmt: regress/fmt alone). The growing corpus stays in
# BUILD/corpus-TARGET, out of the source tree; a finding is written to
# BUILD/findings-TARGET/ and the script exits 1. A finding, once fixed, is
# minimised (fuzz-TARGET -minimize_crash=1 FILE) and kept in
# tests/fuzz/regress/TARGET/, which make check replays.
set -u
B=$1
SECONDS_EACH=$2
RUNS=${3:--1}
TOP=$(pwd)
status=0
mkdir -p "$B/seeds-csfc" "$B/seeds-csfb" "$B/seeds-fmt"
for f in examples/*.csf tests/*/*.csf tests/*.csf stdlib/*/*.csf; do
	[ -f "$f" ] || continue
	n=$(echo "$f" | tr '/' '_')
	cp "$f" "$B/seeds-csfc/$n"
	if [ ! -f "$B/seeds-csfb/${n%.csf}.csfb" ]; then
		(cd "$(dirname "$f")" && CSF_STDLIB="$TOP/stdlib" timeout 60 "$TOP/$B/csfc" "$(basename "$f")" \
			-o "$TOP/$B/seeds-csfb/${n%.csf}.csfb") >/dev/null 2>&1
	fi
done
for t in csfc csfb fmt; do
	mkdir -p "$B/corpus-$t" "$B/findings-$t"
	dict=
	[ "$t" = csfc ] && dict=-dict=tests/fuzz/csf.dict
	echo "fuzz-$t: $SECONDS_EACH s"
	# -timeout: an input that runs for more than 2 s is a hang (one second of CPU, with room for
	# the sanitizers and a busy machine); -rss_limit_mb: one that needs more than 2 GB, a finding
	# shellcheck disable=SC2086 # dict is one option or none
	nice -n 19 "$B/fuzz-$t" -max_total_time="$SECONDS_EACH" -runs="$RUNS" -timeout=2 -rss_limit_mb=2048 \
		-print_final_stats=1 $dict -artifact_prefix="$B/findings-$t/" \
		"$B/corpus-$t" "$B/seeds-$t" "tests/fuzz/regress/$t" 2>"$B/fuzz-$t.log"
	st=$?
	grep -E "^(#[0-9]+.*(DONE|INITED)|stat::number_of_executed_units|stat::peak_rss)" "$B/fuzz-$t.log" | tail -n 4
	if [ $st -ne 0 ]; then
		status=1
		echo "fuzz-$t: FINDING (exit $st); see $B/fuzz-$t.log and $B/findings-$t/"
		grep -E "^(==[0-9]+==ERROR|SUMMARY|.*runtime error|ALARM|.*deadly signal)" "$B/fuzz-$t.log" | head -n 5
	fi
done
exit $status
