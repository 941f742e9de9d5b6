"""View factors between sides and the escape vectors of their diffuse emission, by Embree ray sampling.

METHOD.md "Inter-reflection" and "Speed": ``F_ij`` and ``e_esc`` depend on geometry alone, so they are
computed once per model (the paper's array ``PRB``), kept on disk, and reused for every attitude, for
light and gas alike.

Each side emits ``rays_per_side = g**2`` rays: origins at one uniform point in each of ``g**2`` equal-area
strata of its triangle (a ``g x g`` jittered grid through the area-preserving square-to-triangle map of
Heitz 2019), pushed ``scene.offset_m`` along the side normal; directions cosine-weighted, one in each
cell of a ``g x g`` jittered grid through the concentric disk map of Shirley & Chiu 1997, turned by a
random angle about the normal. A seeded permutation pairs points with directions. Random numbers are
a hash of ``(seed, side, index)``, so every side's rays, and every result, are the same bits whatever
the thread count or batch size.

A ray that meets side ``j`` counts toward ``F_ij``; one that meets a side the model does not have
(``BLIND``) toward ``blind_fraction``. Escape uses the exact unobstructed hemisphere as control
variate, so a side that sees only sky gets ``f_esc = 1``, ``e_esc = (2/3) n_out`` and ``m = 0`` exactly,
and every row sums to one to round-off::

    f_esc = 1 - blocked / N,   e_esc = (2/3) n_out - (1/N) sum_blocked w,
    m = -(1/N) sum_blocked (o - c) x w        (o on the side's surface, c its centroid)

Near field: sampling noise is largest, relative to the value, between edge-adjacent sides that meet
at a concave edge. There ``F_ij`` is integrated instead, unoccluded: Lambert's contour formula for the
view factor from a point to the neighbour triangle, over the emitting triangle with a tensor
Gauss-Legendre rule graded geometrically toward the shared edge and its ends (relative error ~1e-6).

The row keeps summing to one by a ratio estimator: the rest of the row (other sides, escape, blind) is
rescaled by ``(1 - integrated) / (1 - sampled)`` of the near entries. Adding the difference to the escape
share instead would open a closed cavity whenever the sampled near value happened to exceed the exact
one. ``escape_vector`` and ``escape_moment`` keep their sampled (unbiased) values.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import TypeVar

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft
from sunwind.geometry.triangles import STRATIFIED_SEED
from sunwind.geometry.views.disk_cache import (
    CacheEntryError,
    cache_directory,
    geometry_key,
    read_entry,
    write_entry,
)

#: Seed of the emission rays.
VIEW_SEED = STRATIFIED_SEED
#: Bounds of the default rays per side: ``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // n_sides))`` rounded
#: down to a square ``g**2`` (the ``g x g`` grids stratify points and directions alike). 2**24 rays
#: take ~3 s of CPU (made, cast by Embree and tallied); 256 rays (g = 16) keep the noise of one ``F_ij``
#: below ``0.5 / sqrt(256) = 3 %`` absolute, and far less on sums over many sides.
MIN_RAYS, MAX_RAYS, TOTAL_RAYS = 256, 16_384, 2**24
#: Rays per batch of sides, made, cast and tallied in turn by one thread: ~60 bytes each, ~16 MB.
_BATCH_RAYS = 1 << 18
#: Near-field rule: Gauss-Legendre of ``NEAR_ORDER`` points on intervals graded by ``NEAR_RATIO``:
#: ``NEAR_LEVELS_EDGE + 1`` intervals from the shared edge across the triangle, ``NEAR_LEVELS_ENDS + 1``
#: from each end of the edge to its middle; 750 points per pair, relative error ~1e-6.
NEAR_ORDER, NEAR_RATIO, NEAR_LEVELS_EDGE, NEAR_LEVELS_ENDS = 5, 0.25, 4, 2
#: Height of a neighbour's centroid above a side's plane, as a share of the side's size
#: ``sqrt(area)``, beyond which the edge counts as concave (below it the pair is coplanar: F = 0).
CONCAVE_TOLERANCE = 1e-7
#: Version of the method; part of the cache key, so changing the method never reads old entries.
METHOD_VERSION = 1

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)

T = TypeVar("T")


@dataclass(frozen=True, eq=False)
class ViewFactors:
    """Share of each side's Lambertian emission reaching each other side, the sky or a blind side.

    Attributes
    ----------
    matrix : (n_sides, n_sides) scipy.sparse.csr_matrix, float64
        ``F_ij``: share of side i's emission that first strikes side j.
    escape_fraction : (n_sides,) float64
        ``f_esc,i``: share that leaves to open sky.
    escape_vector : (n_sides, 3) float64
        ``e_esc,i = (1/pi) * integral over open sky of cos(theta) w dOmega``, averaged over the side's
        area, body frame; ``(2/3) n_out`` for a side that sees only sky. Diffuse light of power ``W``
        leaving side i pushes it by ``-(W / c) e_esc,i`` [N].
    escape_moment : (n_sides, 3) float64 [m]
        ``m_i``: the same average of ``(r - c_i) x w`` (``r`` the emission point, ``c_i`` the side
        centroid); the torque of that escaping light about ``r_ref`` is
        ``-(W / c) [(c_i - r_ref) x e_esc,i + m_i]`` [N m]. Zero for a side that sees only sky.
    blind_fraction : (n_sides,) float64
        Share that strikes a side the model does not have (absorbed there).
    rays_per_side : int
    seed : int
    seconds : float
        Time the computation took [s] (the original time when loaded from cache).
    origin : str
        "computed ..." or "cache <path>".
    """

    matrix: scipy.sparse.csr_matrix
    escape_fraction: NDArray[np.float64]
    escape_vector: NDArray[np.float64]
    escape_moment: NDArray[np.float64]
    blind_fraction: NDArray[np.float64]
    rays_per_side: int
    seed: int
    seconds: float
    origin: str

    def row_sum_error(self) -> NDArray[np.float64]:
        """``|sum_j F_ij + f_esc,i + f_blind,i - 1|`` of each side, (n_sides,)."""
        rows = np.asarray(self.matrix.sum(axis=1)).ravel()
        return np.abs(rows + self.escape_fraction + self.blind_fraction - 1)

    def reciprocity_error(self, areas: NDArray[np.float64]) -> float:
        """``sum |A_i F_ij - A_j F_ji| / sum A_i F_ij`` over all pairs; 0 where no side sees another.

        ``areas`` : (n_sides,) side areas [m^2]. Sampling noise sets its size: about ``1 / sqrt(hits)``
        of a typical pair, so it is large for fine meshes whose pairs get few hits each.
        """
        exchange = scipy.sparse.diags(np.asarray(areas, dtype=np.float64)) @ self.matrix
        total = exchange.sum()
        return float(abs(exchange - exchange.T).sum() / total) if total > 0 else 0.0

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays [bytes]."""
        m = self.matrix
        arrays = (self.escape_fraction, self.escape_vector, self.escape_moment, self.blind_fraction)
        return m.data.nbytes + m.indices.nbytes + m.indptr.nbytes + sum(a.nbytes for a in arrays)


