#!/bin/sh
# tests/lsp/check.sh CSFC CSFVM DIR: csfc --lsp driven by a client that speaks the protocol
# (client.py, Debian's python3 and its standard library alone).
CSFC=$1
T=$3
mkdir -p "$T/lsp"
if ! [ -x /usr/bin/python3 ]; then
	echo "SKIP: lsp: no /usr/bin/python3"
	exit 0
fi
/usr/bin/python3 "$(dirname "$0")/client.py" "$CSFC" "$T/lsp"
