"""The energy BEM's error bars: bounds on its relative error, from its convergence studies.

* Zero-range limit (``discretisation == "extrapolated"``): the pull-off force's bar is the
  extrapolation's own estimate, which bounds the error on every window of the stored study
  (``tests/test_zero_range_estimator.py``, :func:`bem_energy.zero_range.tail_bracket`); the
  approach is that of the finest finite range, not extrapolated, and has no bar.
* Stiffness (one grid, or the zero-range limit's finest grid): ``c / N + (1+k)/2 |A_h / A - 1|``,
  N elements per equivalent radius, A_h the face's area on the grid; ``c`` fitted on the flat
  circle, the square (also rotated) and the suite's other faces (against the reference table)
  by ``python benchmarks/study_error_models.py`` and stored in ``error_model.json`` beside
  this module.
* A finite range is not the zero-range theory: its pull-off has no bar against Kendall.
"""

from __future__ import annotations

import functools
import json
from importlib import resources

from contact_scene import ErrorBar, Scene

__all__ = ["error_bars", "model"]


@functools.cache
def model() -> dict:
    """The stored model (``error_model.json``), as fitted by ``benchmarks/study_error_models.py``."""
    return json.loads(resources.files(__package__).joinpath("error_model.json").read_text())


def error_bars(
    scene: Scene,
    *,
    spacing: float,
    face_area: float,
    zero_range_estimate: float | None = None,
    zero_range_bracket: tuple[float, float] | None = None,
) -> dict[str, ErrorBar]:
    """The bars of a solve of ``scene`` whose (finest) grid has element side ``spacing`` and face
    area ``face_area``; ``zero_range_estimate``: the zero-range limit's relative error estimate;
    ``zero_range_bracket``: the two limits its finest step allows (the bar's ``interval``)."""
    shape = scene.indenter.shape
    bars: dict[str, ErrorBar] = {}
    if not scene.indenter.profile.is_flat:
        return bars
    N = shape.equivalent_radius / spacing
    defect = abs(face_area / shape.area - 1)
    m = model()["quantities"]["stiffness"]
    c = m["c"] if N >= model()["fit_from"] else m["coarse_c"]
    bars["stiffness"] = ErrorBar(
        c / N + 0.5 * defect,
        f"{c:.3g}/N + 0.5 |dA/A| at N = {N:.3g} (every flat suite face; benchmarks/study_error_models.py)",
    )
    if zero_range_estimate is not None:
        bars["pulloff_force"] = ErrorBar(
            zero_range_estimate,
            "the zero-range extrapolation's estimate (bounds every window of tests/data/zero_range_study.json)",
            # the limits the finest step allows (bem_energy.tail_bracket): the limit lies between them
            # if the tail's effective rate lies in RATE_BRACKET, the assumption the estimate rests on
            interval=None if zero_range_bracket is None else (min(zero_range_bracket), max(zero_range_bracket)),
        )
    return bars
