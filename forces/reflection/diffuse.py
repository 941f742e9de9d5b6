"""The diffuse balance of reflected light between sides, eq. (12), and what of it escapes.

METHOD.md "Inter-reflection" and "Speed". Unknowns are the diffuse power ``W_i`` each side emits
[W] (``W_i = A_i B_i``). Of side ``k``'s emission the share ``E_kj`` arrives at side ``j``, directly
or after mirror reflections and transmissions on the way (the exchange factors of
:mod:`sunwind.geometry.views.exchange_factors`; ``E = F``, the view factors, where no side reflects
specularly or
transmits). Side ``j`` re-emits diffusely the share ``rho_d,j = rho_j (1 - beta_j)`` of what arrives:

    W = S + diag(rho_d) E^T W,        M W = S,   M = I - diag(rho_d) E^T

for diffuse sources ``S`` (diffuse reflections of sunlight and of beams: none on a side with
``rho_d = 0``, whose rows of ``E`` are therefore not followed). The mirrored share ``rho beta`` of
arriving diffuse light keeps its angular spread and a sheet's transmitted share goes straight on,
both inside ``E``; so the balance follows the physics on mixed finishes too, where the paper's
eq. (12), re-emitting the whole ``rho`` (and a sheet's ``sigma`` from its far side) diffusely, does
not. Written in powers, with the factors exactly as sampled, the balance holds to round-off. What
leaves the model is linear in ``W``: force ``-(1/c) sum W_i e_esc,i``, torque about ``r``
``-(1/c) sum W_i [(c_i - r) x e_esc,i + m_i]``, escaped power ``sum W_i f_esc,i`` and absorbed power
``sum_j (1 - rho_j - sigma_j) G_j + sum W_i (f_blind,i + f_truncated,i)`` with ``G = E^T W`` (light
still travelling when a chain was dropped counts as absorbed). So ``g = M^-T w`` for these eight
functionals is solved once per model and material set, and every attitude's totals are ``g^T S``.

Molecules (``mirrored``) use the same balance with ``rho = 1`` and the share each side mirrors as its
``beta``: the view factors where no side mirrors.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from functools import cached_property

import numba
import numpy as np
import scipy.sparse
import scipy.sparse.linalg
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.forces.reflection.views import model_view_factors
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.exchange_factors import ExchangeFactors, exchange_factors
from sunwind.geometry.views.view_factors import ViewFactors

#: Relative residual the iterative solves reach.
SOLVER_TOLERANCE = 1e-13
#: Fixed-point sweeps before the solver turns to GMRES.
_SWEEPS = 400
#: Columns of :attr:`DiffuseExchange.functionals` and :attr:`DiffuseExchange.responses`: escaping
#: momentum rate (3) and its moment about the origin (3), together ``MOMENTA``; escaped power, absorbed
#: power.
MOMENTUM, MOMENT, MOMENTA, ESCAPED, ABSORBED = slice(0, 3), slice(3, 6), slice(0, 6), 6, 7
#: Sides per block of the weighted sums of :func:`_weighted`.
_BLOCK_SIDES = 4096


@dataclass(frozen=True)
class DiffuseTotals:
    """What the diffuse light of one attitude does once all its reflections are done; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Force and torque (about the reference point) of the diffuse light that escapes.
    escaped_W, absorbed_W : float
        Diffuse power that leaves the model, and that sides absorb.

    Examples
    --------
    A momentum rate of 1 W leaving along +z pushes the model along -z by ``1 / c``:

    >>> import numpy as np
    >>> totals = DiffuseTotals.from_sums(np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]), np.zeros(3))
    >>> f"{totals.force_N[2]:.4e}", totals.escaped_W
    ('-3.3356e-09', 1.0)
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    escaped_W: float
    absorbed_W: float

    @classmethod
    def from_sums(cls, values: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        """The totals from the eight sums of :attr:`DiffuseExchange.functionals` over a diffuse
        emission (or of its responses over the sources) [W], torque about ``reference_m``."""
        momentum, moment = values[MOMENTUM], values[MOMENT]
        return cls(
            force_N=-momentum / SPEED_OF_LIGHT,
            torque_Nm=-(moment - np.cross(reference_m, momentum)) / SPEED_OF_LIGHT,
            escaped_W=float(values[ESCAPED]),
            absorbed_W=float(values[ABSORBED]),
        )


class DiffuseExchange:
    """The balance ``(I - diag(rho_d) E^T) W = S`` of one model, its materials and its view factors.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    view : ViewFactors
        View factors of ``craft``'s sides.
    mirrored : (n_sides,) float64, optional
        Rarefied gas: the share of arriving molecules each side sends on mirrored; the rest it
        re-emits diffusely (``rho = 1``, ``beta`` = that share, nothing passes a sheet), so ``E = F``
        where no side mirrors. Only molecules reaching a side the model does not have (``BLIND``)
        count as absorbed. None (default): light.
    cache_dir : path, bool or None
        Where exchange factors are kept on disk
        (:func:`sunwind.geometry.views.exchange_factors.exchange_factors`);
        False: not kept.
    optics : (n_sides, 3) float64, optional
        Light: ``(rho, beta, sigma)`` of each side to use instead of ``craft.side_optics`` (the
        infrared band: ``(1 - eps, 0, 0)``, :mod:`sunwind.forces.thermal`). Not with ``mirrored``.

    Raises
    ------
    ValueError
        Both ``mirrored`` and ``optics`` given.

    Examples
    --------
    On a convex cube nothing a side emits meets another, so ``W = S`` and all of it escapes, pushing the
    cube along ``-(2/3) n / c`` per watt:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> exchange = diffuse_exchange(craft, ReflectionSettings("full", cache_dir=False, rays_per_side=16))
    >>> source = np.zeros(craft.n_sides)
    >>> source[0] = 1.0  # 1 W emitted diffusely by side 0, whose normal is -x
    >>> exchange.solve(source)[:3]
    array([1., 0., 0.])
    >>> totals = exchange.totals(source, np.zeros(3))
    >>> f"{totals.force_N[0]:.4e}", totals.escaped_W, totals.absorbed_W
    ('2.2238e-09', 1.0, 0.0)
    """

    def __init__(
        self,
        craft: Spacecraft,
        view: ViewFactors,
        *,
        mirrored: NDArray[np.float64] | None = None,
        cache_dir: str | os.PathLike | bool | None = False,
        optics: NDArray[np.float64] | None = None,
    ) -> None:
        self.craft = craft
        self.view = view
        #: where the exchange factors, and what is made from them, are kept on disk
        self.cache_dir = cache_dir
        if mirrored is not None and optics is not None:
            raise ValueError("DiffuseExchange takes mirrored (molecules) or optics (light), not both")
        if mirrored is not None:
            n = craft.n_sides
            optics = np.column_stack([np.ones(n), mirrored, np.zeros(n)])
            self.factors = (
                exchange_factors(craft, view, cache_dir, optics)
                if np.any(mirrored > 0)
                else ExchangeFactors.of_view(view)
            )
            re_emitted = 1.0 - mirrored
            self.absorptance = np.zeros(n)
        else:
            optics = craft.side_optics if optics is None else np.ascontiguousarray(optics, dtype=np.float64)
            rho, beta, sigma = optics.T
            self.factors = exchange_factors(craft, view, cache_dir, optics)
            re_emitted = rho * (1 - beta)
            self.absorptance = 1.0 - rho - sigma
        #: ``(rho, beta, sigma)`` of each side in this balance (molecules: ``(1, mirrored, 0)``)
        self.optics = optics
        #: ``diag(rho_d) E^T``: the diffuse power each side re-emits per watt each side emits;
        #: ``M = I - coupling``
        self.coupling = (scipy.sparse.diags(re_emitted) @ self.factors.matrix.T).tocsr()
        #: :meth:`group_absorption` by its absorptance and grouping
        self._group_absorption: dict[str, NDArray[np.float64]] = {}

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
        """Diffuse power ``W`` leaving each side [W], (n_sides,), for diffuse sources ``S`` [W]."""
        return self._solve(self.coupling, np.asarray(source_W, dtype=np.float64))

    @cached_property
    def functionals(self) -> NDArray[np.float64]:
        """The eight weights ``w`` (n_sides, 8) with ``w^T W`` the escaping momentum rate [W] (3), its
        moment about the origin [W m] (3), the escaped and the absorbed power [W]."""
        factors = self.factors
        absorbed = factors.matrix @ self.absorptance + factors.blind_fraction + factors.truncated_fraction
        return np.column_stack([escape_functionals(self.craft, factors), absorbed])

    def adjoint(self, weights: NDArray[np.float64]) -> NDArray[np.float64]:
        """``M^-T w`` for functionals ``w`` (n_sides, k): ``w^T W = (M^-T w)^T S`` for every source ``S``."""
        return self._solve(self.coupling.T.tocsr(), np.asarray(weights, dtype=np.float64))

    def group_absorption(
        self, absorptance: NDArray[np.float64], group: NDArray[np.int64], count: int
    ) -> NDArray[np.float64]:
        """``g = M^-T E (a 1_g)`` for each group of sides, (n_sides, count): ``g^T S`` is the diffuse power
        the sides of each group absorb for sources ``S``, with no forward solve.

        ``count`` adjoint solves, made once per absorptance and grouping and kept.

        Parameters
        ----------
        absorptance : (n_sides,) float64
            Share of the arriving light each side absorbs.
        group : (n_sides,) int64
            Group of each side (its part, say), in ``[0, count)``.
        count : int
            Number of groups.

        Returns
        -------
        (n_sides, count) float64

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.reflection import reflection_plan
        >>> white = sw.Material("white", reflectivity=0.8, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=white, threads=1).craft
        >>> exchange = reflection_plan(craft, sw.ReflectionSettings("full")).exchange
        >>> part, source = craft.facet_part[craft.side_facet], np.full(craft.n_sides, 1.0)
        >>> by_part = exchange.group_absorption(exchange.absorptance, part, 3).T @ source
        >>> arrived = exchange.factors.matrix.T @ exchange.solve(source)
        >>> bool(np.allclose(by_part, np.bincount(part, exchange.absorptance * arrived, 3), rtol=1e-9))
        True
        """
        group = np.ascontiguousarray(group, dtype=np.int64)
        key = hashlib.sha256(np.ascontiguousarray(absorptance, dtype=np.float64).tobytes() + group.tobytes())
        kept = self._group_absorption.get(key.hexdigest())
        if kept is None:
            indicator = np.zeros((len(group), count))
            indicator[np.arange(len(group)), group] = absorptance
            kept = np.ascontiguousarray(self.adjoint(self.factors.matrix @ indicator))
            self._group_absorption[key.hexdigest()] = kept
        return kept

    @cached_property
    def responses(self) -> NDArray[np.float64]:
        """``g = M^-T w`` for the :attr:`functionals`, (n_sides, 8): totals are ``g^T S``."""
        return np.ascontiguousarray(self.adjoint(self.functionals))

    def totals(self, source_W: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        """Escaping force and torque about ``reference_m`` and the power split, for sources ``S`` [W]."""
        return DiffuseTotals.from_sums(weighted_sum(self.responses, source_W), reference_m)

    @cached_property
    def open_sky_functionals(self) -> NDArray[np.float64]:
        """:attr:`functionals` as if every side saw only open sky (``e_esc = (2/3) n``, nothing
        absorbed), (n_sides, 8): what the direct law assumes of diffuse light."""
        craft = self.craft
        vector = LAMBERT_FACTOR * craft.side_normals
        moment = np.cross(craft.side_centroids, vector)
        n = craft.n_sides
        return np.column_stack([vector, moment, np.ones(n), np.zeros(n)])

    def totals_of(self, emitted_W: NDArray[np.float64], reference_m: NDArray[np.float64]) -> DiffuseTotals:
        """The same from a solved ``W`` (diffuse power leaving each side) instead of the sources."""
        return DiffuseTotals.from_sums(weighted_sum(self.functionals, emitted_W), reference_m)


def escape_functionals(craft: Spacecraft, factors: ExchangeFactors) -> NDArray[np.float64]:
    """The first seven of :attr:`DiffuseExchange.functionals` for exchange factors ``factors``: escaping
    momentum rate (3), its moment about the origin (3) and the escaped power, per watt each side emits.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    factors : ExchangeFactors
        Its exchange factors.

    Returns
    -------
    (n_sides, 7) float64

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.0), threads=1).craft
    >>> factors = ExchangeFactors.of_view(compute_view_factors(craft, rays_per_side=16))
    >>> escape_functionals(craft, factors)[0, 6]  # a convex box: everything escapes
    np.float64(1.0)
    """
    moment = np.cross(craft.side_centroids, factors.escape_vector) + factors.escape_moment
    return np.column_stack([factors.escape_vector, moment, factors.escape_fraction])


def diffuse_exchange(craft: Spacecraft, settings: ReflectionSettings) -> DiffuseExchange:
    """Diffuse exchange of ``craft`` with its view factors for ``settings``, built once and kept in its cache.

    Its exchange factors are kept on disk where ``settings`` says.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        Sampling and disk cache of the view factors.

    Returns
    -------
    DiffuseExchange
        The balance of the model's diffuse light.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> exchange = diffuse_exchange(craft, ReflectionSettings("full", cache_dir=False, rays_per_side=16))
    >>> source = np.zeros(craft.n_sides)
    >>> source[0] = 1.0  # 1 W emitted diffusely by side 0, whose normal is -x
    >>> exchange.functionals.shape, exchange.responses.shape
    ((12, 8), (12, 8))
    """
    return craft.cache.get(
        ("diffuse exchange", *settings.view_key),
        lambda: DiffuseExchange(craft, model_view_factors(craft, settings), cache_dir=settings.cache_dir),
    )


def weighted_sum(columns: NDArray[np.float64], weights: NDArray[np.float64]) -> NDArray[np.float64]:
    """Find ``columns.T @ weights``, reading only the rows of nonzero weights.

    Blocks of ``_BLOCK_SIDES`` rows are summed in parallel and added in block order, so the result has
    the same bits whatever the threads did (and no BLAS thread pool is left spinning, taking the cores
    from the next attitude's ray casting).

    Parameters
    ----------
    columns : (n, k) float64, C-ordered
        Per-side columns (adjoint responses).
    weights : (n,) float64
        Per-side weights (sources), mostly zero.

    Returns
    -------
    (k,) float64

    Examples
    --------
    >>> weighted_sum(np.arange(6.0).reshape(3, 2), np.array([0.0, 1.0, 2.0]))
    array([10., 13.])
    """
    n_blocks = -(-len(weights) // _BLOCK_SIDES)
    partial = np.zeros((n_blocks, columns.shape[1]))
    weights = np.ascontiguousarray(weights, dtype=np.float64)
    map_ranges(lambda lo, hi: _block_sums(columns, weights, partial, lo, hi), n_blocks, 2)
    return partial.sum(axis=0)


@numba.njit(cache=True, nogil=True)
def _block_sums(
    columns: NDArray[np.float64],
    weights: NDArray[np.float64],
    partial: NDArray[np.float64],
    first: int,
    last: int,
) -> None:
    """Row ``b`` of ``partial``: ``columns.T @ weights`` over block ``b`` of ``_BLOCK_SIDES`` rows, for
    blocks ``first`` to ``last - 1``."""
    for b in range(first, last):
        for i in range(b * _BLOCK_SIDES, min((b + 1) * _BLOCK_SIDES, weights.shape[0])):
            w = weights[i]
            if w != 0.0:
                for j in range(columns.shape[1]):
                    partial[b, j] += w * columns[i, j]
