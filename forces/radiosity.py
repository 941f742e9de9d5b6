"""The diffuse balance of reflected light between sides, eq. (12), and what of it escapes.

METHOD.md "Inter-reflection" and "Speed". Unknowns are the diffuse power ``W_i`` leaving each side
[W] (``W_i = A_i B_i``). Light side ``k`` emits lands on side ``i`` as ``G_i = sum_k F_ki W_k``; side
``i`` re-emits ``rho_i G_i`` and, on a two-sided sheet, the share ``sigma`` its other side lets through:

    W = E + T G = E + T F^T W,        M W = E,   M = I - T F^T

with ``T = diag(rho) + (sigma of the other side of a sheet)``. Written in powers, with the view
factors exactly as sampled (each row of rays sums to one), the balance holds to round-off whether or
not sampled ``F`` is exactly reciprocal. What leaves the model is linear in ``E``: force ``-(1/c) sum
W_i e_esc,i``, torque about ``r`` ``-(1/c) sum W_i [(c_i - r) x e_esc,i + m_i]``, escaped power
``sum W_i f_esc,i`` and absorbed power ``sum_i (1 - rho_i - sigma'_i) G_i + sum W_i f_blind,i``
(``sigma'`` the share a side sends through to no other side). So ``g = M^-T w`` for these eight
functionals is solved once per model and material set, and every attitude's totals are ``g^T E``.

Diffuse light landing on a side is re-emitted diffusely even by a specular finish (the paper's
approximation: its angular spread is lost); beams are followed specularly by
:mod:`forces.specular_chains`.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse
import scipy.sparse.linalg
from numpy.typing import NDArray

from geometry.errors import InputError
from geometry.sides import TWO_SIDED
from geometry.spacecraft import Spacecraft
from geometry.view_factors import ViewFactors

from .radiation import LAMBERT_FACTOR, SPEED_OF_LIGHT

#: Relative residual the iterative solves reach.
SOLVER_TOLERANCE = 1e-13
#: Fixed-point sweeps before the solver turns to GMRES.
_SWEEPS = 400
#: Columns of :attr:`DiffuseExchange.responses`: escaping momentum (3), its moment about the origin
#: (3), escaped power, absorbed power.
_RESPONSES = 8


@dataclass(frozen=True)
class DiffuseTotals:
    """What the diffuse light of one attitude does once all its reflections are done; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Force and torque (about the reference point) of the diffuse light that escapes.
    escaped_W, absorbed_W : float
        Diffuse power that leaves the model, and that sides absorb.
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    escaped_W: float
    absorbed_W: float


