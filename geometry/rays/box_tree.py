"""A bounding-box tree of a model's triangles, for conservative tests of whole groups of rays.

Embree answers ray queries; some questions are about a bundle of rays at once (does anything lie in
the box a patch of sides sweeps along a direction?), and a tree of tight boxes answers them without
casting a ray. The tree is binary and split by the surface-area heuristic over binned centroids, so
a flat piece of a face and a strut standing on it end up in different boxes: a median split would
put them in one box that reaches off the face.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

#: Leaves hold at most this many triangles.
LEAF_TRIANGLES = 16
#: Centroid bins per axis tried for each split.
_BINS = 16


@dataclass(frozen=True)
class BoxTree:
    """Binary tree of tight boxes round triangles [m]; node 0 is the root.

    Attributes
    ----------
    low, high : (n_nodes, 3) float64
        Corners of each node's box.
    first_child : (n_nodes,) int64
        The node's children are ``first_child`` and ``first_child + 1``; -1 for a leaf.
    order, span : (n,) and (n_nodes, 2) int64
        The triangles under node ``k`` are ``order[span[k, 0]:span[k, 1]]``.
    depth : int
        Most edges from the root to a leaf.

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> tree = box_tree(box().vertices[box().faces], leaf_triangles=4)
    >>> tree.first_child[:3].tolist(), tree.depth, tree.span[0].tolist()
    ([1, 3, -1], 4, [0, 12])
    """

    low: NDArray[np.float64]
    high: NDArray[np.float64]
    first_child: NDArray[np.int64]
    order: NDArray[np.int64]
    span: NDArray[np.int64]
    depth: int


def box_tree(triangles: NDArray[np.float64], leaf_triangles: int = LEAF_TRIANGLES) -> BoxTree:
    """Build the :class:`BoxTree` of a set of triangles.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray of float64
        Triangle corners [m], ``n >= 1``.
    leaf_triangles : int, optional
        Most triangles in a leaf.

    Returns
    -------
    BoxTree
        The tree; node 0 is the root and holds every triangle.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.meshes import box
    >>> tree = box_tree(box().vertices[box().faces], leaf_triangles=4)
    >>> tree.low[0], tree.high[0]
    (array([-0.5, -0.5, -0.5]), array([0.5, 0.5, 0.5]))
    >>> leaves = tree.first_child == -1
    >>> int((tree.span[leaves, 1] - tree.span[leaves, 0]).max())
    4
    """
    low, high, first_child, order, span, depth = _build(
        np.ascontiguousarray(triangles.min(axis=1)),
        np.ascontiguousarray(triangles.max(axis=1)),
        np.ascontiguousarray(triangles.mean(axis=1)),
        max(1, leaf_triangles),
    )
    return BoxTree(low, high, first_child, order, span, int(depth))


@numba.njit(cache=True)
def _area(low: NDArray[np.float64], high: NDArray[np.float64]) -> float:
    """Surface area of a box (0 for an empty one, whose ``low`` exceeds its ``high``)."""
    dx, dy, dz = high[0] - low[0], high[1] - low[1], high[2] - low[2]
    if dx < 0.0 or dy < 0.0 or dz < 0.0:
        return 0.0
    return 2.0 * (dx * dy + dy * dz + dz * dx)


@numba.njit(cache=True)
def _best_split(
    members: NDArray[np.int64],
    low: NDArray[np.float64],
    high: NDArray[np.float64],
    centre: NDArray[np.float64],
) -> tuple[int, float, float]:
    """Axis, centroid range start and bin width of the cheapest binned split of ``members`` by the
    surface-area heuristic (count times box area, summed over both halves); axis -1 where all
    centroids share one bin on every axis."""
    best_axis, best_cost, best_start, best_width = -1, np.inf, 0.0, 0.0
    for axis in range(3):
        start, stop = np.inf, -np.inf
        for i in members:
            start, stop = min(start, centre[i, axis]), max(stop, centre[i, axis])
        width = (stop - start) / _BINS
        if not width > 0.0:
            continue
        counts = np.zeros(_BINS, dtype=np.int64)
        bin_low = np.full((_BINS, 3), np.inf)
        bin_high = np.full((_BINS, 3), -np.inf)
        for i in members:
            b = min(int((centre[i, axis] - start) / width), _BINS - 1)
            counts[b] += 1
            for a in range(3):
                bin_low[b, a] = min(bin_low[b, a], low[i, a])
                bin_high[b, a] = max(bin_high[b, a], high[i, a])
        left_cost = np.zeros(_BINS)
        box_low, box_high = np.full(3, np.inf), np.full(3, -np.inf)
        n = 0
        for b in range(_BINS - 1):
            n += counts[b]
            box_low, box_high = np.minimum(box_low, bin_low[b]), np.maximum(box_high, bin_high[b])
            left_cost[b] = n * _area(box_low, box_high)
        box_low, box_high = np.full(3, np.inf), np.full(3, -np.inf)
        n = 0
        for b in range(_BINS - 1, 0, -1):
            n += counts[b]
            box_low, box_high = np.minimum(box_low, bin_low[b]), np.maximum(box_high, bin_high[b])
            cost = left_cost[b - 1] + n * _area(box_low, box_high)
            if n < len(members) and cost < best_cost:
                best_axis, best_cost, best_start, best_width = axis, cost, start, width * b
    return best_axis, best_start, best_width


@numba.njit(cache=True)
def _build(
    low: NDArray[np.float64], high: NDArray[np.float64], centre: NDArray[np.float64], leaf_triangles: int
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.int64], NDArray[np.int64], NDArray[np.int64], int
]:
    """Tree of the boxes ``low``..``high`` (n, 3) with centroids ``centre``: node boxes, first
    children, order, spans and depth (see :class:`BoxTree`)."""
    n = low.shape[0]
    order = np.arange(n)
    most = 2 * n
    node_low, node_high = np.empty((most, 3)), np.empty((most, 3))
    first_child = np.full(most, -1, dtype=np.int64)
    span, level = np.zeros((most, 2), np.int64), np.zeros(most, np.int64)
    span[0, 1] = n
    pending = [0]
    count, depth = 1, 0
    while len(pending):
        k = pending.pop()
        members = order[span[k, 0] : span[k, 1]]
        for a in range(3):
            node_low[k, a] = low[members, a].min()
            node_high[k, a] = high[members, a].max()
        depth = max(depth, level[k])
        if len(members) <= leaf_triangles:
            continue
        axis, start, width = _best_split(members, low, high, centre)
        split = 0
        if axis >= 0:
            left = centre[members, axis] < start + width
            split = int(left.sum())
            members[:] = np.concatenate((members[left], members[~left]))
        if split == 0 or split == len(members):  # centroids too close to bin: halves in order
            split = len(members) // 2
        first_child[k] = count
        span[count, 0], span[count, 1] = span[k, 0], span[k, 0] + split
        span[count + 1, 0], span[count + 1, 1] = span[k, 0] + split, span[k, 1]
        level[count] = level[count + 1] = level[k] + 1
        pending.append(count)
        pending.append(count + 1)
        count += 2
    return node_low[:count], node_high[:count], first_child[:count], order, span[:count], depth
