"""Presentation shared by the gallery pictures: where they are written, and contact maps with
their lengths in the unit the neighbouring curves use.

``crossval.plotting.plot_contact`` draws in the scene's own length unit and titles a panel with
the bare approach; a picture that plots its curves in mm, or in face radii, needs its contact
maps in the same unit and a title saying which state is shown.

How a script runs when executed, by ``python examples/<name>.py`` or by the documentation
build (``docs/conf.py``), is set by the environment variable ``ADHESIVE_PUNCH_EXAMPLES``:
``full`` (the default for a script: the resolutions of the published pictures, minutes to
tens of minutes) or ``short`` (the versions the tests run, seconds: the documentation build's
default).  A full run writes its picture to ``ADHESIVE_PUNCH_PICTURES`` (default: the current
directory).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

#: grey levels of the paper's contact pictures: the initial face grey, the remaining contact black
FACE_GREY, CONTACT_BLACK = 0.35, 1.0

#: the ways a script can run (ADHESIVE_PUNCH_EXAMPLES)
RUNS = ("full", "short")


def run_mode() -> str:
    """``full`` or ``short``, from ``ADHESIVE_PUNCH_EXAMPLES`` (default ``full``)."""
    mode = os.environ.get("ADHESIVE_PUNCH_EXAMPLES", "full").strip().lower() or "full"
    if mode not in RUNS:
        raise ValueError(f"ADHESIVE_PUNCH_EXAMPLES must be one of {', '.join(RUNS)} (got {mode!r})")
    return mode


def short_run() -> bool:
    """Whether a script run should be the short version (the tests' resolutions)."""
    return run_mode() == "short"


def picture_path(name: str) -> Path:
    """<name>.png in ``ADHESIVE_PUNCH_PICTURES`` (default: the current directory), where a
    full run writes its picture."""
    return Path(os.environ.get("ADHESIVE_PUNCH_PICTURES", ".")) / f"{name}.png"


def contact_map(ax, snapshot, face=None, *, scale: float = 1.0, unit: str = "", title: str | None = None):
    """The contact of ``snapshot`` (black) on its face mask ``face`` (grey), lengths divided by
    ``scale`` and labelled ``x [unit]``; equal aspect, so shapes are not distorted."""
    img = np.zeros(snapshot.contact.shape)
    if face is not None:
        img[face] = FACE_GREY
    img[snapshot.contact] = CONTACT_BLACK
    nx, ny = img.shape
    h = snapshot.spacing / scale
    x0, y0 = (c / scale for c in snapshot.origin)
    ax.imshow(
        img.T,
        origin="lower",
        cmap="Greys",
        vmin=0,
        vmax=1,
        interpolation="nearest",
        extent=(x0 - h / 2, x0 + (nx - 0.5) * h, y0 - h / 2, y0 + (ny - 0.5) * h),
    )
    ax.set_aspect("equal")
    suffix = f" [{unit}]" if unit else ""
    ax.set_xlabel("x" + suffix)
    ax.set_ylabel("y" + suffix)
    if title is not None:
        ax.set_title(title, fontsize=9)
    return ax


def contact_handles(extra=()):
    """Legend entries for the grey/black code of the contact maps (plus ``extra`` handles)."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    cmap = plt.get_cmap("Greys")
    return [
        Patch(facecolor=cmap(FACE_GREY), edgecolor="0.5", lw=0.5, label="face, detached"),
        Patch(facecolor=cmap(CONTACT_BLACK), edgecolor="none", label="in contact"),
        *extra,
    ]


def contact_legend(ax, *, loc="upper right", extra=(), **kw):
    """A legend on ``ax`` for the grey/black code of the contact maps (plus ``extra`` handles)."""
    return ax.legend(handles=contact_handles(extra), loc=loc, fontsize=kw.pop("fontsize", 7), **kw)
