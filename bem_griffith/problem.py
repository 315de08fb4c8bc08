"""The discretised problem: the face on its grid, the half-space operator, the profile and the
critical stress of the local Griffith criterion, fixed for the duration of a solve."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from contact_scene import Homogeneous, PowerLawGraded, Scene, SceneError, rasterise, rasterise_periodic, theory
from contact_scene.discretisation import finest_elements_per_radius
from halfspace.kernel import (
    graded_influence,
    lattice_symbol,
    love_influence,
    love_influence_periodic,
    padded_shape,
    point_kernel_transform,
)
from halfspace.operator import HalfSpaceOperator

from .criterion import stress_factor
from .preconditioner import (
    FourierPreconditioner,
    compact_period,
    fourier_preconditioner,
    inverse_lattice_symbol,
    lattice_inverse_diagonal,
)
from .settings import GriffithSettings
from .windows import WindowMemo, windows_memory_bytes

__all__ = ["Problem", "build_problem", "estimate_memory_gb", "max_elements_per_radius", "SAMPLING_MARGIN"]

#: the factor by which a quantity of the element lattice's symbol, taken from its samples on the
#: padded grid, is widened into a bound: the samples leave out aliases and the frequencies between
#: them (the eigenvalue floor is halved and the energy r.M r doubled; the inverse diagonal has a
#: bound of its own, ``bem_griffith.preconditioner.lattice_inverse_diagonal``)
SAMPLING_MARGIN = 2.0
#: the interval of graded exponents k on which no off-diagonal coefficient of the element
#: lattice's C^-1 is taken to be positive: computed at k = 0, 0.1, 0.25, 0.5, 0.75, 0.9 and 0.95
#: (``tests/test_bem_griffith_ties.py``), not between them; it fails at k = -0.1
WALK_EXPONENTS = (0.0, 0.95)
#: whether problems with the walk property take the preconditioner over a compact period (each
#: product well under half the padded one's cost, for slightly more CG iterations:
#: docs/performance.md); their early decisions bound errors by the residual's largest entry,
#: which needs no r.M r
COMPACT_PRECONDITIONER = True


@dataclass(frozen=True, eq=False, kw_only=True)
class Problem:
    """Everything a solve needs, fixed for its duration.

    operator
        C: face-grid pressures to displacements (FFT convolution).
    face
        Boolean mask [ix, iy] of the grid cells that belong to the face.
    height
        The profile h at the cell centres (zero on a flat face).
    spacing, origin
        Element side Delta and the centre of cell [0, 0].
    critical_stress
        sigma_c of the local Griffith criterion (Eq. 22; graded: Eq. 42, calibrated or not).
    flat
        Whether the profile is flat (then the profile solves are skipped).
    effective_modulus
        E* of a homogeneous body; None for a graded one.
    work_of_adhesion
        w.
    preconditioner
        The Fourier preconditioner of CG (``bem_griffith.preconditioner``), or None: over a
        compact period where ``walk_bounds`` holds (the early decisions' error bounds then come
        from the residual's largest entry, which needs no preconditioner), else over the padded
        grid, where r.M r bounds the energy of CG's error.
    circle_critical_approach
        area -> the critical approach of a circular face of that area (Eq. 14's upper bound;
        Eq. 39's circle for graded bodies); None without adhesion.
    point_kernel
        (A, k) of the point Green's function g(r) = A / r^(1 + k), for the preconditioner.
    windows
        The memo of sub-grid windows, or None when windows are off.
    eigenvalue_floor
        A lower bound on the smallest eigenvalue of every C_SS (half the smallest value of the
        element lattice's symbol, which bounds the spectrum of every finite section of the
        lattice's Toeplitz operator from below); None when unknown.  With it a CG residual r
        bounds the error of the pressures, ||x - x*||_2 <= ||r||_2 / eigenvalue_floor.
    kernel_norm
        The Euclidean norm of all influence coefficients: |(C e)_i| <= kernel_norm ||e||_2 at
        any cell i (Cauchy-Schwarz), which bounds the error of the displacements.
    inverse_diagonal
        An upper bound on every diagonal entry of every C_SS^-1: the mean of the lattice
        symbol's inverse over the Brillouin zone, which is the diagonal D0 of the infinite
        lattice's inverse and bounds that of every finite section from above, sampled finely
        and widened by 1 % (``bem_griffith.preconditioner.lattice_inverse_diagonal``); None
        without the Fourier preconditioner or on a periodic grid.  With it the energy
        norm of a CG iterate's error bounds each pressure's error (``bem_griffith.contact_set``).
    self_influence
        C_00, the displacement of a cell under its own unit pressure: for a cell i outside S,
        c^T C_SS^-1 c < C_00 with c the influences of S on i (the Schur complement of C on S
        and i is positive), which bounds the error of the displacements by the energy norm.
    walk_bounds
        Whether the kernel lies where no off-diagonal coefficient of the infinite element
        lattice's C^-1 is taken to be positive: non-periodic, homogeneous or graded with
        ``WALK_EXPONENTS[0] <= k <= WALK_EXPONENTS[1]``.  Then C^-1 = D0 (I - P), D0 its constant
        diagonal coefficient and P the step matrix of a transient random walk, and for every
        contact set S, C_SS^-1 has no positive off-diagonal entry and positive row sums, so each
        absolute row sum of C_SS^-1 is at most twice its diagonal entry, itself at most D0; and
        for a free cell f the row C_fS C_SS^-1 is the walk's distribution of where it first
        meets S, nonnegative and summing to less than one.  A CG residual r then bounds every
        pressure's error by 2 ``inverse_diagonal`` max |r| (at least 2 D0 max |r|) and every free
        displacement's by max |r|; used with the Fourier preconditioner (docs/methods.md).
    """

    operator: HalfSpaceOperator
    face: np.ndarray
    height: np.ndarray
    spacing: float
    origin: tuple[float, float]
    critical_stress: float
    flat: bool
    effective_modulus: float | None
    work_of_adhesion: float
    preconditioner: FourierPreconditioner | None = None
    circle_critical_approach: Callable[[float], float] | None = None
    point_kernel: tuple[float, float] | None = None
    windows: WindowMemo | None = None
    eigenvalue_floor: float | None = None
    kernel_norm: float = math.inf
    inverse_diagonal: float | None = None
    self_influence: float = math.inf
    walk_bounds: bool = False

    @property
    def cell_area(self) -> float:
        return self.spacing**2

    @property
    def face_elements(self) -> int:
        return int(self.face.sum())


def estimate_memory_gb(nx: int, ny: int) -> float:
    """Working memory of a solve on an nx x ny grid: the padded kernel, its transform and
    scratch, two complex transforms in flight, the preconditioner's circulant (at most on the
    padded grid: kernel, symbol and float32 inverse symbol), the remembered windows and a
    dozen face-grid vectors."""
    padded = 4 * nx * ny
    return (
        padded * 8 * 3 + padded * 16 * 3 + padded * (12 + 2) + windows_memory_bytes(padded) + nx * ny * 8 * 12
    ) / 1e9


def max_elements_per_radius(scene: Scene, max_memory_gb: float | None = None) -> float:
    """The finest grid (elements per equivalent radius) whose memory estimate fits in
    ``max_memory_gb`` (default: :class:`GriffithSettings`' limit), from the face's bounding box."""
    limit = GriffithSettings().max_memory_gb if max_memory_gb is None else max_memory_gb
    return finest_elements_per_radius(scene.indenter.shape, estimate_memory_gb, limit)


def build_problem(scene: Scene, settings: GriffithSettings) -> Problem:
    """Rasterise the face, build the half-space operator and the critical stress; refuse
    grids beyond the memory limit and periodic graded bodies with a SceneError."""
    material = scene.material
    shape = scene.indenter.shape
    periodic = settings.grid.periodic
    if periodic and not isinstance(material, Homogeneous):
        raise SceneError(
            "grid.periodic",
            "the periodic half-space is implemented for homogeneous bodies only "
            "(the graded kernel's image sum needs its own regularisation); use periodic = false",
        )
    h = settings.grid.spacing_for(shape)
    if periodic:
        assert settings.grid.period is not None  # Grid requires the period when periodic
        raster = rasterise_periodic(shape, h, settings.grid.period)
    else:
        raster = rasterise(shape, h)
    nx, ny = raster.shape
    need = estimate_memory_gb(nx, ny) / (4 if periodic else 1)
    if periodic and nx > 1024:
        # the kernel's exact image sum costs 33^2 Love evaluations per coefficient, growing like
        # n^2: minutes beyond 1024^2
        raise SceneError(
            "grid.period",
            f"a periodic cell of {nx} x {ny} elements (> 1024 across) is too large for the "
            "image sum of its kernel; coarsen the grid or shrink the period",
        )
    if need > settings.max_memory_gb:
        raise SceneError(
            "settings.max_memory_gb",
            f"a {nx} x {ny} grid needs about {need:.1f} GB (> {settings.max_memory_gb:g}); "
            "raise max_memory_gb or coarsen the grid",
        )
    w = scene.adhesion.work_of_adhesion
    padded = padded_shape(nx, ny)
    if isinstance(material, Homogeneous):
        E = material.effective_modulus
        kernel = love_influence_periodic(nx, h, E) if periodic else love_influence(nx, ny, h, E, padded)
        sigma_c = theory.critical_stress(E_star=E, work=w, spacing=h)
        circle_approach = (lambda area: theory.upper_bound_approach(E_star=E, work=w, area=area)) if w > 0 else None
        point_kernel = (1.0 / (math.pi * E), 0.0)
    elif isinstance(material, PowerLawGraded):
        E = None
        E0, c0, k = material.surface_modulus, material.reference_depth, material.exponent
        kernel = graded_influence(nx, ny, h, E0, c0, k, padded)
        point_kernel = (theory.graded_green_coefficient(E0=E0, c0=c0, k=k), k)
        sigma_c = theory.graded_critical_stress(E0=E0, c0=c0, k=k, work=w, spacing=h)
        if w > 0:
            sigma_c *= stress_factor(k, settings.graded_criterion)
        circle_approach = (
            (lambda area: theory.graded_critical_approach(E0=E0, c0=c0, k=k, radius=math.sqrt(area / math.pi), work=w))
            if w > 0
            else None
        )
    else:  # pragma: no cover - Scene validates the material
        raise SceneError("material", f"unsupported material {type(material).__name__}")
    operator = HalfSpaceOperator(kernel, (nx, ny), settings.workers, periodic=periodic)
    X, Y = raster.centres()
    height = scene.indenter.profile.height(X, Y)
    inverse = (
        inverse_lattice_symbol(operator.padded_shape, h, point_kernel) if settings.preconditioner == "fourier" else None
    )
    walk_bounds = not periodic and WALK_EXPONENTS[0] <= point_kernel[1] <= WALK_EXPONENTS[1]
    preconditioner = None
    if inverse is not None:
        # without padding a product costs well under half the padded one's, for slightly more CG
        # iterations; its r.M r is no bound, and the walk bounds need none
        preconditioner = (
            fourier_preconditioner(
                (nx, ny), compact_period((nx, ny)), h, point_kernel, padded=False, workers=settings.workers
            )
            if walk_bounds and COMPACT_PRECONDITIONER
            else fourier_preconditioner(
                (nx, ny),
                operator.padded_shape,
                h,
                point_kernel,
                padded=not periodic,
                workers=settings.workers,
                inverse=inverse,
            )
        )
    scale = float(np.abs(kernel).max())
    largest_inverse = None if inverse is None else float(inverse.max())
    # C_00 ~ h / E*: lengths and moduli whose ratio leaves floating point cannot be solved in
    # these units (the single-precision inverse symbol ~ E* / h is checked where it is made,
    # ``inverse_lattice_symbol``)
    if not (0 < scale < math.inf and 0 <= sigma_c < math.inf):
        raise SceneError(
            "material",
            f"the influence coefficients ({scale:.3g} per unit pressure at element side {h:.3g}) or the critical "
            f"stress ({sigma_c:.3g}) leave the floating-point range in these units: rescale lengths and moduli, "
            "e.g. to the face's radius and E*",
        )
    floor = None
    if not periodic:
        # the lattice symbol is positive and smallest at the highest frequencies; the factor 2
        # covers the aliases the sampled symbol leaves out and frequencies between the samples
        if largest_inverse is None:
            transform = point_kernel_transform(point_kernel[1])
            smallest = float(lattice_symbol(operator.padded_shape, h, lambda q: point_kernel[0] * transform(q)).min())
        else:
            smallest = 1.0 / largest_inverse
        floor = smallest / SAMPLING_MARGIN
    return Problem(
        operator=operator,
        face=raster.mask,
        height=np.asarray(height, float),
        spacing=h,
        origin=raster.origin,
        critical_stress=sigma_c,
        flat=scene.indenter.profile.is_flat,
        effective_modulus=E,
        work_of_adhesion=w,
        preconditioner=preconditioner,
        circle_critical_approach=circle_approach,
        point_kernel=point_kernel,
        windows=WindowMemo() if settings.shrink_window and not periodic else None,
        eigenvalue_floor=floor if floor is not None and floor > 0 else None,
        kernel_norm=float(np.sqrt(np.sum(kernel**2))),
        inverse_diagonal=None if inverse is None or periodic else lattice_inverse_diagonal(h, point_kernel),
        self_influence=float(kernel[0, 0]),
        walk_bounds=walk_bounds,
    )
