"""A result in Jupyter: _repr_html_ is csfview's page in an <iframe srcdoc>, the run's rows inside it
bit for bit, every k-th and the last of a big run as csfview decimates (said so in CSF_META), the
title and the notes escaped once for the page and once for the attribute; a run without rows, and
one csfview cannot draw, as text. In node, where it is installed, the page (decoded from the
fragment) draws the ball where the run has it (tests/view/drawn.js)."""
import html.parser
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

from conftest import LIMIT, same_bits, top

OSC = "object p: x = 1\nobject p: v = 0\nrule: x' = v\nrule: v' = -x\ninc t till 1000 by 0.01 watch x, v\n"


class _Parser(html.parser.HTMLParser):
    """The tags of a document with their attributes (values unescaped), the text inside each element
    with an id, and each <script>'s text."""

    def __init__(self, text):
        super().__init__(convert_charrefs=True)
        self.tags, self.text, self.scripts, self.outside = [], {}, [], []
        self._open = []
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        self._open.append((tag, a.get("id")))
        if tag == "script":
            self.scripts.append([a, ""])

    def handle_endtag(self, tag):
        while self._open:
            t, _ = self._open.pop()
            if t == tag:
                break

    def handle_data(self, data):
        if not self._open:
            self.outside.append(data)
        for t, i in self._open:
            if i is not None:
                self.text[i] = self.text.get(i, "") + data
        if self._open and self._open[-1][0] == "script":
            self.scripts[-1][1] += data


def inner(frag):
    """The page in the fragment: its one <iframe>'s srcdoc (the fragment has nothing else)."""
    p = _Parser(frag)
    assert [t for t, _ in p.tags] == ["iframe"] and not "".join(p.outside).strip(), frag[:200]
    a = p.tags[0][1]
    assert a["sandbox"] == "allow-scripts"
    return a["srcdoc"], a


def page_rows(page):
    """The page's CSV (<script id="csv">): the header's cells and the rows as float()."""
    p = _Parser(page)
    csv = [s for a, s in p.scripts if a.get("id") == "csv"]
    assert len(csv) == 1
    lines = [l for l in csv[0].split("\n") if l]
    rows = np.array([[float(x) for x in l.split(",")] for l in lines[1:]], dtype=np.float64)
    return lines[0].split(","), rows.reshape(len(lines) - 1, -1), p


def meta(page):
    m = re.search(r"var CSF_META = \{rows: (\d+), stride: (\d+),", page)
    return int(m.group(1)), int(m.group(2))


@pytest.fixture(scope="module")
def projectile():
    import csf
    return csf.compile(top("examples", "projectile.csf")).run()


def test_the_rows_inside(projectile):
    r = projectile
    page, attrs = inner(r._repr_html_())
    assert page == r.page() and attrs["title"] == "projectile"
    head, rows, p = page_rows(page)
    assert head == ["t", "ball.pos.x [m]", "ball.pos.y [m]", "ball.pos.z [m]", "ball.v.x [m/s]", "ball.v.y [m/s]",
                    "ball.v.z [m/s]"]
    assert same_bits(rows, r.data)
    assert meta(page) == (21, 1)
    assert p.text["title"] == "projectile" and "planes: []" in page
    # nothing on the page is loaded from elsewhere (csfview inlines three.js, dygraphs and view.js)
    refs = [(t, a) for t, a in p.tags if "src" in a or "href" in a or t in ("link", "img", "iframe")]
    assert refs == []
    # two results are two documents: nothing of the page is outside the srcdoc attribute
    assert len(re.findall(r"<iframe\b", r._repr_html_())) == 1 and ' id="' not in r._repr_html_()


def test_decimated(csf):
    r = csf.compile(source=OSC).run()
    assert r.data.shape == (100001, 3)
    # 10000 intervals at most (csfview's): every 10th row
    page = r.page()
    _, rows, _ = page_rows(page)
    assert meta(page) == (100001, 10) and same_bits(rows, r.data[::10])
    # every k-th and the last, k the smallest that keeps at most 7 intervals
    page = r.page(max_rows=7)
    _, rows, _ = page_rows(page)
    k = 14286
    assert meta(page) == (100001, k) and same_bits(rows, r.data[list(range(0, 100001, k)) + [100000]])
    # at most max_values numbers: 3000 // 3 - 1 = 999 intervals, every 101st row and the last
    page = r.page(max_values=3000)
    _, rows, _ = page_rows(page)
    assert meta(page) == (100001, 101) and rows.size <= 3000
    assert same_bits(rows, r.data[list(range(0, 100001, 101)) + [100000]])
    # the notebook's display is bounded the same way: some 10001 rows of 3 numbers, and the JavaScript
    assert len(r._repr_html_()) < 4_000_000


