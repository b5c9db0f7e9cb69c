#!/usr/bin/python3
"""tests/lsp/client.py CSFC DIR - csfc --lsp driven as an editor drives it.

Speaks the Language Server Protocol (Content-Length framing, JSON-RPC 2.0)
to `CSFC --lsp` over a pipe, with the standard library only, and checks:
diagnostics on open (two errors, each at the range of the name csfc's
message points at), after a change that fixes one (one left), after
fixing both (none), a warning as severity 2; hover on `v` names its unit
m/s and the rule line that integrates it, on `ball` what --explain says
of the object, on `W` the rule that computes it; definition of `ball`
and of `b` jumps to their object lines, of `pos` into mechanics/mass_point;
malformed input (not JSON, no Content-Length, nesting 100 000 deep, wrong
types, an unknown method, a document never opened; 300 random documents,
200 random bodies) is answered with an error and the server goes on; shutdown then exit ends it with status 0.
Prints "FAIL: ..." for each failed check; exits 1 if any failed.
"""
import json
import os
import random
import subprocess
import sys
import threading

CSFC, DIR = sys.argv[1], sys.argv[2]
LIMIT = float(os.environ.get("CSF_TEST_LIMIT", "60"))
fails = []


def check(cond, what):
    if not cond:
        fails.append(what)
        print("FAIL: lsp: " + what)


# without CSF_STDLIB: the server finds the standard library beside itself, as an installed csfc does
# (a path it must keep while every compilation releases the compiler's memory)
env = {k: v for k, v in os.environ.items() if k != "CSF_STDLIB"}
proc = subprocess.Popen([CSFC, "--lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, cwd=DIR, env=env)
timer = threading.Timer(LIMIT, proc.kill)  # a hang fails the test
timer.start()


def send_raw(data):
    proc.stdin.write(data)
    proc.stdin.flush()


def send(obj):
    body = json.dumps(obj).encode()
    send_raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)


def receive():
    try:
        return receive_one()
    except (EOFError, ValueError) as e:  # the server died or wrote garbage: the test fails here
        print("FAIL: lsp: %s (after %d checks failed)" % (e, len(fails)))
        proc.kill()
        sys.exit(1)


def receive_one():
    length = None
    while True:
        line = proc.stdout.readline()
        if not line:
            raise EOFError("the server closed its output")
        line = line.strip()
        if not line:
            break
        k, _, v = line.partition(b":")
        if k.lower() == b"content-length":
            length = int(v)
    return json.loads(proc.stdout.read(length))


next_id = [0]


def request(method, params):
    next_id[0] += 1
    send({"jsonrpc": "2.0", "id": next_id[0], "method": method, "params": params})
    while True:
        m = receive()
        if m.get("id") == next_id[0]:
            return m


def notify(method, params):
    send({"jsonrpc": "2.0", "method": method, "params": params})


def diagnostics():
    m = receive()
    check(m.get("method") == "textDocument/publishDiagnostics", "expected diagnostics, got %s" % m)
    return m["params"]["diagnostics"]


def rng(d):
    r = d["range"]
    return (r["start"]["line"], r["start"]["character"], r["end"]["line"], r["end"]["character"])


TWO_ERRORS = """# a ball thrown up, with drag
using mechanics/mass_point
object ball: mass_point
object ball: m = 2 kg
object ball: v = (1, 0, 5) m/s
object ball: b = 0.5 kg/s
using mechanics/rules
rule F: W = g.mul(mass)
rule F: D = v.mul(-bb)
inc t till 1 s by 0.5 s watch pos, v
"""
path = os.path.join(os.path.abspath(DIR), "thrown ball.csf")
uri = "file://" + path.replace(" ", "%20")

r = request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
caps = r.get("result", {}).get("capabilities", {})
check(caps.get("hoverProvider") and caps.get("definitionProvider"), "initialize: %s" % r)
check(caps.get("textDocumentSync", {}).get("change") == 1, "initialize: full sync: %s" % caps)
notify("initialized", {})

notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "csf", "version": 1, "text": TWO_ERRORS}})
d = diagnostics()
check(len(d) == 2, "two errors: %d diagnostics: %s" % (len(d), d))
if len(d) == 2:
    # line 8 (7 from 0) col 19: 'mass'; line 9 col 20: 'bb' (csfc's file:line:col, byte columns from 1)
    check(rng(d[0]) == (7, 18, 7, 22), "the first error's range %s, expected 'mass' (7, 18, 7, 22)" % (rng(d[0]),))
    check(rng(d[1]) == (8, 19, 8, 21), "the second error's range %s, expected 'bb' (8, 19, 8, 21)" % (rng(d[1]),))
    check(d[0]["severity"] == 1 and "unknown name 'mass'" in d[0]["message"] and "did you mean 'm'?" in d[0]["message"],
          "the first message: %s" % d[0])
    check(d[1]["severity"] == 1 and "unresolvable" in d[1]["message"], "the second message: %s" % d[1])

