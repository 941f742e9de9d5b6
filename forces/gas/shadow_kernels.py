"""Numba kernels of the flow's shadows (:mod:`sunwind.forces.gas.shadow`).

:func:`may_be_blocked` sorts out the rays that provably meet nothing (:mod:`sunwind.geometry.rays.hull`);
:func:`lee_rays`, :func:`incidences`, :func:`gather_rays`, :func:`lit_shares` and
:func:`spread_visibility` build the other rays and read their answers. Kernels taking ``lo, hi`` write
rows ``lo:hi`` of their outputs only, so threads given disjoint ranges produce the same bits as one.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import NDArray

#: Smallest ``n . d`` of a ray in float32 that the clearance tests vouch for; grazing rays are cast.
_GRAZING = 1e-6


@numba.njit(cache=True, nogil=True, inline="always")
def _slab(low: float, high: float, origin: float, inverse: float) -> tuple[float, float]:
    """Parameters at which a ray with ``1 / direction = inverse`` (inf for 0) enters and leaves a slab."""
    if inverse == np.inf:
        return (0.0, np.inf) if low <= origin <= high else (1.0, -1.0)
    t0, t1 = (low - origin) * inverse, (high - origin) * inverse
    return min(t0, t1), max(t0, t1)


@numba.njit(cache=True, nogil=True)
def _box_shadows(
    directions: NDArray[np.float64], box_low: NDArray[np.float64], box_high: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """For each direction ``d`` (m, 3): two vectors normal to it, (m, 2, 3), and the bounds of each
    box's projection on them, (m, n_boxes, 4): a ray along ``d`` can meet a box only from an origin
    whose projection lies within (the boxes' margin covers the round-off of the projections)."""
    m, n_boxes = directions.shape[0], box_low.shape[0]
    axes, bounds = np.empty((m, 2, 3)), np.empty((m, n_boxes, 4))
    for j in range(m):
        d = directions[j]
        e1 = np.cross(d, np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0]))
        e1 /= np.linalg.norm(e1)
        axes[j, 0], axes[j, 1] = e1, np.cross(d, e1)
        for box in range(n_boxes):
            for a in range(2):
                low = high = 0.0
                for c in range(3):
                    x, y = axes[j, a, c] * box_low[box, c], axes[j, a, c] * box_high[box, c]
                    low, high = low + min(x, y), high + max(x, y)
                bounds[j, box, 2 * a], bounds[j, box, 2 * a + 1] = low, high
    return axes, bounds


@numba.njit(cache=True, nogil=True)
def may_be_blocked(
    sides: NDArray[np.int64],
    origins: NDArray[np.float32],
    directions: NDArray[np.float32],
    normals: NDArray[np.float64],
    clearance: tuple,
    out: NDArray[np.bool_],
    lo: int,
    hi: int,
) -> None:
    """Whether the rays from sides ``lo:hi`` may meet the model, into ``out`` (n, m, p): False where a
    ray provably meets nothing (:class:`sunwind.geometry.rays.hull.Clearance`).

    Ray ``(k, j, p)`` leaves side ``sides[k]`` from ``origins[k, p]`` (scene coordinates) along
    ``directions[k, j]``, or ``directions[0, j]`` when ``directions`` (n or 1, m, 3) has one row. It is
    clear when it leaves the side's plane (``n . d > _GRAZING`` in float32) and the side is on the
    model's hull, or on its part's hull with the ray missing the box of every other part that reaches
    in front of the side. ``clearance`` holds ``open_sky``, ``own_part_clear``, ``blockers``,
    ``box_low``, ``box_high``. Directions shared by every side first test each box by its
    :func:`_box_shadows`, which decides most misses in four comparisons.
    """
    open_sky, own_part_clear, blockers, box_low, box_high = clearance
    rows, m, points = directions.shape[0], directions.shape[1], origins.shape[1]
    d, inverse = np.empty((m, 3)), np.empty((m, 3))
    shared = rows == 1
    axes, bounds = _box_shadows(directions[0].astype(np.float64), box_low, box_high)
    for k in range(lo, hi):
        s = sides[k]
        if k == lo or not shared:  # the directions of this side
            for j in range(m):
                for a in range(3):
                    d[j, a] = np.float64(directions[min(k, rows - 1), j, a])
                    inverse[j, a] = 1.0 / d[j, a] if d[j, a] != 0.0 else np.inf
        for j in range(m):
            rise = normals[s, 0] * d[j, 0] + normals[s, 1] * d[j, 1] + normals[s, 2] * d[j, 2]
            if rise <= _GRAZING or not own_part_clear[s] or open_sky[s]:
                out[k, j, :] = not open_sky[s] or rise <= _GRAZING
                continue
            for p in range(points):
                o0, o1, o2 = (
                    np.float64(origins[k, p, 0]),
                    np.float64(origins[k, p, 1]),
                    np.float64(origins[k, p, 2]),
                )
                q1 = q2 = 0.0
                if shared:
                    q1 = o0 * axes[j, 0, 0] + o1 * axes[j, 0, 1] + o2 * axes[j, 0, 2]
                    q2 = o0 * axes[j, 1, 0] + o1 * axes[j, 1, 1] + o2 * axes[j, 1, 2]
                hit = False
                for box in range(box_low.shape[0]):
                    if not blockers[s, box]:
                        continue
                    if shared and not (
                        bounds[j, box, 0] <= q1 <= bounds[j, box, 1]
                        and bounds[j, box, 2] <= q2 <= bounds[j, box, 3]
                    ):
                        continue
                    near0, far0 = _slab(box_low[box, 0], box_high[box, 0], o0, inverse[j, 0])
                    near1, far1 = _slab(box_low[box, 1], box_high[box, 1], o1, inverse[j, 1])
                    near2, far2 = _slab(box_low[box, 2], box_high[box, 2], o2, inverse[j, 2])
                    if max(max(near0, near1), max(near2, 0.0)) <= min(min(far0, far1), far2):
                        hit = True
                        break
                out[k, j, p] = hit


