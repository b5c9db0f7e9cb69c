// tests/editors/tokens.js NODE_MODULES GRAMMAR FILE... - the TextMate grammar on whole scenes.
//
// Tokenizes every FILE (the examples, the standard library, the end-to-end scenes, the
// cookbook's scenes) with vscode-textmate, as VS Code does, and checks each line against
// what the compiler's scanner makes of it, found here by plain regular expressions:
//   - every character but blanks has a scope of its own (nothing left as plain source.csf);
//   - nothing is marked invalid (these scenes compile);
//   - a comment (# outside a string) is a comment to the end of the line;
//   - a number followed by a name (not a keyword) is a number and then a unit literal;
//   - the name after `object` is an object's name, after `rule` a letter-word before ':' or
//     'for' is the attribute, `$n` is a binding, `.mul` ... are methods.
// Prints "FAIL: file:line:col: ..." for each miss (the first 20) and the count of lines.
'use strict';
const path = require('path');
const fs = require('fs');
const [mods, grammarPath, ...files] = process.argv.slice(2);
const modules = path.resolve(mods);
const vsctm = require(path.join(modules, 'vscode-textmate'));
const oniguruma = require(path.join(modules, 'vscode-oniguruma'));

const wasm = fs.readFileSync(path.join(modules, 'vscode-oniguruma', 'release', 'onig.wasm')).buffer;
const onigLib = oniguruma.loadWASM(wasm).then(() => ({
	createOnigScanner: (p) => new oniguruma.OnigScanner(p),
	createOnigString: (s) => new oniguruma.OnigString(s),
}));
const registry = new vsctm.Registry({
	onigLib,
	loadGrammar: async () => vsctm.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath),
});

const KEYWORDS = new Set(['atol', 'and', 'or', 'not', 'for', 'if', 'elif', 'else', 'by', 'till', 'watch', 'from', 'when']);
let fails = 0, lines = 0;
function fail(f, ln, col, what) {
	if (++fails <= 20) console.log(`FAIL: ${f}:${ln}:${col + 1}: ${what}`);
}

registry.loadGrammar('source.csf').then((grammar) => {
	for (const f of files) {
		let rule = vsctm.INITIAL;
		const text = fs.readFileSync(f, 'utf8').split('\n');
		text.forEach((line, i) => {
			const r = grammar.tokenizeLine(line, rule);
			rule = r.ruleStack;
			lines++;
			// the scopes of each character
			const at = new Array(line.length);
			for (const t of r.tokens) for (let c = t.startIndex; c < Math.min(t.endIndex, line.length); c++) at[c] = t.scopes;
			const has = (c, s) => at[c] && at[c].some((x) => x.startsWith(s));
			// where a comment starts: the first # outside a string
			let hash = -1, q = false;
			for (let c = 0; c < line.length; c++) {
				if (line[c] === '"') q = !q;
				else if (line[c] === '#' && !q) { hash = c; break; }
			}
			for (let c = 0; c < line.length; c++) {
				if (line[c] === ' ' || line[c] === '\t') continue;
				if (!at[c] || at[c].length < 2) { fail(f, i + 1, c, `'${line[c]}' has no scope: ${line}`); break; }
				if (has(c, 'invalid')) { fail(f, i + 1, c, `marked invalid: ${line}`); break; }
				if (hash >= 0 && c >= hash && !has(c, 'comment.line')) { fail(f, i + 1, c, `not a comment: ${line}`); break; }
				if ((hash < 0 || c < hash) && has(c, 'comment')) { fail(f, i + 1, c, `a comment too early: ${line}`); break; }
			}
			const code = hash >= 0 ? line.slice(0, hash) : line;
			if (/^\s*using\b/.test(code)) return;
			let m;
			const num = /(?<![A-Za-z0-9_.$^])(?<!\^-)(\d+(?:\.(?!\.)\d*)?(?:[eE][+-]?\d+)?)(\s*)([A-Za-z_]\w*)?/g;
			while ((m = num.exec(code))) {
				if (has(m.index, 'keyword.other.unit')) continue;
				if (!has(m.index, 'constant.numeric')) fail(f, i + 1, m.index, `${m[1]} is not a number: ${line}`);
				const u = m.index + m[1].length + m[2].length;
				if (m[3] && !KEYWORDS.has(m[3]) && !has(u, 'keyword.other.unit')) fail(f, i + 1, u, `${m[3]} after ${m[1]} is not a unit: ${line}`);
			}
			if ((m = /^(\s*object\s+)([A-Za-z_]\w*)/.exec(code)) && !has(m[1].length, 'entity.name.type.object'))
				fail(f, i + 1, m[1].length, `not an object's name: ${line}`);
			if ((m = /^(\s*rule\s+)(?!for\b)([A-Za-z]+)\s*(?=[:]|for\b)/.exec(code)) && !has(m[1].length, 'entity.other.attribute-name'))
				fail(f, i + 1, m[1].length, `not a rule's attribute: ${line}`);
			const bind = /\$\d+/g;
			while ((m = bind.exec(code))) if (!has(m.index, 'variable.language.binding')) fail(f, i + 1, m.index, `${m[0]} is not a binding: ${line}`);
			const meth = /\.(mul|dot|cross|mag|angle|unit|proj)\b/g;
			while ((m = meth.exec(code))) if (!has(m.index + 1, 'support.function.method')) fail(f, i + 1, m.index + 1, `.${m[1]} is not a method: ${line}`);
		});
	}
	console.log(`tokens: ${files.length} files, ${lines} lines, ${fails} failed`);
	process.exit(fails ? 1 : 0);
});
