"""A run as csfview's page (csfview(1), csf-python(7) Result.page): in Jupyter, inline.

csfview writes the page (viewer/view.html, view.js, Debian's three.js and dygraphs, the rows as CSV
text): this module only hands it a run's rows and what else it reads. A big run is decimated here
first, by csfview's own rule (every k-th row and the last, k the smallest that keeps at most the
intervals asked for), so that no more than max_values numbers become text; --decimated tells
csfview, and the page says, which rows of how many it shows. In a notebook the page goes into an
<iframe srcdoc=...>, a document of its own (its ids and scripts cannot meet another result's), its
scripts sandboxed from the notebook; nothing is fetched when it is shown.
"""
import html
import os
import subprocess
import tempfile

from . import _lib

MAX_ROWS = 10000      # csfview's --max-rows: intervals between the rows shown
MAX_VALUES = 200000   # numbers a page carries at most (some 20 bytes of text each)


def stride(rows, width, max_rows=MAX_ROWS, max_values=MAX_VALUES):
    """k for a run of rows x width numbers: csfview's, for at most min(max_rows, max_values / width - 1)
    intervals (and at least 2)."""
    m = max(2, min(int(max_rows), int(max_values) // max(width, 1) - 1))
    return max(1, -(-(rows - 1) // m))


def shown(rows, k):
    """The rows shown of rows with stride k: every k-th from the first, and the last."""
    idx = list(range(0, rows, k))
    if rows and idx[-1] != rows - 1:
        idx.append(rows - 1)
    return idx


def _csv(result, idx):
    head = ["t"] + [c.name + (" [%s]" % c.unit if c.unit else "") for c in result.columns]
    lines = [",".join(head)]
    lines += [",".join(map(repr, row)) for row in result.data[idx].tolist()]
    return ("\n".join(lines) + "\n").encode()


def _title(result):
    path = result.model.path
    if path:
        name = os.path.basename(os.fspath(path))
        return name[:-4] if name.endswith(".csf") else name
    return "csf run"


def _note(result):
    n = len(result)
    if result.stopped:
        return "Stopped by the progress function after %d rows." % n
    if result.status == 130:
        return "Interrupted after %d rows." % n
    return ""


def page(result, max_rows=MAX_ROWS, max_values=MAX_VALUES, title=None):
    """The page csfview writes of the result's rows (a whole HTML document, a str); raises RuntimeError
    with the reason when there is none (no rows; csfview, or the packages it inlines, missing)."""
    rows, width = result.data.shape
    if rows == 0:
        raise RuntimeError("the run has no rows: nothing to show")
    k = stride(rows, width, max_rows, max_values)
    idx = shown(rows, k)
    try:
        prog = _lib.program("csfview")
    except FileNotFoundError as e:
        raise RuntimeError(str(e)) from None
    args = [prog, "-o", "-", "--title", title or _title(result),
            "--max-rows", str(max(2, len(idx) - 1))]
    if k > 1:
        args += ["--decimated", "%d,%d" % (rows, k)]
    if _note(result):
        args += ["--note", _note(result)]
    with tempfile.TemporaryDirectory(prefix="csf-view-") as tmp:
        model = result.model
        if model.path and os.path.isfile(model.path):
            args += ["--scene", os.fspath(model.path)]
        elif model.source is not None:
            scene = os.path.join(tmp, "scene.csf")
            with open(scene, "w", encoding="utf-8") as f:
                f.write(model.source)
            args += ["--scene", scene]
        if result.diagnostics:
            log = os.path.join(tmp, "log")
            with open(log, "w", encoding="utf-8") as f:
                f.write(result.diagnostics)
            args += ["--log", log]
        try:
            p = subprocess.run(args, input=_csv(result, idx), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               timeout=600)
        except (OSError, subprocess.SubprocessError) as e:
            raise RuntimeError("cannot run %s: %s" % (prog, e)) from None
    if p.returncode != 0:
        raise RuntimeError(p.stderr.decode("utf-8", "replace").strip() or "csfview failed (status %d)" % p.returncode)
    return p.stdout.decode("utf-8")


def _height(result, idx):
    """The page's height in pixels, laid out narrow (the view above the plots): the header, the 3-D
    view and its controls, a line per object, a panel per unit of the columns that change."""
    data = result.data[idx]
    units = {c.unit for j, c in enumerate(result.columns, 1) if (data[:, j] != data[0, j]).any()}
    objects = sum(1 for c in result.columns if c.component == 0 and c.vector.split(".")[-1] == "pos")
    return min(2400, 140 + 460 + 60 + 22 * (objects + 1) + 250 * len(units) + 40)


def fragment(result, max_rows=MAX_ROWS, max_values=MAX_VALUES, height=None, title=None):
    """An HTML fragment for a notebook: the page in an <iframe srcdoc>, or, for a run without rows or
    when csfview cannot draw it, the result's repr, the reason and its diagnostics as text."""
    try:
        doc = page(result, max_rows, max_values, title)
    except RuntimeError as e:
        parts = [repr(result), str(e)] + ([result.diagnostics.rstrip("\n")] if result.diagnostics else [])
        return '<div class="csf-result">%s</div>' % "".join(
            "<pre>%s</pre>" % html.escape(p, quote=True) for p in parts)
    if height is None:
        height = _height(result, shown(len(result), stride(*result.data.shape, max_rows, max_values)))
    return ('<iframe class="csf-result" title="%s" srcdoc="%s" sandbox="allow-scripts" '
            'style="width: 100%%; height: %dpx; border: 1px solid #ddd"></iframe>' %
            (html.escape(title or _title(result), quote=True), html.escape(doc, quote=True), int(height)))
