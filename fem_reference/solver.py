"""The FEM reference for circular flat punches: stiffness, energy release rate and pull-off.

Solved once, dimensionless, for u_z = 1 on the unit face; then scaled:
homogeneous K = E a K^ (E Young's modulus), graded K = E0 (a/c0)^k a K^.

Energy release rate at the punch edge, two ways (cross-checked in the result):
* stiffness derivative (virtual crack extension): nodes within 0.25 a of the edge slide
  radially with the edge (blending to rest at 0.5 a); at fixed displacement data
  dU/da = (1/2) x^T (dM/da) x with the same solution x (stationarity), so no re-solve;
* compliance derivative: K(a +- delta) re-solved on the two moved meshes.
Griffith (G = w, Eqs. 4-6 and 36-40): d_c = -sqrt(4 pi a w / K'(a)), F_A = K(a) |d_c|.

Error estimate: the unit problem is solved again one polynomial degree lower on the same mesh;
the change, scaled by the measured per-degree error ratio, plus the domain truncation, bounds
the relative errors of K, F_A and d_c (:func:`error_estimates`; ``Result.error_bars``,
``accuracy_estimate`` their largest).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import os
import time
from dataclasses import dataclass

import numpy as np
from skfem import MeshTri

from contact_scene import Circle, Curve, ErrorBar, Homogeneous, PowerLawGraded, Result, Scene, SceneError, SolverStats
from contact_scene.errors import check_type
from contact_scene.result import zero_range_note
from contact_scene.validation import check_fields, choice, flag, real, whole

from .model import (
    FACTOR_ENTRY_BYTES,
    KERNELS,
    SOLVE_TOLERANCE,
    Material,
    Model,
    assemble,
    bases,
    build_mesh,
    build_tensor_mesh,
    local_saddle_matrices,
    saddle_matrix,
    solve_unit_approach,
    unknowns,
)

__all__ = [
    "FemSettings",
    "estimate_memory_gb",
    "solve",
    "solve_with_resolution",
    "unit_solution",
    "UnitSolution",
]

log = logging.getLogger("fem_reference")


#: the working memory a solve may take by default (``FemSettings.max_memory_gb``), as
#: :data:`bem_energy.problem.MAX_MEMORY_GB`
MAX_MEMORY_GB = 8.0

#: the gradings ``FemSettings`` accepts
GRADING_RANGE = (0.05, 4.0)


@dataclass(frozen=True)
class FemSettings:
    """Mesh and element settings.

    Parameters
    ----------
    grading : float, optional
        Element diameter at most ``grading`` x its distance from the punch edge (smaller is
        finer), in [0.05, 4]; 1 by default.  ``crossval solve --resolution N`` sets
        grading = 1/N.  At most 2 for a homogeneous body (see :func:`build`; a larger one is
        refused when solving).  For a graded body (k > 0) the mesh is a tensor product whose
        cells grow by the factor 1 + grading away from the edge line and the surface (see
        :func:`fem_reference.model.build_tensor_mesh`).
    order : int, optional
        Polynomial degree of the displacement (Taylor-Hood: pressure one lower), in [2, 4]; 4
        by default: the convergence study (benchmarks/study_fem.py) reaches 1e-5 at a fraction
        of the cost of degree 2.
    domain_radius : float, optional
        Truncation, in punch radii, in [16, 2^40]; 2^20 by default: the far boundary is clamped
        there (error about a/L).
    h_min : float, optional
        Smallest element at the edge, in punch radii, in [1e-12, 0.1]; 1e-5 by default.
    vce_radius : float, optional
        r1 of the virtual crack extension, in punch radii, in [0.01, 0.5]; 0.25 by default:
        nodes within r1 of the punch edge slide radially with the edge, blending to rest at
        2 r1.
    compliance_check : bool, optional
        Also compute dK/da by re-solving on the two moved meshes (doubles the cost); it
        agrees with the stiffness derivative to about 1e-6 (graded k = 0.25, grading 2), the
        precision of two solves' difference over 2e-4 a.  False by default.
    max_memory_gb : float, optional
        The working memory a solve may take, in GB, > 0; :data:`MAX_MEMORY_GB` (8) by default.
        A mesh whose estimated factorisation (:func:`estimate_memory_gb`) needs more is refused
        before assembly, naming ``fem.grading`` and the gradings that fit; a fall-back
        factorisation that might not fit is not tried (the solve's residual is then reported).
    fields_path : str or None, optional
        Where to write the displacement and pressure at pull-off (VTU or XDMF, by meshio)
        when the scene asks for fields; None by default (then a scene asking for fields is
        refused when solving).
    kernels : str, optional
        ``"vectorised"`` (default): element matrices from batched products of precomputed
        strains, a nested-dissection elimination order and diagonal pivots
        (:func:`fem_reference.model.nested_dissection`).  ``"scikit-fem"``: scikit-fem's
        ``asm`` of the weak forms and SuperLU's default ordering with threshold pivoting, the
        plain statement of the same discretisation, several times slower; both give the same
        matrices to rounding and the same answers to the solve's precision
        (``benchmarks/bench_fem.py`` runs them side by side).

    Raises
    ------
    contact_scene.SceneError
        Naming ``fem.<field>`` and its allowed values, for a value outside them;
        ``fem.fields_path`` for a path that does not end in .vtu or .xdmf.
    """

    grading: float = real(1.0, ge=GRADING_RANGE[0], le=GRADING_RANGE[1])
    order: int = whole(4, ge=2, le=4)
    domain_radius: float = real(2.0**20, ge=16.0, le=2.0**40)
    h_min: float = real(1e-5, ge=1e-12, le=0.1)
    vce_radius: float = real(0.25, ge=0.01, le=0.5)
    compliance_check: bool = flag(False)
    max_memory_gb: float = real(MAX_MEMORY_GB, gt=0.0)
    fields_path: str | None = None
    kernels: str = choice("vectorised", KERNELS)

    def __post_init__(self):
        check_fields(self, "fem")
        path = self.fields_path
        # checked here, not after the solve that would write it
        if path is not None and (
            not isinstance(path, (str, os.PathLike)) or os.path.splitext(str(path))[1].lower() not in FIELD_FORMATS
        ):
            raise SceneError("fem.fields_path", f"must be a path ending in {' or '.join(FIELD_FORMATS)} (got {path!r})")


#: entries of the nested-dissection LU factors per n log2(n) unknowns n: 15.5, 16.0, 16.3,
#: 16.4 measured on tensor meshes of 91,000 - 546,000 unknowns (degree 4, k = 0.05 and 0.25)
#: and 14.3, 16.9 on the isotropic mesh (nu = 0.3, grading 2, 1)
FACTOR_ENTRIES_PER_N_LOG_N = 17.0


def estimate_memory_gb(mesh: MeshTri, order: int) -> float:
    """Working memory of the solve of degree ``order`` on ``mesh``, in GB: the LU factors
    dominate (:data:`FACTOR_ENTRIES_PER_N_LOG_N`, at
    :data:`fem_reference.model.FACTOR_ENTRY_BYTES` each)."""
    n = unknowns(mesh, order)
    return FACTOR_ENTRIES_PER_N_LOG_N * n * math.log2(n) * FACTOR_ENTRY_BYTES / 1e9


def _fits(material: Material, settings: FemSettings, grading: float) -> bool:
    mesh = build(material, dataclasses.replace(settings, grading=grading))
    return estimate_memory_gb(mesh, settings.order) <= settings.max_memory_gb


def _finest_above(material: Material, settings: FemSettings) -> float | None:
    """The smallest grading, to 1 %, above ``settings.grading`` whose mesh
    :func:`estimate_memory_gb` fits in ``settings.max_memory_gb`` (the estimate grows as the
    grading shrinks); None when not even the coarsest allowed one fits."""
    # bisection between settings.grading, which does not fit, and the coarsest allowed grading;
    # the fine end is never rebuilt (an isotropic mesh at grading 0.05 takes half a minute)
    lo, hi = settings.grading, GRADING_RANGE[1] if material.mapping != 1.0 else MAX_ISOTROPIC_GRADING
    if not _fits(material, settings, hi):
        return None
    while hi / lo > 1.01:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if _fits(material, settings, mid) else (mid, hi)
    return hi


#: the file formats the fields are written in (by meshio)
FIELD_FORMATS = (".vtu", ".xdmf")


@dataclass(frozen=True, eq=False)
class UnitSolution:
    """Dimensionless results for a = 1, unit modulus scale, d = 1.

    A scene's values follow by scaling (see the module): K = S a K^, dK/da = S dK^/da, with
    S = E (homogeneous) or E0 (a/c0)^k (graded).

    Attributes
    ----------
    stiffness : float
        K^, from the energy form x^T M x.
    stiffness_reaction : float
        K^ from the reaction force on the punch (a check on the energy form).
    dK_vce : float
        dK^/da by the stiffness derivative (virtual crack extension); NaN when the energy
        release rate was not asked for.
    dK_compliance : float or None
        dK^/da by re-solving on the two moved meshes, when ``FemSettings.compliance_check``
        asks for it; None otherwise.
    dofs : int
        Degrees of freedom of the saddle-point system.
    elements : int
        Triangles of the mesh.
    timings : dict
        Wall time of each phase (mesh, solve, energy release, compliance check), in seconds.
    mesh : skfem.MeshTri or None
        The mesh, kept when the energy release rate was computed (for the error estimate and
        the fields); None otherwise.
    model : fem_reference.model.Model or None
        The assembled model, likewise.
    x : numpy.ndarray or None
        The solution vector (displacement, then pressure degrees of freedom), likewise.
    residual : float
        The largest relative residual of the linear solves.
    """

    stiffness: float
    stiffness_reaction: float
    dK_vce: float
    dK_compliance: float | None
    dofs: int
    elements: int
    timings: dict
    mesh: MeshTri | None = None
    model: Model | None = None
    x: np.ndarray | None = None
    residual: float = 0.0


def write_fields(path: str, u: UnitSolution, *, radius: float, approach: float, modulus_scale: float) -> None:
    """Displacement (u_r, u_z) and pressure at approach ``approach`` on the mesh vertices,
    in the scene's units (lengths scaled by the punch radius), written with meshio."""
    import meshio

    model, x, mesh = u.model, u.x, u.mesh
    if model is None or x is None or mesh is None:
        raise ValueError("write_fields needs a UnitSolution with its model, solution and mesh (energy_release=True)")
    nu_dofs = model.ub.N
    m = model.material.mapping
    ur = x[model.ub.nodal_dofs[0]] * approach
    uz = x[model.ub.nodal_dofs[1]] * approach
    p = x[nu_dofs + model.pb.nodal_dofs[0]] * approach * modulus_scale
    pts = np.column_stack([mesh.p[0] * radius, (mesh.p[1] ** m) * radius])
    meshio.write(path, meshio.Mesh(pts, [("triangle", mesh.t.T)], point_data={"u_r": ur, "u_z": uz, "pressure": p}))


def _energy(M, x) -> float:
    # x^T M x with numpy's pairwise sum, not a threaded BLAS dot: bit-identical whatever the
    # thread count (serial, worker processes and cluster runs agree)
    return float(np.add.reduce(x * (M @ x)))


def _shift(mesh: MeshTri, r1: float, mapping: float = 1.0) -> np.ndarray:
    """Virtual extension field: 1 within r1 of the punch edge, down to 0 at 2 r1, in physical
    distance (zeta^m is the depth; with mapped distance the field of k = 0.9 was a skin
    z < 1e-6 deep and F_A came out 1e-3 off while K was right to 2e-6)."""
    rho = np.hypot(mesh.p[0] - 1.0, mesh.p[1] ** mapping)
    return np.clip((2 * r1 - rho) / r1, 0.0, 1.0)


def _moved(mesh: MeshTri, delta: float, q: np.ndarray) -> MeshTri:
    p = mesh.p.copy()
    p[0] = p[0] + delta * q
    return MeshTri(p, mesh.t)


def build(material: Material, settings: FemSettings) -> MeshTri:
    """The mesh of ``settings`` for ``material``: tensor-product for a graded body, else isotropic.

    The isotropic mesh stops refining the elements that touch the punch edge once the grading
    reaches about 3 (such an element's centroid is a third of its size from the edge): K is
    then 1e-2 off (nu = 0.3: 7.8e-5 at grading 2.5, 1.4e-2 at 3) and converges too slowly in
    the degree for the error estimate; hence grading <= 2 there."""
    if material.mapping == 1.0 and settings.grading > MAX_ISOTROPIC_GRADING:
        raise SceneError(
            "fem.grading",
            f"a homogeneous body's mesh needs grading <= {MAX_ISOTROPIC_GRADING:g} "
            f"(coarser ones leave the punch edge unresolved); got {settings.grading:g}",
        )
    if material.mapping != 1.0:
        return build_tensor_mesh(
            domain=settings.domain_radius, ratio=1.0 + settings.grading, h_min=settings.h_min, mapping=material.mapping
        )
    return build_mesh(
        domain=settings.domain_radius, grading=settings.grading, h_min=settings.h_min, h_max_near=settings.grading
    )


def unit_solution(
    material: Material, settings: FemSettings, *, energy_release: bool = True, mesh: MeshTri | None = None
) -> UnitSolution:
    """The unit problem on ``mesh`` (default: :func:`build` of ``settings``).

    Parameters
    ----------
    material : fem_reference.model.Material
        The dimensionless material: exponent k in [0, 1 - 1e-9] (see :func:`applies`) and
        Poisson's ratio.
    settings : FemSettings
        Mesh, degree and kernels.
    energy_release : bool, optional
        Also compute dK^/da by the stiffness derivative (and by the compliance derivative when
        ``settings.compliance_check``); True by default.  False gives the stiffness alone.
    mesh : skfem.MeshTri or None, optional
        The mesh to solve on; by default :func:`build` of ``settings``.

    Returns
    -------
    UnitSolution
        The dimensionless stiffness, its derivative and the solve's residual.

    Raises
    ------
    contact_scene.SceneError
        ``fem.grading`` when building the mesh of a homogeneous body with grading > 2, or
        for a mesh whose estimated memory (:func:`estimate_memory_gb`) exceeds
        ``settings.max_memory_gb`` (the message names the gradings that fit).
    """
    t0 = time.perf_counter()
    log.info("meshing (grading %g)", settings.grading)
    mesh = build(material, settings) if mesh is None else mesh
    need = estimate_memory_gb(mesh, settings.order)
    if need > settings.max_memory_gb:
        # refused before the assembly: a factorisation past the machine's memory does not fail
        # cleanly, it swaps or is killed
        finest = _finest_above(material, settings)
        allowed = (
            f"gradings >= {finest:.3g} fit"
            if finest is not None
            else "no allowed grading fits: raise fem.max_memory_gb or fem.h_min"
        )
        raise SceneError(
            "fem.grading",
            f"the mesh of grading {settings.grading:g} has {unknowns(mesh, settings.order):,} unknowns, "
            f"an estimated {need:.1f} GB to factorise, more than fem.max_memory_gb = {settings.max_memory_gb:g}; "
            f"for this material, order and h_min {allowed}",
        )
    t1 = time.perf_counter()
    log.info("assembling and solving: %d elements of degree %d", mesh.t.shape[1], settings.order)
    model = assemble(mesh, material, order=settings.order, kernels=settings.kernels)
    x, residual = solve_unit_approach(model, kernels=settings.kernels, max_memory_gb=settings.max_memory_gb)
    t2 = time.perf_counter()
    Mx = model.M @ x
    K = 2 * math.pi * float(np.add.reduce(x * Mx))  # the pairwise sum of _energy
    K_react = 2 * math.pi * float(np.add.reduce(Mx[model.punch]))
    if not energy_release:
        return UnitSolution(
            K,
            K_react,
            math.nan,
            None,
            model.M.shape[0],
            mesh.t.shape[1],
            {"mesh": t1 - t0, "solve": t2 - t1},
            residual=residual,
        )
    delta = 1e-4
    # only elements with a moved vertex change, so dM/da is assembled on those alone
    q = _shift(mesh, settings.vce_radius, material.mapping)
    moved = np.flatnonzero((q[mesh.t] > 0).any(axis=0))
    if settings.kernels == "vectorised":
        # x^T (dM/da) x element by element: no global matrix for the moved elements
        Kp, dofs = local_saddle_matrices(*bases(_moved(mesh, delta, q), settings.order, None, moved), material)
        Km, _ = local_saddle_matrices(*bases(_moved(mesh, -delta, q), settings.order, None, moved), material)
        xe = x[dofs.T]
        dK_vce = 2 * math.pi * float(np.add.reduce(np.einsum("ea,eab,eb->e", xe, Kp - Km, xe))) / (2 * delta)
    else:
        Mp, _, _ = saddle_matrix(
            _moved(mesh, delta, q), material, order=settings.order, elements=moved, kernels=settings.kernels
        )
        Mm, _, _ = saddle_matrix(
            _moved(mesh, -delta, q), material, order=settings.order, elements=moved, kernels=settings.kernels
        )
        dK_vce = 2 * math.pi * _energy(Mp - Mm, x) / (2 * delta)
    t3 = time.perf_counter()
    timings = {"mesh": t1 - t0, "solve": t2 - t1, "energy_release": t3 - t2}
    dK_c = None
    if settings.compliance_check:
        plus = assemble(
            _moved(mesh, delta, q), material, order=settings.order, face_radius=1 + delta, kernels=settings.kernels
        )
        minus = assemble(
            _moved(mesh, -delta, q), material, order=settings.order, face_radius=1 - delta, kernels=settings.kernels
        )
        (xp, rp), (xm, rm) = (
            solve_unit_approach(m, kernels=settings.kernels, max_memory_gb=settings.max_memory_gb)
            for m in (plus, minus)
        )
        residual = max(residual, rp, rm)
        dK_c = 2 * math.pi * (_energy(plus.M, xp) - _energy(minus.M, xm)) / (2 * delta)
        timings["compliance_check"] = time.perf_counter() - t3
    return UnitSolution(
        K, K_react, dK_vce, dK_c, model.M.shape[0], mesh.t.shape[1], timings, mesh, model, x, residual=residual
    )


# The error estimate compares the solution with the one of the neighbouring polynomial degree on
# the same mesh.  On these meshes, graded geometrically toward the punch edge, the error falls by
# a nearly constant factor rho per degree (exponential convergence in p), so the difference D of
# the two solutions gives the error of degree p as D / (rho - 1) (neighbour p - 1) or
# D rho / (rho - 1) (neighbour p + 1).  A rho below the true one overstates the error, so
# the smallest measured factor is used, rounded down (benchmarks/study_fem.py, columns rho:
# errors of K and K' against Eqs. 1 and 34):
#   isotropic mesh (homogeneous), degree 3 -> 4: 13.0 - 21.1 over nu = -0.5, 0, 0.3, 0.5 at
#     grading 1 and 2: rho = 11; degree 2 -> 3: 19.2 - 28.8 (nu = 0, 0.3, 0.5): rho = 16.
#   tensor mesh (graded), degree 3 -> 4: rho x grading = 9.2 - 14.6 over k = 0.25, 0.5, 0.75,
#     0.9 at grading 1, 2, 3, 4 (cells grow by 1 + grading, so one more degree gains about as
#     much as the cell is small against its distance from the edge; 11.6 - 14.6 at grading
#     2 - 4, 9.2 - 11.0 at grading 1, the lowest K' at k = 0.75): rho = 8 / grading;
#     degree 2 -> 3: rho x grading = 11.9 - 18.2 (k = 0.5, 0.9 at grading 2, 4): the same.
#   Below grading 1 the factor is held at its grading-1 value: it only grows as cells shrink,
#   so the estimate stays a bound there (and overstates the error more).
# With these, accuracy_estimate / largest error of (K, F_A, d_c) = 2.0 - 4.6 over the study's
# cases (homogeneous at grading 1, 2; graded at 1, 2, 4); each bound / its own error
# 1.2 - 2.6 for K and d_c (F_A's error is a near-cancellation of theirs, its bound their sum).
_RHO_ISOTROPIC = {(4, 3): 11.0, (3, 2): 16.0}
_RHO_TENSOR = {(4, 3): 8.0, (3, 2): 8.0}
MAX_ISOTROPIC_GRADING = 2.0


def order_ratio(material: Material, grading: float, high: int, low: int) -> float:
    """The error ratio rho between degrees ``low`` and ``high`` assumed by :func:`error_estimates`."""
    if material.mapping == 1.0:
        return _RHO_ISOTROPIC[(high, low)]
    return _RHO_TENSOR[(high, low)] / max(grading, 1.0)


def comparison_order(order: int) -> int:
    """The degree the error estimate compares with: one lower (cheaper), or 3 for degree 2."""
    return order - 1 if order > 2 else order + 1


def error_estimates(u: UnitSolution, mat: Material, settings: FemSettings) -> tuple[dict, UnitSolution]:
    """Bounds on the relative errors of K, F_A and d_c, and the comparison solution.

    Discretisation: |K_p / K_q - 1| and |K'_p / K'_q - 1| between degree p and its neighbour q
    on the same mesh, scaled by the per-degree ratio of :func:`order_ratio`.  Truncation: the clamped boundary at
    L = domain_radius a stiffens the body by about (a/L) in K and 2 (a/L) in K' (K ~ a (1 + c a/L),
    c = 0.9 measured with L = 2^16 and 2^20); both meshes share it, so it is added.  Then
    d_c ~ K'^(-1/2) carries half the error of K', and F_A = K |d_c| at most the sum of both."""
    q = comparison_order(settings.order)
    other = unit_solution(mat, dataclasses.replace(settings, order=q, compliance_check=False), mesh=u.mesh)
    rho = order_ratio(mat, settings.grading, max(settings.order, q), min(settings.order, q))
    scale = 1.0 / (rho - 1.0) if q < settings.order else rho / (rho - 1.0)
    trunc = 1.0 / settings.domain_radius
    est_K = scale * abs(u.stiffness / other.stiffness - 1) + trunc
    est_dK = scale * abs(u.dK_vce / other.dK_vce - 1) + 2 * trunc
    est = {"stiffness": est_K, "pulloff_approach": est_dK / 2, "pulloff_force": est_K + est_dK / 2}
    return est, other


#: the largest graded exponent, 1 - 1e-9 (compared as floats).  The depth mapping z = zeta^m,
#: m = 1/(1 - k), amplifies the rounding of the mesh's depth coordinates by m.  Measured errors
#: of K against Eq. 34: 5.5e-7 at 1 - k = 1e-9 on the default mesh (bound 9.8e-7); on
#: grading 2 (bound 1.0e-6) 1.6e-8 at 1e-10, then 2.2e-6, 2.7e-5, 8.9e-4, 8.3e-3 at
#: 1 - k = 1e-11 ... 1e-14, past the bound with the solve reported converged; at 1e-15 the
#: cells degenerate.
MAX_GRADED_EXPONENT = 1 - 1e-9


def _material(scene: Scene) -> tuple[Material, float]:
    """Dimensionless material and the modulus scale with K = scale a K^."""
    m = scene.material
    shape = scene.indenter.shape
    assert isinstance(shape, Circle), "applies() admits circles only"
    a = shape.radius
    if isinstance(m, Homogeneous):
        return Material(0.0, m.poisson_ratio), m.youngs_modulus
    if isinstance(m, PowerLawGraded):
        if m.exponent < 0:
            raise SceneError(
                "material.exponent",
                f"the FEM covers 0 <= k <= 1 - 1e-9 only: nu = 1/(2+k) > 1/2 for k < 0 is not a positive definite "
                f"material (got k = {m.exponent:g})",
            )
        return Material(m.exponent, m.poisson_ratio), m.surface_modulus * (a / m.reference_depth) ** m.exponent
    raise SceneError("material", f"unsupported material {type(m).__name__}")  # pragma: no cover


def _too_close_to_one(k: float) -> str:
    return (
        "the FEM covers graded media with 0 <= k <= 1 - 1e-9 only: the depth mapping "
        f"z = zeta^m, m = 1/(1 - k) = {1 / (1 - k):.3g}, amplifies the rounding of the mesh coordinates "
        f"by m (got k = {k!r})"
    )


def applies(scene: Scene) -> str | None:
    """Whether the FEM can represent a scene, and if not why.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene.

    Returns
    -------
    str or None
        None for a circular flat punch on a homogeneous body or a graded one with
        0 <= k <= 1 - 1e-9 (nu = 1/(2+k) > 1/2 for k < 0 is not positive definite; closer to
        1 the depth mapping's rounding, m eps with m = 1/(1 - k), outgrows the accuracy, see
        :data:`MAX_GRADED_EXPONENT`); else the reason.
    """
    if not isinstance(scene.indenter.shape, Circle) or not scene.indenter.profile.is_flat:
        return "fem_reference models circular flat punches only (axisymmetric)"
    m = scene.material
    if isinstance(m, PowerLawGraded) and m.exponent < 0:
        return "fem_reference covers graded media with 0 <= k <= 1 - 1e-9 only (nu > 1/2 for k < 0)"
    if isinstance(m, PowerLawGraded) and m.exponent > MAX_GRADED_EXPONENT:
        return "fem_reference: " + _too_close_to_one(m.exponent)
    return None


def solve(scene: Scene, settings: FemSettings | None = None, *, callback=None) -> Result:
    """Stiffness, energy release rate and Griffith pull-off of a circular flat punch.

    Griffith's condition G = w (Eqs. 4-6, 36-40) with the energy release rate from the
    stiffness derivative gives d_c = -sqrt(4 pi a w / K'(a)) and F_A = K(a) abs(d_c).

    Parameters
    ----------
    scene : contact_scene.Scene
        A scene :func:`applies` admits.
    settings : FemSettings or None, optional
        Mesh and element settings; ``FemSettings()`` by default.
    callback : callable, optional
        Called once as ``callback(approach, force, contact_area)`` with the pull-off state
        (d_c, -F_A, pi a^2), or the state at ``loading.pull_limit`` when the punch is still
        attached there.

    Returns
    -------
    contact_scene.Result
        ``discretisation="mesh"``, with error bars on stiffness, pull-off force and approach
        (:func:`error_estimates`; at a pull limit short of d_c the punch is still attached,
        F = K abs(limit), with the stiffness's bar on both); ``converged`` False, with a message,
        when the saddle-point solve did not reach its tolerance or dK/da is not positive (no
        Griffith point: F_A = d_c = 0 stand in, with no pull-off bars).  Fields, when the scene
        asks for them, are those of the pull-off state, written to ``fields_path`` (which
        ``info["fields_path"]`` names).  No snapshots are recorded: a message names the
        approaches asked for.  An adhesion range is ignored: the result is the zero-range
        (Griffith) limit, and a message says so; so are turning points (the monotonic pull's
        F_A is the same, and a message names them).

    Raises
    ------
    contact_scene.SceneError
        ``indenter.shape`` for a face that is not a circle with a flat profile;
        ``material.exponent`` for a graded body with k < 0 or k > 1 - 1e-9 (see
        :func:`applies`); ``fem.grading`` for a homogeneous body with grading > 2 or a mesh
        beyond ``fem.max_memory_gb`` (see :func:`unit_solution`);
        ``fem.fields_path`` when the scene asks for fields and the settings give no path.
    """
    check_type("scene", scene, Scene)
    why = applies(scene)
    if why:
        raise SceneError("indenter.shape" if "circular" in why else "material.exponent", why)
    settings = check_type("settings", settings or FemSettings(), FemSettings)
    mat, modulus_scale = _material(scene)
    shape = scene.indenter.shape
    assert isinstance(shape, Circle), "applies() admits circles only"
    a = shape.radius
    w = scene.adhesion.work_of_adhesion
    u = unit_solution(mat, settings)
    K = modulus_scale * a * u.stiffness
    dK = modulus_scale * u.dK_vce  # d(S a K^(a))/da with K^ computed at a = 1 (scale-free)
    # a stiffness that does not grow with the radius has no Griffith point: that is a failed
    # solve (a nearly singular system), not a number to take the square root of
    released = dK > 0 and math.isfinite(dK)
    if w > 0 and released:
        d_c = -math.sqrt(4 * math.pi * a * w / dK)
    else:
        d_c = 0.0
    F_A = K * abs(d_c)
    log.info("error estimate: the unit problem one degree lower")
    est, comparison = error_estimates(u, mat, settings)
    timings = dict(u.timings)
    timings["error_estimate"] = sum(comparison.timings.values())
    msgs = []
    residual = max(u.residual, comparison.residual)
    solved = residual < SOLVE_TOLERANCE and released
    if not released:
        msgs.append(
            f"the stiffness's derivative dK/da = {dK:.3g} is not positive: no Griffith point, the pull-off "
            "is not computed (F_A = 0 and d_c = 0 stand for it) and the solve is not to be trusted"
        )
        est = {"stiffness": est["stiffness"]}
    if residual >= SOLVE_TOLERANCE:
        msgs.append(
            f"the saddle-point solve left a relative residual {residual:.1e} > {SOLVE_TOLERANCE:g} "
            "after every factorisation: the numbers are not to be trusted"
        )
    if u.dK_compliance is not None:
        agree = abs(u.dK_vce / u.dK_compliance - 1)
        if agree > 1e-3:
            msgs.append(f"energy release rate: stiffness and compliance derivatives differ by {agree:.2e}")
    # the flat circle stays in full contact, F = K d, until Griffith's condition at d_c; turning
    # points before d_c retrace that branch, so only a pull limit short of d_c changes the result
    limit = scene.loading.pull_limit
    attached_at_limit = limit is not None and limit > d_c
    if attached_at_limit:
        assert limit is not None
        msgs.append(f"still attached at the pull limit d = {limit:g} (strong adhesion; Griffith's d_c = {d_c:.6g})")
        end, F_end = limit, K * abs(limit)
        curve = Curve(np.array([0.0, end]), np.array([0.0, -F_end]), np.array([math.pi * a * a] * 2))
        # the largest tension is K |limit| at a given approach: the stiffness's error alone
        est = {"stiffness": est["stiffness"], "pulloff_force": est["stiffness"]}
    else:
        end, F_end = d_c, F_A
        curve = Curve(np.array([0.0, d_c, d_c]), np.array([0.0, -F_A, 0.0]), np.array([math.pi * a * a] * 2 + [0.0]))
    if scene.outputs.fields:
        if not settings.fields_path:
            raise SceneError(
                "fem.fields_path", "the scene asks for fields: give FemSettings(fields_path=...) (.vtu or .xdmf)"
            )
        # at the pull-off state: d_c, or the pull limit where the punch is still attached
        write_fields(settings.fields_path, u, radius=a, approach=end, modulus_scale=modulus_scale)
    if scene.outputs.snapshots:
        wanted = sorted(set(scene.outputs.snapshots), reverse=True)
        msgs.append(
            f"fem_reference recorded no snapshot at {len(wanted)} of the approaches asked for: "
            + ", ".join(f"d = {x:g}" for x in wanted)
            + " (it records no snapshots: it solves the pull-off state only)"
        )
    if scene.loading.turning_points:
        msgs.append(
            "fem_reference traces the monotonic pull only, not the turning points "
            + ", ".join(f"d = {t:g}" for t in scene.loading.turning_points)
            + f": before d_c = {d_c:.6g} they retrace the same line F = K d, past it the punch has "
            "detached on the first pull, so F_A is that pull's"
        )
    range_message = zero_range_note(scene, "fem_reference")
    if range_message is not None:
        msgs.append(range_message)
    if callback is not None:
        callback(end, -F_end, math.pi * a * a)
    log.info(
        "fem_reference: %d dofs, K^ = %.10g, dK^ vce %.10g compliance %s",
        u.dofs,
        u.stiffness,
        u.dK_vce,
        "not computed" if u.dK_compliance is None else f"{u.dK_compliance:.10g}",
    )
    return Result(
        method="fem_reference",
        pulloff_force=F_end,
        pulloff_approach=end,
        stiffness=K,
        converged=solved,
        residual=residual,
        grid_spacing=settings.h_min * a,
        curve=curve if scene.outputs.curve else None,
        detached=not attached_at_limit,
        detachment_approach=None if attached_at_limit else d_c,
        timings=timings,
        accuracy_estimate=max(est.values()),
        messages=tuple(msgs),
        error_bars={
            q: ErrorBar(
                v,
                f"degree {settings.order} against {comparison_order(settings.order)} on the same "
                f"mesh, scaled by the per-degree ratio, plus the truncation "
                f"1/{settings.domain_radius:g} "
                "(bounds the error on every tested case: tests/test_fem_reference.py)",
            )
            for q, v in est.items()
        },
        stats=SolverStats(linear_solves=2 + (u.dK_compliance is not None) * 2, unknowns=int(u.dofs)),
        face_area=None,
        discretisation="mesh",
        info={
            "dofs": u.dofs,
            "elements": u.elements,
            "dK_da_vce": modulus_scale * u.dK_vce,
            "dK_da_compliance": None if u.dK_compliance is None else modulus_scale * u.dK_compliance,
            "stiffness_reaction": modulus_scale * a * u.stiffness_reaction,
            "grading": settings.grading,
            "order": settings.order,
            "error_estimates": est,
            "comparison_order": comparison_order(settings.order),
            "comparison_stiffness": modulus_scale * a * comparison.stiffness,
            "comparison_dK_da": modulus_scale * comparison.dK_vce,
            # continuum identities the discrete solution misses: K ~ a^(1+k) (so a K'/((1+k) K) = 1)
            # and the reaction equals the energy form; diagnostics, not error bounds
            "scaling_defect": abs(u.dK_vce / ((1 + mat.k) * u.stiffness) - 1),
            "reaction_defect": abs(u.stiffness_reaction / u.stiffness - 1),
            # where the fields the scene asked for went (Result holds no mesh fields)
            **({"fields_path": settings.fields_path} if scene.outputs.fields else {}),
        },
    )


def solve_with_resolution(scene: Scene, resolution: float | None, *, callback=None) -> Result:
    """Registry entry: ``resolution`` N sets grading = 1/N (default grading 1).

    Parameters
    ----------
    scene : contact_scene.Scene
        A scene :func:`applies` admits.
    resolution : float or None
        N, with grading = 1/N in [0.05, 4] (at most 2 for a homogeneous body), so N in
        [0.25, 20] ([0.5, 20] homogeneous); None for the default ``FemSettings()``.
    callback : callable, optional
        Passed on to :func:`solve`.

    Returns
    -------
    contact_scene.Result
        As :func:`solve`; for a scene that asks for fields, without them and with a message
        saying so (the FEM writes fields to a file, which this entry point does not name).

    Raises
    ------
    contact_scene.SceneError
        ``fem.grading`` for N outside that range; as :func:`solve` otherwise.
    """
    if resolution is not None and not resolution > 0:  # 1/N: zero or negative has no grading
        raise SceneError("fem.grading", f"resolution N = 1/grading must be > 0 (got {resolution!r})")
    s = FemSettings() if resolution is None else FemSettings(grading=1.0 / resolution)
    if not scene.outputs.fields:
        return solve(scene, s, callback=callback)
    # the FEM writes fields only to a file (FemSettings.fields_path), which the registry's callers
    # (the command line, the harness) do not name: solve without them and say so, rather than
    # stop a comparison of every method on the scene
    plain = dataclasses.replace(scene, outputs=dataclasses.replace(scene.outputs, fields=False))
    result = solve(plain, s, callback=callback)
    note = (
        "fields not written: the FEM writes its fields to a file only (FemSettings(fields_path=...) in "
        "fem_reference.solve), which this entry point does not name"
    )
    return dataclasses.replace(result, messages=(*result.messages, note))
