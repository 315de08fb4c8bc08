"""The result type shared by every method."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Curve", "Snapshot", "Result", "JSON_KEYS"]

#: the keys every method fills in ``crossval solve --json``
JSON_KEYS = ("method", "pulloff_force", "pulloff_approach", "stiffness", "converged",
             "wall_time_s", "grid_spacing", "curve")


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
    contact: np.ndarray              # bool mask on the method's grid, [ix, iy]
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
        return np.meshgrid(self.origin[0] + self.spacing * np.arange(nx),
                           self.origin[1] + self.spacing * np.arange(ny), indexing="ij")


@dataclass(frozen=True, eq=False)
class Result:
    method: str
    pulloff_force: float                 # magnitude of the largest tensile force
    pulloff_approach: float              # approach at that force
    stiffness: float                     # initial dF/dd of the pressed contact
    converged: bool
    grid_spacing: float                  # element side, or characteristic mesh size
    curve: Curve | None = None
    detached: bool = True                # contact lost within the loading range
    detachment_approach: float | None = None
    snapshots: tuple[Snapshot, ...] = ()
    last_stable: Snapshot | None = None
    iterations: int = 0
    residual: float = 0.0
    timings: dict = field(default_factory=dict)
    accuracy_estimate: float | None = None
    messages: tuple[str, ...] = ()
    info: dict = field(default_factory=dict)

    def __post_init__(self):
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
            "curve": None if self.curve is None else {
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
        }
        return out