def default_rays_per_side(n_sides: int) -> int:
    """``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // n_sides))`` rounded down to a square."""
    return math.isqrt(max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // max(n_sides, 1)))) ** 2


def resolve_rays_per_side(rays_per_side: int | None, n_sides: int) -> int:
    """Rays per side to cast: the default for None, else ``rays_per_side`` rounded up to a square."""
    if rays_per_side is None:
        return default_rays_per_side(n_sides)
    integer = isinstance(rays_per_side, (int, np.integer)) and not isinstance(rays_per_side, bool)
    if not integer or rays_per_side < 1:
        raise InputError(f"rays_per_side = {rays_per_side!r} must be a positive integer")
    return (math.isqrt(int(rays_per_side) - 1) + 1) ** 2


# ---------------------------------------------------------------------------------------- computation


def compute_view_factors(
    craft: Spacecraft, rays_per_side: int | None = None, seed: int = VIEW_SEED, *, near_field: bool = True
) -> ViewFactors:
    """Sample view factors, escape fractions, escape vectors and moments of every side.

    Parameters
    ----------
    craft : Spacecraft
    rays_per_side : int, optional
        Rays per side, rounded up to a square; default :func:`default_rays_per_side`.
    seed : int
        Seed of the rays (non-negative, below 2**64).
    near_field : bool
        Integrate ``F_ij`` of concave edge-adjacent pairs (see the module notes); False keeps the
        sampled values (for comparison).
    """
    start = time.perf_counter()
    rays = resolve_rays_per_side(rays_per_side, craft.n_sides)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64:
        raise InputError(f"seed = {seed!r} must be an integer from 0 to 2**64 - 1")
    n = craft.n_sides
    nnz, cols, hits, blind, blocked, sum_w, sum_m = _sample(craft, math.isqrt(rays), seed)
    matrix = scipy.sparse.csr_matrix((hits / rays, cols, np.r_[0, np.cumsum(nnz)]), shape=(n, n))
    escape = (rays - blocked) / rays
    blind_fraction = blind / rays
    if near_field:
        matrix, scale = _with_near_field(craft, matrix)
        escape, blind_fraction = escape * scale, blind_fraction * scale
    return ViewFactors(
        matrix=matrix,
        escape_fraction=escape,
        escape_vector=(2 / 3) * craft.side_normals - sum_w / rays,
        escape_moment=-sum_m / rays,
        blind_fraction=blind_fraction,
        rays_per_side=rays,
        seed=int(seed),
        seconds=time.perf_counter() - start,
        origin="computed",
    )


def _sample(craft: Spacecraft, grid: int, seed: int) -> tuple[NDArray, ...]:
    """Cast ``grid**2`` rays from every side in threaded batches; the per-side tallies of
    :func:`_tally`, concatenated in side order."""
    scene = craft.scene

    def batch(lo: int, hi: int) -> tuple[NDArray, ...]:
        origins, directions, lever = emission_rays(craft, np.arange(lo, hi), grid, seed)
        struck = craft.struck_sides(scene.first_hit(origins, directions), directions)
        return _tally(struck, directions, lever, grid**2)

    tallies = map_side_batches(batch, craft.n_sides, grid**2)
    return tuple(np.concatenate(field) for field in zip(*tallies, strict=True))


def map_side_batches(function: Callable[[int, int], T], n: int, rays_per_side: int) -> list[T]:
    """``[function(lo, hi) for each batch]`` over ``range(n)`` in batches of about ``_BATCH_RAYS`` rays
    (``rays_per_side`` per item), made, cast and tallied in turn by one thread; results in order.

    Batch boundaries follow the thread count: ``function`` must treat every item on its own.
    """
    per_batch = max(1, _BATCH_RAYS // rays_per_side)

    def work(lo: int, hi: int) -> list[T]:
        return [function(s, min(s + per_batch, hi)) for s in range(lo, hi, per_batch)]

    return [t for chunk in map_ranges(work, n, per_batch) for t in chunk]


def emission_rays(
    craft: Spacecraft, sides: NDArray[np.int64], grid: int, seed: int
) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float64]]:
    """The ``grid**2`` emission rays of each of ``sides`` with ``seed``: origins (scene coordinates,
    float32), directions (float32) and levers (surface point minus side centroid [m]), ray ``r`` of
    ``sides[k]`` at row ``k grid**2 + r`` (see the module docstring and :func:`_emission_rays`)."""
    scene = craft.scene
    return _emission_rays(
        craft.triangles,
        craft.side_facet,
        craft.side_normals,
        np.asarray(sides, dtype=np.int64),
        grid,
        np.uint64(seed),
        scene.centre,
        scene.half_size,
        scene.offset_m,
    )


