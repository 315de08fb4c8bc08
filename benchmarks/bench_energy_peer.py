"""The energy BEM's finite-range pull-off against ContactMechanics, timed in one run.

The peer is ContactMechanics' free-boundary FFT half-space (``FreeFFTElasticHalfSpace``)
with its companion package Adhesion's exponential potential (``Adhesion.Interactions.
Exponential``, phi = -w exp(-g / rho), our ``bem_energy.Potential``) under a hard wall
(``Adhesion.System.BoundedSmoothContactSystem``), each equilibrium minimised by scipy's
L-BFGS-B through the system's ``minimize_proxy``.  It solves the same discrete problem as
ours with ``kernel="love"``: the same raster of the face, Love's uniformly loaded squares
(Johnson's formula in the peer) and a zero-padded grid of at least 2n - 1 cells per side (2n
in the peer, ``scipy.fft.next_fast_len(2n)`` in ours), so both are the exact non-periodic
half-space and differ only in how each equilibrium is found.

The peer has no pull-off driver of its own, so both runs take the same loading path: our
continuation (``bem_energy.continuation.pull``: uniform steps over the same span, secant warm
starts, bisection of the snap-off to the same tolerance) and our force maximum
(``bem_energy.peak.force_maximum``), with the peer's minimisations in place of ours.  Both
stop a minimisation at the same scaled projected gradient ``gtol`` (the peer's L-BFGS-B with
``pgtol = gtol * cell * rho / C_00`` and ``ftol = 0``, which is ours in its units); what
differs is the minimiser (our projected, Fourier-preconditioned CG against L-BFGS-B) and our
early stop of a trial that peels off (``EnergySettings.stop_peeling_trials``, which a
generic minimiser has no counterpart of).  Ours is timed for the whole ``bem_energy.solve``
(set-up, press and stiffness included); the peer from building its system to the pull-off.
The two alternate, ``--repeat`` times each (3 by default), and the medians of the wall times
are compared, and those of the CPU times (one thread each: on a shared machine the CPU time is
the steadier measure of the work done).

Cases: the circle a = 1, E* = 1, w = 1 / (2 pi) at rho = 0.1 a on 32 elements per radius
(l_c = E* rho^2 / w = 2.0 elements, seconds) by default; ``--large`` adds the issue's case,
rho = 0.05 a on 116 per radius (l_c = 1.8 elements, minutes).

    python benchmarks/bench_energy_peer.py [--large] [--repeat N] [--large-repeat N] [--update]

``--large-repeat`` sets the large case's repeats alone (``--repeat`` by default): its peer
takes minutes of CPU per run.

``--update`` writes docs/performance_energy_peer.json (rendered into the docs by
``python benchmarks/docs_tables.py``).  Without ContactMechanics and Adhesion (the ``peers``
extra) the script says so and exits 0.
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from dataclasses import dataclass

import _timing  # thread settings first
import numpy as np
from _timing import table

import bem_energy as be
import contact_scene as cs
from bem_energy.continuation import LoadingPath, pull
from bem_energy.equilibria import Equilibria
from bem_energy.minimisers import Minimum, unit_ratio
from bem_energy.peak import force_maximum
from bem_energy.problem import EnergyProblem, build_problem
from bem_energy.resolution import critical_approach_scale

try:
    from Adhesion.Interactions import Exponential
    from Adhesion.System import BoundedSmoothContactSystem
    from ContactMechanics import FreeFFTElasticHalfSpace
    from SurfaceTopography import Topography
except ImportError as err:  # the peers extra is optional
    PEER_MISSING: str | None = f"{err}"
else:
    PEER_MISSING = None

#: the work of adhesion of the issue's case, with E* = 1 and a = 1
WORK = 1.0 / (2.0 * math.pi)
#: (name, range rho / a, elements per radius): the default case and the issue's (--large)
CASES = {"small": (0.1, 32.0), "large": (0.05, 116.0)}
#: gaps off the face, in ranges: exp(-FAR) underflows to 0, so the peer's potential acts on the face only
FAR = 1e3


def circle(rho: float) -> cs.Scene:
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(WORK, rho))


def settings(elements_per_radius: float) -> be.EnergySettings:
    """Ours on Love's kernel, the peer's discretisation of the half-space."""
    return be.EnergySettings(grid=cs.Grid(elements_per_radius=elements_per_radius), kernel="love")


class PeerSystem:
    """ContactMechanics' half-space and Adhesion's exponential potential on our problem's face.

    The topography is the raster's n_x x n_y block: the face's profile where the face is (the
    peer's gap u - (heights + offset) is ours, U - (d - h), with heights = -h and offset = d),
    far below elsewhere so that the potential vanishes there; the hard wall bounds the face's
    displacements only.  The peer's displacement grid is 2 n_x x 2 n_y."""

    def __init__(self, prob: EnergyProblem, *, gtol: float, memory: int, max_iterations: int):
        assert prob.potential is not None and prob.potential.kind == "exponential"
        self.prob = prob
        nx, ny = prob.n
        h = prob.spacing
        self.face = prob.face_block
        self.rho = prob.potential.range
        heights = np.full((nx, ny), -FAR * self.rho)
        heights[self.face] = -prob.height
        size = (nx * h, ny * h)
        self.substrate = FreeFFTElasticHalfSpace((nx, ny), prob.modulus, size)
        self.system = BoundedSmoothContactSystem(
            self.substrate, Exponential(prob.potential.work, self.rho), Topography(heights, size)
        )
        self.shape = tuple(self.substrate.nb_subdomain_grid_pts)
        # the physical gradient (cell (P + phi')) at which ours stops: gtol in units of the
        # pressure that displaces one element by rho, capped at a multiple of the adhesive
        # stress (bem_energy.minimisers.projected_gradient, unit_ratio)
        self.unit = prob.cell * self.rho / prob.self_compliance * unit_ratio(prob, self.rho, True)
        self.gtol = gtol
        self.options = dict(gtol=gtol * self.unit, ftol=0.0, maxcor=memory, maxiter=max_iterations)
        self.seconds = 0.0

    def lower_bound(self, d: float) -> np.ndarray:
        nx, ny = self.prob.n
        lb = np.full(self.shape, -np.inf)
        lb[:nx, :ny][self.face] = d - self.prob.height
        return lb

    def minimum(self, U0: np.ndarray, d: float) -> Minimum:
        """The peer's equilibrium at approach d from the warm start U0 (its own grid)."""
        t = time.perf_counter()
        lb = self.lower_bound(d)
        bounds = np.ma.masked_array(lb, mask=~np.isfinite(lb))
        res = self.system.minimize_proxy(offset=d, initial_displacements=U0, lbounds=bounds, options=self.options)
        self.seconds += time.perf_counter() - t
        U = np.asarray(res.x).reshape(self.shape)
        grad = np.asarray(res.jac).reshape(self.shape).copy()
        at_wall = U <= lb + 1e-9 * self.rho
        grad[at_wall] = np.minimum(grad[at_wall], 0.0)
        pg = float(np.abs(grad).max()) / self.unit
        # the force the wall and the potential exert on the punch, per cell: -substrate.force
        P = -self.substrate.force.copy() / self.prob.cell
        ok = pg <= self.gtol
        return Minimum(U, P, float(res.fun), int(res.nit), int(res.nfev), ok, pg, "" if ok else str(res.message))

    def force(self, m: Minimum) -> float:
        nx, ny = self.prob.n
        return float(self.prob.cell * m.P[:nx, :ny][self.face].sum())

    def gap(self, m: Minimum, d: float) -> np.ndarray:
        nx, ny = self.prob.n
        return m.U[:nx, :ny][self.face] - (d - self.prob.height)


class PeerEquilibria(Equilibria):
    """Our loading path's equilibria, found by the peer; counted as ours are."""

    def __init__(self, prob: EnergyProblem, st: be.EnergySettings, face_radius: float, peer: PeerSystem):
        super().__init__(prob, st, face_radius)
        self.peer = peer
        self.peel_fraction = None  # every trial minimised to the end

    def minimum(self, U0, d, adhesive):
        assert adhesive, "the peer runs the adhesive pull only"
        m = self.peer.minimum(U0, d)
        self.work.add(m, d)
        return m

    def pulling_trial(self, U0, d, adhesive):
        return self.minimum(U0, d, adhesive)

    def force(self, m):
        return self.peer.force(m)

    def contact(self, m, d):
        nx, ny = self.prob.n
        at_wall = np.zeros(self.peer.shape, bool)
        at_wall[:nx, :ny][self.peer.face] = self.peer.gap(m, d) <= 1e-9 * self.peer.rho
        return at_wall

    def attached(self, m, d, adhesive):
        return bool(self.peer.gap(m, d).min() < self.peer.rho)


@dataclass
class PeerPullOff:
    force: float
    approach: float
    kind: str
    minimisations: int
    iterations: int
    evaluations: int
    unconverged: int
    worst_gradient: float
    minimise_seconds: float


def peer_pull_off(scene: cs.Scene, st: be.EnergySettings) -> PeerPullOff:
    """The pull-off of ``scene`` along our loading path with the peer's equilibria.

    The same problem and pull as ``bem_energy.pull_off`` of a flat face pressed to d = 0 (the
    pressed state without adhesion is U = 0 there): span, step and snap tolerance as ours."""
    potential = be.Potential(scene.adhesion.work_of_adhesion, scene.adhesion.range)
    h = st.grid.spacing_for(scene.indenter.shape)
    prob = build_problem(scene, h, potential, memory=st.memory, kernel=st.kernel)
    peer = PeerSystem(prob, gtol=st.gtol, memory=st.memory, max_iterations=st.max_iterations)
    eq = PeerEquilibria(prob, st, scene.indenter.shape.equivalent_radius, peer)
    scale = critical_approach_scale(scene)
    rho = potential.range
    d0 = 0.0
    path = LoadingPath(eq)
    m = eq.minimum(np.zeros(peer.shape), d0, True)
    path.record(d0, m)
    span = abs(d0) + 2.0 * scale + 5.0 * rho
    tolerance = st.snap_tolerance * (scale + rho)
    out = pull(
        eq, scene, path, d0, m, True, step=span / st.steps, snap_tolerance=tolerance, max_steps=20 * st.steps + 100
    )
    peak = force_maximum(eq, path, out.snap_off, True, tolerance=tolerance)
    w = eq.work
    return PeerPullOff(
        peak.force,
        peak.approach,
        peak.kind,
        w.minimisations,
        w.iterations,
        w.evaluations,
        w.unconverged,
        w.worst_gradient,
        peer.seconds,
    )


def run_case(name: str, repeat: int):
    rho, N = CASES[name]
    scene, st = circle(rho), settings(N)
    ours_t, peer_t, ours_c, peer_c = [], [], [], []
    ours = peer = None
    for _ in range(repeat):  # alternate, so that both meet the same load on a shared machine
        t, c = time.perf_counter(), time.process_time()
        ours = be.solve(scene, st)
        ours_t.append(time.perf_counter() - t)
        ours_c.append(time.process_time() - c)
        t, c = time.perf_counter(), time.process_time()
        peer = peer_pull_off(scene, st)
        peer_t.append(time.perf_counter() - t)
        peer_c.append(time.process_time() - c)
        print(f"  {name}: ours {ours_t[-1]:.2f} s ({ours_c[-1]:.2f} s CPU)", end=", ")
        print(f"peer {peer_t[-1]:.2f} s ({peer_c[-1]:.2f} s CPU)", flush=True)
    assert ours is not None and peer is not None
    t_o, t_p = statistics.median(ours_t), statistics.median(peer_t)
    c_o, c_p = statistics.median(ours_c), statistics.median(peer_c)
    info = ours.info
    lc = rho**2 / WORK
    row = [
        f"circle, rho = {rho:g} a, l_c = {lc * N:.1f} Delta",
        f"{N:g}",
        "x".join(map(str, info["grid"])),
        repeat,
        f"{t_o:.2f}",
        f"{t_p:.2f}",
        f"{t_p / t_o:.1f}",
        f"{c_p / c_o:.1f}",
        f"{ours.pulloff_force:.7f}",
        f"{peer.force:.7f}",
        f"{peer.force / ours.pulloff_force - 1:+.1e}",
        f"{info['minimisations']} / {peer.minimisations}",
        f"{ours.iterations} / {peer.iterations}",
        f"{info['evaluations']} / {peer.evaluations}",
    ]
    raw = {
        "case": name,
        "repeat": repeat,
        "range": rho,
        "elements_per_radius": N,
        "grid": info["grid"],
        "padded_grid": {"ours": info["padded_grid"], "peer": [2 * n for n in info["grid"]]},
        "seconds": {"ours": ours_t, "peer": peer_t},
        "cpu_seconds": {"ours": ours_c, "peer": peer_c},
        "pulloff_force": {"ours": ours.pulloff_force, "peer": peer.force},
        "pulloff_approach": {"ours": ours.pulloff_approach, "peer": peer.approach},
        "peak": {"ours": info["peak"], "peer": peer.kind},
        "minimisations": {"ours": info["minimisations"], "peer": peer.minimisations},
        "iterations": {"ours": ours.iterations, "peer": peer.iterations},
        "evaluations": {"ours": info["evaluations"], "peer": peer.evaluations},
        "worst_scaled_gradient": {"ours": ours.residual, "peer": peer.worst_gradient},
        "unconverged": {"ours": ours.stats.unconverged, "peer": peer.unconverged},
        "converged": ours.converged,
    }
    print(
        f"  {name}: peaks {info['peak']} / {peer.kind}, worst scaled gradient {ours.residual:.2g} / "
        f"{peer.worst_gradient:.2g}, unconverged {ours.stats.unconverged} / {peer.unconverged}",
        flush=True,
    )
    return row, raw


HEADERS = (
    "case",
    "per radius",
    "grid",
    "runs",
    "ours s",
    "peer s",
    "peer / ours",
    "peer / ours, CPU",
    "ours F_A",
    "peer F_A",
    "peer / ours - 1",
    "minimisations (ours / peer)",
    "iterations (ours / peer)",
    "evaluations (ours / peer)",
)


def main(argv: list[str]) -> int:
    if PEER_MISSING is not None:
        print(f"skipped: the peer is not installed ({PEER_MISSING}); pip install contactmechanics adhesion")
        return 0
    repeat = int(argv[argv.index("--repeat") + 1]) if "--repeat" in argv else 3
    repeats = {
        "small": repeat,
        "large": int(argv[argv.index("--large-repeat") + 1]) if "--large-repeat" in argv else repeat,
    }
    record = _timing.provenance_record()
    names = ["small", "large"] if "--large" in argv else ["small"]
    rows, raws = [], []
    st = settings(32.0)
    print(
        f"ours: projected CG; peer: ContactMechanics + Adhesion, scipy L-BFGS-B (memory {st.memory}); both stop at "
        f"a scaled projected gradient {st.gtol:g}, snap tolerance {st.snap_tolerance:g}, {st.steps} steps; "
        f"median of {repeats}, alternating",
        flush=True,
    )
    tolerances = {"gtol": st.gtol, "snap_tolerance": st.snap_tolerance, "steps": st.steps, "memory": st.memory}
    for name in names:
        row, raw = run_case(name, repeats[name])
        rows.append(row)
        raws.append(raw)
        print(table(rows, HEADERS), flush=True)
        if "--update" in argv:  # after each case: a long --large run keeps the cases it finished
            _timing.write_doc_table("performance_energy_peer", HEADERS, rows, record, cases=raws, tolerances=tolerances)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
