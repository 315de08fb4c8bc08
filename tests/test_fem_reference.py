"""The axisymmetric FEM reference against Kendall (Eqs. 1, 4-6) and the graded closed forms
(Eqs. 34, 38-39).  Tolerances are the issue's targets where the convergence study
(benchmarks/study_fem.py) meets them, else the level that study reached (noted)."""

import dataclasses
import functools

import numpy as np
import pytest

import contact_scene as cs
import fem_reference as fr
from contact_scene import theory as T
from fem_reference.model import Material


def scene(material, radius=1.0, work=1.0):
    return cs.Scene(cs.Indenter(cs.Circle(radius)), material, cs.Adhesion(work))


QUANTITIES = ("stiffness", "pulloff_force", "pulloff_approach")


def errors(r, mat, radius, work):
    """Relative errors of K, F_A and d_c against Eqs. 1, 6, 4 (homogeneous) or 34, 39, 38."""
    if isinstance(mat, cs.Homogeneous):
        E = mat.effective_modulus
        exact = (
            T.kendall_stiffness(E_star=E, radius=radius),
            T.kendall_adhesion_force(E_star=E, radius=radius, work=work),
            T.kendall_critical_approach(E_star=E, radius=radius, work=work),
        )
    else:
        kw = dict(E0=mat.surface_modulus, c0=mat.reference_depth, k=mat.exponent, radius=radius)
        exact = (
            T.graded_stiffness(**kw),
            T.graded_adhesion_force(**kw, work=work),
            T.graded_critical_approach(**kw, work=work),
        )
    return {q: abs(getattr(r, q) / x - 1) for q, x in zip(QUANTITIES, exact, strict=True)}


@functools.cache
def solved(material, grading, order=4, radius=0.7, work=0.3):
    """A solve shared by the tests below (the same case is asked for by more than one; pass
    every positional argument the same way, the cache keys on them as given)."""
    return fr.solve(scene(material, radius=radius, work=work), fr.FemSettings(grading=grading, order=order))


def homogeneous(nu):
    """E* = 2 for every nu: the exact answers are the same numbers."""
    return cs.Homogeneous(2.0 * (1 - nu**2), nu)


@pytest.mark.parametrize("nu", [-0.5, 0.0, 0.2, 0.3, 0.45, 0.499, 0.5])
def test_homogeneous_kendall_for_every_poisson_ratio(nu):
    """Eqs. 1, 4, 6 for nu across (-1, 1/2], within the solver's own per-quantity error bounds;
    at grading 2, the coarsest the homogeneous mesh allows, those bounds are below 1e-4 (the
    measured errors: 1.9e-5 ... 2.5e-5 in K).  nu = 0 is where a mixed form carrying the
    pressure as -lambda div u fails: lambda = 0 there, and dropping 1/lambda makes the body
    incompressible (K = 2 x Eq. 1, seen with an estimate of 3e-5)."""
    mat = homogeneous(nu)
    r = solved(mat, 2.0, 4)
    err, est = errors(r, mat, 0.7, 0.3), r.info["error_estimates"]
    for q in QUANTITIES:
        assert err[q] <= est[q], (q, err[q], est[q])
    assert r.accuracy_estimate == max(est.values()) < 1e-4
    assert r.info["stiffness_reaction"] == pytest.approx(r.stiffness, rel=1e-8)


def test_homogeneous_kendall_at_the_default_grading():
    """The issue's target, 1e-5, at the default grading (measured nu = 0.3: K 8.4e-6, F_A 4e-7,
    d_c 7.9e-6)."""
    mat = cs.Homogeneous(2.0, 0.3)
    r = fr.solve(scene(mat, radius=0.7, work=0.3))
    err = errors(r, mat, 0.7, 0.3)
    assert max(err.values()) < 1e-5
    assert all(err[q] <= r.info["error_estimates"][q] for q in QUANTITIES)


def estimate_failures(r, material) -> list[str]:
    """What is wrong with a solve's error estimate: a quantity whose error its bound does not
    cover, or an accuracy_estimate above ten times the largest error (not sharp)."""
    err, est = errors(r, material, 0.7, 0.3), r.info["error_estimates"]
    out = [f"{q}: error {err[q]:.2e} > bound {est[q]:.2e}" for q in QUANTITIES if not err[q] <= est[q]]
    worst = max(err.values())
    if not worst <= r.accuracy_estimate <= 10 * worst:
        out.append(f"accuracy_estimate {r.accuracy_estimate:.2e} outside [{worst:.2e}, 10 x that]")
    return out


# homogeneous nu and graded k, each at the grading a test can afford; the last runs degree 2,
# whose estimate compares with degree 3 (the finer neighbour) instead of degree 3 with 2
ESTIMATE_CASES = [(homogeneous(nu), 2.0, 4) for nu in (-0.5, 0.0, 0.3, 0.5)] + [
    (cs.PowerLawGraded(1.5, 2.0, 0.5), 2.0, 4),
    (cs.PowerLawGraded(1.5, 2.0, 0.9), 4.0, 4),
    (homogeneous(0.3), 2.0, 2),
]