@numba.njit(cache=True, nogil=True)
def _mix(z: np.uint64) -> np.uint64:
    """SplitMix64 finaliser: a bijective hash of 64-bit integers."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@numba.njit(cache=True, nogil=True)
def side_key(seed: np.uint64, side: int) -> np.uint64:
    """Key of the random numbers of ``side``'s rays under ``seed``."""
    return _mix(seed ^ _mix(np.uint64(side) + _GOLDEN))


@numba.njit(cache=True, nogil=True)
def uniform(key: np.uint64, index: int) -> float:
    """Random number in [0, 1), a hash of ``key`` and ``index``."""
    return float(_mix(key + np.uint64(index + 1) * _GOLDEN) >> np.uint64(11)) * 2.0**-53


@numba.njit(cache=True, nogil=True)
def _disk(a: float, b: float) -> tuple[float, float]:
    """Concentric map (Shirley & Chiu 1997) of the unit square onto the unit disk, area-preserving."""
    a, b = 2 * a - 1, 2 * b - 1
    if a == 0 and b == 0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        r, phi = a, (math.pi / 4) * (b / a)
    else:
        r, phi = b, math.pi / 2 - (math.pi / 4) * (a / b)
    return r * math.cos(phi), r * math.sin(phi)


@numba.njit(cache=True, nogil=True)
def _square_to_triangle(a: float, b: float) -> tuple[float, float]:
    """Low-distortion area-preserving map (Heitz 2019) of the unit square onto barycentrics (b1, b2)."""
    if b > a:
        a *= 0.5
        return a, b - a
    b *= 0.5
    return a - b, b


