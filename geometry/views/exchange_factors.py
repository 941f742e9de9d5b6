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
from typing import NamedTuple

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.sides import SOLID
from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft
from sunwind.geometry.views.disk_cache import (
    CacheEntryError,
    cache_directory,
    geometry_key,
    read_entry,
    write_entry,
)
from sunwind.geometry.views.view_factors import (
    ViewFactors,
    emission_rays,
    map_side_batches,
    side_key,
    uniform,
)

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
        """``E = F``: the exchange factors of a model no side of which sends arriving light on."""
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
        """``|sum_j E_ij (1 - onward_j) + f_esc,i + f_blind,i + f_truncated,i - 1|`` per side, with
        ``onward`` (n_sides,) the share each side sends on (:func:`onward_share`)."""
        stays = self.matrix @ (1.0 - onward)
        return np.abs(stays + self.escape_fraction + self.blind_fraction + self.truncated_fraction - 1)

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays [bytes]."""
        m = self.matrix
        arrays = (
            self.escape_fraction,
            self.escape_vector,
            self.escape_moment,
            self.blind_fraction,
            self.truncated_fraction,
        )
        return m.data.nbytes + m.indices.nbytes + m.indptr.nbytes + sum(a.nbytes for a in arrays)


def onward_share(craft: Spacecraft) -> NDArray[np.float64]:
    """``rho beta + sigma`` of each side (n_sides,): the share of arriving light it sends on as a ray."""
    rho, beta, sigma = craft.side_optics.T
    return rho * beta + sigma


# ---------------------------------------------------------------------------------------- computation


def compute_exchange_factors(
    craft: Spacecraft, view: ViewFactors, cutoff: float = EXCHANGE_CUTOFF, depth: int = EXCHANGE_DEPTH
) -> ExchangeFactors:
    """Exchange factors of ``craft`` from its view factors ``view`` (see the module docstring).

    Parameters
    ----------
    craft : Spacecraft
    view : ViewFactors
        View factors of ``craft``; their rays (at most :data:`CHAIN_RAYS` per side) are cast again.
    cutoff : float
        A chain ends below this share of its first weight.
    depth : int
        A chain ends after meeting this many surfaces.
    """
    start = time.perf_counter()
    onward = onward_share(craft)
    onward_weight = np.asarray(view.matrix @ onward)
    rho, beta, _ = craft.side_optics.T
    emits = rho * (1 - beta) > 0
    traced = np.flatnonzero((onward_weight > 0) & emits)
    unfollowed = np.where(emits, 0.0, onward_weight)
    if not len(traced):
        plain = ExchangeFactors.of_view(view)
        return replace(plain, truncated_fraction=unfollowed, seconds=time.perf_counter() - start)
    grid = math.isqrt(min(view.rays_per_side, CHAIN_RAYS))
    scene = craft.scene
    tables = _Tables(
        optics=craft.side_optics,
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
        rows, *rest = _trace(craft, tables, traced[lo:hi], grid)
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


class _Tables(NamedTuple):
    """What the kernels read: per-side arrays (contiguous), each side's onward weight and the
    settings."""

    optics: NDArray[np.float64]  # (n_sides, 3) rho, beta, sigma
    onward: NDArray[np.float64]  # (n_sides,) share sent on
    solid: NDArray[np.bool_]  # (n_sides,) side of a closed body
    normals: NDArray[np.float64]  # (n_sides, 3) outward
    centroids: NDArray[np.float64]  # (n_sides, 3) [m]
    onward_weight: NDArray[np.float64]  # (n_sides,) q_i = sum_j F_ij onward_j
    offset_m: float  # ray origins pushed this far off their surface [m]
    half_size: float  # scene unit [m]
    cutoff: float
    depth: int
    seed: np.uint64


class _Tallies(NamedTuple):
    """Per-emitter sums of a batch, added to in place by the kernels (see :class:`ExchangeFactors`)."""

    escape: NDArray[np.float64]  # (count,)
    vector: NDArray[np.float64]  # (count, 3)
    moment: NDArray[np.float64]  # (count, 3)
    blind: NDArray[np.float64]  # (count,)
    truncated: NDArray[np.float64]  # (count,)


def _trace(craft: Spacecraft, t: _Tables, sides: NDArray[np.int64], grid: int) -> tuple[NDArray, ...]:
    """Follow the emission rays of ``sides`` beyond their first surface; per-side tallies.

    Returns
    -------
    rows, cols, weights : (k,) int64, int64, float64
        Arrivals after the first surface: position in ``sides``, receiving side, summed weight.
    escape, vector, moment, blind, truncated
        The batch's :class:`_Tallies`.
    chains : (1,) int64
        Rays cast beyond the first surface.
    """
    scene = craft.scene
    count = len(sides)
    origins, directions, lever = emission_rays(craft, sides, grid, t.seed)
    facets, distance = scene.intersect(origins, directions)
    struck = craft.struck_sides(facets, directions)
    tallies = _Tallies(
        np.zeros(count), np.zeros((count, 3)), np.zeros((count, 3)), np.zeros(count), np.zeros(count)
    )
    rays = _first_landings(t, tallies, sides, grid * grid, struck, distance, directions, lever)
    arrivals, chains = [(np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0))], 0
    while len(rays[0]):
        emitter, origin, direction, weight = rays[0], rays[3], rays[4], rays[5]
        chains += len(emitter)
        facets, distance = scene.intersect(scene.to_scene(origin), direction.astype(np.float32))
        struck = craft.struck_sides(facets, direction)
        landed = struck >= 0
        arrivals.append((emitter[landed], struck[landed], weight[landed]))
        rays = _arrive(t, tallies, sides, grid * grid, rays, struck, distance)
    merged = _merge(*(np.concatenate(field) for field in zip(*arrivals, strict=True)))
    return (*merged, *tallies, np.array([chains]))


def _merge(owner: NDArray, side: NDArray, weight: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """Sum the weights of equal ``(owner, side)``, in arrival order; rows and cols ascending."""
    order = np.lexsort((side, owner))  # stable: equal pairs keep their arrival order
    owner, side, weight = owner[order], side[order], weight[order]
    if not len(weight):
        return owner, side, weight
    starts = np.flatnonzero(np.r_[True, (owner[1:] != owner[:-1]) | (side[1:] != side[:-1])])
    return owner[starts], side[starts], np.add.reduceat(weight, starts)


# ------------------------------------------------------------------------------------------- kernels


@numba.njit(cache=True, nogil=True)
def _onto(point: NDArray, side: int, normals: NDArray, centroids: NDArray) -> None:
    """Project ``point`` [m] onto the plane of ``side``, in place."""
    h = 0.0
    for c in range(3):
        h += (point[c] - centroids[side, c]) * normals[side, c]
    for c in range(3):
        point[c] -= h * normals[side, c]


@numba.njit(cache=True, nogil=True)
def _leave(tallies: _Tallies, k: int, w: float, at: NDArray, d: NDArray, centroid: NDArray) -> None:
    """Weight ``w`` of emitter ``k`` (centroid ``centroid`` [m]) escaping along ``d`` on the line
    through ``at`` [m]."""
    tallies.escape[k] += w
    l0, l1, l2 = at[0] - centroid[0], at[1] - centroid[1], at[2] - centroid[2]
    tallies.vector[k, 0] += w * d[0]
    tallies.vector[k, 1] += w * d[1]
    tallies.vector[k, 2] += w * d[2]
    tallies.moment[k, 0] += w * (l1 * d[2] - l2 * d[1])
    tallies.moment[k, 1] += w * (l2 * d[0] - l0 * d[2])
    tallies.moment[k, 2] += w * (l0 * d[1] - l1 * d[0])


@numba.njit(cache=True, nogil=True)
def _new_rays(size: int) -> tuple:
    """Empty ray arrays of ``size`` rows: emitter, ray, level, origin [m], direction, weight, first."""
    return (
        np.empty(size, dtype=np.int64),
        np.empty(size, dtype=np.int64),
        np.empty(size, dtype=np.int64),
        np.empty((size, 3)),
        np.empty((size, 3)),
        np.empty(size),
        np.empty(size),
    )


@numba.njit(cache=True, nogil=True)
def _rays_out(out: tuple, m: int) -> tuple:
    """The first ``m`` rows of ray arrays ``out``."""
    emitter, ray, level, origin, direction, weight, first = out
    return (
        emitter[:m].copy(),
        ray[:m].copy(),
        level[:m].copy(),
        origin[:m].copy(),
        direction[:m].copy(),
        weight[:m].copy(),
        first[:m].copy(),
    )


@numba.njit(cache=True, nogil=True)
def _send_on(
    t: _Tables,
    tallies: _Tallies,
    out: tuple,
    m: int,
    ray: tuple,
    side: int,
    point: NDArray,
    d: NDArray,
    weight: float,
    n: int,
) -> int:
    """Split the weight arriving at ``side`` (at ``point`` [m] along ``d``): a closed body's transmitted
    share leaves along ``d``; the mirror or sheet share goes on as the ray written at row ``m`` of
    ``out``, unless below the cutoff or past the depth. ``ray`` is (position of the emitter in the
    batch, its side, ray index, surfaces met, first weight). Returns the next free row."""
    k, emitter, index, level, first = ray
    rho, beta, sigma = t.optics[side, 0], t.optics[side, 1], t.optics[side, 2]
    mirror = rho * beta
    if t.solid[side] and sigma > 0.0:
        _leave(tallies, k, weight * sigma, point, d, t.centroids[emitter])
        sigma = 0.0
    going = weight * (mirror + sigma)
    if going <= 0.0:
        return m
    if going < t.cutoff * first or level >= t.depth:
        tallies.truncated[k] += going
        return m
    through = mirror == 0.0
    if mirror > 0.0 and sigma > 0.0:
        u = uniform(side_key(t.seed, emitter), 5 * n + 1 + index * (t.depth + 1) + level)
        through = u * (mirror + sigma) >= mirror
    o_emitter, o_ray, o_level, o_origin, o_direction, o_weight, o_first = out
    normal = t.normals[side]
    dn = d[0] * normal[0] + d[1] * normal[1] + d[2] * normal[2]
    lift = -t.offset_m if through else t.offset_m
    for c in range(3):
        o_direction[m, c] = d[c] if through else d[c] - 2.0 * dn * normal[c]
        o_origin[m, c] = point[c] + lift * normal[c]
    o_emitter[m], o_ray[m], o_level[m] = k, index, level
    o_weight[m], o_first[m] = going, first
    return m + 1


@numba.njit(cache=True, nogil=True)
def _first_landings(
    t: _Tables,
    tallies: _Tallies,
    sides: NDArray[np.int64],
    n: int,
    struck: NDArray[np.int64],
    distance: NDArray[np.float32],
    directions: NDArray[np.float32],
    lever: NDArray[np.float64],
) -> tuple:
    """Rays going on from the first surface of the ``n`` emission rays of each of ``sides``, sharing
    its onward weight ``q_i`` (a side none of whose rays meets a side sending light on puts it in
    ``truncated``). ``struck``, ``distance`` (scene units), ``directions`` and ``lever`` are those of
    :func:`sunwind.geometry.views.view_factors.emission_rays`."""
    out = _new_rays(sides.shape[0] * n)
    m = 0
    point = np.empty(3)
    d = np.empty(3)
    for k in range(sides.shape[0]):
        s = sides[k]
        sampled = 0.0
        for r in range(k * n, (k + 1) * n):
            if struck[r] >= 0:
                sampled += t.onward[struck[r]]
        if sampled == 0.0:
            tallies.truncated[k] += t.onward_weight[s]
            continue
        weight = t.onward_weight[s] / sampled
        for r in range(k * n, (k + 1) * n):
            j = struck[r]
            if j < 0 or t.onward[j] == 0.0:
                continue
            reach = float(distance[r]) * t.half_size
            for c in range(3):
                d[c] = float(directions[r, c])
                point[c] = t.centroids[s, c] + lever[r, c] + t.offset_m * t.normals[s, c] + reach * d[c]
            _onto(point, j, t.normals, t.centroids)
            m = _send_on(t, tallies, out, m, (k, s, r - k * n, 1, weight), j, point, d, weight, n)
    return _rays_out(out, m)


@numba.njit(cache=True, nogil=True)
def _arrive(
    t: _Tables,
    tallies: _Tallies,
    sides: NDArray[np.int64],
    n: int,
    rays: tuple,
    struck: NDArray[np.int64],
    distance: NDArray[np.float32],
) -> tuple:
    """``rays`` met ``struck`` at ``distance`` (scene units): tally escapes and blind hits, and return
    the rays going on from the surfaces met."""
    emitter, index, level, origin, direction, weight, first = rays
    out = _new_rays(emitter.shape[0])
    m = 0
    point = np.empty(3)
    for r in range(emitter.shape[0]):
        k, j = emitter[r], struck[r]
        s = sides[k]
        d = direction[r]
        if j == ESCAPED:
            _leave(tallies, k, weight[r], origin[r], d, t.centroids[s])
        elif j == BLIND:
            tallies.blind[k] += weight[r]
        elif t.onward[j] > 0:
            reach = float(distance[r]) * t.half_size
            for c in range(3):
                point[c] = origin[r, c] + reach * d[c]
            _onto(point, j, t.normals, t.centroids)
            ray = (k, s, index[r], level[r] + 1, first[r])
            m = _send_on(t, tallies, out, m, ray, j, point, d, weight[r], n)
    return _rays_out(out, m)


# ----------------------------------------------------------------------------------------- disk cache


def _settings(craft: Spacecraft, view: ViewFactors, cutoff: float, depth: int) -> dict[str, object]:
    """What besides the geometry the result depends on: the optics, the view factors and the method."""
    digest = hashlib.sha256()
    m = view.matrix
    for array in (
        craft.side_optics,
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


def _to_arrays(factors: ExchangeFactors) -> dict[str, NDArray]:
    m = factors.matrix
    return {
        "data": m.data,
        "indices": m.indices,
        "indptr": m.indptr,
        "escape_fraction": factors.escape_fraction,
        "escape_vector": factors.escape_vector,
        "escape_moment": factors.escape_moment,
        "blind_fraction": factors.blind_fraction,
        "truncated_fraction": factors.truncated_fraction,
        "chains": np.array(factors.chains),
        "seconds": np.array(factors.seconds),
    }


def _from_arrays(arrays: dict[str, NDArray], view: ViewFactors, origin: str) -> ExchangeFactors:
    """The entry's exchange factors; CacheEntryError where its arrays do not fit the model."""
    n = len(view.escape_fraction)
    try:
        indptr, indices, data = arrays["indptr"], arrays["indices"], arrays["data"]
        vectors = ("escape_vector", "escape_moment")
        fits = (
            indptr.shape == (n + 1,)
            and indices.shape == data.shape == (indptr[-1],)
            and all(
                arrays[k].shape == (n,) for k in ("escape_fraction", "blind_fraction", "truncated_fraction")
            )
            and all(arrays[k].shape == (n, 3) for k in vectors)
        )
        if not fits:
            raise CacheEntryError("was corrupt (arrays of the wrong shape)")
        return ExchangeFactors(
            matrix=scipy.sparse.csr_matrix((data, indices, indptr), shape=(n, n)),
            escape_fraction=arrays["escape_fraction"],
            escape_vector=arrays["escape_vector"],
            escape_moment=arrays["escape_moment"],
            blind_fraction=arrays["blind_fraction"],
            truncated_fraction=arrays["truncated_fraction"],
            rays_per_side=view.rays_per_side,
            seed=view.seed,
            chains=int(arrays["chains"]),
            seconds=float(arrays["seconds"]),
            origin=origin,
        )
    except (KeyError, IndexError, ValueError) as error:
        raise CacheEntryError(f"was corrupt ({type(error).__name__}: {error})") from error


