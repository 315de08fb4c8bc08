"""Axisymmetric mixed (Taylor-Hood P2-P1) finite elements for a rigid flat circular punch.

Everything here is dimensionless: punch radius a = 1, modulus scale 1 (E for a homogeneous
body, E(z) = z^k for a graded one with c0 = 1).  :mod:`fem_reference.solver` scales back.

Coordinates (r, zeta) with depth z = zeta^m.  For a graded body the displacement under the
punch has a boundary layer u_z ~ d - C z^(1-k); with m = 1/(1 - k) it is linear in zeta, so
polynomial elements capture it, and the weak form's weight mu / J stays finite at the surface.
m = 1 for a homogeneous body.  Strains in the mapped coordinates (J = dz/dzeta = m zeta^(m-1)):

    eps_rr = du_r/dr, eps_zz = du_z/dzeta / J, eps_tt = u_r / r, 2 eps_rz = du_r/dzeta / J + du_z/dr

and the volume element is 2 pi r J dr dzeta.  The strain energy is split into its deviatoric
and volumetric parts, 2 mu (eps:eps - (tr eps)^2 / 3) + K_b (tr eps)^2 with the bulk modulus
K_b = E / (3 (1 - 2 nu)), and the pressure p = -K_b tr eps is the mixed unknown: the form holds
-tr eps = p / K_b with 1/K_b = 3 (1 - 2 nu) / E, finite for every nu in (-1, 1/2] and zero at
nu = 1/2, which is then exact and does not lock.  (Carrying p = -lambda tr eps instead needs
1/lambda, which is infinite at nu = 0: dropping it there solves an incompressible body.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, cast

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import (
    Basis,
    BilinearForm,
    ElementTriP1,
    ElementTriP2,
    ElementTriP3,
    ElementTriP4,
    ElementVector,
    MeshTri,
    asm,
)

__all__ = [
    "KERNELS",
    "Material",
    "Model",
    "assemble",
    "bases",
    "build_mesh",
    "build_tensor_mesh",
    "global_matrix",
    "local_saddle_matrices",
    "nested_dissection",
    "saddle_matrix",
    "unknowns",
    "solve_unit_approach",
]


@dataclass(frozen=True)
class Material:
    """Dimensionless material: E(z) = z^k (k = 0: homogeneous, E = 1) and Poisson's ratio."""

    k: float
    nu: float

    @property
    def mapping(self) -> float:
        return 1.0 / (1.0 - self.k) if self.k > 0 else 1.0


def build_mesh(
    *,
    domain: float,
    grading: float,
    h_min: float,
    h_max_near: float = 0.25,
    far_grading: float | None = None,
    near_radius: float = 2.0,
) -> MeshTri:
    """A triangle mesh of [0, domain]^2 in (r, z) for a homogeneous body, refined
    (red-green-blue, longest edge) until every element's diameter is at most ``grading`` times
    its distance from the punch edge (1, 0), at most ``h_max_near`` within radius 2 of the axis
    foot, and down to ``h_min`` at the edge.  The punch edge and the dyadic nodes 2^j are
    vertices, so the face r <= 1 is a union of boundary facets.  Graded bodies use
    :func:`build_tensor_mesh`."""
    rs = np.concatenate([[0.0, 0.5], 2.0 ** np.arange(0, int(np.ceil(np.log2(domain))) + 1)])
    rs = rs[rs <= domain]
    if rs[-1] < domain:
        rs = np.append(rs, domain)
    m = MeshTri.init_tensor(rs, rs)
    for _ in range(200):
        p, t = m.p, m.t
        c = p[:, t].mean(axis=1)
        e = np.stack([p[:, t[i]] - p[:, t[(i + 1) % 3]] for i in range(3)])
        diam = np.sqrt((e**2).sum(axis=1)).max(axis=0)
        dist = np.hypot(c[0] - 1.0, c[1])
        near = np.hypot(c[0], c[1]) < 2.0
        g = np.where(dist < near_radius, grading, far_grading if far_grading is not None else grading)
        mark = (diam > np.maximum(g * dist, h_min)) | (near & (diam > h_max_near))
        if not mark.any():
            break
        m = m.refined(np.flatnonzero(mark))
    return m


