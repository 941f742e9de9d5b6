"""Pieces of a model lying on or near one another: candidate pairs from a box tree, and shared area.

A CAD export lays surfaces on surfaces (a blanket over the panel it covers, a decal, a face written
twice) and leaves open borders a hair apart. Both are questions about pairs of nearby pieces: the box
tree of :mod:`sunwind.geometry.rays.box_tree` gives the pairs whose boxes come within a distance of
each other, and :func:`overlap_areas` the area two facets share when one is laid flat on the other's
plane.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.box_tree import box_tree

#: Two facets sharing less than this share of the smaller one's area only touch.
TOUCHING_SHARE = 1e-6


@dataclass(frozen=True, eq=False)
class Pairs:
    """Pairs of pieces (:func:`box_pairs`).

    Attributes
    ----------
    first, second : (m,) int64
        The two pieces of each pair, ``first < second``, sorted by ``first``.

    Examples
    --------
    >>> import numpy as np
    >>> pairs = Pairs(np.array([0, 0]), np.array([1, 2]))
    >>> list(zip(pairs.first.tolist(), pairs.second.tolist()))
    [(0, 1), (0, 2)]
    """

    first: NDArray[np.int64]
    second: NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class Stacked(Pairs):
    """Pairs of facets laid on one another (:func:`stacked`).

    Attributes
    ----------
    first, second : (m,) int64
        The two facets of each pair, ``first < second``.
    area_m2 : (m,) float64
        Area they share [m^2] (:func:`overlap_areas`).
    height_m : (m,) float64
        Mean height of ``second``'s corners over the plane of ``first``, along its normal [m].

    Examples
    --------
    >>> import numpy as np
    >>> floor = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    >>> found = stacked(np.array([floor, floor + [0, 0, 0.002]]), margin=0.01, parallel=0.999)
    >>> isinstance(found, Pairs), found.area_m2, found.height_m.round(6)
    (True, array([0.5]), array([0.002]))
    """

    area_m2: NDArray[np.float64]
    height_m: NDArray[np.float64]


def box_pairs(pieces: NDArray[np.float64], margin: float) -> Pairs:
    """Find the pairs of pieces whose bounding boxes come within ``margin`` of each other.

    Parameters
    ----------
    pieces : (n, k, 3) float64
        Corners of each piece [m]: triangles (k = 3) or segments (k = 2).
    margin : float
        Largest gap between two boxes, along every axis [m].

    Returns
    -------
    Pairs
        A superset of the pairs of pieces closer than ``margin`` (boxes are tested, not the pieces).

    Examples
    --------
    >>> import numpy as np
    >>> segments = np.array([[[0, 0, 0], [1, 0, 0]], [[0, 0.01, 0], [1, 0.01, 0]], [[0, 5, 0], [1, 5, 0]]])
    >>> near = box_pairs(segments.astype(float), 0.1)  # the first two, 1 cm apart
    >>> near.first, near.second
    (array([0]), array([1]))
    """
    pieces = np.ascontiguousarray(pieces, dtype=np.float64)
    if len(pieces) < 2:
        return Pairs(np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
    first, second, _, _ = _near_pairs(pieces, margin, np.zeros((0, 3, 3)), 0.0)
    return Pairs(first, second)


def overlap_areas(
    triangles: NDArray[np.float64], first: NDArray[np.int64], second: NDArray[np.int64]
) -> NDArray[np.float64]:
    """Area [m^2] that triangle ``second`` covers of triangle ``first`` seen along ``first``'s normal.

    ``second`` is projected onto the plane of ``first`` and clipped by it (Sutherland-Hodgman); for two
    facets of one plane this is the area they share, zero where they only touch along an edge.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Facet corners [m].
    first, second : (m,) int64
        Pairs of facets.

    Returns
    -------
    (m,) float64
        Shared area of each pair [m^2]; zero where ``first`` is degenerate.

    Examples
    --------
    >>> import numpy as np
    >>> square = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 0, 0], [1, 1, 0], [0, 1, 0]]])
    >>> half = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0.5, 0, 0], [1, 0, 0], [1, 1, 0]]])
    >>> overlap_areas(square.astype(float), np.array([0]), np.array([1]))  # neighbours: touching only
    array([0.])
    >>> overlap_areas(half.astype(float), np.array([0]), np.array([1]))  # a quarter of the square
    array([0.25])
    """
    return _overlap_areas(
        np.ascontiguousarray(triangles, dtype=np.float64),
        np.ascontiguousarray(first, dtype=np.int64),
        np.ascontiguousarray(second, dtype=np.int64),
    )


def stacked(triangles: NDArray[np.float64], margin: float, parallel: float) -> Stacked:
    """Find the pairs of facets laid on one another.

    Such facets are parallel (or facing each other) to within ``parallel``, every corner of each lies
    within ``margin`` of the other's plane, and they share more than ``TOUCHING_SHARE`` of the smaller
    one's area.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Facet corners [m].
    margin : float
        Farthest a corner may lie off the other facet's plane [m].
    parallel : float
        Least ``|cos|`` of the angle between the two normals.

    Returns
    -------
    Stacked
        The pairs, ``first < second``, with their shared area and height.

    Examples
    --------
    >>> import numpy as np
    >>> floor = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]])
    >>> beside = np.array([[1, 0, 0], [1, 1, 0], [0, 1, 0.0]])  # touches the floor along an edge
    >>> above = floor + [0, 0, 0.001]  # a layer 1 mm over it
    >>> found = stacked(np.array([floor, above, beside]), margin=0.01, parallel=0.9998)
    >>> found.first, found.second, found.area_m2, found.height_m.round(6)
    (array([0]), array([1]), array([0.5]), array([0.001]))
    """
    triangles = np.ascontiguousarray(triangles, dtype=np.float64)
    if len(triangles) < 2:
        none = np.zeros(0, dtype=np.int64)
        return Stacked(none, none, np.zeros(0), np.zeros(0))
    return Stacked(*_near_pairs(triangles, margin, triangles, parallel))


def _near_pairs(
    pieces: NDArray[np.float64], margin: float, triangles: NDArray[np.float64], parallel: float
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]]:
    """Pairs of ``pieces`` whose boxes come within ``margin``; with ``triangles`` (the pieces) rather
    than none, only those laid on one another, with their shared area and height (:func:`stacked`)."""
    tree = box_tree(pieces)
    return _pairs(
        np.ascontiguousarray(pieces.min(axis=1)),
        np.ascontiguousarray(pieces.max(axis=1)),
        tree.low,
        tree.high,
        tree.first_child,
        tree.order,
        tree.span,
        tree.depth,
        margin,
        triangles,
        parallel,
    )


@numba.njit(cache=True, nogil=True)
def _pairs(
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    node_low: NDArray[np.float64],
    node_high: NDArray[np.float64],
    first_child: NDArray[np.int64],
    order: NDArray[np.int64],
    span: NDArray[np.int64],
    depth: int,
    margin: float,
    triangles: NDArray[np.float64],
    parallel: float,
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]]:
    """Pairs ``i < j`` whose boxes ``low``..``high`` come within ``margin``: each box grown by it is
    sent down the tree of all boxes. With ``triangles`` (n, 3, 3), only the pairs laid on one another
    (:func:`_layered`) are kept, with their shared area and height, so that a crowd of small facets
    within ``margin`` of each other costs time, not memory; else (0, 3, 3), every pair (area and
    height zero)."""
    n = low.shape[0]
    test = triangles.shape[0] > 0
    capacity = 64 if test else 4 * n + 64
    out_i = np.empty(capacity, dtype=np.int64)
    out_j = np.empty(capacity, dtype=np.int64)
    out_area, out_height = np.zeros(capacity), np.zeros(capacity)
    count = 0
    stack = np.empty(2 * depth + 4, dtype=np.int64)
    work, frame = np.empty((2, 12, 2)), np.empty((4, 3))
    normals, twice = np.zeros((triangles.shape[0], 3)), np.zeros(triangles.shape[0])
    for i in range(triangles.shape[0]):
        twice[i] = _unit_normal(triangles[i], normals[i])
    for i in range(n):
        top = 1
        stack[0] = 0
        while top > 0:
            top -= 1
            k = stack[top]
            apart = False
            for d in range(3):
                apart |= node_low[k, d] > high[i, d] + margin or node_high[k, d] < low[i, d] - margin
            if apart:
                continue
            if first_child[k] >= 0:
                stack[top] = first_child[k]
                stack[top + 1] = first_child[k] + 1
                top += 2
                continue
            for m in range(span[k, 0], span[k, 1]):
                j = order[m]
                if j <= i:
                    continue
                near = True
                for d in range(3):
                    near &= low[j, d] <= high[i, d] + margin and high[j, d] >= low[i, d] - margin
                if not near:
                    continue
                area = height = 0.0
                if test:
                    cosine = normals[i, 0] * normals[j, 0] + normals[i, 1] * normals[j, 1]
                    if (
                        twice[i] == 0.0
                        or twice[j] == 0.0
                        or abs(cosine + normals[i, 2] * normals[j, 2]) < parallel
                    ):
                        continue
                    area, height = _layered(triangles, normals, twice, i, j, margin, frame, work)
                    if area == 0.0:
                        continue
                if count == capacity:
                    capacity *= 2
                    grown_i = np.empty(capacity, dtype=np.int64)
                    grown_j = np.empty(capacity, dtype=np.int64)
                    grown_area, grown_height = np.zeros(capacity), np.zeros(capacity)
                    grown_i[:count], grown_j[:count] = out_i[:count], out_j[:count]
                    grown_area[:count], grown_height[:count] = out_area[:count], out_height[:count]
                    out_i, out_j, out_area, out_height = grown_i, grown_j, grown_area, grown_height
                out_i[count], out_j[count], out_area[count], out_height[count] = i, j, area, height
                count += 1
    return out_i[:count], out_j[:count], out_area[:count], out_height[:count]


@numba.njit(cache=True, nogil=True)
def _overlap_areas(
    triangles: NDArray[np.float64], first: NDArray[np.int64], second: NDArray[np.int64]
) -> NDArray[np.float64]:
    """:func:`overlap_areas` pair by pair."""
    out = np.zeros(first.shape[0])
    work = np.empty((2, 12, 2))
    frame = np.empty((4, 3))
    for p in range(first.shape[0]):
        out[p] = _shared_area(triangles[first[p]], triangles[second[p]], frame, work)
    return out


@numba.njit(cache=True, nogil=True)
def _layered(
    triangles: NDArray[np.float64],
    normals: NDArray[np.float64],
    twice: NDArray[np.float64],
    i: int,
    j: int,
    margin: float,
    frame: NDArray[np.float64],
    work: NDArray[np.float64],
) -> tuple[float, float]:
    """Shared area of parallel facets ``i`` and ``j`` (unit ``normals``, ``twice`` their areas) when
    each lies within ``margin`` of the other's plane (0 otherwise, and where it is ``TOUCHING_SHARE`` of
    the smaller one or less), and the mean height of ``j`` over ``i``; ``frame`` (4, 3) and ``work``
    (2, 12, 2) are scratch."""
    t, s = triangles[i], triangles[j]
    mean = 0.0
    for c in range(3):
        up = down = 0.0
        for d in range(3):
            up += (s[c, d] - t[0, d]) * normals[i, d]
            down += (t[c, d] - s[0, d]) * normals[j, d]
        if abs(up) > margin or abs(down) > margin:
            return 0.0, 0.0
        mean += up / 3
    shared = _shared_area(t, s, frame, work)
    if shared <= TOUCHING_SHARE * min(twice[i], twice[j]) / 2:
        return 0.0, 0.0
    return shared, mean


@numba.njit(cache=True, nogil=True)
def _unit_normal(t: NDArray[np.float64], out: NDArray[np.float64]) -> float:
    """Write the unit normal of triangle ``t`` by the right-hand rule into ``out`` (3,) (zero for a
    degenerate one); return twice its area."""
    ux, uy, uz = t[1, 0] - t[0, 0], t[1, 1] - t[0, 1], t[1, 2] - t[0, 2]
    vx, vy, vz = t[2, 0] - t[0, 0], t[2, 1] - t[0, 1], t[2, 2] - t[0, 2]
    out[0], out[1], out[2] = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    size = np.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2])
    if size > 0.0:
        out /= size
    return size


@numba.njit(cache=True, nogil=True)
def _shared_area(
    t: NDArray[np.float64], s: NDArray[np.float64], frame: NDArray[np.float64], work: NDArray[np.float64]
) -> float:
    """Area of triangle ``s`` projected onto the plane of ``t`` and clipped by ``t`` (Sutherland-Hodgman
    in a 2-D frame ``u, v`` of that plane, where ``t`` runs counter-clockwise); ``frame`` (4, 3) and
    ``work`` (2, 12, 2) are scratch."""
    normal, u, v = frame[0], frame[1], frame[2]
    if _unit_normal(t, normal) == 0.0:
        return 0.0
    for d in range(3):
        u[d] = t[1, d] - t[0, d]
    u /= np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
    v[0] = normal[1] * u[2] - normal[2] * u[1]  # in the plane, square to u
    v[1] = normal[2] * u[0] - normal[0] * u[2]
    v[2] = normal[0] * u[1] - normal[1] * u[0]
    polygon, clipped = work[0], work[1]
    clip = frame[3]  # the clipping triangle: (0, 0), (clip[0], 0), (clip[1], clip[2])
    for c in range(3):
        x_s = y_s = 0.0
        for d in range(3):
            x_s += (s[c, d] - t[0, d]) * u[d]
            y_s += (s[c, d] - t[0, d]) * v[d]
        polygon[c, 0], polygon[c, 1] = x_s, y_s
    clip[0] = clip[1] = clip[2] = 0.0
    for d in range(3):
        clip[0] += (t[1, d] - t[0, d]) * u[d]
        clip[1] += (t[2, d] - t[0, d]) * u[d]
        clip[2] += (t[2, d] - t[0, d]) * v[d]
    size = 3
    for e in range(3):
        if e == 0:
            ax, ay, bx, by = 0.0, 0.0, clip[0], 0.0
        elif e == 1:
            ax, ay, bx, by = clip[0], 0.0, clip[1], clip[2]
        else:
            ax, ay, bx, by = clip[1], clip[2], 0.0, 0.0
        kept = 0
        for c in range(size):
            px, py = polygon[c, 0], polygon[c, 1]
            qx, qy = polygon[(c + 1) % size, 0], polygon[(c + 1) % size, 1]
            side_p = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
            side_q = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax)
            if side_p >= 0.0:
                clipped[kept, 0], clipped[kept, 1] = px, py
                kept += 1
            if (side_p >= 0.0) != (side_q >= 0.0):
                w = side_p / (side_p - side_q)
                clipped[kept, 0], clipped[kept, 1] = px + w * (qx - px), py + w * (qy - py)
                kept += 1
        size = kept
        for c in range(size):
            polygon[c, 0], polygon[c, 1] = clipped[c, 0], clipped[c, 1]
        if size < 3:
            return 0.0
    twice_area = 0.0
    for c in range(size):
        twice_area += polygon[c, 0] * polygon[(c + 1) % size, 1] - polygon[(c + 1) % size, 0] * polygon[c, 1]
    return abs(twice_area) / 2