@pytest.mark.parametrize(
    "material,grading,order",
    ESTIMATE_CASES,
    ids=["nu=-0.5", "nu=0", "nu=0.3", "nu=0.5", "k=0.5", "k=0.9 grading 4", "nu=0.3 degree 2"],
)
def test_error_estimate_bounds_the_error_and_is_sharp(material, grading, order):
    """accuracy_estimate (the largest per-quantity bound) lies between the true largest error
    of K, F_A, d_c and ten times it; each bound covers its own quantity.  The degree-pair
    factors come from benchmarks/study_fem.py (estimate / error 2.0 - 4.6 over its cases)."""
    failures = estimate_failures(solved(material, grading, order), material)
    assert not failures, failures


@pytest.mark.parametrize(
    "rho,fails", [(100.0, "error"), (1.5, "outside")], ids=["ratio 100: too small", "ratio 1.5: not sharp"]
)
def test_a_wrong_degree_ratio_fails_the_estimate_check(monkeypatch, rho, fails):
    """The estimate scales the change between two degrees by 1 / (rho - 1), rho the per-degree
    error ratio (11 to 21 measured on the homogeneous mesh, benchmarks/study_fem.py).  Assuming
    the degrees converge much faster than they do (rho = 100) leaves the error uncovered;
    much slower (1.5) makes the bound more than ten times the error.  Solved afresh: the shared
    cache must not see the mutant."""
    import fem_reference.solver as fem_solver

    monkeypatch.setattr(fem_solver, "order_ratio", lambda *args: rho)
    material = homogeneous(0.3)
    r = fr.solve(scene(material, radius=0.7, work=0.3), fr.FemSettings(grading=2.0, order=4))
    failures = estimate_failures(r, material)
    assert any(fails in f for f in failures), failures


def test_incompressible_does_not_lock_and_converges():
    # nu = 1/2 exactly: the mixed form is exact; the error falls with the grading
    errs = []
    for g in (2.0, 1.0):
        u = fr.unit_solution(Material(0.0, 0.5), fr.FemSettings(grading=g))
        errs.append(abs(u.stiffness / (2 / (1 - 0.25)) - 1))
    assert errs[1] < errs[0] / 2 and errs[1] < 3e-5


def test_energy_release_rate_two_ways():
    """The stiffness derivative against the compliance derivative, K(a + delta) - K(a - delta)
    over 2 delta = 2e-4 a: that difference of two solves magnifies their relative precision
    (their reaction defects: 1e-11 to 6e-10 on graded meshes) 5,000-fold, so they agree to a few 1e-6 at best
    (measured -1.0e-6); a wrong derivative is off at O(1)."""
    u = fr.unit_solution(Material(0.25, 1 / 2.25), fr.FemSettings(grading=2.0, compliance_check=True))
    assert u.dK_vce == pytest.approx(u.dK_compliance, rel=5e-6)


# the targets at the default grading; k = 0.25 and 0.5 (about 8 s of CPU each with the
# error estimate's second solve) stay out of CI, which covers them at grading 2 through the
# estimator tests (test_error_estimate_bounds_the_error_and_is_sharp) and the regression rows
@pytest.mark.parametrize(
    "k,tol",
    [pytest.param(0.25, 1e-4, marks=pytest.mark.slow), pytest.param(0.5, 1e-4, marks=pytest.mark.slow), (0.75, 1e-3)],
)
def test_graded_stiffness_and_pulloff(k, tol):
    """Eqs. 34, 38, 39 on the default (tensor-product) mesh; measured K error 2.0e-5, 5.0e-5,
    9.3e-4, and the solver's estimate covers it."""
    mat = cs.PowerLawGraded(1.5, 2.0, k)
    r = fr.solve(scene(mat, radius=0.8, work=0.2))
    K = T.graded_stiffness(E0=1.5, c0=2.0, k=k, radius=0.8)
    assert r.stiffness == pytest.approx(K, rel=tol)
    kw = dict(E0=1.5, c0=2.0, k=k, radius=0.8, work=0.2)
    assert r.pulloff_force == pytest.approx(T.graded_adhesion_force(**kw), rel=tol)
    assert r.pulloff_approach == pytest.approx(T.graded_critical_approach(**kw), rel=tol)
    assert abs(r.stiffness / K - 1) <= r.accuracy_estimate


