"""Pohrt-Popov adhesive boundary-element method on a square grid (FFT convolution)."""

from halfspace import HalfSpaceOperator, love_influence, love_square_integral

from .result import GriffithInfo
from .settings import GriffithSettings
from .solver import PressResult, press, solve, solve_with_resolution

__all__ = [
    "solve",
    "press",
    "PressResult",
    "solve_with_resolution",
    "GriffithSettings",
    "GriffithInfo",
    "HalfSpaceOperator",
    "love_influence",
    "love_square_integral",
]
