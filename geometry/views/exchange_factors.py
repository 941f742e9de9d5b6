"""Specular-diffuse exchange factors: where each side's Lambertian emission arrives, through mirror
reflections and transmissions on the way (METHOD.md "Inter-reflection"; Sparrow & Cess, *Radiation
Heat Transfer*, ch. 3).

The view factor ``F_ij`` counts the first surface a ray of side ``i``'s diffuse emission meets. On a
side ``j`` that reflects a share ``rho_j beta_j`` specularly or lets ``sigma_j`` through, that share
of the light does not stay: it goes on as a ray. The exchange factor ``E_ij`` counts it wherever it
arrives::

    E_ij = share of side i's emission arriving at side j, directly or after any number of mirror
           reflections and transmissions (before j splits it)

Side ``j`` re-emits the diffuse share ``rho_j (1 - beta_j)`` of what arrives (the radiosity balance of
:mod:`sunwind.forces.reflection.diffuse`), absorbs ``1 - rho_j - sigma_j`` and sends the rest on. Where no
side reflects
specularly or transmits, ``E = F`` (:meth:`ExchangeFactors.of_view`).

``E = F + C``: the first arrivals are the view factors themselves (near-field entries included),
and ``C`` the arrivals after them. Side ``i`` sends on ``q_i = sum_j F_ij (rho_j beta_j + sigma_j)``
of its emission; to follow it, its emission rays are cast again with the view factors' sampling
code and seed (:func:`sunwind.geometry.views.view_factors.emission_rays`: the same rays where the view factors
cast at most :data:`CHAIN_RAYS` per side, a coarser stratified set of the same law where they cast
more, since only the onward share is sampled anew). A ray whose first surface ``j`` sends light on
carries ``q_i (rho_j beta_j + sigma_j) / sum_r (rho_jr beta_jr + sigma_jr)`` of it (a ratio estimator
over the side's rays: they carry exactly ``q_i`` between them) and is followed, as
:mod:`sunwind.forces.reflection.beams` follows beams:

* on a side with a mirror share the ray goes on along ``d - 2 (d . n) n`` with its weight times
  ``rho beta``; through a sheet (``sigma``) straight on, from the far side, times ``sigma``; a sheet
  with both picks one at random in proportion, carrying both shares (unbiased, one ray per chain);
* light a closed body transmits leaves unchanged along ``d``, as in the direct law;
* a chain ends when it escapes, meets a side the model does not have (``BLIND``: absorbed), carries
  less than ``cutoff`` of its first weight, or has met ``depth`` surfaces (``truncated``).

Escaping weight is tallied like the view factors' escape: ``f_esc`` the weight, ``e_esc`` the weight
times the final direction (the same ``(1/pi) cos`` normalisation, so ``(2/3) n`` for a side that sees
only sky) and ``m`` the weight times ``(p - c_i) x d`` on the final segment's line (``r x d`` is the
same at every point of a line). Per emitting side the weight balances to round-off::

    sum_j E_ij (1 - rho_j beta_j - sigma_j) + f_esc,i + f_blind,i + f_truncated,i = 1

Only rows that matter are followed: those of sides that re-emit diffusely (``rho (1 - beta) > 0``;
a side without has no diffuse sources) and see a side sending light on. On a model with none nothing
is cast. An unfollowed row keeps ``E = F`` with its ``q_i`` counted as truncated, as is the ``q_i``
of a side none of whose rays met a side sending light on (``q_i`` below about one ray's weight).

Random numbers (the pick on translucent mirrors) hash ``(seed, side, ray, depth)`` and each side's
chains are summed in its own ray order, so every result is the same bits whatever the thread count.
"""

from __future__ import annotations

import hashlib
import math
import os
import time
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.sides import SOLID
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.disk_cache import (
    cache_directory,
    check_balance,
    factor_arrays,
    factor_fields,
    geometry_key,
    kept_on_disk,
)
from sunwind.geometry.views.exchange_chains import ChainTables, trace_chains
from sunwind.geometry.views.hemisphere import map_side_batches
from sunwind.geometry.views.view_factors import ViewFactors

#: A chain ends when its weight falls below this share of the weight it started with.
EXCHANGE_CUTOFF = 1e-6
#: A chain ends after meeting this many surfaces (0.95**256 = 2e-6 for a good mirror).
EXCHANGE_DEPTH = 256
#: Emission rays per side followed beyond their first surface: the view factors' count, at most this
#: (a square). The first arrivals are the view factors themselves; only what goes on is sampled anew.
CHAIN_RAYS = 1024
#: Version of the method; part of the cache key.
METHOD_VERSION = 1


