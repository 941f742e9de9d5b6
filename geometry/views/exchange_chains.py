"""The chains of the exchange factors (:mod:`.exchange_factors`): a side's emission rays followed through
mirror reflections and transmissions until they escape, are absorbed, fade or meet too many surfaces,
tallied per emitting side in its own ray order (the same bits whatever the thread count)."""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft
from sunwind.geometry.views.hemisphere import emission_rays, side_key, uniform


class ChainTables(NamedTuple):
    """Hold what the chain kernels read: per-side arrays (contiguous), onward weights and the settings.

    Attributes
    ----------
    optics : (n_sides, 3) ndarray of float64
        ``rho, beta, sigma`` of each side.
    onward : (n_sides,) ndarray of float64
        Share each side sends on.
    solid : (n_sides,) ndarray of bool
        Sides of closed bodies.
    normals : (n_sides, 3) ndarray of float64
        Outward normals.
    centroids : (n_sides, 3) ndarray of float64
        Side centroids [m].
    onward_weight : (n_sides,) ndarray of float64
        ``q_i = sum_j F_ij onward_j``.
    offset_m : float
        Ray origins are pushed this far off their surface [m].
    half_size : float
        Scene unit [m].
    cutoff : float
        A chain ends below this share of its first weight.
    depth : int
        A chain ends after meeting this many surfaces.
    seed : numpy.uint64
        Seed of the rays.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> from sunwind.geometry.sides import SOLID
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> onward = craft.side_optics[:, 0] * craft.side_optics[:, 1] + craft.side_optics[:, 2]
    >>> tables = ChainTables(craft.side_optics, onward, craft.facet_kind[craft.side_facet] == SOLID,
    ...     craft.side_normals, craft.side_centroids, np.asarray(view.matrix @ onward), craft.scene.offset_m,
    ...     craft.scene.half_size, 1e-6, 256, np.uint64(view.seed))
    >>> tables.depth, round(float(tables.onward[0]), 3)
    (256, 0.25)
    """

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


def trace_chains(
    craft: Spacecraft, t: ChainTables, sides: NDArray[np.int64], grid: int
) -> tuple[NDArray, ...]:
    """Follow the emission rays of some sides beyond their first surface, tallying per side.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    t : ChainTables
        Per-side arrays and settings.
    sides : (count,) ndarray of int64
        The emitting sides.
    grid : int
        Strata per axis: ``grid**2`` rays per side.

    Returns
    -------
    rows, cols, weights : (k,) ndarray of int64, int64, float64
        Arrivals after the first surface: position in ``sides``, receiving side, summed weight.
    escape, vector, moment, blind, truncated : ndarray
        The batch's :class:`_Tallies`: per-side sums of escaping weight, its direction and moment, blind
        and truncated weight.
    chains : (1,) ndarray of int64
        Rays cast beyond the first surface.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> from sunwind.geometry.sides import SOLID
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> onward = craft.side_optics[:, 0] * craft.side_optics[:, 1] + craft.side_optics[:, 2]
    >>> tables = ChainTables(craft.side_optics, onward, craft.facet_kind[craft.side_facet] == SOLID,
    ...     craft.side_normals, craft.side_centroids, np.asarray(view.matrix @ onward), craft.scene.offset_m,
    ...     craft.scene.half_size, 1e-6, 256, np.uint64(view.seed))
    >>> rows, cols, weights, escape, *rest, chains = trace_chains(craft, tables, np.array([16, 17]), 8)
    >>> escape.shape, int(chains[0]), bool((weights > 0).all())
    ((2,), 13, True)
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
    t: ChainTables,
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
    t: ChainTables,
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
    t: ChainTables,
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