def test_escaped(csf, tmp_path):
    # a title with & < > " ': escaped in the page, escaped again in the attribute; read back whole
    odd = tmp_path / "a<b&\"c'd.csf"
    shutil.copy(top("examples", "projectile.csf"), odd)
    r = csf.compile(str(odd)).run()
    page, attrs = inner(r._repr_html_())
    assert attrs["title"] == "a<b&\"c'd"
    p = _Parser(page)
    assert p.text["title"] == "a<b&\"c'd"
    assert "<h1 id=\"title\">a&lt;b&amp;&quot;c'd</h1>" in page
    head, rows, _ = page_rows(page)
    assert same_bits(rows, r.data)


def test_failed_run(csf):
    m = csf.compile(source="object p: x = 1 m\nobject p: v = 1 m/s\nrule: x' = v\nassert x < 1.5 m\n"
                           "inc t till 2 s by 0.1 s watch x\n")
    with pytest.raises(csf.RunError) as e:
        m.run()
    r = e.value.result
    assert len(r) == 5
    page, _ = inner(r._repr_html_())
    _, rows, p = page_rows(page)
    assert same_bits(rows, r.data)
    assert p.text["note"] == ("<stdin>:4: assertion failed at t=0.5: x < 1.5 m (object p)\n"
                              "The run ended at t = 0.4, before the end of the scene at t = 2.")
    # a run a progress function ended says so
    r = m.run(params={"p.v": "0.1 m/s"}, progress=lambda t, n: t >= 0.5, progress_interval=0)
    assert r.stopped and len(r) == 6
    page, _ = inner(r._repr_html_())
    assert _Parser(page).text["note"].startswith("Stopped by the progress function after 6 rows.\n")


def test_no_rows(csf):
    m = csf.compile(source="object p: x = 1 m\nobject p: v = 1 m/s\nrule: x' = v\nassert x < 0.5 m\n"
                           "inc t till 2 s by 0.1 s watch x\n")
    with pytest.raises(csf.RunError) as e:
        m.run()
    r = e.value.result
    assert len(r) == 0
    frag = r._repr_html_()
    p = _Parser(frag)
    assert [t for t, _ in p.tags] == ["div", "pre", "pre", "pre"]
    assert "".join(p.outside) == ""
    texts = re.findall(r"<pre>(.*?)</pre>", frag, re.S)
    assert [html.unescape(x) for x in texts] == [repr(r), "the run has no rows: nothing to show",
                                                 "<stdin>:4: assertion failed at t=0: x < 0.5 m (object p)"]
    with pytest.raises(RuntimeError, match="no rows"):
        r.page()


def test_no_csfview(projectile, monkeypatch):
    monkeypatch.setenv("CSF_CSFVIEW", "/nonexistent/csfview")
    frag = projectile._repr_html_()
    assert frag.startswith('<div class="csf-result"><pre>&lt;csf.Result: 21 rows')
    assert "cannot run /nonexistent/csfview" in frag and "<iframe" not in frag


@pytest.mark.skipif(shutil.which("node") is None, reason="no node")
def test_drawn_in_node(projectile, tmp_path):
    # the page the notebook shows, run by its own scripts: the ball at t = 1 s and 2 s where the run has it
    r = projectile
    page, _ = inner(r._repr_html_())
    f = tmp_path / "p.html"
    f.write_text(page)
    for k in (10, 20):
        p = subprocess.run(["node", top("tests", "view", "drawn.js"), str(f), repr(r.t[k])], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=LIMIT)
        assert p.returncode == 0, p.stderr.decode()
        ball = [l.split() for l in p.stdout.decode().splitlines() if l.startswith("object ball ")]
        assert len(ball) == 1 and [float(x) for x in ball[0][2:5]] == r["ball.pos"][k].tolist()
