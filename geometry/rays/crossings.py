"""Where facets pass through each other: lines along which a shadow can begin that no edge casts.

CAD assemblies overlap: a yoke through a wall, a blanket laid through the bracket it covers, two
shells of one part sunk into each other. Where facet ``g`` passes through the plane of facet ``f``
inside it, the part of ``g`` in front of ``f`` shades ``f`` from the line where they cross: a shadow
edge on ``f`` that is the projection of no silhouette edge. The lines are found once per model, for
every pair of facets that cross (a box tree of the facets finds the candidates), and handed to the
shadow-edge pass as outline segments on both facets' sides (:mod:`.shadow_edges`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.overlaps import box_pairs
from sunwind.geometry.rays.edge_kernels import clip_moments
from sunwind.geometry.rays.mesh_edges import mesh_edges
from sunwind.geometry.spacecraft import Spacecraft

#: Heights within this share of the model's half-size of a facet's plane count as on it: a facet whose edge
#: lies on another (to the precision of the file and of the rays' origin offset) touches it along that
#: line, where its shadow begins.
_ON_PLANE = 1e-6
#: Coplanar facets sharing less than this share of a side's area (in its coordinates, where the whole
#: side has 1/2) only touch: neighbours whose copies of a shared edge an exporter moved apart overlap
#: in slivers some 1e-7 wide; ignoring an overlap this small changes a side's lit area by 2e-5 at most.
_SHARED_AREA = 1e-5
#: Crossing lines shorter than this share of the model's half-size are dropped (touching corners).
_SHORTEST = 1e-7


@dataclass(frozen=True, eq=False)
class Crossings:
    """The lines where facets cross, in each facet's own coordinates.

    Attributes
    ----------
    start : (n_facets + 1,) int64
        Facet ``f``'s lines are rows ``start[f]:start[f + 1]``.
    segments : (n, 2, 2) float64
        End points of each line as ``(w1, w2)`` on its facet's triangle ``A, B, C``:
        ``P = A + w1 (B - A) + w2 (C - A)``.
    other : (n,) int64
        The facet that crosses it there.
    cover_start : (n_facets + 1,) int64, cover : (c, 3, 2) float64
        The coplanar facets that overlap facet ``f`` and come after it in the file, as triangles in its
        coordinates: rows ``cover_start[f]:cover_start[f + 1]``. Two facets in one plane are a duplicate
        layer (an exporter's second winding, a decal, a blanket drawn on its panel); the later one is
        taken to lie on top, shading the earlier one wherever they overlap, so that a doubled surface is
        lit once. Their edges are outline segments on the covered facet too.
    open_edges : (n, 3) bool
        Which edges of ``other`` no facet wholly in front of the facet's plane continues (the facets
        across each dip behind it too, or there are none): seen from the facet, the crossing facet's
        shadow may end at such an edge, which need be no silhouette edge.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> a = box()
    >>> b = MeshData(a.vertices + 0.5, a.faces, a.face_part, ["other"], a.face_material)  # sunk into a
    >>> craft = build_spacecraft(MeshData.concatenate([a, b]),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> lines = crossings(craft)
    >>> int(lines.start[-1]), lines.segments[0], int(lines.other[0]), len(lines.cover)
    (12, array([[0. , 0.5],
           [0.5, 0.5]]), 20, 0)
    """

    start: NDArray[np.int64]
    segments: NDArray[np.float64]
    other: NDArray[np.int64]
    open_edges: NDArray[np.bool_]
    cover_start: NDArray[np.int64]
    cover: NDArray[np.float64]

    def covered(self, facets: NDArray[np.int64], points: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Test whether points of facets lie under a coplanar facet that covers them.

        Parameters
        ----------
        facets : (n,) ndarray of int64
            Facet of each point.
        points : (n, 2) ndarray of float64
            Points ``(w1, w2)`` in their facet's coordinates.

        Returns
        -------
        (n,) ndarray of bool
            True where a later coplanar facet lies on the point.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.mesh_data import MeshData
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import plate
        >>> sheet = plate(divisions=1)
        >>> craft = build_spacecraft(MeshData.concatenate([sheet, sheet]), two_sided=["plate"],
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> lines = crossings(craft)
        >>> lines.covered(np.array([0, 2]), np.array([[0.2, 0.2], [0.2, 0.2]]))  # the first copy lies under
        array([ True, False])
        """
        return _covered(self.cover_start, self.cover, facets, np.ascontiguousarray(points, dtype=np.float64))


def crossings(craft: Spacecraft) -> Crossings:
    """Find the lines where the facets of a model cross; made once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    Crossings
        The lines on each facet, and the coplanar facets that cover it.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> a = box()
    >>> b = MeshData(a.vertices + 0.5, a.faces, a.face_part, ["other"], a.face_material)  # sunk into a
    >>> craft = build_spacecraft(MeshData.concatenate([a, b]),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> lines = crossings(craft)
    >>> lines is crossings(craft), int(lines.start[-1])  # 6 facet pairs cross, a line on each facet
    (True, 12)
    """

    def make() -> Crossings:
        triangles = craft.triangles
        half = float(np.ptp(triangles.reshape(-1, 3), axis=0).max()) / 2
        corner = mesh_edges(craft).corner[craft.faces]
        near = box_pairs(triangles, _ON_PLANE * half)
        keep, ends, cover = _crossing_tests(triangles, near.first, near.second, corner, half)
        first, second, ends, cover = near.first[keep], near.second[keep], ends[keep], cover[keep]
        crossed, above = first[cover], second[cover]  # a coplanar facet covers the one before it
        shade = _shades(triangles, crossed, above)
        cover_order = np.argsort(crossed, kind="stable")
        cover_start = np.searchsorted(crossed[cover_order], np.arange(craft.n_facets + 1))
        shade = shade[cover_order]
        first, second, ends = first[~cover], second[~cover], ends[~cover]
        facet = np.concatenate([first, second, np.repeat(crossed[cover_order], 3)])
        other = np.concatenate([second, first, np.repeat(above[cover_order], 3)])
        points = _side_coordinates(triangles, np.concatenate([first, second]), np.concatenate([ends, ends]))
        edges_2d = np.stack([shade, np.roll(shade, -1, axis=1)], axis=2).reshape(-1, 2, 2)
        segments = np.concatenate([points, edges_2d])
        edges = mesh_edges(craft)
        open_edges = _open_edges(
            triangles, facet, other, edges.facet_edges, edges.start, edges.facet, _ON_PLANE * half
        )
        open_edges[2 * len(first) :] = False  # a cover's edges are outline segments as they are
        order = np.argsort(facet, kind="stable")
        start = np.searchsorted(facet[order], np.arange(craft.n_facets + 1))
        return Crossings(
            start.astype(np.int64),
            segments[order],
            other[order],
            open_edges[order],
            cover_start.astype(np.int64),
            shade,
        )

    return craft.cache.get("facet crossings", make)


def _side_coordinates(
    triangles: NDArray[np.float64], facet: NDArray[np.int64], points: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``(w1, w2)`` of ``points`` (n, 2, 3) [m] on the triangles of ``facet`` (n,), (n, 2, 2)."""
    a, b, c = (triangles[facet, i][:, None] for i in range(3))
    ab, ac, ap = b - a, c - a, points - a
    g11, g12, g22 = (ab * ab).sum(-1), (ab * ac).sum(-1), (ac * ac).sum(-1)
    r1, r2 = (ap * ab).sum(-1), (ap * ac).sum(-1)
    det = g11 * g22 - g12 * g12
    return np.stack([(g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det], axis=-1)


@numba.njit(cache=True, nogil=True)
def _open_edges(
    triangles: NDArray[np.float64],
    facet: NDArray[np.int64],
    other: NDArray[np.int64],
    facet_edges: NDArray[np.int64],
    start: NDArray[np.int64],
    edge_facet: NDArray[np.int64],
    eps: float,
) -> NDArray[np.bool_]:
    """For each crossing (``facet`` crossed by ``other``), which edges of ``other`` have no facet across
    them lying wholly (by more than ``eps``) in front of ``facet``'s plane, (n, 3): where the facet
    across dips behind the plane too, its shadow on ``facet`` may end at the edge."""
    out = np.ones((facet.shape[0], 3), dtype=np.bool_)
    for k in range(facet.shape[0]):
        f, g = facet[k], other[k]
        n, d = _plane(triangles[f])
        for e in range(3):
            edge = facet_edges[g, e]
            if edge < 0:
                continue
            for j in range(start[edge], start[edge + 1]):
                h = edge_facet[j]
                if h == g:
                    continue
                front = True
                for c in range(3):
                    front &= n @ triangles[h, c] - d > eps
                if front:
                    out[k, e] = False
    return out


@numba.njit(cache=True, nogil=True)
def _crossing_tests(
    triangles: NDArray[np.float64],
    first: NDArray[np.int64],
    second: NDArray[np.int64],
    corner: NDArray[np.int64],
    half_size: float,
) -> tuple[NDArray[np.bool_], NDArray[np.float64], NDArray[np.bool_]]:
    """Of the candidate pairs ``first``, ``second`` (boxes within reach), those that cross or that
    cover one another (coplanar and overlapping); the line where a crossing pair meets (m, 2, 3) [m];
    which pairs are covers. Pairs sharing a corner do not cross (they meet along it)."""
    count = first.shape[0]
    keep = np.zeros(count, dtype=np.bool_)
    out_ends = np.zeros((count, 2, 3))
    out_cover = np.zeros(count, dtype=np.bool_)
    ends = np.empty((2, 3))
    eps = _ON_PLANE * half_size
    shortest = _SHORTEST * half_size
    for k in range(count):
        i, j = first[k], second[k]
        shared = False
        for a in range(3):
            for b in range(3):
                shared |= corner[i, a] == corner[j, b]
        cover = _coplanar(triangles[i], triangles[j], eps)
        if cover:
            if not _overlap(triangles[i], triangles[j]):
                continue
        elif shared or not _cross(triangles[i], triangles[j], eps, ends):
            continue
        length = 0.0
        for d in range(3):
            length += (ends[1, d] - ends[0, d]) ** 2
        if not cover and length <= shortest * shortest:
            continue
        keep[k], out_cover[k] = True, cover
        out_ends[k] = ends
    return keep, out_ends, out_cover


@numba.njit(cache=True, nogil=True)
def _coplanar(t1: NDArray[np.float64], t2: NDArray[np.float64], eps: float) -> bool:
    """Whether every corner of ``t2`` lies within ``eps`` of ``t1``'s plane."""
    n, d = _plane(t1)
    for a in range(3):
        if abs(n @ t2[a] - d) > eps:
            return False
    return True


@numba.njit(cache=True, nogil=True)
def _overlap(t1: NDArray[np.float64], t2: NDArray[np.float64]) -> bool:
    """Whether coplanar triangles ``t1`` and ``t2`` share an area (not just an edge or a corner):
    ``t2`` in ``t1``'s coordinates clipped by ``t1``."""
    g = np.empty((3, 2))
    _in_coordinates(t1, t2, g)
    lines = np.empty((3, 3))
    orient = (g[1, 0] - g[0, 0]) * (g[2, 1] - g[0, 1]) - (g[1, 1] - g[0, 1]) * (g[2, 0] - g[0, 0])
    if orient == 0.0:
        return False
    s = 1.0 if orient > 0 else -1.0
    for e in range(3):
        p, q = g[e], g[(e + 1) % 3]
        lines[e, 0], lines[e, 1] = -s * (q[1] - p[1]), s * (q[0] - p[0])
        lines[e, 2] = -(lines[e, 0] * p[0] + lines[e, 1] * p[1])
    whole = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    part = np.empty(3)
    clip_moments(whole, lines, 3, np.empty((2, 6, 2)), part)
    return part[0] > _SHARED_AREA


@numba.njit(cache=True, nogil=True)
def _shades(
    triangles: NDArray[np.float64], crossed: NDArray[np.int64], above: NDArray[np.int64]
) -> NDArray[np.float64]:
    """Corners of each covering facet ``above`` in the coordinates of the facet it covers, (m, 3, 2)."""
    out = np.zeros((crossed.shape[0], 3, 2))
    for k in range(crossed.shape[0]):
        _in_coordinates(triangles[crossed[k]], triangles[above[k]], out[k])
    return out


@numba.njit(cache=True, nogil=True)
def _in_coordinates(t1: NDArray[np.float64], t2: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Write the corners of ``t2`` as ``(w1, w2)`` on ``t1`` (in its plane) into ``out`` (3, 2)."""
    ab, ac = t1[1] - t1[0], t1[2] - t1[0]
    g11, g12, g22 = ab @ ab, ab @ ac, ac @ ac
    det = g11 * g22 - g12 * g12
    for a in range(3):
        ap = t2[a] - t1[0]
        r1, r2 = ap @ ab, ap @ ac
        out[a, 0] = (g22 * r1 - g12 * r2) / det
        out[a, 1] = (g11 * r2 - g12 * r1) / det


@numba.njit(cache=True, nogil=True)
def _plane(t: NDArray[np.float64]) -> tuple[NDArray[np.float64], float]:
    """Unit normal and offset of triangle ``t``'s plane (normal zero for a degenerate one)."""
    n = np.cross(t[1] - t[0], t[2] - t[0])
    length = np.sqrt(n @ n)
    if length > 0:
        n /= length
    return n, n @ t[0]


@numba.njit(cache=True, nogil=True)
def _interval(
    t: NDArray[np.float64],
    height: NDArray[np.float64],
    origin: NDArray[np.float64],
    along: NDArray[np.float64],
) -> tuple[float, float, bool]:
    """The stretch of triangle ``t`` on the line ``origin + s along`` (the other plane, where the
    corners' ``height`` above it change sign), as parameters ``s``; False where it does not reach it."""
    lo, hi = np.inf, -np.inf
    for a in range(3):
        b = (a + 1) % 3
        if height[a] == 0.0:
            s = (t[a] - origin) @ along
            lo, hi = min(lo, s), max(hi, s)
        if (height[a] < 0.0 < height[b]) or (height[b] < 0.0 < height[a]):
            w = height[a] / (height[a] - height[b])
            s = (t[a] + w * (t[b] - t[a]) - origin) @ along
            lo, hi = min(lo, s), max(hi, s)
    return lo, hi, hi >= lo


@numba.njit(cache=True, nogil=True)
def _cross(t1: NDArray[np.float64], t2: NDArray[np.float64], eps: float, ends: NDArray[np.float64]) -> bool:
    """Write the line where triangles ``t1`` and ``t2`` cross into ``ends`` (2, 3); False where they do
    not, or lie in one plane (heights within ``eps`` count as zero)."""
    n1, d1 = _plane(t1)
    n2, d2 = _plane(t2)
    h2 = np.empty(3)
    h1 = np.empty(3)
    for a in range(3):
        h2[a] = n1 @ t2[a] - d1
        h1[a] = n2 @ t1[a] - d2
        if abs(h2[a]) <= eps:
            h2[a] = 0.0
        if abs(h1[a]) <= eps:
            h1[a] = 0.0
    if h2.min() > 0.0 or h2.max() < 0.0 or h1.min() > 0.0 or h1.max() < 0.0:
        return False
    if (h2 == 0.0).all() or (h1 == 0.0).all():
        return False  # coplanar: no line
    along = np.cross(n1, n2)
    size = np.sqrt(along @ along)
    if size < 1e-12:
        return False
    along /= size
    # a point on both planes
    origin = (d1 * np.cross(n2, along) + d2 * np.cross(along, n1)) / size
    lo1, hi1, ok1 = _interval(t1, h1, origin, along)
    lo2, hi2, ok2 = _interval(t2, h2, origin, along)
    if not (ok1 and ok2):
        return False
    lo, hi = max(lo1, lo2), min(hi1, hi2)
    if hi <= lo:
        return False
    for d in range(3):
        ends[0, d] = origin[d] + lo * along[d]
        ends[1, d] = origin[d] + hi * along[d]
    return True


@numba.njit(cache=True, nogil=True)
def _covered(
    start: NDArray[np.int64],
    cover: NDArray[np.float64],
    facets: NDArray[np.int64],
    points: NDArray[np.float64],
) -> NDArray[np.bool_]:
    out = np.zeros(facets.shape[0], dtype=np.bool_)
    for k in range(facets.shape[0]):
        f = facets[k]
        x, y = points[k, 0], points[k, 1]
        for c in range(start[f], start[f + 1]):
            positive = negative = False
            for i in range(3):
                a, b = cover[c, i], cover[c, (i + 1) % 3]
                value = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])
                positive |= value > 0.0
                negative |= value < 0.0
            if not (positive and negative):
                out[k] = True
                break
    return out
