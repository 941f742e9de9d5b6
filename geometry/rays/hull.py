"""Rays that provably meet nothing: convex hulls of the model and of its parts, and boxes of parts.

A side whose plane supports the convex hull of every vertex of the model sees open sky over its whole
open hemisphere: a ray leaving it along any ``d`` with ``n . d > 0`` moves away from that plane and
meets nothing. A side whose plane supports the hull of its own part cannot be blocked by that part,
and a ray that misses the box of every other part cannot be blocked at all. Shadow and visibility rays
that pass these tests need not be cast; their answer is known.

The hull tests allow vertices ``HULL_TOLERANCE`` (a share of the extent) in front of the plane, far
below the offset ray origins are pushed off their side (``sunwind.geometry.rays.scene.ORIGIN_OFFSET``); the
boxes
are taken in the float32 scene coordinates rays are cast in and widened by ``BOX_MARGIN``, far above
their round-off. A ray these tests clear is thus clear for Embree too.

The highest point of a point set along a side's normal is found on its hull by walking the hull's
edges uphill from the previous side's answer: on a convex polytope a vertex no neighbour rises above
is the highest, so the cost per side is a few steps on meshes whose nearby sides face alike.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.spatial import ConvexHull, QhullError

from sunwind.geometry.spacecraft import Spacecraft

#: Largest height above a side's plane, as a share of the largest extent of the model (or part), at
#: which a vertex still counts as on the plane (1e-8 m on a 10 m model).
HULL_TOLERANCE = 1e-9
#: Widening of each part's box, in scene units (the model's half-size): far above the float32 round-off
#: of scene coordinates (6e-8), so a ray that misses the widened box misses every triangle in it.
BOX_MARGIN = 1e-5
#: Most parts whose boxes are kept; a model with more is cleared by the hull of the whole model only.
MAX_PARTS = 64


@dataclass(frozen=True, eq=False)
class Clearance:
    """What can block a ray leaving each side of one model (module docstring).

    Attributes
    ----------
    open_sky : (n_sides,) bool
        The side's plane supports the hull of the model: nothing blocks it.
    own_part_clear : (n_sides,) bool
        The side's plane supports the hull of its own part: only other parts can block it.
    blockers : (n_sides, n_boxes) bool
        The boxes of other parts that reach in front of the side's plane: only these can block it.
    box_low, box_high : (n_boxes, 3) float64
        Corners of each part's box, scene coordinates, widened by ``BOX_MARGIN``.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> clear = clearance(craft)
    >>> int(clear.open_sky.sum()), int(clear.own_part_clear.sum()), clear.blockers.shape
    (32, 144, (144, 3))
    """

    open_sky: NDArray[np.bool_]
    own_part_clear: NDArray[np.bool_]
    blockers: NDArray[np.bool_]
    box_low: NDArray[np.float64]
    box_high: NDArray[np.float64]

    @property
    def arrays(self) -> tuple[NDArray, ...]:
        """The arrays in the order :func:`~sunwind.geometry.rays.clear_kernels.may_be_blocked` takes them.

        Returns
        -------
        tuple of ndarray
            ``open_sky, own_part_clear, blockers, box_low, box_high``.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> [a.shape for a in clearance(craft).arrays]
        [(144,), (144,), (144, 3), (3, 3), (3, 3)]
        """
        return self.open_sky, self.own_part_clear, self.blockers, self.box_low, self.box_high


def clearance(craft: Spacecraft) -> Clearance:
    """Find what can block a ray leaving each side of a model; made once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    Clearance
        Its hull tests and part boxes.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> clear = clearance(craft)
    >>> clear is clearance(craft), clear.blockers.sum(axis=1)[[0, 16, 48]].tolist()
    (True, [0, 1, 2])
    """
    return craft.cache.get("hull clearance", lambda: _clearance(craft))


def _clearance(craft: Spacecraft) -> Clearance:
    normals, centroids = craft.side_normals, craft.side_centroids
    open_sky = supporting_planes(*_points_and_tolerance(craft, craft.faces), normals, centroids)
    parts, side_box = np.unique(craft.facet_part[craft.side_facet], return_inverse=True)
    if len(parts) > MAX_PARTS:
        return Clearance(
            open_sky, open_sky, np.zeros((craft.n_sides, 0), bool), np.zeros((0, 3)), np.zeros((0, 3))
        )
    own = open_sky.copy()
    low, high = np.empty((len(parts), 3)), np.empty((len(parts), 3))
    for box, part in enumerate(parts):
        facets = np.flatnonzero(craft.facet_part == part)
        sides = np.flatnonzero(side_box == box)
        own[sides] |= supporting_planes(
            *_points_and_tolerance(craft, craft.faces[facets]), normals[sides], centroids[sides]
        )
        corners = craft.scene.to_scene(craft.triangles[facets]).reshape(-1, 3).astype(np.float64)
        low[box], high[box] = corners.min(axis=0) - BOX_MARGIN, corners.max(axis=0) + BOX_MARGIN
    anchors = craft.scene.to_scene(centroids).astype(np.float64)
    blockers = _boxes_in_front(normals, anchors, low, high)
    blockers[np.arange(craft.n_sides), side_box.reshape(-1)] = False
    return Clearance(open_sky, own, blockers, low, high)


@numba.njit(cache=True, nogil=True)
def _boxes_in_front(
    normals: NDArray[np.float64],
    anchors: NDArray[np.float64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
) -> NDArray[np.bool_]:
    """Whether any point of each box lies in front of each plane (normal, anchor), (n_planes, n_boxes)."""
    out = np.empty((normals.shape[0], low.shape[0]), dtype=np.bool_)
    for i in range(normals.shape[0]):
        for box in range(low.shape[0]):
            height = 0.0  # the box corner highest along the normal
            for d in range(3):
                height += normals[i, d] * (
                    (high[box, d] if normals[i, d] > 0 else low[box, d]) - anchors[i, d]
                )
            out[i, box] = height > 0.0
    return out


def _points_and_tolerance(craft: Spacecraft, faces: NDArray[np.int64]) -> tuple[NDArray[np.float64], float]:
    """The vertices of ``faces`` [m] and the hull tolerance for them [m]."""
    points = craft.vertices[np.unique(faces)]
    return points, HULL_TOLERANCE * float(np.ptp(points, axis=0).max())


def supporting_planes(
    points: NDArray[np.float64],
    tolerance: float,
    normals: NDArray[np.float64],
    anchors: NDArray[np.float64],
) -> NDArray[np.bool_]:
    """Test whether no point lies more than ``tolerance`` in front of each plane.

    Parameters
    ----------
    points : (n_points, 3) ndarray of float64
        The point set [m], at least three points not on one line.
    tolerance : float
        Height [m] above a plane that still counts as on it.
    normals : (n_planes, 3) ndarray of float64
        Unit normal of each plane, pointing to its front.
    anchors : (n_planes, 3) ndarray of float64
        A point of each plane [m].

    Returns
    -------
    (n_planes,) ndarray of bool
        True where the plane supports the points' convex hull.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.meshes import box
    >>> normals = np.array([[1.0, 0, 0], [1.0, 0, 0]])
    >>> supporting_planes(box().vertices, 1e-9, normals, np.array([[0.5, 0, 0], [0.0, 0, 0]]))
    array([ True, False])
    """
    try:
        hull = ConvexHull(points)
        corners = np.unique(hull.simplices)
        local = np.searchsorted(corners, hull.simplices)
        edges = np.concatenate([local[:, [0, 1]], local[:, [1, 2]], local[:, [2, 0]]])
    except QhullError:  # a flat point set (or one triangle): the convex polygon in its plane
        centred = points - points.mean(axis=0)
        plane = np.linalg.svd(centred, full_matrices=False)[2][:2]
        corners = ConvexHull(centred @ plane.T).vertices  # in order around the polygon
        ring = np.arange(len(corners))
        edges = np.column_stack([ring, np.roll(ring, -1)])
    graph = scipy.sparse.csr_matrix(
        (np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(len(corners), len(corners))
    )
    graph = (graph + graph.T).tocsr()
    heights = _highest(np.ascontiguousarray(points[corners]), graph.indptr, graph.indices, normals)
    return heights - np.einsum("ij,ij->i", normals, anchors) <= tolerance


@numba.njit(cache=True, nogil=True)
def _highest(
    corners: NDArray[np.float64],
    indptr: NDArray[np.int32],
    indices: NDArray[np.int32],
    normals: NDArray[np.float64],
) -> NDArray[np.float64]:
    """``max_v n . v`` over the hull's ``corners`` for each normal, by an uphill walk on the hull's
    edges (``indptr``, ``indices``: CSR adjacency) started where the previous walk ended."""
    out = np.empty(normals.shape[0])
    at = 0
    for i in range(normals.shape[0]):
        n0, n1, n2 = normals[i, 0], normals[i, 1], normals[i, 2]
        best = n0 * corners[at, 0] + n1 * corners[at, 1] + n2 * corners[at, 2]
        moved = True
        while moved:
            moved = False
            for k in range(indptr[at], indptr[at + 1]):
                w = indices[k]
                height = n0 * corners[w, 0] + n1 * corners[w, 1] + n2 * corners[w, 2]
                if height > best:
                    best, at, moved = height, w, True
                    break
        out[i] = best
    return out
