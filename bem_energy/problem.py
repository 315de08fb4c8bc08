"""The discrete energy of a rigid face on a half-space, on a zero-padded FFT grid.

Variables are the surface displacements U (down > 0) of the whole padded grid.  The pressure
is P = C^-1 U, where C is the circulant of the element influence coefficients zero-padded to
at least 2n - 1 (its symbol is positive: checked at set-up).  Only face cells interact with the
punch, so at a stationary point P vanishes off the face and U = C P holds with P supported on
the face: the circulant of the padded grid then gives the exact non-periodic half-space
solution, which is why the padding region carries free variables instead of being dropped.

Energy (per the whole face, in J):  Pi(U) = cell * [ 1/2 U.P + sum_face phi(g) ],
g = U - (d - h) >= 0 on the face (hard wall), h the profile height.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import scipy.fft as sfft

from contact_scene import Homogeneous, PowerLawGraded, Scene, SceneError, rasterise
from contact_scene.discretisation import finest_elements_per_radius
from halfspace.collocation import collocated_graded_influence, collocated_influence
from halfspace.kernel import graded_influence, love_influence
from halfspace.operator import mirrors

# pocketfft's own entry points write into a given array (``out``), which scipy.fft's do not;
# None (scipy.fft's allocating calls) where they are missing or differ from scipy.fft
from halfspace.pocketfft import POCKETFFT as _pocketfft, norm_factor

from .potentials import Potential, process_zone_exponent, process_zone_length, process_zone_modulus

__all__ = [
    "EnergyProblem",
    "EnergyState",
    "build_problem",
    "estimate_memory_gb",
    "max_elements_per_radius",
    "MAX_MEMORY_GB",
]

#: the working memory a solve may take by default (``max_memory_gb`` of the solvers)
MAX_MEMORY_GB = 8.0


class EnergyState(NamedTuple):
    """The energy at a state U and the terms the projected CG reads
    (:meth:`EnergyProblem.energy_state`).

    Attributes
    ----------
    energy : float
        Pi(U), in physical units; NaN when not summed (``energy_state(..., total=False)``).
    pressure : numpy.ndarray
        C^-1 U on the padded grid.
    face_pressure : numpy.ndarray
        Its face entries (1-D, face order).
    face_gradient : numpy.ndarray
        dPi/dU at the face cells (1-D, face order); off the face it is cell P.
    stress : numpy.ndarray or None
        phi'(g) at the face cells; None without the adhesive term.
    curvature : numpy.ndarray or None
        phi''(g) at the face cells; None without the adhesive term.
    phi : numpy.ndarray or None
        phi(g) of the face cells; None without the adhesive term.
    """

    energy: float
    pressure: np.ndarray
    face_pressure: np.ndarray
    face_gradient: np.ndarray
    stress: np.ndarray | None
    curvature: np.ndarray | None
    phi: np.ndarray | None


def estimate_memory_gb(nx: int, ny: int, memory: int = 10) -> float:
    """Working memory of one L-BFGS-B solve on the 2n x 2n padded grid: the correction pairs
    dominate (2 m vectors), plus the symbol and a handful of work arrays."""
    padded = 4 * max(nx, ny) ** 2
    return padded * 8 * (2 * memory + 16) / 1e9


def max_elements_per_radius(scene: Scene, *, max_memory_gb: float = MAX_MEMORY_GB, memory: int = 10) -> int:
    """The finest grid, in elements per equivalent radius, whose memory estimate
    (:func:`estimate_memory_gb`) fits in ``max_memory_gb``, from the face's bounding box.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene.
    max_memory_gb : float, optional
        The limit, :data:`MAX_MEMORY_GB` by default.
    memory : int, optional
        L-BFGS-B's correction pairs (``EnergySettings.memory``).

    Returns
    -------
    int
        The largest whole number of elements per radius that fits (at least 1).
    """
    return finest_elements_per_radius(
        scene.indenter.shape, lambda nx, ny: estimate_memory_gb(nx, ny, memory), max_memory_gb
    )


@dataclass(frozen=True, eq=False)
class EnergyProblem:
    """The discrete energy of a rigid face on a half-space, on a zero-padded FFT grid.

    Built by :func:`build_problem`; see the module for the energy and why the padding region
    carries free variables.

    Attributes
    ----------
    symbol : numpy.ndarray
        rfft2 of the padded kernel: U = C P.
    face : numpy.ndarray
        Boolean mask of the face's cells on the padded grid.
    n : tuple of int
        (nx, ny), the raster's grid, in the top-left corner of the padded grid.
    height : numpy.ndarray
        The profile's height on the face cells (1-D, in the order of ``U[face]``).
    spacing : float
        Element side.
    origin : tuple of float
        (x, y) of the centre of cell (0, 0).
    potential : bem_energy.Potential or None
        The adhesive potential; None without adhesion.
    modulus : float
        E* (E_k = 1 / (pi A_k) for a graded body): sets the process zone.
    self_compliance : float
        C_00, the kernel's self coefficient: sets the minimisers' scales.
    exponent : float
        The grading exponent k (0: homogeneous).
    """

    symbol: np.ndarray  # rfft2 of the padded kernel: U = C P
    face: np.ndarray  # bool on the padded grid
    n: tuple[int, int]  # the raster's grid (top-left corner of the padded grid)
    height: np.ndarray  # profile height on the face cells (1-D, face order)
    spacing: float
    origin: tuple[float, float]
    potential: Potential | None
    modulus: float  # E* (E_k = 1 / (pi A_k) for a graded body): sets the process zone
    self_compliance: float  # C_00, the kernel's self coefficient: sets the minimisers' scales
    exponent: float = 0.0  # the grading exponent k (0: homogeneous)
    #: the factors that multiply a spectrum for C^-1 (double and single precision) and for C
    #: (single precision), each with the inverse transform's 1/n folded in (:meth:`_transform`)
    inverse_factor: np.ndarray = field(init=False, repr=False)
    inverse_factor_single: np.ndarray = field(init=False, repr=False)
    symbol_factor_single: np.ndarray = field(init=False, repr=False)
    #: the face's mask on the raster's corner of the padded grid (:meth:`on_face`)
    face_block: np.ndarray = field(init=False, repr=False)
    #: per-thread transform buffers (:meth:`_transform`, :meth:`_spectrum`)
    _scratch: threading.local = field(init=False, repr=False)
    #: the mirrored transforms' half (:meth:`_mirrored`): (its first row, its rows), or None
    #: where the face, the profile or the padded grid does not mirror
    _mirror: tuple[int, int] | None = field(init=False, repr=False)
    #: each factor's first rows for :meth:`_mirrored`, twice each (the spectrum's real view)
    _half_factors: dict = field(init=False, repr=False)

    def __post_init__(self):
        # a product with a reciprocal, not a quotient: a complex division costs several
        # multiplications, a sizeable part of a transform pair on the finest grids
        scale = norm_factor(self.padded[0] * self.padded[1], np.float64)
        inverse = scale / self.symbol
        object.__setattr__(self, "inverse_factor", inverse)
        with np.errstate(over="ignore", under="ignore"):
            inverse_single = inverse.astype(np.float32)
            symbol_single = (scale * self.symbol).astype(np.float32)
        if not all(np.all(np.isfinite(f)) and np.all(f != 0) for f in (inverse, inverse_single, symbol_single)):
            # the single-precision transforms carry C and C^-1 (~ h / E* and E* / h): lengths and
            # moduli whose ratio leaves their range cannot be minimised in these units
            raise SceneError(
                "material",
                "the influence coefficients leave the single-precision range in these units: rescale lengths "
                "and moduli, e.g. to the face's radius and E*",
            )
        object.__setattr__(self, "inverse_factor_single", inverse_single)
        object.__setattr__(self, "symbol_factor_single", symbol_single)
        object.__setattr__(self, "face_block", self.crop(self.face).copy())
        object.__setattr__(self, "_scratch", threading.local())
        object.__setattr__(self, "_mirror", self._mirror_layout())
        object.__setattr__(self, "_half_factors", {})

    def _buffer(self, name: str, shape: tuple[int, int], dtype) -> np.ndarray:
        """This thread's work array ``name``, allocated once per problem.  The transforms of a
        minimisation run on arrays of a few megabytes; a fresh one each time is fresh pages
        from the system, whose faults cost system time on every transform."""
        buffer = self._scratch.__dict__.get(name)
        if buffer is None:
            buffer = np.empty(shape, dtype)
            setattr(self._scratch, name, buffer)
        return buffer

    def _spectrum(self, U: np.ndarray) -> np.ndarray:
        """rfft2 of ``U`` in this thread's half-spectrum buffer of U's precision."""
        Mx, My = self.padded
        if U.dtype == np.float32:
            out = self._buffer("spectrum_single", (Mx, My // 2 + 1), np.complex64)
        else:
            out = self._buffer("spectrum", (Mx, My // 2 + 1), np.complex128)
        # scipy.fft.rfft2's own call, into ``out``: the same numbers
        return _pocketfft.r2c(U, (0, 1), True, 0, out, 1)

    def _mirror_layout(self) -> tuple[int, int] | None:
        """Where a mirrored array's half lies on the padded grid, or None.

        The face (in rows 0 .. nx - 1) and its profile mirror about the half-sample centre
        c / 2, c = nx - 1 odd, and so does the padded grid of even period M, whose rows i and
        (c - i) mod M then pair up: an array with U[i] = U[(c - i) mod M] for every row is even
        about c / 2 and about c / 2 + M / 2, both half-sample centres, and its rows nx / 2 ..
        nx / 2 + M / 2 - 1 carry it (a DCT-II's data).  A raster anchored at a mirror-symmetric
        face's centroid has an even nx (:func:`contact_scene.rasterise`); an odd nx or M keeps
        the full transforms.  Returns (first row, number of rows)."""
        nx, _ = self.n
        M, _ = self.padded
        if _pocketfft is None or M % 2 or nx % 2:
            return None
        height = np.zeros(self.face_block.shape)
        height[self.face_block] = self.height
        if not (mirrors(self.face_block) and mirrors(height)):
            return None
        return nx // 2, M // 2

    def _mirrors(self, A: np.ndarray) -> bool:
        """Whether ``A`` equals its mirror image about the face's middle row, exactly (row i
        and row (nx - 1 - i) mod M on the padded grid of M rows)."""
        nx, _ = self.n
        M, _ = self.padded
        h, q = nx // 2, (M - nx) // 2
        face_rows = np.array_equal(A[:h], A[nx - 1 : nx - 1 - h : -1])
        return bool(face_rows and np.array_equal(A[nx : nx + q], A[M - 1 : M - 1 - q : -1]))

    def _mirrored(self, A: np.ndarray, factor: np.ndarray, out: np.ndarray) -> np.ndarray:
        """:meth:`_transform` of an array that mirrors (:meth:`_mirrors`), over half the rows.

        Along the rows the array is even about two centres (:meth:`_mirror_layout`), and so is
        the product (the kernel is even): the row-axis transform pair of period M is a DCT-II
        and -III over the half's rows (unnormalised, their round trip is M times the identity,
        as the complex pair's is), and the column transforms run on those rows only.  The other
        rows are copied from their mirror images, so the product mirrors exactly and the
        minimisers' iterates, which the products and cell-by-cell operations make, stay mirrored
        once started mirrored.  Equal to the full transform to round-off
        (``tests/test_energy_mirror.py``)."""
        assert self._mirror is not None
        first, rows = self._mirror
        nx, _ = self.n
        _, My = self.padded
        dtype = A.dtype
        half = slice(first, first + rows)
        complex_type = np.complex64 if dtype == np.float32 else np.complex128
        spectrum = self._buffer(f"mirror_spectrum_{dtype.char}", (rows, My // 2 + 1), complex_type)
        view = spectrum.view(dtype)  # real and imaginary parts side by side, both transformed
        half_factor = self._half_factors.get(id(factor))
        if half_factor is None:
            # the three factors are this problem's own arrays, alive as long as it is
            half_factor = self._half_factors[id(factor)] = np.repeat(factor[:rows], 2, axis=1)
        _pocketfft.r2c(A[half], (1,), True, 0, spectrum, 1)
        _pocketfft.dct(view, 2, (0,), 0, view, 1)
        np.multiply(view, half_factor, out=view)
        _pocketfft.dct(view, 3, (0,), 0, view, 1)
        _pocketfft.c2r(spectrum, (1,), My, False, 0, out[half], 1)
        # row i's mirror image is row (nx - 1 - i) mod M, in the half just written
        out[:first] = out[nx - 1 : first - 1 : -1]
        out[first + rows :] = out[first + rows - 1 : nx - 1 : -1]
        return out

    def _transform(self, A: np.ndarray, factor: np.ndarray, out: np.ndarray) -> np.ndarray:
        """irfft2(rfft2(A) * factor) into ``out``, in the precision of ``A`` and ``out``, with
        ``factor`` carrying the inverse's 1/n (``inverse_factor`` and the like)."""
        if _pocketfft is None:  # pragma: no cover - see the import
            F = sfft.rfft2(A)
            F *= factor
            np.copyto(out, sfft.irfft2(F, s=self.padded, norm="forward", overwrite_x=True))
            return out
        if self._mirror is not None and self._mirrors(A):
            return self._mirrored(A, factor, out)
        F = self._spectrum(A)
        F *= factor
        # the inverse one axis at a time (pocketfft's own order), unnormalised: the 2-D call
        # copies the spectrum before transforming it, which costs a fifth to a third of it here
        _pocketfft.c2c(F, (0,), False, 0, F, 1)
        return _pocketfft.c2r(F, (1,), self.padded[1], False, 0, out, 1)

    def _single_precision(self, A: np.ndarray, factor: np.ndarray, out: np.ndarray | None) -> np.ndarray:
        """:meth:`_transform` in single precision; returned in double precision (in ``out`` if
        given), or, for ``A`` and ``out`` both in single precision, in ``out`` without copies."""
        if A.dtype == np.float32 and out is not None and out.dtype == np.float32:
            return self._transform(A, factor, out)
        single = self._buffer("real_single", self.padded, np.float32)
        np.copyto(single, A, casting="same_kind")
        result = self._transform(single, factor, single)
        if out is None:
            return result.astype(np.float64)
        np.copyto(out, result)
        return out

    @property
    def padded(self) -> tuple[int, int]:
        """(Mx, My), the padded grid of the variables."""
        return self.face.shape

    @property
    def cell(self) -> float:
        """Area of one element, spacing^2."""
        return self.spacing**2

    @property
    def process_zone(self) -> float:
        """The process zone l_c of the potential (:func:`bem_energy.process_zone_length`); inf without adhesion."""
        if self.potential is None:
            return math.inf
        return process_zone_length(
            modulus=self.modulus, work=self.potential.work, range=self.potential.range, exponent=self.exponent
        )

    def pressure(self, U: np.ndarray) -> np.ndarray:
        """P = C^-1 U on the padded grid.

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements (down > 0) on the padded grid.

        Returns
        -------
        numpy.ndarray
            The pressures on the padded grid.
        """
        return self._transform(U, self.inverse_factor, np.empty(self.padded))

    def displacement(self, P: np.ndarray) -> np.ndarray:
        """U = C P on the padded grid.

        Parameters
        ----------
        P : numpy.ndarray
            Pressures on the padded grid.

        Returns
        -------
        numpy.ndarray
            The surface displacements (down > 0) on the padded grid.
        """
        F = sfft.rfft2(P)
        F *= self.symbol
        return sfft.irfft2(F, s=self.padded, overwrite_x=True)

    def pressure_single(self, U: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """C^-1 U in single precision: a search direction's pressure.

        Returned in double precision unless ``out`` is float32.

        The projected CG adds it, times the step, to a pressure that is recomputed in double
        precision from U every few dozen iterations and before a minimum is accepted, so its
        round-off (1e-7 relative to the step's pressure) perturbs the path, not the minimum.

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements on the padded grid.
        out : numpy.ndarray or None, optional
            A float64 or float32 array of the padded grid's shape to write the result into (a
            new float64 one when None); with ``U`` and ``out`` both float32 the transform reads
            and writes them directly.

        Returns
        -------
        numpy.ndarray
            C^-1 U on the padded grid (``out`` when given), float64 unless ``out`` is float32.
        """
        return self._single_precision(U, self.inverse_factor_single, out)

    def preconditioned(self, G: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """C G in single precision: the projected CG's preconditioner.

        Returned in double precision unless ``out`` is float32.

        It only chooses search directions, whose step lengths, energies and gradients are evaluated
        in double precision, so its round-off (1e-7 relative) changes the iterates' path by that
        much but not the minimum they converge to.

        Parameters
        ----------
        G : numpy.ndarray
            A gradient on the padded grid.
        out : numpy.ndarray or None, optional
            A float64 or float32 array of the padded grid's shape to write the result into (a
            new float64 one when None); with ``G`` and ``out`` both float32 the transform reads
            and writes them directly.

        Returns
        -------
        numpy.ndarray
            C G on the padded grid (``out`` when given), float64 unless ``out`` is float32.
        """
        return self._single_precision(G, self.symbol_factor_single, out)

    def on_face(self, A: np.ndarray) -> np.ndarray:
        """The face cells' entries of a padded-grid array, 1-D in the order of ``A[face]``.

        The same as ``A[self.face]``, read from the raster's corner only: the face lies there,
        and a mask over the whole padded grid reads four times as many cells.

        Parameters
        ----------
        A : numpy.ndarray
            An array on the padded grid.

        Returns
        -------
        numpy.ndarray
            A copy of its face entries.
        """
        return self.crop(A)[self.face_block]

    def gap(self, U: np.ndarray, d: float) -> np.ndarray:
        """The gap g = U - (d - h) on the face cells (>= 0 at the hard wall).

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements on the padded grid.
        d : float
            Approach of the punch.

        Returns
        -------
        numpy.ndarray
            The gaps, 1-D in the order of ``U[face]``.
        """
        return self.on_face(U) - (d - self.height)

    def energy(self, U: np.ndarray, d: float, adhesive: bool, P: np.ndarray | None = None):
        """The energy Pi(U), its gradient and the pressure, in physical units.

        Pi = cell [1/2 U.P + sum over the face of phi(g)] (the module's energy); the adhesive term
        only when ``adhesive`` and the problem has a potential.

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements on the padded grid.
        d : float
            Approach of the punch.
        adhesive : bool
            Whether the adhesive potential is switched on.
        P : numpy.ndarray or None, optional
            C^-1 U when already known (saves two FFTs).

        Returns
        -------
        energy : float
            Pi.
        gradient : numpy.ndarray
            dPi/dU on the padded grid.
        P : numpy.ndarray
            The pressures C^-1 U.
        """
        E, G, P, _, _ = self.energy_terms(U, d, adhesive, P)
        return E, G, P

    def energy_terms(
        self,
        U: np.ndarray,
        d: float,
        adhesive: bool,
        P: np.ndarray | None = None,
    ):
        """:meth:`energy` with phi''(g) and phi(g) of each face cell, from one exponential.

        The whole gradient on the padded grid with the face cells' phi'' and phi (a step's
        model needs the curvature, and ``bem_energy.minimisers.step_energy_change`` sums a step's
        energy change from the cells' phi); the projected CG itself reads the same terms from
        :meth:`energy_state`, without the gradient's array.

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements on the padded grid.
        d : float
            Approach of the punch.
        adhesive : bool
            Whether the adhesive potential is switched on.
        P : numpy.ndarray or None, optional
            C^-1 U when already known (saves two FFTs).

        Returns
        -------
        energy, gradient, P
            As for :meth:`energy`.
        curvature : numpy.ndarray or None
            phi'' at the face cells' gaps (1-D, face order); None without the adhesive term.
        phi : numpy.ndarray or None
            phi(g) of the face cells (1-D, face order); None without the adhesive term.
        """
        state = self.energy_state(U, d, adhesive, P)
        G = self.gradient(state.pressure, state.face_gradient)
        return state.energy, G, state.pressure, state.curvature, state.phi

    def gradient(
        self, P: np.ndarray, face_gradient: np.ndarray, out: np.ndarray | None = None, scale: float = 1.0
    ) -> np.ndarray:
        """dPi/dU on the padded grid, times ``scale``.

        It is cell P off the face, and the face cells' own entries (:meth:`energy_state`'s
        ``face_gradient``) on it.

        Parameters
        ----------
        P : numpy.ndarray
            The pressures C^-1 U on the padded grid.
        face_gradient : numpy.ndarray
            dPi/dU at the face cells (1-D, face order).
        out : numpy.ndarray or None, optional
            An array of the padded grid's shape, not ``P`` itself, to write into, in double or
            single precision (a new double-precision one when None).
        scale : float, optional
            A factor for the whole gradient; a power of two scales it exactly.

        Returns
        -------
        numpy.ndarray
            The gradient (``out`` when given).
        """
        G = np.multiply(P, self.cell * scale, out=out, casting="same_kind")
        # the face's entries over cell P: one pass over the padded grid
        self.crop(G)[self.face_block] = face_gradient * scale
        return G

    def energy_state(
        self,
        U: np.ndarray,
        d: float,
        adhesive: bool,
        P: np.ndarray | None = None,
        U_face: np.ndarray | None = None,
        total: bool = True,
    ) -> EnergyState:
        """The energy, the pressure and the face cells' terms, without the gradient's array.

        Off the face the gradient is cell P, so the face's entries carry all it adds: the
        projected CG reads the gradient from P and these, and an iteration streams one array of
        the padded grid less through memory (two with the trial state's).

        Parameters
        ----------
        U : numpy.ndarray
            Surface displacements on the padded grid.
        d : float
            Approach of the punch.
        adhesive : bool
            Whether the adhesive potential is switched on.
        P : numpy.ndarray or None, optional
            C^-1 U when already known (saves two FFTs).
        U_face : numpy.ndarray or None, optional
            ``on_face(U)`` when already known.
        total : bool, optional
            Whether to sum the energy; without it (a trial step's state, whose energy the
            projected CG sums from the step's change) ``energy`` is NaN and the pass over
            U.P is saved.

        Returns
        -------
        EnergyState
            The energy Pi, P, the gradient's face entries and the potential's terms.
        """
        if P is None:
            P = self.pressure(U)
        if U_face is None:
            U_face = self.on_face(U)
        E = 0.5 * float(np.vdot(U, P)) if total else math.nan
        P_face = self.on_face(P)
        face_gradient, stress, curvature, phi = self.face_terms(U_face, P_face, d, adhesive)
        if total and phi is not None:
            E += float(np.sum(phi))
        return EnergyState(self.cell * E, P, P_face, face_gradient, stress, curvature, phi)

    def face_terms(self, U_face: np.ndarray, P_face: np.ndarray, d: float, adhesive: bool):
        """The face cells' part of :meth:`energy_state`, from their own U and P.

        A trial step of the projected CG forms only these before it is accepted.

        Parameters
        ----------
        U_face, P_face : numpy.ndarray
            The face cells' displacements and pressures (1-D, face order).
        d : float
            Approach of the punch.
        adhesive : bool
            Whether the adhesive potential is switched on.

        Returns
        -------
        face_gradient : numpy.ndarray
            dPi/dU at the face cells.
        stress, curvature, phi : numpy.ndarray or None
            phi', phi'' and phi at the face cells' gaps; None without the adhesive term.
        """
        if adhesive and self.potential is not None:
            phi, stress, curvature = self.potential.evaluate(U_face - (d - self.height))
            return (P_face + stress) * self.cell, stress, curvature, phi
        return P_face * self.cell, None, None, None

    def force(self, P: np.ndarray) -> float:
        """The normal force on the punch: cell times the sum of P over the face.

        Parameters
        ----------
        P : numpy.ndarray
            Pressures on the padded grid.

        Returns
        -------
        float
            The force (compressive > 0, tensile < 0).
        """
        return float(self.cell * np.sum(self.on_face(P)))

    def crop(self, A: np.ndarray) -> np.ndarray:
        """The raster's (nx, ny) corner of a padded-grid array.

        Parameters
        ----------
        A : numpy.ndarray
            An array on the padded grid.

        Returns
        -------
        numpy.ndarray
            A view of its first nx x ny entries, indexed like the raster's mask.
        """
        return A[: self.n[0], : self.n[1]]


#: the half-space discretisations (``EnergySettings.kernel``): (homogeneous, graded) coefficients
KERNELS = {
    "collocation": (collocated_influence, collocated_graded_influence),
    "love": (love_influence, graded_influence),
}


def build_problem(
    scene: Scene,
    spacing: float,
    potential: Potential | None,
    *,
    memory: int = 10,
    max_memory_gb: float = MAX_MEMORY_GB,
    kernel: str = "collocation",
) -> EnergyProblem:
    """The discrete problem of ``scene`` on a grid of ``spacing``.

    The face is rasterised, the half-space discretised by ``kernel`` (see
    :class:`bem_energy.EnergySettings`) on a square padded grid whose circulant is checked to be
    positive definite.

    Parameters
    ----------
    scene : contact_scene.Scene
        Face, profile and material.
    spacing : float
        Element side, > 0.
    potential : bem_energy.Potential or None
        The adhesive potential; None without adhesion.
    memory : int, optional
        L-BFGS-B correction pairs, for the memory estimate, >= 1.
    max_memory_gb : float, optional
        Largest working memory allowed (GB), > 0.
    kernel : str, optional
        ``"collocation"`` (point-collocated, :func:`halfspace.collocated_influence`) or
        ``"love"`` (element integrals, :func:`halfspace.love_influence`).

    Returns
    -------
    bem_energy.EnergyProblem
        The problem.

    Raises
    ------
    contact_scene.SceneError
        Naming ``settings.kernel`` (an unknown kernel), ``settings.grid`` (a grid beyond
        ``max_memory_gb``), ``grid.spacing`` (a grid too coarse for the face) or ``material``
        (an influence matrix that is not positive definite, or units in which the influence
        coefficients or the range leave single precision).
    """
    if kernel not in KERNELS:
        raise SceneError("settings.kernel", f"must be one of {', '.join(map(repr, sorted(KERNELS)))} (got {kernel!r})")
    if potential is not None:
        # the displacements go through single-precision transforms, and the gaps the potential
        # acts over are of the order of its range: a range below float32's normal numbers
        # underflows them to zero, and the minimiser then makes no progress; a thousandth of
        # the range keeps its digits
        single = np.finfo(np.float32)
        low, high = float(single.tiny) * 1e3, float(single.max) * 1e-3
        if not low <= potential.range <= high:
            given = scene.adhesion.range is not None
            raise SceneError(
                "material",
                f"the interaction range {potential.range:.3g}"
                + ("" if given else " (the one a zero-range sequence sets from w, the modulus and the face)")
                + f" leaves the single-precision range of the transforms ({low:.3g} ... {high:.3g}) in these "
                "units: rescale lengths, moduli and the work of adhesion, e.g. to the face's radius and E*",
            )
    homogeneous, graded = KERNELS[kernel]
    shape = scene.indenter.shape
    raster = rasterise(shape, spacing)
    nx, ny = raster.shape
    need = estimate_memory_gb(nx, ny, memory)
    if need > max_memory_gb:
        raise SceneError(
            "settings.grid",
            f"a {nx} x {ny} grid needs about {need:.1f} GB for the energy "
            f"method (> {max_memory_gb:g}); coarsen the grid",
        )
    # a square window of the kernel: truncating the Love kernel to an elongated window (2 nx x
    # 2 ny for a 4:1 rectangle) gave a circulant with negative eigenvalues; the square one
    # stays positive definite (checked below, for either kernel)
    n = max(nx, ny)
    # an FFT-friendly size: 2 n = 404 (4 x 101) took 7.5 ms per FFT pair, 405 took 2.8 ms
    m = sfft.next_fast_len(2 * n, real=True)
    M = (m, m)
    mat = scene.material
    modulus = process_zone_modulus(mat)
    if isinstance(mat, Homogeneous):
        K = homogeneous(n, n, spacing, modulus, M)
    elif isinstance(mat, PowerLawGraded):
        K = graded(n, n, spacing, mat.surface_modulus, mat.reference_depth, mat.exponent, M)
    else:  # pragma: no cover - Scene validates the material
        raise SceneError("material", f"unsupported material {type(mat).__name__}")
    symbol = sfft.rfft2(K).real
    if not symbol.min() > 0:
        raise SceneError(
            "material",
            "the padded influence matrix is not positive definite for this material "
            f"(smallest eigenvalue {symbol.min():.3g}); the energy method cannot use it",
        )
    face = np.zeros(M, bool)
    face[:nx, :ny] = raster.mask
    X, Y = raster.centres()
    height = np.asarray(scene.indenter.profile.height(X, Y), float)[raster.mask]
    return EnergyProblem(
        symbol,
        face,
        (nx, ny),
        height,
        float(spacing),
        raster.origin,
        potential,
        float(modulus),
        float(K[0, 0]),
        process_zone_exponent(mat),
    )
