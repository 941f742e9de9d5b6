"""Embree against the brute-force numpy twin, on the same rays."""

import numpy as np
import pytest
import trimesh

from sunwind.geometry.rays.scene import BruteForceScene, RayScene


@pytest.fixture(scope="module")
def clutter():
    """A few overlapping bodies: rays hit, graze and miss."""
    rng = np.random.default_rng(7)
    parts = []
    for k in range(4):
        body = (
            trimesh.creation.icosphere(1, radius=0.3 + 0.1 * k)
            if k % 2
            else trimesh.creation.box(extents=rng.uniform(0.2, 0.8, 3))
        )
        body.apply_translation(rng.uniform(-1, 1, 3))
        parts.append(body)
    mesh = trimesh.util.concatenate(parts)
    return mesh.vertices[mesh.faces]


@pytest.mark.parametrize("threads", ["1", "2"])
def test_embree_and_brute_force_agree(clutter, threads, monkeypatch, limit_threads):
    limit_threads(int(threads))
    embree, brute = RayScene(clutter), BruteForceScene(clutter)
    rng = np.random.default_rng(3)
    n = 40_000  # large enough to be split over threads
    origins = embree.to_scene(rng.uniform(-1.5, 1.5, (n, 3)))
    directions = rng.normal(size=(n, 3))
    directions = (directions / np.linalg.norm(directions, axis=1)[:, None]).astype(np.float32)
    hit = embree.occluded(origins, directions)
    first = embree.first_hit(origins, directions)
    check = slice(0, 3_000)
    brute_first = brute.first_hit(origins[check], directions[check])
    # rays passing within float32 round-off of an edge may differ; there are none or a handful
    brute_hit = brute.occluded(origins[check], directions[check])
    assert np.mean(hit[check] == brute_hit) > 0.999
    assert np.mean(first[check] == brute_first) > 0.999
    assert 0.05 < hit.mean() < 0.95  # a real mix of hits and misses
    assert np.array_equal(hit, first >= 0)
    assert np.array_equal(embree.clear(origins, directions), ~hit)
    assert np.array_equal(brute.clear(origins[check], directions[check]), ~brute_hit)
    facets, distance = embree.intersect(origins, directions)
    brute_facets, brute_distance = brute.intersect(origins[check], directions[check])
    assert np.array_equal(facets, first)
    both = (facets[check] >= 0) & (facets[check] == brute_facets)
    np.testing.assert_allclose(distance[check][both], brute_distance[both], rtol=1e-5, atol=1e-6)


def test_origins_are_offset_off_the_surface_so_rays_leaving_it_escape():
    sphere = trimesh.creation.icosphere(4, radius=3.0)
    corners = sphere.vertices[sphere.faces]
    scene = RayScene(corners)
    centroids = corners.mean(axis=1)
    normals = sphere.face_normals
    origins = scene.origins(centroids, normals)
    # every direction within 89.9 deg of the normal leaves a convex body
    rng = np.random.default_rng(0)
    tangent = np.cross(normals, rng.normal(size=normals.shape))
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    grazing = np.cos(np.radians(89.9)) * normals + np.sin(np.radians(89.9)) * tangent
    for directions in (normals, grazing):
        assert not scene.occluded(origins, directions.astype(np.float32)).any()
    # and rays into the body hit the far side
    assert scene.occluded(origins, (-normals).astype(np.float32)).all()
