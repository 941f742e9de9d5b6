"""Sides a shadow's outline crosses, found from the occluders rather than from the sides' own points.

A shadow's outline is the projection, along the source direction, of the model's silhouette edges: the
edges with exactly one adjacent side facing the source (a closed body's rim, a sheet's border). Rays
cast from points along those edges away from the source land on the sides the outline crosses, and the
edge itself, projected onto such a side's plane, is the outline there. The shadow-edge pass
(:mod:`.shadow_edges`) refines those sides too and cuts them along those lines, so that a thin occluder
whose shadow falls inside large sides without touching any of their corners (a strut across a
low-polygon bus) is not missed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import Spacecraft

#: Probe spacing along a silhouette edge, as a share of the width of the model's narrow sides (the
#: ``WIDTH_PERCENTILE`` percentile of the facets' least altitudes): a shadow outline crossing a side
#: that narrow meets a probe or two.
SPACING_SHARE = 0.25
WIDTH_PERCENTILE = 10.0
#: Most probe points on one edge.
MAX_POINTS_PER_EDGE = 1024
#: Probes over all edges at most this many per edge, or ``MIN_PROBE_BUDGET``: the spacing is doubled
#: until they fit (a mesh of many slivers would otherwise ask for millions).
PROBES_PER_EDGE = 8
MIN_PROBE_BUDGET = 1 << 16


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
    # a facet's width: its least altitude, twice its area over its longest edge
    longest = np.max(length[inverse.reshape(-1, 3)], axis=1)
    width = 2 * craft.side_areas / np.maximum(longest, np.finfo(float).tiny)
    spacing = SPACING_SHARE * float(np.percentile(width, WIDTH_PERCENTILE))
    for _ in range(64):  # widen the spacing until the probes of all edges fit the budget
        points = np.clip(np.ceil(length / spacing), 1, MAX_POINTS_PER_EDGE).astype(np.int64)
        if points.sum() <= max(PROBES_PER_EDGE * len(length), MIN_PROBE_BUDGET):
            break
        spacing *= 2
    return _Edges(inverse.reshape(-1, 3), unique, points)


@dataclass(frozen=True)
class Outline:
    """Where shadow outlines land: the silhouette edge behind each (side, edge) pair found by a probe.

    Attributes
    ----------
    sides : (m,) int64
        Facing sides an outline lands on.
    edges : (m,) int64
        The silhouette edge whose shadow lands there (facet edge number), ascending.
    ends : (m, 2, 3) float64
        End points [m] of that edge.
    rays : int
        Rays cast to find them.
    """

    sides: NDArray[np.int64]
    edges: NDArray[np.int64]
    ends: NDArray[np.float64]
    rays: int


def outline(craft: Spacecraft, direction: NDArray[np.float64], facing: NDArray[np.int64]) -> Outline:
    """The facing sides that shadow outlines of the model land on, for a source along unit
    ``direction`` (``facing``: the sides facing it), and the silhouette edge of each.

    Each probe point of a silhouette edge casts a ray away from the source: the first side it meets is
    where the edge's shadow lands, unless it is a facet at the edge itself; and then one toward the
    source: the shadow is an outline only where the edge is lit."""
    edges = craft.cache.get("facet edges", lambda: _edges(craft))
    scene = craft.scene
    probe_edge, up, down = _probes(
        edges.side_edges,
        facing,
        edges.vertices,
        edges.points,
        craft.vertices,
        craft.side_centroids,
        craft.side_normals,
        direction,
        scene.centre,
        scene.half_size,
        scene.offset_m,
    )
    hit = scene.first_hit(down, np.broadcast_to((-direction).astype(np.float32), down.shape))
    facing_side = np.full(craft.n_facets, -1)
    facing_side[craft.side_facet[facing]] = facing
    landed = _landing_sides(hit, probe_edge, edges.vertices, craft.faces, facing_side)
    probes = np.flatnonzero(landed >= 0)
    lit = scene.clear(up[probes], np.broadcast_to(direction.astype(np.float32), (len(probes), 3)))
    probes = probes[lit]
    keys = np.unique(probe_edge[probes] * craft.n_sides + landed[probes])  # grouped by edge
    edge, sides = keys // craft.n_sides, keys % craft.n_sides
    return Outline(sides, edge, craft.vertices[edges.vertices[edge]], len(down) + len(lit))


@numba.njit(cache=True, nogil=True)
def _probes(
    side_edges: NDArray[np.int64],
    facing: NDArray[np.int64],
    edge_vertices: NDArray[np.int64],
    points: NDArray[np.int64],
    vertices: NDArray[np.float64],
    side_centroids: NDArray[np.float64],
    normals: NDArray[np.float64],
    direction: NDArray[np.float64],
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]]:
    """The probe points of the silhouette edges (those with exactly one adjacent facing side): the
    edge of each and its ray origins toward and away from the source, float32 scene coordinates. The
    ray toward the source starts ``offset_m`` off the edge along its facing side's normal (and the
    source direction); the ray away from it, across the source direction away from that side, so
    that neither runs along a face edge-on to the source."""
    count = np.zeros(edge_vertices.shape[0], dtype=np.int32)
    owner = np.empty(edge_vertices.shape[0], dtype=np.int64)
    for k in range(facing.shape[0]):
        for c in range(3):
            count[side_edges[facing[k], c]] += 1
            owner[side_edges[facing[k], c]] = facing[k]
    total = 0
    for e in range(count.shape[0]):
        if count[e] == 1:
            total += points[e]
    edge = np.empty(total, dtype=np.int64)
    up = np.empty((total, 3), dtype=np.float32)
    down = np.empty((total, 3), dtype=np.float32)
    away, across = np.empty(3), np.empty(3)
    k = 0
    for e in range(count.shape[0]):
        if count[e] != 1:
            continue
        a, b = vertices[edge_vertices[e, 0]], vertices[edge_vertices[e, 1]]
        # across: the edge made normal to the source direction; away: from the facing side's
        # centroid to the edge, normal to both
        across_u = 0.0
        for d in range(3):
            across[d] = b[d] - a[d]
            across_u += across[d] * direction[d]
        for d in range(3):
            across[d] -= across_u * direction[d]
        across /= max(np.sqrt(across @ across), 1e-300)
        along = sideways = 0.0
        for d in range(3):
            away[d] = (a[d] + b[d]) / 2 - side_centroids[owner[e], d]
            along += away[d] * direction[d]
            sideways += away[d] * across[d]
        for d in range(3):
            away[d] -= along * direction[d] + sideways * across[d]
        away /= max(np.sqrt(away @ away), 1e-300)
        for i in range(points[e]):
            t = (i + 0.5) / points[e]  # midpoints of equal pieces
            edge[k] = e
            for d in range(3):
                x = a[d] + t * (b[d] - a[d]) - centre[d]
                up[k, d] = (x + offset_m * (normals[owner[e], d] + direction[d])) / half_size
                down[k, d] = (x + offset_m * (away[d] - direction[d])) / half_size
            k += 1
    return edge, up, down


@numba.njit(cache=True, nogil=True)
def _landing_sides(
    hit: NDArray[np.int32],
    probe_edge: NDArray[np.int64],
    edge_vertices: NDArray[np.int64],
    faces: NDArray[np.int64],
    facing_side: NDArray[np.int64],
) -> NDArray[np.int64]:
    """The facing side each probe's ray away from the source lands on, -1 where it escapes or meets a
    facet at its own edge (one sharing a vertex with it)."""
    out = np.full(hit.shape[0], -1, dtype=np.int64)
    for k in range(hit.shape[0]):
        f = hit[k]
        if f < 0:
            continue
        own = False
        a, b = edge_vertices[probe_edge[k], 0], edge_vertices[probe_edge[k], 1]
        for c in range(3):
            own |= faces[f, c] == a or faces[f, c] == b
        if not own:
            out[k] = facing_side[f]
    return out