def test_refuses_what_it_cannot_represent():
    with pytest.raises(cs.SceneError, match="circular"):
        fr.solve(cs.Scene(cs.Indenter(cs.Square(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0)))
    with pytest.raises(cs.SceneError, match="material.exponent"):
        fr.solve(scene(cs.PowerLawGraded(1.0, 1.0, -0.5)))
    # the isotropic mesh leaves the punch edge unresolved beyond grading 2 (K 1.4e-2 off at 3)
    with pytest.raises(cs.SceneError, match="fem.grading"):
        fr.solve(scene(cs.Homogeneous(1.0, 0.3)), fr.FemSettings(grading=3.0))
    # the registry's resolution is 1/grading: zero has no grading (was a ZeroDivisionError)
    for bad in (0.0, -1.0):
        with pytest.raises(cs.SceneError, match="fem.grading"):
            fr.solve_with_resolution(scene(cs.Homogeneous(1.0, 0.3)), bad)


def test_fields_only_when_asked(tmp_path):
    import meshio

    mat = cs.Homogeneous(1.0, 0.3)
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), mat, cs.Adhesion(1.0), outputs=cs.Outputs(fields=True))
    with pytest.raises(cs.SceneError, match="fields_path"):
        fr.solve(sc, fr.FemSettings(grading=2.0))
    # a path that is not one, or names a format meshio is not asked for, is refused before the solve
    for bad in (5, str(tmp_path / "f.txt")):
        with pytest.raises(cs.SceneError) as caught:
            fr.FemSettings(fields_path=bad)
        assert caught.value.field == "fem.fields_path"
    path = tmp_path / "f.vtu"
    r = fr.solve(sc, fr.FemSettings(grading=2.0, fields_path=str(path)))
    m = meshio.read(path)
    face = (m.points[:, 1] == 0) & (m.points[:, 0] <= 1.0)
    # the face moves rigidly with the punch at pull-off
    assert np.allclose(m.point_data["u_z"][face], r.pulloff_approach, rtol=1e-10)


def test_stiffness_converges_at_the_rate_of_the_element_order():
    """Taylor-Hood P2/P1 on meshes graded toward the edge singularity: the stiffness is an
    energy, its error the square of the energy-norm error, so it falls like h^(2p) =
    dofs^-p = dofs^-2 (benchmarks/study_fem.py: 2.0 between 7.5e3, 2.7e4 and 1.0e5 unknowns)."""
    import numpy as np

    dofs, errs = [], []
    for g in (1.0, 0.7, 0.5):
        u = fr.unit_solution(Material(0.0, 0.3), fr.FemSettings(grading=g, order=2))
        dofs.append(u.dofs)
        errs.append(abs(u.stiffness / (2 / (1 - 0.09)) - 1))
    rate = -np.polyfit(np.log(dofs), np.log(errs), 1)[0]
    assert 1.8 <= rate <= 2.6, (dofs, errs, rate)


def test_graded_estimate_covers_the_error_at_the_coarsest_grading():
    """At grading 4 (the coarsest allowed) the degree pair converges slowest (rho = 8/4 is
    assumed); the estimate must still cover the error (measured k = 0.75: K error 1.24e-3)."""
    r = fr.solve(scene(cs.PowerLawGraded(1.0, 1.0, 0.75)), fr.FemSettings(grading=4.0))
    err = abs(r.stiffness / T.graded_stiffness(E0=1.0, c0=1.0, k=0.75, radius=1.0) - 1)
    assert 0 < err <= r.accuracy_estimate


def _scaled_difference(M1, M0):
    """max |M1 - M0|_ij / sqrt(s_i s_j), s the row maxima of |M0|: the matrices' entries span
    28 decades (near-surface elements of a graded body against the far field), so a difference
    relative to the largest entry would miss every small element."""
    D = (M1 - M0).tocoo()
    s = np.asarray(abs(M0).max(axis=1).todense()).ravel()
    return (abs(D.data) / np.sqrt(s[D.row] * s[D.col])).max()


@pytest.mark.parametrize(
    "material,grading", [(Material(0.5, 0.4), 4.0), (Material(0.0, 0.5), 2.0)], ids=["graded k=0.5", "nu=1/2"]
)
def test_vectorised_element_matrices_are_scikit_fems_assembly_of_the_weak_forms(material, grading):
    """The default kernels integrate the weak forms of fem_reference.model._forms with batched
    products; scikit-fem's asm of those forms is their plain statement.  Entry by entry (scaled
    by the rows' sizes) they agree to rounding, for every degree, over the whole mesh and over
    a subset of elements (as for the moved elements of the energy release rate): measured
    0.8e-15 ... 1.6e-15, so 1e-13.  A wrong shear or deviatoric weight, a dropped mapping
    Jacobian or a pressure coupling of the wrong sign is off at O(1)."""
    from fem_reference.model import saddle_matrix

    mesh = fr.solver.build(material, fr.FemSettings(grading=grading))
    some = np.arange(0, mesh.t.shape[1], 5)
    for order, elements in ((2, None), (3, None), (4, None), (4, some)):
        M1, _, _ = saddle_matrix(mesh, material, order=order, elements=elements)
        M0, _, _ = saddle_matrix(mesh, material, order=order, elements=elements, kernels="scikit-fem")
        assert M1.shape == M0.shape
        assert _scaled_difference(M1, M0) < 1e-13, (order, elements is None)