# the same text, its cli compile: the same messages as csfc prints
with open(path, "w") as f:
    f.write(TWO_ERRORS)
cli = subprocess.run([CSFC, path, "-o", os.devnull], capture_output=True, text=True)
for x in d:
    check(x["message"] in cli.stderr, "the message is csfc's: %s not in %s" % (x["message"], cli.stderr))

one = TWO_ERRORS.replace("mul(mass)", "mul(m)")
notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": one}]})
d = diagnostics()
check(len(d) == 1 and rng(d[0]) == (8, 19, 8, 21), "one error fixed: %s" % d)

good = one.replace("(-bb)", "(-b)")
notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": good}]})
d = diagnostics()
check(d == [], "both fixed: %s" % d)


def hover(line, ch):
    r = request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": line, "character": ch}})
    res = r.get("result")
    return res["contents"]["value"] if res else ""


def definition(line, ch):
    r = request("textDocument/definition", {"textDocument": {"uri": uri}, "position": {"line": line, "character": ch}})
    return r.get("result")


lines = good.split("\n")
# v in "rule F: D = v.mul(-b)" (line 9, from 0: 8)
h = hover(8, lines[8].index("v.mul"))
check("m/s" in h and "`m/s`" in h and "vector" in h and "ball.v" in h, "hover on v: %r" % h)
check("state variable" in h, "hover on v says it is integrated: %r" % h)
# W: computed by the rule on line 8, unit N
h = hover(7, lines[7].index("W"))
check("line 8" in h and "`N`" in h, "hover on W: %r" % h)
# b in "-b": kg/s, constant
h = hover(8, lines[8].index("-b") + 1)
check("`kg/s`" in h and "constant" in h, "hover on b: %r" % h)
# ball on its object line: --explain's line for the object
h = hover(3, lines[3].index("ball") + 2)
check(h.startswith("object ball:") and "pos (state)" in h, "hover on ball: %r" % h)
# the rule keyword: what the rule solves for
h = hover(7, 1)
check("solves for W" in h, "hover on rule: %r" % h)
check(hover(0, 3) == "", "hover in a comment: %r" % hover(0, 3))

loc = definition(3, lines[3].index("ball"))
check(loc and loc["uri"] == uri and loc["range"]["start"] == {"line": 2, "character": 7},
      "definition of ball: the object line 3 (2 from 0), got %s" % loc)
loc = definition(8, lines[8].index("-b") + 1)
check(loc and loc["uri"] == uri and loc["range"]["start"]["line"] == 5, "definition of b: line 6 (5 from 0), got %s" % loc)
loc = definition(9, lines[9].index("pos"))
check(loc and loc["uri"].endswith("/mechanics/mass_point.csf"), "definition of pos: mass_point.csf, got %s" % loc)

