#!/usr/bin/python3
"""tests/cookbook/run.py DOC BUILD DIR - every recipe of the cookbook, run as it is written.

The cookbook (doc/cookbook.md) is the source: each recipe ('## ' heading) holds its scene in a
block fenced as ```csf FILE (written to FILE), and console blocks (```console) of commands
('$ ' lines) each followed by the exact output it prints. Every command runs with sh, all in
one directory (a recipe may use an earlier one's files), with csfc, csfvm and csfview of BUILD
first on PATH (each under a time limit) and the build's Python package on PYTHONPATH; its standard output must be the lines
the cookbook shows. The checks the recipes state are commands too (awk against the closed
form), so a recipe whose physics is wrong fails here. A recipe that needs the Python package
(python3 ... import csf) is a SKIP line under the sanitizers (no libcsf.so there), and one
that needs numpy or h5py a SKIP line without them.
run.py --extract DOC DIR writes the scenes alone (for the editors' test).
"""
import os
import re
import subprocess
import sys


def recipes(doc):
    """[(title, [(kind, name, lines)])]: kind 'csf' (a scene FILE) or 'console'."""
    out, cur, block = [], None, None
    for line in open(doc, encoding="utf-8").read().split("\n"):
        if block is not None:
            if line == "```":
                cur[1].append(block)
                block = None
            else:
                block[2].append(line)
            continue
        m = re.match(r"```(csf|console)(?: (\S+))?$", line)
        if m and cur:
            block = (m.group(1), m.group(2), [])
        elif line.startswith("## "):
            cur = (line[3:], [])
            out.append(cur)
    return out


def main():
    if sys.argv[1] == "--extract":
        os.makedirs(sys.argv[3], exist_ok=True)
        for i, (title, blocks) in enumerate(recipes(sys.argv[2])):
            for kind, name, lines in blocks:
                if kind == "csf":
                    with open(os.path.join(sys.argv[3], "%02d_%s" % (i + 1, name)), "w") as f:
                        f.write("\n".join(lines) + "\n")
        return 0
    doc, build, top = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
    limit = os.environ.get("CSF_TEST_LIMIT", "300")
    bindir = os.path.join(top, "bin")
    os.makedirs(bindir, exist_ok=True)
    for tool in ("csfc", "csfvm", "csfview"):
        with open(os.path.join(bindir, tool), "w") as f:
            f.write('#!/bin/sh\nexec timeout %s "%s" "$@"\n' % (limit, os.path.join(build, tool)))
        os.chmod(os.path.join(bindir, tool), 0o755)
    env = dict(os.environ, PATH=bindir + ":/usr/bin:/bin:" + os.environ.get("PATH", ""),
               PYTHONPATH=os.path.join(build, "python"), PYTHONDONTWRITEBYTECODE="1", LC_ALL="C")
    san = os.environ.get("CSF_SAN")
    fails = ran = 0
    for i, (title, blocks) in enumerate(recipes(doc)):
        d = os.path.join(top, "recipes")  # one directory: later recipes use the files of earlier ones
        os.makedirs(d, exist_ok=True)
        text = "\n".join("\n".join(b[2]) for b in blocks if b[0] == "console")
        needs = [m for m in ("numpy", "h5py") if ("import csf" in text and m == "numpy") or ("import h5py" in text and m == "h5py")]
        if "import csf" in text and san:
            print("SKIP: cookbook: %s: the sanitizer build has no libcsf.so" % title)
            continue
        if needs and subprocess.run(["/usr/bin/python3", "-c", "import " + ", ".join(needs)], capture_output=True).returncode:
            print("SKIP: cookbook: %s: no %s in /usr/bin/python3" % (title, " or ".join(needs)))
            continue
        ok = True
        for kind, name, lines in blocks:
            if kind == "csf":
                with open(os.path.join(d, name), "w") as f:
                    f.write("\n".join(lines) + "\n")
                continue
            cmds = []
            for line in lines:
                if line.startswith("$ "):
                    cmds.append([line[2:], []])
                elif cmds:
                    cmds[-1][1].append(line)
            for cmd, want in cmds:
                r = subprocess.run(["sh", "-c", cmd], cwd=d, env=env, capture_output=True, text=True)
                got = r.stdout.rstrip("\n").split("\n") if r.stdout.strip("\n") else []
                while want and want[-1] == "":
                    want.pop()
                if got != want:
                    print("FAIL: cookbook: %s: $ %s\n  expected: %s\n  got: %s%s" % (title, cmd, want[:4], got[:4],
                          ("\n  stderr: " + r.stderr.strip()[:300]) if r.stderr.strip() else ""))
                    ok = False
                    break
            if not ok:
                break
        ran += 1
        fails += not ok
    print("cookbook: %d recipes run, %d failed" % (ran, fails))
    return 1 if fails or not ran else 0


sys.exit(main())