@numba.njit(cache=True, nogil=True)
def _frame(n: NDArray[np.float64], angle: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two unit tangents completing the unit normal ``n`` to a right-handed frame, turned by ``angle``
    about it (branchless frame of Duff et al. 2017)."""
    sign = math.copysign(1.0, n[2])
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    t1 = np.array([1 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]])
    t2 = np.array([b, sign + n[1] * n[1] * a, -n[1]])
    c, s = math.cos(angle), math.sin(angle)
    return c * t1 + s * t2, c * t2 - s * t1


@numba.njit(cache=True, nogil=True)
def _emission_rays(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    sides: NDArray[np.int64],
    grid: int,
    seed: np.uint64,
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float64]]:
    """The ``grid**2`` emission rays of each of ``sides`` (see the module docstring).

    Returns
    -------
    origins : (count * grid**2, 3) float32
        Scene coordinates, pushed ``offset_m`` off the surface.
    directions : (count * grid**2, 3) float32
        Unit, body frame, cosine-weighted about the side normal.
    lever : (count * grid**2, 3) float64
        Surface point minus side centroid [m].
    """
    n = grid * grid
    count = sides.shape[0]
    origins = np.empty((count * n, 3), dtype=np.float32)
    directions = np.empty((count * n, 3), dtype=np.float32)
    lever = np.empty((count * n, 3))
    order = np.empty(n, dtype=np.int64)
    third = 1.0 / 3.0
    for k in range(count):
        s = sides[k]
        key = side_key(seed, s)
        # random numbers: direction jitter [0, 2n), point jitter [2n, 4n), pairing [4n, 5n), turn 5n
        # (above 5n: picks of the exchange factors' chains)
        for i in range(n):
            order[i] = i
        for i in range(n - 1, 0, -1):
            j = int(uniform(key, 4 * n + i) * (i + 1))
            order[i], order[j] = order[j], order[i]
        normal = normals[s]
        t1, t2 = _frame(normal, 2 * math.pi * uniform(key, 5 * n))
        corners = triangles[side_facet[s]]
        for i in range(n):
            x, y = _disk(
                (i // grid + uniform(key, 2 * i)) / grid, (i % grid + uniform(key, 2 * i + 1)) / grid
            )
            z = math.sqrt(max(0.0, 1.0 - x * x - y * y))
            c = order[i]
            b1, b2 = _square_to_triangle(
                (c // grid + uniform(key, 2 * n + 2 * c)) / grid,
                (c % grid + uniform(key, 2 * n + 2 * c + 1)) / grid,
            )
            b0 = 1.0 - b1 - b2
            r = k * n + i
            for d in range(3):
                point = b0 * corners[0, d] + b1 * corners[1, d] + b2 * corners[2, d]
                lever[r, d] = (
                    (b0 - third) * corners[0, d] + (b1 - third) * corners[1, d] + (b2 - third) * corners[2, d]
                )
                origins[r, d] = (point + offset_m * normal[d] - centre[d]) / half_size
                directions[r, d] = x * t1[d] + y * t2[d] + z * normal[d]
    return origins, directions, lever


@numba.njit(cache=True, nogil=True)
def _tally(
    struck: NDArray[np.int64], directions: NDArray[np.float32], lever: NDArray[np.float64], n: int
) -> tuple[NDArray, ...]:
    """Per-side sums of ``n`` consecutive rays per side, in ray order.

    Returns
    -------
    nnz : (count,) int64
        Distinct sides struck by each side's rays.
    cols, hits : (sum(nnz),) int64
        Those sides, ascending per emitting side, and their ray counts.
    blind, blocked : (count,) int64
        Rays that struck a blind side; rays that struck anything.
    sum_w, sum_m : (count, 3) float64
        Sums of ``w`` and of ``lever x w`` over the blocked rays.
    """
    count = struck.shape[0] // n
    nnz = np.zeros(count, dtype=np.int64)
    cols = np.empty(struck.shape[0], dtype=np.int64)
    hits = np.empty(struck.shape[0], dtype=np.int64)
    blind = np.zeros(count, dtype=np.int64)
    blocked = np.zeros(count, dtype=np.int64)
    sum_w = np.zeros((count, 3))
    sum_m = np.zeros((count, 3))
    targets = np.empty(n, dtype=np.int64)
    at = 0
    for k in range(count):
        m = 0
        for r in range(k * n, (k + 1) * n):
            target = struck[r]
            if target == ESCAPED:
                continue
            blocked[k] += 1
            w0, w1, w2 = float(directions[r, 0]), float(directions[r, 1]), float(directions[r, 2])
            l0, l1, l2 = lever[r, 0], lever[r, 1], lever[r, 2]
            sum_w[k, 0] += w0
            sum_w[k, 1] += w1
            sum_w[k, 2] += w2
            sum_m[k, 0] += l1 * w2 - l2 * w1
            sum_m[k, 1] += l2 * w0 - l0 * w2
            sum_m[k, 2] += l0 * w1 - l1 * w0
            if target == BLIND:
                blind[k] += 1
            else:
                targets[m] = target
                m += 1
        sides = np.sort(targets[:m])
        for i in range(m):
            if i == 0 or sides[i] != sides[i - 1]:
                cols[at] = sides[i]
                hits[at] = 0
                nnz[k] += 1
                at += 1
            hits[at - 1] += 1
    return nnz, cols[:at].copy(), hits[:at].copy(), blind, blocked, sum_w, sum_m


# ----------------------------------------------------------------------------------------- near field


def concave_pairs(craft: Spacecraft) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Edge-adjacent sides ``(a, b)``, a < b, each with the other's centroid in front of its plane."""
    a, b = craft.side_neighbours
    centroid, normal, size = craft.side_centroids, craft.side_normals, np.sqrt(craft.side_areas)
    gap = centroid[b] - centroid[a]
    above_a = np.einsum("nd,nd->n", gap, normal[a]) > CONCAVE_TOLERANCE * size[a]
    above_b = np.einsum("nd,nd->n", -gap, normal[b]) > CONCAVE_TOLERANCE * size[b]
    keep = above_a & above_b
    return a[keep], b[keep]


@lru_cache(maxsize=1)
def _near_rule() -> tuple[NDArray[np.float64], ...]:
    """Nodes and weights ``(u, wu, v, wv)`` on [0, 1] of the near-field rule: ``u`` graded toward 0
    (the shared edge), ``v`` toward both 0 and 1 (its ends)."""
    x, w = np.polynomial.legendre.leggauss(NEAR_ORDER)
    x, w = (x + 1) / 2, w / 2

    def graded(levels: int, length: float) -> tuple[NDArray, NDArray]:
        breaks = np.r_[0.0, NEAR_RATIO ** np.arange(levels, -1, -1.0)] * length
        lo, hi = breaks[:-1, None], breaks[1:, None]
        return (lo + (hi - lo) * x).ravel(), ((hi - lo) * w).ravel()

    u, wu = graded(NEAR_LEVELS_EDGE, 1.0)
    half, w_half = graded(NEAR_LEVELS_ENDS, 0.5)
    return u, wu, np.r_[half, 1 - half[::-1]], np.r_[w_half, w_half[::-1]]


def edge_pair_view_factors(
    emitters: NDArray[np.float64], normals: NDArray[np.float64], receivers: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Unoccluded view factor from each emitting triangle to its receiver, which lies in front of it.

    Parameters
    ----------
    emitters : (n, 3, 3) float64
        Corners ``(A, B, C)`` [m], ``AB`` the edge shared with the receiver (the rule is graded toward it).
    normals : (n, 3) float64
        Unit normal of each emitter's side, toward the receiver.
    receivers : (n, 3, 3) float64
        Receiver corners [m].

    Returns
    -------
    (n,) float64
    """
    u, wu, v, wv = _near_rule()
    out = np.empty(len(emitters))

    def work(lo: int, hi: int) -> None:
        out[lo:hi] = _edge_pair_kernel(emitters[lo:hi], normals[lo:hi], receivers[lo:hi], u, wu, v, wv)

    map_ranges(work, len(emitters), 256)
    return out


@numba.njit(cache=True, nogil=True)
def _point_view_factor(
    p0: float, p1: float, p2: float, n: NDArray[np.float64], corners: NDArray[np.float64]
) -> float:
    """View factor from a differential area at ``p`` [m] with unit normal ``n`` to a triangle in front
    of it, by Lambert's contour formula ``F = |sum_k gamma_k n . g_k| / (2 pi)``, ``g_k`` the unit
    vector along ``R_k x R_k+1`` and ``gamma_k`` the angle between ``R_k`` and ``R_k+1``
    (``R_k = corner_k - p``)."""
    total = 0.0
    for k in range(3):
        k1 = (k + 1) % 3
        x0, y0, z0 = corners[k, 0] - p0, corners[k, 1] - p1, corners[k, 2] - p2
        x1, y1, z1 = corners[k1, 0] - p0, corners[k1, 1] - p1, corners[k1, 2] - p2
        cx, cy, cz = y0 * z1 - z0 * y1, z0 * x1 - x0 * z1, x0 * y1 - y0 * x1
        length = math.sqrt(cx * cx + cy * cy + cz * cz)
        if length > 0.0:
            gamma = math.atan2(length, x0 * x1 + y0 * y1 + z0 * z1)
            total += gamma * (n[0] * cx + n[1] * cy + n[2] * cz) / length
    return abs(total) / (2 * math.pi)


@numba.njit(cache=True, nogil=True)
def _edge_pair_kernel(
    emitters: NDArray[np.float64],
    normals: NDArray[np.float64],
    receivers: NDArray[np.float64],
    u: NDArray[np.float64],
    wu: NDArray[np.float64],
    v: NDArray[np.float64],
    wv: NDArray[np.float64],
) -> NDArray[np.float64]:
    """:func:`edge_pair_view_factors` on ``p(u, v) = (1 - u)(A + v (B - A)) + u C``, whose area element is
    ``2 area (1 - u) du dv``: ``F = 2 integral (1 - u) F_dA(p) du dv``."""
    out = np.empty(emitters.shape[0])
    for k in range(emitters.shape[0]):
        e = emitters[k]
        total = 0.0
        for i in range(u.shape[0]):
            inner = 0.0
            for j in range(v.shape[0]):
                a, b, c = (1 - u[i]) * (1 - v[j]), (1 - u[i]) * v[j], u[i]  # weights on A, B, C
                p0 = a * e[0, 0] + b * e[1, 0] + c * e[2, 0]
                p1 = a * e[0, 1] + b * e[1, 1] + c * e[2, 1]
                p2 = a * e[0, 2] + b * e[1, 2] + c * e[2, 2]
                inner += wv[j] * _point_view_factor(p0, p1, p2, normals[k], receivers[k])
            total += wu[i] * (1 - u[i]) * inner
        out[k] = 2 * total
    return out


def _oriented_emitters(craft: Spacecraft, a: NDArray[np.int64], b: NDArray[np.int64]) -> NDArray[np.float64]:
    """Corners of side ``a``'s facet ordered ``(A, B, C)`` with ``AB`` the edge it shares with ``b``'s."""
    faces_a, faces_b = craft.faces[craft.side_facet[a]], craft.faces[craft.side_facet[b]]
    shared = (faces_a[:, :, None] == faces_b[:, None, :]).any(axis=2)
    apex = np.argmin(shared, axis=1)  # the corner not on the shared edge
    order = (apex[:, None] + np.array([1, 2, 0])) % 3
    return craft.triangles[craft.side_facet[a][:, None], order]


def _with_near_field(
    craft: Spacecraft, matrix: scipy.sparse.csr_matrix
) -> tuple[scipy.sparse.csr_matrix, NDArray[np.float64]]:
    """``matrix`` with its concave edge-neighbour entries integrated, and the factor (n_sides,) that
    escape and blind shares are to be multiplied by.

    Row i's near entries (sampled sum ``s_i``) get the integrated values (sum ``a_i``, scaled to 1 if
    it exceeds 1); the rest of the row is multiplied by ``(1 - a_i) / (1 - s_i)``, so the row still
    sums to one. A row whose rays all met near neighbours (``s_i = 1``) keeps its sampled values.
    """
    n = craft.n_sides
    a, b = concave_pairs(craft)
    if not len(a):
        return matrix, np.ones(n)
    emitters, receivers = _oriented_emitters(craft, a, b), craft.triangles[craft.side_facet[b]]
    forward = edge_pair_view_factors(emitters, craft.side_normals[a], receivers)
    rows, cols = np.r_[a, b], np.r_[b, a]
    exact = np.r_[forward, forward * craft.side_areas[a] / craft.side_areas[b]]  # reciprocity
    sampled = np.asarray(matrix[rows, cols]).ravel()
    s = np.bincount(rows, sampled, minlength=n)
    total = np.bincount(rows, exact, minlength=n)
    exact = exact / np.maximum(total, 1)[rows]
    fixed = s < 1 - 1e-9  # s is a multiple of 1 / rays: below 1 - 1 / rays unless every ray met a neighbour
    scale = np.ones(n)
    scale[fixed] = (1 - np.minimum(total, 1)[fixed]) / (1 - s[fixed])
    keep = fixed[rows]
    change = (exact - scale[rows] * sampled)[keep]  # near entries: from their scaled sampled value to exact
    near = scipy.sparse.csr_matrix((change, (rows[keep], cols[keep])), shape=(n, n))
    return (scipy.sparse.diags(scale) @ matrix + near).tocsr(), scale


# ----------------------------------------------------------------------------------------- disk cache


def _settings(rays_per_side: int, seed: int) -> dict[str, object]:
    """Everything besides the geometry that the result depends on: the cache key's settings."""
    return {
        "what": "view_factors",
        "method": METHOD_VERSION,
        "rays_per_side": rays_per_side,
        "seed": int(seed),
        "near_field": [NEAR_ORDER, NEAR_RATIO, NEAR_LEVELS_EDGE, NEAR_LEVELS_ENDS, CONCAVE_TOLERANCE],
    }


def _to_arrays(factors: ViewFactors) -> dict[str, NDArray]:
    m = factors.matrix
    return {
        "data": m.data,
        "indices": m.indices,
        "indptr": m.indptr,
        "escape_fraction": factors.escape_fraction,
        "escape_vector": factors.escape_vector,
        "escape_moment": factors.escape_moment,
        "blind_fraction": factors.blind_fraction,
        "seconds": np.array(factors.seconds),
    }


def _from_arrays(arrays: dict[str, NDArray], n_sides: int, rays: int, seed: int, origin: str) -> ViewFactors:
    """The entry's view factors; CacheEntryError where its arrays do not fit ``n_sides`` sides."""
    try:
        indptr, indices, data = arrays["indptr"], arrays["indices"], arrays["data"]
        fits = (
            indptr.shape == (n_sides + 1,)
            and indices.shape == data.shape == (indptr[-1],)
            and all(arrays[k].shape == (n_sides,) for k in ("escape_fraction", "blind_fraction"))
            and all(arrays[k].shape == (n_sides, 3) for k in ("escape_vector", "escape_moment"))
        )
        if not fits:
            raise CacheEntryError("was corrupt (arrays of the wrong shape)")
        matrix = scipy.sparse.csr_matrix((data, indices, indptr), shape=(n_sides, n_sides))
        return ViewFactors(
            matrix=matrix,
            escape_fraction=arrays["escape_fraction"],
            escape_vector=arrays["escape_vector"],
            escape_moment=arrays["escape_moment"],
            blind_fraction=arrays["blind_fraction"],
            rays_per_side=rays,
            seed=int(seed),
            seconds=float(arrays["seconds"]),
            origin=origin,
        )
    except (KeyError, IndexError, ValueError) as error:
        raise CacheEntryError(f"was corrupt ({type(error).__name__}: {error})") from error


def view_factors(
    craft: Spacecraft,
    rays_per_side: int | None = None,
    seed: int = VIEW_SEED,
    cache_dir: str | os.PathLike | bool | None = None,
) -> ViewFactors:
    """:func:`compute_view_factors`, kept on disk and read back when the geometry and settings match.

    Parameters
    ----------
    craft, rays_per_side, seed
        As for :func:`compute_view_factors`.
    cache_dir : path, bool or None
        Directory of the cache; None (or True): ``$SUNWIND_CACHE_DIR``, else ``~/.cache/sunwind``
        (``$XDG_CACHE_HOME`` if set); False: no disk cache.

    ``origin`` of the result says what happened: "cache <path>", "computed (stored in cache <path>)",
    or "computed (...)" naming a corrupt or stale entry that was rebuilt, or a cache that could not be
    written. Cache trouble is never an error and never gives a wrong result.
    """
    directory = cache_directory(cache_dir)
    if directory is None:
        return compute_view_factors(craft, rays_per_side, seed)
    rays = resolve_rays_per_side(rays_per_side, craft.n_sides)
    key = geometry_key(craft, _settings(rays, seed))
    path = directory / f"view_factors-{key[:32]}.npz"
    notes = []
    try:
        return _from_arrays(read_entry(path, key), craft.n_sides, rays, seed, f"cache {path}")
    except FileNotFoundError:
        pass
    except CacheEntryError as problem:
        notes.append(f"cache entry {path} {problem}: rebuilt")
    factors = compute_view_factors(craft, rays, seed)
    try:
        write_entry(path, key, _to_arrays(factors))
        notes.append(f"stored in cache {path}")
    except OSError as error:
        notes.append(f"cache {directory} not writable ({error}): not stored")
    return replace(factors, origin=f"computed ({'; '.join(notes)})")
