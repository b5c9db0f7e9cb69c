#!/bin/sh
# tests/cookbook/check.sh CSFC CSFVM DIR BUILD: the cookbook (doc/cookbook.md, csf-cookbook(7)).
#  - man/csf-cookbook.7 is what doc/md2man.py makes of doc/cookbook.md (the one source), and
#    groff reads it without a warning;
#  - every recipe runs as written, each command printing the lines the cookbook shows, the
#    last one its check against the exact answer (run.py).
T=$3
B=$4
fail=0
mkdir -p "$T/cookbook"
if ! /usr/bin/python3 doc/md2man.py doc/cookbook.md >"$T/cookbook/made.7" || ! cmp -s "$T/cookbook/made.7" man/csf-cookbook.7; then
	echo "FAIL: cookbook: man/csf-cookbook.7 is not doc/md2man.py's page of doc/cookbook.md (make it again: /usr/bin/python3 doc/md2man.py doc/cookbook.md >man/csf-cookbook.7)"
	fail=1
fi
if command -v groff >/dev/null 2>&1 && [ -n "$(groff -man -ww -z man/csf-cookbook.7 2>&1)" ]; then
	echo "FAIL: cookbook: groff warns: $(groff -man -ww -z man/csf-cookbook.7 2>&1 | head -n 2)"
	fail=1
fi
/usr/bin/python3 tests/cookbook/run.py doc/cookbook.md "$B" "$T/cookbook" || fail=1
exit $fail