def _geometric(first: float, end: float, ratio: float) -> np.ndarray:
    """0, first, first*ratio, ... (steps never below ``first``), the last node >= ``end``."""
    x = [0.0, first]
    while x[-1] < end:
        x.append(x[-1] * ratio)
    return np.array(x)


#: The zeta-graded lines of :func:`build_tensor_mesh` are left out when the first physical line
#: zeta[1] = h_min^(1 - k) lies less than this fraction of the layer [0, h_min] above h_min, the
#: first of them.  For k -> 0 (m -> 1) the two families nearly coincide (h_min^-k - 1 = 11.5 k at
#: h_min = 1e-5, and the next pair likewise): a sliver layer between two full ones, and with
#: nu = 1/(2 + k) -> 1/2 the saddle-point solve loses digits.  Measured (degree 4, the relative
#: residual, tolerance 1e-8): grading 4: 4.5e-5, 3.8e-7, 3.2e-8, 1.0e-8, 3.0e-9, 1.6e-9 at
#: k = 1e-9, 1e-4, 1e-3, 3e-3, 0.01, 0.02 (sliver 1e-8 ... 0.26 of the layer); grading 1:
#: 5.2e-8, 1.7e-8, 5.1e-9 at k = 1e-3, 3e-3, 0.01; at k = 1e-3, grading 4, K 1.8 % below the
#: mesh without the slivers.  With this rule (full solves, gradings 1, 2, 4): 2.7e-10 ... 1.1e-9
#: for k = 1e-9 ... 0.03 (family left out) and 0.04 (kept, a first gap of 0.58).  At 1/2
#: (k < 0.035 at h_min = 1e-5) the first layer is at most 1.5 h_min thick; the family is kept,
#: and the mesh unchanged, for every k >= 0.25 at every grading and h_min <= 0.1 the settings
#: allow (0.1^-0.25 - 1 = 0.78).  Near-coincidences farther down are merged by
#: :data:`COINCIDENT_GAP`.
FILL_MIN_GAP = 0.5


#: A zeta-graded line of :func:`build_tensor_mesh` is also left out where a physical line lies
#: within this fraction of the zeta-graded step below it (h_min for the first): ratio^i and
#: h_min^-k, the two families' steps, coincide by accident (ln(4/3) / ln(10) = 0.1249, so at
#: grading 1/3 every k near a multiple of 0.025 does), and the last zeta-graded line, past the
#: first physical one, may fall next to the second.  Such a sliver layer, with nu = 1/(2 + k)
#: near 1/2, leaves the diagonal-pivot factorisation short of the solve's tolerance, and the
#: pivoting fall-backs, at grading 1/3, needed more than 6 GB (the limit they ran under).  Measured (the
#: first factorisation's relative residual, tolerance 1e-8; the gap / step): k = 0.05, grading
#: 1/3: 4.6e-7 (0.0011), with that line merged 8.1e-9 (0.056, and F_A 1.1x its error bound);
#: k = 0.1, 1/3: 6.3e-8 (0.0023); k = 0.06, 1: 4.2e-8 (0.0048); k = 0.08, 1.5: 1.2e-8 (0.0079);
#: k = 0.05, 0.75: 1.1e-8 (0.029).  Merged, each solve is below the tolerance (at most 1.5e-9).
COINCIDENT_GAP = 0.1


def _apart(fill: np.ndarray, physical: np.ndarray) -> np.ndarray:
    """The lines of ``fill`` (0 first, then geometric) not within :data:`COINCIDENT_GAP` of
    their own step from a line of ``physical``."""
    if len(fill) < 2:
        return fill
    lines, step = fill[1:], np.diff(fill)
    gap = np.abs(lines[:, None] - physical[None, :]).min(axis=1)
    return np.concatenate([fill[:1], lines[gap >= COINCIDENT_GAP * step]])


