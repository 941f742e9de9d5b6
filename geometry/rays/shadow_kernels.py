"""Numba kernels of the shadow pass (:mod:`sunwind.geometry.rays.shadows`): ray origins, facing tests, lit
shares and lit centroids. Each runs serially over its rows, so its results do not depend on threads."""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

#: Sides per block of the balanced order.
BLOCK = 512


@numba.njit(cache=True, nogil=True)
def facing_origins(
    normals: NDArray[np.float64],
    direction: NDArray[np.float64],
    ordered_origins: NDArray[np.float32],
    order: NDArray[np.int64],
    block_low: NDArray[np.float64],
    block_high: NDArray[np.float64],
    first: int,
    last: int,
) -> tuple[NDArray[np.int64], NDArray[np.float32]]:
    """Sides of ``order[first * BLOCK:last * BLOCK]`` with ``normals . direction > 0``, and their
    origins (``ordered_origins[k]`` belongs to side ``order[k]``). The bounds of each block's normal
    components bound ``n . direction`` over it: a block that cannot face is skipped unread, one that
    must face is copied whole without reading normals."""
    d0, d1, d2 = direction[0], direction[1], direction[2]
    start, stop = first * BLOCK, min(last * BLOCK, order.shape[0])
    width = ordered_origins.shape[1] * 3  # float32 values per side
    facing = np.empty(stop - start, dtype=np.int64)
    out = np.empty((stop - start, ordered_origins.shape[1], 3), dtype=np.float32)
    source, target = ordered_origins.reshape(-1), out.reshape(-1)
    count = 0
    for b in range(first, last):
        upper = lower = 0.0
        for d, component in enumerate((d0, d1, d2)):
            a, c = block_low[b, d] * component, block_high[b, d] * component
            upper += max(a, c)
            lower += min(a, c)
        if upper <= 0.0:
            continue
        low, high = b * BLOCK, min((b + 1) * BLOCK, stop)
        if lower > 0.0:  # every side of the block faces the source: one contiguous copy
            for j in range(high - low):
                facing[count + j] = order[low + j]
            for j in range((high - low) * width):
                target[count * width + j] = source[low * width + j]
            count += high - low
            continue
        for k in range(low, high):
            s = order[k]
            if normals[s, 0] * d0 + normals[s, 1] * d1 + normals[s, 2] * d2 > 0.0:
                facing[count] = s
                for j in range(width):
                    target[count * width + j] = source[k * width + j]
                count += 1
    return facing[:count], out[:count]


@numba.njit(cache=True, nogil=True)
def sample_origins(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    sides: NDArray[np.int64],
    barycentric: NDArray[np.float64],
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> NDArray[np.float32]:
    """Sample points of ``sides`` pushed ``offset_m`` along their normals, in float32 scene
    coordinates ``(p - centre) / half_size``, (len(sides), n_points, 3)."""
    points = barycentric.shape[0]
    out = np.empty((sides.shape[0], points, 3), dtype=np.float32)
    for k in range(sides.shape[0]):
        s = sides[k]
        f = side_facet[s]
        for p in range(points):
            w0, w1, w2 = barycentric[p, 0], barycentric[p, 1], barycentric[p, 2]
            for d in range(3):
                x = w0 * triangles[f, 0, d] + w1 * triangles[f, 1, d] + w2 * triangles[f, 2, d]
                out[k, p, d] = (x + offset_m * normals[s, d] - centre[d]) / half_size
    return out


@numba.njit(cache=True, nogil=True)
def lit_shares(lit: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Share of each row of lit flags (n, points) that is lit, (n,)."""
    n, points = lit.shape
    share = np.empty(n)
    for k in range(n):
        count = 0
        for p in range(points):
            count += lit[k, p]
        share[k] = count / points
    return share


@numba.njit(cache=True, nogil=True)
def lit_centroids(
    sides: NDArray[np.int64],
    lit: NDArray[np.bool_],
    barycentric: NDArray[np.float64],
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    centroid: NDArray[np.float64],
) -> None:
    """Write the mean of the lit points of each part-lit side of ``sides`` (lit flags (n, points) of
    its points at ``barycentric``) into ``centroid[s]``: the triangle at their mean barycentric."""
    n, points = lit.shape
    for k in range(n):
        count = 0
        w0 = w1 = w2 = 0.0
        for p in range(points):
            if lit[k, p]:
                count += 1
                w0 += barycentric[p, 0]
                w1 += barycentric[p, 1]
                w2 += barycentric[p, 2]
        if 0 < count < points:
            f = side_facet[sides[k]]
            for d in range(3):
                corner = w0 * triangles[f, 0, d] + w1 * triangles[f, 1, d] + w2 * triangles[f, 2, d]
                centroid[sides[k], d] = corner / count
