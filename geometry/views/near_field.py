"""View factors between sides that meet at a concave edge, integrated instead of sampled.

Sampling noise is largest, relative to the value, between edge-adjacent sides that meet at a concave
edge. There ``F_ij`` is integrated, unoccluded: Lambert's contour formula for the view factor from a
point to the neighbour triangle, over the emitting triangle with a tensor Gauss-Legendre rule graded
geometrically toward the shared edge and its ends (relative error ~1e-6). The row keeps summing to one
by a ratio estimator: the rest of the row (other sides, escape, blind) is rescaled by ``(1 -
integrated) / (1 - sampled)`` of the near entries (:func:`with_near_field`).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.spacecraft import Spacecraft

#: Near-field rule: Gauss-Legendre of ``NEAR_ORDER`` points on intervals graded by ``NEAR_RATIO``:
#: ``NEAR_LEVELS_EDGE + 1`` intervals from the shared edge across the triangle, ``NEAR_LEVELS_ENDS + 1``
#: from each end of the edge to its middle; 750 points per pair, relative error ~1e-6.
NEAR_ORDER, NEAR_RATIO, NEAR_LEVELS_EDGE, NEAR_LEVELS_ENDS = 5, 0.25, 4, 2


#: Height of a neighbour's centroid above a side's plane, as a share of the side's size
#: ``sqrt(area)``, beyond which the edge counts as concave (below it the pair is coplanar: F = 0).
CONCAVE_TOLERANCE = 1e-7


def concave_pairs(craft: Spacecraft) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Find the edge-adjacent sides that each have the other's centroid in front of their plane.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    a : (k,) ndarray of int64
        The first side of each pair.
    b : (k,) ndarray of int64
        The second, ``a < b``.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> corners = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> fold = MeshData(corners, [[0, 1, 2], [0, 3, 1]], [0, 0], ["fold"], [-1, -1])  # a floor and a wall
    >>> craft = build_spacecraft(fold, two_sided=["fold"],
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> concave_pairs(craft)  # the floor's and the wall's fronts face each other
    (array([0]), array([1]))
    """
    a, b = craft.side_neighbours
    centroid, normal, size = craft.side_centroids, craft.side_normals, np.sqrt(craft.side_areas)
    gap = centroid[b] - centroid[a]
    above_a = np.einsum("nd,nd->n", gap, normal[a]) > CONCAVE_TOLERANCE * size[a]
    above_b = np.einsum("nd,nd->n", -gap, normal[b]) > CONCAVE_TOLERANCE * size[b]
    keep = above_a & above_b
    return a[keep], b[keep]


@lru_cache(maxsize=1)
def _near_rule() -> tuple[NDArray[np.float64], ...]:
    """Nodes and weights ``(u, wu, v, wv)`` on [0, 1] of the near-field rule: ``u`` graded toward 0
    (the shared edge), ``v`` toward both 0 and 1 (its ends)."""
    x, w = np.polynomial.legendre.leggauss(NEAR_ORDER)
    x, w = (x + 1) / 2, w / 2

    def graded(levels: int, length: float) -> tuple[NDArray, NDArray]:
        breaks = np.r_[0.0, NEAR_RATIO ** np.arange(levels, -1, -1.0)] * length
        lo, hi = breaks[:-1, None], breaks[1:, None]
        return (lo + (hi - lo) * x).ravel(), ((hi - lo) * w).ravel()

    u, wu = graded(NEAR_LEVELS_EDGE, 1.0)
    half, w_half = graded(NEAR_LEVELS_ENDS, 0.5)
    return u, wu, np.r_[half, 1 - half[::-1]], np.r_[w_half, w_half[::-1]]