def build_tensor_mesh(*, domain: float, ratio: float, h_min: float, mapping: float) -> MeshTri:
    """A tensor-product triangle mesh of [0, domain] x [0, domain^(1/m)] in (r, zeta): radial
    lines graded geometrically (factor ``ratio``) away from the punch edge r = 1 on both sides,
    depth lines graded geometrically in the *physical* depth z = zeta^m from ``h_min`` down
    to the domain's depth, and in zeta itself above the first of them (unless that one lies
    within :data:`FILL_MIN_GAP` h_min of h_min: k -> 0, where the two families nearly coincide;
    and without a zeta-graded line next to a physical one, :data:`COINCIDENT_GAP`).

    Why not the isotropic mesh of :func:`build_mesh` for a graded body: in the mapped depth
    zeta the edge singularity is anisotropic.  Near the edge the solution varies over the
    physical distance, so cells need dz and dr below ``ratio - 1`` times that distance; an
    element sized by its mapped distance from the edge is far too coarse (k = 0.95 maps
    z = zeta^20: zeta-graded layers at 0.59 and 1.77 are z = 3e-5 and 9e4, with nothing in
    between).  Tensor lines give each cell its own width and height.  Measured (order 4,
    ratio 2, K of Eq. 34): 8e-6, 4e-6, 1.5e-6 at k = 0.5, 0.75, 0.95, against 5e-5, 9e-4,
    2e-2 with layers graded in zeta and 5e-4, 4e-3 on the isotropic mesh."""
    d = _geometric(h_min, 1.0, ratio)
    d = d[(d > 0) & (d < 1.0)]
    far = _geometric(2.0, domain, ratio)[1:]
    rs = np.unique(np.concatenate([[0.0, 1.0], 1.0 - d, 1.0 + d, far[far < domain], [domain]]))
    rs = rs[(rs >= 0) & (rs <= domain)]
    zeta_max = domain ** (1.0 / mapping)
    zeta = _geometric(h_min, domain, ratio) ** (1.0 / mapping)
    # the zeta-graded lines, h_min first, only where they subdivide the first physical layer
    # [0, zeta[1]]: for k -> 0 (m -> 1) zeta[1] = h_min^(1 - k) nears h_min and the two families
    # nearly coincide (see FILL_MIN_GAP)
    fill = _geometric(h_min, zeta[1], ratio) if zeta[1] - h_min >= FILL_MIN_GAP * h_min else np.zeros(1)
    zs = np.unique(np.concatenate([zeta, _apart(fill, zeta)]))
    # no sliver layer under the bottom line; compared in the physical depth: in zeta the whole
    # graded range is ln(domain / h_min) / m wide, under 1e-9 for 1 - k < 4e-11, and a cut at
    # zeta_max (1 - 1e-9) then dropped every physically graded line
    with np.errstate(over="ignore"):  # a line far below the domain may overflow to inf: dropped
        zs = np.append(zs[zs**mapping < domain * (1 - 1e-9)], zeta_max)
    return MeshTri.init_tensor(rs, zs)


@dataclass(frozen=True, eq=False)
class Model:
    mesh: MeshTri
    ub: Basis
    pb: Basis
    M: sp.csr_matrix  # the saddle-point matrix [[A, B^T], [B, -C]] (per radian)
    fixed: np.ndarray  # constrained dofs of the combined vector
    punch: np.ndarray  # u_z dofs on the face (prescribed = d)
    material: Material


def _weights(zeta, mat: Material):
    """The weights of the weak forms at depth coordinates ``zeta``, each one power of zeta.

    Returns (sqrt(mu J), sqrt(mu / J), J, J / E) with J = m zeta^(m-1), E = zeta^(m k) and
    mu = E / (2 (1 + nu)): the strain energy is mu J S^T D S with S = (du_r/dr,
    du_z/dzeta / J, u_r / r, du_r/dzeta / J + du_z/dr), that is T^T D T with T = sqrt(mu J) S,
    whose r-derivative and hoop terms carry sqrt(mu J) and zeta-derivative terms sqrt(mu / J);
    the pressure couples to J tr eps and its own form carries J / E.

    Why not J and E, then strains over J times the weight mu J: near the surface of a graded
    body mu J = m zeta^(2 m k) / (2 (1 + nu)) underflows while 1 / J overflows, though their
    product mu / J is the constant 1 / (2 (1 + nu) m) (m k - m + 1 = 0 for m = 1/(1 - k)).
    At k = 0.96 (m = 25) the weight mu r J dx of 110 quadrature points of the default mesh
    (degree 4) was an exact 0; at k = 0.97 (m = 33.3), of 2,172, which left 1,411 dofs of the
    first layer (zeta <= 7.5e-6) without their zeta-stiffness (a zero diagonal) and every
    factorisation met a zero pivot; at k = 0.99 J itself underflowed and 0 x inf gave NaN
    entries.  As single powers they underflow only where their true value is negligible: the
    mu / J and J / E a graded body needs are exponent-0 powers, 1 to rounding."""
    k, nu, m = mat.k, mat.nu, mat.mapping
    shear = 2 * (1 + nu)
    root_mu_J = math.sqrt(m / shear) * zeta ** ((m - 1 + m * k) / 2)
    root_mu_over_J = zeta ** ((m * k - m + 1) / 2) / math.sqrt(shear * m)
    J = m * zeta ** (m - 1) if m != 1 else np.ones_like(zeta)
    J_over_E = m * zeta ** (m - 1 - m * k)
    return root_mu_J, root_mu_over_J, J, J_over_E


