"""The examples run (short versions) and say what they claim."""
import pytest

from contact_scene import theory as T


def test_kendall_example_agrees_with_theory():
    from examples.kendall_circle import run

    out = run(resolution=16, fem_grading=2.0)
    assert abs(out["bem"].pulloff_force / out["kendall"] - 1) <= 0.5 / 16     # the BEM envelope
    assert abs(out["fem"].pulloff_force / out["kendall"] - 1) < 1e-4