@numba.njit(cache=True, nogil=True)
def lee_rays(
    sides: NDArray[np.int64],
    gamma: NDArray[np.float64],
    normals: NDArray[np.float64],
    centroids: NDArray[np.float64],
    u: NDArray[np.float64],
    elevation: float,
    frame: tuple[NDArray[np.float64], float, float],
    origins: NDArray[np.float32],
    probes: NDArray[np.float32],
    lo: int,
    hi: int,
) -> None:
    """Probe rays of lee sides ``lo:hi`` (``gamma`` = ``n . u`` of each): ``origins`` and ``probes``,
    (n, 1, 3).

    The probe leaves the side's centroid pushed ``offset`` [m] along its normal, in scene coordinates
    ``(p - centre) / half_size`` (``frame``, as :meth:`sunwind.geometry.rays.scene.SceneFrame.origins`),
    upstream
    along the side, ``(u - gamma n)/|...|`` (0 where that length is below 1e-12), raised by
    ``elevation`` [rad] toward the normal; both rounded to float32.
    """
    centre, half_size, offset = frame
    along, rise = math.cos(elevation), math.sin(elevation)
    for k in range(lo, hi):
        s = sides[k]
        n0, n1, n2 = normals[s, 0], normals[s, 1], normals[s, 2]
        for d in range(3):
            origins[k, 0, d] = np.float32((centroids[s, d] + offset * normals[s, d] - centre[d]) / half_size)
        a0, a1, a2 = u[0] - gamma[k] * n0, u[1] - gamma[k] * n1, u[2] - gamma[k] * n2
        length = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        if length > 1e-12:
            a0, a1, a2 = a0 / length, a1 / length, a2 / length
        else:
            a0 = a1 = a2 = 0.0
        p0, p1, p2 = along * a0 + rise * n0, along * a1 + rise * n1, along * a2 + rise * n2
        size = math.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
        probes[k, 0, 0], probes[k, 0, 1], probes[k, 0, 2] = p0 / size, p1 / size, p2 / size


@numba.njit(cache=True, nogil=True)
def incidences(
    sides: NDArray[np.int64],
    normals: NDArray[np.float64],
    directions: NDArray[np.float64],
    out: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """``max(n . d, 0)`` of sides ``lo:hi`` on each of ``directions`` (m, 3), into ``out`` (n, m)."""
    for k in range(lo, hi):
        s = sides[k]
        for j in range(directions.shape[0]):
            c = (
                normals[s, 0] * directions[j, 0]
                + normals[s, 1] * directions[j, 1]
                + normals[s, 2] * directions[j, 2]
            )
            out[k, j] = max(c, 0.0)


@numba.njit(cache=True, nogil=True)
def gather_rays(
    cast: NDArray[np.bool_],
    incidence: NDArray[np.float64],
    origins: NDArray[np.float32],
    rays: NDArray[np.float32],
) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]]:
    """The rays to cast from ``origins`` (n, p, 3) along ``rays`` (m, 3), direction by direction: those
    with ``cast`` (n, m, p) where the side faces the direction (``incidence`` (n, m) > 0).

    Returns ``i m + j`` of each (side row ``i``, direction ``j``), and the rays' origins and directions.
    """
    n, m, points = cast.shape
    count = 0
    for j in range(m):
        for i in range(n):
            if incidence[i, j] > 0.0:
                for p in range(points):
                    count += cast[i, j, p]
    pair = np.empty(count, dtype=np.int64)
    ray_origins = np.empty((count, 3), dtype=np.float32)
    ray_directions = np.empty((count, 3), dtype=np.float32)
    r = 0
    for j in range(m):
        for i in range(n):
            if incidence[i, j] > 0.0:
                for p in range(points):
                    if cast[i, j, p]:
                        pair[r] = i * m + j
                        for d in range(3):
                            ray_origins[r, d] = origins[i, p, d]
                            ray_directions[r, d] = rays[j, d]
                        r += 1
    return pair, ray_origins, ray_directions


@numba.njit(cache=True, nogil=True)
def lit_shares(
    pair: NDArray[np.int64], blocked: NDArray[np.bool_], points: int, n: int, m: int
) -> NDArray[np.float64]:
    """Lit share (n, m) of ``points`` rays per side and direction, where only the rays ``pair``
    (``i m + j``) were cast and ``blocked`` says which of them met the model."""
    hits = np.zeros(n * m, dtype=np.int64)
    for r in range(pair.shape[0]):
        hits[pair[r]] += blocked[r]
    return ((points - hits) / points).reshape(n, m)


@numba.njit(cache=True, nogil=True)
def spread_visibility(
    facing: NDArray[np.int64],
    incidence: NDArray[np.float64],
    lit: NDArray[np.float64],
    visible: NDArray[np.float64],
) -> None:
    """``visible[facing[i]] = sum_j incidence[i, j] lit[i, j] / sum_j incidence[i, j]`` where the
    denominator is positive, summed in the order of ``j``."""
    for i in range(facing.shape[0]):
        weighted = weights = 0.0
        for j in range(incidence.shape[1]):
            weighted += incidence[i, j] * lit[i, j]
            weights += incidence[i, j]
        if weights > 0.0:
            visible[facing[i]] = weighted / weights