def _forms(mat: Material):
    nu = mat.nu
    inv_bulk_coef = 3 * (1 - 2 * nu)  # E / K_b: 0 at nu = 1/2, 9 at nu -> -1

    def scaled_strains(u, w):
        # sqrt(mu J) (eps_rr, eps_zz, eps_tt, 2 eps_rz), each term one weight of _weights
        alpha, beta, _, _ = _weights(w.x[1], mat)
        du = u.grad
        return (alpha * du[0][0], beta * du[1][1], alpha * u[0] / w.x[0], beta * du[0][1] + alpha * du[1][0])

    @BilinearForm
    def a(u, v, w):
        eu, ev = scaled_strains(u, w), scaled_strains(v, w)
        dev = eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2] - (eu[0] + eu[1] + eu[2]) * (ev[0] + ev[1] + ev[2]) / 3
        return (2 * dev + eu[3] * ev[3]) * w.x[0]

    @BilinearForm
    def b(u, q, w):
        r = w.x[0]
        _, _, J, _ = _weights(w.x[1], mat)
        du = u.grad
        # J tr eps = J (du_r/dr + u_r/r) + du_z/dzeta
        return -q * (J * (du[0][0] + u[0] / r) + du[1][1]) * r

    @BilinearForm
    def c(p, q, w):
        if inv_bulk_coef == 0:
            return 0.0 * p * q
        _, _, _, J_over_E = _weights(w.x[1], mat)
        return p * q * inv_bulk_coef * J_over_E * w.x[0]

    return a, b, c


_ORDERS = {2: (ElementTriP2, ElementTriP1), 3: (ElementTriP3, ElementTriP2), 4: (ElementTriP4, ElementTriP3)}

#: how the saddle-point system is assembled and factorised (``FemSettings.kernels``)
KERNELS = ("vectorised", "scikit-fem")

# the deviatoric energy 2 (e.f - tr e tr f / 3) on (eps_rr, eps_zz, eps_tt) and the shear
# (2 eps_rz)(2 eps_rz') in one 4x4 matrix: a(u, v) = mu r J S_u^T D S_v for the strain vectors
# S = (eps_rr, eps_zz, eps_tt, 2 eps_rz) of _forms
_DEVIATORIC = np.array([[4, -2, -2, 0], [-2, 4, -2, 0], [-2, -2, 4, 0], [0, 0, 0, 3]]) / 3.0


def unknowns(mesh: MeshTri, order: int) -> int:
    """Degrees of freedom of the saddle-point system of degree ``order`` on ``mesh``, counted
    without building the bases: a P_p scalar field has a dof per vertex, p - 1 per edge and
    (p - 1)(p - 2)/2 per triangle; two displacement components of degree p, a pressure of p - 1."""
    vertices, edges, triangles = mesh.p.shape[1], mesh.facets.shape[1], mesh.t.shape[1]

    def scalar(p: int) -> int:
        return vertices + (p - 1) * edges + (p - 1) * (p - 2) // 2 * triangles

    return 2 * scalar(order) + scalar(order - 1)


def bases(
    mesh: MeshTri, order: int, intorder: int | None = None, elements: np.ndarray | None = None
) -> tuple[Basis, Basis]:
    """Taylor-Hood displacement and pressure bases of degree ``order`` and ``order`` - 1."""
    eu, ep = _ORDERS[order]
    # 2p: exact for the polynomial part of the integrands (degree 2(p-1) + 1 with the weight r);
    # 2p + 2 changed K by < 1e-6 relative on the study cases but scikit-fem's degree-10 rule
    # made the degree-4 assembly 6.5x slower (3.7 s against 0.57 s at 1,600 elements)
    intorder = intorder if intorder is not None else 2 * order
    kw = {} if elements is None else {"elements": elements}
    return Basis(mesh, ElementVector(eu()), intorder=intorder, **kw), Basis(mesh, ep(), intorder=intorder, **kw)


