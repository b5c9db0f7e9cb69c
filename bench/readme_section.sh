#!/bin/sh
# readme_section.sh README NAME FILE - replaces the lines of README between
# the markers <!-- NAME:begin ... and <!-- NAME:end ... with the contents of
# FILE (the benchmarks' results sections). Does nothing if README is empty,
# missing, or has no such section.
set -eu
readme=$1 name=$2 file=$3
[ -n "$readme" ] && [ -f "$readme" ] && grep -q "^<!-- $name:begin" "$readme" || exit 0
awk -v sum="$file" -v b="^<!-- $name:begin" -v e="^<!-- $name:end" '
	$0 ~ b { print; while ((getline l < sum) > 0) print l; skip = 1; next }
	$0 ~ e { skip = 0 }
	!skip' "$readme" > "$readme.tmp"
mv "$readme.tmp" "$readme"
echo "updated $readme ($name)" >&2
