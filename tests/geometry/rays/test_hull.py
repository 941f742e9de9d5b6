"""Sides on convex hulls and part boxes: the rays they clear really meet nothing."""

from __future__ import annotations

import numpy as np
import pytest

from sunwind import meshes
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.clear_kernels import may_be_blocked
from sunwind.geometry.rays.hull import HULL_TOLERANCE, MAX_PARTS, clearance, supporting_planes
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.meshes.samples import sample_spacecraft

MATERIAL = Material("m", 0.3, 0.5)


def craft_of(mesh, two_sided=()):
    return build_spacecraft(mesh, uniform=MATERIAL, two_sided=two_sided)


def brute_force(points, normals, anchors, tolerance):
    """No point more than ``tolerance`` in front of each plane, by testing every point."""
    heights = normals @ points.T - np.einsum("ij,ij->i", normals, anchors)[:, None]
    return heights.max(axis=1) <= tolerance


@pytest.fixture(scope="module")
def sample():
    return build_spacecraft(sample_spacecraft(5_000))


@pytest.mark.parametrize("flat", [False, True])
@pytest.mark.parametrize("seed", range(3))
def test_supporting_planes_match_brute_force(seed, flat):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(300, 3)) * [1.0, 2.0, 0.0 if flat else 0.5]
    points = points @ np.linalg.qr(rng.normal(size=(3, 3)))[0] + [1.0, -2.0, 3.0]  # a tilted plane
    normals = rng.normal(size=(500, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    # planes through a point of each: the highest point along the normal supports, others do not
    highest = points[np.argmax(normals @ points.T, axis=1)]
    anchors = np.where(rng.random((500, 1)) < 0.5, highest, points[rng.integers(0, 300, 500)])
    expected = brute_force(points, normals, anchors, 1e-9)
    assert expected.any() and not expected.all()
    assert np.array_equal(supporting_planes(points, 1e-9, normals, anchors), expected)


def test_sample_spacecraft_hull_sides_match_brute_force(sample):
    points = sample.vertices
    tolerance = HULL_TOLERANCE * np.ptp(points, axis=0).max()
    expected = brute_force(points, sample.side_normals, sample.side_centroids, tolerance)
    clear = clearance(sample)
    assert np.array_equal(clear.open_sky, expected)
    assert 0 < expected.sum() < sample.n_sides
    assert np.all(clear.own_part_clear[clear.open_sky])


@pytest.mark.parametrize(
    "mesh, two_sided",
    [
        (primitives.sphere(1.0, subdivisions=12), ()),
        (primitives.box((1.0, 2.0, 0.5), divisions=3), ()),
        (primitives.cylinder(0.5, 1.5, segments=32), ()),
        (primitives.plate(1.0, 2.0, 4), ("*",)),  # flat: the joggled hull
        (
            MeshData(np.eye(3), np.array([[0, 1, 2]]), np.zeros(1, np.int32), ("p",), -np.ones(1, np.int32)),
            ("*",),
        ),
    ],
    ids=["sphere", "box", "cylinder", "plate", "triangle"],
)
def test_every_side_of_a_convex_body_or_sheet_is_open(mesh, two_sided):
    assert clearance(craft_of(mesh, two_sided)).open_sky.all()


def test_part_hulls_and_boxes(sample):
    clear = clearance(sample)
    part = sample.facet_part[sample.side_facet]
    parts = np.unique(part)
    assert clear.box_low.shape == (len(parts), 3) and clear.blockers.shape == (sample.n_sides, len(parts))
    for box, name in enumerate(parts):
        sides = np.flatnonzero(part == name)
        corners = sample.scene.to_scene(sample.triangles[sample.facet_part == name]).reshape(-1, 3)
        assert np.all(corners >= clear.box_low[box]) and np.all(corners <= clear.box_high[box])
        assert not clear.blockers[sides, box].any()  # the own part is covered by own_part_clear
        points = sample.vertices[np.unique(sample.faces[sample.facet_part == name])]
        tolerance = HULL_TOLERANCE * np.ptp(points, axis=0).max()
        own = brute_force(points, sample.side_normals[sides], sample.side_centroids[sides], tolerance)
        assert np.array_equal(clear.own_part_clear[sides], own | clear.open_sky[sides])
    assert clear.own_part_clear.sum() > clear.open_sky.sum()


def test_a_model_of_many_parts_is_cleared_by_its_hull_only():
    boxes = [
        meshes.label(meshes.transform(primitives.box((0.5, 0.5, 0.5)), translation=(k, 0.0, 0.0)), f"b{k}")
        for k in range(MAX_PARTS + 1)
    ]
    craft = craft_of(MeshData.concatenate(boxes))
    clear = clearance(craft)
    assert clear.blockers.shape == (craft.n_sides, 0)
    assert np.array_equal(clear.own_part_clear, clear.open_sky)
    assert 0 < clear.open_sky.sum() < craft.n_sides


@pytest.mark.parametrize("seed", range(3))
def test_rays_found_clear_meet_nothing(sample, seed):
    """From every side, a random direction into its open hemisphere: Embree never finds a hit on a ray
    the clearance tests call clear, and most rays are decided without Embree."""
    rng = np.random.default_rng(seed)
    normals = sample.side_normals
    directions = rng.normal(size=(sample.n_sides, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    directions *= np.sign(np.einsum("ij,ij->i", directions, normals))[:, None]
    directions = directions.astype(np.float32)
    sides = np.arange(sample.n_sides)
    origins = side_sampler(sample).origins(2)
    clear = clearance(sample)
    arrays = (clear.open_sky, clear.own_part_clear, clear.blockers, clear.box_low, clear.box_high)
    maybe = np.empty((sample.n_sides, 1, origins.shape[1]), dtype=bool)
    may_be_blocked(sides, origins, directions[:, None], normals, arrays, maybe, 0, sample.n_sides)
    hit = sample.scene.occluded(origins.reshape(-1, 3), np.repeat(directions, origins.shape[1], axis=0))
    assert not np.any(hit & ~maybe.reshape(-1))
    assert 0.5 < np.mean(~maybe) and hit.any()


@pytest.mark.parametrize("seed", range(3))
def test_rays_along_shared_directions_found_clear_meet_nothing(sample, seed):
    """The same for directions every side casts along, tested first by the boxes' projections."""
    rng = np.random.default_rng(seed)
    directions = rng.normal(size=(3, 3))
    directions = (directions / np.linalg.norm(directions, axis=1)[:, None]).astype(np.float32)
    clear = clearance(sample)
    arrays = (clear.open_sky, clear.own_part_clear, clear.blockers, clear.box_low, clear.box_high)
    sides = np.arange(sample.n_sides)
    origins = side_sampler(sample).origins(2)
    maybe = np.empty((sample.n_sides, 3, origins.shape[1]), dtype=bool)
    may_be_blocked(sides, origins, directions[None], sample.side_normals, arrays, maybe, 0, sample.n_sides)
    for j, direction in enumerate(directions):
        facing = sample.side_normals @ direction > 0
        hit = sample.scene.occluded(origins[facing].reshape(-1, 3), np.tile(direction, (4 * facing.sum(), 1)))
        assert not np.any(hit & ~maybe[facing, j].reshape(-1))
        assert 0.5 < np.mean(~maybe[facing, j]) and hit.any()
