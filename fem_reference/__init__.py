"""Axisymmetric scikit-fem reference for circular flat punches (homogeneous, incompressible, graded)."""

from .solver import FemSettings, UnitSolution, applies, solve, solve_with_resolution, unit_solution

__all__ = ["FemSettings", "UnitSolution", "applies", "solve", "solve_with_resolution", "unit_solution"]