# columns are UTF-16 code units (LSP's), csfc's are bytes: after a pi (2 bytes, 1 unit), the range
# of 'qq' in characters, and a hover's column back to bytes
PI = "object p: x = 1 m \nrule: y = \u03c0 * x + qq\ninc t till 1 s by 1 s watch y\n"
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": PI}]})
d = diagnostics()
q = PI.split("\n")[1].index("qq")
check(len(d) == 1 and rng(d[0]) == (1, q, 1, q + 2), "the range of qq after a pi: %s, expected (1, %d, 1, %d)" % (d, q, q + 2))
r = request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": 1, "character": q}})
check(r.get("result") is None, "hover in a text with an error: null, got %s" % r)
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": PI.replace(" + qq", "")}]})
check(diagnostics() == [], "the pi scene without qq compiles")
r = request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": 1, "character": PI.split("\n")[1].index("x")}})
h = (r.get("result") or {}).get("contents", {}).get("value", "")
check(h.startswith("**p.x**") and "`m`" in h, "hover on x after a pi (a column in UTF-16 units): %r" % h)
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": good}]})
check(diagnostics() == [], "good again after the pi")

# a second document: names bound by a `for` list ($0 the first, pos$1 the second), hover over them
ROD = """using mechanics/mass_point
object pivot: anchor
object bob: mass_point
object bob: pos = (1, 0, 0) m
using mechanics/rules
rule F: W = g.mul(m)
rule C for bob, pivot: (pos - pos$1).mag = 1 m
inc t till 1 s by 0.5 s watch bob.pos
"""
uri2 = "file://" + os.path.join(os.path.abspath(DIR), "rod.csf")
notify("textDocument/didOpen", {"textDocument": {"uri": uri2, "languageId": "csf", "version": 1, "text": ROD}})
check(diagnostics() == [], "the rod compiles")
rl = ROD.split("\n")[6]
for col, want in ((rl.index("(pos") + 1, "**bob.pos**"), (rl.index("pos$1"), "**pivot.pos**")):
    r = request("textDocument/hover", {"textDocument": {"uri": uri2}, "position": {"line": 6, "character": col}})
    h = (r.get("result") or {}).get("contents", {}).get("value", "")
    check(h.startswith(want) and "`m`" in h, "hover at %d of the rod's rule: %r, expected %s" % (col, h, want))
r = request("textDocument/hover", {"textDocument": {"uri": uri2}, "position": {"line": 3, "character": 13}})
h = (r.get("result") or {}).get("contents", {}).get("value", "")
check(h.startswith("**bob.pos**") and "state variable" in h, "hover on pos of bob's line: %r" % h)
notify("textDocument/didClose", {"textDocument": {"uri": uri2}})
check(diagnostics() == [], "the rod closed")

# a warning: severity 2, at the rule
warned = good.replace("rule F: D", "rule: D")
notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 4}, "contentChanges": [{"text": warned}]})
d = diagnostics()
check(len(d) == 1 and d[0]["severity"] == 2 and rng(d[0])[0] == 8 and "nothing reads" in d[0]["message"],
      "a warning: %s" % d)

# malformed messages: each answered, the server goes on
send_raw(b"Content-Length: 9\r\n\r\n{not json")
m = receive()
check(m.get("error", {}).get("code") == -32700, "not JSON: %s" % m)
send_raw(b"Content-Type: x\r\n\r\n")
m = receive()
check(m.get("error", {}).get("code") == -32600, "no Content-Length: %s" % m)
deep = b"[" * 100000 + b"]" * 100000
send_raw(b"Content-Length: %d\r\n\r\n" % len(deep) + deep)
m = receive()
check(m.get("error", {}).get("code") == -32700, "nesting 100000 deep: %s" % m)
send_raw(b'Content-Length: 2\r\n\r\n[]')
m = receive()
check(m.get("error", {}).get("code") == -32600, "not an object: %s" % m)
r = request("textDocument/frobnicate", {})
check(r.get("error", {}).get("code") == -32601, "unknown method: %s" % r)
r = request("textDocument/hover", {"textDocument": {"uri": "file:///nowhere.csf"}, "position": {"line": 0, "character": 0}})
check(r.get("error", {}).get("code") == -32602, "hover on a document never opened: %s" % r)
r = request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": "x", "character": -5}})
check(r.get("result") is None and "error" not in r, "hover at a bad position: %s" % r)
r = request("textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": 1000, "character": 1e300}})
check(r.get("result") is None, "hover past the end: %s" % r)
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": 7})
notify("textDocument/didOpen", {"textDocument": {"uri": 5}})
s = b'{"jsonrpc":"2.0","id":"s\\u00e9","method":"x\\ud800"}'
send_raw(b"Content-Length: %d\r\n\r\n" % len(s) + s)
m = receive()
check(m.get("error", {}).get("code") == -32700, "a lone surrogate: %s" % m)
# a binary document, NUL bytes in it: one error, then a good text again
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": "\u0000\u0001object"}]})
d = diagnostics()
check(len(d) == 1 and d[0]["severity"] == 1, "a binary document: %s" % d)
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": good}]})
check(diagnostics() == [], "good again")
# many compilations in one process (the arena released each time)
for i in range(200):
    notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": good if i % 2 else TWO_ERRORS}]})
    n = len(diagnostics())
    if n != (0 if i % 2 else 2):
        check(False, "compilation %d: %d diagnostics" % (i, n))
        break
