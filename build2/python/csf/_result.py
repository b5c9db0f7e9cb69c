"""A run's rows as numpy arrays, indexed by column, vector and property name (csf-python(7), Result)."""
from typing import NamedTuple

import numpy as np


class Stats(NamedTuple):
    """csfvm --stats's figures: integrator steps, right-hand side evaluations, the run's seconds."""
    steps: int
    rhs: int
    seconds: float


class _Index:
    """Where each name's values are in a run's table (t in column 0, then the model's columns):
    a column (`ball.pos.x`), a vector (`ball.pos`: 3 columns) or a property of several objects
    (`pos`: a vector of each object that has one; `m`, `pos.x`: a scalar), with their units."""

    def __init__(self, columns):
        self.col = {"t": 0}
        self.vec = {}
        self.units = {"t": "s"}
        props = {}
        for i, c in enumerate(columns):
            j = i + 1
            self.col[c.name] = j
            self.units[c.name] = c.unit
            if c.component == 0:
                self.vec[c.vector] = j
                self.units[c.vector] = c.unit
        for table, width in ((self.col, 1), (self.vec, 3)):
            for name, j in table.items():
                obj, dot, prop = name.partition(".")
                if dot:
                    props.setdefault(prop, []).append((obj, j, width))
        self.prop = {}
        for prop, owners in props.items():
            if prop in self.col or prop in self.vec or len({w for _, _, w in owners}) != 1:
                continue  # a column's own name wins; a property that is a vector here and a scalar there is ambiguous
            self.prop[prop] = owners
            units = {self.units[o + "." + prop] for o, _, _ in owners}
            if len(units) == 1:
                self.units[prop] = units.pop()

    def keys(self):
        return list(self.col) + list(self.vec) + list(self.prop)

    def get(self, data, key):
        j = self.col.get(key)
        if j is not None:
            return data[:, j]
        j = self.vec.get(key)
        if j is not None:
            return data[:, j:j + 3]
        owners = self.prop.get(key)
        if owners is None:
            raise KeyError(key)
        w, n = owners[0][2], len(owners)
        starts = [j for _, j, _ in owners]
        if w == 1:
            step = starts[1] - starts[0] if n > 1 else 1
            if step > 0 and starts == list(range(starts[0], starts[0] + step * n, step)):
                return data[:, starts[0]:starts[0] + step * (n - 1) + 1:step]
            return data[:, starts]
        if starts == list(range(starts[0], starts[0] + 3 * n, 3)):  # one after the other: a view
            return data[:, starts[0]:starts[0] + 3 * n].reshape(data.shape[0], n, 3)
        idx = [j + k for j in starts for k in range(3)]
        return data[:, idx].reshape(data.shape[0], n, 3)


class Result:
    """A run's rows: .data (rows x (1 + columns): t, then the columns, the doubles csfvm's CSV prints),
    .t, r["ball.pos"], r["pos"], .units, .stats, .diagnostics, .status, to_pandas()."""

    def __init__(self, model, data, diagnostics, stats, status):
        self.model = model
        self.data = data
        self.diagnostics = diagnostics
        self.stats = stats
        self.status = status
        self.stopped = False  # ended early by a progress callback
        if model._index is None:
            model._index = _Index(model.columns)
        self._index = model._index

    @property
    def t(self):
        return self.data[:, 0]

    @property
    def columns(self):
        return self.model.columns

    @property
    def units(self):
        """The unit of every name r[...] takes ("" when none; t: "s")."""
        return dict(self._index.units)

    def __getitem__(self, key):
        return self._index.get(self.data, key)

    def __contains__(self, key):
        return key in self._index.col or key in self._index.vec or key in self._index.prop

    def keys(self):
        """Every name r[...] takes: t and the columns, the vectors, the properties of several objects."""
        return self._index.keys()

    def objects(self, key):
        """The objects, in order, whose values r[key] gives for a property (`pos`), one per row of its
        second axis."""
        return [o for o, _, _ in self._index.prop[key]]

    def __len__(self):
        return self.data.shape[0]

    def __repr__(self):
        return "<csf.Result: %d rows, t = %s .. %s, %d columns%s>" % (
            len(self), self.t[0] if len(self) else "-", self.t[-1] if len(self) else "-", len(self.columns),
            "" if self.status == 0 else ", status %d" % self.status)

    def to_pandas(self):
        """A DataFrame: t and the columns (the header's names without units), the units in
        df.attrs["units"]."""
        import pandas as pd
        names = ["t"] + [c.name for c in self.columns]
        df = pd.DataFrame(self.data, columns=names, copy=False)
        df.attrs["units"] = {n: self._index.units[n] for n in names}
        return df

    def _column_names(self, key):
        """The columns of a name r[...] takes: a column, a vector's three, a property's of each object."""
        if key in self._index.col:
            return [key]
        if key in self._index.vec:
            return [key + "." + x for x in "xyz"]
        if key in self._index.prop:
            return [n for o in self.objects(key) for n in self._column_names(o + "." + key)]
        raise KeyError(key)

    def plot(self, names=None, ax=None):
        """The watched columns (or names: columns, vectors, properties) against t with matplotlib, a line
        per column, one panel per unit with the unit on its axis; returns the figure."""
        import matplotlib.pyplot as plt
        cols = ([c.name for c in self.columns] if names is None else
                [n for key in names for n in self._column_names(key)])
        units = []
        for n in cols:
            if self._index.units.get(n, "") not in units:
                units.append(self._index.units.get(n, ""))
        if ax is None:
            fig, axes = plt.subplots(len(units), 1, sharex=True, squeeze=False, figsize=(7, 2.2 * len(units) + 0.6))
            axes = axes[:, 0]
        else:
            axes, fig = [ax] * len(units), ax.figure
        for a, u in zip(axes, units):
            for n in cols:
                if self._index.units.get(n, "") == u:
                    a.plot(self.t, self[n], label=n)
            a.set_ylabel("[%s]" % u if u else "")
            a.legend(loc="best", fontsize="small")
        axes[-1].set_xlabel("t [s]")
        return fig

    def page(self, max_rows=10000, max_values=200000, title=None):
        """csfview's page of the run (a whole HTML document: the 3-D animation and the plots, the rows
        and the JavaScript inside it), of every k-th row and the last when the run has more than
        max_rows intervals or max_values numbers (the page says so). RuntimeError with csfview's
        message when it cannot (a run without rows, csfview or libjs-three missing)."""
        from ._view import page
        return page(self, max_rows, max_values, title)

    def html(self, max_rows=10000, max_values=200000, height=None, title=None):
        """page() as an HTML fragment for a notebook, an <iframe srcdoc=...> of its own; a run without
        rows, or one csfview cannot draw, as its repr, the reason and its diagnostics."""
        from ._view import fragment
        return fragment(self, max_rows, max_values, height, title)

    def _repr_html_(self):
        """Jupyter's display of a result: html()."""
        return self.html()

    def to_dict(self):
        """{name: 1-D array} of t and every column."""
        return {n: self.data[:, j] for n, j in self._index.col.items()}