@dataclass(frozen=True, eq=False)
class ExchangeFactors:
    """Share of each side's Lambertian emission arriving at each side, through mirrors and sheets.

    Attributes
    ----------
    matrix : (n_sides, n_sides) scipy.sparse.csr_matrix, float64
        ``E_ij``: share of side i's emission arriving at side j, directly or after mirror reflections
        and transmissions, before j splits it.
    escape_fraction : (n_sides,) float64
        ``f_esc,i``: share that leaves to open sky, directly or after them.
    escape_vector : (n_sides, 3) float64
        ``e_esc,i``: escaping weight times its final direction, with the ``(1/pi) cos`` normalisation of
        :attr:`ViewFactors.escape_vector`; diffuse light of power ``W`` leaving side i and escaping
        pushes the model by ``-(W / c) e_esc,i`` [N].
    escape_moment : (n_sides, 3) float64 [m]
        ``m_i``: escaping weight times ``(p - c_i) x d`` (``p`` on its final line, ``c_i`` the side
        centroid); torque about ``r_ref`` ``-(W / c) [(c_i - r_ref) x e_esc,i + m_i]`` [N m].
    blind_fraction : (n_sides,) float64
        Share that meets a side the model does not have (absorbed there).
    truncated_fraction : (n_sides,) float64
        Share still travelling when its chain was dropped (cutoff, depth), and the onward share of a
        row not followed (module docstring); counted as absorbed.
    rays_per_side, seed : int
        Emission rays per side followed beyond their first surface, and their seed (the view
        factors').
    chains : int
        Rays followed beyond their first surface.
    seconds : float
        Time the computation took [s] (the original time when loaded from cache).
    origin : str
        "view factors" (nothing sends light on), "computed ..." or "cache <path>".

    Examples
    --------
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> exchange = compute_exchange_factors(craft, view)  # half of what is reflected goes on
    >>> exchange.origin, exchange.chains, exchange.matrix.shape
    ('computed', 163, (144, 144))
    >>> round(float(view.escape_fraction[16]), 4), round(float(exchange.escape_fraction[16]), 4)
    (0.8906, 0.918)
    """

    matrix: scipy.sparse.csr_matrix
    escape_fraction: NDArray[np.float64]
    escape_vector: NDArray[np.float64]
    escape_moment: NDArray[np.float64]
    blind_fraction: NDArray[np.float64]
    truncated_fraction: NDArray[np.float64]
    rays_per_side: int
    seed: int
    chains: int
    seconds: float
    origin: str

    @classmethod
    def of_view(cls, view: ViewFactors) -> ExchangeFactors:
        """Make the exchange factors ``E = F`` of a model no side of which sends arriving light on.

        Parameters
        ----------
        view : ViewFactors
            The model's view factors.

        Returns
        -------
        ExchangeFactors
            The view factors' arrays, nothing truncated, ``origin`` "view factors".

        Examples
        --------
        >>> from sunwind.geometry.views.view_factors import compute_view_factors
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> plain = ExchangeFactors.of_view(view)
        >>> plain.matrix is view.matrix, plain.chains, plain.origin
        (True, 0, 'view factors')
        """
        return cls(
            matrix=view.matrix,
            escape_fraction=view.escape_fraction,
            escape_vector=view.escape_vector,
            escape_moment=view.escape_moment,
            blind_fraction=view.blind_fraction,
            truncated_fraction=np.zeros(len(view.escape_fraction)),
            rays_per_side=view.rays_per_side,
            seed=view.seed,
            chains=0,
            seconds=0.0,
            origin="view factors",
        )

    def row_sum_error(self, onward: NDArray[np.float64]) -> NDArray[np.float64]:
        """Measure how far each side's emission is from balancing.

        Parameters
        ----------
        onward : (n_sides,) ndarray of float64
            The share each side sends on (:func:`onward_share`).

        Returns
        -------
        (n_sides,) ndarray of float64
            ``|sum_j E_ij (1 - onward_j) + f_esc,i + f_blind,i + f_truncated,i - 1|``.

        Examples
        --------
        >>> from sunwind.geometry.views.view_factors import compute_view_factors
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> exchange = compute_exchange_factors(craft, view)  # half of what is reflected goes on
        >>> float(exchange.row_sum_error(onward_share(craft.side_optics)).max()) < 1e-12
        True
        """
        stays = self.matrix @ (1.0 - onward)
        return np.abs(stays + self.escape_fraction + self.blind_fraction + self.truncated_fraction - 1)

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays [bytes].

        Returns
        -------
        int
            Bytes of the sparse matrix and the per-side arrays.

        Examples
        --------
        >>> from sunwind.geometry.views.view_factors import compute_view_factors
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> exchange = compute_exchange_factors(craft, view)  # half of what is reflected goes on
        >>> exchange.nbytes
        12496
        """
        m = self.matrix
        arrays = (
            self.escape_fraction,
            self.escape_vector,
            self.escape_moment,
            self.blind_fraction,
            self.truncated_fraction,
        )
        return m.data.nbytes + m.indices.nbytes + m.indptr.nbytes + sum(a.nbytes for a in arrays)


def onward_share(optics: NDArray[np.float64]) -> NDArray[np.float64]:
    """Find the share of arriving light each side sends on as a ray: ``rho beta + sigma``.

    Parameters
    ----------
    optics : (n_sides, 3) ndarray of float64
        ``rho, beta, sigma`` of each side.

    Returns
    -------
    (n_sides,) ndarray of float64
        The onward share.

    Examples
    --------
    >>> import numpy as np
    >>> onward_share(np.array([[0.5, 0.5, 0.0], [0.2, 0.0, 0.3]]))
    array([0.25, 0.3 ])
    """
    rho, beta, sigma = optics.T
    return rho * beta + sigma


# ---------------------------------------------------------------------------------------- computation


def compute_exchange_factors(
    craft: Spacecraft,
    view: ViewFactors,
    cutoff: float = EXCHANGE_CUTOFF,
    depth: int = EXCHANGE_DEPTH,
    optics: NDArray[np.float64] | None = None,
    rows: NDArray[np.int64] | None = None,
) -> ExchangeFactors:
    """Compute the exchange factors of a model from its view factors (see the module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    view : ViewFactors
        View factors of ``craft``; their rays (at most :data:`CHAIN_RAYS` per side) are cast again.
    cutoff : float
        A chain ends below this share of its first weight.
    depth : int
        A chain ends after meeting this many surfaces.
    optics : (n_sides, 3) ndarray of float64, optional
        ``rho, beta, sigma`` of every side; default ``craft.side_optics`` (sunlight's). Molecules give
        their own (:mod:`sunwind.forces.gas.exchange`).
    rows : (k,) int64, optional
        Follow the chains of these sides only; the other rows are the view factors' (first arrivals) and
        are not the exchange factors: for callers that read these rows alone. Default: every side.

    Returns
    -------
    ExchangeFactors
        ``E``, escape, blind and truncated shares; ``origin`` "computed".

    Examples
    --------
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> exchange = compute_exchange_factors(craft, view)  # half of what is reflected goes on
    >>> bool((exchange.matrix - view.matrix).min() >= 0)  # E = F + C, C the later arrivals
    True
    >>> black = np.zeros((craft.n_sides, 3))  # nothing sends light on: E = F
    >>> compute_exchange_factors(craft, view, optics=black).chains
    0
    """
    start = time.perf_counter()
    optics = np.ascontiguousarray(craft.side_optics if optics is None else optics, dtype=np.float64)
    onward = onward_share(optics)
    onward_weight = np.asarray(view.matrix @ onward)
    rho, beta, _ = optics.T
    emits = rho * (1 - beta) > 0
    traced = np.flatnonzero((onward_weight > 0) & emits)
    if rows is not None:
        traced = np.intersect1d(traced, rows)
    unfollowed = np.where(emits, 0.0, onward_weight)
    if not len(traced):
        plain = ExchangeFactors.of_view(view)
        return replace(plain, truncated_fraction=unfollowed, seconds=time.perf_counter() - start)
    grid = math.isqrt(min(view.rays_per_side, CHAIN_RAYS))
    scene = craft.scene
    tables = ChainTables(
        optics=optics,
        onward=np.ascontiguousarray(onward),
        solid=craft.facet_kind[craft.side_facet] == SOLID,
        normals=np.ascontiguousarray(craft.side_normals),
        centroids=np.ascontiguousarray(craft.side_centroids),
        onward_weight=onward_weight,
        offset_m=scene.offset_m,
        half_size=scene.half_size,
        cutoff=float(cutoff),
        depth=int(depth),
        seed=np.uint64(view.seed),
    )

    def batch(lo: int, hi: int) -> tuple[NDArray, ...]:
        rows, *rest = trace_chains(craft, tables, traced[lo:hi], grid)
        return traced[lo + rows], *rest

    parts = map_side_batches(batch, len(traced), grid**2)
    rows, cols, weights, escape, vector, moment, blind, truncated, chains = (
        np.concatenate(field) for field in zip(*parts, strict=True)
    )
    n = craft.n_sides
    onward_matrix = scipy.sparse.csr_matrix((weights, (rows, cols)), shape=(n, n))

    def plus(base: NDArray, extra: NDArray) -> NDArray:
        out = np.array(base, dtype=np.float64)
        out[traced] += extra
        return out

    return ExchangeFactors(
        matrix=(view.matrix + onward_matrix).tocsr(),
        escape_fraction=plus(view.escape_fraction, escape),
        escape_vector=plus(view.escape_vector, vector),
        escape_moment=plus(view.escape_moment, moment),
        blind_fraction=plus(view.blind_fraction, blind),
        truncated_fraction=plus(unfollowed, truncated),
        rays_per_side=grid**2,
        seed=view.seed,
        chains=int(chains.sum()),
        seconds=time.perf_counter() - start,
        origin="computed",
    )


# ----------------------------------------------------------------------------------------- disk cache


def _settings(optics: NDArray[np.float64], view: ViewFactors, cutoff: float, depth: int) -> dict[str, object]:
    """What besides the geometry the result depends on: the optics, the view factors and the method."""
    digest = hashlib.sha256()
    m = view.matrix
    for array in (
        optics,
        m.data,
        m.indices,
        m.indptr,
        view.escape_fraction,
        view.escape_vector,
        view.escape_moment,
        view.blind_fraction,
    ):
        data = np.ascontiguousarray(array)
        digest.update(f"{data.dtype.str}{data.shape}".encode())
        digest.update(data.tobytes())
    return {
        "what": "exchange_factors",
        "method": METHOD_VERSION,
        "rays_per_side": view.rays_per_side,
        "seed": view.seed,
        "cutoff": float(cutoff),
        "depth": int(depth),
        "optics_and_view": digest.hexdigest(),
    }


#: Per-side arrays of the exchange factors (width 1 or 3), and their numbers, as stored on disk.
_COLUMNS = {
    "escape_fraction": 1,
    "escape_vector": 3,
    "escape_moment": 3,
    "blind_fraction": 1,
    "truncated_fraction": 1,
}
_NUMBERS = ("chains", "seconds")


def exchange_factors(
    craft: Spacecraft,
    view: ViewFactors,
    cache_dir: str | os.PathLike | bool | None = False,
    optics: NDArray[np.float64] | None = None,
) -> ExchangeFactors:
    """Compute the exchange factors as :func:`compute_exchange_factors`, kept on disk when asked.

    They are read back when geometry, optics and view factors match; ``E = F`` at no cost where no side
    sends light on. ``origin`` says what happened, as for the view factors. Cache trouble is never an
    error.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    view : ViewFactors
        As for :func:`compute_exchange_factors`.
    cache_dir : path, bool or None
        Directory of the cache as for :func:`sunwind.geometry.views.view_factors.view_factors` (None or
        True: the default directory); False (the default): no disk cache.
    optics : (n_sides, 3) ndarray of float64, optional
        As for :func:`compute_exchange_factors`.

    Returns
    -------
    ExchangeFactors
        The factors, from the cache or computed.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> folder = tempfile.TemporaryDirectory()
    >>> exchange_factors(craft, view, cache_dir=folder.name).origin
    'computed (stored in cache .../exchange_factors-....npz)'
    >>> exchange_factors(craft, view, cache_dir=folder.name).origin
    'cache .../exchange_factors-....npz'
    >>> folder.cleanup()
    """
    directory = cache_directory(cache_dir)
    optics = np.ascontiguousarray(craft.side_optics if optics is None else optics, dtype=np.float64)
    if directory is None or not np.any(onward_share(optics) > 0):
        return compute_exchange_factors(craft, view, optics=optics)

    def decode(arrays, origin: str) -> ExchangeFactors:
        fields = factor_fields(arrays, len(view.escape_fraction), _COLUMNS, _NUMBERS)
        factors = ExchangeFactors(**fields, rays_per_side=view.rays_per_side, seed=view.seed, origin=origin)
        check_balance(factors.row_sum_error(onward_share(optics)))
        return factors

    return kept_on_disk(
        directory,
        "exchange_factors",
        geometry_key(craft, _settings(optics, view, EXCHANGE_CUTOFF, EXCHANGE_DEPTH)),
        lambda: compute_exchange_factors(craft, view, optics=optics),
        lambda factors: factor_arrays(factors, _COLUMNS, _NUMBERS),
        decode,
    )
