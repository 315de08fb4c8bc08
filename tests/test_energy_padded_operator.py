"""The energy BEM's padded FFT transforms.

The transforms written into reused buffers must give the same numbers, bit for bit, as
scipy.fft's allocating calls with the same factors (so that reusing buffers is a pure speed
change), and those factors, reciprocals of the symbol with the inverse's 1/n folded in, must
give C^-1 U and C G to the round-off of their precision.
"""

import math

import numpy as np
import pytest
import scipy.fft as sfft

import bem_energy as be
import contact_scene as cs


def scene(shape):
    return cs.Scene(cs.Indenter(shape), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02))


@pytest.mark.parametrize(
    "shape, spacing",
    [(cs.Circle(1.0), 0.1), (cs.Circle(1.0), 0.05), (cs.Triangle.equilateral(2.0), 0.1)],
    ids=["circle 45^2", "circle 90^2", "triangle 45^2"],
)
def test_buffered_transforms_equal_scipy_fft_bit_for_bit(shape, spacing):
    prob = be.build_problem(scene(shape), spacing, None)
    rng = np.random.default_rng(3)
    U = rng.standard_normal(prob.padded)
    s = prob.padded
    expected_pressure = sfft.irfft2(sfft.rfft2(U) * prob.inverse_factor, s=s, norm="forward")
    single = U.astype(np.float32)
    expected_single = sfft.irfft2(sfft.rfft2(single) * prob.inverse_factor_single, s=s, norm="forward")
    expected_single = expected_single.astype(np.float64)
    expected_preconditioned = sfft.irfft2(sfft.rfft2(single) * prob.symbol_factor_single, s=s, norm="forward")
    expected_preconditioned = expected_preconditioned.astype(np.float64)
    # the factors against the quotient and product with the symbol itself
    quotient = sfft.irfft2(sfft.rfft2(U) / prob.symbol, s=s)
    product = sfft.irfft2(sfft.rfft2(U) * prob.symbol, s=s)
    # a transform pair's round-off: about the precision's eps per level of its log2(n) levels
    depth = math.log2(s[0] * s[1])
    double, single_eps = 2 * depth * np.finfo(np.float64).eps, 2 * depth * np.finfo(np.float32).eps
    assert np.max(np.abs(expected_pressure - quotient)) <= double * np.max(np.abs(quotient))
    assert np.max(np.abs(expected_single - quotient)) <= single_eps * np.max(np.abs(quotient))
    assert np.max(np.abs(expected_preconditioned - product)) <= single_eps * np.max(np.abs(product))
    for _ in range(2):  # the second time through reuses the buffers the first one left behind
        assert np.array_equal(prob.pressure(U), expected_pressure)
        assert np.array_equal(prob.pressure_single(U), expected_single)
        assert np.array_equal(prob.preconditioned(U), expected_preconditioned)
        out = np.full(s, np.nan)
        assert prob.pressure_single(U, out=out) is out
        assert np.array_equal(out, expected_single)
        assert prob.preconditioned(U, out=out) is out
        assert np.array_equal(out, expected_preconditioned)
        # single precision in and out (the projected CG's direction arrays): the same numbers
        out_single = np.full(s, np.nan, np.float32)
        assert prob.pressure_single(single, out=out_single) is out_single
        assert np.array_equal(out_single, expected_single)
        assert prob.preconditioned(single, out=out_single) is out_single
        assert np.array_equal(out_single, expected_preconditioned)
    # a result handed out is not a buffer that the next product overwrites
    first = prob.pressure_single(U)
    prob.pressure_single(2 * U)
    assert np.array_equal(first, expected_single)


@pytest.mark.parametrize("single", [True, False])
def test_projected_cg_states_are_its_own_and_consistent(single):
    # the CG reuses work arrays within a minimisation and the problem reuses transform buffers
    # across them: a returned state must keep its values through later minimisations, and its
    # pressure must be C^-1 of its displacement (an array written by two owners would not be)
    rho = 0.08
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02, rho))
    prob = be.build_problem(sc, 1 / 12, be.Potential(0.02, rho, "exponential"))
    U0 = np.zeros(prob.padded)
    first = be.minimise(prob, U0, -0.05, True, method="pk", gtol=1e-8, single_precision_directions=single)
    U, P = first.U.copy(), first.P.copy()
    second = be.minimise(prob, first.U, -0.1, True, method="pk", gtol=1e-8, single_precision_directions=single)
    assert first.converged and second.converged
    assert first.iterations > 5 and second.iterations > 5  # enough iterations to reuse every array
    assert np.array_equal(first.U, U) and np.array_equal(first.P, P)
    for m in (first, second):
        assert np.max(np.abs(m.P - prob.pressure(m.U))) <= 1e-9 * np.max(np.abs(m.P))


@pytest.mark.parametrize("single_precision", [True, False])
def test_directions_work_in_any_units(single_precision):
    # the same dimensionless problem in units of about a nanometre and a gigapascal (or a
    # megapascal), scaled by powers of two so that every rounding scales exactly: the iterates
    # must be the same, scaled.  Without the gradient's power-of-two scaling the
    # single-precision directions' products (about C_00 times the squared gradient) fall below
    # float32's range there, and the conjugate directions degrade silently to steepest descent
    # (more iterations, another minimum within the tolerance); and with double-precision
    # directions the single-precision preconditioner's image of a converging press's gradient
    # underflowed to zero, which left no direction (a division by zero at gtol = 1e-13)
    results = {}
    for a, modulus in ((1.0, 1.0), (2.0**-30, 2.0**30), (2.0**-30, 2.0**20)):
        rho, gtol = 0.0625 * a, 1e-8
        work = 0.015625 * modulus * a
        sc = cs.Scene(cs.Indenter(cs.Circle(a)), cs.Homogeneous(modulus, 0.0), cs.Adhesion(work, rho))
        prob = be.build_problem(sc, a / 16, be.Potential(work, rho, "exponential"))
        options = dict(method="pk", single_precision_directions=single_precision)
        first = be.minimise(prob, np.zeros(prob.padded), -0.0625 * a, True, gtol=gtol, **options)
        second = be.minimise(prob, first.U, -0.125 * a, True, gtol=gtol, **options)
        press = be.minimise(prob, np.zeros(prob.padded), 0.05 * a, False, gtol=1e-13, **options)
        assert first.converged and second.converged and press.converged
        results[a, modulus] = (
            first.iterations,
            second.iterations,
            press.iterations,
            prob.force(second.P) / (modulus * a * a),
            prob.force(press.P) / (modulus * a * a),
        )
    reference = results[1.0, 1.0]
    for result in results.values():
        assert result == reference
