"""The model's edges found by position, not by vertex number: what the shadow pass takes from topology.

CAD exports write a surface as many pieces: each face with its own copies of its vertices (split
normals), sheets of either winding, parts that touch without sharing a vertex. Two facets are
neighbours here when their corners coincide to ``WELD_SHARE`` of the model's half-size, whatever their
vertex numbers, winding or part; an edge may have one facet (a sheet's border, an unwelded seam), two,
or more (a fin on a wall, a duplicate layer). Each facet's incidence on an edge records the way it runs
the edge, so that the silhouette test (:func:`sunwind.geometry.rays.outline.outline`) needs neither a
consistent winding nor closed bodies.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from sunwind.geometry.spacecraft import Spacecraft

#: Corners closer than this share of the model's half-size are one corner (the shadow rays' origin
#: offset is the same share: nothing finer is resolved by them).
WELD_SHARE = 1e-6


@dataclass(frozen=True, eq=False)
class MeshEdges:
    """Edges and corners of a model by position.

    Attributes
    ----------
    corner : (n_vertices,) int64
        The welded corner each vertex is, numbered from 0 to ``n_corners - 1``.
    n_corners : int
        Number of welded corners.
    ends : (n_edges, 2) int64
        A vertex at each end of each edge (end 0 has the smaller corner number).
    facet_edges : (n_facets, 3) int64
        The edge of each facet's sides ``(v0, v1)``, ``(v1, v2)``, ``(v2, v0)``; -1 where the facet's two
        corners are one (a sliver shorter than the weld).
    start : (n_edges + 1,) int64
        The facets on edge ``e`` are ``facet[start[e]:start[e + 1]]``.
    facet : (n_incidences,) int64
        Facets on each edge, grouped by edge.
    way : (n_incidences,) int8
        +1 where the facet runs its edge from end 0 to end 1 (right-hand rule of its normal), else -1.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> edges = mesh_edges(craft)
    >>> edges.n_corners, edges.n_edges, edges.facet_edges.shape
    (8, 18, (12, 3))
    """

    corner: NDArray[np.int64]
    n_corners: int
    ends: NDArray[np.int64]
    facet_edges: NDArray[np.int64]
    start: NDArray[np.int64]
    facet: NDArray[np.int64]
    way: NDArray[np.int8]

    @property
    def n_edges(self) -> int:
        """Number of edges.

        Returns
        -------
        int
            ``len(ends)``.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box
        >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> mesh_edges(craft).n_edges  # 12 of the cube and a diagonal on each of its 6 faces
        18
        """
        return len(self.ends)

    def edge_facet_count(self) -> NDArray[np.int64]:
        """Count the facets on each edge.

        Returns
        -------
        (n_edges,) ndarray of int64
            1 for a border, 2 for an edge between two facets, more for a fin or a duplicate layer.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box
        >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> set(mesh_edges(craft).edge_facet_count().tolist())
        {2}
        """
        return np.diff(self.start)


def mesh_edges(craft: Spacecraft) -> MeshEdges:
    """Find the edges and corners of a model by position; made once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    MeshEdges
        Its welded corners and edges.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> edges = mesh_edges(craft)
    >>> edges is mesh_edges(craft), edges.way[:4].tolist()
    (True, [1, -1, -1, 1])
    """
    return craft.cache.get("mesh edges", lambda: _build(craft.vertices, craft.faces))


def welded_corners(vertices: NDArray[np.float64], share: float = WELD_SHARE) -> NDArray[np.int64]:
    """Number the vertices so that vertices that coincide get one number.

    Vertices closer than ``share`` of the half-size of their bounding box are one corner (chains of close
    vertices join); corners are numbered 0, 1, ... in order of their first vertex.

    Parameters
    ----------
    vertices : (n, 3) ndarray of float64
        Vertex positions [m].
    share : float, optional
        Weld distance as a share of the half-size.

    Returns
    -------
    (n,) ndarray of int64
        Corner number of each vertex.

    Examples
    --------
    >>> import numpy as np
    >>> welded_corners(np.array([[0.0, 0, 0], [1, 0, 0], [1, 1e-9, 0]]))
    array([0, 1, 1])
    """
    if not len(vertices):
        return np.zeros(0, dtype=np.int64)
    half = float(np.ptp(vertices, axis=0).max()) / 2
    pairs = cKDTree(vertices).query_pairs(share * half, output_type="ndarray") if half > 0 else None
    n = len(vertices)
    if pairs is None:
        return np.zeros(n, dtype=np.int64)
    if not len(pairs):
        return np.arange(n, dtype=np.int64)
    graph = scipy.sparse.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    label = connected_components(graph, directed=False)[1]
    # renumber by first vertex so that the numbering does not depend on the component search
    first = np.full(label.max() + 1, n)
    np.minimum.at(first, label, np.arange(n))
    _, renumbered = np.unique(first[label], return_inverse=True)
    return renumbered.astype(np.int64)


def _build(vertices: NDArray[np.float64], faces: NDArray[np.int64]) -> MeshEdges:
    corner = welded_corners(vertices)
    n_corners = int(corner.max()) + 1 if len(corner) else 0
    run = corner[faces][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)  # each facet side as (from, to)
    vertex_run = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    real = run[:, 0] != run[:, 1]
    low, high = run.min(axis=1), run.max(axis=1)
    keys = low * n_corners + high
    unique, first, inverse = np.unique(keys[real], return_index=True, return_inverse=True)
    facet_edges = np.full(len(run), -1, dtype=np.int64)
    facet_edges[real] = inverse
    incidence = np.flatnonzero(real)
    order = np.argsort(inverse, kind="stable")
    start = np.searchsorted(inverse[order], np.arange(len(unique) + 1))
    facet = incidence[order] // 3
    way = np.where(run[incidence[order], 0] == low[incidence[order]], 1, -1).astype(np.int8)
    # an end vertex of each edge, end 0 at the smaller corner number
    at = incidence[first]
    forward = run[at, 0] == low[at]
    ends = np.where(forward[:, None], vertex_run[at], vertex_run[at][:, ::-1])
    return MeshEdges(corner, n_corners, ends, facet_edges.reshape(-1, 3), start.astype(np.int64), facet, way)


def side_corners(craft: Spacecraft) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Find the welded corners of each side and the sides at each corner; made once and kept in the cache.

    Vertices that coincide are one corner, whatever their numbers, the facets' winding or part
    (:func:`mesh_edges`). A sheet's front and back share corners, but never both face the source.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    ids : (n_sides, 3) ndarray of int64
        Corner numbers of each side.
    start : (n_corners + 1,) ndarray of int64
        The sides at corner ``i`` are ``sides[start[i]:start[i + 1]]``.
    sides : (3 * n_sides,) ndarray of int64
        Sides, grouped by corner.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> ids, start, sides = side_corners(craft)
    >>> ids[0].tolist(), sides[start[0]:start[1]].tolist()
    ([3, 2, 0], [0, 1, 4, 5, 8, 9])
    """

    def make() -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
        ids = mesh_edges(craft).corner[craft.faces[craft.side_facet]]
        order = np.argsort(ids.reshape(-1), kind="stable")
        start = np.searchsorted(ids.reshape(-1)[order], np.arange(mesh_edges(craft).n_corners + 1))
        return ids, start, order // 3

    return craft.cache.get("side corners", make)