@pytest.mark.parametrize(
    "material,grading", [(Material(0.9, 1 / 2.9), 4.0), (Material(0.0, 0.5), 2.0)], ids=["graded k=0.9", "nu=1/2"]
)
def test_nested_dissection_solve_is_the_default_orderings(material, grading):
    """The same unit problem through both kernels (nested dissection with diagonal pivots
    against COLAMD with threshold pivoting): K is an energy, stationary in the solution, so it
    agrees to the solves' precision (1e-9, measured <= 8e-10 on the default graded mesh); the
    stiffness derivative x^T (dM/da) x is not stationary and its finite difference over
    delta = 1e-4 carries the rounding of the moved element matrices: spread 1e-6 between
    delta = 0.7e-4 and 1.4e-4 for scikit-fem's assembly, 3e-7 for the vectorised one
    (graded k = 0.5, grading 2), so 5e-6, the tolerance of the compliance check.  nu = 1/2
    has a zero pressure diagonal: no pivot of the nested-dissection order may meet it first."""
    s = fr.FemSettings(grading=grading, order=3)
    new = fr.unit_solution(material, s)
    old = fr.unit_solution(material, dataclasses.replace(s, kernels="scikit-fem"))
    assert new.stiffness == pytest.approx(old.stiffness, rel=1e-9)
    assert new.dK_vce == pytest.approx(old.dK_vce, rel=5e-6)
    assert new.stiffness_reaction == pytest.approx(new.stiffness, rel=1e-8)


def test_nested_dissection_is_a_permutation_with_less_fill():
    """The elimination order holds every dof once, and it is what makes the solve fast: the
    factors of the graded degree-4 system hold under half of COLAMD's entries (measured: 6.2
    million against 18.4 million here at grading 4, 29 million against 157 million on the
    default k = 0.5 mesh)."""
    import scipy.sparse.linalg as spla

    from fem_reference.model import assemble, nested_dissection

    material = Material(0.9, 1 / 2.9)
    mesh = fr.solver.build(material, fr.FemSettings(grading=4.0))
    m = assemble(mesh, material, order=4)
    n = m.M.shape[0]
    order = nested_dissection(np.vstack([m.ub.element_dofs, m.pb.element_dofs + m.ub.N]), mesh, pressure_from=m.ub.N)
    assert np.array_equal(np.sort(order), np.arange(n))
    free = np.setdiff1d(np.arange(n), m.fixed)
    position = np.empty(n, dtype=int)
    position[order] = np.arange(n)
    nd = free[np.argsort(position[free])]
    colamd = spla.splu(m.M[free][:, free].tocsc(), options={"DiagPivotThresh": 0.01})
    dissected = spla.splu(
        m.M[nd][:, nd].tocsc(), permc_spec="NATURAL", options={"DiagPivotThresh": 0.0, "SymmetricMode": True}
    )
    fill = dissected.L.nnz + dissected.U.nnz
    assert fill < (colamd.L.nnz + colamd.U.nnz) / 2, (fill, colamd.L.nnz + colamd.U.nnz)


def test_kernels_setting_is_checked():
    with pytest.raises(cs.SceneError, match="fem.kernels"):
        fr.FemSettings(kernels="fast")


def test_an_inaccurate_linear_solve_is_reported_not_raised(monkeypatch):
    """A saddle-point solve whose residual stays above the tolerance after every factorisation
    (forced here by a zero tolerance) gives converged = False with the residual and a message,
    and the harness fails it; it neither raises nor returns a silent number."""
    import fem_reference.model as fm
    import fem_reference.solver as fs
    from crossval.compare import check_results

    monkeypatch.setattr(fm, "SOLVE_TOLERANCE", 0.0)
    monkeypatch.setattr(fs, "SOLVE_TOLERANCE", 0.0)
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0))
    r = fr.solve(sc, fr.FemSettings(grading=2.0))
    assert not r.converged and r.residual > 0
    assert any("residual" in m for m in r.messages)
    assert not any(c.passed for c in check_results(sc, {"fem_reference": r}))


def test_a_pull_limit_short_of_griffiths_approach_ends_attached(tmp_path):
    # the flat circle stays in full contact, F = K d, until d_c (Eq. 4): a pull limit before it
    # ends attached at tension K |limit|, which the Griffith BEM reports the same way
    mat = homogeneous(0.3)
    full = solved(mat, 2, 2, 1.0, 1.0)
    d_c = full.detachment_approach
    limit = 0.5 * d_c
    sc = dataclasses.replace(scene(mat), loading=cs.Loading(pull_limit=limit), outputs=cs.Outputs(snapshots=(limit,)))
    r = fr.solve(sc, fr.FemSettings(grading=2, order=2))
    assert not r.detached and r.detachment_approach is None
    assert r.pulloff_approach == limit
    assert r.pulloff_force == pytest.approx(full.stiffness * abs(limit), rel=1e-12)
    assert r.pulloff_force == pytest.approx(0.5 * full.pulloff_force, rel=1e-12)
    assert any("still attached at the pull limit" in m for m in r.messages)
    assert any("no snapshots" in m for m in r.messages)
    assert set(r.error_bars) == {"stiffness", "pulloff_force"}
    # fields asked for are those of the state reported: the face at the limit, not at d_c
    import meshio

    path = tmp_path / "limit.vtu"
    with_fields = dataclasses.replace(sc, outputs=cs.Outputs(fields=True))
    fielded = fr.solve(with_fields, fr.FemSettings(grading=2, order=2, fields_path=str(path)))
    m = meshio.read(path)
    face = (m.points[:, 1] == 0) & (m.points[:, 0] <= 1.0)
    assert np.allclose(m.point_data["u_z"][face], fielded.pulloff_approach, rtol=1e-10)
    assert fielded.pulloff_approach == limit
    # a limit beyond d_c changes nothing
    beyond_limit = dataclasses.replace(sc, loading=cs.Loading(pull_limit=2 * d_c))
    beyond = fr.solve(beyond_limit, fr.FemSettings(grading=2, order=2))
    assert beyond.detached and beyond.pulloff_force == full.pulloff_force
    assert beyond.detachment_approach == full.detachment_approach


