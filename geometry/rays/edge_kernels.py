"""Numba kernels of the shadow-edge pass (:mod:`sunwind.geometry.rays.shadow_edges`).

Points of a side are given by their coordinates ``(w1, w2)`` on its facet's triangle ``A, B, C``:
``P = A + w1 (B - A) + w2 (C - A)``; the whole side is the triangle (0, 0), (1, 0), (0, 1) of area 1/2.
A node is a sub-triangle of a side in these coordinates, with the lit flags of its three corners.
Each kernel runs serially over its rows, so its results do not depend on threads.
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

#: Most outline lines a node is cut along at once (``2**MAX_LINES`` sign patterns, the cells of their
#: arrangement; a leaf's lit cells are a bit mask of them).
MAX_LINES = 4
#: Share of the way toward the side's centroid that corner and edge points are drawn in before casting.
INSET = 1e-4
#: Margin in side coordinates within which a point counts as on a line or a node's boundary.
_MARGIN = 1e-9


@numba.njit(cache=True, nogil=True)
def boundary_sides(
    corner_ids: NDArray[np.int64], facing: NDArray[np.int64], lit: NDArray[np.bool_], n_ids: int
) -> NDArray[np.int64]:
    """Find the facing sides that share a corner with a facing side of the other lit flag.

    Parameters
    ----------
    corner_ids : (n_sides, 3) ndarray of int64
        Corner numbers of each side (a back side's apart from the front's).
    facing : (n_facing,) ndarray of int64
        The sides facing the source.
    lit : (n_facing,) ndarray of bool
        Lit flag of each facing side (its centroid ray's).
    n_ids : int
        Number of corner numbers.

    Returns
    -------
    (k,) ndarray of int64
        The sides of ``facing`` on a border between lit and dark sides, ascending.

    Examples
    --------
    >>> import numpy as np
    >>> corner_ids = np.array([[0, 1, 2], [1, 2, 3], [4, 5, 6]])
    >>> boundary_sides(corner_ids, np.array([0, 1, 2]), np.array([True, False, True]), 7)
    array([0, 1])
    """
    seen = np.zeros((n_ids, 2), dtype=np.bool_)
    for k in range(facing.shape[0]):
        for c in range(3):
            seen[corner_ids[facing[k], c], 1 if lit[k] else 0] = True
    out = np.empty(facing.shape[0], dtype=np.int64)
    count = 0
    for k in range(facing.shape[0]):
        for c in range(3):
            i = corner_ids[facing[k], c]
            if seen[i, 0] and seen[i, 1]:
                out[count] = facing[k]
                count += 1
                break
    return out[:count]


@numba.njit(cache=True, nogil=True)
def node_origins(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    node_side: NDArray[np.int64],
    points: NDArray[np.float64],
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
    inset: float,
) -> NDArray[np.float32]:
    """Make the ray origins of points of sides, in float32 scene coordinates.

    Each point is drawn ``inset`` of the way toward its side's centroid (a corner or edge point is not
    cast from exactly on an edge) and pushed ``offset_m`` along the normal.

    Parameters
    ----------
    triangles : (n_facets, 3, 3) ndarray of float64
        Facet corners [m].
    side_facet : (n_sides,) ndarray of int64
        Facet of each side.
    normals : (n_sides, 3) ndarray of float64
        Outward normal of each side.
    node_side : (n,) ndarray of int64
        Side of each point.
    points : (n, 2) ndarray of float64
        Points ``(w1, w2)`` in side coordinates.
    centre : (3,) ndarray of float64
        Centre of the scene frame [m].
    half_size : float
        Half-size of the scene frame [m].
    offset_m : float
        Push along the normal [m].
    inset : float
        Share of the way toward the centroid.

    Returns
    -------
    (n, 3) ndarray of float32
        The origins.

    Examples
    --------
    The public way in is :meth:`~sunwind.geometry.rays.quadtree.Caster.lit`, which casts from them:

    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> scene = craft.scene
    >>> o = node_origins(craft.triangles, craft.side_facet, craft.side_normals, np.array([8]),
    ...     np.array([[0.0, 0.0]]), scene.centre, scene.half_size, scene.offset_m, INSET)
    >>> corner = craft.triangles[craft.side_facet[8], 0]
    >>> bool(np.allclose(o * scene.half_size + scene.centre, corner, atol=1e-4))
    True
    """
    out = np.empty((points.shape[0], 3), dtype=np.float32)
    keep = 1.0 - inset
    for k in range(points.shape[0]):
        s = node_side[k]
        f = side_facet[s]
        w1 = keep * points[k, 0] + inset / 3.0
        w2 = keep * points[k, 1] + inset / 3.0
        for d in range(3):
            a = triangles[f, 0, d]
            x = a + w1 * (triangles[f, 1, d] - a) + w2 * (triangles[f, 2, d] - a)
            out[k, d] = (x + offset_m * normals[s, d] - centre[d]) / half_size
    return out


@numba.njit(cache=True, nogil=True)
def _project(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    side: int,
    ends: NDArray[np.float64],
    direction: NDArray[np.float64],
    out: NDArray[np.float64],
) -> bool:
    """Write the shadow of edge ``ends`` (2, 3) [m] on the plane of ``side`` along ``direction`` into
    ``out`` (2, 2), in side coordinates: the part of the edge in front of the plane (between it and the
    source), projected. False where no part of it is in front."""
    f = side_facet[side]
    facing = h0 = h1 = 0.0
    for d in range(3):
        facing += normals[side, d] * direction[d]
        h0 += (ends[0, d] - triangles[f, 0, d]) * normals[side, d]
        h1 += (ends[1, d] - triangles[f, 0, d]) * normals[side, d]
    if facing <= 0.0:
        return False
    if h0 <= 0.0 and h1 <= 0.0:
        return False
    lo, hi = 0.0, 1.0  # the part with positive height, as a share of the edge
    if h0 <= 0.0:
        lo = h0 / (h0 - h1)
    elif h1 <= 0.0:
        hi = h0 / (h0 - h1)
    g11 = g12 = g22 = 0.0
    for d in range(3):
        ab, ac = triangles[f, 1, d] - triangles[f, 0, d], triangles[f, 2, d] - triangles[f, 0, d]
        g11 += ab * ab
        g12 += ab * ac
        g22 += ac * ac
    det = g11 * g22 - g12 * g12
    for e in range(2):
        t = lo if e == 0 else hi
        h = h0 + t * (h1 - h0)
        r1 = r2 = 0.0
        for d in range(3):
            along = ends[0, d] + t * (ends[1, d] - ends[0, d]) - (h / facing) * direction[d]
            flat = along - triangles[f, 0, d]
            r1 += flat * (triangles[f, 1, d] - triangles[f, 0, d])
            r2 += flat * (triangles[f, 2, d] - triangles[f, 0, d])
        out[e, 0] = (g22 * r1 - g12 * r2) / det
        out[e, 1] = (g11 * r2 - g12 * r1) / det
    # an edge along the source direction casts a point, not an outline
    return hi > lo and abs(out[1, 0] - out[0, 0]) + abs(out[1, 1] - out[0, 1]) > _MARGIN


@numba.njit(cache=True, nogil=True)
def outline_segments(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    direction: NDArray[np.float64],
    seed_side: NDArray[np.int64],
    seed_edge: NDArray[np.int64],
    edge_ends: NDArray[np.float64],
    corner_ids: NDArray[np.int64],
    id_start: NDArray[np.int64],
    id_sides: NDArray[np.int64],
    is_facing: NDArray[np.bool_],
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Carry the shadows of silhouette edges over the facing sides they cross, in side coordinates.

    Each edge's shadow is followed from the sides its probes landed on outward over the facing sides
    sharing a corner with a side it crosses, so a shadow stretched across many small or grazing sides is
    found on all of them.

    Parameters
    ----------
    triangles : (n_facets, 3, 3) ndarray of float64
        Facet corners [m].
    side_facet : (n_sides,) ndarray of int64
        Facet of each side.
    normals : (n_sides, 3) ndarray of float64
        Outward normal of each side.
    direction : (3,) ndarray of float64
        Unit vector toward the source.
    seed_side : (m,) ndarray of int64
        Sides the probes landed on, grouped by edge.
    seed_edge : (m,) ndarray of int64
        The silhouette edge of each seed.
    edge_ends : (m, 2, 3) ndarray of float64
        End points of the edge of each seed [m].
    corner_ids : (n_sides, 3) ndarray of int64
        Corner numbers of each side.
    id_start : (n_ids + 1,) ndarray of int64
        The sides at corner ``i`` are ``id_sides[id_start[i]:id_start[i + 1]]``.
    id_sides : ndarray of int64
        Sides, grouped by corner.
    is_facing : (n_sides,) ndarray of bool
        Whether each side faces the source.

    Returns
    -------
    sides : (k,) ndarray of int64
        Side of each segment, in the order found.
    segments : (k, 2, 2) ndarray of float64
        End points in side coordinates.

    Examples
    --------
    Called by :func:`~sunwind.geometry.rays.shadow_edges.outline_of`:

    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.quadtree import Caster
    >>> from sunwind.geometry.rays.shadow_edges import outline_of
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> outline_of(craft, direction, facing, Caster(craft, direction)).side[:4]
    array([24, 24, 26, 26])
    """
    mark = np.full(normals.shape[0], -1, dtype=np.int64)
    whole = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    capacity = max(16, 4 * seed_side.shape[0])
    out_side = np.empty(capacity, dtype=np.int64)
    out_segment = np.empty((capacity, 2, 2))
    queue = np.empty(normals.shape[0], dtype=np.int64)
    segment = np.empty((2, 2))
    count = k = 0
    while k < seed_side.shape[0]:
        edge, head, tail = seed_edge[k], 0, 0
        ends = edge_ends[k]
        while k < seed_side.shape[0] and seed_edge[k] == edge:
            if mark[seed_side[k]] != edge:
                mark[seed_side[k]] = edge
                queue[tail] = seed_side[k]
                tail += 1
            k += 1
        while head < tail:
            side = queue[head]
            head += 1
            if not _project(triangles, side_facet, normals, side, ends, direction, segment):
                continue
            if through(whole, segment[0], segment[1]) == 0:
                continue
            if count == capacity:
                capacity *= 2
                grown_side = np.empty(capacity, dtype=np.int64)
                grown_segment = np.empty((capacity, 2, 2))
                grown_side[:count], grown_segment[:count] = out_side[:count], out_segment[:count]
                out_side, out_segment = grown_side, grown_segment
            out_side[count], out_segment[count] = side, segment
            count += 1
            for c in range(3):
                i = corner_ids[side, c]
                for j in range(id_start[i], id_start[i + 1]):
                    other = id_sides[j]
                    if is_facing[other] and mark[other] != edge:
                        mark[other] = edge
                        queue[tail] = other
                        tail += 1
    return out_side[:count], out_segment[:count]


