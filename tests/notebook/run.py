"""tests/notebook/run.py NOTEBOOK.ipynb SECONDS - runs a notebook of examples/ through nbclient, as
Jupyter would (a python3 kernel, in the notebook's directory; tests/run.sh, job notebook, puts the
build's package on PYTHONPATH). Fails when the notebook as committed has outputs (it is a source
file), when a cell raises (the notebook's asserts compare with closed forms), when a cell takes more
than SECONDS, or when a cell that is a csf.Result does not show csfview's page inline.
Prints one line per failure and exits 1; 0 and one line of what ran otherwise."""
import os
import sys

import nbclient
import nbformat


def main(path, seconds):
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    fail = []
    for i, c in enumerate(nb.cells):
        if c.cell_type == "code" and (c.outputs or c.execution_count is not None):
            fail.append("%s: cell %d (%s) has outputs: a notebook is committed without them" % (path, i, c.get("id")))
    client = nbclient.NotebookClient(nb, timeout=seconds, kernel_name="python3",
                                     resources={"metadata": {"path": os.path.dirname(os.path.abspath(path))}})
    try:
        client.execute()
    except nbclient.exceptions.CellExecutionError as e:
        fail.append("%s: %s" % (path, str(e).strip().splitlines()[-1]))
    except nbclient.exceptions.CellTimeoutError as e:
        fail.append("%s: a cell ran more than %d s: %s" % (path, seconds, str(e).splitlines()[0]))
    views = 0
    for c in nb.cells:
        if c.cell_type != "code" or c.source.strip() != "r":
            continue
        html = [o["data"].get("text/html", "") for o in c.outputs if o.get("output_type") == "execute_result"]
        if len(html) == 1 and html[0].startswith('<iframe class="csf-result" ') and "var CSF_META" in html[0]:
            views += 1
        else:
            fail.append("%s: cell %s: not csfview's page inline: %.200r" % (path, c.get("id"), html))
    if not views and not fail:
        fail.append("%s: no cell shows a result (a cell that is just r)" % path)
    for f in fail:
        print("FAIL: notebook: " + f)
    if not fail:
        print("%s: %d cells ran, %d page inline" % (path, len(nb.cells), views))
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], int(sys.argv[2])))
