#!/bin/sh
# tests/editors/check.sh DIR BUILD [SCENES...]: the editor support of editors/.
#  - the TextMate grammar (editors/vscode) under vscode-tmgrammar-test, on the annotated samples
#    of tests/editors/samples (one per token class), and on whole scenes (tokens.js: every example,
#    the standard library, the end-to-end and run-time scenes, and SCENES: the cookbook's);
#  - the Vim files (editors/vim) in headless vim: the syntax group at every place the samples
#    annotate (vim_expect.py turns their scopes into Vim's groups), indentation by = and the
#    ftplugin's options (vim_indent.vim; the filetype of a .csf file).
# The samples are .sample files, not .csf: they are not scenes (tests/layout compiles every .csf).
# The tools come from make deps-editors: node and npm (Debian), vscode-tmgrammar-test (npm, into
# BUILD/editors-deps), vim (Debian); a SKIP line for each that is missing.
set -u
T=$1
B=$2
shift 2
mkdir -p "$T/editors"
fail=0
mods=$B/editors-deps/node_modules
# the sanitizer build shares the plain build's tools
[ -d "$mods" ] || mods=build/editors-deps/node_modules
samples=$(ls tests/editors/samples/*.sample)
scenes="$(ls examples/*.csf stdlib/*/*.csf tests/e2e/*.csf tests/runtime/*.csf tests/warn/*.csf) $*"
if ! command -v node >/dev/null 2>&1; then
	echo "SKIP: editors: no node (make deps-editors installs nodejs, npm and vscode-tmgrammar-test)"
elif ! [ -x "$mods/.bin/vscode-tmgrammar-test" ]; then
	echo "SKIP: editors: no $mods/.bin/vscode-tmgrammar-test (make deps-editors installs it)"
else
	# shellcheck disable=SC2086 # lists of files
	if ! timeout 120 "$mods/.bin/vscode-tmgrammar-test" -c -g editors/vscode/syntaxes/csf.tmLanguage.json $samples \
		>"$T/editors/tm.out" 2>&1 || grep -q ERROR "$T/editors/tm.out"; then
		echo "FAIL: editors: vscode-tmgrammar-test: $(grep -m 3 -v successfuly "$T/editors/tm.out")"
		fail=1
	fi
	# shellcheck disable=SC2086
	if ! timeout 120 node tests/editors/tokens.js "$mods" editors/vscode/syntaxes/csf.tmLanguage.json $scenes \
		>"$T/editors/tokens.out" 2>&1; then
		echo "FAIL: editors: the grammar on whole scenes: $(head -n 3 "$T/editors/tokens.out")"
		fail=1
	fi
	tail -n 1 "$T/editors/tokens.out"
	# the extension's manifest names the files it ships
	if ! node -e 'const p = require(process.argv[1] + "/package.json"), fs = require("fs");
		const c = JSON.parse(fs.readFileSync(process.argv[1] + "/language-configuration.json"));
		if (!fs.existsSync(process.argv[1] + "/" + p.contributes.grammars[0].path) || c.comments.lineComment !== "#") process.exit(1);' \
		"$(pwd)/editors/vscode" 2>"$T/editors/pkg.err"; then
		echo "FAIL: editors: editors/vscode/package.json or language-configuration.json: $(head -n 2 "$T/editors/pkg.err")"
		fail=1
	fi
fi
if ! command -v vim >/dev/null 2>&1; then
	echo "SKIP: editors: no vim (make deps-editors installs it)"
else
	# shellcheck disable=SC2086
	/usr/bin/python3 tests/editors/vim_expect.py $samples >"$T/editors/expect"
	vimrun() {
		timeout 60 vim -es -N -u NONE -i NONE --cmd "set rtp^=$(pwd)/editors/vim" -c 'filetype plugin indent on' \
			-c 'syntax on' "$@" </dev/null >/dev/null 2>&1
	}
	vimrun -c "let g:expect='$T/editors/expect'" -c "let g:scene='examples/projectile.csf'" -c "let g:out='$T/editors/vim.out'" -c 'source tests/editors/vim_check.vim'
	vimrun -c "let g:sample='tests/editors/indented.sample'" -c "let g:out='$T/editors/indent.out'" -c 'source tests/editors/vim_indent.vim'
	for f in vim.out indent.out; do
		if ! [ -f "$T/editors/$f" ]; then
			echo "FAIL: editors: vim wrote no $f"
			fail=1
		elif grep FAIL "$T/editors/$f" | head -n 3 | grep .; then
			fail=1
		fi
	done
	tail -n 1 "$T/editors/vim.out" 2>/dev/null
fi
exit $fail