def local_saddle_matrices(ub: Basis, pb: Basis, mat: Material) -> tuple[np.ndarray, np.ndarray]:
    """Element matrices [[A_e, B_e^T], [B_e, -C_e]] of the forms of :func:`_forms`, shape
    (elements, n, n) with n = displacement + pressure basis functions per element, and their
    global dofs (n, elements; pressure dofs after the ub.N displacement dofs).

    The same integrals as scikit-fem's ``asm`` of :func:`_forms` (equal to rounding, checked in
    tests/test_fem_reference.py), but each basis function's strains and the quadrature
    weights mu r J dx are evaluated once, and the n^2 pairs come from one batched matrix
    product per element instead of one Python call of the form per pair."""
    r, zeta = ub.mapping.F(ub.X, tind=ub.tind)  # quadrature points (elements, points)
    alpha, beta, J, J_over_E = _weights(zeta, mat)
    rdx = r * ub.dx
    nel, nq = r.shape
    # T = sqrt(mu J) S, S = (eps_rr, eps_zz, eps_tt, 2 eps_rz): a(u, v) = sum r dx T_u^T D T_v
    T = np.empty((ub.Nbfun, 4, nel, nq))
    trace = np.empty((ub.Nbfun, nel, nq))  # J tr eps
    for a, (f,) in enumerate(ub.basis):
        g = f.grad
        hoop = np.asarray(f)[0] / r
        T[a, 0] = alpha * g[0][0]
        T[a, 1] = beta * g[1][1]
        T[a, 2] = alpha * hoop
        T[a, 3] = beta * g[0][1] + alpha * g[1][0]
        trace[a] = J * (g[0][0] + hoop) + g[1][1]
    DT = np.einsum("kl,alnq->ankq", _DEVIATORIC, T).reshape(ub.Nbfun, nel, 4 * nq)
    WT = (T * rdx).transpose(0, 2, 1, 3).reshape(ub.Nbfun, nel, 4 * nq)
    A = np.matmul(WT.transpose(1, 0, 2), DT.transpose(1, 2, 0))  # (elements, nu, nu)
    psi = np.stack([np.asarray(f) for (f,) in pb.basis])  # (np, elements, points)
    B = -np.einsum("ieq,aeq->eia", psi * rdx, trace)
    inv_bulk_coef = 3 * (1 - 2 * mat.nu)
    n_u, n_p = ub.Nbfun, pb.Nbfun
    Ke = np.zeros((nel, n_u + n_p, n_u + n_p))
    Ke[:, :n_u, :n_u] = A
    Ke[:, n_u:, :n_u] = B
    Ke[:, :n_u, n_u:] = B.transpose(0, 2, 1)
    if inv_bulk_coef != 0:
        Ke[:, n_u:, n_u:] = -np.einsum("ieq,jeq->eij", psi * (inv_bulk_coef * J_over_E * rdx), psi)
    return Ke, np.vstack([ub.element_dofs, pb.element_dofs + ub.N])


def global_matrix(Ke: np.ndarray, dofs: np.ndarray, n: int) -> sp.csr_matrix:
    """Sum of the element matrices ``Ke`` (elements, m, m) on their global ``dofs`` (m, elements)."""
    rows = np.broadcast_to(dofs.T[:, :, None], Ke.shape)
    cols = np.broadcast_to(dofs.T[:, None, :], Ke.shape)
    return sp.csr_matrix((Ke.ravel(), (rows.ravel(), cols.ravel())), shape=(n, n))


def saddle_matrix(
    mesh: MeshTri,
    mat: Material,
    *,
    order: int = 2,
    intorder: int | None = None,
    elements: np.ndarray | None = None,
    kernels: str = "vectorised",
) -> tuple[sp.csr_matrix, Basis, Basis]:
    """[[A, B^T], [B, -C]] over all elements, or only over ``elements`` (same global size)."""
    ub, pb = bases(mesh, order, intorder, elements)
    if kernels == "vectorised":
        Ke, dofs = local_saddle_matrices(ub, pb, mat)
        return global_matrix(Ke, dofs, ub.N + pb.N), ub, pb
    a, b, c = _forms(mat)
    A = asm(a, ub)
    B = asm(b, ub, pb)
    C = asm(c, pb)
    return cast(sp.csr_matrix, sp.bmat([[A, B.T], [B, -C]], format="csr")), ub, pb


