"""Plots of results; every function takes ``ax=None`` and returns the axes it drew on."""

from __future__ import annotations

import numpy as np

__all__ = [
    "plot_curve",
    "plot_contact",
    "plot_surface",
    "plot_error_vs_time",
    "plot_agreement",
    "resolution_unit",
    "METHOD_COLOURS",
]

#: one colour per method, the same in every figure
METHOD_COLOURS = {"bem_griffith": "C0", "bem_energy": "C1", "fem_reference": "C2"}


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
    ax.imshow(
        img.T,
        origin="lower",
        cmap="Greys",
        vmin=0,
        vmax=1,
        extent=(x0 - h / 2, x0 + (nx - 0.5) * h, y0 - h / 2, y0 + (ny - 0.5) * h),
    )
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


def _decade_limits(values):
    """Log-axis limits on whole decades around ``values``, at least one decade apart, so that
    the axis always carries at least two labelled major ticks."""
    v = np.asarray([x for x in values if np.isfinite(x) and x > 0], float)
    if len(v) == 0:
        return 1e-3, 1.0
    # a margin, so that no marker sits on the axis and is cut in half
    lo, hi = np.floor(np.log10(v.min() / 1.5)), np.ceil(np.log10(v.max() * 1.5))
    if hi <= lo:
        hi = lo + 1
    return 10.0**lo, 10.0**hi


def resolution_unit(study, method) -> str:
    """What ``method``'s resolution counts on the study's scene, as the error panel's legend
    names the numbers written beside its runs (e.g. ``"elements/radius"``).

    Parameters
    ----------
    study : crossval.study.Study
        The study whose scene decides the meaning (the energy BEM's differs between a
        zero-range sequence and a finite range).
    method : str
        A key of :data:`crossval.METHODS`.

    Returns
    -------
    str
        The method's own measure, without the generic "N" the methods' axis labels share.
    """
    from .methods import METHODS

    return METHODS[method].resolution(study.scene).label.removeprefix("N:").strip()


#: the smallest wall time the panel places a run at: a log axis has no zero, and a run that
#: recorded none (an edited or foreign cache entry) must still be drawn
_MIN_TIME_S = 1e-3