@numba.njit(cache=True, nogil=True)
def crossing_outlines(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    direction: NDArray[np.float64],
    side: NDArray[np.int64],
    other: NDArray[np.int64],
    open_edges: NDArray[np.bool_],
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Find the shadows on sides of the open edges of the facets that pass through them.

    The edges are those of facet ``other`` that nothing in front of the side continues; their parts in
    front of the side's plane are projected onto it. What lies behind the side's plane shades it not, so
    such an edge may bound the crossing facet's shadow, fold or not.

    Parameters
    ----------
    triangles : (n_facets, 3, 3) ndarray of float64
        Facet corners [m].
    side_facet : (n_sides,) ndarray of int64
        Facet of each side.
    normals : (n_sides, 3) ndarray of float64
        Outward normal of each side.
    direction : (3,) ndarray of float64
        Unit vector toward the source.
    side : (k,) ndarray of int64
        The crossed sides.
    other : (k,) ndarray of int64
        The facet crossing each.
    open_edges : (k, 3) ndarray of bool
        Which edges of ``other`` nothing in front of the side continues.

    Returns
    -------
    sides : (j,) ndarray of int64
        Side of each segment.
    segments : (j, 2, 2) ndarray of float64
        End points in side coordinates.

    Examples
    --------
    >>> import numpy as np
    >>> triangles = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]],   # a floor
    ...                       [[0.2, 0.2, -1], [0.2, 0.2, 1], [0.6, 0.2, 1]]])  # a fin through it
    >>> normals = np.array([[0.0, 0, 1], [0, -1, 0]])
    >>> sides, segments = crossing_outlines(triangles, np.array([0, 1]), normals,
    ...     np.array([0.0, -0.6, 0.8]), np.array([0]), np.array([1]), np.array([[True, True, True]]))
    >>> sides, segments[0]  # the first runs up the floor from the foot of the fin's leading edge
    (array([0, 0, 0]), array([[0.2 , 0.2 ],
           [0.2 , 0.95]]))
    """
    out_side = np.empty(3 * side.shape[0], dtype=np.int64)
    out_segment = np.empty((3 * side.shape[0], 2, 2))
    ends = np.empty((2, 3))
    segment = np.empty((2, 2))
    count = 0
    for k in range(side.shape[0]):
        for e in range(3):
            if not open_edges[k, e]:
                continue
            ends[0], ends[1] = triangles[other[k], e], triangles[other[k], (e + 1) % 3]
            if _project(triangles, side_facet, normals, side[k], ends, direction, segment):
                out_side[count], out_segment[count] = side[k], segment
                count += 1
    return out_side[:count], out_segment[:count]


@numba.njit(cache=True, nogil=True)
def through(corners: NDArray[np.float64], p: NDArray[np.float64], q: NDArray[np.float64]) -> int:
    """Tell how a segment meets a triangle, by Cyrus-Beck clipping of the segment by the three edges.

    Parameters
    ----------
    corners : (3, 2) ndarray of float64
        The triangle.
    p, q : (2,) ndarray of float64
        Ends of the segment.

    Returns
    -------
    int
        0 not at all, 1 with an end inside, 2 passing through (both ends outside).

    Examples
    --------
    >>> import numpy as np
    >>> tri = np.array([[0.0, 0], [1, 0], [0, 1]])
    >>> through(tri, np.array([-1.0, 0.2]), np.array([2.0, 0.2])), through(tri, np.array([0.1, 0.1]),
    ...     np.array([2.0, 0.1])), through(tri, np.array([2.0, 2]), np.array([3.0, 3]))
    (2, 1, 0)
    """
    orient = (corners[1, 0] - corners[0, 0]) * (corners[2, 1] - corners[0, 1]) - (
        corners[1, 1] - corners[0, 1]
    ) * (corners[2, 0] - corners[0, 0])
    sign = 1.0 if orient > 0 else -1.0
    enter, leave = 0.0, 1.0
    for i in range(3):
        a, b = corners[i], corners[(i + 1) % 3]
        ex, ey = b[0] - a[0], b[1] - a[1]
        # inside where sign * cross(e, x - a) > 0
        at_p = sign * (ex * (p[1] - a[1]) - ey * (p[0] - a[0]))
        at_q = sign * (ex * (q[1] - a[1]) - ey * (q[0] - a[0]))
        if at_p <= _MARGIN and at_q <= _MARGIN:
            return 0
        if at_p < _MARGIN:
            enter = max(enter, (_MARGIN - at_p) / (at_q - at_p))
        elif at_q < _MARGIN:
            leave = min(leave, (at_p - _MARGIN) / (at_p - at_q))
    if leave - enter <= 0.0:
        return 0
    return 2 if enter > 0.0 and leave < 1.0 else 1


@numba.njit(cache=True, nogil=True)
def line_through(p: NDArray[np.float64], q: NDArray[np.float64]) -> tuple[float, float, float]:
    """Find the line through two points, positive on the left of ``p -> q``.

    Parameters
    ----------
    p, q : (2,) ndarray of float64
        Two distinct points.

    Returns
    -------
    tuple of float
        ``(a, b, c)``: the line ``a x + b y + c = 0``.

    Examples
    --------
    >>> import numpy as np
    >>> a, b, c = line_through(np.array([0.0, 0.0]), np.array([1.0, 0.0]))
    >>> a * 0.5 + b * 1.0 + c  # a point on the left: positive
    1.0
    """
    a, b = -(q[1] - p[1]), q[0] - p[0]
    return a, b, -(a * p[0] + b * p[1])


@numba.njit(cache=True, nogil=True)
def clip_moments(
    corners: NDArray[np.float64],
    lines: NDArray[np.float64],
    n_lines: int,
    scratch: NDArray[np.float64],
    out: NDArray[np.float64],
) -> None:
    """Write the area and first moments of the part of a triangle where some lines are all positive.

    Sutherland-Hodgman clipping of the triangle by each line in turn.

    Parameters
    ----------
    corners : (3, 2) ndarray of float64
        The triangle.
    lines : (k, 3) ndarray of float64
        Lines ``(a, b, c)``, positive where ``a x + b y + c > 0``.
    n_lines : int
        How many of ``lines`` to clip by.
    scratch : (2, 3 + n_lines or more, 2) ndarray of float64
        Work space.
    out : (3,) ndarray of float64
        Written: ``(area, area * w1, area * w2)`` of the clipped part.

    Examples
    --------
    >>> import numpy as np
    >>> tri, out = np.array([[0.0, 0], [1, 0], [0, 1]]), np.zeros(3)
    >>> clip_moments(tri, np.array([[1.0, 0.0, -0.5]]), 1, np.zeros((2, 8, 2)), out)  # keep x > 0.5
    >>> out.round(4)
    array([0.125 , 0.0833, 0.0208])
    """
    polygon, clipped = scratch[0], scratch[1]
    polygon[:3] = corners
    count = 3
    for j in range(n_lines):
        kept = 0
        for i in range(count):
            a, b = polygon[i], polygon[(i + 1) % count]
            fa = lines[j, 0] * a[0] + lines[j, 1] * a[1] + lines[j, 2]
            fb = lines[j, 0] * b[0] + lines[j, 1] * b[1] + lines[j, 2]
            if fa >= 0.0:
                clipped[kept] = a
                kept += 1
            if (fa >= 0.0) != (fb >= 0.0):
                t = fa / (fa - fb)
                clipped[kept, 0] = a[0] + t * (b[0] - a[0])
                clipped[kept, 1] = a[1] + t * (b[1] - a[1])
                kept += 1
        polygon[:kept] = clipped[:kept]
        count = kept
    out[:] = 0.0
    for i in range(1, count - 1):  # a fan from the first vertex of the convex polygon
        p, q, r = polygon[0], polygon[i], polygon[i + 1]
        piece = 0.5 * abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
        out[0] += piece
        out[1] += piece * (p[0] + q[0] + r[0]) / 3.0
        out[2] += piece * (p[1] + q[1] + r[1]) / 3.0
