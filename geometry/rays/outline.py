"""Sides a shadow's outline crosses, found from the occluders rather than from the sides' own points.

A shadow's outline is the projection, along the source direction, of the model's silhouette edges: the
edges with exactly one adjacent side facing the source (a closed body's rim, a sheet's border). Rays
cast from points along those edges away from the source land on the sides the outline crosses. Adaptive
sampling refines those sides too, so that a thin occluder whose shadow falls inside large sides without
touching any of their starting points (a strut across a low-polygon bus) is not missed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import Spacecraft

#: Probe spacing along a silhouette edge, as a share of the model's median edge length.
SPACING_SHARE = 0.125
#: Most probe points on one edge.
MAX_POINTS_PER_EDGE = 64


@dataclass(frozen=True)
class _Edges:
    """The facet edges of a model: each side's three edges and each edge's two vertices."""

    side_edges: NDArray[np.int64]  # (n_sides, 3) index into the edges
    vertices: NDArray[np.int64]  # (n_edges, 2)
    points: NDArray[np.int64]  # (n_edges,) probe points on each edge


def _edges(craft: Spacecraft) -> _Edges:
    corners = craft.faces[craft.side_facet]
    pairs = corners[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    pairs = np.sort(pairs, axis=1)
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    length = np.linalg.norm(craft.vertices[unique[:, 0]] - craft.vertices[unique[:, 1]], axis=1)
    spacing = SPACING_SHARE * float(np.median(length))
    points = np.clip(np.ceil(length / spacing), 1, MAX_POINTS_PER_EDGE).astype(np.int64)
    return _Edges(inverse.reshape(-1, 3), unique, points)


def outline_sides(craft: Spacecraft, direction: NDArray[np.float64], facing: NDArray[np.int64]) -> NDArray:
    """Facing sides that a shadow outline of the model crosses, for a source along unit ``direction``
    (``facing``: the sides facing it). One first-hit ray per probe point of each silhouette edge."""
    edges = craft.cache.get("facet edges", lambda: _edges(craft))
    count = np.bincount(edges.side_edges[facing].reshape(-1), minlength=len(edges.vertices))
    silhouette = np.flatnonzero(count == 1)
    if not len(silhouette):
        return np.zeros(0, dtype=np.int64)
    n = edges.points[silhouette]
    edge = np.repeat(silhouette, n)
    start = np.repeat(np.cumsum(n) - n, n)
    t = (np.arange(len(edge)) - start + 0.5) / np.repeat(n, n)  # midpoints of n equal pieces
    a, b = (craft.vertices[edges.vertices[edge, k]] for k in (0, 1))
    scene = craft.scene
    origins = scene.to_scene(a + t[:, None] * (b - a) - scene.offset_m * direction)
    hit = scene.first_hit(origins, np.broadcast_to((-direction).astype(np.float32), origins.shape))
    ends = edges.vertices[edge]
    hit_corners = craft.faces[np.maximum(hit, 0)]
    own = (hit_corners[:, :, None] == ends[:, None, :]).any(axis=(1, 2))  # a facet at the edge itself
    landed = np.zeros(craft.n_facets, dtype=bool)
    landed[hit[(hit >= 0) & ~own]] = True
    return facing[landed[craft.side_facet[facing]]]
