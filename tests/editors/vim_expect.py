#!/usr/bin/python3
"""tests/editors/vim_expect.py SAMPLE... - the TextMate samples' annotations as Vim's syntax groups.

Reads the annotated samples of tests/editors/samples (vscode-tmgrammar-test's format: a
line of code, then comment lines whose carets or '<-' mark columns and name the scope
expected there) and prints, for each marked column, "FILE LINE COL GROUPS": the Vim syntax
groups (one of them, '|'-separated) that editors/vim/syntax/csf.vim must give it. Scopes
Vim does not colour (punctuation, operators) are left out. One set of annotations tests
both editors.
"""
import re
import sys

GROUPS = {
    "comment.line.number-sign.csf": "csfComment",
    "keyword.control.import.csf": "csfUsing",
    "keyword.control.import.from.csf": "csfFrom",
    "string.unquoted.path.csf": "csfUsingPath",
    "string.quoted.double.csf": "csfString",
    "storage.type.object.csf": "csfObject",
    "entity.name.type.object.csf": "csfObjectName",
    "entity.name.type.kind.csf": "csfKind|csfKindName",
    "variable.other.property.csf": "csfProperty|csfMember",
    "constant.numeric.csf": "csfNumber",
    "keyword.other.unit.csf": "csfUnit",
    "storage.modifier.vector.csf": "csfVector|csfVectorKw",
    "storage.type.def.csf": "csfDef",
    "storage.modifier.global.csf": "csfGlobal",
    "variable.other.global.csf": "csfGlobalName",
    "keyword.other.rule.csf": "csfRule",
    "entity.other.attribute-name.csf": "csfAttribute",
    "keyword.other.for.csf": "csfFor|csfSumFor",
    "variable.other.object.csf": "csfForName|csfName",
    "variable.language.binding.csf": "csfBinding",
    "keyword.operator.derivative.csf": "csfDerivative",
    "keyword.control.conditional.csf": "csfConditional",
    "keyword.operator.logical.csf": "csfOperatorWord",
    "keyword.operator.range.csf": "csfRange",
    "variable.other.component.csf": "csfComponent",
    "keyword.control.when.csf": "csfWhen",
    "keyword.control.assert.csf": "csfAssert",
    "keyword.control.stop.csf": "csfStop",
    "variable.language.csf": "csfPredefined",
    "keyword.control.start.csf": "csfStart|csfStartKw",
    "variable.language.time.csf": "csfTime",
    "variable.other.watched.csf": "csfName",
    "variable.other.csf": "csfName",
    "constant.language.csf": "csfConstant",
    "invalid.illegal.protected.csf": "csfProtected",
    "support.function.method.csf": "csfMethod",
    "support.function.math.csf": "csfFunction",
    "support.function.coordinates.csf": "csfFunction",
    "support.function.sum.csf": "csfFunction",
    "support.function.contact.csf": "csfFunction",
    "keyword.other.atol.csf": "csfAtol",
}

for path in sys.argv[1:]:
    code_line = 0
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            m = re.match(r"#(\s*)(\^+|<-+)\s+(\S+)\s*$", line)
            if n == 1 or not m:
                code_line = n
                continue
            if m.group(2).startswith("<"):
                cols = range(0, len(m.group(2)) - 1)
            else:
                start = 1 + len(m.group(1))
                cols = range(start, start + len(m.group(2)))
            scope = m.group(3)
            if scope not in GROUPS:
                continue
            # Vim counts bytes from 1
            text = open(path, encoding="utf-8").read().split("\n")[code_line - 1]
            for c in cols:
                byte = len(text[:c].encode()) + 1
                print(path, code_line, byte, GROUPS[scope])