def plot_error_vs_time(study, ax=None, *, notes=None):
    """One line per method: the relative error of the studied quantity against each run's
    wall time, the run's resolution written beside it in the method's own measure (named in
    the legend).

    Every panel has the same axis, wall time, because resolutions are not comparable across
    methods (elements per radius, elements per process zone, 1/grading): a shared resolution
    axis would place runs side by side whose numbers mean different things.  Where timings
    are noise the panel says so instead of changing axis: runs shorter than
    ``study.TIME_NOISE_FLOOR_S`` sit in a hatched band, and a method whose time does not grow
    with its resolution says so in its legend entry.

    The error is against ``study.reference_info``; its error bar is drawn as a grey band
    (errors inside it are not resolved and are drawn hollow).  The axis is the error's
    magnitude; a marker points up for a run above the reference and down for one below it, so
    that a sign change (a dip through zero) shows.  ``notes`` ({method: text}) adds a word to a
    method's legend entry, e.g. that its errors are calibration residuals.  Without a reference
    the panel says so instead of plotting.

    Parameters
    ----------
    study : crossval.study.Study
        The rows to plot and the reference they are measured against.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on; a new figure's by default.
    notes : dict, optional
        Method -> text appended to its legend entry.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    import textwrap

    from matplotlib.lines import Line2D
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter, NullLocator

    from .study import TIME_NOISE_FLOOR_S

    ax = _axes(ax)
    ref = study.reference_info
    unc = ref.uncertainty if ref is not None else 0.0
    ref_name = ref.name if ref is not None else study.reference_name
    rows = [r for r in study.rows if np.isfinite(r.error)]
    ax.set_title("\n".join(textwrap.wrap(f"error against {ref_name}", 48)), fontsize=8)
    if not rows or (ref is not None and ref.kind == "none") or all(r.error <= unc for r in rows):
        why = (
            ref_name
            if ref is None or ref.kind == "none"
            else f"every error lies within the reference's error bar (+-{unc:.1e})"
        )
        ax.text(
            0.5,
            0.5,
            "\n".join(textwrap.wrap(f"no trustworthy reference: {why}", 40)),
            ha="center",
            va="center",
            transform=ax.transAxes,
            fontsize=8,
        )
        ax.xaxis.set_major_locator(NullLocator())
        ax.yaxis.set_major_locator(NullLocator())
        return ax
    by_method = {
        m: sorted((r for r in rows if r.method == m), key=lambda r: r.resolution)
        for m in dict.fromkeys(r.method for r in rows)
    }

    def when(r):
        t = r.wall_time_s
        return max(t, _MIN_TIME_S) if np.isfinite(t) else _MIN_TIME_S

    for m, mr in by_method.items():
        x = [when(r) for r in mr]
        e = [max(r.error, 1e-12) for r in mr]
        label = f"{m}; beside each run: {resolution_unit(study, m)}"
        if len(mr) > 1 and np.any(np.diff([r.wall_time_s for r in mr]) <= 0):
            label += "; its time does not grow with resolution (noise)"
        if notes and notes.get(m):
            label += f"; {notes[m]}"
        # wrapped: the legend sits beside the panel and would squeeze the figure's other panels
        label = textwrap.fill(label, 40, subsequent_indent="  ")
        # the line joins a method's runs in order of resolution, so a time that falls as the
        # resolution grows shows as the line turning back
        (line,) = ax.plot(x, e, "-", lw=1, label=label, color=METHOD_COLOURS.get(m))
        for i, (xi, r, ei) in enumerate(zip(x, mr, e, strict=True)):
            # the axis is the magnitude: the marker says on which side of the reference the run lies
            marker = "v" if r.signed_error < 0 else "^"
            ax.plot(xi, ei, marker, color=line.get_color(), ms=5, mfc=line.get_color() if r.error > unc else "white")
            # above and below the marker in turn, so that neighbours' labels do not overprint
            ax.annotate(
                f"{r.resolution:.3g}",
                (xi, ei),
                textcoords="offset points",
                xytext=(4, 3) if i % 2 == 0 else (4, -9),
                fontsize=7,
                color=line.get_color(),
            )
    ax.set_xscale("log")
    ax.set_yscale("log")
    lo, hi = _decade_limits([r.error for r in rows] + ([unc] if unc > 0 else []))
    ax.set_ylim(lo, hi)
    if unc > 0:
        ax.axhspan(lo, unc, color="0.85", zorder=0, label=f"reference error bar (+-{unc:.1e})")
    ax.yaxis.set_major_locator(LogLocator(base=10))
    ax.yaxis.set_minor_locator(LogLocator(base=10, subs=(2, 5)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    # with a single decade the 2 and 5 ticks carry the scale too
    ax.yaxis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}") if hi / lo <= 10 else NullFormatter())
    ts = sorted(when(r) for r in rows)
    # room on the right for the last run's label
    x0, x1 = ts[0] / 1.25, ts[-1] * 1.6
    ax.set_xlim(x0, x1)
    if ts[0] < TIME_NOISE_FLOOR_S:
        ax.axvspan(
            x0,
            min(TIME_NOISE_FLOOR_S, x1),
            facecolor="none",
            edgecolor="0.85",
            hatch="///",
            lw=0,
            zorder=0,
            label=f"under {TIME_NOISE_FLOOR_S:g} s: timings are noise",
        )
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_locator(LogLocator(base=10, subs=(2, 5)))
    # with fewer than two powers of ten in view the 2 and 5 ticks carry the scale too
    decades = np.floor(np.log10(x1)) - np.ceil(np.log10(x0)) + 1
    ax.xaxis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}") if decades < 2 else NullFormatter())
    ax.set_xlabel("wall time of the run [s]; beside each run: its resolution, in its method's own measure", fontsize=8)
    ax.set_ylabel(f"relative error of {study.quantity}")
    handles, _ = ax.get_legend_handles_labels()
    handles += [
        Line2D([], [], ls="none", marker=m, color="0.3", ms=5, label=f"{side} the reference")
        for m, side in (("^", "above"), ("v", "below"))
    ]
    if unc > 0 and any(r.error <= unc for r in rows):
        handles.append(
            Line2D([], [], ls="none", marker="^", color="0.3", mfc="white", ms=5, label="hollow: inside its error bar")
        )
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return ax


#: what a blank cell of the agreement map means, written into the cell
BLANK_REASONS = {
    "n/a": "method does not apply",
    "is ref.": "the method is the reference",
    "no ref.": "no trustworthy reference",
}


def plot_agreement(matrix, scenes, methods, ax=None, *, notes=None):
    """Heat map of |relative difference| (log10) per scene and method.  A cell without a value
    is hatched and carries its reason (``notes[i][j]``, e.g. a key of ``BLANK_REASONS``);
    ``notes`` may also annotate cells with a value (e.g. "calib.")."""
    from matplotlib.patches import Rectangle

    ax = _axes(ax)
    arr = np.asarray(matrix, float)
    m = np.log10(np.maximum(arr, 1e-8))
    im = ax.imshow(np.ma.masked_invalid(m), cmap="viridis_r", vmin=-6, vmax=0, aspect="auto")
    ax.set_xticks(range(len(methods)), methods, rotation=30, ha="right", fontsize=8)
    ax.set_yticks(range(len(scenes)), scenes, fontsize=8)
    for i in range(len(scenes)):
        for j in range(len(methods)):
            v = arr[i, j]
            note = notes[i][j] if notes is not None else ""
            if not np.isfinite(v):
                ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="white", edgecolor="0.6", hatch="///", lw=0))
                ax.text(
                    j,
                    i,
                    note or "-",
                    ha="center",
                    va="center",
                    fontsize=7,
                    color="k",
                    bbox=dict(facecolor="white", edgecolor="none", pad=1),
                )
            else:
                text = f"{v:.1e}" + (f"\n{note}" if note else "")
                ax.text(j, i, text, ha="center", va="center", fontsize=6 if note else 7, color="k" if v < 1e-3 else "w")
    ax.figure.colorbar(im, ax=ax, label="log10 |F_A / reference - 1|")
    return ax
