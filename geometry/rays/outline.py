"""Sides a shadow's outline crosses, found from the occluders rather than from the sides' own points.

A shadow's outline is the projection, along the source direction, of the model's silhouette edges.
An edge is a silhouette edge when, seen from the source, every facet on it that is not edge-on lies on
the same side of it: a sheet's border or an unwelded seam (one facet), a fold of a surface such as a
closed body's rim (two facets folded over each other), whatever the facets' winding, part or kind
(:mod:`.mesh_edges` finds edges by position). A closed body wound outward gives exactly the edges
between a side facing the source and one facing away; a box of two-sided sheets, lit on the inside of
its far walls, gives the same rim. Rays cast from points along those edges away from the source land
on the sides the outline crosses, and the edge itself, projected onto such a side's plane, is the
outline there. The shadow-edge pass (:mod:`.shadow_edges`) refines those sides too and cuts them along
those lines, so that a thin occluder whose shadow falls inside large sides without touching any of
their corners (a strut across a low-polygon bus) is not missed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.mesh_edges import MeshEdges, mesh_edges
from sunwind.geometry.spacecraft import Spacecraft

#: Probe spacing along a silhouette edge, as a share of the width of the model's narrow sides (the
#: ``WIDTH_PERCENTILE`` percentile of the facets' least altitudes): a shadow outline crossing a side
#: that narrow meets a probe or two.
SPACING_SHARE = 0.25
WIDTH_PERCENTILE = 10.0
#: Most probe points on one edge.
MAX_POINTS_PER_EDGE = 1024
#: Least probe points on one edge: a short edge whose shadow lands on two sides (the nearer hiding the
#: farther from part of the edge) has a probe toward each end.
LEAST_POINTS = 2
#: Probes over all edges at most this many per edge, or ``MIN_PROBE_BUDGET``: the spacing is doubled
#: until they fit (a mesh of many slivers would otherwise ask for millions).
PROBES_PER_EDGE = 8
MIN_PROBE_BUDGET = 1 << 16
#: A facet whose normal is within this cosine of square to the source direction is edge-on, counted
#: as facing away.
EDGE_ON = 1e-12


def probe_counts(craft: Spacecraft, edges: MeshEdges) -> NDArray[np.int64]:
    """Count the probe points on each edge of a model; made once per model and kept in its cache.

    Each edge gets its length over the probe spacing, at least ``LEAST_POINTS``, at most
    ``MAX_POINTS_PER_EDGE``, the spacing widened until all fit the budget.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    edges : MeshEdges
        Its edges (:func:`~.mesh_edges.mesh_edges`).

    Returns
    -------
    (n_edges,) ndarray of int64
        Probe points per edge.

    Examples
    --------
    >>> from sunwind.geometry.rays.mesh_edges import mesh_edges
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> counts = probe_counts(craft, mesh_edges(craft))
    >>> counts[:4], int(counts.sum())
    (array([6, 6, 9, 6]), 1104)
    """

    def make() -> NDArray[np.int64]:
        ends = craft.vertices[edges.ends]
        length = np.linalg.norm(ends[:, 1] - ends[:, 0], axis=1)
        # a facet's width: its least altitude, twice its area over its longest edge
        corners = craft.triangles
        sides = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2)
        width = 2 * craft.facet_areas / np.maximum(sides.max(axis=1), np.finfo(float).tiny)
        spacing = SPACING_SHARE * float(np.percentile(width, WIDTH_PERCENTILE))
        for _ in range(64):  # widen the spacing until the probes of all edges fit the budget
            points = np.clip(np.ceil(length / spacing), LEAST_POINTS, MAX_POINTS_PER_EDGE).astype(np.int64)
            if points.sum() <= max(PROBES_PER_EDGE * len(length), MIN_PROBE_BUDGET):
                break
            spacing *= 2
        return points

    return craft.cache.get("edge probes", make)


@dataclass(frozen=True)
class Outline:
    """Where shadow outlines land: the silhouette edge behind each (side, edge) pair found by a probe.

    Attributes
    ----------
    sides : (m,) int64
        Facing sides an outline lands on.
    edges : (m,) int64
        The silhouette edge whose shadow lands there (:class:`~.mesh_edges.MeshEdges` number), ascending.
    ends : (m, 2, 3) float64
        End points [m] of that edge.
    rays : int
        Rays cast to find them.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> found = outline(craft, direction, np.flatnonzero(craft.side_normals @ direction > 0))
    >>> found.sides[:4], found.edges[:4], found.ends.shape
    (array([69, 71, 24, 28]), array([ 85,  85, 100, 100]), (14, 2, 3))
    """

    sides: NDArray[np.int64]
    edges: NDArray[np.int64]
    ends: NDArray[np.float64]
    rays: int


def silhouette(craft: Spacecraft, direction: NDArray[np.float64]) -> NDArray[np.int8]:
    """Find which way each edge of a model casts an outline seen from a direction.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source, body frame.

    Returns
    -------
    (n_edges,) ndarray of int8
        +1 or -1 toward ``±direction x (end 1 - end 0)`` (away from its facets), 0 where it casts none.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> away = silhouette(craft, direction)
    >>> int((away != 0).sum()), away[10:13]
    (44, array([ 0,  1, -1], dtype=int8))
    """
    edges = mesh_edges(craft)
    return _silhouette(edges.start, edges.facet, edges.way, craft.facet_normals @ direction)


def outline(craft: Spacecraft, direction: NDArray[np.float64], facing: NDArray[np.int64]) -> Outline:
    """Find the facing sides that shadow outlines land on, and the silhouette edge of each.

    Each probe point of a silhouette edge casts a ray away from the source, started just beyond the
    edge as seen from the source: the first side it meets is where the edge's shadow lands, unless it
    is a facet on the edge itself; and then one toward the source: the shadow is an outline only where
    the edge is lit.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source, body frame.
    facing : (n_facing,) ndarray of int64
        The sides facing it.

    Returns
    -------
    Outline
        The (side, edge) pairs found and the rays cast.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> found = outline(craft, direction, np.flatnonzero(craft.side_normals @ direction > 0))
    >>> found.rays, sorted(set(found.sides.tolist()))[:5]
    (302, [24, 26, 28, 30, 54])
    """
    edges = mesh_edges(craft)
    scene = craft.scene
    away = silhouette(craft, direction)
    probe_edge, up, down = _probes(
        away,
        edges.ends,
        probe_counts(craft, edges),
        craft.vertices,
        direction,
        scene.centre,
        scene.half_size,
        scene.offset_m,
    )
    hit = scene.first_hit(down, np.broadcast_to((-direction).astype(np.float32), down.shape))
    facing_side = np.full(craft.n_facets, -1)
    facing_side[craft.side_facet[facing]] = facing
    landed = _landing_sides(hit, probe_edge, edges.start, edges.facet, facing_side)
    probes = np.flatnonzero(landed >= 0)
    lit = scene.clear(up[probes], np.broadcast_to(direction.astype(np.float32), (len(probes), 3)))
    probes = probes[lit]
    keys = np.unique(probe_edge[probes] * craft.n_sides + landed[probes])  # grouped by edge
    edge, sides = keys // craft.n_sides, keys % craft.n_sides
    return Outline(sides, edge, craft.vertices[edges.ends[edge]], len(down) + len(lit))


@numba.njit(cache=True, nogil=True)
def _silhouette(
    start: NDArray[np.int64], facet: NDArray[np.int64], way: NDArray[np.int8], facing: NDArray[np.float64]
) -> NDArray[np.int8]:
    """:func:`silhouette` from each facet's ``n . direction`` (``facing``). A facet that runs its edge
    from end 0 to end 1 (``way`` +1) and faces the source lies, seen from the source, on the left of
    the edge, toward ``direction x (end 1 - end 0)``; one that faces away (or is edge-on, within
    ``EDGE_ON``) on the right. The outline is cast away from the facets, where they all lie on one
    side. Counting an edge-on facet as facing away makes exactly one edge of it a fold between a
    facet facing the source and one facing away, whatever its winding."""
    out = np.zeros(start.shape[0] - 1, dtype=np.int8)
    for e in range(start.shape[0] - 1):
        left = right = False
        for k in range(start[e], start[e + 1]):
            if (facing[facet[k]] > EDGE_ON) == (way[k] > 0):
                left = True
            else:
                right = True
        if left != right:
            out[e] = -1 if left else 1
    return out


@numba.njit(cache=True, nogil=True)
def _probes(
    away: NDArray[np.int8],
    ends: NDArray[np.int64],
    points: NDArray[np.int64],
    vertices: NDArray[np.float64],
    direction: NDArray[np.float64],
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> tuple[NDArray[np.int64], NDArray[np.float32], NDArray[np.float32]]:
    """The probe points of the silhouette edges (``away`` nonzero): the edge of each and its ray
    origins toward and away from the source, float32 scene coordinates, both started ``offset_m``
    beyond the edge as seen from the source (outside its facets' shadow), one toward the source and
    one away from it, so that neither meets a facet on the edge or runs along a face edge-on."""
    total = 0
    for e in range(away.shape[0]):
        if away[e] != 0:
            total += points[e]
    edge = np.empty(total, dtype=np.int64)
    up = np.empty((total, 3), dtype=np.float32)
    down = np.empty((total, 3), dtype=np.float32)
    across = np.empty(3)
    k = 0
    for e in range(away.shape[0]):
        if away[e] == 0:
            continue
        a, b = vertices[ends[e, 0]], vertices[ends[e, 1]]
        # across: direction x (b - a), normal to the source direction and the edge, signed away
        across[0] = direction[1] * (b[2] - a[2]) - direction[2] * (b[1] - a[1])
        across[1] = direction[2] * (b[0] - a[0]) - direction[0] * (b[2] - a[2])
        across[2] = direction[0] * (b[1] - a[1]) - direction[1] * (b[0] - a[0])
        across *= away[e] / max(np.sqrt(across @ across), 1e-300)
        for i in range(points[e]):
            t = (i + 0.5) / points[e]  # midpoints of equal pieces
            edge[k] = e
            for d in range(3):
                x = a[d] + t * (b[d] - a[d]) - centre[d]
                up[k, d] = (x + offset_m * (across[d] + direction[d])) / half_size
                down[k, d] = (x + offset_m * (across[d] - direction[d])) / half_size
            k += 1
    return edge, up, down


@numba.njit(cache=True, nogil=True)
def _landing_sides(
    hit: NDArray[np.int32],
    probe_edge: NDArray[np.int64],
    start: NDArray[np.int64],
    facet: NDArray[np.int64],
    facing_side: NDArray[np.int64],
) -> NDArray[np.int64]:
    """The facing side each probe's ray away from the source lands on, -1 where it escapes, meets a
    facet on its own edge, or meets a facet on the side that faces away (the inside of a body)."""
    out = np.full(hit.shape[0], -1, dtype=np.int64)
    for k in range(hit.shape[0]):
        f = hit[k]
        if f < 0:
            continue
        e = probe_edge[k]
        own = False
        for j in range(start[e], start[e + 1]):
            own |= facet[j] == f
        if not own:
            out[k] = facing_side[f]
    return out