def exchange_factors(
    craft: Spacecraft, view: ViewFactors, cache_dir: str | os.PathLike | bool | None = False
) -> ExchangeFactors:
    """:func:`compute_exchange_factors`, kept on disk and read back when geometry, optics and view
    factors match; ``E = F`` at no cost where no side sends light on.

    Parameters
    ----------
    craft, view
        As for :func:`compute_exchange_factors`.
    cache_dir : path, bool or None
        Directory of the cache as for :func:`sunwind.geometry.views.view_factors.view_factors` (None or True:
        the
        default directory); False (the default): no disk cache.

    ``origin`` says what happened, as for the view factors. Cache trouble is never an error.
    """
    directory = cache_directory(cache_dir)
    if directory is None or not np.any(onward_share(craft) > 0):
        return compute_exchange_factors(craft, view)
    key = geometry_key(craft, _settings(craft, view, EXCHANGE_CUTOFF, EXCHANGE_DEPTH))
    path = directory / f"exchange_factors-{key[:32]}.npz"
    notes = []
    try:
        return _from_arrays(read_entry(path, key), view, f"cache {path}")
    except FileNotFoundError:
        pass
    except CacheEntryError as problem:
        notes.append(f"cache entry {path} {problem}: rebuilt")
    factors = compute_exchange_factors(craft, view)
    try:
        write_entry(path, key, _to_arrays(factors))
        notes.append(f"stored in cache {path}")
    except OSError as error:
        notes.append(f"cache {directory} not writable ({error}): not stored")
    return replace(factors, origin=f"computed ({'; '.join(notes)})")
