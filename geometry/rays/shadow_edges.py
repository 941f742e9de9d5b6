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

import math

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.edge_kernels import (
    boundary_sides,
    classify_nodes,
    node_origins,
    outline_segments,
)
from sunwind.geometry.rays.node_rounds import (
    BISECTION_POINTS,
    add_chords,
    advance,
    chord_trials,
    chord_update,
    resolve_splits,
    settle_regions,
)
from sunwind.geometry.rays.outline import outline
from sunwind.geometry.spacecraft import Spacecraft

#: Share of the way toward the side's centroid that corner and edge points are drawn in before casting.
INSET = 1e-4
#: Levels below the ``tolerance`` depth to which nodes that two or more outline segments cross are split
#: (a thin shadow between a node's corners, two thin shadows crossing).
MOST_EXTRA_DEPTH = 5
_WHOLE_SIDE = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])


def side_corners(craft: Spacecraft) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Corner numbers of each side, (n_sides, 3): its vertices, a back side's numbered apart so that
    front and back sides never share a corner; and the sides at each corner number ``i``,
    ``sides[start[i]:start[i + 1]]``. Made once and kept in the model's cache."""

    def make() -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
        back = (craft.side_sign < 0)[:, None]
        ids = craft.faces[craft.side_facet] + len(craft.vertices) * back
        order = np.argsort(ids.reshape(-1), kind="stable")
        start = np.searchsorted(ids.reshape(-1)[order], np.arange(2 * len(craft.vertices) + 1))
        return ids, start, order // 3

    return craft.cache.get("side corners", make)


