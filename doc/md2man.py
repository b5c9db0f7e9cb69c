#!/usr/bin/python3
"""doc/md2man.py doc/cookbook.md > man/csf-cookbook.7 - the cookbook as a manual page.

doc/cookbook.md is the source; man/csf-cookbook.7 is made from it by this script and kept in
the tree (make install installs it without Python); tests/cookbook/check.sh makes it again and
fails when the two differ. The Markdown is the little the cookbook uses: '# ' the title, '## '
a recipe (a subsection of RECIPES), paragraphs, `code` (bold), and fenced blocks (```csf FILE:
a scene with its file name, ```console: commands and their output), shown as examples.
"""
import re
import sys


def esc(s):
    """Text escaped for roff: backslashes, dashes, and a leading dot or quote."""
    s = s.replace("\\", "\\e").replace("-", "\\-")
    return "\\&" + s if s[:1] in (".", "'") else s


def inline(s):
    out = []
    for i, part in enumerate(re.split(r"`([^`]*)`", s)):
        out.append("\\fB" + esc(part) + "\\fR" if i % 2 else esc(part))
    return "".join(out)


def main():
    lines = open(sys.argv[1], encoding="utf-8").read().split("\n")
    out = ['.\\" Made from doc/cookbook.md by doc/md2man.py: edit that file, not this one.',
           '.TH CSF-COOKBOOK 7 "2026" "CSF 0.1.0" "CSF Manual"',
           ".SH NAME",
           "csf-cookbook \\- short CSF recipes, each a complete scene with its output and its check",
           ".SH DESCRIPTION"]
    para, block, recipes = [], None, False

    def flush():
        if para:
            out.append(".PP")
            out.append(inline(" ".join(para)))
            para.clear()

    for line in lines:
        if block is not None:
            if line == "```":
                out.append(".EE")
                block = None
            else:
                out.append(esc(line) if line else "")
            continue
        m = re.match(r"```(\w+)(?: (\S+))?$", line)
        if m:
            flush()
            out.append(".PP")
            if m.group(2):
                out.append("\\fI" + esc(m.group(2)) + "\\fR:")
            out.append(".EX")
            block = m.group(1)
        elif line.startswith("# "):
            continue
        elif line.startswith("## "):
            flush()
            if not recipes:
                out.append(".SH RECIPES")
                recipes = True
            out.append(".SS " + esc(line[3:]))
        elif not line.strip():
            flush()
        else:
            para.append(line.strip())
    flush()
    out += [".SH SEE ALSO", ".BR csfc (1),", ".BR csfvm (1),", ".BR csfview (1),", ".BR csf (5),", ".BR csf\\-python (7)"]
    sys.stdout.write("\n".join(out) + "\n")


main()
