"""The result type shared by every method."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from .scene import Scene

__all__ = [
    "Curve",
    "Snapshot",
    "Result",
    "SolverStats",
    "ErrorBar",
    "QUANTITIES",
    "JSON_KEYS",
    "unrecorded_snapshots",
    "zero_range_note",
]

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
    """Force-approach curve: approach d, normal force F (< 0 tensile), contact area A.

    The three arrays are 1-D, of equal length, in the order of the loading path, and stored as
    float arrays; arrays of other shapes raise ValueError.

    Attributes
    ----------
    approach : numpy.ndarray
        The approach d of the punch at each point (a length; < 0 when pulled).
    force : numpy.ndarray
        The normal force F there (< 0 tensile).
    contact_area : numpy.ndarray
        The area in contact there.
    """

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
    """The contact set (and, when asked, fields) at one approach.

    Attributes
    ----------
    approach : float
        The approach d of the punch.
    force : float
        The normal force F there (< 0 tensile).
    contact : numpy.ndarray
        Boolean mask of the elements in contact, on the method's grid, indexed [ix, iy].
    spacing : float
        The element side Delta of that grid.
    origin : tuple of float
        (x, y) of the centre of element [0, 0].
    pressure : numpy.ndarray or None
        The pressure (compressive > 0) on the same grid as ``contact``, when the scene asks for
        fields (``Outputs.fields``); None otherwise.
    displacement : numpy.ndarray or None
        The surface displacement u (along the approach: u = d - h in contact) on the same grid,
        when the scene asks for fields; None otherwise.
    """

    approach: float
    force: float
    contact: np.ndarray
    spacing: float
    origin: tuple[float, float]
    pressure: np.ndarray | None = None
    displacement: np.ndarray | None = None

    @property
    def contact_area(self) -> float:
        """The area in contact: the elements in contact times Delta^2."""
        return float(np.count_nonzero(self.contact)) * self.spacing**2

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """Cell-centre coordinates X, Y on the snapshot's grid, indexed like ``contact``.

        Returns
        -------
        X, Y : numpy.ndarray
            The x and y of each element's centre, of the shape of ``contact``.
        """
        nx, ny = self.contact.shape
        return np.meshgrid(
            self.origin[0] + self.spacing * np.arange(nx), self.origin[1] + self.spacing * np.arange(ny), indexing="ij"
        )

    def to_json(self) -> dict:
        """The snapshot in plain JSON types: its scalars, and its contact map run-length encoded.

        Returns
        -------
        dict
            ``approach``, ``force``, ``contact_area`` and ``spacing`` (floats), ``origin``
            ([x, y]); ``contact``, the mask in the run-length encoding of
            :meth:`decode_contact` (exact, and short for a compact contact set); ``fields``,
            None when the snapshot holds no fields, else a dict naming the arrays held
            (``pressure``, ``displacement``) that the JSON leaves out and where to read them:
            ``Snapshot.pressure`` and ``Snapshot.displacement`` of the Result the method's
            ``solve`` returns in Python.
        """
        held = [name for name in ("pressure", "displacement") if getattr(self, name) is not None]
        return {
            "approach": float(self.approach),
            "force": float(self.force),
            "contact_area": self.contact_area,
            "spacing": float(self.spacing),
            "origin": [float(self.origin[0]), float(self.origin[1])],
            "contact": _encode_mask(self.contact),
            "fields": None
            if not held
            else {
                "left_out": held,
                "shape": list(self.contact.shape),
                "how_to_get": "not written to JSON (one float per element each): read "
                + " and ".join(f"Snapshot.{name}" for name in held)
                + " from the Result the method's solve() returns in Python",
            },
        }

    @staticmethod
    def decode_contact(encoded: Mapping[str, Any]) -> np.ndarray:
        """The boolean contact mask from its run-length encoding in :meth:`to_json`.

        The encoding: ``shape`` [nx, ny]; ``runs``, the lengths of alternating runs of elements
        out of and in contact along the mask flattened with iy fastest (index [ix, iy]), the
        first run out of contact (of length 0 when element [0, 0] is in contact).

        Parameters
        ----------
        encoded : Mapping
            The ``contact`` entry of :meth:`to_json`'s dict.

        Returns
        -------
        numpy.ndarray
            The mask, of shape ``encoded["shape"]``, indexed [ix, iy].

        Raises
        ------
        ValueError
            If the runs do not cover the shape's elements exactly.
        """
        shape = tuple(int(n) for n in encoded["shape"])
        runs = np.asarray(encoded["runs"], dtype=np.int64)
        if runs.sum() != math.prod(shape):
            raise ValueError(f"the runs cover {runs.sum()} elements, not the {math.prod(shape)} of shape {shape}")
        values = np.arange(len(runs)) % 2 == 1
        return np.repeat(values, runs).reshape(shape)


def _encode_mask(mask: np.ndarray) -> dict:
    """Run-length encoding of a boolean mask (see :meth:`Snapshot.decode_contact`)."""
    flat = np.asarray(mask, bool).ravel()
    # the indices where the value changes, with the ends; the first run is out of contact
    edges = np.flatnonzero(np.diff(flat.astype(np.int8))) + 1
    bounds = np.concatenate(([0], edges, [flat.size]))
    runs = np.diff(bounds).tolist()
    if flat.size and flat[0]:
        runs = [0, *runs]
    return {
        "encoding": "run-length: alternating runs out of and in contact (the first out), iy fastest",
        "shape": list(mask.shape),
        "elements": int(np.count_nonzero(flat)),
        "runs": runs,
    }


def unrecorded_snapshots(
    wanted, recorded, *, start: float, highest: float, lowest: float, end: str, method: str
) -> str | None:
    """The message naming the snapshot approaches a pull asked for but did not record, and why.

    Parameters
    ----------
    wanted : iterable of float
        The approaches the scene asks for (``Outputs.snapshots``).
    recorded : iterable of float
        The approaches of the snapshots the method recorded.
    start : float
        The approach the pull starts from (the pressed state).
    highest, lowest : float
        The highest and lowest approach the loading path (turning points included) reached.
    end : str
        What ended the path at ``lowest``, completing "below d = <lowest>, ...": "where the
        punch detached", "the pull limit", "where the pull stopped after 1000 events".
    method : str
        The method's name, for the message.

    Returns
    -------
    str or None
        One message listing each approach not recorded with its reason; None when every
        approach asked for was recorded.
    """
    done = {float(a) for a in recorded}
    missed = sorted({float(a) for a in wanted} - done, reverse=True)
    if not missed:
        return None
    reasons = []
    for a in missed:
        if a > highest:
            where = (
                "where the pull starts (after the press; snapshots are taken while pulling)"
                if highest == start
                else "the highest approach the loading path reaches"
            )
            reasons.append(f"d = {a:g} lies above d = {highest:g}, {where}")
        elif a < lowest:
            reasons.append(f"d = {a:g} lies below d = {lowest:g}, {end}")
        else:
            reasons.append(f"d = {a:g} lies on the path (d = {lowest:g} to {highest:g}) but was not recorded")
    return f"{method} recorded no snapshot at {len(missed)} of the approaches asked for: " + "; ".join(reasons)


@dataclass(frozen=True)
class SolverStats:
    """The work a solve did, in counters every method fills (0 where one does not apply).

    Each counter is a whole number >= 0; a solver that fills a bad one raises ValueError (a
    bug, not bad input).

    Attributes
    ----------
    linear_solves : int
        Linear systems solved: contact-set solves (Griffith BEM), minimisations (energy BEM),
        factorisations (FEM).
    linear_iterations : int
        Their iterations: preconditioned CG steps, minimiser iterations.
    operator_applications : int
        Applications of the elastic operator: FFT convolutions, energy-and-gradient evaluations.
    events : int
        Steps of the loading path: detachment events (Griffith), continuation steps (energy).
    unconverged : int
        Sub-solves that stopped before their tolerance (each also says so in ``messages``).
    unknowns : int
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
    """A bound on a result's relative error, ``abs(value / exact - 1) <= relative``.

    It comes from an error model that a convergence study showed to cover the method's error.

    Attributes
    ----------
    relative : float
        The bound on the relative error, finite and >= 0.
    source : str
        The study and the number the bar comes from (a reader can re-run it).
    role : str
        ``"validation"`` (the default): the quantity is an independent prediction;
        ``"calibration"``: the method was fitted to this quantity on this very scene, so
        matching it validates nothing.
    interval : tuple of float or None
        Where the method also brackets the exact value itself, ``(low, high)`` in the quantity's
        units (the energy BEM's zero-range limit: the two limits its last step allows, for a tail
        whose effective rate lies in ``bem_energy.zero_range.RATE_BRACKET``); the exact value lies inside it
        under that assumption, a sharper claim on one side than ``relative``, and one that
        fails where the assumption does (a coarse sequence whose finest range is 0.08 of the
        radius left Kendall's force 0.2 per cent above it: ``examples/energy_zero_range.py``).
        None otherwise.
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

    A non-finite number among the scalars or on the curve, or a face area that is not positive,
    raises FloatingPointError on construction: a solver that has lost its answer says so
    rather than returning NaN.

    Attributes
    ----------
    method : str
        The method's name, as ``crossval`` registers it (``"bem_griffith"``, ``"bem_energy"``,
        ``"fem_reference"``).
    pulloff_force : float
        F_A, the magnitude of the largest tensile force on the pull.
    pulloff_approach : float
        The approach at that force.
    stiffness : float
        The initial dF/dd of the pressed contact.
    converged : bool
        Whether the solve can be trusted to its tolerances: every sub-solve reached its own
        and the method's conditions held (the energy BEM's process zone resolved, say);
        ``messages`` says why not.
    grid_spacing : float
        The element side Delta, or the characteristic mesh size.
    curve : Curve or None
        The force-approach curve, when the scene asks for it (``Outputs.curve``).
    detached : bool
        Whether contact was lost within the loading range.
    detachment_approach : float or None
        The approach at which the punch came off; None when it did not, or where the method
        did not locate it.
    snapshots : tuple of Snapshot
        The contact set at each approach of ``Outputs.snapshots`` that the loading path passed;
        ``messages`` names those it did not, and why.
    last_stable : Snapshot or None
        The last attached state before detachment, where the method records it.
    iterations : int
        The linear or minimiser iterations of the whole solve (0 where not counted).
    residual : float
        The worst residual of its sub-solves, in the method's own measure (relative CG
        residual, scaled projected gradient, relative residual of the saddle-point solve).
    timings : dict
        Wall time of each phase of the solve, in seconds.
    accuracy_estimate : float or None
        The largest relative error bound, where the method estimates one.
    messages : tuple of str
        What a reader must know: unconverged sub-solves, unresolved scales, a punch still
        attached at the end of the pull.
    info : Mapping
        Method-specific diagnostics, typed per method, for people and JSON; the harness does
        not read it.
    stats : SolverStats
        The work counters.
    error_bars : dict
        Per quantity of :data:`QUANTITIES`, the method's bounded relative error on this scene
        (an :class:`ErrorBar`); a quantity without a bar is not claimed to any accuracy.
    face_area : float or None
        The area of the face as discretised, e.g. a BEM grid's staircase (> 0); None when the
        face is exact.
    discretisation : str
        ``"grid"``: one square-element grid; ``"mesh"``: a finite-element mesh;
        ``"extrapolated"``: a limit over several discretisations.
    """

    method: str
    pulloff_force: float
    pulloff_approach: float
    stiffness: float
    converged: bool
    grid_spacing: float
    curve: Curve | None = None
    detached: bool = True
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
    error_bars: dict = field(default_factory=dict)
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
        """The wall time of the solve, in seconds: the sum of ``timings``."""
        return float(sum(self.timings.values()))

    def to_json(self) -> dict:
        """The result in plain JSON types (lists, floats, None), as ``crossval solve --json`` prints it.

        Every field of the Result is there, and the arrays it holds are either written out or
        named, with where to read them, under ``left_out``.

        Returns
        -------
        dict
            The keys of :data:`JSON_KEYS` (``curve`` None or a dict of its three lists); then
            ``detached``, ``detachment_approach``, ``iterations``, ``residual``, ``timings``,
            ``accuracy_estimate``, ``messages``, ``info``, ``stats``, ``error_bars``,
            ``face_area`` and ``discretisation`` as they are; ``snapshots`` (a list) and
            ``last_stable`` (None or one), each snapshot as :meth:`Snapshot.to_json` gives it
            (approach, force, contact area, spacing, origin and the contact map run-length
            encoded; its pressure and displacement fields named but not written out); and
            ``left_out``, a list of what the JSON omits and how to get it (empty when nothing
            is omitted).
        """
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
            "snapshots": [s.to_json() for s in self.snapshots],
            "last_stable": None if self.last_stable is None else self.last_stable.to_json(),
        }
        held = [s for s in (*self.snapshots, self.last_stable) if s is not None]
        fields = [name for name in ("pressure", "displacement") if any(getattr(s, name) is not None for s in held)]
        out["left_out"] = (
            [
                f"the {' and '.join(fields)} fields of the snapshots and last_stable (one float per "
                "element of each snapshot's grid, indexed [ix, iy]): read "
                + " and ".join(f"Result.snapshots[i].{name}" for name in fields)
                + " (and last_stable's) from the Result the method's solve() returns in Python"
            ]
            if fields
            else []
        )
        return out


def zero_range_note(scene: Scene, method: str) -> str | None:
    """The message of a zero-range method given a scene with a finite adhesion range.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene solved.
    method : str
        The method's name, for the message.

    Returns
    -------
    str or None
        That the range (named) is ignored and the result is the zero-range (Griffith /
        JKR-type) limit; None when the scene has no range.
    """
    adhesion = scene.adhesion
    if adhesion.range is None:
        return None
    return (
        f"adhesion range rho = {adhesion.range:g} ({adhesion.potential} potential) ignored: {method} models "
        "the zero-range (Griffith / JKR-type) limit, and this result is that limit, not the finite range's "
        "pull-off; bem_energy solves the finite range"
    )
