"""Numba kernels of the leaves of the shadow-edge pass: chords bisected to their crossings, each
leaf's lit moments, and what the leaves say of any point of a side (the certificate's question).

A leaf is a node whose lit part is known: up to ``MAX_LINES`` lines cut it into cells, each named by
its sign pattern (bit ``j`` set where line ``j`` is positive), and a bit mask says which cells are lit
(a uniform leaf has no line and the one pattern 0).
A chord is a node cut along the line through the points where its two mixed edges change state (the
edges from the corner whose state differs, the apex, to the other two); each edge's crossing is
bracketed by a lit end and a dark end, and each round casts ``BISECTION_POINTS`` points evenly inside
each bracket and keeps the piece between the last lit point before the first dark one and that dark
point. A chord's leaf records the bracket's width as its ``band``, where the chord and the true edge
of the shadow may disagree. Each kernel runs serially over its rows, so its results do not depend on
threads.
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.edge_kernels import MAX_LINES, clip_moments

#: Points cast per bisected edge and round: each round divides its bracket by four.
BISECTION_POINTS = 3
#: Bits of a crossing's position each round locates.
BITS_PER_ROUND = 2.0
#: A located chord is checked this many bracket widths either side of its middle.
CHECK_BANDS = 4.0
#: What the leaves say of a point: dark, lit, or within a chord's band (either).
DARK, LIT, EITHER = 0, 1, 2


@numba.njit(cache=True, nogil=True)
def lone_corner(lit: NDArray[np.bool_]) -> int:
    """Find the corner of a node whose flag the other two do not share.

    Parameters
    ----------
    lit : (3,) ndarray of bool
        Corner flags, not all alike.

    Returns
    -------
    int
        0, 1 or 2.

    Examples
    --------
    >>> import numpy as np
    >>> lone_corner(np.array([True, False, True]))
    1
    """
    return 2 if lit[0] == lit[1] else (1 if lit[0] == lit[2] else 0)


@numba.njit(cache=True, nogil=True)
def start_chords(
    corners: NDArray[np.float64],
    lit: NDArray[np.bool_],
    mid_lit: NDArray[np.bool_],
    started: NDArray[np.bool_],
) -> tuple:
    """Start the chords of nodes whose corners disagree.

    Where ``started``, the edge midpoints' flags ``mid_lit`` are the first bisection step.

    Parameters
    ----------
    corners : (n, 3, 2) ndarray of float64
        Each node, in side coordinates.
    lit : (n, 3) ndarray of bool
        Corner flags, not all alike.
    mid_lit : (n, 3) ndarray of bool
        Flags of the edge midpoints, read where ``started``.
    started : (n,) ndarray of bool
        Whether the midpoints were cast.

    Returns
    -------
    apex : (n, 2) ndarray of float64
        The lone corner (:func:`lone_corner`) of each node.
    apex_lit : (n,) ndarray of bool
        Its flag.
    lit_end : (n, 2, 2) ndarray of float64
        The lit end of the bracket on each of the chord's two edges.
    dark_end : (n, 2, 2) ndarray of float64
        The dark end of each bracket.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])
    >>> lit = np.array([[True, False, False]])  # corner 0 lit, the others dark
    >>> apex, apex_lit, lit_end, dark_end = start_chords(corners, lit, np.zeros((1, 3), bool),
    ...     np.array([False]))
    >>> apex, apex_lit, dark_end
    (array([[0., 0.]]), array([ True]), array([[[1., 0.],
            [0., 1.]]]))
    """
    n = corners.shape[0]
    apex = np.empty((n, 2))
    apex_lit = np.empty(n, dtype=np.bool_)
    lit_end = np.empty((n, 2, 2))
    dark_end = np.empty((n, 2, 2))
    for k in range(n):
        lone = lone_corner(lit[k])
        apex[k], apex_lit[k] = corners[k, lone], lit[k, lone]
        for e in range(2):
            other = corners[k, (lone + 1 + e) % 3]
            lit_end[k, e] = apex[k] if apex_lit[k] else other
            dark_end[k, e] = other if apex_lit[k] else apex[k]
            if started[k]:
                # the mixed edges lone -> lone + 1 and lone -> lone + 2 have midpoints lone and lone + 2
                m = lone if e == 0 else (lone + 2) % 3
                middle = (corners[k, lone] + other) / 2
                if mid_lit[k, m]:
                    lit_end[k, e] = middle
                else:
                    dark_end[k, e] = middle
    return apex, apex_lit, lit_end, dark_end


@numba.njit(cache=True, nogil=True)
def chord_trials(
    lit_end: NDArray[np.float64], dark_end: NDArray[np.float64], steps: NDArray[np.float64]
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Find the chords still being located and their next trial points.

    Parameters
    ----------
    lit_end : (n, 2, 2) ndarray of float64
        The lit end of the bracket on each of the chord's two edges.
    dark_end : (n, 2, 2) ndarray of float64
        The dark end of each bracket.
    steps : (n,) ndarray of float64
        Bisection steps each chord has to go.

    Returns
    -------
    trying : (m,) ndarray of int64
        The chords with ``steps > 0``.
    points : (m * 2 * BISECTION_POINTS, 2) ndarray of float64
        ``BISECTION_POINTS`` points evenly inside the bracket of each of their two edges.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])
    >>> lit = np.array([[True, False, False]])  # corner 0 lit, the others dark
    >>> apex, apex_lit, lit_end, dark_end = start_chords(corners, lit, np.zeros((1, 3), bool),
    ...     np.array([False]))
    >>> trying, points = chord_trials(lit_end, dark_end, np.array([2.0]))
    >>> trying, points[:3]
    (array([0]), array([[0.25, 0.  ],
           [0.5 , 0.  ],
           [0.75, 0.  ]]))
    """
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
    """Narrow the brackets of chords in place from the flags of their trial points.

    Parameters
    ----------
    lit_end : (n, 2, 2) ndarray of float64
        The lit end of the bracket on each of the chord's two edges.
    dark_end : (n, 2, 2) ndarray of float64
        The dark end of each bracket.
    steps : (n,) ndarray of float64
        Bisection steps to go; lowered by ``BITS_PER_ROUND``.
    trying : (m,) ndarray of int64
        The chords tried (:func:`chord_trials`).
    lit : (m * 2 * BISECTION_POINTS,) ndarray of bool
        Flags of their trial points.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])
    >>> lit = np.array([[True, False, False]])  # corner 0 lit, the others dark
    >>> apex, apex_lit, lit_end, dark_end = start_chords(corners, lit, np.zeros((1, 3), bool),
    ...     np.array([False]))
    >>> steps = np.array([2.0])
    >>> trying, points = chord_trials(lit_end, dark_end, steps)
    >>> chord_update(lit_end, dark_end, steps, trying, points.sum(axis=1) < 0.4)  # lit below w1 + w2 = 0.4
    >>> lit_end[0], dark_end[0], steps
    (array([[0.25, 0.  ],
           [0.  , 0.25]]), array([[0.5, 0. ],
           [0. , 0.5]]), array([0.]))
    """
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
def chord_leaves(
    apex: NDArray[np.float64],
    apex_lit: NDArray[np.bool_],
    lit_end: NDArray[np.float64],
    dark_end: NDArray[np.float64],
) -> tuple:
    """Make each chord a leaf: a line through the middles of its two brackets, and its band.

    The line is positive on the lit side (one line each; lit mask 0b10) and the band is the wider
    bracket's length. With both crossings at the apex, the leaf is uniform, of the other corners' state
    (no line).

    Parameters
    ----------
    apex : (n, 2) ndarray of float64
        The lone corner of each chord's node.
    apex_lit : (n,) ndarray of bool
        Its flag.
    lit_end : (n, 2, 2) ndarray of float64
        The lit end of the bracket on each of the chord's two edges.
    dark_end : (n, 2, 2) ndarray of float64
        The dark end of each bracket.

    Returns
    -------
    lines : (n, MAX_LINES, 3) ndarray of float64
        The chord's line in row 0.
    n_lines : (n,) ndarray of int64
        1, or 0 for a uniform leaf.
    mask : (n,) ndarray of uint64
        Lit cells.
    band : (n,) ndarray of float64
        Bracket width [side coordinates].

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])
    >>> lit = np.array([[True, False, False]])  # corner 0 lit, the others dark
    >>> apex, apex_lit, lit_end, dark_end = start_chords(corners, lit, np.zeros((1, 3), bool),
    ...     np.array([False]))
    >>> lines, n_lines, mask, band = chord_leaves(apex, apex_lit, lit_end, dark_end)
    >>> lines[0, 0] / lines[0, 0, 0], n_lines, mask, band  # w1 + w2 = 0.5, lit below it
    (array([ 1. ,  1. , -0.5]), array([1]), array([2], dtype=uint64), array([1.]))
    """
    n = apex.shape[0]
    lines = np.zeros((n, MAX_LINES, 3))
    n_lines = np.ones(n, dtype=np.int64)
    mask = np.full(n, 2, dtype=np.uint64)
    band = np.zeros(n)
    for k in range(n):
        p = (lit_end[k, 0] + dark_end[k, 0]) / 2
        q = (lit_end[k, 1] + dark_end[k, 1]) / 2
        a, b = -(q[1] - p[1]), q[0] - p[0]
        c = -(a * p[0] + b * p[1])
        if abs(a) + abs(b) <= 1e-12:
            n_lines[k] = 0
            mask[k] = 0 if apex_lit[k] else 1
            continue
        if (a * apex[k, 0] + b * apex[k, 1] + c > 0) != apex_lit[k]:
            a, b, c = -a, -b, -c
        lines[k, 0, 0], lines[k, 0, 1], lines[k, 0, 2] = a, b, c
        for e in range(2):
            d = dark_end[k, e] - lit_end[k, e]
            band[k] = max(band[k], np.sqrt(d[0] * d[0] + d[1] * d[1]))
    return lines, n_lines, mask, band