class _Caster:
    """Casts rays toward the source from points of sides, counting them."""

    def __init__(self, craft: Spacecraft, direction: NDArray[np.float64]) -> None:
        self.craft, self.direction, self.rays = craft, direction, 0

    def lit(self, sides: NDArray[np.int64], points: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Lit flag of each point ``points`` (n, 2) of ``sides`` (n,)."""
        craft, scene = self.craft, self.craft.scene
        origins = node_origins(
            craft.triangles,
            craft.side_facet,
            craft.side_normals,
            sides,
            np.ascontiguousarray(points),
            scene.centre,
            scene.half_size,
            scene.offset_m,
            INSET,
        )
        self.rays += len(origins)
        along = np.broadcast_to(self.direction.astype(np.float32), origins.shape)
        return scene.clear(origins, along)


def refine_edges(
    craft: Spacecraft,
    direction: NDArray[np.float64],
    facing: NDArray[np.int64],
    centre_lit: NDArray[np.bool_],
    fraction: NDArray[np.float64],
    centroid: NDArray[np.float64],
    tolerance: float,
) -> int:
    """Replace the centroid-ray answers ``fraction`` (lit share) and ``centroid`` (lit centroid [m]) of
    the sides a shadow edge crosses by their lit polygons, in place; return the rays cast.

    ``facing`` are the sides facing ``direction`` and ``centre_lit`` the answer of each one's centroid
    ray; ``tolerance`` is the share of a side's area that the lit part of each refined side is found to.
    """
    caster = _Caster(craft, direction)
    state = np.zeros(craft.n_sides, dtype=bool)
    state[facing] = centre_lit
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
    order = np.argsort(segment_side, kind="stable")
    segment_side, segments = segment_side[order], segments[order]
    bordering = boundary_sides(corner_ids, facing, centre_lit, 2 * len(craft.vertices))
    sides = np.union1d(bordering, segment_side)
    if not len(sides):
        return caster.rays
    moments = _lit_moments(caster, sides, state[sides], segment_side, segments, tolerance)
    area = moments[:, 0]
    fraction[sides] = np.clip(2.0 * area, 0.0, 1.0)
    lit = area > 0
    w = moments[lit, 1:] / area[lit, None]
    a, b, c = np.moveaxis(craft.triangles[craft.side_facet[sides[lit]]], 1, 0)
    centroid[sides] = craft.side_centroids[sides]
    centroid[sides[lit]] = a + w[:, :1] * (b - a) + w[:, 1:] * (c - a)
    return caster.rays


def _depths(tolerance: float) -> NDArray[np.int64]:
    """Split depths (uniform, mixed, most) of :func:`~.edge_kernels.classify_nodes` for ``tolerance``:
    a node at depth ``d`` holds ``4**-d`` of its side."""
    depth = max(1, math.ceil(math.log(1 / tolerance, 4)))
    return np.array([depth, depth, depth + MOST_EXTRA_DEPTH], dtype=np.int64)


def _lit_moments(
    caster: _Caster,
    sides: NDArray[np.int64],
    centre_lit: NDArray[np.bool_],
    segment_side: NDArray[np.int64],
    segments: NDArray[np.float64],
    tolerance: float,
) -> NDArray[np.float64]:
    """Lit area and its first moments ``(a, a w1, a w2)`` of each of ``sides`` in side coordinates
    (the whole side has area 1/2), (len(sides), 3). Each round casts one batch: the edge midpoints of
    the nodes being split or checked, the next bisection points of every chord still being located,
    and the ray of each region."""
    n = len(sides)
    moments = np.zeros((n, 3))
    root = np.arange(n)
    corners = np.broadcast_to(_WHOLE_SIDE, (n, 3, 2)).copy()
    lit = caster.lit(np.repeat(sides, 3), corners.reshape(-1, 2)).reshape(n, 3)
    centre_differs = (lit == ~centre_lit[:, None]).all(axis=1)
    depths, steps = _depths(tolerance), math.ceil(math.log2(1 / tolerance))
    chords: list[NDArray] = [np.zeros(0, dtype=np.int64), np.zeros((0, 3, 2)), np.zeros((0, 2))]
    chords += [np.zeros(0, dtype=bool), np.zeros((0, 2, 2)), np.zeros((0, 2, 2)), np.zeros(0)]
    depth = 0
    while len(root) or (chords[-1] > 0).any():
        action, part = classify_nodes(
            sides[root], corners, lit, depth, centre_differs, segment_side, segments, depths
        )
        (root, corners, lit, mid, check), new, regions = advance(root, corners, lit, action, part, moments)
        # a crossing is located to the node's share of the tolerance on its side's area
        chords = _joined_chords(chords, new, max(1, steps - 2 * depth))
        trying, trial = chord_trials(chords[4], chords[5], chords[6])
        flags = caster.lit(
            np.concatenate(
                [
                    np.repeat(sides[root], 3),
                    np.repeat(sides[chords[0][trying]], 2 * BISECTION_POINTS),
                    sides[regions[0]],
                ]
            ),
            np.concatenate([mid.reshape(-1, 2), trial, regions[4]]),
        )
        n_mid, n_trial = 3 * len(root), len(trial)
        chord_update(chords[4], chords[5], chords[6], trying, flags[n_mid : n_mid + n_trial])
        settle_regions(*regions[:4], flags[n_mid + n_trial :], moments)
        (root, corners, lit), new = resolve_splits(
            root, corners, lit, mid, flags[:n_mid].reshape(-1, 3), check, moments
        )
        # a checked node's midpoints were its chord's first bisection step
        chords = _joined_chords(chords, new, max(1, steps - 2 * depth) - 1)
        centre_differs = np.zeros(len(root), dtype=bool)
        depth += 1
    add_chords(*chords[:6], moments)
    return moments


def _joined_chords(chords: list[NDArray], new: tuple, steps: int) -> list[NDArray]:
    """``chords`` (root, corners, apex, apex_lit, lit_end, dark_end, steps) with ``new`` chords that
    have ``steps`` bisection steps (bits) to go."""
    new = (*new, np.full(len(new[0]), float(steps)))
    return [np.concatenate([old, more]) for old, more in zip(chords, new, strict=True)]
