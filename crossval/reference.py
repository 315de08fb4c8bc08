"""Reference results for people who test their own solvers against this package."""

from __future__ import annotations

import math
import numbers
import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import contact_scene as cs

from . import face_references
from .compare import relative_difference
from .methods import reference_method
from .suite import load_scene_or_builtin

__all__ = ["Reference", "reference", "assert_matches_reference", "UncheckedWarning"]


class UncheckedWarning(UserWarning):
    """A quantity read from a curve that the reference has no error bar on, so not compared.

    :func:`assert_matches_reference` compares the others and names it, rather than let a
    passing assertion suggest it was compared."""


@dataclass(frozen=True, eq=False)
class Reference:
    """A reference result and its error bars (the method's, from its convergence studies).

    Returned by :func:`reference`; :func:`assert_matches_reference` compares a solver's numbers
    with it.

    Attributes
    ----------
    scene : contact_scene.Scene
        The scene.
    result : contact_scene.Result or None
        The reference method's result; its ``error_bars`` are the reference's accuracy.  None
        when the reference table holds the face (``table``).
    table : dict
        ``{quantity: crossval.face_references.FaceReference}``: converged values with their
        bars from ``crossval/references/faces.json``, used instead of a solve.
    """

    scene: cs.Scene
    result: cs.Result | None
    table: dict = field(default_factory=dict)

    @property
    def source(self) -> str:
        """Where the reference's values come from: the table, or the method that solved it."""
        if self.table:
            return "reference table"
        assert self.result is not None
        return self.result.method

    def value(self, quantity: str) -> float:
        """The reference value of ``quantity``.

        Parameters
        ----------
        quantity : str
            ``"pulloff_force"``, ``"pulloff_approach"`` or ``"stiffness"``.

        Returns
        -------
        float
            The value, in the scene's units (NaN where the reference has none).
        """
        if self.table:
            ref = self.table.get(quantity)
            return math.nan if ref is None else ref.value
        assert self.result is not None
        return float(getattr(self.result, quantity))

    def error_bar(self, quantity: str) -> float | None:
        """The reference's own relative accuracy on ``quantity``, or None if it claims none.

        Parameters
        ----------
        quantity : str
            A field of :class:`contact_scene.Result`: ``"pulloff_force"``, ``"pulloff_approach"``
            or ``"stiffness"``.

        Returns
        -------
        float or None
            The bound on abs(value / exact - 1), or None.
        """
        if self.table:
            ref = self.table.get(quantity)
            return None if ref is None else ref.relative
        assert self.result is not None
        bar = self.result.error_bars.get(quantity)
        return None if bar is None else bar.relative

    @property
    def tolerance(self) -> float:
        """The pull-off force's bar (the quantity every built-in reference has one for)."""
        bar = self.error_bar("pulloff_force")
        return math.inf if bar is None else bar


def reference(scene_or_name, *, resolution: float = 64) -> Reference:
    """The most accurate method's result for a scene.

    The FEM for the circular flat punches it covers (with its error estimate as bar); the
    reference table's converged values for the faces it holds (``crossval/references/faces.json``,
    no solve); else the Griffith BEM at ``resolution`` elements per radius (with its error
    model's bars).

    Parameters
    ----------
    scene_or_name : contact_scene.Scene or str or os.PathLike
        A scene, the name of a built-in scene (``crossval scene list``) or a scene file's path.
    resolution : float, optional
        Elements per radius sqrt(A/pi) of the Griffith BEM when the FEM does not apply, > 0.

    Returns
    -------
    crossval.Reference
        The scene and the reference result.

    Raises
    ------
    contact_scene.SceneError
        Field ``file`` for an unknown name or an unreadable file, the offending field of an
        invalid scene file, or field ``scene`` for something that is not a scene, name or path,
        or when no registered method can give a reference.
    RuntimeError
        If the reference solve did not converge (its messages say why).
    """
    if not isinstance(scene_or_name, (cs.Scene, str, os.PathLike)):
        raise cs.SceneError(
            "scene", f"must be a Scene, a built-in scene's name or a scene file's path (got {scene_or_name!r})"
        )
    # checked whether or not a grid solve reads it: a bad value is refused, not ignored
    cs.errors.check_real("resolution", resolution, lo=0, lo_open=True)
    if isinstance(scene_or_name, cs.Scene):
        scene = scene_or_name
    else:
        scene = load_scene_or_builtin(scene_or_name if isinstance(scene_or_name, str) else Path(scene_or_name))
    bounded = reference_method(scene, "bounded")
    table = face_references.for_scene(scene)
    if bounded is not None:
        method, r = bounded.name, bounded.solve(scene)
    elif table:
        return Reference(scene, None, table)
    else:
        grid = reference_method(scene, "sequence")
        if grid is None:
            finite = scene.adhesion.range is not None and scene.adhesion.work_of_adhesion > 0
            raise cs.SceneError(
                "scene",
                "no registered method can give a reference for this scene"
                + (
                    f" (adhesion.range = {scene.adhesion.range:g} is finite: the reference methods model zero "
                    "range, and bem_energy, which models a finite one, has no error bar on its pull-off there)"
                    if finite
                    else ""
                ),
            )
        method, r = grid.name, grid.solve(scene, resolution=resolution)
    if not r.converged:
        raise RuntimeError(f"the reference solve ({method}) did not converge: {'; '.join(r.messages)}")
    return Reference(scene, r)


_SIGNS = (
    "this package's convention is F < 0 in tension and d < 0 when pulled (the pull-off force is the "
    "magnitude of the most tensile F); if your code counts tension positive, pass curve=(-d, -F)"
)