@numba.njit(cache=True, nogil=True)
def chord_checks(
    apex: NDArray[np.float64],
    apex_lit: NDArray[np.bool_],
    lit_end: NDArray[np.float64],
    dark_end: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Place the two check points of each located chord.

    One point lies on its lit side and one on its dark side, ``CHECK_BANDS`` bands off the middle of the
    chord.

    Parameters
    ----------
    apex : (n, 2) ndarray of float64
        The lone corner of each chord's node.
    apex_lit : (n,) ndarray of bool
        Its flag.
    lit_end : (n, 2, 2) ndarray of float64
        The lit end of the bracket on each of the chord's two edges.
    dark_end : (n, 2, 2) ndarray of float64
        The dark end of each bracket.

    Returns
    -------
    points : (n, 2, 2) ndarray of float64
        The lit-side and dark-side points.
    needed : (n,) ndarray of bool
        False where there is no line to check (both crossings at the apex).

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[[0.0, 0], [1, 0], [0, 1]]])
    >>> lit = np.array([[True, False, False]])  # corner 0 lit, the others dark
    >>> apex, apex_lit, lit_end, dark_end = start_chords(corners, lit, np.zeros((1, 3), bool),
    ...     np.array([False]))
    >>> points, needed = chord_checks(apex, apex_lit, lit_end, dark_end)
    >>> points.shape, needed
    ((1, 2, 2), array([ True]))
    """
    n = apex.shape[0]
    points = np.zeros((n, 2, 2))
    needed = np.ones(n, dtype=np.bool_)
    lines, n_lines, _, band = chord_leaves(apex, apex_lit, lit_end, dark_end)
    for k in range(n):
        if n_lines[k] == 0:
            needed[k] = False
            continue
        a, b = lines[k, 0, 0], lines[k, 0, 1]
        norm = np.sqrt(a * a + b * b)
        mx = ((lit_end[k, 0, 0] + dark_end[k, 0, 0]) + (lit_end[k, 1, 0] + dark_end[k, 1, 0])) / 4
        my = ((lit_end[k, 0, 1] + dark_end[k, 0, 1]) + (lit_end[k, 1, 1] + dark_end[k, 1, 1])) / 4
        reach = max(CHECK_BANDS * band[k], 1e-9) / norm
        points[k, 0, 0], points[k, 0, 1] = mx + reach * a, my + reach * b
        points[k, 1, 0], points[k, 1, 1] = mx - reach * a, my - reach * b
    return points, needed


@numba.njit(cache=True, nogil=True)
def pattern_of(lines: NDArray[np.float64], count: int, x: float, y: float) -> int:
    """Find the sign pattern of a point on some lines.

    Parameters
    ----------
    lines : (k, 3) ndarray of float64
        Lines ``(a, b, c)``.
    count : int
        How many of ``lines`` to use.
    x, y : float
        The point.

    Returns
    -------
    int
        Bit ``j`` set where line ``j`` is positive; -1 where the point lies on a line (to round-off).

    Examples
    --------
    >>> import numpy as np
    >>> lines = np.array([[1.0, 0, -0.5], [0, 1.0, -0.25]])
    >>> pattern_of(lines, 2, 0.6, 0.1), pattern_of(lines, 2, 0.6, 0.3), pattern_of(lines, 1, 0.5, 0.2)
    (1, 3, -1)
    """
    p = 0
    for j in range(count):
        value = lines[j, 0] * x + lines[j, 1] * y + lines[j, 2]
        if abs(value) <= 1e-12 * (abs(lines[j, 0]) + abs(lines[j, 1]) + abs(lines[j, 2])):
            return -1
        if value > 0.0:
            p |= 1 << j
    return p


@numba.njit(cache=True, nogil=True)
def leaf_moments(
    root: NDArray[np.int64],
    corners: NDArray[np.float64],
    lines: NDArray[np.float64],
    n_lines: NDArray[np.int64],
    mask: NDArray[np.uint64],
    n_roots: int,
) -> NDArray[np.float64]:
    """Sum the lit area and its first moments of each side over the lit cells of its leaves.

    Parameters
    ----------
    root : (m,) ndarray of int64
        Side (root) index of each leaf.
    corners : (m, 3, 2) ndarray of float64
        Each leaf's node, in side coordinates.
    lines : (m, MAX_LINES, 3) ndarray of float64
        Lines cutting each leaf.
    n_lines : (m,) ndarray of int64
        How many lines each leaf has.
    mask : (m,) ndarray of uint64
        Lit cells of each leaf, by sign pattern.
    n_roots : int
        Number of sides.

    Returns
    -------
    (n_roots, 3) ndarray of float64
        ``(a, a w1, a w2)`` in side coordinates (the whole side has area 1/2).

    Examples
    --------
    Called by :meth:`~sunwind.geometry.rays.quadtree.Leaves.moments`:

    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.quadtree import Caster, Segments, resolve_sides
    >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
    >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
    ...     np.zeros(2, np.int8), 0, none, 1e-2)
    >>> leaves.moments()[:, 0].round(4)
    array([0.0501, 0.2035])
    """
    moments = np.zeros((n_roots, 3))
    scratch = np.empty((2, 3 + MAX_LINES, 2))
    oriented = np.empty((MAX_LINES, 3))
    part = np.empty(3)
    for k in range(root.shape[0]):
        count = n_lines[k]
        for p in range(2**count):
            if (mask[k] >> np.uint64(p)) & np.uint64(1) == np.uint64(0):
                continue
            for j in range(count):
                s = 1.0 if (p >> j) & 1 else -1.0
                for c in range(3):
                    oriented[j, c] = s * lines[k, j, c]
            clip_moments(corners[k], oriented, count, scratch, part)
            for c in range(3):
                moments[root[k], c] += part[c]
    return moments


@numba.njit(cache=True, nogil=True)
def leaf_states(
    start: NDArray[np.int64],
    corners: NDArray[np.float64],
    lines: NDArray[np.float64],
    n_lines: NDArray[np.int64],
    mask: NDArray[np.uint64],
    band: NDArray[np.float64],
    query_root: NDArray[np.int64],
    query_point: NDArray[np.float64],
) -> NDArray[np.int8]:
    """Say what the leaves make of query points: ``LIT``, ``DARK`` or ``EITHER``.

    ``EITHER`` is on a line or within a chord's band of it, or in no leaf.

    Parameters
    ----------
    start : (k + 1,) ndarray of int64
        The leaves of root ``r`` are rows ``start[r]:start[r + 1]``.
    corners : (m, 3, 2) ndarray of float64
        Each leaf's node.
    lines : (m, MAX_LINES, 3) ndarray of float64
        Lines cutting each leaf.
    n_lines : (m,) ndarray of int64
        How many lines each leaf has.
    mask : (m,) ndarray of uint64
        Lit cells of each leaf.
    band : (m,) ndarray of float64
        Each leaf's chord band.
    query_root : (q,) ndarray of int64
        Root of each query point.
    query_point : (q, 2) ndarray of float64
        The points, in side coordinates.

    Returns
    -------
    (q,) ndarray of int8
        ``LIT``, ``DARK`` or ``EITHER`` for each point.

    Examples
    --------
    Called by :meth:`~sunwind.geometry.rays.quadtree.Leaves.states`:

    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.quadtree import Caster, Segments, resolve_sides
    >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
    >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
    ...     np.zeros(2, np.int8), 0, none, 1e-2)
    >>> leaves.states(np.array([0, 0]), np.array([[0.1, 0.1], [0.1, 0.8]])).tolist() == [DARK, LIT]
    True
    """
    out = np.full(query_root.shape[0], EITHER, dtype=np.int8)
    for q in range(query_root.shape[0]):
        x, y = query_point[q, 0], query_point[q, 1]
        r = query_root[q]
        for k in range(start[r], start[r + 1]):
            if not _holds(corners[k], x, y):
                continue
            p = pattern_of(lines[k], n_lines[k], x, y)
            for j in range(n_lines[k]):
                norm = np.sqrt(lines[k, j, 0] ** 2 + lines[k, j, 1] ** 2)
                if abs(lines[k, j, 0] * x + lines[k, j, 1] * y + lines[k, j, 2]) <= band[k] * norm:
                    p = -1
            if p >= 0:
                out[q] = LIT if (mask[k] >> np.uint64(p)) & np.uint64(1) else DARK
            break
    return out


@numba.njit(cache=True, nogil=True)
def _holds(corners: NDArray[np.float64], x: float, y: float) -> bool:
    """Whether point (x, y) lies in triangle ``corners`` (boundary included, to round-off)."""
    positive = negative = False
    for i in range(3):
        a, b = corners[i], corners[(i + 1) % 3]
        value = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])
        positive |= value > 1e-15
        negative |= value < -1e-15
    return not (positive and negative)
