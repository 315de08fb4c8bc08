"""The force maximum of a pull (``bem_energy.peak``) on synthetic attached branches.

A fake set of equilibria stands in for the minimiser: attached states exist for d >= d_fold
and their force is a given function of d, so that what the snap-off search and Brent find can
be compared with the exact maximum.  Two branch shapes occur in the energy BEM: a smooth
maximum shortly before the snap-off (finite range, peeling edge) and a tension still rising
steeply into a fold, F - F* ~ sqrt(d - d*).  The force tolerance may stop the search early
only on the first; on the second the bisection must run to the approach tolerance as before.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from bem_energy import peak
from bem_energy.continuation import LoadingPath


@dataclass
class FakeMinimum:
    U: np.ndarray
    force: float
    attached: bool


class Branch:
    """Attached states for d >= d_fold with force ``F(d)`` (negative: tension); counts the
    trials and where they were made."""

    def __init__(self, F, d_fold):
        self.F, self.d_fold = F, d_fold
        self.trials: list[float] = []

    def state(self, d):
        attached = d >= self.d_fold
        return FakeMinimum(np.zeros(1), self.F(d) if attached else 0.0, attached)

    def pulling_trial(self, U0, d, adhesive):
        self.trials.append(d)
        return self.state(d)

    def minimum(self, U0, d, adhesive):
        self.trials.append(d)
        return self.state(d)

    def attached(self, m, d, adhesive):
        return m.attached

    def force(self, m):
        return m.force

    def contact_area(self, m, d):
        return 1.0 if m.attached else 0.0


def pull(branch: Branch, d_start, step, *, tolerance, locate_detachment=False, force_tolerance=None):
    """Continuation in steps of ``step`` from ``d_start`` down to the first detached state, then
    the snap-off search and the force maximum, as ``bem_energy.continuation.pull`` does."""
    path = LoadingPath(branch)
    d = d_start
    m = branch.state(d)
    path.record(d, m)
    while True:
        d_next = d - step
        m_next = branch.pulling_trial(m.U, d_next, True)
        if not m_next.attached:
            snap = peak.locate_snap_off(
                branch,
                path,
                d,
                m,
                d_next,
                m_next,
                True,
                tolerance=tolerance,
                locate_detachment=locate_detachment,
                force_tolerance=force_tolerance,
            )
            path.record(snap.detached_approach, snap.detached_state, False)
            break
        path.record(d_next, m_next)
        d, m = d_next, m_next
    n_path = len(branch.trials)
    point = peak.force_maximum(branch, path, snap, True, tolerance=tolerance, force_tolerance=force_tolerance)
    return point, snap, n_path


# a smooth maximum of tension 1 at d = -1.01, between two continuation steps, just before
# the snap-off at d = -1.0103 (the circle's finest range looks like this: the tension
# flattens, then the branch ends)
def smooth(d):
    return -(1.0 - 2.0 * (d + 1.01) ** 2)


SMOOTH_FOLD = -1.0103
# a tension rising into a fold at d* = -1.013 (F* = -1, between two continuation steps), as
# toward the zero-range snap-off
FOLD = -1.013


def rising(d):
    x = max(d - FOLD, 0.0)
    return -(1.0 - 0.5 * math.sqrt(x) - 2.0 * x)  # d(F) is a parabola only near the fold


STEP, TOL = 0.05, 1e-4


@pytest.mark.parametrize("force_tolerance", [1e-4, 3e-4, 1e-3])
def test_a_flattening_maximum_is_found_to_the_force_tolerance_with_fewer_trials(force_tolerance):
    """Smooth maximum just before the snap-off: with the force tolerance the search ends on
    the tangent bound of the concave tension, the largest tension found lies within that
    fraction of the true one (1 here), and it takes fewer trials than bisecting the approach."""
    exact = 1.0
    plain = Branch(smooth, SMOOTH_FOLD)
    p0, _, _ = pull(plain, -0.6, STEP, tolerance=TOL)
    fast = Branch(smooth, SMOOTH_FOLD)
    p1, _, _ = pull(fast, -0.6, STEP, tolerance=TOL, force_tolerance=force_tolerance)
    assert p0.force == pytest.approx(exact, rel=1e-6)
    assert exact * (1 - force_tolerance) <= p1.force <= exact * (1 + 1e-12)
    assert len(fast.trials) < len(plain.trials)


def test_a_rising_fold_is_still_bisected_to_the_approach_tolerance():
    """Tension rising steeply into a fold: the last points do not flatten, so the force
    tolerance changes nothing, trial for trial (the tangent bound would not hold there: a
    bound from the last secant slope would stop with the fold's last 0.5 sqrt(width) missed)."""
    plain = Branch(rising, FOLD)
    p0, s0, _ = pull(plain, -0.6, STEP, tolerance=TOL)
    fast = Branch(rising, FOLD)
    p1, s1, _ = pull(fast, -0.6, STEP, tolerance=TOL, force_tolerance=1e-3)
    assert fast.trials == plain.trials
    assert p1 == p0
    assert s1.attached_approach - s1.detached_approach <= TOL
    assert p1.force == pytest.approx(1.0, abs=0.5 * math.sqrt(TOL))


def test_the_bound_without_the_flattening_check_misses_a_fold(monkeypatch):
    """The mutant the flattening check guards against: taking the last secant slope as a
    bound whatever the shape stops the search while the tension still rises toward the fold,
    and the force falls short of the bisected one by more than twice the tolerance."""
    p0, _, _ = pull(Branch(rising, FOLD), -0.6, STEP, tolerance=TOL)
    monkeypatch.setattr(peak, "FLATTENING", math.inf)
    p1, _, _ = pull(Branch(rising, FOLD), -0.6, STEP, tolerance=TOL, force_tolerance=1e-3)
    assert p1.force < p0.force * (1 - 2e-3)


def test_flattening_slope():
    """The last secant slope of the tension, only where it has fallen below half the one
    before it (pulling lowers d; forces are negative in tension)."""
    assert peak.flattening_slope([(0.0, -1.0), (-1.0, -2.0), (-2.0, -2.2)]) == pytest.approx(0.2)
    assert peak.flattening_slope([(0.0, -1.0), (-1.0, -2.0), (-2.0, -2.6)]) is None  # 0.6 of the slope before
    assert peak.flattening_slope([(0.0, -1.0), (-1.0, -2.0), (-2.0, -1.5)]) == 0.0  # past the maximum
    assert peak.flattening_slope([(-1.0, -2.0), (-2.0, -2.2)]) is None  # two points: no shape


def test_brent_tolerance_is_the_distance_at_which_the_parabola_loses_the_force_tolerance():
    """For a recorded parabola F = -A (1 - c (d - d0)^2), sampled unevenly and off its
    vertex, the distance at which it loses a fraction f of the middle point's tension is
    sqrt(f |F_1| / (A c)); never below the approach tolerance."""
    A, c, d0, f = 2.5, 3.0, -0.47, 2e-4

    class Path:
        approach = [-0.4, -0.5, -0.62]
        force = [-A * (1 - c * (x - d0) ** 2) for x in approach]

        class largest:
            index = 1

        def __len__(self):
            return 3

    expected = math.sqrt(f * abs(Path.force[1]) / (A * c))
    assert peak.brent_tolerance(Path(), 1e-6, f) == pytest.approx(expected, rel=1e-9)
    assert peak.brent_tolerance(Path(), 1.0, f) == 1.0
    assert peak.brent_tolerance(Path(), 1e-6, None) == 1e-6
    Path.approach = [-0.4, -0.5, -0.4]  # a turning point: no parabola
    assert peak.brent_tolerance(Path(), 1e-6, f) == 1e-6


# a maximum that the search meets only after its first chance to stop: the first attached
# point it adds (d = -1.0125) lies 4.5e-4 below the maximum of 1 at d = -1.02, which is just
# before the snap-off at -1.0205
def sharp(d):
    return -(1.0 - 8.0 * (d + 1.02) ** 2)


SHARP_FOLD = -1.0205


@pytest.mark.parametrize("force_tolerance", [1e-4, 3e-4])
def test_the_search_stops_only_within_the_tolerance_and_its_placed_trials_pay(force_tolerance, monkeypatch):
    """The tangent bound, not the first flattening, ends the search: the force lies within the
    tolerance of the maximum although the first flattening point does not (a wrong bound, one
    that stopped there, is caught); and placing the trials where the bound would be met takes
    fewer trials than halving the bracket under the same bound."""
    assert 1.0 + sharp(-1.0125) > force_tolerance  # the first chance to stop is too early
    placed = Branch(sharp, SHARP_FOLD)
    p, _, _ = pull(placed, -0.6, STEP, tolerance=TOL, force_tolerance=force_tolerance)
    assert 1.0 - force_tolerance <= p.force <= 1.0 + 1e-12
    monkeypatch.setattr(peak, "CLOSEST", math.inf)  # every trial halfway
    halved = Branch(sharp, SHARP_FOLD)
    p_halved, _, _ = pull(halved, -0.6, STEP, tolerance=TOL, force_tolerance=force_tolerance)
    assert 1.0 - force_tolerance <= p_halved.force
    assert len(placed.trials) < len(halved.trials)


def test_brent_stops_at_the_force_tolerance_with_fewer_trials():
    """A smooth maximum bracketed by attached continuation states (the snap-off far beyond):
    with the force tolerance Brent's trials end within 4/9 of it of the maximum (1, at
    d = -0.98, between two steps; a cubic term keeps the parabolic steps from being exact),
    in fewer trials than to the approach tolerance."""

    def bent(d):
        x = d + 0.98
        return -(1.0 - 3.0 * x**2 + 0.5 * x**3)

    ftol = 3e-4
    counts = []
    for force_tolerance in (None, ftol):
        branch = Branch(bent, -1.3)
        p, _, n_path = pull(branch, -0.6, STEP, tolerance=TOL, force_tolerance=force_tolerance)
        assert p.kind == "refined"
        assert 1.0 - 4 / 9 * ftol <= p.force <= 1.0 + 1e-12
        counts.append(len(branch.trials) - n_path)
    assert counts[1] < counts[0]


class CurvedBranch(Branch):
    """A branch whose state is U = (d, d^2): a secant predicts a state only approximately, and
    which two states it goes through shows in the prediction; records each trial's warm start."""

    def __init__(self, F, d_fold):
        super().__init__(F, d_fold)
        self.starts: list[tuple[float, np.ndarray]] = []

    def state(self, d):
        m = super().state(d)
        return FakeMinimum(np.array([d, d * d]), m.force, m.attached)

    def pulling_trial(self, U0, d, adhesive):
        self.starts.append((d, np.array(U0, float)))
        return super().pulling_trial(U0, d, adhesive)


def test_snap_off_trials_start_from_the_secant_through_the_last_two_attached_states():
    """Each trial of the search starts where the line through the last two attached states
    puts it (as the continuation's steps do); without the state before the bracket (the
    first step of a pull) the first trial starts from the last attached state."""
    branch = CurvedBranch(rising, FOLD)
    path = LoadingPath(branch)
    d_prev, d_att, d_det = FOLD + 2 * STEP, FOLD + STEP, FOLD - 0.5 * STEP
    path.record(d_prev, branch.state(d_prev))
    path.record(d_att, branch.state(d_att))
    snap = peak.locate_snap_off(
        branch,
        path,
        d_att,
        branch.state(d_att),
        d_det,
        branch.state(d_det),
        True,
        tolerance=TOL,
        previous=(d_prev, branch.state(d_prev).U),
    )
    assert snap.attached_approach - snap.detached_approach <= TOL
    # replay the search: the attached states in the order it found them
    attached = [d_prev, d_att]
    for d, start in branch.starts:
        d0, d1 = attached[-2], attached[-1]
        U0, U1 = branch.state(d0).U, branch.state(d1).U
        assert start == pytest.approx(U1 + (U1 - U0) * ((d - d1) / (d1 - d0)), rel=1e-12, abs=1e-15)
        if d >= FOLD:
            attached.append(d)
    assert len(attached) >= 5  # the secant moved with the bracket several times
    branch.starts.clear()
    peak.locate_snap_off(branch, path, d_att, branch.state(d_att), d_det, branch.state(d_det), True, tolerance=TOL)
    assert np.array_equal(branch.starts[0][1], branch.state(d_att).U)