def edge_pair_view_factors(
    emitters: NDArray[np.float64], normals: NDArray[np.float64], receivers: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Integrate the unoccluded view factor from each emitting triangle to its receiver, in front of it.

    Parameters
    ----------
    emitters : (n, 3, 3) ndarray of float64
        Corners ``(A, B, C)`` [m], ``AB`` the edge shared with the receiver (the rule is graded toward it).
    normals : (n, 3) ndarray of float64
        Unit normal of each emitter's side, toward the receiver.
    receivers : (n, 3, 3) ndarray of float64
        Receiver corners [m].

    Returns
    -------
    (n,) ndarray of float64
        ``F`` from each emitter to its receiver.

    Examples
    --------
    >>> import numpy as np
    >>> floor = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    >>> wall = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 0, 1]]])
    >>> edge_pair_view_factors(floor, np.array([[0.0, 0, 1]]), wall).round(6)
    array([0.211325])
    """
    u, wu, v, wv = _near_rule()
    out = np.empty(len(emitters))

    def work(lo: int, hi: int) -> None:
        out[lo:hi] = _edge_pair_kernel(emitters[lo:hi], normals[lo:hi], receivers[lo:hi], u, wu, v, wv)

    map_ranges(work, len(emitters), 256)
    return out


@numba.njit(cache=True, nogil=True)
def _point_view_factor(
    p0: float, p1: float, p2: float, n: NDArray[np.float64], corners: NDArray[np.float64]
) -> float:
    """View factor from a differential area at ``p`` [m] with unit normal ``n`` to a triangle in front
    of it, by Lambert's contour formula ``F = |sum_k gamma_k n . g_k| / (2 pi)``, ``g_k`` the unit
    vector along ``R_k x R_k+1`` and ``gamma_k`` the angle between ``R_k`` and ``R_k+1``
    (``R_k = corner_k - p``)."""
    total = 0.0
    for k in range(3):
        k1 = (k + 1) % 3
        x0, y0, z0 = corners[k, 0] - p0, corners[k, 1] - p1, corners[k, 2] - p2
        x1, y1, z1 = corners[k1, 0] - p0, corners[k1, 1] - p1, corners[k1, 2] - p2
        cx, cy, cz = y0 * z1 - z0 * y1, z0 * x1 - x0 * z1, x0 * y1 - y0 * x1
        length = math.sqrt(cx * cx + cy * cy + cz * cz)
        if length > 0.0:
            gamma = math.atan2(length, x0 * x1 + y0 * y1 + z0 * z1)
            total += gamma * (n[0] * cx + n[1] * cy + n[2] * cz) / length
    return abs(total) / (2 * math.pi)


@numba.njit(cache=True, nogil=True)
def _edge_pair_kernel(
    emitters: NDArray[np.float64],
    normals: NDArray[np.float64],
    receivers: NDArray[np.float64],
    u: NDArray[np.float64],
    wu: NDArray[np.float64],
    v: NDArray[np.float64],
    wv: NDArray[np.float64],
) -> NDArray[np.float64]:
    """:func:`edge_pair_view_factors` on ``p(u, v) = (1 - u)(A + v (B - A)) + u C``, whose area element is
    ``2 area (1 - u) du dv``: ``F = 2 integral (1 - u) F_dA(p) du dv``."""
    out = np.empty(emitters.shape[0])
    for k in range(emitters.shape[0]):
        e = emitters[k]
        total = 0.0
        for i in range(u.shape[0]):
            inner = 0.0
            for j in range(v.shape[0]):
                a, b, c = (1 - u[i]) * (1 - v[j]), (1 - u[i]) * v[j], u[i]  # weights on A, B, C
                p0 = a * e[0, 0] + b * e[1, 0] + c * e[2, 0]
                p1 = a * e[0, 1] + b * e[1, 1] + c * e[2, 1]
                p2 = a * e[0, 2] + b * e[1, 2] + c * e[2, 2]
                inner += wv[j] * _point_view_factor(p0, p1, p2, normals[k], receivers[k])
            total += wu[i] * (1 - u[i]) * inner
        out[k] = 2 * total
    return out


def _oriented_emitters(craft: Spacecraft, a: NDArray[np.int64], b: NDArray[np.int64]) -> NDArray[np.float64]:
    """Corners of side ``a``'s facet ordered ``(A, B, C)`` with ``AB`` the edge it shares with ``b``'s."""
    faces_a, faces_b = craft.faces[craft.side_facet[a]], craft.faces[craft.side_facet[b]]
    shared = (faces_a[:, :, None] == faces_b[:, None, :]).any(axis=2)
    apex = np.argmin(shared, axis=1)  # the corner not on the shared edge
    order = (apex[:, None] + np.array([1, 2, 0])) % 3
    return craft.triangles[craft.side_facet[a][:, None], order]


def with_near_field(
    craft: Spacecraft, matrix: scipy.sparse.csr_matrix
) -> tuple[scipy.sparse.csr_matrix, NDArray[np.float64]]:
    """Replace the concave edge-neighbour entries of sampled view factors by integrated ones.

    Row i's near entries (sampled sum ``s_i``) get the integrated values (sum ``a_i``, scaled to 1 if
    it exceeds 1); the rest of the row is multiplied by ``(1 - a_i) / (1 - s_i)``, so the row still
    sums to one. A row whose rays all met near neighbours (``s_i = 1``) keeps its sampled values.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    matrix : (n_sides, n_sides) scipy.sparse.csr_matrix
        Sampled view factors.

    Returns
    -------
    matrix : (n_sides, n_sides) scipy.sparse.csr_matrix
        The factors with the near entries integrated.
    scale : (n_sides,) ndarray of float64
        The factor escape and blind shares are to be multiplied by.

    Examples
    --------
    >>> from sunwind.geometry.views.view_factors import compute_view_factors
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> corners = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    >>> fold = MeshData(corners, [[0, 1, 2], [0, 3, 1]], [0, 0], ["fold"], [-1, -1])  # a floor and a wall
    >>> craft = build_spacecraft(fold, two_sided=["fold"],
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> sampled = compute_view_factors(craft, 64, near_field=False).matrix
    >>> matrix, scale = with_near_field(craft, sampled)
    >>> round(float(sampled[0, 1]), 3), round(float(matrix[0, 1]), 4), scale.round(4)
    (0.266, 0.2113, array([1.0739, 0.9524, 1.    , 1.    ]))
    """
    n = craft.n_sides
    a, b = concave_pairs(craft)
    if not len(a):
        return matrix, np.ones(n)
    emitters, receivers = _oriented_emitters(craft, a, b), craft.triangles[craft.side_facet[b]]
    forward = edge_pair_view_factors(emitters, craft.side_normals[a], receivers)
    rows, cols = np.r_[a, b], np.r_[b, a]
    exact = np.r_[forward, forward * craft.side_areas[a] / craft.side_areas[b]]  # reciprocity
    sampled = np.asarray(matrix[rows, cols]).ravel()
    s = np.bincount(rows, sampled, minlength=n)
    total = np.bincount(rows, exact, minlength=n)
    exact = exact / np.maximum(total, 1)[rows]
    fixed = s < 1 - 1e-9  # s is a multiple of 1 / rays: below 1 - 1 / rays unless every ray met a neighbour
    scale = np.ones(n)
    scale[fixed] = (1 - np.minimum(total, 1)[fixed]) / (1 - s[fixed])
    keep = fixed[rows]
    change = (exact - scale[rows] * sampled)[keep]  # near entries: from their scaled sampled value to exact
    near = scipy.sparse.csr_matrix((change, (rows[keep], cols[keep])), shape=(n, n))
    return (scipy.sparse.diags(scale) @ matrix + near).tocsr(), scale