def test_a_stiffness_that_does_not_grow_with_the_radius_is_reported_not_raised(monkeypatch):
    """dK/da <= 0 has no Griffith point (a near-singular solve gave one at k = 1e-9 on a coarse
    mesh, where sqrt of a negative number was raised): converged = False with a message, no
    pull-off bar, finite numbers, and the harness fails it."""
    import fem_reference.solver as fs
    from crossval.compare import check_results

    real = fs.unit_solution

    def negative_release(*args, **kwargs):
        u = real(*args, **kwargs)
        return dataclasses.replace(u, dK_vce=-abs(u.dK_vce))

    monkeypatch.setattr(fs, "unit_solution", negative_release)
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0))
    r = fr.solve(sc, fr.FemSettings(grading=2, order=2))
    assert not r.converged
    assert any("is not positive" in m for m in r.messages)
    assert not any("saddle-point" in m for m in r.messages)  # the solve itself met its tolerance
    assert set(r.error_bars) == {"stiffness"}
    assert r.pulloff_force == 0.0 and r.pulloff_approach == 0.0
    assert not any(c.passed for c in check_results(sc, {"fem_reference": r}))


# k -> 1: the depth mapping z = zeta^m has m = 1/(1 - k) = 33 ... 1000 here
@pytest.mark.parametrize("k", [0.97, 0.99, 0.999])
def test_graded_stiffness_and_pulloff_as_the_exponent_nears_one(k):
    """Eqs. 34, 38, 39 for k up to 0.999, where the weights mu J and 1/J of the near-surface
    quadrature points used to under- and overflow (k >= 0.97 raised: zero pivots, NaN entries
    at 0.99).  At grading 4, the coarsest allowed, each quantity within the solver's own bound
    (measured K errors 1.2e-4, 4.1e-5, 4.6e-6 against bounds 3.0e-4, 9.8e-5, 1.1e-5); the
    stiffness and the reaction on the punch agree to the solve's precision."""
    mat = cs.PowerLawGraded(1.5, 2.0, k)
    r = fr.solve(scene(mat, radius=0.7, work=0.3), fr.FemSettings(grading=4.0))
    assert r.converged, r.messages
    err, est = errors(r, mat, 0.7, 0.3), r.info["error_estimates"]
    for q in QUANTITIES:
        assert err[q] <= est[q], (q, err[q], est[q])
    assert r.accuracy_estimate < 1e-3
    assert r.info["stiffness_reaction"] == pytest.approx(r.stiffness, rel=1e-8)


def test_near_surface_weights_of_a_graded_body_are_exact_where_their_factors_underflow():
    """mu / J = 1 / (2 (1 + nu) m) and J / E = m are constants of the mapping (m k - m + 1 = 0),
    even where zeta^(m-1) itself underflows (k = 0.99: zeta^99 at zeta = 1e-6); and every free
    displacement dof keeps a positive diagonal (k = 0.97 had 1,411 exact zeros, k = 0.99 NaN
    entries, when they were formed as products of an underflowed and an overflowed factor)."""
    from fem_reference.model import _weights, assemble

    for k in (0.5, 0.97, 0.99, 0.999):
        mat = Material(k, 1 / (2 + k))
        m = mat.mapping
        zeta = np.array([1e-12, 1e-6, 1e-3, 0.5, 1.0])
        alpha, beta, J, J_over_E = _weights(zeta, mat)
        assert np.all(np.isfinite(alpha)) and np.all(np.isfinite(J))
        assert beta**2 == pytest.approx(np.full(5, 1 / (2 * (1 + mat.nu) * m)), rel=1e-12)
        assert J_over_E == pytest.approx(np.full(5, m), rel=1e-12)
    for k in (0.97, 0.99):
        mat = Material(k, 1 / (2 + k))
        model = assemble(fr.solver.build(mat, fr.FemSettings(grading=4.0)), mat, order=2)
        assert np.all(np.isfinite(model.M.data))
        free = np.setdiff1d(np.arange(model.ub.N), model.fixed)
        assert np.all(model.M.diagonal()[free] > 0)