def _from_curve(approach, force):
    d = np.asarray(approach, float)
    F = np.asarray(force, float)
    if d.ndim != 1 or d.shape != F.shape or len(d) < 2:
        raise ValueError("curve must be two 1-D arrays of equal length >= 2 (approach, force)")
    if not np.any(F < 0):
        raise AssertionError(f"the curve has no tensile force (no F < 0): {_SIGNS}")
    i = int(np.argmax(-F))
    if d[i] > 0:
        # an adhesive punch is pulled (d < 0) to its largest tension; one at a pressed approach
        # is the press's compression counted negative, tension positive
        raise AssertionError(f"the most tensile force lies at a pressed approach d = {d[i]:.6g} > 0: {_SIGNS}")
    j = int(np.flatnonzero(d != d[0])[0]) if np.any(d != d[0]) else 1
    return float(-F[i]), float(d[i]), float((F[j] - F[0]) / (d[j] - d[0]))


def assert_matches_reference(
    ref: Reference, *, pulloff_force=None, pulloff_approach=None, stiffness=None, curve=None, rtol: float = 0.0
) -> None:
    """Assert that a solver's numbers match the reference within its error bars plus ``rtol``.

    A ``curve`` (approach, force) is reduced to its largest tensile force, the approach there,
    and the slope of its first segment; of these, quantities the reference has no bar for are
    not compared, and an :class:`UncheckedWarning` names them (pytest lists it in its warnings
    summary).  A quantity given explicitly that the reference has no bar for is an error
    (ValueError), not a pass, and so is a call that leaves nothing to compare.  Signs are this
    package's: F < 0 in tension, d < 0 when pulled.

    Parameters
    ----------
    ref : crossval.Reference
        The reference (:func:`reference`).
    pulloff_force : float, optional
        The pull-off force, a magnitude (>= 0).
    pulloff_approach : float, optional
        The approach at the pull-off force (< 0 when pulled).
    stiffness : float, optional
        The initial stiffness dF/dd.
    curve : tuple of array_like, optional
        (approach, force), two 1-D arrays of equal length >= 2; the quantities given explicitly
        take precedence over those read from the curve.
    rtol : float, optional
        Relative tolerance added to the reference's own bar, >= 0.

    Raises
    ------
    AssertionError
        Naming every quantity that differs from the reference by more than the reference's bar
        on it plus ``rtol`` (value, reference, difference, tolerance); also for a negative
        ``pulloff_force``, a curve without tension or one whose largest tension lies at a
        pressed approach d > 0 (with a note on sign conventions).
    ValueError
        If a quantity given explicitly has no bar in the reference or is not a finite number,
        none of the quantities given or read can be compared, ``curve`` is malformed, or
        ``rtol`` is not a finite number >= 0.

    Warns
    -----
    UncheckedWarning
        Naming the quantities read from ``curve`` that the reference has no bar for.
    """
    __tracebackhide__ = True  # pytest shows the message, not this function's body
    # a NaN tolerance would make every comparison pass (nan > x is False), a negative one fail
    if isinstance(rtol, bool) or not isinstance(rtol, numbers.Real) or not (0 <= rtol < math.inf):
        raise ValueError(f"rtol must be a finite number >= 0 (got {rtol!r})")
    for name, v in (("pulloff_force", pulloff_force), ("pulloff_approach", pulloff_approach), ("stiffness", stiffness)):
        if v is not None and (isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v)):
            raise ValueError(f"{name} must be a finite number (got {v!r})")
    if pulloff_force is not None and pulloff_force < 0:
        raise AssertionError(f"pulloff_force = {pulloff_force:.6g} is negative; it is a magnitude: {_SIGNS}")
    explicit = {
        n
        for n, v in (("pulloff_force", pulloff_force), ("pulloff_approach", pulloff_approach), ("stiffness", stiffness))
        if v is not None
    }
    if curve is not None:
        f, d, k = _from_curve(*curve)
        pulloff_force = f if pulloff_force is None else pulloff_force
        pulloff_approach = d if pulloff_approach is None else pulloff_approach
        stiffness = k if stiffness is None else stiffness
    bad, unchecked, compared = [], [], 0
    for name, value in (
        ("pulloff_force", pulloff_force),
        ("pulloff_approach", pulloff_approach),
        ("stiffness", stiffness),
    ):
        if value is None:
            continue
        own = ref.error_bar(name)
        if own is None:
            if name in explicit:
                raise ValueError(
                    f"scene {ref.scene.name or '(unnamed)'}: the reference ({ref.source}) has no "
                    f"error bar on {name}, so it cannot be checked against it"
                )
            unchecked.append(name)
            continue
        compared += 1
        tol = own + rtol
        want = ref.value(name)
        diff = relative_difference(value, want)
        if not abs(diff) <= tol:
            bad.append(
                f"{name}: {value:.6g} vs reference {want:.6g} ({ref.source}): {diff:+.3%}, "
                f"tolerance {tol:.3%} (reference accuracy {own:.3%} + rtol {rtol:.3%})"
            )
    if bad:
        raise AssertionError(f"scene {ref.scene.name or '(unnamed)'}: " + "; ".join(bad))
    if not compared:
        raise ValueError(
            f"scene {ref.scene.name or '(unnamed)'}: nothing to compare: the reference ({ref.source}) has no error bar "
            f"on {', '.join(unchecked) or 'any quantity given'}"
        )
    if unchecked:
        warnings.warn(
            f"scene {ref.scene.name or '(unnamed)'}: {', '.join(unchecked)} read from the curve not compared: the "
            f"reference ({ref.source}) has no error bar on {'it' if len(unchecked) == 1 else 'them'}",
            UncheckedWarning,
            stacklevel=2,
        )
