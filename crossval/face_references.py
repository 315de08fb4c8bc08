"""Converged reference values for the built-in faces without a closed form.

``crossval/references/faces.json`` (written by ``python benchmarks/reference_table.py``, which
states its procedure, resolutions and revision in the file) holds, per face, F_A / F_A,upper
(Eq. 13), the approach at F_A over d_c,upper (Eq. 14) and the stiffness over 2 E* sqrt(A/pi)
(Eq. 9), each with a relative error bar: the Griffith BEM extrapolated over grids and the
energy BEM's zero-range limit, the better-bounded of the two as the reference.  Being
dimensionless, each entry serves every scene with that face (same shape and size) on a
homogeneous half-space, at any E* and w; :func:`for_scene` turns it into the scene's units.
A method is checked against another method's value where the table has one (its own would
share its bias); against its own extrapolated value the check is a calibration residual.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from importlib import resources

import contact_scene as cs
from contact_scene import theory as T

__all__ = ["FaceReference", "for_scene", "table"]

#: where the table lives inside the package
TABLE = "references/faces.json"


@dataclass(frozen=True)
class FaceReference:
    """One quantity of the table in a scene's units.

    Attributes
    ----------
    value : float
        The reference value (N, m or N/m in the scene's units).
    relative : float
        Its relative error bar.
    source : str
        The face, the method the value comes from and the table's command and revision.
    method : str
        The method the value comes from.
    by_method : tuple of FaceReference
        Each method's own converged value in the table, with its bar.
    """

    value: float
    relative: float
    source: str
    #: the method the value comes from ("bem_griffith", "bem_energy")
    method: str = ""
    #: every method's own converged value, each a FaceReference in the scene's units, so that a
    #: method can be checked against another's rather than its own
    by_method: tuple[FaceReference, ...] = ()

    def independent_of(self, method: str) -> FaceReference | None:
        """The table's value for this quantity from a method other than ``method``, or None.

        Parameters
        ----------
        method : str
            The method to be checked.

        Returns
        -------
        FaceReference or None
            This reference if it comes from another method, else another method's converged
            value with its bar, else None (only ``method`` itself has a value).
        """
        if self.method != method:
            return self
        return next((other for other in self.by_method if other.method != method), None)


@functools.cache
def table() -> dict:
    """The stored table (``crossval/references/faces.json``), as written by its benchmark."""
    return json.loads(resources.files("crossval").joinpath(TABLE).read_text())


def _face_name(scene: cs.Scene) -> str | None:
    from .suite import BUILTIN

    shape = scene.indenter.shape
    for name, entry in table()["faces"].items():
        built = BUILTIN.get(entry.get("scene", name))
        # the built-in scene of that name, not a rotated variant stored under another key
        if built is not None and entry.get("scene", name) == name and built.indenter.shape == shape:
            return name
    return None


def for_scene(scene: cs.Scene) -> dict[str, FaceReference]:
    """The table's values for ``scene`` in its own units, by quantity; empty if none apply.

    Applies to a flat punch of one of the table's faces (the same shape and size as the built-in
    scene of that name) on a homogeneous half-space, at any E* and w; with a finite adhesion range
    the stiffness only (the forces and approaches are the zero-range limit's), and so with
    turning points or a pull limit that may stop the pull short of the force maximum (the
    table's are those of one monotonic pull).

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene.

    Returns
    -------
    dict
        ``{quantity: FaceReference}`` for the quantities the table has a reference for.
    """
    if not (scene.indenter.profile.is_flat and isinstance(scene.material, cs.Homogeneous)):
        return {}
    name = _face_name(scene)
    if name is None:
        return {}
    shape = scene.indenter.shape
    E, w = scene.material.effective_modulus, scene.adhesion.work_of_adhesion
    A, phi = shape.nominal_area, shape.filling_factor
    scale = {
        "pulloff_force": T.upper_bound_force(E_star=E, work=w, area=A, filling_factor=phi),
        "pulloff_approach": T.upper_bound_approach(E_star=E, work=w, area=A, filling_factor=phi),
        "stiffness": 2.0 * E * math.sqrt(A / math.pi),
    }
    doc = table()

    def source(method: str) -> str:
        return (
            f"reference table, {name}: {method} (crossval/references/faces.json, revision {doc.get('revision', '?')})"
        )

    quantities = doc["faces"][name]["quantities"]
    loading = scene.loading
    monotonic = not loading.turning_points
    if monotonic and loading.pull_limit is not None:
        approach = (quantities.get("pulloff_approach") or {}).get("reference")
        # the limit must lie beyond the force maximum's approach, its bar included
        monotonic = approach is not None and loading.pull_limit < (
            approach["value"] * scale["pulloff_approach"] * (1 + approach["relative_bar"])
        )
    out = {}
    for q, entry in quantities.items():
        ref = entry.get("reference")
        if q not in scale or not ref:
            continue
        if q != "stiffness" and scene.adhesion.range is not None:
            continue  # the table is the zero-range limit; the stiffness does not see the adhesion
        if q != "stiffness" and not monotonic:
            continue  # the pull may end, or turn, before the force maximum
        by_method = tuple(
            FaceReference(entry[m]["value"] * scale[q], entry[m]["relative_bar"], source(m), m)
            for m in ("bem_griffith", "bem_energy")
            if isinstance(entry.get(m), dict) and "value" in entry[m]
        )
        out[q] = FaceReference(
            ref["value"] * scale[q], ref["relative_bar"], source(ref["method"]), ref["method"], by_method
        )
    return out
