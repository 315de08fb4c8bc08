"""Plots of results; every function takes ``ax=None`` and returns the axes it drew on."""
from __future__ import annotations

import numpy as np

__all__ = ["plot_curve", "plot_contact", "plot_surface", "plot_error_vs_time", "plot_agreement"]


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


def plot_surface(snapshot, ax=None, *, stride: int = 1):
    """A 3-D view of the surface under a partially detached punch: the displacement -u
    (up = toward the punch) of a snapshot taken with fields (``Outputs(fields=True)``), contact
    cells dark.  ``ax`` must be a 3-D axes (``projection="3d"``) when given."""
    if snapshot.displacement is None:
        raise ValueError("the snapshot has no displacement field; ask for it with Outputs(fields=True)")
    if ax is None:
        import matplotlib.pyplot as plt

        ax = plt.figure().add_subplot(projection="3d")
    u = snapshot.displacement[::stride, ::stride]
    nx, ny = u.shape
    h = snapshot.spacing * stride
    x0, y0 = snapshot.origin
    X, Y = np.meshgrid(x0 + h * np.arange(nx), y0 + h * np.arange(ny), indexing="ij")
    colours = np.where(snapshot.contact[::stride, ::stride], 0.15, 0.75)
    from matplotlib import cm

    ax.plot_surface(X, Y, -u, facecolors=cm.Greys_r(colours), linewidth=0, antialiased=False, shade=True)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("-u (toward the punch)")
    ax.set_title(f"d = {snapshot.approach:.4g}")
    return ax


def plot_error_vs_time(study, ax=None):
    """One line per method: relative error of the studied quantity against wall time."""
    ax = _axes(ax)
    for m in dict.fromkeys(r.method for r in study.rows):
        rows = sorted((r for r in study.rows if r.method == m and r.error > 0), key=lambda r: r.wall_time_s)
        if rows:
            ax.loglog([r.wall_time_s for r in rows], [r.error for r in rows], "o-", label=m)
    from matplotlib.ticker import NullFormatter

    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel(f"relative error of {study.quantity}")
    ax.set_title(f"against {study.reference_name}", fontsize=8)
    ax.legend(fontsize=8)
    return ax


def plot_agreement(matrix, scenes, methods, ax=None):
    """Heat map of |relative difference| (log10) per scene and method; NaN ("-") where not run
    or where the method is its own reference."""
    ax = _axes(ax)
    m = np.log10(np.maximum(np.asarray(matrix, float), 1e-8))
    im = ax.imshow(m, cmap="viridis_r", vmin=-6, vmax=0, aspect="auto")
    ax.set_xticks(range(len(methods)), methods, rotation=30, ha="right", fontsize=8)
    ax.set_yticks(range(len(scenes)), scenes, fontsize=8)
    for i in range(len(scenes)):
        for j in range(len(methods)):
            v = matrix[i][j]
            ax.text(j, i, "-" if not np.isfinite(v) else f"{v:.1e}", ha="center", va="center", fontsize=7,
                    color="k" if np.isfinite(v) and v < 1e-3 else "w")
    ax.figure.colorbar(im, ax=ax, label="log10 |F_A / reference - 1|")
    return ax
