"""Which first mirror beams provably escape, so that they need no ray (METHOD.md "Inter-reflection").

Coplanar sides form patches; a patch's first beams of one kind leave its box along one direction,
away from its plane, so they can meet only facets reaching off the plane on that side. The patch's
box swept along the beam is tested against a tree of boxes of the facets
(:mod:`sunwind.geometry.rays.box_tree`), going down only into nodes that reach off the plane on the
beam's side; where it misses every leaf that does, its beams escape, as a ray cast would find
(:func:`sunwind.forces.reflection.beam_kernels.escaping_patches`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.box_tree import BoxTree, box_tree
from sunwind.geometry.spacecraft import Spacecraft


@dataclass(frozen=True)
class EscapeTest:
    """Patches of coplanar sides and a tree of facet boxes, for the first mirror beams' escape test.

    Read by :func:`sunwind.forces.reflection.beam_kernels.escaping_patches`. Patches hold up to
    ``_PATCH_SIDES`` sides of one plane, with their box [m] grown by ``_margin`` and their plane; the
    tree's boxes are tight round the facets.

    Parameters
    ----------
    side_patch : (n_sides,) int64
        Patch of each side, -1 for none.
    patch_low, patch_high : (n_patches, 3) float64
        Corners of each patch's grown box [m].
    patch_normal : (n_patches, 3) float64
        Unit normal of each patch's plane.
    patch_offset : (n_patches,) float64
        ``n . x`` of each patch's plane [m].
    tree : BoxTree
        Tree of the facets' boxes.
    margin_m : float
        Growth of the nodes' boxes for the sweep [m], as ``_margin``.
    reach_m : float
        A node reaches off a plane where its box does by more than this [m].

    Examples
    --------
    The two triangles of each face of a cube make one patch:

    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> test = escape_test(craft)
    >>> len(test.patch_offset), sorted(test.side_patch.tolist()) == sorted(list(range(6)) * 2)
    (6, True)
    """

    side_patch: NDArray[np.int64]  # (n_sides,) patch of each side, -1 for none
    patch_low: NDArray[np.float64]  # (n_patches, 3)
    patch_high: NDArray[np.float64]  # (n_patches, 3)
    patch_normal: NDArray[np.float64]  # (n_patches, 3) unit normal of the plane
    patch_offset: NDArray[np.float64]  # (n_patches,) ``n . x`` of the plane [m]
    tree: BoxTree
    margin_m: float  # growth of the nodes' boxes for the sweep, as ``_margin``
    reach_m: float  # a node reaches off a plane where its box does by more than this


#: Most sides in a patch whose first beams are tested for escape together.
_PATCH_SIDES = 64
#: Sides within this share of the origin offset of one plane form patches; facets reach off a
#: patch's plane where they rise more than ``_REACH`` offsets from it (rays start one offset off).
_FLAT, _REACH = 0.1, 0.5


def escape_test(craft: Spacecraft) -> EscapeTest:
    """Escape test of ``craft``, built once (~0.5 s for 10^5 facets) and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    EscapeTest
        Its patches of coplanar sides and the tree of its facet boxes.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> escape_test(craft) is escape_test(craft)
    True
    """
    return craft.cache.get("beam escape test", lambda: _escape_test(craft))


def _escape_test(craft: Spacecraft) -> EscapeTest:
    side_patch, low, high, normal, offset = _patches(craft)
    return EscapeTest(
        side_patch=side_patch,
        patch_low=low,
        patch_high=high,
        patch_normal=normal,
        patch_offset=offset,
        tree=box_tree(craft.triangles),
        margin_m=_margin(craft),
        reach_m=_REACH * craft.scene.offset_m,
    )


def _margin(craft: Spacecraft) -> float:
    """Growth of the escape test's boxes [m]: the origin offset, and the float32 round-off of the
    scene with room to spare."""
    return craft.scene.offset_m + 1e-6 * craft.scene.half_size


def _halves(points: NDArray[np.float64], members: NDArray[np.int64], depth: int) -> list[NDArray[np.int64]]:
    """``members`` split ``depth`` times in two at the median of their ``points`` along the longest
    extent: ``2**depth`` sets, in the left-to-right order of the binary tree."""
    parts = [members]
    for _ in range(depth):
        halves = []
        for part in parts:
            p = points[part]
            order = part[np.argsort(p[:, np.argmax(np.ptp(p, axis=0))], kind="stable")]
            halves += [order[: len(order) // 2], order[len(order) // 2 :]]
        parts = halves
    return parts


def _bounds(craft: Spacecraft, facets: NDArray[np.int64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Box of ``facets`` grown by the margin [m]."""
    corners = craft.triangles[facets].reshape(-1, 3)
    return corners.min(axis=0) - _margin(craft), corners.max(axis=0) + _margin(craft)


def _patches(craft: Spacecraft) -> tuple[NDArray, NDArray, NDArray, NDArray, NDArray]:
    """Patches of coplanar sides facing the same way: the patch of each side (-1 for none), each
    patch's box (n_patches, 3) twice, and its plane's unit normal (n_patches, 3) and offset [m]."""
    normals = craft.side_normals
    offsets = np.einsum("nd,nd->n", normals, craft.side_centroids)
    flat = _FLAT * craft.scene.offset_m
    key = np.column_stack([np.round(normals * 1e9), np.round(offsets / flat)])
    _, group = np.unique(key, axis=0, return_inverse=True)
    order = np.argsort(group.reshape(-1), kind="stable")
    runs = np.split(order, np.flatnonzero(np.diff(group.reshape(-1)[order])) + 1)
    side_patch = np.full(craft.n_sides, -1, dtype=np.int64)
    low, high, patch_normal, patch_offset = [], [], [], []
    for run in runs:
        if len(run) < 2:
            continue
        depth = int(np.ceil(np.log2(len(run) / _PATCH_SIDES))) if len(run) > _PATCH_SIDES else 0
        for patch in _halves(craft.side_centroids, run, depth):
            corners = craft.triangles[craft.side_facet[patch]].reshape(-1, 3)
            n, c = normals[patch[0]], offsets[patch[0]]
            if np.abs(corners @ n - c).max() > flat:  # not one plane after all
                continue
            side_patch[patch] = len(low)
            box = _bounds(craft, craft.side_facet[patch])
            low.append(box[0])
            high.append(box[1])
            patch_normal.append(n)
            patch_offset.append(c)
    return (
        side_patch,
        np.reshape(low, (-1, 3)),
        np.reshape(high, (-1, 3)),
        np.reshape(patch_normal, (-1, 3)),
        np.asarray(patch_offset, dtype=np.float64),
    )
