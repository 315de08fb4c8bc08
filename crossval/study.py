"""Error against resolution and against run time, with fitted convergence rates."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import contact_scene as cs

from .compare import reference_values
from .methods import applicable_methods
from .runner import Job, run_jobs

__all__ = ["StudyRow", "Study", "study", "DEFAULT_RESOLUTIONS"]

#: per method, the resolutions a study sweeps unless told otherwise (BEM: elements per
#: radius; FEM: 1/grading)
DEFAULT_RESOLUTIONS = {"bem_griffith": (8, 12, 16, 24, 32), "bem_energy": (1.0, 2.0, 3.0),
                       "fem_reference": (0.5, 2 / 3, 1.0)}

# the most accurate method first: the finest run of the first applicable one is the
# reference where the scene has no closed form
_ACCURACY_ORDER = ("fem_reference", "bem_griffith", "bem_energy")


@dataclass(frozen=True)
class StudyRow:
    method: str
    resolution: float
    wall_time_s: float
    value: float
    error: float            # relative, against the reference


@dataclass(frozen=True, eq=False)
class Study:
    scene: cs.Scene
    quantity: str
    reference: float
    reference_name: str
    rows: tuple[StudyRow, ...]
    rates: dict = field(default_factory=dict)          # method -> fitted order in resolution
    time_rates: dict = field(default_factory=dict)     # method -> fitted exponent of error vs time
    results: dict = field(default_factory=dict)        # (method, resolution) -> Result


def _fit(x, y):
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x > 0) & (y > 0)
    if ok.sum() < 2:
        return float("nan")
    return float(-np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def study(scene: cs.Scene, *, methods=None, resolutions: dict | None = None, quantity: str = "pulloff_force",
          workers: int = 1, scheduler=None, cache=None, callback=None) -> Study:
    """Run each method over its resolutions; measure the error of ``quantity`` against the
    closed form where one exists, else against the finest run of the most accurate method."""
    names = [m.name for m in applicable_methods(scene)] if methods is None else list(methods)
    res = {m: tuple((resolutions or {}).get(m, DEFAULT_RESOLUTIONS[m])) for m in names}
    jobs = [Job(scene, m, r) for m in names for r in res[m]]
    results = run_jobs(jobs, workers=workers, scheduler=scheduler, cache=cache, callback=callback)
    by = {(j.method, j.resolution): r for j, r in zip(jobs, results)}
    theory = reference_values(scene)
    if quantity in theory:
        ref, ref_name = theory[quantity], theory["source"]
    else:
        best = next(m for m in _ACCURACY_ORDER if m in names)
        finest = max(res[best])
        ref, ref_name = getattr(by[(best, finest)], quantity), f"{best} at resolution {finest:g}"
    rows = []
    for (m, r), result in by.items():
        v = getattr(result, quantity)
        rows.append(StudyRow(m, r, result.wall_time_s, v, abs(v / ref - 1) if ref else math.inf))
    rates, trates = {}, {}
    for m in names:
        mr = [row for row in rows if row.method == m and not (row.error == 0 and ref_name.startswith(m))]
        rates[m] = _fit([row.resolution for row in mr], [row.error for row in mr])
        trates[m] = _fit([row.wall_time_s for row in mr], [row.error for row in mr])
    return Study(scene, quantity, ref, ref_name, tuple(rows), rates, trates, by)
