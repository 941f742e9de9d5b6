"""Numba kernels of the quadtree of the shadow-edge pass: what becomes of each node, which points it
casts, and what their rays make of it (:mod:`sunwind.geometry.rays.quadtree`).

A node is a sub-triangle of a side in the side's coordinates ``(w1, w2)`` (the whole side is (0, 0),
(1, 0), (0, 1)), with the lit flag of a ray at each corner, its depth (a node at depth ``d`` holds
``4**-d`` of its side) and flags. Where outline segments cross a node, their lines cut it into the
cells of their arrangement (at most ``MAX_LINES`` lines); on a flat side under a distant source every
edge of the shadow lies on such a line if the outline is complete, so each cell is wholly lit or
wholly dark, and one ray from inside each cell says which. Nothing is taken on trust: a node's corners
must agree with the cells they lie in, or the node is split (``SUSPECT``) and its children cut along
the lines again, down to the depth limit, where it is resolved by rays alone: checked at its edge
midpoints and cut along bisected chords. A side without ``TRUST`` is resolved by rays alone. Each
kernel runs serially over its rows, so its results do not depend on threads.
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.edge_kernels import INSET, MAX_LINES, clip_moments, line_through, through
from sunwind.geometry.rays.leaf_kernels import lone_corner, pattern_of

#: What becomes of a node: a leaf now (uniform by its corners), cut into the cells of the outline lines
#: crossing it (a ray in each), checked at its edge midpoints, cut along a bisected chord, or split.
LEAF, ARRANGE, CHECK, BISECT, SPLIT = 0, 1, 2, 3, 4
#: Node flags: the outline may be cut along; the side's centroid ray disagrees with the node's corners
#: (whole sides only); a corner disagreed with the node's cells, so it is split (its children trust the
#: outline again, each cut along the lines crossing it) or, at the depth limit, resolved by rays alone.
TRUST, CENTRE_DIFFERS, SUSPECT = 1, 2, 4
#: Most points a node casts in one round: a ray in each cell of ``MAX_LINES`` lines, or three midpoints.
MOST_POINTS = 2**MAX_LINES
#: Cells smaller than this share of their node are not cast at (they carry no area worth a ray).
_SMALLEST_CELL = 1e-12
#: Lines closer than this (in side coordinates) are one line.
_SAME_LINE = 1e-10
#: A node's children as corners of the parent (0, 1, 2) and its edge midpoints (3, 4, 5 on 01, 12, 20).
_CHILDREN = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])


@numba.njit(cache=True, nogil=True)
def classify_nodes(
    node_side: NDArray[np.int64],
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    depth: NDArray[np.int64],
    flags: NDArray[np.int8],
    floor: NDArray[np.int64],
    segment_side: NDArray[np.int64],
    segments: NDArray[np.float64],
    depths: NDArray[np.int64],
) -> tuple:
    """Decide what becomes of each node (``LEAF`` ... ``SPLIT``), the lines cutting it and its points.

    A node crossed by more lines than ``MAX_LINES`` is split below depth ``most``; a node not cut along
    lines whose corners disagree is checked at its edge midpoints below ``mixed`` and cut along a chord
    at the limit; a whole side whose corners agree is checked at its edge midpoints; a node whose corners
    agree is otherwise a uniform leaf.

    Parameters
    ----------
    node_side : (n,) ndarray of int64
        Side of each node.
    corners : (n, 3, 2) ndarray of float64
        Each node, in side coordinates.
    lit : (n, 3) ndarray of bool
        Corner flags.
    depth : (n,) ndarray of int64
        Depth of each node.
    flags : (n,) ndarray of int8
        Node flags (``TRUST``, ``CENTRE_DIFFERS``, ``SUSPECT``).
    floor : (n,) ndarray of int64
        Depth each node is split to before anything else (0 but in the fallback).
    segment_side : (m,) ndarray of int64
        Side of each outline segment, ascending.
    segments : (m, 2, 2) ndarray of float64
        The outline segments, in side coordinates.
    depths : (3,) ndarray of int64
        ``(uniform, mixed, most)`` (:func:`~.quadtree.depths`).

    Returns
    -------
    action : (n,) ndarray of int8
        ``LEAF``, ``ARRANGE``, ``CHECK``, ``BISECT`` or ``SPLIT``.
    lines : (n, MAX_LINES, 3) ndarray of float64
        The distinct lines of the outline segments crossing an ``ARRANGE`` node.
    n_lines : (n,) ndarray of int64
        How many.
    points : (n, MOST_POINTS, 2) ndarray of float64
        Points to cast: a point inside each cell of an ``ARRANGE`` node, or the edge midpoints of a
        ``SPLIT`` or ``CHECK`` node.
    pattern : (n, MOST_POINTS) ndarray of int64
        Sign pattern of the cell of each point.
    n_points : (n,) ndarray of int64
        How many points.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])  # a whole side
    >>> lit = np.array([[False, True, True]])  # corner 0 in shadow
    >>> outline = np.array([[[0.5, -0.1], [-0.1, 0.5]]])  # one outline segment across it, on side 7
    >>> zero, one, trust = np.zeros(1, np.int64), np.ones(1, np.int64), np.full(1, TRUST, np.int8)
    >>> action, lines, n_lines, points, pattern, n_points = classify_nodes(np.array([7]), corners, lit,
    ...     one, trust, zero, np.array([7]), outline, np.array([5, 5, 10]))
    >>> action.tolist() == [ARRANGE], n_lines, n_points, pattern[0, :2]
    (True, array([1]), array([2]), array([0, 1]))
    """
    n = node_side.shape[0]
    action = np.empty(n, dtype=np.int8)
    lines = np.zeros((n, MAX_LINES, 3))
    n_lines = np.zeros(n, dtype=np.int64)
    points = np.zeros((n, MOST_POINTS, 2))
    pattern = np.zeros((n, MOST_POINTS), dtype=np.int64)
    n_points = np.zeros(n, dtype=np.int64)
    scratch = np.empty((2, 3 + MAX_LINES, 2))
    for k in range(n):
        suspect = (flags[k] & SUSPECT) != 0
        trust = (flags[k] & TRUST) != 0 and not suspect
        count = 0
        if trust and depth[k] >= floor[k]:
            first = np.searchsorted(segment_side, node_side[k])
            last = np.searchsorted(segment_side, node_side[k], side="right")
            for j in range(first, last):
                if through(corners[k], segments[j, 0], segments[j, 1]):
                    count = _add_line(segments[j], lines[k], count)
        agree = lit[k, 0] == lit[k, 1] and lit[k, 1] == lit[k, 2]
        if depth[k] < floor[k] or (suspect and depth[k] < depths[1]):
            action[k] = SPLIT
        elif count > MAX_LINES:
            action[k] = SPLIT if depth[k] < depths[2] else (LEAF if agree else BISECT)
        elif count:
            n_lines[k] = count
            action[k] = ARRANGE
            n_points[k] = _cells(corners[k], lines[k], count, scratch, points[k], pattern[k])
        elif not agree:
            action[k] = CHECK if depth[k] < depths[1] else BISECT
        elif (flags[k] & CENTRE_DIFFERS) != 0:
            action[k] = SPLIT if depth[k] < depths[1] else LEAF
        else:
            action[k] = CHECK if depth[k] == 0 or depth[k] == floor[k] else LEAF
        if action[k] == SPLIT or action[k] == CHECK:
            for e in range(3):
                points[k, e] = (corners[k, e] + corners[k, (e + 1) % 3]) / 2
            n_points[k] = 3
    return action, lines, n_lines, points, pattern, n_points


@numba.njit(cache=True, nogil=True)
def _add_line(segment: NDArray[np.float64], lines: NDArray[np.float64], count: int) -> int:
    """Add the line of ``segment`` to ``lines[:count]`` unless it is there already (either way round);
    return the new count, ``MAX_LINES + 1`` once there are more lines than room."""
    if count > MAX_LINES:
        return count
    a, b, c = line_through(segment[0], segment[1])
    norm = np.sqrt(a * a + b * b)
    if norm == 0.0:
        return count
    a, b, c = a / norm, b / norm, c / norm
    for j in range(count):
        for s in (1.0, -1.0):
            if abs(s * a - lines[j, 0]) + abs(s * b - lines[j, 1]) + abs(s * c - lines[j, 2]) <= _SAME_LINE:
                return count
    if count == MAX_LINES:
        return MAX_LINES + 1
    lines[count, 0], lines[count, 1], lines[count, 2] = a, b, c
    return count + 1


@numba.njit(cache=True, nogil=True)
def _cells(
    corners: NDArray[np.float64],
    lines: NDArray[np.float64],
    count: int,
    scratch: NDArray[np.float64],
    points: NDArray[np.float64],
    pattern: NDArray[np.int64],
) -> int:
    """Write a point for each cell of the arrangement of ``lines[:count]`` in the node, placed so that
    its ray (drawn ``INSET`` toward the side's centroid, :func:`~.edge_kernels.node_origins`) starts at
    the cell's centroid, and the cell's sign pattern (bit ``j`` set where line ``j`` is positive);
    return the number of cells."""
    oriented = np.empty((MAX_LINES, 3))
    part, whole = np.empty(3), np.empty(3)
    clip_moments(corners, lines, 0, scratch, whole)
    keep = 1.0 - INSET
    cells = 0
    for p in range(2**count):
        for j in range(count):
            s = 1.0 if (p >> j) & 1 else -1.0
            for c in range(3):
                oriented[j, c] = s * lines[j, c]
        clip_moments(corners, oriented, count, scratch, part)
        if part[0] <= _SMALLEST_CELL * whole[0]:
            continue
        # a cell may be thinner than the inset moves a point: the ray must start in the cell
        x, y = part[1] / part[0], part[2] / part[0]
        points[cells, 0], points[cells, 1] = (x - INSET / 3.0) / keep, (y - INSET / 3.0) / keep
        pattern[cells] = p
        cells += 1
    return cells


@numba.njit(cache=True, nogil=True)
def resolve_nodes(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    depth: NDArray[np.int64],
    flags: NDArray[np.int8],
    action: NDArray[np.int8],
    lines: NDArray[np.float64],
    n_lines: NDArray[np.int64],
    pattern: NDArray[np.int64],
    n_points: NDArray[np.int64],
    cast: NDArray[np.bool_],
) -> tuple:
    """Read the rays cast at the nodes' points and decide each node.

    Parameters
    ----------
    root : (n,) ndarray of int64
        Root (side) index of each node.
    corners : (n, 3, 2) ndarray of float64
        Each node, in side coordinates.
    lit : (n, 3) ndarray of bool
        Corner flags.
    depth : (n,) ndarray of int64
        Depth of each node.
    flags : (n,) ndarray of int8
        Node flags.
    action, lines, n_lines, pattern, n_points : ndarray
        As :func:`classify_nodes` returned them.
    cast : (n, MOST_POINTS) ndarray of bool
        Lit flags of the points, as :func:`classify_nodes` laid them out.

    Returns
    -------
    kind : (n,) ndarray of int8
        0 a leaf; 1 split into four children (from its midpoints); 2 kept for the next round no longer
        trusting the outline (a corner disagrees with its cell); 3 a chord (its midpoints its first
        bisection step where it has them cast: a ``CHECK`` node).
    mask : (n,) ndarray of uint64
        For a leaf, bit ``p`` set where the cell of sign pattern ``p`` is lit (a node without lines has
        the one pattern 0).
    children : tuple of ndarray
        Root, corners, lit, depth and flags of the children, in node order.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])  # a whole side
    >>> lit = np.array([[False, True, True]])  # corner 0 in shadow
    >>> outline = np.array([[[0.5, -0.1], [-0.1, 0.5]]])  # one outline segment across it, on side 7
    >>> zero, one, trust = np.zeros(1, np.int64), np.ones(1, np.int64), np.full(1, TRUST, np.int8)
    >>> action, lines, n_lines, points, pattern, n_points = classify_nodes(np.array([7]), corners, lit,
    ...     one, trust, zero, np.array([7]), outline, np.array([5, 5, 10]))
    >>> cast = np.zeros((1, MOST_POINTS), dtype=bool)
    >>> cast[0, 0] = True  # the cell away from corner 0 is lit, the one at it is not
    >>> kind, mask, children = resolve_nodes(zero, corners, lit, one, trust, action, lines, n_lines,
    ...     pattern, n_points, cast)
    >>> kind, mask, len(children[0])  # a leaf, lit in the cell of pattern 0
    (array([0], dtype=int8), array([1], dtype=uint64), 0)
    """
    n = root.shape[0]
    kind = np.zeros(n, dtype=np.int8)
    mask = np.zeros(n, dtype=np.uint64)
    one = np.uint64(1)
    for k in range(n):
        a = action[k]
        if a == LEAF:
            mask[k] = one if lit[k, 0] else np.uint64(0)
        elif a == ARRANGE:
            for i in range(n_points[k]):
                if cast[k, i]:
                    mask[k] |= one << np.uint64(pattern[k, i])
            if not _corners_agree(corners[k], lit[k], lines[k], n_lines[k], pattern[k], n_points[k], mask[k]):
                kind[k] = 2
        elif a == CHECK:
            agree = lit[k, 0] == lit[k, 1] and lit[k, 1] == lit[k, 2]
            if agree:
                same = cast[k, 0] == lit[k, 0] and cast[k, 1] == lit[k, 0] and cast[k, 2] == lit[k, 0]
                if same:
                    mask[k] = one if lit[k, 0] else np.uint64(0)
                else:
                    kind[k] = 1
            else:
                lone = lone_corner(lit[k])
                kind[k] = 3 if cast[k, (lone + 1) % 3] == lit[k, (lone + 1) % 3] else 1
        elif a == SPLIT:
            kind[k] = 1
        else:
            kind[k] = 3
    n_children = 4 * int(np.sum(kind == 1))
    child_root = np.empty(n_children, dtype=np.int64)
    child_corners = np.empty((n_children, 3, 2))
    child_lit = np.empty((n_children, 3), dtype=np.bool_)
    child_depth = np.empty(n_children, dtype=np.int64)
    child_flags = np.empty(n_children, dtype=np.int8)
    row = 0
    for k in range(n):
        if kind[k] != 1:
            continue
        for c in range(4):
            child_root[row], child_depth[row] = root[k], depth[k] + 1
            child_flags[row] = flags[k] & ~(CENTRE_DIFFERS | SUSPECT)
            for v in range(3):
                p = _CHILDREN[c, v]
                if p < 3:
                    child_corners[row, v], child_lit[row, v] = corners[k, p], lit[k, p]
                else:
                    child_corners[row, v] = (corners[k, p - 3] + corners[k, (p - 2) % 3]) / 2
                    child_lit[row, v] = cast[k, p - 3]
            row += 1
    return kind, mask, (child_root, child_corners, child_lit, child_depth, child_flags)


@numba.njit(cache=True, nogil=True)
def _corners_agree(
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    lines: NDArray[np.float64],
    count: int,
    pattern: NDArray[np.int64],
    cells: int,
    mask: np.uint64,
) -> bool:
    """Whether each corner not on a line lies in a cast cell whose state is the corner's own (the
    corner's ray starts ``INSET`` of the way toward the side's centroid, and is placed so here)."""
    keep = 1.0 - INSET
    for i in range(3):
        x, y = keep * corners[i, 0] + INSET / 3.0, keep * corners[i, 1] + INSET / 3.0
        p = pattern_of(lines, count, x, y)
        if p < 0:
            continue
        found = False
        for c in range(cells):
            found |= pattern[c] == p
        if not found:
            continue  # a corner in a cell too small to cast at
        if ((mask >> np.uint64(p)) & np.uint64(1) == np.uint64(1)) != lit[i]:
            return False
    return True
