"""The result type shared by every method."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Curve", "Snapshot", "Result", "SolverStats", "ErrorBar", "QUANTITIES", "JSON_KEYS"]

#: the scalar outputs every method computes, and that error bars and checks refer to
QUANTITIES = ("pulloff_force", "pulloff_approach", "stiffness")

#: the keys every method fills in ``crossval solve --json``
JSON_KEYS = (
    "method",
    "pulloff_force",
    "pulloff_approach",
    "stiffness",
    "converged",
    "wall_time_s",
    "grid_spacing",
    "curve",
)


@dataclass(frozen=True, eq=False)
class Curve:
    """Force-approach curve: approach d, normal force F (< 0 tensile), contact area A."""

    approach: np.ndarray
    force: np.ndarray
    contact_area: np.ndarray

    def __post_init__(self):
        a = np.asarray(self.approach, float)
        f = np.asarray(self.force, float)
        c = np.asarray(self.contact_area, float)
        if not (a.shape == f.shape == c.shape and a.ndim == 1):
            raise ValueError("curve arrays must be 1-D and of equal length")
        object.__setattr__(self, "approach", a)
        object.__setattr__(self, "force", f)
        object.__setattr__(self, "contact_area", c)

    def __len__(self):
        return len(self.approach)


@dataclass(frozen=True, eq=False)
class Snapshot:
    """The contact set (and, when asked, fields) at one approach."""

    approach: float
    force: float
    contact: np.ndarray  # bool mask on the method's grid, [ix, iy]
    spacing: float
    origin: tuple[float, float]
    pressure: np.ndarray | None = None
    displacement: np.ndarray | None = None

    @property
    def contact_area(self) -> float:
        return float(np.count_nonzero(self.contact)) * self.spacing**2

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """Cell-centre coordinates X, Y on the snapshot's grid, indexed like ``contact``."""
        nx, ny = self.contact.shape
        return np.meshgrid(
            self.origin[0] + self.spacing * np.arange(nx), self.origin[1] + self.spacing * np.arange(ny), indexing="ij"
        )


@dataclass(frozen=True)
class SolverStats:
    """The work a solve did, in counters every method fills (0 where one does not apply).

    linear_solves
        Linear systems solved: contact-set solves (Griffith BEM), minimisations (energy BEM),
        factorisations (FEM).
    linear_iterations
        Their iterations: preconditioned CG steps, minimiser iterations.
    operator_applications
        Applications of the elastic operator: FFT convolutions, energy-and-gradient evaluations.
    events
        Steps of the loading path: detachment events (Griffith), continuation steps (energy).
    unconverged
        Sub-solves that stopped before their tolerance (each also says so in ``messages``).
    unknowns
        Size of the discrete problem: face elements (BEM) or degrees of freedom (FEM).
    """

    linear_solves: int = 0
    linear_iterations: int = 0
    operator_applications: int = 0
    events: int = 0
    unconverged: int = 0
    unknowns: int = 0

    def __post_init__(self):
        # not declared fields (contact_scene.validation): a bad count is a solver's bug, not bad
        # input, so it raises a plain ValueError rather than the SceneError the CLI reports as
        # a user's mistake
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise ValueError(f"SolverStats.{f.name} must be an integer >= 0 (got {v!r})")
            object.__setattr__(self, f.name, int(v))


@dataclass(frozen=True)
class ErrorBar:
    """A bound on a result's relative error, ``|value / exact - 1| <= relative``, from an error
    model that a convergence study showed to cover the method's error.

    source
        The study and the number the bar comes from (a reader can re-run it).
    role
        ``"validation"``: the quantity is an independent prediction; ``"calibration"``: the
        method was fitted to this quantity on this very scene, so matching it validates nothing.
    interval
        Where the method also brackets the exact value itself, ``(low, high)`` in the quantity's
        units (the energy BEM's zero-range limit: the two limits its last step allows); the
        exact value lies inside it, which is a sharper claim on one side than ``relative``.
    """

    relative: float
    source: str
    role: str = "validation"
    interval: tuple[float, float] | None = None

    def __post_init__(self):
        # a solver's error model builds this: a bad bar is a bug, not a user's input (see SolverStats)
        if not (isinstance(self.relative, (int, float)) and math.isfinite(self.relative) and self.relative >= 0):
            raise ValueError(f"ErrorBar.relative must be a finite number >= 0 (got {self.relative!r})")
        if self.role not in ("validation", "calibration"):
            raise ValueError(f"ErrorBar.role must be 'validation' or 'calibration' (got {self.role!r})")
        object.__setattr__(self, "relative", float(self.relative))
        if self.interval is not None:
            low, high = (float(x) for x in self.interval)
            if not (math.isfinite(low) and math.isfinite(high) and low <= high):
                raise ValueError(f"ErrorBar.interval must be finite (low, high), low <= high (got {self.interval!r})")
            object.__setattr__(self, "interval", (low, high))