def assemble(
    mesh: MeshTri,
    mat: Material,
    *,
    order: int = 2,
    intorder: int | None = None,
    face_radius: float = 1.0,
    kernels: str = "vectorised",
) -> Model:
    M, ub, pb = saddle_matrix(mesh, mat, order=order, intorder=intorder, kernels=kernels)
    L = mesh.p[0].max()
    Z = mesh.p[1].max()
    tol = 1e-12 * L
    axis = ub.get_dofs(lambda x: x[0] < tol).all("u^1")
    far = ub.get_dofs(lambda x: (x[0] > L - tol * L) | (x[1] > Z * (1 - 1e-12))).all()
    face = ub.get_dofs(lambda x: (x[1] < tol) & (x[0] < face_radius * (1 + 1e-12))).all("u^2")
    fixed = np.unique(np.concatenate([axis, far, face]))
    return Model(mesh, ub, pb, M, fixed, np.setdiff1d(face, far), mat)


def nested_dissection(dofs: np.ndarray, mesh: MeshTri, *, pressure_from: int, leaf: int = 4) -> np.ndarray:
    """A fill-reducing elimination order of the dofs of ``dofs`` (per element, as from
    :func:`local_saddle_matrices`; dofs in no element come last).

    The elements are split recursively in two halves by a mesh line near their median along
    the axis whose cut shares fewer dofs; the shared dofs (the separator) are eliminated after
    both halves, so every factorisation step only fills within a half or its separator.  Why
    not SuperLU's default COLAMD: it orders the columns for A^T A and ignores that the matrix
    is structurally symmetric; on the graded tensor mesh (108,000 unknowns, degree 4) its
    factors held 157 million entries, these 29 million.  Within each block displacement dofs
    come before pressure dofs, so that the pivots of the saddle point (zero pressure diagonal
    at nu = 1/2) have met their displacements first."""
    n = int(dofs.max()) + 1
    centroid = mesh.p[:, mesh.t].mean(axis=1)
    taken = np.zeros(n, dtype=bool)
    is_pressure = np.arange(n) >= pressure_from
    # mark[d] == stamp: d belongs to an element of the current left half (a fresh stamp per
    # trial cut, so the array is never cleared)
    mark = np.zeros(n, dtype=np.int64)
    stamp = 0
    out = []
    stack: list = [np.arange(mesh.t.shape[1])]
    while stack:
        item = stack.pop()
        if isinstance(item, tuple):  # a separator, after its halves
            out.append(item[0])
            continue
        E = item
        local = dofs[:, E]
        best = None
        if len(E) > leaf:
            for ax in (0, 1):
                c = centroid[ax, E]
                median = np.median(c)
                vertices = mesh.p[ax, mesh.t[:, E]]
                gap = np.abs(vertices - median)
                left = c < vertices[gap == gap.min()].min()  # the mesh line nearest the median
                if left.all() or not left.any():
                    left = c < median
                    if left.all() or not left.any():
                        continue
                stamp += 1
                mark[local[:, left]] = stamp
                right = local[:, ~left]
                sep = np.unique(right[mark[right] == stamp])
                sep = sep[~taken[sep]]
                score = len(sep) * (1 + 2 * abs(left.mean() - 0.5))  # small and balanced
                if best is None or score < best[0]:
                    best = (score, left, sep)
        if best is None:  # a leaf
            own = np.unique(local)
            own = own[~taken[own]]
            taken[own] = True
            out.append(own[np.argsort(is_pressure[own], kind="stable")])
            continue
        _, left, sep = best
        taken[sep] = True
        stack += [(sep[np.argsort(is_pressure[sep], kind="stable")],), E[~left], E[left]]
    order = np.concatenate(out)
    return np.concatenate([order, np.flatnonzero(~np.isin(np.arange(n), order))])


#: the relative residual below which a saddle-point solve counts as converged
SOLVE_TOLERANCE = 1e-8

#: bytes of working memory per entry of a sparse LU factor: the measured peak (resident) of a
#: solve over the entries of its factors, 20.6 (k = 0.05, grading 1/3, 155 million entries)
FACTOR_ENTRY_BYTES = 21.0