class DiffuseExchange:
    """The balance ``(I - T F^T) W = E`` of one model, its materials and its view factors.

    Parameters
    ----------
    craft : Spacecraft
    view : ViewFactors
        View factors of ``craft``'s sides.
    """

    def __init__(self, craft: Spacecraft, view: ViewFactors, *, re_emit_all: bool = False) -> None:
        self.craft = craft
        self.view = view
        n = craft.n_sides
        if re_emit_all:
            # rarefied gas: every molecule that lands is re-emitted (rho = 1, nothing passes a sheet)
            self.transfer = scipy.sparse.identity(n, format="csr")
            self.absorptance = np.zeros(n)
        else:
            rho, _, sigma = craft.side_optics.T
            facet_sides = craft.facet_sides[craft.side_facet]
            other = np.where(craft.side_sign > 0, facet_sides[:, 1], facet_sides[:, 0])
            passes = (craft.facet_kind[craft.side_facet] == TWO_SIDED) & (other >= 0) & (sigma > 0)
            # T[i, i] = rho_i; T[other(k), k] = sigma_k: light sent through a sheet leaves its other side
            rows = np.r_[np.arange(n), other[passes]]
            cols = np.r_[np.arange(n), np.flatnonzero(passes)]
            self.transfer = scipy.sparse.csr_matrix((np.r_[rho, sigma[passes]], (rows, cols)), shape=(n, n))
            self.absorptance = 1.0 - rho - np.where(passes, sigma, 0.0)
        #: ``T F^T``: the diffuse power each side re-emits per watt each side emits; ``M = I - coupling``
        self.coupling = (self.transfer @ view.matrix.T).tocsr()

    def _solve(self, coupling: scipy.sparse.csr_matrix, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
        """``(I - coupling)^-1 rhs`` for one or more right-hand sides (n,) or (n, k).

        All columns iterate together ``x <- rhs + coupling x`` (the reflections one after another,
        converging as fast as light dies out in the model); columns not settled to
        :data:`SOLVER_TOLERANCE` after :data:`_SWEEPS` sweeps go on by GMRES from there.
        """
        x = np.array(rhs, dtype=np.float64)
        if not np.any(x):
            return x
        for _ in range(_SWEEPS):
            step = rhs + coupling @ x - x
            x += step
            if np.all(np.abs(step).max(axis=0) <= SOLVER_TOLERANCE * np.abs(x).max(axis=0)):
                return x
        columns = x.reshape(len(x), -1)
        matrix = scipy.sparse.identity(coupling.shape[0], format="csr") - coupling
        targets = np.reshape(rhs, columns.shape)
        for k in range(columns.shape[1]):
            columns[:, k] = self._gmres(matrix, targets[:, k], columns[:, k])
        return x

    def _gmres(self, matrix, rhs: NDArray[np.float64], start: NDArray[np.float64]) -> NDArray[np.float64]:
        x, info = scipy.sparse.linalg.gmres(
            matrix, rhs, x0=start, rtol=SOLVER_TOLERANCE, atol=0.0, restart=60, maxiter=2000
        )
        residual = np.linalg.norm(matrix @ x - rhs) / max(np.linalg.norm(rhs), np.finfo(float).tiny)
        if info != 0 and residual > 1e3 * SOLVER_TOLERANCE:
            raise InputError(
                f"the diffuse reflection balance did not converge (relative residual {residual:.1e})",
                path=self.craft.source,
                hint="a closed cavity with reflectivity 1 traps light forever; lower its reflectivity",
            )
        return x

    def solve(self, source_W: NDArray[np.float64]) -> NDArray[np.float64]:
        """Diffuse power ``W`` leaving each side [W], (n_sides,), for diffuse sources ``E`` [W]."""
        return self._solve(self.coupling, np.asarray(source_W, dtype=np.float64))

    @cached_property
    def functionals(self) -> NDArray[np.float64]:
        """The eight weights ``w`` (n_sides, 8) with ``w^T W`` the escaping momentum rate [W] (3), its
        moment about the origin [W m] (3), the escaped and the absorbed power [W]."""
        craft, view = self.craft, self.view
        moment = np.cross(craft.side_centroids, view.escape_vector) + view.escape_moment
        absorbed = view.matrix @ self.absorptance + view.blind_fraction
        return np.column_stack([view.escape_vector, moment, view.escape_fraction, absorbed])

    def adjoint(self, weights: NDArray[np.float64]) -> NDArray[np.float64]:
        """``M^-T w`` for functionals ``w`` (n_sides, k): ``w^T W = (M^-T w)^T E`` for every source ``E``."""
        return self._solve(self.coupling.T.tocsr(), np.asarray(weights, dtype=np.float64))

    @cached_property
    def responses(self) -> NDArray[np.float64]:
        """``g = M^-T w`` for the :attr:`functionals`, (n_sides, 8): totals are ``g^T E``."""
        return self.adjoint(self.functionals)

    def totals(self, source_W: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        """Escaping force and torque about ``reference_m`` and the power split, for sources ``E`` [W]."""
        return self._totals(self.responses.T @ source_W, reference_m)

    @cached_property
    def open_sky_functionals(self) -> NDArray[np.float64]:
        """:attr:`functionals` as if every side saw only open sky (``e_esc = (2/3) n``, nothing
        absorbed), (n_sides, 8): what the direct law assumes of diffuse light."""
        craft = self.craft
        vector = LAMBERT_FACTOR * craft.side_normals
        moment = np.cross(craft.side_centroids, vector)
        n = craft.n_sides
        return np.column_stack([vector, moment, np.ones(n), np.zeros(n)])

    def open_sky_totals(
        self, source_W: NDArray[np.float64], reference_m: NDArray[np.float64]
    ) -> DiffuseTotals:
        """:meth:`totals` as if every side saw only open sky."""
        return self._totals(self.open_sky_functionals.T @ source_W, reference_m)

    def totals_of(self, emitted_W: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        """The same from a solved ``W`` (diffuse power leaving each side) instead of the sources."""
        return self._totals(self.functionals.T @ emitted_W, reference_m)

    @staticmethod
    def _totals(values: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        momentum, moment = values[0:3], values[3:6]
        return DiffuseTotals(
            force_N=-momentum / SPEED_OF_LIGHT,
            torque_Nm=-(moment - np.cross(reference_m, momentum)) / SPEED_OF_LIGHT,
            escaped_W=float(values[6]),
            absorbed_W=float(values[7]),
        )


def interference_criterion(craft: Spacecraft, view: ViewFactors) -> float:
    """``K_IS`` of eq. (7): reflected light that meets the spacecraft again over light that escapes.

    ``Omega_inf / 2 pi`` is taken as the cosine-weighted open-sky share ``f_esc``, the share of a
    side's diffusely reflected light that escapes, which is the ratio eq. (7) describes. 0 for a
    convex body or a black one.
    """
    rho_area = craft.side_optics[:, 0] * craft.side_areas
    escaping = float(rho_area @ view.escape_fraction)
    returning = float(rho_area @ (1.0 - view.escape_fraction))
    if returning == 0.0:
        return 0.0
    return returning / escaping if escaping > 0 else float("inf")


_exchanges: weakref.WeakKeyDictionary[Spacecraft, dict] = weakref.WeakKeyDictionary()


def diffuse_exchange(craft: Spacecraft, view: ViewFactors) -> DiffuseExchange:
    """The :class:`DiffuseExchange` of ``craft`` with ``view``, built once and kept with the model."""
    kept = _exchanges.setdefault(craft, {})
    if id(view) not in kept or kept[id(view)].view is not view:
        kept[id(view)] = DiffuseExchange(craft, view)
    return kept[id(view)]