def test_exponents_within_1e_9_of_one_are_refused():
    """Beyond k = 1 - 1e-9 the mapping's m = 1/(1 - k) multiplies the rounding of the depth
    coordinates past the accuracy (K 2.2e-6 off at 1 - k = 1e-11, 8.3e-3 at 1e-14, each
    reported converged): a documented limit, as k < 0 is, not a wrong number."""
    inside = scene(cs.PowerLawGraded(1.0, 1.0, 1 - 1e-9))
    assert fr.applies(inside) is None
    outside = scene(cs.PowerLawGraded(1.0, 1.0, 1 - 1e-10))
    assert "0 <= k <= 1 - 1e-9" in fr.applies(outside)
    with pytest.raises(cs.SceneError, match="material.exponent"):
        fr.solve(outside)


def test_tensor_mesh_keeps_its_physical_depth_lines_for_a_huge_mapping():
    """The bottom line's sliver cut is made in the physical depth: in zeta the whole graded
    range is ln(domain / h_min) / m wide, under the 1e-9 the cut once allowed for m > 2.5e10,
    which dropped every physically graded line.  The lines' depths z = zeta^m are the same
    geometric sequence for m = 10 and m = 1e11 (to the mapping's rounding, m eps)."""
    from fem_reference.model import build_tensor_mesh

    for m in (10.0, 1e11):
        zeta = np.unique(build_tensor_mesh(domain=2.0**20, ratio=2.0, h_min=1e-5, mapping=m).p[1])
        z = zeta**m
        for target in 1e-5 * 2.0 ** np.arange(37):  # h_min 2^j up to the domain's 2^20
            assert np.abs(z / target - 1).min() < 1e-3, (m, target)


@pytest.mark.slow
@pytest.mark.parametrize("k", [0.97, 0.98, 0.99, 0.999, 1 - 1e-9])
def test_graded_near_one_meets_the_target_at_the_default_grading(k):
    """The 1e-5 target on the default mesh as k -> 1 (measured K errors 1.0e-6, 9.1e-7,
    6.4e-7, 5.7e-7, 5.5e-7), each quantity within its bound."""
    mat = cs.PowerLawGraded(1.5, 2.0, k)
    r = fr.solve(scene(mat, radius=0.8, work=0.2))
    err, est = errors(r, mat, 0.8, 0.2), r.info["error_estimates"]
    assert r.converged and max(err.values()) < 1e-5
    for q in QUANTITIES:
        assert err[q] <= est[q], (q, err[q], est[q])


def test_snapshots_and_a_range_are_named_as_not_done():
    """The FEM solves the pull-off state of the zero-range limit: the snapshot approaches asked
    for are named, and a range once ignored silently is named as ignored."""
    mat = homogeneous(0.3)
    sc = dataclasses.replace(
        scene(mat), adhesion=cs.Adhesion(1.0, 0.3), outputs=cs.Outputs(snapshots=(-1.0, -2.0, -1.0))
    )
    r = fr.solve(sc, fr.FemSettings(grading=2, order=2))
    notes = [m for m in r.messages if m.startswith("fem_reference recorded no snapshot at 2 of")]
    assert len(notes) == 1 and "d = -1, d = -2" in notes[0], r.messages
    notes = [m for m in r.messages if "range rho = 0.3" in m]
    assert len(notes) == 1 and "ignored" in notes[0] and "zero-range" in notes[0]
    plain = fr.solve(scene(mat), fr.FemSettings(grading=2, order=2))
    assert plain.pulloff_force == r.pulloff_force and not any("range" in m for m in plain.messages)
    # turning points: the monotonic pull's F_A, and a note that the path was not traced
    turned = fr.solve(
        dataclasses.replace(scene(mat), loading=cs.Loading(turning_points=(-0.5, 0.2))),
        fr.FemSettings(grading=2, order=2),
    )
    assert turned.pulloff_force == plain.pulloff_force
    assert [m for m in turned.messages if "not the turning points d = -0.5, d = 0.2" in m]
    assert not any("turning" in m for m in plain.messages)


@pytest.mark.parametrize("k,grading", [(1e-9, 4.0), (1e-6, 2.0), (1e-3, 4.0)])
def test_a_small_exponent_converges_and_meets_the_closed_forms(k, grading):
    """k -> 0 on the coarse meshes: the tensor mesh's zeta-graded lines once nearly coincided
    with the physically graded ones (slivers 11.5 k of a layer) and, with nu = 1/(2 + k) near
    1/2, the solve reported a residual up to 4.5e-5 (k = 1e-6, grading 4: K = -8.9e5, dK/da
    negative).  Now each quantity lies within its bound (measured K errors 5.9e-3, 4.0e-4,
    5.9e-3 against bounds 1.4e-2, 7.6e-4, 1.4e-2), the bound shrinking with the grading as at
    k = 0 (Kendall, nu = 1/2: 2.3e-5 at grading 2)."""
    mat = cs.PowerLawGraded(1.5, 2.0, k)
    r = solved(mat, grading)
    assert r.converged, r.messages
    assert r.residual < 1e-8
    err, est = errors(r, mat, 0.7, 0.3), r.info["error_estimates"]
    for q in QUANTITIES:
        assert err[q] <= est[q], (q, err[q], est[q])
    assert r.info["stiffness_reaction"] == pytest.approx(r.stiffness, rel=1e-8)


