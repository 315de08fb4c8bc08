"""What the pull records as it goes: the force-approach curve, the snapshots the scene asks
for, and the caller's progress callback."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from contact_scene import Curve, Snapshot

from .contact_set import ContactSolution
from .problem import Problem

__all__ = ["PullRecorder"]


class PullRecorder:
    """Collects curve points (approach, force, contact area) and snapshots at the requested
    approaches; ``callback(approach, force, contact_area)`` sees every curve point."""

    def __init__(
        self,
        problem: Problem,
        snapshot_approaches,
        fields: bool,
        callback: Callable[[float, float, float], None] | None = None,
    ):
        self.problem = problem
        self.fields = fields
        self.callback = callback
        self.approach: list[float] = []
        self.force: list[float] = []
        self.contact_area: list[float] = []
        self.snapshots: list[Snapshot] = []
        self._wanted = sorted(snapshot_approaches, reverse=True)
        self._taken: set = set()

    def point(self, approach: float, solution: ContactSolution) -> None:
        """One curve point: the state ``solution`` at ``approach``."""
        cell = self.problem.cell_area
        force = solution.force(approach, cell) if solution.attached else 0.0
        self.approach.append(float(approach))
        self.force.append(float(force))
        self.contact_area.append(float(solution.contact.sum() * cell))
        if self.callback is not None:
            self.callback(approach, force, float(solution.contact.sum() * cell))

    def snapshots_between(self, start: float, end: float, solution: ContactSolution) -> None:
        """Snapshots at the wanted approaches in [start, end] (either order) not yet taken,
        all of the contact set ``solution`` holds across that interval."""
        low, high = min(start, end), max(start, end)
        for approach in [a for a in self._wanted if low <= a <= high and a not in self._taken]:
            self._taken.add(approach)
            self.snapshots.append(self.snapshot(approach, solution))

    def snapshot(self, approach: float, solution: ContactSolution) -> Snapshot:
        """The state ``solution`` at ``approach``, with its fields when the scene asks for them."""
        problem = self.problem
        pressure = displacement = None
        if self.fields:
            pressure = np.zeros(problem.face.shape)
            pressure[solution.contact] = solution.pressure(approach)
            displacement = solution.displacement(approach)
        force = solution.force(approach, problem.cell_area) if solution.attached else 0.0
        return Snapshot(
            float(approach),
            force,
            solution.contact.copy(),
            problem.spacing,
            problem.origin,
            pressure,
            displacement,
        )

    def peak(self) -> int:
        """The index of the largest tension on the curve so far, the pull-off's point (the
        pressed state is always recorded first)."""
        return int(np.argmax(-np.asarray(self.force)))

    def curve(self) -> Curve:
        return Curve(np.array(self.approach), np.array(self.force), np.array(self.contact_area))
