"""Numba kernel of the hull tests (:mod:`sunwind.geometry.rays.hull`): which rays provably meet nothing.

:func:`may_be_blocked` sorts out the rays leaving sides that a :class:`~sunwind.geometry.rays.hull.Clearance`
vouches for; the others are cast. Kernels taking ``lo, hi`` write rows ``lo:hi`` of their outputs only,
so threads given disjoint ranges produce the same bits as one.
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
    """Write whether the rays from sides ``lo:hi`` may meet the model: False where one provably meets nothing.

    Ray ``(k, j, p)`` leaves side ``sides[k]`` from ``origins[k, p]`` (scene coordinates) along
    ``directions[k, j]``, or ``directions[0, j]`` when ``directions`` has one row. It is clear when it
    leaves the side's plane (``n . d > _GRAZING`` in float32) and the side is on the model's hull, or on
    its part's hull with the ray missing the box of every other part that reaches in front of the side
    (:class:`sunwind.geometry.rays.hull.Clearance`). Directions shared by every side first test each box by
    its :func:`_box_shadows`, which decides most misses in four comparisons.

    Parameters
    ----------
    sides : (n,) ndarray of int64
        The sides the rays leave.
    origins : (n, p, 3) ndarray of float32
        Ray origins of each side, scene coordinates.
    directions : (n, m, 3) or (1, m, 3) ndarray of float32
        Unit ray directions, per side or shared by all.
    normals : (n_sides, 3) ndarray of float64
        Outward normal of every side of the model.
    clearance : tuple
        ``open_sky, own_part_clear, blockers, box_low, box_high``
        (:attr:`~sunwind.geometry.rays.hull.Clearance.arrays`).
    out : (n, m, p) ndarray of bool
        Written: True where the ray must be cast.
    lo, hi : int
        Rows of ``sides`` to do.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.rays.hull import clearance
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> sides = np.array([0, 8])  # the bus's -x and +x faces
    >>> origins = craft.scene.origins(craft.side_centroids[sides], craft.side_normals[sides])[:, None]
    >>> along = np.array([[[-1.0, 0, 0], [1.0, 0, 0]]], dtype=np.float32)
    >>> out = np.empty((2, 2, 1), dtype=bool)
    >>> may_be_blocked(sides, origins, along, craft.side_normals, clearance(craft).arrays, out, 0, 2)
    >>> out[..., 0]  # a ray out of its face meets nothing; one into it must be cast
    array([[False,  True],
           [ True, False]])
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
def cone_may_be_blocked(
    sides: NDArray[np.int64],
    spheres: NDArray[np.float64],
    axis: NDArray[np.float64],
    half_angle: float,
    clearance: tuple,
    out: NDArray[np.bool_],
    lo: int,
    hi: int,
) -> None:
    """Write whether any ray leaving each side within a cone about an axis may meet the model.

    False where the side is on the model's hull, or on its own part's hull with the cone from the side
    missing every other part's box in front of it (each box taken as its bounding sphere, the side as
    ``spheres``: centre and radius round its corners, scene coordinates).

    A sphere of radius ``r`` (both spheres' radii) whose centre lies at ``t`` from the side's, ``D =
    |t| > r``, is missed when ``t`` lies more than ``half_angle + asin(r / D)`` off the axis: ``t . axis
    < cos(half_angle) sqrt(D^2 - r^2) - sin(half_angle) r`` (``half_angle <= pi / 2``, so that the
    cone and the sphere's cone, under ``pi / 2``, never span the sky).

    Parameters
    ----------
    sides : (n,) ndarray of int64
        The sides the rays leave.
    spheres : (n_sides, 4) ndarray of float64
        Centre and radius of a sphere round each side of the model, scene coordinates.
    axis : (3,) ndarray of float64
        Unit axis of the cone.
    half_angle : float
        Half-angle of the cone [rad], at most ``pi / 2``.
    clearance : tuple
        ``open_sky, own_part_clear, blockers, box_low, box_high``
        (:attr:`~sunwind.geometry.rays.hull.Clearance.arrays`).
    out : (n,) ndarray of bool
        Written: True where a ray of the cone may be blocked.
    lo, hi : int
        Rows of ``sides`` to do.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.rays.hull import clearance
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> centres = craft.scene.to_scene(craft.side_centroids).astype(np.float64)
    >>> spheres = np.column_stack([centres, np.full(craft.n_sides, 0.1)])
    >>> out = np.empty(2, dtype=bool)
    >>> cone_may_be_blocked(np.array([0, 8]), spheres, np.array([-1.0, 0, 0]), 0.3, clearance(craft).arrays,
    ...     out, 0, 2)
    >>> out  # both on the model's hull: nothing can block them
    array([False, False])
    """
    open_sky, own_part_clear, blockers, box_low, box_high = clearance
    n_boxes = box_low.shape[0]
    box_centre, box_radius = np.empty((n_boxes, 3)), np.empty(n_boxes)
    for box in range(n_boxes):
        box_centre[box] = 0.5 * (box_low[box] + box_high[box])
        box_radius[box] = 0.5 * math.sqrt(np.sum((box_high[box] - box_low[box]) ** 2))
    cos_cone, sin_cone = math.cos(half_angle), math.sin(half_angle)
    for k in range(lo, hi):
        s = sides[k]
        if open_sky[s] or not own_part_clear[s]:
            out[k] = not open_sky[s]
            continue
        hit = False
        for box in range(n_boxes):
            if not blockers[s, box]:
                continue
            t0 = box_centre[box, 0] - spheres[s, 0]
            t1 = box_centre[box, 1] - spheres[s, 1]
            t2 = box_centre[box, 2] - spheres[s, 2]
            radius = spheres[s, 3] + box_radius[box]
            clear_of = t0 * t0 + t1 * t1 + t2 * t2 - radius * radius
            if clear_of <= 0.0:  # the spheres overlap
                hit = True
                break
            along = t0 * axis[0] + t1 * axis[1] + t2 * axis[2]
            if along >= cos_cone * math.sqrt(clear_of) - sin_cone * radius:
                hit = True
                break
        out[k] = hit