def _tensor_nodes(k, grading):
    from fem_reference.model import build_tensor_mesh

    m = Material(k, 1 / (2 + k)).mapping
    return build_tensor_mesh(domain=2.0**20, ratio=1 + grading, h_min=1e-5, mapping=m).p


def test_tensor_mesh_drops_near_coincident_lines_only_for_small_exponents(monkeypatch):
    """The zeta-graded lines are left out when the first of them, h_min, lies within
    FILL_MIN_GAP = 1/2 of a layer of the first physical line h_min^(1 - k): k < 0.035 here.
    There no layer is thinner than a tenth of both its neighbours (once 1.2e-8 at k = 1e-9,
    0.0025 at k = 1e-3, grading 4); for k >= 0.25 the mesh is, node for node, the one built
    with every zeta-graded line (FILL_MIN_GAP = 0, the rule-free path)."""
    import fem_reference.model as model

    for k in (1e-9, 1e-6, 1e-3, 0.01):
        for grading in (0.5, 1.0, 2.0, 4.0):
            t = np.diff(np.unique(_tensor_nodes(k, grading)[1]))
            sandwiched = t[1:-1] / np.minimum(t[:-2], t[2:])
            assert sandwiched.min() > 0.1, (k, grading, sandwiched.min())
    kept = {(k, g): _tensor_nodes(k, g) for k in (0.25, 0.5, 0.9, 0.999) for g in (1.0, 2.0, 4.0)}
    monkeypatch.setattr(model, "FILL_MIN_GAP", 0.0)
    for (k, g), nodes in kept.items():
        assert np.array_equal(nodes, _tensor_nodes(k, g)), (k, g)


def test_the_registry_entry_solves_a_scene_asking_for_fields_without_them_and_says_so():
    # the command line and the harness name no fields file: the FEM refused the scene, which
    # stopped `crossval compare` of every method on it after the others had run
    import dataclasses

    from fem_reference.solver import solve_with_resolution

    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0))
    asking = dataclasses.replace(scene, outputs=cs.Outputs(fields=True))
    plain, noted = solve_with_resolution(scene, 0.5), solve_with_resolution(asking, 0.5)
    assert noted.converged and noted.pulloff_force == plain.pulloff_force
    assert any("fields not written" in m for m in noted.messages)
    assert not any("fields not written" in m for m in plain.messages)


@pytest.mark.parametrize("k,grading", [(0.05, 1 / 3), (0.1, 1 / 3), (0.06, 1.0), (0.08, 1.5), (0.05, 0.75), (0.9, 2.0)])
def test_tensor_mesh_merges_zeta_lines_next_to_physical_ones(k, grading):
    """The zeta-graded steps ratio^i and the physical ones h_min^-k ratio^(j(1 - k)) coincide
    by accident (at grading 1/3 for k near every multiple of 0.025): k = 0.05 left a layer
    0.0011 of its neighbours, the diagonal-pivot factorisation's residual 4.6e-7, and the
    pivoting fall-backs ran the machine out of memory.  A zeta-graded line within
    COINCIDENT_GAP = 1/10 of its step from a physical line is merged into it, so no layer is
    thinner than a tenth of both neighbours, as for small k (the test above)."""
    t = np.diff(np.unique(_tensor_nodes(k, grading)[1]))
    sandwiched = t[1:-1] / np.minimum(t[:-2], t[2:])
    assert sandwiched.min() > 0.1, sandwiched.min()


@pytest.mark.parametrize("k,grading", [(0.08, 1.5), (0.06, 1.0)])
def test_a_graded_mesh_near_a_coincidence_solves_with_diagonal_pivots(monkeypatch, k, grading):
    """On these meshes the sliver layer left the first (nested dissection, diagonal pivots)
    factorisation at a residual of 1.2e-8 and 4.2e-8, above the 1e-8 tolerance; the
    threshold-pivoting fall-back then filled 4.3x as much (k = 0.08) and past 6 GB (k = 0.06,
    grading 1, 90,000 unknowns).  A second factorisation fails this test before it is tried."""
    import scipy.sparse.linalg as spla

    import fem_reference.model as fm
    from fem_reference.solver import build

    calls, splu = [], spla.splu

    def first_only(A, **kw):
        assert not calls, "fell back to a pivoting factorisation"
        calls.append(kw)
        return splu(A, **kw)

    monkeypatch.setattr(fm.spla, "splu", first_only)
    mat = Material(k, 1 / (2 + k))
    model = fm.assemble(build(mat, fr.FemSettings(grading=grading)), mat, order=4)
    _, residual = fm.solve_unit_approach(model)
    assert residual < fm.SOLVE_TOLERANCE


