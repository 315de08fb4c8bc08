"""Plots of results; every function takes ``ax=None`` and returns the axes it drew on."""
from __future__ import annotations

import numpy as np

__all__ = ["plot_curve", "plot_contact"]


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def plot_curve(result, ax=None, *, normalise: tuple[float, float] | None = None, **kw):
    """Force against approach; ``normalise=(d_ref, F_ref)`` divides both (e.g. by Eqs. 13-14)."""
    ax = _axes(ax)
    d, F = result.curve.approach, result.curve.force
    if normalise is not None:
        d, F = d / abs(normalise[0]), F / abs(normalise[1])
    ax.plot(d, F, label=kw.pop("label", result.method), **kw)
    ax.set_xlabel("approach d" + (" / |d_ref|" if normalise else ""))
    ax.set_ylabel("force F" + (" / F_ref" if normalise else ""))
    return ax


def plot_contact(snapshot, ax=None, *, face=None):
    """The contact set like the paper draws it: face grey, remaining contact black."""
    ax = _axes(ax)
    img = np.zeros(snapshot.contact.shape)
    if face is not None:
        img[face] = 0.35
    img[snapshot.contact] = 1.0
    nx, ny = img.shape
    h = snapshot.spacing
    x0, y0 = snapshot.origin
    ax.imshow(img.T, origin="lower", cmap="Greys", vmin=0, vmax=1,
              extent=(x0 - h / 2, x0 + (nx - 0.5) * h, y0 - h / 2, y0 + (ny - 0.5) * h))
    ax.set_aspect("equal")
    ax.set_title(f"d = {snapshot.approach:.4g}")
    return ax
