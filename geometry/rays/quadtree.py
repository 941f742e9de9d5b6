"""The lit part of chosen sides, resolved node by node by rays at the corners of a quadtree and cut
along the outline segments where rays inside the parts agree: the engine of the shadow-edge pass.

METHOD.md "Shadowing and sampling". Each side is the root of a quadtree of nodes (sub-triangles
halving its edges) in its own coordinates ``(w1, w2)``, with a ray at every node corner. What becomes
of each node is decided by :func:`~.node_kernels.classify_nodes` and its rays read by
:func:`~.node_kernels.resolve_nodes`; chords are bisected by :mod:`.leaf_kernels`. Each round casts one
batch of rays. The result is the sides' :class:`Leaves`: what every part of each side is, from which
the lit share and centroid follow and which the certificate (:mod:`.certificate`) asks about points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.crossings import crossings
from sunwind.geometry.rays.edge_kernels import INSET, MAX_LINES, node_origins
from sunwind.geometry.rays.leaf_kernels import (
    BISECTION_POINTS,
    chord_checks,
    chord_leaves,
    chord_trials,
    chord_update,
    leaf_moments,
    leaf_states,
    start_chords,
)
from sunwind.geometry.rays.node_kernels import (
    CENTRE_DIFFERS,
    CHECK,
    MOST_POINTS,
    SUSPECT,
    classify_nodes,
    resolve_nodes,
)
from sunwind.geometry.spacecraft import Spacecraft

#: Levels below the ``tolerance`` depth to which nodes that two or more outline segments cross are split
#: (a thin shadow between a node's corners, two thin shadows crossing).
MOST_EXTRA_DEPTH = 5
_WHOLE_SIDE = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])


class Caster:
    """Cast rays toward the source from points of sides, counting them.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source, body frame.

    Attributes
    ----------
    craft : Spacecraft
        The model.
    direction : (3,) ndarray of float64
        Unit vector toward the source.
    rays : int
        Rays cast so far; others add theirs (the outline's probes) too.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> caster = Caster(craft, direction)
    >>> caster.lit(np.array([24, 24]), np.array([[0.1, 0.1], [0.1, 0.8]])), caster.rays
    (array([False,  True]), 2)
    """

    def __init__(self, craft: Spacecraft, direction: NDArray[np.float64]) -> None:
        self.craft, self.direction, self.rays = craft, direction, 0

    def lit(self, sides: NDArray[np.int64], points: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Cast a ray toward the source from each of some points of sides.

        Points a coplanar facet covers count as dark (:func:`uncovered`).

        Parameters
        ----------
        sides : (n,) ndarray of int64
            Side of each point.
        points : (n, 2) ndarray of float64
            Points ``(w1, w2)`` in their side's coordinates.

        Returns
        -------
        (n,) ndarray of bool
            True where the point is lit.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> Caster(craft, direction).lit(np.array([8, 24]), np.array([[0.3, 0.3], [0.1, 0.1]]))
        array([ True, False])
        """
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
        # the cover is asked where the ray starts: the point drawn ``INSET`` toward the centroid
        inset = (1.0 - INSET) * np.asarray(points) + INSET / 3.0
        return uncovered(craft, sides, inset, scene.clear(origins, along))


def uncovered(
    craft: Spacecraft, sides: NDArray[np.int64], points: NDArray[np.float64], lit: NDArray[np.bool_]
) -> NDArray[np.bool_]:
    """Darken the points of sides that a coplanar facet covers.

    A duplicate layer is lit once, on top (:class:`~.crossings.Crossings`).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    sides : (n,) ndarray of int64
        Side of each point.
    points : (n, 2) ndarray of float64
        Points ``(w1, w2)`` in their side's coordinates.
    lit : (n,) ndarray of bool
        Lit flag of each point by its ray; changed in place.

    Returns
    -------
    (n,) ndarray of bool
        ``lit``, False where a coplanar facet covers the point.

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
    >>> uncovered(craft, np.array([0, 2]), np.array([[0.2, 0.2], [0.2, 0.2]]), np.array([True, True]))
    array([False,  True])
    """
    lines = crossings(craft)
    if not len(lines.cover):
        return lit
    facets = craft.side_facet[sides]
    has = lines.cover_start[facets + 1] > lines.cover_start[facets]
    if has.any():
        lit[has] &= ~lines.covered(facets[has], points[has])
    return lit


@dataclass(frozen=True)
class Segments:
    """Outline segments on sides, in side coordinates.

    Attributes
    ----------
    side : (m,) ndarray of int64
        The side of each segment, ascending.
    ends : (m, 2, 2) ndarray of float64
        End points ``(w1, w2)`` of each segment.

    Examples
    --------
    >>> import numpy as np
    >>> segments = Segments.of(np.array([5, 2]), np.array([[[0, 0], [1, 0]], [[0, 0], [0, 1]]], float))
    >>> segments.side, segments.ends[0]
    (array([2, 5]), array([[0., 0.],
           [0., 1.]]))
    """

    side: NDArray[np.int64]
    ends: NDArray[np.float64]

    @classmethod
    def of(cls, side: NDArray[np.int64], ends: NDArray[np.float64]) -> Segments:
        """Make segments sorted by side.

        Parameters
        ----------
        side : (m,) ndarray of int64
            The side of each segment, in any order.
        ends : (m, 2, 2) ndarray of float64
            End points of each segment in its side's coordinates.

        Returns
        -------
        Segments
            The segments, stably sorted by side.

        Examples
        --------
        >>> import numpy as np
        >>> Segments.of(np.array([5, 2]), np.zeros((2, 2, 2))).side
        array([2, 5])
        """
        order = np.argsort(side, kind="stable")
        return cls(np.ascontiguousarray(side[order]), np.ascontiguousarray(ends[order]))


@dataclass(frozen=True, eq=False)
class Leaves:
    """What every part of some sides is: the leaves of their quadtrees.

    Attributes
    ----------
    sides : (k,) int64
        The sides, ascending.
    start : (k + 1,) int64
        The leaves of ``sides[i]`` are rows ``start[i]:start[i + 1]``.
    corners : (m, 3, 2) float64
        Each leaf's node in side coordinates.
    lines : (m, MAX_LINES, 3) float64, n_lines : (m,) int64
        Lines cutting the leaf into cells, each named by its sign pattern (bit ``j`` set where line
        ``j`` is positive).
    mask : (m,) uint64
        Bit ``p`` set where the cell of pattern ``p`` is lit (a leaf without lines: bit 0, its state).
    band : (m,) float64
        A chord's bracket [side coordinates], where its line and the shadow's true edge may differ; 0
        for leaves cut exactly or uniform.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
    >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
    ...     np.zeros(2, np.int8), 0, none, 1e-2)
    >>> leaves.sides, leaves.start  # side 24 is one leaf cut along a chord, side 26 seven
    (array([24, 26]), array([0, 1, 8]))
    """

    sides: NDArray[np.int64]
    start: NDArray[np.int64]
    corners: NDArray[np.float64]
    lines: NDArray[np.float64]
    n_lines: NDArray[np.int64]
    mask: NDArray[np.uint64]
    band: NDArray[np.float64]

    @classmethod
    def empty(cls) -> Leaves:
        """Make leaves of no side.

        Returns
        -------
        Leaves
            Empty arrays of the right shapes.

        Examples
        --------
        >>> Leaves.empty().sides, Leaves.empty().corners.shape
        (array([], dtype=int64), (0, 3, 2))
        """
        return cls.of(np.zeros(0, np.int64), np.zeros(0, np.int64), _no_leaves())

    @classmethod
    def of(cls, sides: NDArray[np.int64], root: NDArray[np.int64], parts: tuple) -> Leaves:
        """Gather the leaves of sides from rows given in any order.

        Parameters
        ----------
        sides : (k,) ndarray of int64
            The sides, ascending.
        root : (m,) ndarray of int64
            Index into ``sides`` of each row's side.
        parts : tuple of ndarray
            ``corners, lines, n_lines, mask, band`` of each row (see the attributes).

        Returns
        -------
        Leaves
            The rows grouped by side.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.rays.edge_kernels import MAX_LINES
        >>> whole = np.array([[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]])
        >>> parts = (whole, np.zeros((1, MAX_LINES, 3)), np.zeros(1, np.int64), np.ones(1, np.uint64),
        ...     np.zeros(1))
        >>> leaves = Leaves.of(np.array([7]), np.array([0]), parts)  # side 7, wholly lit
        >>> leaves.start, leaves.moments().round(4)
        (array([0, 1]), array([[0.5   , 0.1667, 0.1667]]))
        """
        order = np.argsort(root, kind="stable")
        start = np.searchsorted(root[order], np.arange(len(sides) + 1)).astype(np.int64)
        return cls(sides, start, *(np.ascontiguousarray(p[order]) for p in parts))

    def moments(self) -> NDArray[np.float64]:
        """Compute the lit area and its first moments of each side, in side coordinates.

        Returns
        -------
        (k, 3) ndarray of float64
            ``(a, a w1, a w2)``; the whole side has area 1/2.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
        >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> leaves.moments().round(4)  # lit shares 2 a: 0.1 and 0.4
        array([[0.0501, 0.0053, 0.0395],
               [0.2035, 0.0955, 0.0843]])
        """
        root = np.repeat(np.arange(len(self.sides)), np.diff(self.start))
        return leaf_moments(root, self.corners, self.lines, self.n_lines, self.mask, len(self.sides))

    def find(self, sides: NDArray[np.int64]) -> NDArray[np.int64]:
        """Find the index of sides in :attr:`sides`.

        Parameters
        ----------
        sides : (n,) ndarray of int64
            Sides to look up.

        Returns
        -------
        (n,) ndarray of int64
            Index of each, -1 where it has no leaves.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
        >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> leaves.find(np.array([26, 0]))
        array([ 1, -1])
        """
        index = np.searchsorted(self.sides, sides)
        inside = index < len(self.sides)
        found = np.zeros(len(sides), dtype=bool)
        found[inside] = self.sides[index[inside]] == sides[inside]
        return np.where(found, index, -1)

    def states(self, index: NDArray[np.int64], points: NDArray[np.float64]) -> NDArray[np.int8]:
        """Say what the leaves make of points of their sides.

        Parameters
        ----------
        index : (q,) ndarray of int64
            Index into :attr:`sides` of each point's side.
        points : (q, 2) ndarray of float64
            Points ``(w1, w2)`` in side coordinates.

        Returns
        -------
        (q,) ndarray of int8
            ``LIT``, ``DARK`` or ``EITHER`` (:mod:`.leaf_kernels`).

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
        >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> leaves.states(np.array([0, 0]), np.array([[0.1, 0.1], [0.1, 0.8]]))  # DARK, LIT
        array([0, 1], dtype=int8)
        """
        return leaf_states(
            self.start,
            self.corners,
            self.lines,
            self.n_lines,
            self.mask,
            self.band,
            np.ascontiguousarray(index, dtype=np.int64),
            np.ascontiguousarray(points, dtype=np.float64),
        )

    def band_share(self) -> NDArray[np.float64]:
        """Find the share of each side's area within its chords' bands, where a chord may be wrong.

        Returns
        -------
        (k,) ndarray of float64
            Share of each side's area.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
        >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> leaves.band_share().round(4)
        array([0.0313, 0.0322])
        """
        edge = np.linalg.norm(self.corners - np.roll(self.corners, 1, axis=1), axis=2).max(axis=1)
        root = np.repeat(np.arange(len(self.sides)), np.diff(self.start))
        return 2.0 * np.bincount(root, weights=self.band * edge, minlength=len(self.sides))

    def replaced(self, other: Leaves) -> Leaves:
        """Replace the leaves of the sides of another set by theirs.

        Parameters
        ----------
        other : Leaves
            Leaves of some sides, which replace these leaves' of the same sides.

        Returns
        -------
        Leaves
            Leaves of the union of the sides; these leaves when ``other`` is empty.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
        >>> leaves = resolve_sides(Caster(craft, direction), np.array([24, 26]), np.array([False, False]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> more = resolve_sides(Caster(craft, direction), np.array([26, 28]), np.array([False, True]),
        ...     np.zeros(2, np.int8), 0, none, 1e-2)
        >>> leaves.replaced(more).sides, leaves.replaced(Leaves.empty()) is leaves
        (array([24, 26, 28]), True)
        """
        if not len(other.sides):
            return self
        keep = ~np.isin(self.sides, other.sides)
        rows = np.repeat(keep, np.diff(self.start))
        root = np.concatenate(
            [np.repeat(self.sides, np.diff(self.start))[rows], np.repeat(other.sides, np.diff(other.start))]
        )
        sides = np.union1d(self.sides[keep], other.sides)
        parts = (
            np.concatenate([getattr(self, f)[rows], getattr(other, f)])
            for f in ("corners", "lines", "n_lines", "mask", "band")
        )
        return Leaves.of(sides, np.searchsorted(sides, root), tuple(parts))


def _no_leaves() -> tuple:
    return (
        np.zeros((0, 3, 2)),
        np.zeros((0, MAX_LINES, 3)),
        np.zeros(0, np.int64),
        np.zeros(0, np.uint64),
        np.zeros(0),
    )


def depths(tolerance: float) -> NDArray[np.int64]:
    """Find the split depths (uniform, mixed, most) of :func:`~.node_kernels.classify_nodes` for a tolerance.

    A node at depth ``d`` holds ``4**-d`` of its side.

    Parameters
    ----------
    tolerance : float
        Share of a side's area its lit part is found to, in (0, 1).

    Returns
    -------
    (3,) ndarray of int64
        Depths ``d, d, d + MOST_EXTRA_DEPTH`` with ``d = max(1, ceil(log4(1 / tolerance)))``.

    Examples
    --------
    >>> depths(1e-3), depths(0.5)
    (array([ 5,  5, 10]), array([1, 1, 6]))
    """
    depth = max(1, math.ceil(math.log(1 / tolerance, 4)))
    return np.array([depth, depth, depth + MOST_EXTRA_DEPTH], dtype=np.int64)


def resolve_sides(
    caster: Caster,
    sides: NDArray[np.int64],
    centre_lit: NDArray[np.bool_],
    flags: NDArray[np.int8],
    floor: int,
    segments: Segments,
    tolerance: float,
) -> Leaves:
    """Resolve the lit part of sides into :class:`Leaves`, each to ``tolerance`` of its area.

    Each round casts one batch: the points of the nodes being decided and the next bisection points of
    every chord still being located.

    Parameters
    ----------
    caster : Caster
        Casts the rays and counts them.
    sides : (n,) ndarray of int64
        The sides, ascending.
    centre_lit : (n,) ndarray of bool
        State of each side's centroid ray.
    flags : (n,) ndarray of int8
        Node flags of each root (:mod:`.node_kernels`).
    floor : int
        Depth every side is split to before anything else (0 but in the fallback).
    segments : Segments
        The outline segments.
    tolerance : float
        Share of a side's area its lit part is found to.

    Returns
    -------
    Leaves
        The leaves of ``sides``.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> caster = Caster(craft, direction)
    >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
    >>> leaves = resolve_sides(caster, np.array([24]), np.array([False]), np.zeros(1, np.int8), 0, none, 1e-2)
    >>> round(2 * float(leaves.moments()[0, 0]), 3), caster.rays  # lit share of side 24, rays cast
    (0.1, 26)
    """
    n = len(sides)
    corners = np.broadcast_to(_WHOLE_SIDE, (n, 3, 2)).copy()
    lit = caster.lit(np.repeat(sides, 3), corners.reshape(-1, 2)).reshape(n, 3)
    differs = (lit == ~centre_lit[:, None]).all(axis=1)
    nodes = _Nodes(
        np.arange(n),
        corners,
        lit,
        np.zeros(n, dtype=np.int64),
        (flags | np.where(differs, CENTRE_DIFFERS, 0)).astype(np.int8),
        np.full(n, floor, dtype=np.int64),
    )
    limits, steps = depths(tolerance), math.ceil(math.log2(1 / tolerance))
    leaves: list[tuple] = []
    roots: list[NDArray] = []
    chords = _Chords()
    while len(nodes.root) or chords.active():
        action, lines, n_lines, points, pattern, n_points = classify_nodes(
            sides[nodes.root],
            nodes.corners,
            nodes.lit,
            nodes.depth,
            nodes.flags,
            nodes.floor,
            segments.side,
            segments.ends,
            limits,
        )
        used = np.arange(MOST_POINTS) < n_points[:, None]
        trying, trial = chord_trials(chords.lit_end, chords.dark_end, chords.steps)
        checking, check = chords.checks()
        flat = caster.lit(
            np.concatenate(
                [
                    np.repeat(sides[nodes.root], n_points),
                    np.repeat(sides[chords.root[trying]], 2 * BISECTION_POINTS),
                    np.repeat(sides[chords.root[checking]], 2),
                ]
            ),
            np.concatenate([points[used], trial, check.reshape(-1, 2)]),
        )
        counts = np.cumsum([int(n_points.sum()), len(trial)])
        cast = np.zeros((len(nodes.root), MOST_POINTS), dtype=bool)
        cast[used] = flat[: counts[0]]
        chord_update(chords.lit_end, chords.dark_end, chords.steps, trying, flat[counts[0] : counts[1]])
        again = chords.checked(checking, flat[counts[1] :].reshape(-1, 2), limits[2])
        kind, mask, children = resolve_nodes(
            nodes.root,
            nodes.corners,
            nodes.lit,
            nodes.depth,
            nodes.flags,
            action,
            lines,
            n_lines,
            pattern,
            n_points,
            cast,
        )
        leaf = kind == 0
        roots.append(nodes.root[leaf])
        leaves.append(
            (nodes.corners[leaf], lines[leaf], n_lines[leaf], mask[leaf], np.zeros(int(leaf.sum())))
        )
        chord = kind == 3
        chords.add(nodes.take(chord), cast[chord, :3], action[chord] == CHECK, steps)
        # a corner disagreed with its cell: split, or resolved by rays alone at the depth limit
        distrusted = nodes.take(kind == 2)
        distrusted.flags |= SUSPECT
        nodes = _Nodes.joined([_Nodes(*children, nodes.floor[kind == 1].repeat(4)), distrusted, again])
    roots.append(chords.root)
    leaves.append(chords.leaves())
    parts = tuple(np.concatenate([rows[i] for rows in leaves]) for i in range(5))
    return Leaves.of(sides, np.concatenate(roots), parts)


@dataclass
class _Nodes:
    """Nodes of a round: root (index into the sides), corners, corner flags, depth, node flags and the
    depth each is split to before anything else."""

    root: NDArray[np.int64]
    corners: NDArray[np.float64]
    lit: NDArray[np.bool_]
    depth: NDArray[np.int64]
    flags: NDArray[np.int8]
    floor: NDArray[np.int64]

    def take(self, rows: NDArray) -> _Nodes:
        return _Nodes(*(getattr(self, f.name)[rows] for f in fields(self)))

    @classmethod
    def joined(cls, parts: list[_Nodes]) -> _Nodes:
        return cls(*(np.concatenate([getattr(p, f.name) for p in parts]) for f in fields(cls)))


class _Chords:
    """Chords being located: the node of each, its apex, apex state, brackets and bisection steps to
    go; once located, each is checked by a ray either side of its middle before it is kept."""

    def __init__(self) -> None:
        empty = np.zeros(0, dtype=np.int64)
        self.node = _Nodes(
            empty, np.zeros((0, 3, 2)), np.zeros((0, 3), bool), empty, empty.astype(np.int8), empty
        )
        self.apex = np.zeros((0, 2))
        self.apex_lit = np.zeros(0, dtype=bool)
        self.lit_end = np.zeros((0, 2, 2))
        self.dark_end = np.zeros((0, 2, 2))
        self.steps = np.zeros(0)
        self.checked_ok = np.zeros(0, dtype=bool)

    @property
    def root(self) -> NDArray[np.int64]:
        return self.node.root

    def active(self) -> bool:
        return bool((self.steps > 0).any() or (~self.checked_ok).any())

    def add(self, nodes: _Nodes, mid_lit: NDArray[np.bool_], started: NDArray[np.bool_], bits: int) -> None:
        """Start chords of ``nodes`` (disagreeing corners), each crossing to be located to ``bits`` less
        one per level of depth (at least 1), one fewer where the node's midpoints were cast
        (``started``): to ``2**-bits`` of the side's edge at any depth, so that the bands of the chords
        along one outline, some ``2**depth`` nodes of edge ``2**-depth``, add up to that share of the
        side's area, not ``2**depth`` times it."""
        if not len(nodes.root):
            return
        apex, apex_lit, lit_end, dark_end = start_chords(nodes.corners, nodes.lit, mid_lit, started)
        steps = np.maximum(1, bits - nodes.depth).astype(float) - started
        self._append(nodes, apex, apex_lit, lit_end, dark_end, steps)

    def _append(self, nodes, apex, apex_lit, lit_end, dark_end, steps) -> None:
        self.node = _Nodes.joined([self.node, nodes])
        self.apex = np.concatenate([self.apex, apex])
        self.apex_lit = np.concatenate([self.apex_lit, apex_lit])
        self.lit_end = np.concatenate([self.lit_end, lit_end])
        self.dark_end = np.concatenate([self.dark_end, dark_end])
        self.steps = np.concatenate([self.steps, steps])
        self.checked_ok = np.concatenate([self.checked_ok, np.zeros(len(steps), dtype=bool)])

    def checks(self) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """The chords located but not yet checked, and the two points (k, 2, 2) each is checked at."""
        checking = np.flatnonzero((self.steps <= 0) & ~self.checked_ok)
        points, needed = chord_checks(
            self.apex[checking], self.apex_lit[checking], self.lit_end[checking], self.dark_end[checking]
        )
        self.checked_ok[checking[~needed]] = True
        checking = checking[needed]
        return checking, points[needed]

    def checked(self, checking: NDArray[np.int64], flags: NDArray[np.bool_], most: int) -> _Nodes:
        """Keep the chords ``checking`` whose points' ``flags`` (k, 2) are lit on the chord's lit side and
        dark on its dark side; the others, where the shadow's edge is no one straight line, are taken
        out and returned as nodes to split (unless at depth ``most``, where they are kept)."""
        good = flags[:, 0] & ~flags[:, 1]
        deep = self.node.depth[checking] >= most
        self.checked_ok[checking[good | deep]] = True
        bad = checking[~(good | deep)]
        again = self.node.take(bad)
        again.floor = again.depth + 1
        keep = np.ones(len(self.steps), dtype=bool)
        keep[bad] = False
        self.node = self.node.take(keep)
        for name in ("apex", "apex_lit", "lit_end", "dark_end", "steps", "checked_ok"):
            setattr(self, name, getattr(self, name)[keep])
        return again

    def leaves(self) -> tuple:
        lines, n_lines, mask, band = chord_leaves(self.apex, self.apex_lit, self.lit_end, self.dark_end)
        return self.node.corners, lines, n_lines, mask, band