def test_a_mesh_beyond_the_memory_limit_is_refused_naming_the_grading_that_fits():
    """The finest grading allowed (0.05) for a graded body is 16 million unknowns, an estimated
    140 GB: refused before assembly, naming fem.grading and the finest grading whose
    estimate fits, rather than swapping or killing the process during the factorisation."""
    import re

    from fem_reference.solver import build, estimate_memory_gb

    mat = Material(0.05, 1 / 2.05)
    settings = fr.FemSettings(grading=0.05)
    with pytest.raises(cs.SceneError) as info:
        fr.unit_solution(mat, settings)
    assert info.value.field == "fem.grading"
    finest = float(re.search(r"gradings >= ([0-9.]+) fit", str(info.value)).group(1))

    def need(g):
        return estimate_memory_gb(build(mat, dataclasses.replace(settings, grading=g)), settings.order)

    # the bisection's answer to 1 % (and the 3 digits printed): it fits, 2 % finer does not
    assert need(finest * 1.005) <= settings.max_memory_gb < need(finest / 1.02)


def test_the_memory_limit_is_a_setting_and_the_refusal_says_when_nothing_fits():
    mat = Material(0.25, 1 / 2.25)
    with pytest.raises(cs.SceneError, match="no allowed grading fits") as info:
        fr.unit_solution(mat, fr.FemSettings(max_memory_gb=1e-3), energy_release=False)
    assert info.value.field == "fem.grading"
    with pytest.raises(cs.SceneError, match="fem.max_memory_gb"):
        fr.FemSettings(max_memory_gb=0.0)


def test_a_fall_back_factorisation_that_might_not_fit_is_not_tried(monkeypatch):
    """With every zeta-graded line kept (both sliver rules off) k = 1e-3 at grading 4 leaves the
    first factorisation far from the tolerance; with a memory limit below FALLBACK_FILL times
    its factors the solve returns that residual (reported as not converged) instead of a
    pivoting factorisation of unknown fill."""
    import scipy.sparse.linalg as spla

    import fem_reference.model as fm
    from fem_reference.solver import build

    monkeypatch.setattr(fm, "FILL_MIN_GAP", 0.0)
    monkeypatch.setattr(fm, "COINCIDENT_GAP", 0.0)
    calls, splu = [], spla.splu

    def counted(A, **kw):
        calls.append(kw)
        return splu(A, **kw)

    monkeypatch.setattr(fm.spla, "splu", counted)
    mat = Material(1e-3, 1 / 2.001)
    model = fm.assemble(build(mat, fr.FemSettings(grading=4.0)), mat, order=4)
    _, residual = fm.solve_unit_approach(model, max_memory_gb=0.1)
    assert len(calls) == 1 and residual > fm.SOLVE_TOLERANCE
    calls.clear()
    _, unlimited = fm.solve_unit_approach(model)
    assert len(calls) > 1 and unlimited <= residual


@pytest.mark.parametrize("error", [MemoryError, SystemError])
def test_a_factorisation_out_of_memory_says_so_or_keeps_the_first_result(monkeypatch, error):
    """SuperLU reports a failed allocation as MemoryError or SystemError ("gstrf was called
    with invalid arguments"): on the first factorisation the solve says it ran out of memory
    and names the grading; on a fall-back it keeps the first factorisation's result."""
    import scipy.sparse.linalg as spla

    import fem_reference.model as fm
    from fem_reference.solver import build

    mat = Material(0.5, 0.4)
    model = fm.assemble(build(mat, fr.FemSettings(grading=4.0)), mat, order=2)
    splu, calls = spla.splu, []

    def failing(after):
        def factorise(A, **kw):
            calls.append(kw)
            if len(calls) > after:
                raise error("gstrf was called with invalid arguments")
            return splu(A, **kw)

        return factorise

    monkeypatch.setattr(fm.spla, "splu", failing(0))
    with pytest.raises(MemoryError, match="fem.grading"):
        fm.solve_unit_approach(model)
    calls.clear()
    monkeypatch.setattr(fm, "SOLVE_TOLERANCE", 0.0)  # every factorisation "fails": fall back
    monkeypatch.setattr(fm.spla, "splu", failing(1))
    x, residual = fm.solve_unit_approach(model)
    assert len(calls) == 2 and np.isfinite(residual) and np.all(np.isfinite(x))


@pytest.mark.slow
def test_a_small_exponent_at_grading_one_third_solves_and_meets_the_closed_forms():
    """k = 0.05 at grading 1/3 ran out of memory (a sliver layer 0.0011 of its neighbours, then
    the pivoting fall-back; about 50 s and 3.2 GB now).  Merged, its mesh is no larger than
    those of its neighbours k = 0.03 and 0.1 at the same grading, the solve converges and each
    quantity lies within its bound against Eqs. 34, 38 and 39."""
    from fem_reference.solver import build

    def elements(k):
        return build(Material(k, 1 / (2 + k)), fr.FemSettings(grading=1 / 3)).t.shape[1]

    assert elements(0.03) <= elements(0.05) <= elements(0.1)
    mat = cs.PowerLawGraded(1.5, 2.0, 0.05)
    r = solved(mat, 1 / 3)
    assert r.converged, r.messages
    err, est = errors(r, mat, 0.7, 0.3), r.info["error_estimates"]
    for q in QUANTITIES:
        assert err[q] <= est[q], (q, err[q], est[q])
