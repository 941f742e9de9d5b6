"""Numba kernels of one round of the shadow-edge pass (:mod:`sunwind.geometry.rays.shadow_edges`):
the nodes' leaves added to their sides, the split nodes' children, and the chords' bisection.

A chord is the cut of a node along the line through the points where its two mixed edges change
state: the edges from the corner whose state differs (the apex) to the other two. Each edge's
crossing is bracketed by a lit end and a dark end; a round casts ``BISECTION_POINTS`` points evenly
inside each bracket and keeps the piece between the last lit point before the first dark one and that
dark point. Each kernel runs serially over its rows, so its results do not depend on threads.
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.edge_kernels import BISECT, CHECK, EXACT_CUT, REGION, SPLIT, UNIFORM, clip_moments

#: Points cast per bisected edge and round: each round divides its bracket by four.
BISECTION_POINTS = 3
#: Bits of a crossing's position each round locates.
BITS_PER_ROUND = 2.0
#: A node's children as corners of the parent (0, 1, 2) and its edge midpoints (3, 4, 5 on 01, 12, 20).
_CHILDREN = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])


@numba.njit(cache=True, nogil=True)
def advance(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    action: NDArray[np.int8],
    part: NDArray[np.float64],
    moments: NDArray[np.float64],
) -> tuple:
    """Add the moments ``part`` of the leaves (``UNIFORM``, ``EXACT_CUT``) to ``moments[root]`` in place;
    return the nodes whose edge midpoints are cast next (``SPLIT`` and ``CHECK``: root, corners, lit,
    midpoints (n, 3, 2), whether it is a check), the ``BISECT`` nodes as new chords (root, corners,
    apex, apex_lit, lit_end, dark_end), and the ``REGION`` nodes (root, corners, their corners' state,
    the region's moments, its centroid)."""
    n_split = n_bisect = n_region = 0
    for k in range(root.shape[0]):
        if action[k] == UNIFORM or action[k] == EXACT_CUT:
            for c in range(3):
                moments[root[k], c] += part[k, c]
        n_split += action[k] == SPLIT or action[k] == CHECK
        n_bisect += action[k] == BISECT
        n_region += action[k] == REGION
    split_root = np.empty(n_split, dtype=np.int64)
    split_corners = np.empty((n_split, 3, 2))
    split_lit = np.empty((n_split, 3), dtype=np.bool_)
    mid = np.empty((n_split, 3, 2))
    check = np.empty(n_split, dtype=np.bool_)
    chords = _new_chords(n_bisect)
    region_root = np.empty(n_region, dtype=np.int64)
    region_corners = np.empty((n_region, 3, 2))
    region_lit = np.empty(n_region, dtype=np.bool_)
    region = np.empty((n_region, 3))
    region_point = np.empty((n_region, 2))
    i = j = r = 0
    for k in range(root.shape[0]):
        if action[k] == REGION:
            region_root[r], region_corners[r], region_lit[r] = root[k], corners[k], lit[k, 0]
            region[r] = part[k]
            region_point[r, 0], region_point[r, 1] = part[k, 1] / part[k, 0], part[k, 2] / part[k, 0]
            r += 1
        elif action[k] == SPLIT or action[k] == CHECK:
            split_root[i], split_corners[i], split_lit[i] = root[k], corners[k], lit[k]
            check[i] = action[k] == CHECK
            for e in range(3):
                mid[i, e] = (corners[k, e] + corners[k, (e + 1) % 3]) / 2
            i += 1
        elif action[k] == BISECT:
            _start_chord(chords, j, root[k], corners[k], lit[k])
            j += 1
    nodes = (split_root, split_corners, split_lit, mid, check)
    regions = (region_root, region_corners, region_lit, region, region_point)
    return nodes, chords, regions


@numba.njit(cache=True, nogil=True)
def _new_chords(n: int) -> tuple:
    """Empty chord arrays for ``n`` chords: root, corners, apex, apex_lit, lit_end, dark_end."""
    return (
        np.empty(n, dtype=np.int64),
        np.empty((n, 3, 2)),
        np.empty((n, 2)),
        np.empty(n, dtype=np.bool_),
        np.empty((n, 2, 2)),
        np.empty((n, 2, 2)),
    )


@numba.njit(cache=True, nogil=True)
def _lone(lit: NDArray[np.bool_]) -> int:
    """The corner of a node with disagreeing corner flags ``lit`` (3,) whose flag the other two share not."""
    return 2 if lit[0] == lit[1] else (1 if lit[0] == lit[2] else 0)


@numba.njit(cache=True, nogil=True)
def _start_chord(chords: tuple, j: int, root: int, corners: NDArray, lit: NDArray[np.bool_]) -> int:
    """Write chord ``j`` of a node with disagreeing corners; return its apex (the lone corner)."""
    lone = _lone(lit)
    chords[0][j], chords[1][j] = root, corners
    apex, apex_lit = corners[lone], lit[lone]
    chords[2][j], chords[3][j] = apex, apex_lit
    for e in range(2):
        other = corners[(lone + 1 + e) % 3]
        chords[4][j, e] = apex if apex_lit else other
        chords[5][j, e] = other if apex_lit else apex
    return lone


@numba.njit(cache=True, nogil=True)
def resolve_splits(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    mid: NDArray[np.float64],
    mid_lit: NDArray[np.bool_],
    check: NDArray[np.bool_],
    moments: NDArray[np.float64],
) -> tuple:
    """Resolve the nodes whose edge midpoints ``mid`` (n, 3, 2) were cast (flags ``mid_lit`` (n, 3)).
    A ``CHECK`` node whose corners agree and whose midpoints agree with them is uniform (added to
    ``moments[root]`` in place); one with disagreeing corners whose uniform edge's midpoint agrees with
    that edge's ends becomes a chord, its two mixed edges' midpoints its first bisection step. Every
    other node is split into its four children. Returns the children (root, corners, lit) and the new
    chords (as :func:`advance`)."""
    n = root.shape[0]
    kind = np.zeros(n, dtype=np.int8)  # 0 children, 1 uniform, 2 chord
    for k in range(n):
        if not check[k]:
            continue
        agree = lit[k, 0] == lit[k, 1] and lit[k, 1] == lit[k, 2]
        if agree:
            if mid_lit[k, 0] == lit[k, 0] and mid_lit[k, 1] == lit[k, 0] and mid_lit[k, 2] == lit[k, 0]:
                kind[k] = 1
        else:
            lone = _lone(lit[k])
            if mid_lit[k, (lone + 1) % 3] == lit[k, (lone + 1) % 3]:
                kind[k] = 2
    n_children, n_chords = 4 * int(np.sum(kind == 0)), int(np.sum(kind == 2))
    out_root = np.empty(n_children, dtype=np.int64)
    out_corners = np.empty((n_children, 3, 2))
    out_lit = np.empty((n_children, 3), dtype=np.bool_)
    chords = _new_chords(n_chords)
    lines = np.empty((0, 3))
    scratch = np.empty((2, 4, 2))
    whole = np.empty(3)
    row = j = 0
    for k in range(n):
        if kind[k] == 1:
            if lit[k, 0]:
                clip_moments(corners[k], lines, 0, scratch, whole)
                for c in range(3):
                    moments[root[k], c] += whole[c]
        elif kind[k] == 2:
            lone = _start_chord(chords, j, root[k], corners[k], lit[k])
            # the mixed edges lone -> lone + 1 and lone -> lone + 2 have midpoints lone and lone + 2
            for e, m in enumerate((lone, (lone + 2) % 3)):
                if mid_lit[k, m]:
                    chords[4][j, e] = mid[k, m]
                else:
                    chords[5][j, e] = mid[k, m]
            j += 1
        else:
            for c in range(4):
                out_root[row] = root[k]
                for v in range(3):
                    p = _CHILDREN[c, v]
                    if p < 3:
                        out_corners[row, v], out_lit[row, v] = corners[k, p], lit[k, p]
                    else:
                        out_corners[row, v], out_lit[row, v] = mid[k, p - 3], mid_lit[k, p - 3]
                row += 1
    return (out_root, out_corners, out_lit), chords


@numba.njit(cache=True, nogil=True)
def chord_trials(
    lit_end: NDArray[np.float64], dark_end: NDArray[np.float64], steps: NDArray[np.float64]
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """The chords still being located (``steps > 0``) and their next points: ``BISECTION_POINTS``
    evenly inside the bracket of each of their two edges, (m * 2 * BISECTION_POINTS, 2)."""
    trying = np.flatnonzero(steps > 0)
    points = np.empty((trying.shape[0] * 2 * BISECTION_POINTS, 2))
    row = 0
    for k in trying:
        for e in range(2):
            for i in range(BISECTION_POINTS):
                t = (i + 1) / (BISECTION_POINTS + 1)
                points[row] = lit_end[k, e] + t * (dark_end[k, e] - lit_end[k, e])
                row += 1
    return trying, points


@numba.njit(cache=True, nogil=True)
def chord_update(
    lit_end: NDArray[np.float64],
    dark_end: NDArray[np.float64],
    steps: NDArray[np.float64],
    trying: NDArray[np.int64],
    lit: NDArray[np.bool_],
) -> None:
    """Narrow the brackets of chords ``trying`` in place from the flags ``lit`` of their trial points."""
    row = 0
    for k in trying:
        for e in range(2):
            lo, hi = lit_end[k, e].copy(), dark_end[k, e].copy()
            first_dark = BISECTION_POINTS + 1
            for i in range(BISECTION_POINTS):
                if not lit[row + i] and first_dark > BISECTION_POINTS:
                    first_dark = i + 1
            row += BISECTION_POINTS
            step = hi - lo
            lit_end[k, e] = lo + ((first_dark - 1) / (BISECTION_POINTS + 1)) * step
            dark_end[k, e] = lo + (first_dark / (BISECTION_POINTS + 1)) * step
        steps[k] -= BITS_PER_ROUND


@numba.njit(cache=True, nogil=True)
def add_chords(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    apex: NDArray[np.float64],
    apex_lit: NDArray[np.bool_],
    lit_end: NDArray[np.float64],
    dark_end: NDArray[np.float64],
    moments: NDArray[np.float64],
) -> None:
    """Add the lit moments of each chord's node, cut along the line through the middles of its two
    brackets, to ``moments[root]`` in place. Both crossings at the apex: the node is as its other
    corners are."""
    line = np.empty((1, 3))
    scratch = np.empty((2, 4, 2))
    part = np.empty(3)
    for k in range(root.shape[0]):
        p = (lit_end[k, 0] + dark_end[k, 0]) / 2
        q = (lit_end[k, 1] + dark_end[k, 1]) / 2
        a, b = -(q[1] - p[1]), q[0] - p[0]
        c = -(a * p[0] + b * p[1])
        if abs(a) + abs(b) <= 1e-12:
            a = b = 0.0
            c = -1.0 if apex_lit[k] else 1.0
        elif (a * apex[k, 0] + b * apex[k, 1] + c > 0) != apex_lit[k]:
            a, b, c = -a, -b, -c
        line[0, 0], line[0, 1], line[0, 2] = a, b, c
        clip_moments(corners[k], line, 1, scratch, part)
        for i in range(3):
            moments[root[k], i] += part[i]


@numba.njit(cache=True, nogil=True)
def settle_regions(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    corner_lit: NDArray[np.bool_],
    region: NDArray[np.float64],
    region_lit: NDArray[np.bool_],
    moments: NDArray[np.float64],
) -> None:
    """Add the lit moments of each ``REGION`` node to ``moments[root]`` in place, given the state of its
    region (the ray from the region's centroid) and of its corners (all alike): the region lit and the
    rest dark, the rest lit and the region dark, or the node uniform."""
    lines = np.empty((0, 3))
    scratch = np.empty((2, 4, 2))
    whole = np.empty(3)
    for k in range(root.shape[0]):
        clip_moments(corners[k], lines, 0, scratch, whole)
        for c in range(3):
            if region_lit[k] == corner_lit[k]:
                lit_part = whole[c] if corner_lit[k] else 0.0
            else:
                lit_part = region[k, c] if region_lit[k] else whole[c] - region[k, c]
            moments[root[k], c] += lit_part
