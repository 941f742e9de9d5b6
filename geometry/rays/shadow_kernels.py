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
    """Gather the sides of some blocks that face a direction, with their kept ray origins.

    The bounds of each block's normal components bound ``n . direction`` over it: a block that cannot
    face is skipped unread, one that must face is copied whole without reading normals.

    Parameters
    ----------
    normals : (n_sides, 3) ndarray of float64
        Outward normal of each side.
    direction : (3,) ndarray of float64
        Unit vector toward the source.
    ordered_origins : (n_sides, p, 3) ndarray of float32
        Origins in the balanced order: row ``k`` belongs to side ``order[k]``.
    order : (n_sides,) ndarray of int64
        The balanced order of the sides.
    block_low, block_high : (n_blocks, 3) ndarray of float64
        Bounds of each block's normal components.
    first, last : int
        The blocks to do: ``order[first * BLOCK:last * BLOCK]``.

    Returns
    -------
    sides : (n_facing,) ndarray of int64
        The facing sides.
    origins : (n_facing, p, 3) ndarray of float32
        Their origins.

    Examples
    --------
    Called by :meth:`~sunwind.geometry.rays.shadows.SideSampler.facing_rays`:

    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> sides, origins = side_sampler(craft).facing_rays(direction, 1)
    >>> sides.shape, origins.shape
    ((72,), (72, 1, 3))
    """
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
    """Make the sample points of sides, pushed off along their normals, in float32 scene coordinates.

    Parameters
    ----------
    triangles : (n_facets, 3, 3) ndarray of float64
        Facet corners [m].
    side_facet : (n_sides,) ndarray of int64
        Facet of each side.
    normals : (n_sides, 3) ndarray of float64
        Outward normal of each side.
    sides : (n,) ndarray of int64
        The sides to sample.
    barycentric : (p, 3) ndarray of float64
        Barycentric coordinates of the points.
    centre : (3,) ndarray of float64
        Centre of the scene frame [m].
    half_size : float
        Half-size of the scene frame [m].
    offset_m : float
        Push along the normal [m].

    Returns
    -------
    (n, p, 3) ndarray of float32
        ``(point + offset_m * normal - centre) / half_size``.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> scene = craft.scene
    >>> o = sample_origins(craft.triangles, craft.side_facet, craft.side_normals, np.array([8]),
    ...     np.array([[1 / 3, 1 / 3, 1 / 3]]), scene.centre, scene.half_size, scene.offset_m)
    >>> bool(np.allclose(o[0, 0], scene.origins(craft.side_centroids[8:9], craft.side_normals[8:9])[0]))
    True
    """
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
    """Find the share of each row of lit flags that is lit.

    Parameters
    ----------
    lit : (n, p) ndarray of bool
        Lit flags of each side's points.

    Returns
    -------
    (n,) ndarray of float64
        Lit share of each row.

    Examples
    --------
    >>> import numpy as np
    >>> lit_shares(np.array([[True, False, True, True], [False, False, False, False]]))
    array([0.75, 0.  ])
    """
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
    """Write the mean of the lit points of each partly lit side into its row of ``centroid``.

    The mean is the triangle's point at the mean barycentric of the lit points.

    Parameters
    ----------
    sides : (n,) ndarray of int64
        The sides.
    lit : (n, p) ndarray of bool
        Lit flags of each side's points.
    barycentric : (p, 3) ndarray of float64
        Barycentric coordinates of the points.
    triangles : (n_facets, 3, 3) ndarray of float64
        Facet corners [m].
    side_facet : (n_sides,) ndarray of int64
        Facet of each side.
    centroid : (n_sides, 3) ndarray of float64
        Written at the partly lit sides [m].

    Examples
    --------
    >>> import numpy as np
    >>> triangles = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    >>> centroid = np.zeros((1, 3))
    >>> bary = np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])
    >>> lit = np.array([[True, True, False]])  # the first two corners lit
    >>> lit_centroids(np.array([0]), lit, bary, triangles, np.array([0]), centroid)
    >>> centroid
    array([[0.5, 0. , 0. ]])
    """
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
