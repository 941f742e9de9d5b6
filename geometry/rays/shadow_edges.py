"""The lit part of the sides a shadow edge crosses, located by rays at their corners and cut along the
outline itself: the default shadow pass after one ray from each side's centroid.

METHOD.md "Shadowing and sampling". The sides examined are those sharing a corner with a side whose
centroid ray has the other answer, and those an outline segment crosses: the shadow of a silhouette
edge whose probe landed there (:mod:`.outline`), carried over the facing sides it crosses. Each side
is the root of a quadtree of nodes (sub-triangles in its own coordinates) with a ray at every node
corner. A node is cut exactly along the outline segments crossing it when they bound one convex
region and its corners agree with them (:func:`~.edge_kernels.classify_nodes`); when its corners all
agree, one ray from inside that region gives the region's state. A node with no such outline is
uniform if its corners (and, for a whole side, its edge midpoints) agree, cut along a chord bisected
to ``tolerance`` if they do not, or split, to depths set by ``tolerance``
(:func:`_depths`). Shadow outlines on a flat side are straight (projected silhouette edges), so the
error lies only in chords and in nodes accepted at a depth limit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.certificate import ShadowCheck, check_pass
from sunwind.geometry.rays.crossings import crossings
from sunwind.geometry.rays.edge_kernels import boundary_sides, crossing_outlines, outline_segments
from sunwind.geometry.rays.leaf_kernels import DARK, LIT
from sunwind.geometry.rays.mesh_edges import mesh_edges, side_corners
from sunwind.geometry.rays.node_kernels import TRUST
from sunwind.geometry.rays.outline import outline
from sunwind.geometry.rays.quadtree import Caster, Leaves, Segments, resolve_sides
from sunwind.geometry.spacecraft import Spacecraft

#: Rounds of refining the sides a refined side's shadow edge runs on into, at most.
MOST_SPILL_ROUNDS = 8
#: Points on each edge of a refined side at which its leaves are asked for a change of state.
SPILL_POINTS = 8


@dataclass(frozen=True, eq=False)
class Refined:
    """What the shadow-edge pass found: the leaves of every side it refined, and the rays it cast.

    Attributes
    ----------
    leaves : Leaves
        Leaves of the refined sides.
    rays : int
        Rays cast, the check's included.
    check : ShadowCheck
        What the pass's check found (:mod:`.certificate`).

    Examples
    --------
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> centre_lit = side_sampler(craft).illuminate(direction, samples=1).lit_fraction[facing] > 0.5
    >>> fraction, centroid = np.zeros(craft.n_sides), craft.side_centroids.copy()
    >>> fraction[facing] = centre_lit
    >>> refined = refine_edges(craft, direction, facing, centre_lit, fraction, centroid, 1e-3)
    >>> isinstance(refined, Refined), len(refined.leaves.sides)
    (True, 21)
    """

    leaves: Leaves
    rays: int
    check: ShadowCheck


def outline_of(
    craft: Spacecraft, direction: NDArray[np.float64], facing: NDArray[np.int64], caster: Caster
) -> Segments:
    """Find the outline segments on the facing sides.

    These are the shadows of the silhouette edges whose probes landed there (:mod:`.outline`), carried
    over the facing sides they cross, and the lines where other facets pass through them
    (:mod:`.crossings`).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source, body frame.
    facing : (n_facing,) ndarray of int64
        The sides facing it.
    caster : Caster
        Counts the outline's probe rays.

    Returns
    -------
    Segments
        The segments, in side coordinates.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.quadtree import Caster
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> segments = outline_of(craft, direction, facing, Caster(craft, direction))
    >>> segments.side[:6], segments.ends.shape
    (array([24, 24, 26, 26, 26, 26]), (17, 2, 2))
    """
    lines = outline(craft, direction, facing)
    caster.rays += lines.rays
    corner_ids, id_start, id_sides = side_corners(craft)
    is_facing = np.zeros(craft.n_sides, dtype=bool)
    is_facing[facing] = True
    segment_side, segments = outline_segments(
        craft.triangles,
        craft.side_facet,
        craft.side_normals,
        direction,
        lines.sides,
        lines.edges,
        lines.ends,
        corner_ids,
        id_start,
        id_sides,
        is_facing,
    )
    crossed_side, crossed = _crossing_segments(craft, direction, is_facing)
    return Segments.of(np.concatenate([segment_side, crossed_side]), np.concatenate([segments, crossed]))


def refine_edges(
    craft: Spacecraft,
    direction: NDArray[np.float64],
    facing: NDArray[np.int64],
    centre_lit: NDArray[np.bool_],
    fraction: NDArray[np.float64],
    centroid: NDArray[np.float64],
    tolerance: float,
) -> Refined:
    """Replace the centroid-ray answers of the sides a shadow edge crosses by their lit polygons, in place.

    The sides refined are those sharing a corner with a side whose centroid ray has the other answer,
    those an outline segment crosses, and then, round by round, every facing side across an edge of a
    refined side whose leaves change state along that edge, where the side's own answer is uniform.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source, body frame.
    facing : (n_facing,) ndarray of int64
        The sides facing it.
    centre_lit : (n_facing,) ndarray of bool
        The answer of each facing side's centroid ray.
    fraction : (n_sides,) ndarray of float64
        Lit share of each side; the refined sides' are written.
    centroid : (n_sides, 3) ndarray of float64
        Lit centroid of each side [m]; the refined sides' are written.
    tolerance : float
        Share of a side's area that the lit part of each refined side is found to.

    Returns
    -------
    Refined
        The leaves, the rays cast and the check.

    Examples
    --------
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> centre_lit = side_sampler(craft).illuminate(direction, samples=1).lit_fraction[facing] > 0.5
    >>> fraction, centroid = np.zeros(craft.n_sides), craft.side_centroids.copy()
    >>> fraction[facing] = centre_lit
    >>> refined = refine_edges(craft, direction, facing, centre_lit, fraction, centroid, 1e-3)
    >>> refined.rays, fraction[[24, 26]].round(3)
    (689, array([0.1, 0.4]))
    """
    caster = Caster(craft, direction)
    state = np.zeros(craft.n_sides, dtype=bool)
    state[facing] = centre_lit
    segments = outline_of(craft, direction, facing, caster)
    corner_ids, id_start, _ = side_corners(craft)
    bordering = boundary_sides(corner_ids, facing, centre_lit, len(id_start) - 1)
    sides = np.union1d(bordering, segments.side)
    leaves = Leaves.empty()
    for _ in range(MOST_SPILL_ROUNDS):
        if not len(sides):
            break
        more = resolve_sides(
            caster, sides, state[sides], np.full(len(sides), TRUST, np.int8), 0, segments, tolerance
        )
        leaves = leaves.replaced(more)
        sides = spilled(craft, leaves, more, state, facing)
    leaves, check = check_pass(caster, leaves, facing, state.astype(float), segments, tolerance)
    write_leaves(craft, leaves, fraction, centroid)
    return Refined(leaves, caster.rays, check)


def write_leaves(
    craft: Spacecraft, leaves: Leaves, fraction: NDArray[np.float64], centroid: NDArray[np.float64]
) -> None:
    """Write the lit share and lit centroid of the sides of some leaves, in place.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    leaves : Leaves
        Leaves of some sides.
    fraction : (n_sides,) ndarray of float64
        Lit share by side; the leaves' sides are written.
    centroid : (n_sides, 3) ndarray of float64
        Lit centroid by side [m]; the leaves' sides are written (their centroid where nothing is lit).

    Examples
    --------
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
    >>> fraction, centroid = np.ones(craft.n_sides), craft.side_centroids.copy()
    >>> write_leaves(craft, leaves, fraction, centroid)
    >>> fraction[[24, 26]].round(3), centroid[24].round(3)
    (array([0.1  , 0.407]), array([-0.105,  0.5  , -0.053]))
    """
    sides = leaves.sides
    if not len(sides):
        return
    moments = leaves.moments()
    area = moments[:, 0]
    fraction[sides] = np.clip(2.0 * area, 0.0, 1.0)
    lit = area > 0
    w = moments[lit, 1:] / area[lit, None]
    a, b, c = np.moveaxis(craft.triangles[craft.side_facet[sides[lit]]], 1, 0)
    centroid[sides] = craft.side_centroids[sides]
    centroid[sides[lit]] = a + w[:, :1] * (b - a) + w[:, 1:] * (c - a)


def spilled(
    craft: Spacecraft,
    leaves: Leaves,
    latest: Leaves,
    state: NDArray[np.bool_],
    facing: NDArray[np.int64],
) -> NDArray[np.int64]:
    """Find the facing sides a shadow edge runs on into, across an edge of a newly refined side.

    These are the facing sides, not yet in ``leaves``, across an edge of a side of ``latest`` along
    which that side's leaves have a state other than their own (``state``, their centroid ray's).
    ``SPILL_POINTS`` points on each edge are asked.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    leaves : Leaves
        Leaves of every side refined so far.
    latest : Leaves
        Leaves of the sides refined in the last round.
    state : (n_sides,) ndarray of bool
        Centroid-ray state of each side.
    facing : (n_facing,) ndarray of int64
        The sides facing the source.

    Returns
    -------
    (k,) ndarray of int64
        The sides to refine next, ascending.

    Examples
    --------
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
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> lit = np.zeros(craft.n_sides, dtype=bool)
    >>> lit[facing] = True
    >>> spilled(craft, leaves, leaves, lit, facing)
    array([28, 30])
    """
    k = len(latest.sides)
    if not k:
        return np.zeros(0, dtype=np.int64)
    t = (np.arange(SPILL_POINTS) + 0.5) / SPILL_POINTS
    along = np.stack(
        [np.column_stack([t, 0 * t]), np.column_stack([1 - t, t]), np.column_stack([0 * t, 1 - t])]
    )  # edges (v0, v1), (v1, v2), (v2, v0) of the side's triangle
    points = np.broadcast_to(along, (k, 3, SPILL_POINTS, 2)).reshape(-1, 2)
    said = latest.states(np.repeat(np.arange(k), 3 * SPILL_POINTS), points).reshape(k, 3, SPILL_POINTS)
    has_lit, has_dark = (said == LIT).any(axis=2), (said == DARK).any(axis=2)
    edges = mesh_edges(craft)
    edge = edges.facet_edges[craft.side_facet[latest.sides]].reshape(-1)
    real = edge >= 0
    owner = np.repeat(np.arange(k * 3), 1)[real]
    edge = edge[real]
    count = edges.start[edge + 1] - edges.start[edge]
    rows = np.repeat(edges.start[edge] - np.cumsum(count) + count, count) + np.arange(count.sum())
    owner = np.repeat(owner, count)
    facing_side = np.full(craft.n_facets, -1)
    facing_side[craft.side_facet[facing]] = facing
    facing_side[craft.side_facet[leaves.sides]] = -1  # a side with leaves already is not spilled into
    other = facing_side[edges.facet[rows]]
    keep = other >= 0
    other, owner = other[keep], owner[keep]
    lit_there = state[other]
    wrong = np.where(lit_there, has_dark.reshape(-1)[owner], has_lit.reshape(-1)[owner])
    return np.unique(other[wrong])


def _crossing_segments(
    craft: Spacecraft, direction: NDArray[np.float64], is_facing: NDArray[np.bool_]
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Outline segments where other facets pass through the facing sides (``is_facing``, by side)
    (:mod:`.crossings`): the line where each crosses, and the shadows of its edges in front of the side
    (:func:`crossing_outlines`). Returns each segment's side and the segments (k, 2, 2) in side
    coordinates."""
    lines = crossings(craft)
    crossed = craft.cache.get(
        "crossed sides", lambda: np.flatnonzero(np.diff(lines.start)[craft.side_facet] > 0)
    )
    facing = crossed[is_facing[crossed]]
    first, last = lines.start[craft.side_facet[facing]], lines.start[craft.side_facet[facing] + 1]
    count = last - first
    rows = np.repeat(first - np.cumsum(count) + count, count) + np.arange(count.sum())
    side = np.repeat(facing, count)
    edge_side, edges = crossing_outlines(
        craft.triangles,
        craft.side_facet,
        craft.side_normals,
        direction,
        side,
        lines.other[rows],
        lines.open_edges[rows],
    )
    return np.concatenate([side, edge_side]), np.concatenate([lines.segments[rows], edges])