#: the fill a pivoting fall-back factorisation is assumed to add over the first one: row swaps
#: undo the nested-dissection order, measured 4.3x (k = 0.08, grading 1.5, a sliver layer)
#: and more than 11x (k = 0.06, grading 1: 23 million entries first, past 6 GB with pivoting)
FALLBACK_FILL = 25.0


def solve_unit_approach(
    model: Model, M: sp.csr_matrix | None = None, *, kernels: str = "vectorised", max_memory_gb: float = math.inf
) -> tuple[np.ndarray, float]:
    """The combined solution vector (u, p) for u_z = 1 on the face, and the relative residual
    of the linear solve (the best of the factorisations tried; above :data:`SOLVE_TOLERANCE`
    the caller reports the result as not converged).  A fall-back factorisation is tried only
    when :data:`FALLBACK_FILL` times the first one's entries fit in ``max_memory_gb``."""
    M = model.M if M is None else M
    n = M.shape[0]
    x = np.zeros(n)
    x[model.punch] = 1.0
    free = np.setdiff1d(np.arange(n), model.fixed)
    if kernels == "vectorised":
        order = nested_dissection(
            np.vstack([model.ub.element_dofs, model.pb.element_dofs + model.ub.N]), model.mesh, pressure_from=model.ub.N
        )
        position = np.empty(n, dtype=np.int64)
        position[order] = np.arange(n)
        free = free[np.argsort(position[free], kind="stable")]
    rhs = -(M[free][:, model.fixed] @ x[model.fixed])
    A = M[free][:, free].tocsc()
    attempts: list[tuple[Literal["COLAMD", "NATURAL"], float, bool]]
    if kernels == "vectorised":
        # the diagonal pivots of the nested-dissection order first (no fill from row swaps:
        # 1.8 s against 21 s with 1 % threshold pivoting on the graded mesh); a factorisation
        # that meets a zero pivot or leaves a large residual falls back to pivoting
        attempts = [("NATURAL", 0.0, True), ("NATURAL", 0.01, True), ("COLAMD", 1.0, False)]
    else:
        # relaxed partial pivoting (take the diagonal unless it is < 1/100 of the column's largest)
        # cuts SuperLU's fill and time (nu = 0.3: 0.95 s against 1.38 s, K equal to 1e-14); no
        # pivoting at all breaks the nu = 1/2 saddle point (zero pressure diagonal), so the
        # residual is checked and a failed factorisation falls back to full partial pivoting
        attempts = [("COLAMD", 0.01, False), ("COLAMD", 1.0, False)]
    residual, best = math.inf, None
    first_entries = None
    for permc, threshold, symmetric in attempts:
        # pivoting fills unpredictably: on 500,000 unknowns the fall-back outgrew 6 GB,
        # so a large system keeps its first factorisation's (reported) residual
        if first_entries is not None and FALLBACK_FILL * first_entries * FACTOR_ENTRY_BYTES > max_memory_gb * 1e9:
            break
        try:
            lu = spla.splu(A, permc_spec=permc, options={"DiagPivotThresh": threshold, "SymmetricMode": symmetric})
        except RuntimeError:  # an exactly zero pivot
            continue
        except (MemoryError, SystemError) as exc:
            # SuperLU reports a failed allocation as either (SystemError: "gstrf was called
            # with invalid arguments"); the memory estimate before assembly should prevent it
            if best is not None:
                break  # keep the first factorisation's result and its reported residual
            raise MemoryError(
                f"fem_reference: the factorisation of {A.shape[0]} unknowns ran out of memory ({exc}); "
                "choose a coarser fem.grading or a lower fem.max_memory_gb, whose estimate refuses such meshes"
            ) from exc
        if first_entries is None:
            first_entries = lu.nnz
        y = lu.solve(rhs)
        del lu  # not held while the next one is factorised
        r = float(np.linalg.norm(A @ y - rhs) / np.linalg.norm(rhs))
        if np.all(np.isfinite(y)) and r < residual:
            residual, best = r, y
        if residual < SOLVE_TOLERANCE:
            break
    if best is None:
        raise FloatingPointError(
            "fem_reference: every factorisation of the saddle-point matrix met a zero pivot "
            "or produced no finite solution (a singular system: check the material and mesh)"
        )
    x[free] = best
    return x, residual
