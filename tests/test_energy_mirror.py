"""Mirror-symmetric energy problems: a face and profile that mirror about the raster's middle row
make the whole padded problem mirror (rows i and (nx - 1 - i) mod M), and an array that mirrors
takes half-size transforms (``EnergyProblem._mirrored``): the same products to round-off,
mirrored exactly, so a minimisation started mirrored stays on them."""

import math

import numpy as np
import pytest
import scipy.fft as sfft

import bem_energy as be
import bem_energy.problem as bp
import contact_scene as cs


def scene(shape, profile=None):
    if profile is None:
        return cs.Scene(cs.Indenter(shape), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02))
    loading = cs.Loading(press_approach=0.01)
    return cs.Scene(cs.Indenter(shape, profile), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02), loading)


def mirror_rows(prob):
    nx, _ = prob.n
    M, _ = prob.padded
    return (nx - 1 - np.arange(M)) % M


def mirrored_random(prob, seed=3):
    U = np.random.default_rng(seed).standard_normal(prob.padded)
    return 0.5 * (U + U[mirror_rows(prob)])


def full_products(prob, U):
    """C^-1 U (double and single) and C U (single) by scipy.fft's full transforms."""
    s = prob.padded
    single = U.astype(np.float32)
    return (
        sfft.irfft2(sfft.rfft2(U) * prob.inverse_factor, s=s, norm="forward"),
        sfft.irfft2(sfft.rfft2(single) * prob.inverse_factor_single, s=s, norm="forward").astype(np.float64),
        sfft.irfft2(sfft.rfft2(single) * prob.symbol_factor_single, s=s, norm="forward").astype(np.float64),
    )


def products(prob, U):
    return prob.pressure(U), prob.pressure_single(U), prob.preconditioned(U)


@pytest.mark.parametrize(
    "shape, spacing",
    [(cs.Triangle.equilateral(2.0), 0.05), (cs.Circle(1.0), 0.07), (cs.Rectangle(4.0, 1.0), 0.1)],
    ids=["triangle 90^2", "circle 60^2", "rectangle 96^2"],
)
def test_mirrored_products_take_half_transforms_and_equal_the_full_ones(shape, spacing, count_calls):
    """C^-1 U in double and single precision and C U in single precision of a U that mirrors:
    half transforms, equal to the full ones to their precision's round-off (about eps per level
    of log2(n) levels, as for the full transforms against the exact quotient), mirrored exactly.
    A U off its mirror by one single-precision ulp in one cell takes the full transforms, bit
    for bit."""
    prob = be.build_problem(scene(shape), spacing, None)
    assert prob._mirror is not None
    U = mirrored_random(prob)
    calls = count_calls(bp.EnergyProblem, "_mirrored")
    depth = math.log2(prob.padded[0] * prob.padded[1])
    bounds = [2 * depth * np.finfo(t).eps for t in (np.float64, np.float32, np.float32)]
    rows = mirror_rows(prob)
    for got, expected, bound in zip(products(prob, U), full_products(prob, U), bounds, strict=True):
        assert np.max(np.abs(got - expected)) <= bound * np.max(np.abs(expected))
        assert np.array_equal(got, got[rows])
    assert calls["_mirrored"] == 3
    # single precision in and out (the projected CG's direction arrays)
    out = np.full(prob.padded, np.nan, np.float32)
    assert prob.pressure_single(U.astype(np.float32), out=out) is out
    assert np.array_equal(out, out[rows]) and calls["_mirrored"] == 4
    off = U.copy()
    off[0, 0] = np.nextafter(np.float32(off[0, 0]), np.float32(np.inf))  # off in either precision
    assert not prob._mirrors(off)
    for got, expected in zip(products(prob, off), full_products(prob, off), strict=True):
        assert np.array_equal(got, expected)
    assert calls["_mirrored"] == 4


def test_a_swapped_cosine_transform_fails_the_comparison(monkeypatch):
    """The comparison above catches a wrong half product: a DCT-II in place of the DCT-III
    leaves the product wrong by far more than round-off."""
    prob = be.build_problem(scene(cs.Triangle.equilateral(2.0)), 0.05, None)
    U = mirrored_random(prob)
    real = bp._pocketfft

    class Swapped:
        def __getattr__(self, name):
            return getattr(real, name)

        def dct(self, a, kind, *args):
            return real.dct(a, 2 if kind == 3 else kind, *args)

    monkeypatch.setattr(bp, "_pocketfft", Swapped())
    expected = full_products(prob, U)[0]
    assert np.max(np.abs(prob.pressure(U) - expected)) > 1e-2 * np.max(np.abs(expected))


@pytest.mark.parametrize(
    "shape, profile, spacing",
    [
        (cs.Triangle.equilateral(2.0, rotation_deg=90.0), None, 0.05),  # a corner along the rows' axis
        (cs.Circle(1.0), cs.Paraboloid(4.0, apex=(0.25, 0.0)), 0.07),  # a profile off the mirror
        (cs.Circle(1.0), None, 0.1),  # an odd padded grid (45^2)
    ],
    ids=["rotated triangle", "shifted apex", "odd padded grid"],
)
def test_a_problem_that_does_not_mirror_keeps_the_full_transforms(shape, profile, spacing, monkeypatch):
    prob = be.build_problem(scene(shape, profile), spacing, None)
    assert prob._mirror is None
    monkeypatch.setattr(bp.EnergyProblem, "_mirrored", lambda self, *a: pytest.fail("half transforms"))
    U = np.zeros(prob.padded)  # mirrors whatever the face: only the problem's layout decides
    assert np.array_equal(prob.pressure(U), U)


def test_a_mirrored_pull_stays_mirrored_and_is_the_pull_with_full_transforms(monkeypatch, count_calls):
    """The triangle's pull at a fixed range: every product on the half transforms, the last
    state mirrored exactly, and the pull-off force of the full transforms within the peak
    search's own tolerance (the paths differ at round-off, and the peak is located to that
    tolerance; ``EnergySettings.peak_tolerance``)."""
    rho = 0.05
    sc = cs.Scene(cs.Indenter(cs.Triangle.equilateral(2.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02, rho))
    st = be.EnergySettings(grid=cs.Grid(spacing=0.05))
    calls = count_calls(bp.EnergyProblem, "_mirrored", "_spectrum")
    a = be.solve(sc, st)
    assert calls["_mirrored"] > 100 and calls["_spectrum"] == 0
    monkeypatch.setattr(bp.EnergyProblem, "_mirror_layout", lambda self: None)
    b = be.solve(sc, st)
    assert calls["_spectrum"] > 100
    assert a.converged and b.converged
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=st.peak_tolerance)