# hostile input, seeded: 300 documents made of pieces of the scene shuffled and cut (each answered
# with its diagnostics), hover and definition everywhere in them, and 200 bodies of random bytes
# and broken JSON (each answered with an error, or ignored as a notification)
rnd = random.Random(35)
pieces = good.replace("\n", " \n ").split(" ") + ["(", ")", "$1", "'", ":", "\t", "\u00e9", "\u03c0", "if", "else:", "\x00"]
for i in range(300):
    text = " ".join(rnd.choice(pieces) for _ in range(rnd.randint(0, 80)))
    notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": text}]})
    diagnostics()
    if i % 10 == 0:
        for _ in range(5):
            pos = {"line": rnd.randint(-1, 12), "character": rnd.randint(-1, 40)}
            request("textDocument/hover" if rnd.random() < 0.5 else "textDocument/definition",
                    {"textDocument": {"uri": uri}, "position": pos})
for i in range(200):
    body = bytes(rnd.randint(0, 255) for _ in range(rnd.randint(0, 60)))
    if i % 2:
        body = json.dumps({"jsonrpc": "2.0", "id": i, "method": "textDocument/hover", "params": {}}).encode()
        body = body[:rnd.randint(0, len(body))]
    send_raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)
    r = request("textDocument/definition", {"textDocument": {"uri": uri}, "position": {"line": 0, "character": 0}})
    if "result" not in r:
        check(False, "after hostile body %d the server answers %s" % (i, r))
        break
notify("textDocument/didChange", {"textDocument": {"uri": uri}, "contentChanges": [{"text": good}]})
check(diagnostics() == [], "good after the hostile input")

notify("textDocument/didClose", {"textDocument": {"uri": uri}})
check(diagnostics() == [], "closed: its diagnostics cleared")

r = request("shutdown", None)
check("result" in r and r["result"] is None, "shutdown: %s" % r)
notify("exit", None)
try:
    st = proc.wait(LIMIT)
except subprocess.TimeoutExpired:
    proc.kill()
    st = None
timer.cancel()
check(st == 0, "exit after shutdown: status %s" % st)

# exit without shutdown: status 1; the end of the input: status 1
for msgs in ([{"jsonrpc": "2.0", "method": "exit"}], []):
    p = subprocess.Popen([CSFC, "--lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    data = b"".join(b"Content-Length: %d\r\n\r\n%s" % (len(json.dumps(x)), json.dumps(x).encode()) for x in msgs)
    out, _ = p.communicate(data, timeout=LIMIT)
    check(p.returncode == 1, "%s without shutdown: status %d" % ("exit" if msgs else "end of input", p.returncode))

# a model named beside --lsp: bad usage
p = subprocess.run([CSFC, "--lsp", "x.csf"], capture_output=True, text=True, timeout=LIMIT)
check(p.returncode == 2 and "--lsp" in p.stderr, "csfc --lsp x.csf: status %d, %s" % (p.returncode, p.stderr))

print("lsp: %d failed" % len(fails))
sys.exit(1 if fails else 0)
