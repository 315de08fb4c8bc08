"""Regression references: versioned JSON of results with tolerances, stored in the package.

For people who use this package as the reference in their own regression tests, and for
ours: a change that moves a stored number beyond its tolerance is reported, never silent.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .cache import package_version
from .methods import METHODS, applicable_methods
from .runner import Job, run_jobs
from .suite import SUITE

__all__ = ["REFERENCE_FILE", "CASES", "MISSING", "STALE", "regress", "regression_jobs", "Mismatch"]

REFERENCE_FILE = Path(__file__).with_name("references") / "suite.json"
FORMAT = 1
QUANTITIES = ("pulloff_force", "pulloff_approach", "stiffness")
#: one quick run per method and suite scene (BEM: 16 elements per radius; energy BEM: one
#: element per process zone; FEM: grading 2)
CASES = {m.name: m.sweeps.regression for m in METHODS.values()}
#: the same code reproduces its numbers to round-off; 1e-7 leaves room for other BLAS/FFT builds
#: in the direct solvers.  The energy BEM's minimisers stop at a gradient tolerance, so a change
#: of round-off alone (its transforms' rounding) moves its values by up to 2e-7 (measured over
#: the suite); its cases carry 1e-6.  So do the FEM's: its pull-off force and approach come from
#: a finite difference of energies, whose rounding moves them by up to about 2e-7 between
#: machines whose linear-algebra kernels round differently (the stiffness by about 1e-10)
RTOL = 1e-7
RTOL_BY_METHOD = {"bem_energy": 1e-6, "fem_reference": 1e-6}


@dataclass(frozen=True)
class Mismatch:
    """A stored number that the current code no longer reproduces within its tolerance.

    Attributes
    ----------
    scene : str
        The suite scene's name.
    method : str
        The method's name.
    quantity : str
        ``"pulloff_force"``, ``"pulloff_approach"`` or ``"stiffness"``; for a case the file does
        not hold, :data:`MISSING`, and for a case the file holds that is no longer computed (the
        suite lost it), :data:`STALE` (both with NaN values and a zero tolerance).
    stored : float
        The value in the reference file.
    now : float
        The value the current code computes.
    rtol : float
        The relative tolerance stored with the case.
    """

    scene: str
    method: str
    quantity: str
    stored: float
    now: float
    rtol: float

    def explain(self) -> str:
        """One line: the case, both values, their relative change and the tolerance.

        Returns
        -------
        str
            "scene/method: quantity = now, stored value (relative change, tolerance)".
        """
        if self.quantity == MISSING:
            return f"{self.scene}/{self.method}: computed, but not in the reference file (run with --update to add it)"
        if self.quantity == STALE:
            return (
                f"{self.scene}/{self.method}: in the reference file, but no longer computed (the suite lost the "
                "case; run with --update to drop it)"
            )
        return (
            f"{self.scene}/{self.method}: {self.quantity} = {self.now:.10g}, stored {self.stored:.10g} "
            f"({self.now / self.stored - 1:+.2e}, tolerance {self.rtol:.0e})"
        )


#: the quantity of a :class:`Mismatch` for a case the reference file does not hold
MISSING = "(missing from the reference file)"
#: the quantity of a :class:`Mismatch` for a stored case the suite no longer computes
STALE = "(no longer computed)"


def regression_jobs() -> list[Job]:
    """The regression cases: every suite scene (:data:`crossval.SUITE`) through each method
    that applies to it, at the method's regression resolution (:data:`CASES`).

    Returns
    -------
    list of crossval.runner.Job
        One job per case.
    """
    return [Job(SUITE[s], m.name, CASES[m.name]) for s in SUITE for m in applicable_methods(SUITE[s])]


def regress(*, update: bool = False, path: Path | None = None, workers: int = 1, callback=None) -> list[Mismatch]:
    """Recompute the cases and compare them with ``path`` (or rewrite it with ``update``).

    The cases are every suite scene (:data:`crossval.SUITE`) through each method that applies to
    it, at the method's regression resolution (:data:`CASES`).  They are always recomputed (no
    disk cache), so that a stored result cannot hide a change.

    Parameters
    ----------
    update : bool, optional
        Rewrite ``path`` with the current values, the package version and a relative tolerance
        per case (:data:`RTOL`, or the method's in :data:`RTOL_BY_METHOD`) instead of
        comparing (the file is replaced whole, so an interrupted run
        leaves the previous one).
    path : pathlib.Path, optional
        The reference file; None (default) for the one stored in the package
        (:data:`REFERENCE_FILE`).
    workers : int, optional
        Local processes; more than one runs the solves in a process pool.
    callback : callable, optional
        ``callback(job, result)`` after each solve (progress).

    Returns
    -------
    list of Mismatch
        Each quantity (pull-off force, approach at pull-off, stiffness) that differs from the
        stored value by more than the stored relative tolerance (a NaN on either side is a
        mismatch), each case the file does not hold and each it holds that is no longer
        computed; empty when everything matches, and always empty with ``update``.

    Raises
    ------
    ValueError
        If the file is in another format than this version reads.
    FileNotFoundError
        If ``path`` does not exist (without ``update``).
    """
    path = REFERENCE_FILE if path is None else Path(path)
    jobs = regression_jobs()
    results = run_jobs(jobs, workers=workers, callback=callback)
    current: list[dict[str, Any]] = [
        {
            "scene": j.scene.name,
            "method": j.method,
            "resolution": j.resolution,
            "values": {q: getattr(r, q) for q in QUANTITIES},
            "rtol": RTOL_BY_METHOD.get(j.method, RTOL),
        }
        for j, r in zip(jobs, results, strict=True)
    ]
    if update:
        data = {"format": FORMAT, "package_version": package_version(), "cases": current}
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "w") as f:
            json.dump(data, f, indent=1)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
        return []
    stored = json.loads(Path(path).read_text())
    if stored.get("format") != FORMAT:
        raise ValueError(f"{path}: reference format {stored.get('format')!r}, expected {FORMAT}")
    index = {(c["scene"], c["method"], c["resolution"]): c for c in stored["cases"]}
    computed = {(c["scene"], c["method"], c["resolution"]) for c in current}
    out = [
        Mismatch(scene, method, STALE, float("nan"), float("nan"), 0)
        for scene, method, resolution in index
        if (scene, method, resolution) not in computed
    ]
    for c in current:
        ref = index.get((c["scene"], c["method"], c["resolution"]))
        if ref is None:
            out.append(Mismatch(c["scene"], c["method"], MISSING, float("nan"), float("nan"), 0))
            continue
        for q in QUANTITIES:
            a, b = ref["values"][q], c["values"][q]
            if not abs(b - a) <= ref["rtol"] * abs(a):
                out.append(Mismatch(c["scene"], c["method"], q, a, b, ref["rtol"]))
    return out
