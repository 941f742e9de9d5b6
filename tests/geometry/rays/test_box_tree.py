"""The bounding-box tree: tight boxes that nest and hold every triangle once, split where parts part."""

import numpy as np
import pytest

from sunwind.geometry.rays.box_tree import box_tree
from sunwind.meshes.primitives import cylinder, plate


def _tree_checks(triangles, leaf_triangles):
    tree = box_tree(triangles, leaf_triangles)
    leaf = tree.first_child < 0
    # the leaves' spans tile the order, which holds each triangle once
    np.testing.assert_array_equal(np.sort(tree.order), np.arange(len(triangles)))
    spans = tree.span[leaf][np.argsort(tree.span[leaf, 0])]
    assert spans[0, 0] == 0 and spans[-1, 1] == len(triangles)
    np.testing.assert_array_equal(spans[1:, 0], spans[:-1, 1])
    assert np.all(spans[:, 1] - spans[:, 0] >= 1)
    assert np.all(spans[:, 1] - spans[:, 0] <= leaf_triangles)
    # each node's box is tight round its triangles; children split their parent's span
    for k in range(len(tree.low)):
        corners = triangles[tree.order[tree.span[k, 0] : tree.span[k, 1]]].reshape(-1, 3)
        np.testing.assert_array_equal(tree.low[k], corners.min(axis=0))
        np.testing.assert_array_equal(tree.high[k], corners.max(axis=0))
        c = tree.first_child[k]
        if c >= 0:
            assert tree.span[c, 0] == tree.span[k, 0] and tree.span[c + 1, 1] == tree.span[k, 1]
            assert tree.span[c, 1] == tree.span[c + 1, 0]
    return tree


@pytest.mark.parametrize("leaf_triangles", [1, 4, 16])
def test_boxes_are_tight_and_the_leaves_hold_every_triangle_once(leaf_triangles):
    rng = np.random.default_rng(5)
    triangles = rng.uniform(-1, 1, (300, 1, 3)) + 0.05 * rng.normal(size=(300, 3, 3))
    triangles[:40] = triangles[0]  # repeated triangles share a centroid: split in order
    _tree_checks(triangles, leaf_triangles)


def test_one_triangle_is_a_leaf():
    tree = _tree_checks(np.eye(3)[None], 16)
    assert len(tree.low) == 1 and tree.depth == 0


def test_no_leaf_of_a_plate_reaches_up_a_strut_standing_on_it():
    """A median split boxes the strut's foot with the plate round it, in a box reaching 0.3 m off the
    plate's plane; the area heuristic keeps them apart: leaves holding plate triangles reach only as
    high as the strut's bottom cap, 1 mm above the plate."""
    sheet = plate(2.0, 2.0, 40)
    strut = cylinder(0.03, 0.8, segments=12, rings=8)
    standing = strut.vertices + np.array([0.1, -0.2, 0.4 + 1e-3])
    triangles = np.concatenate([sheet.vertices[sheet.faces], standing[strut.faces]])
    tree = _tree_checks(triangles, 16)
    is_strut = np.arange(len(triangles)) >= len(sheet.faces)
    holds_plate = [
        k
        for k in np.flatnonzero(tree.first_child < 0)
        if not is_strut[tree.order[tree.span[k, 0] : tree.span[k, 1]]].all()
    ]
    assert tree.high[holds_plate, 2].max() <= 1e-3 + 1e-12
