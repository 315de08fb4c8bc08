"""Run a scene through every applicable method and check each against theory and each other.

Every tolerance is an error bar a method states for its own result (``Result.error_bars``),
fitted by a convergence study that shows it covers the method's error; the bar names the study:

* bem_griffith: ``bem_griffith.error_model`` (``benchmarks/study_error_models.py``): c/N plus the
  local criterion's plateau plus the result's own staircase area defect, per quantity; faces
  with corners against the reference table's converged values; graded faces with the calibrated
  criterion add the calibration's terms, and on the flat circle their pull-off is a calibration
  residual (``role="calibration"``), not a validation.
* fem_reference: its per-quantity bounds (degree pair plus truncation; tests/test_fem_reference.py:
  error <= bound on every tested case).
* bem_energy: ``bem_energy.error_model``: the zero-range limit's force by its extrapolation
  estimate (bounds every window of the stored study), the stiffness c/N plus the area defect;
  no bar on a finite range's pull-off (it is not the zero-range theory) or on the approach.

Faces without a closed form are checked between the bounds (Eqs. 13, 18; the lower bound less
the method's bar) and across methods.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

import contact_scene as cs
from contact_scene import theory as T

from . import face_references
from .methods import METHODS, applicable_methods

__all__ = [
    "Check",
    "Comparison",
    "compare",
    "check_results",
    "raster_checks",
    "same_grid_partners",
    "reference_values",
    "reference_source",
    "error_bar",
]


def relative_difference(value: float, reference: float) -> float:
    """``value / reference - 1``; against a zero reference, 0 for a value of exactly zero (a scene
    without adhesion, w = 0, has F_A = 0 and its approach 0 in closed form and in every method)
    and infinite otherwise.

    Parameters
    ----------
    value, reference : float
        The value checked and what it is compared with.

    Returns
    -------
    float
        The relative difference.
    """
    if reference:
        return value / reference - 1
    return 0.0 if value == 0 else math.inf


@dataclass(frozen=True)
class Check:
    """One check of a result (or a pair of results) against a reference, with its tolerance.

    Attributes
    ----------
    method : str
        The method checked, or ``"a vs b"`` for a pair.
    quantity : str
        ``pulloff_force``, ``pulloff_approach`` or ``stiffness``; ``"<quantity> bracket"`` when
        a reference must lie in a method's bracket; ``raster mirror`` / ``raster rotation 90``
        for the raster's equivariance; ``converged`` for a result that did not converge.
    value : float
        The value checked (for a bracket check: the reference's value).
    reference : float
        The value it is compared with; for ``kind="bounds"`` the lower end of the interval.
    reference_name : str
        Where the reference comes from (a closed form's equations, a method's name).
    tolerance : float
        Relative tolerance (``"relative"``), slack below the lower bound (``"bounds"``), or the
        number of cells allowed to differ (``"exact"``).
    kind : str
        ``"relative"``, ``"bounds"`` or ``"exact"``.
    upper : float or None
        The upper end of the interval (``kind="bounds"``); None: unbounded above.
    role : str
        ``"validation"``: an independent check; ``"calibration"``: a residual of a quantity the
        method was fitted to (it can fail, but its passing validates nothing).
    converged : bool
        Whether every result the check compares converged; a check of an unconverged result fails.
    basis : str
        Where the tolerance comes from (the error model's study, or the rule between methods).
    """

    method: str
    quantity: str
    value: float
    reference: float
    reference_name: str
    tolerance: float  # relative; the allowed interval's slack for bounds; cells for "exact"
    kind: str = "relative"  # "relative" | "bounds" | "exact" (a count that must not exceed tolerance)
    upper: float | None = None  # for bounds
    #: "validation": an independent check; "calibration": a residual of a quantity the method
    #: was fitted to (it can fail, but its passing validates nothing)
    role: str = "validation"
    #: whether every result the check compares converged; a check of an unconverged result fails
    converged: bool = True
    #: where the tolerance comes from (the error model's study, or the rule between methods)
    basis: str = ""

    @property
    def difference(self) -> float:
        """The relative difference ``value / reference - 1`` (:func:`relative_difference`)."""
        return relative_difference(self.value, self.reference)

    @property
    def passed(self) -> bool:
        """Whether the check holds: converged, and within its tolerance or interval."""
        if not self.converged:
            return False
        if self.kind == "bounds":
            upper = math.inf if self.upper is None else self.upper
            return self.reference * (1 - self.tolerance) <= self.value <= upper * (1 + 1e-12)
        if self.kind == "exact":
            return self.value <= self.tolerance
        return abs(self.difference) <= self.tolerance

    @property
    def label(self) -> str:
        """One word for listings: ok, FAIL, or calib for a calibration residual within its bound."""
        if not self.passed:
            return "FAIL"
        return "calib" if self.role == "calibration" else "ok"

    def explain(self) -> str:
        """One sentence for people: the value, the reference, the difference and the tolerance.

        Returns
        -------
        str
            The explanation, naming why a check of an unconverged result fails.
        """
        if not self.converged and self.quantity == "converged":
            return f"{self.method}: did not converge ({self.basis or 'see the result messages'})"
        if not self.converged:
            # a pair's check names both results: say which ones did not converge, not only the value
            who = (
                "a result that did not converge"
                if " vs " not in self.method
                else "a pair with a result that did not converge"
            )
            return (
                f"{self.method}: {self.quantity} = {self.value:.6g} against {self.reference_name} "
                f"{self.reference:.6g} comes from {who}, so it fails whatever its value"
            )
        if self.role == "calibration":
            return (
                f"{self.method}: {self.quantity} = {self.value:.6g}, calibration residual against "
                f"{self.reference_name} {self.reference:.6g}: {self.difference:+.3%} (bound {self.tolerance:.3%}; "
                "matches by construction, not a validation)"
            )
        if self.kind == "exact":
            return (
                f"{self.method}: {self.quantity}: {self.value:.0f} cells differ "
                f"(allowed {self.tolerance:.0f}; {self.basis})"
            )
        if self.kind == "bounds":
            return (
                f"{self.method}: {self.quantity} = {self.value:.6g} should lie in [{self.reference:.6g} "
                f"(lower bound, slack {self.tolerance:.2%}), {self.upper:.6g}] ({self.reference_name})"
            )
        return (
            f"{self.method}: {self.quantity} = {self.value:.6g} differs from {self.reference_name} "
            f"{self.reference:.6g} by {self.difference:+.3%} (tolerance {self.tolerance:.3%})"
        )


@dataclass(frozen=True, eq=False)
class Comparison:
    """A scene's results by method and their checks, as :func:`compare` returns them.

    Attributes
    ----------
    scene : contact_scene.Scene
        The scene compared.
    results : dict
        ``{name: Result}``: each method's result, and the same-grid partner solves
        (``"bem_energy on bem_griffith's grid (w = 0)"``, see :func:`same_grid_partners`).
    theory : dict
        The closed-form values (:func:`reference_values`).
    checks : tuple of Check
        Every check, against theory and between methods.
    skipped : dict
        ``{method: reason}`` for the methods that do not apply to the scene.
    """

    scene: cs.Scene
    results: dict
    theory: dict
    checks: tuple[Check, ...] = ()
    skipped: dict = field(default_factory=dict)  # method -> why it does not apply

    @property
    def passed(self) -> bool:
        """Whether every check passed."""
        return all(c.passed for c in self.checks)

    @property
    def unchecked(self) -> dict[str, tuple[str, ...]]:
        """``{method: quantities}``: the methods' values that no check holds to anything.

        No closed form, no reference-table entry, and no error bar of this method (or of a
        second one) on this scene: listed so that a reader does not take silence for agreement."""
        quantities: tuple[str, ...] = ("stiffness",)
        if self.scene.adhesion.work_of_adhesion > 0:
            quantities = ("pulloff_force", "pulloff_approach", "stiffness")
        out = {}
        for name in self.results:
            if name not in METHODS:  # a same-grid partner solve, there for one check only
                continue
            missing = tuple(
                q
                for q in quantities
                if not any(c.quantity.split(" ")[0] == q and name in c.method.split(" vs ") for c in self.checks)
            )
            if missing:
                out[name] = missing
        return out


def reference_source(theory: dict, quantity: str) -> str:
    """Where the reference value of ``quantity`` in :func:`reference_values`' dict comes from:
    the reference table's entry for it, else the scene's closed form ("" when there is none)."""
    return theory.get("sources", {}).get(quantity, theory.get("source", ""))


def reference_values(scene: cs.Scene) -> dict:
    """Closed-form values for the scene where the sheet has them, and the reference table's
    converged values (with their relative bars under ``"bars"`` and sources under ``"sources"``)
    for the faces it holds (:mod:`crossval.face_references`); for a finite adhesion range the
    stiffness only (the others are the zero-range limit's)."""
    shape, mat, w = scene.indenter.shape, scene.material, scene.adhesion.work_of_adhesion
    prof = scene.indenter.profile
    out: dict[str, Any] = {}
    if isinstance(mat, cs.Homogeneous):
        E = mat.effective_modulus
        if prof.is_flat and isinstance(shape, cs.Circle):
            out.update(
                pulloff_force=T.kendall_adhesion_force(E_star=E, radius=shape.radius, work=w),
                pulloff_approach=T.kendall_critical_approach(E_star=E, radius=shape.radius, work=w),
                stiffness=T.kendall_stiffness(E_star=E, radius=shape.radius),
                source="Kendall (Eqs. 1, 4, 6)",
            )
        elif prof.is_flat:
            out.update(
                upper_force=T.upper_bound_force(
                    E_star=E, work=w, area=shape.nominal_area, filling_factor=shape.filling_factor
                ),
                lower_force=T.lower_bound_force(E_star=E, work=w, incircle_radius=shape.incircle().radius),
                source="bounds (Eqs. 13, 18)",
            )
            # converged values with error bars where the reference table has the face
            table = {q: ref for q, ref in face_references.for_scene(scene).items() if w > 0 or q == "stiffness"}
            for q, ref in table.items():
                out[q] = ref.value
            if table:
                out["bars"] = {q: ref.relative for q, ref in table.items()}
                out["sources"] = {q: ref.source for q, ref in table.items()}
        elif isinstance(prof, (cs.Paraboloid, cs.Sphere)):
            out.update(pulloff_force=T.jkr_pulloff_force(work=w, sphere_radius=prof.radius), source="JKR 1.5 pi w R")
    elif isinstance(mat, cs.PowerLawGraded) and prof.is_flat and isinstance(shape, cs.Circle):
        E0, c0, k = mat.surface_modulus, mat.reference_depth, mat.exponent
        out.update(
            pulloff_force=T.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=shape.radius, work=w),
            pulloff_approach=T.graded_critical_approach(E0=E0, c0=c0, k=k, radius=shape.radius, work=w),
            stiffness=T.graded_stiffness(E0=E0, c0=c0, k=k, radius=shape.radius),
            source="graded (Eqs. 34, 38, 39)",
        )
    if scene.adhesion.range is not None and w > 0:
        # the closed forms and the table are the zero-range limit: a finite range's forces and
        # approaches are not theirs (the stiffness, without adhesion, is)
        for q in ("pulloff_force", "pulloff_approach", "upper_force", "lower_force"):
            out.pop(q, None)
        for part in ("bars", "sources"):
            if part in out:
                out[part] = {q: v for q, v in out[part].items() if q == "stiffness"}
    return out


def error_bar(result: cs.Result, quantity: str) -> cs.ErrorBar | None:
    """The method's own bar on ``quantity`` (None: the method claims no accuracy for it here)."""
    return result.error_bars.get(quantity)


#: The two BEMs' stiffnesses on one grid differ by their kernels' discretisation only: on the
#: flat circle, square (also at 45 degrees), triangle, 4:1 rectangle and star at N = 8 ... 64
#: elements per radius, K_love / K_collocation - 1 = +0.045/N ... +0.069/N
#: (benchmarks/study_halfspace_kernels.py; tests/test_halfspace.py), and the suite's star up to
#: +0.075/N at N = 32 ... 128 (the two stiffness models' data, benchmarks/study_error_models.py).
#: The window is the first range widened by 0.015/N on either side (a quarter of its centre),
#: as N times the ratio less one; the star is 0.015/N inside its upper edge.
#: It has a sign: a 1 % error in either kernel moves the ratio by 1 % and leaves the window
#: from N = 32 on (tested), and the collocated self term taken from the element's own centre
#: (mutant H3 of benchmarks/mutation_study.py) turns the difference to -0.07/N ... -0.08/N.
SAME_GRID_WINDOW: dict[tuple[str, str], tuple[float, float]] = {("love", "collocation"): (0.03, 0.09)}


def _kernel_window(a: cs.Result, b: cs.Result) -> tuple[float, float] | None:
    """The window of N (K_a / K_b - 1) for two results on one grid, from their kernels."""
    ka, kb = METHODS[a.method].grid_kernel, METHODS[b.method].grid_kernel
    if ka is None or kb is None:
        return None
    if (ka, kb) in SAME_GRID_WINDOW:
        return SAME_GRID_WINDOW[ka, kb]
    if (kb, ka) in SAME_GRID_WINDOW:
        lo, hi = SAME_GRID_WINDOW[kb, ka]
        return (-hi, -lo)  # K_b / K_a - 1 to first order in 1/N
    return None


def _same_grid(a: cs.Result, b: cs.Result) -> bool:
    """Two single-grid results on grids of one element size: the same staircase face, so the
    difference of their stiffnesses is the two kernels' discretisation only."""
    return (
        a.discretisation == b.discretisation == "grid"
        and a.method != b.method
        and math.isclose(a.grid_spacing, b.grid_spacing, rel_tol=1e-12)
    )


def _cells_differing(a: np.ndarray, b: np.ndarray) -> int:
    if a.shape != b.shape:
        return int(max(np.count_nonzero(a), np.count_nonzero(b)))
    return int(np.count_nonzero(a != b))


def raster_checks(scene: cs.Scene, results: dict) -> list[Check]:
    """The face's raster at each grid method's element size is equivariant: the raster of the
    mirrored (rotated by 90 degrees) face is the mirrored (rotated) raster, cell for cell.

    Exact by the raster's rule (nodes anchored at the centroid, ``contact_scene.raster``), for
    every face, symmetric or not; a grid that is off by part of a cell, or a cell test that is
    not the centre's, breaks it while leaving every force within the staircase's error.  One
    check per distinct element size; rasterising costs milliseconds at the report's grids."""
    shape = scene.indenter.shape
    checks: list[Check] = []
    seen: set[float] = set()
    for name, r in results.items():
        h = r.grid_spacing
        if r.discretisation != "grid" or h is None or h in seen:
            continue
        seen.add(h)
        m = cs.rasterise(shape, h).mask
        for quantity, moved, expected in (
            ("raster mirror", cs.rasterise(shape.mirrored(), h).mask, (m[::-1, :],)),
            ("raster rotation 90", cs.rasterise(shape.rotated(90), h).mask, (np.rot90(m), np.rot90(m, -1))),
        ):
            wrong = min(_cells_differing(moved, e) for e in expected)
            checks.append(
                Check(
                    name,
                    quantity,
                    float(wrong),
                    0.0,
                    "the transformed raster",
                    0.0,
                    kind="exact",
                    converged=r.converged,  # the rule: an unconverged result fails every check it enters
                    basis=f"cells at h = {h:.4g}, nodes anchored at the centroid (contact_scene.raster)",
                )
            )
    return checks


def same_grid_partners(scene: cs.Scene, results: dict, *, among=None) -> dict[str, tuple[cs.Scene, str, float]]:
    """The solves that put every method with a grid kernel on the grid of each single-grid
    result it has no result on: ``{key: (scene without adhesion, method, N per radius)}``.

    A flat punch's stiffness does not depend on adhesion, so the partner solves the scene
    with w = 0 (one linear contact problem, seconds) and the pair's stiffnesses are held to
    their kernels' measured same-grid difference (:data:`SAME_GRID_WINDOW`), a check about
    twenty times sharper than the two methods' own bars; the energy BEM's zero-range result
    is extrapolated over grids and cannot be paired otherwise.  ``among``: the method names
    allowed as partners (default: every registered method)."""
    if not scene.indenter.profile.is_flat:
        return {}
    import dataclasses

    bare = dataclasses.replace(
        scene, adhesion=dataclasses.replace(scene.adhesion, work_of_adhesion=0.0, range=None, potential="exponential")
    )
    R = scene.indenter.shape.equivalent_radius
    out: dict[str, tuple[cs.Scene, str, float]] = {}
    for r in results.values():
        if r.discretisation != "grid" or METHODS[r.method].grid_kernel is None:
            continue
        for m in METHODS.values():
            if among is not None and m.name not in among:
                continue
            if m.grid_kernel is None or m.name == r.method or m.applies(bare) is not None:
                continue
            if not m.resolution(bare).per_radius:
                continue
            if any(o.method == m.name and _same_grid(r, o) for o in results.values()):
                continue
            N = R / r.grid_spacing
            out[f"{m.name} on {r.method}'s grid (w = 0)"] = (bare, m.name, N)
    return out


def _bracket_check(method: str, quantity: str, value: float, slack: float, bar: cs.ErrorBar, name: str, **kw) -> Check:
    """``value`` (with its own relative bar ``slack``) must reach into ``bar.interval``, the
    interval a method brackets the exact value of ``quantity`` by."""
    assert bar.interval is not None
    low, high = bar.interval
    return Check(method, f"{quantity} bracket", value, low, name, slack, kind="bounds", upper=high * (1 + slack), **kw)


def check_results(scene: cs.Scene, results: dict) -> tuple[Check, ...]:
    """Checks of solved results against the closed forms and against each other.

    A method is checked on the quantities it has an error bar for (``Result.error_bars``, from its
    convergence studies): against a closed form within its bar; against another method within
    the two bars added in quadrature (their discretisation errors are independent), except two
    single-grid BEMs on one grid, whose stiffnesses share the staircase face and are held to
    their kernels' measured difference (:data:`SAME_GRID_WINDOW`).  A result that did not
    converge fails every check it enters."""
    theory = reference_values(scene)
    # the reference table's entries, with every method's value (theory holds the reference's)
    table = {q: v for q, v in face_references.for_scene(scene).items() if q in theory.get("bars", {})}
    checks = []
    src = theory.get("source", "")
    for name, r in results.items():
        if not r.converged:
            # whatever bars it has, an unconverged result fails: never a check silently skipped
            checks.append(
                Check(name, "converged", 0.0, 1.0, "convergence", 0.0, converged=False, basis="; ".join(r.messages))
            )
        for q in ("pulloff_force", "pulloff_approach", "stiffness"):
            bar = error_bar(r, q)
            ref_value = float(theory.get(q, math.nan))
            ref_bar = theory.get("bars", {}).get(q, 0.0)  # the reference's own bar (0: a closed form)
            ref_src = reference_source(theory, q)
            own_table_value = False
            if q in table:
                # a table value from this very method shares its bias: check against another
                # method's value where the table has one, else it is a calibration residual
                other = table[q].independent_of(r.method)
                if other is not None:
                    ref_value, ref_bar, ref_src = other.value, other.relative, other.source
                else:
                    own_table_value, ref_bar = True, 0.0
            if q in theory and bar is not None and bar.interval is not None:
                # the method brackets the exact value: the closed form must lie inside
                checks.append(
                    _bracket_check(
                        name,
                        q,
                        ref_value,
                        ref_bar,
                        bar,
                        f"its bracket on the exact {q}; the value checked is {ref_src}'s",
                        role=bar.role,
                        converged=r.converged,
                        basis=bar.source,
                    )
                )
            if q in theory and bar is not None:
                checks.append(
                    Check(
                        name,
                        q,
                        getattr(r, q),
                        ref_value,
                        ref_src + (" (its own extrapolated value)" if own_table_value else ""),
                        # a closed form is exact; another method's table value has its own bar
                        math.hypot(bar.relative, ref_bar),
                        role="calibration" if own_table_value else bar.role,
                        converged=r.converged,
                        basis=bar.source
                        if not ref_bar
                        else f"{bar.source}; the table's bar {ref_bar:.2%} in quadrature",
                    )
                )
        bar = error_bar(r, "pulloff_force")
        if "upper_force" in theory and bar is not None:
            checks.append(
                Check(
                    name,
                    "pulloff_force",
                    r.pulloff_force,
                    theory["lower_force"],
                    src,
                    bar.relative,
                    kind="bounds",
                    upper=theory["upper_force"],
                    converged=r.converged,
                    basis=bar.source,
                )
            )
    checks.extend(raster_checks(scene, results))
    names = list(results)
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            a, b = results[names[i]], results[names[j]]
            for q in ("pulloff_force", "stiffness"):
                ba, bb = error_bar(a, q), error_bar(b, q)
                if ba is None or bb is None:
                    continue
                role = "calibration" if "calibration" in (ba.role, bb.role) else "validation"
                window = _kernel_window(a, b) if q == "stiffness" and _same_grid(a, b) else None
                if window is not None:
                    N = scene.indenter.shape.equivalent_radius / a.grid_spacing
                    lo, hi = window
                    checks.append(
                        Check(
                            f"{names[i]} vs {names[j]}",
                            q,
                            a.stiffness,
                            b.stiffness * (1 + lo / N),
                            f"{names[j]} x (1 + [{lo:+g}, {hi:+g}]/N) at N = {N:.4g}",
                            0.0,
                            kind="bounds",
                            upper=b.stiffness * (1 + hi / N),
                            role=role,
                            converged=a.converged and b.converged,
                            basis="the kernels' measured same-grid difference (crossval.compare.SAME_GRID_WINDOW)",
                        )
                    )
                    continue
                for bx, nx, y, by, ny in ((ba, names[i], b, bb, names[j]), (bb, names[j], a, ba, names[i])):
                    if bx.interval is None:
                        continue
                    # the other method's value, within its own bar, must reach into the bracket
                    checks.append(
                        _bracket_check(
                            f"{ny} vs {nx}",
                            q,
                            getattr(y, q),
                            by.relative,
                            bx,
                            f"{nx}'s bracket on the exact {q}, widened by {ny}'s bar",
                            role=role,
                            converged=a.converged and b.converged,
                            basis=f"{bx.source}; {by.source}",
                        )
                    )
                tol = math.hypot(ba.relative, bb.relative)
                basis = "the two error bars in quadrature"
                checks.append(
                    Check(
                        f"{names[i]} vs {names[j]}",
                        q,
                        getattr(a, q),
                        getattr(b, q),
                        names[j],
                        tol,
                        role=role,
                        converged=a.converged and b.converged,
                        basis=basis,
                    )
                )
    return tuple(checks)


def compare(
    scene: cs.Scene,
    *,
    methods=None,
    resolution: float | None = None,
    resolutions: dict | None = None,
    callback=None,
    point_callback=None,
) -> Comparison:
    """Solve ``scene`` with every applicable method (or those named) and check the results.

    Besides each method's own result, a method with a grid kernel also runs on the other grid
    method's grid without adhesion (:func:`same_grid_partners`), for the same-grid stiffness
    check.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene.
    methods : list of str, optional
        Method names (``crossval.METHODS``); default: every method that applies.
    resolution : float, optional
        The grid methods' elements per equivalent radius sqrt(A/pi); default: each method's own.
    resolutions : dict, optional
        ``{method: resolution}`` in a method's own measure, e.g. ``{"bem_energy": 1.0}``: the
        energy method's coarse zero-range sequence, seconds instead of minutes.
    callback : callable, optional
        ``callback(name, result)`` after each solve.
    point_callback : callable, optional
        ``point_callback(method, approach, force, contact_area)`` at each point of a solver's
        curve as it is computed (progress).

    Returns
    -------
    Comparison
        The results, the closed-form values, the checks and the methods skipped.

    Raises
    ------
    contact_scene.SceneError
        ``methods`` or ``resolutions`` names an unknown method (``methods``: not a list of
        names), or a resolution a method refuses.
    """
    if methods is not None:
        if not isinstance(methods, (list, tuple)) or not all(isinstance(m, str) for m in methods):
            raise cs.SceneError("methods", f"must be a list of method names (got {methods!r})")
        unknown_methods = [m for m in methods if m not in METHODS]
        if unknown_methods:
            raise cs.SceneError(
                "methods", f"unknown method(s) {', '.join(unknown_methods)}; available: {', '.join(METHODS)}"
            )
    chosen = applicable_methods(scene) if methods is None else [METHODS[m] for m in methods]
    skipped = {m.name: m.applies(scene) for m in METHODS.values() if m.applies(scene)}
    own = dict(resolutions or {})
    unknown = set(own) - set(METHODS)
    if unknown:
        raise cs.SceneError(
            "resolutions", f"unknown method(s) {', '.join(sorted(unknown))}; available: {', '.join(METHODS)}"
        )
    results = {}
    for m in chosen:
        res = own[m.name] if m.name in own else (resolution if m.resolution_is_grid(scene) else None)
        cb = None if point_callback is None else (lambda d, F, A, _m=m.name: point_callback(_m, d, F, A))
        r = m.solve(scene, resolution=res, callback=cb)
        results[m.name] = r
        if callback is not None:
            callback(m.name, r)
    for key, (bare, name, N) in same_grid_partners(scene, results, among=[m.name for m in chosen]).items():
        r = METHODS[name].solve(bare, resolution=N)
        results[key] = r
        if callback is not None:
            callback(key, r)
    return Comparison(scene, results, reference_values(scene), check_results(scene, results), skipped)