@dataclass(frozen=True, eq=False)
class Result:
    """What every method returns.

    Besides the curve and the pull-off point: ``stats`` (typed work counters), ``error_bars``
    (per quantity of :data:`QUANTITIES`, the method's bounded relative error on this scene; a
    quantity without a bar is not claimed to any accuracy), ``face_area`` (the area of the face as
    discretised, e.g. a BEM grid's staircase; None when the face is exact), ``discretisation``
    (``"grid"``: one square-element grid; ``"mesh"``: a finite-element mesh; ``"extrapolated"``:
    a limit over several discretisations) and ``info`` (method-specific diagnostics, typed per
    method, for people and JSON; the harness does not read it).
    """

    method: str
    pulloff_force: float  # magnitude of the largest tensile force
    pulloff_approach: float  # approach at that force
    stiffness: float  # initial dF/dd of the pressed contact
    converged: bool
    grid_spacing: float  # element side, or characteristic mesh size
    curve: Curve | None = None
    detached: bool = True  # contact lost within the loading range
    detachment_approach: float | None = None
    snapshots: tuple[Snapshot, ...] = ()
    last_stable: Snapshot | None = None
    iterations: int = 0
    residual: float = 0.0
    timings: dict = field(default_factory=dict)
    accuracy_estimate: float | None = None
    messages: tuple[str, ...] = ()
    # a Mapping, so that each method's TypedDict of diagnostics (GriffithInfo, EnergyInfo...) fits
    info: Mapping[str, Any] = field(default_factory=dict)
    stats: SolverStats = field(default_factory=SolverStats)
    error_bars: dict = field(default_factory=dict)  # quantity -> ErrorBar
    face_area: float | None = None
    discretisation: str = "grid"

    def __post_init__(self):
        if self.discretisation not in ("grid", "mesh", "extrapolated"):
            raise ValueError(
                f"Result.discretisation must be 'grid', 'mesh' or 'extrapolated' (got {self.discretisation!r})"
            )
        for q, bar in self.error_bars.items():
            if q not in QUANTITIES or not isinstance(bar, ErrorBar):
                raise ValueError(f"Result.error_bars maps {', '.join(QUANTITIES)} to ErrorBar (got {q!r}: {bar!r})")
        if self.face_area is not None and not (math.isfinite(self.face_area) and self.face_area > 0):
            raise FloatingPointError(
                f"{self.method}: face_area is not a positive number ({self.face_area}); this is a solver bug"
            )
        for name in ("pulloff_force", "pulloff_approach", "stiffness", "grid_spacing", "residual"):
            v = getattr(self, name)
            if not math.isfinite(v):
                raise FloatingPointError(f"{self.method}: {name} is not finite ({v}); this is a solver bug")
        if self.curve is not None:
            for arr in (self.curve.approach, self.curve.force, self.curve.contact_area):
                if not np.all(np.isfinite(arr)):
                    raise FloatingPointError(f"{self.method}: the curve contains NaN or inf; this is a solver bug")

    @property
    def wall_time_s(self) -> float:
        return float(sum(self.timings.values()))

    def to_json(self) -> dict:
        """The fixed JSON keys of ``crossval solve`` (plus a few optional extras)."""
        out = {
            "method": self.method,
            "pulloff_force": self.pulloff_force,
            "pulloff_approach": self.pulloff_approach,
            "stiffness": self.stiffness,
            "converged": bool(self.converged),
            "wall_time_s": self.wall_time_s,
            "grid_spacing": self.grid_spacing,
            "curve": None
            if self.curve is None
            else {
                "approach": self.curve.approach.tolist(),
                "force": self.curve.force.tolist(),
                "contact_area": self.curve.contact_area.tolist(),
            },
            "detached": bool(self.detached),
            "detachment_approach": self.detachment_approach,
            "iterations": int(self.iterations),
            "residual": float(self.residual),
            "timings": {k: float(v) for k, v in self.timings.items()},
            "accuracy_estimate": self.accuracy_estimate,
            "messages": list(self.messages),
            "info": dict(self.info),
            "stats": dataclasses.asdict(self.stats),
            "error_bars": {q: dataclasses.asdict(b) for q, b in self.error_bars.items()},
            "face_area": self.face_area,
            "discretisation": self.discretisation,
        }
        return out
