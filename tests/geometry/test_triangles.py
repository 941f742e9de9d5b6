"""Triangle maths and the subdivision quadrature."""

import numpy as np
import pytest

from sunwind.geometry import triangles as tri


def test_level_one_is_the_centroid():
    assert np.allclose(tri.subdivision_barycentric(1), 1 / 3)


@pytest.mark.parametrize("level", [2, 3, 5, 8])
def test_stratified_points_lie_one_in_each_congruent_sub_triangle(level):
    bary = tri.subdivision_barycentric(level)
    corners = tri._sub_triangles(level)
    assert bary.shape == (level**2, 3) and np.allclose(bary.sum(axis=1), 1.0)
    # each sub-triangle has area 1 / level^2 of the whole and holds its own point
    edges = np.stack([corners[:, 1, 1:] - corners[:, 0, 1:], corners[:, 2, 1:] - corners[:, 0, 1:]], axis=2)
    # in the (w1, w2) plane the whole triangle has area 1/2
    assert np.allclose(np.abs(np.linalg.det(edges)) / 2, 0.5 / level**2)
    local = np.linalg.solve(edges, (bary[:, 1:] - corners[:, 0, 1:])[..., None])[..., 0]
    assert (local >= 0).all() and (local.sum(axis=1) <= 1).all()
    assert tri.subdivision_barycentric(level) is bary  # kept, and the same on every call


def test_stratified_estimate_of_a_cut_triangle_is_unbiased_and_converges():
    # share of the unit right triangle on one side of a line at an angle to every row of points
    corners = np.array([[[0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0]]])
    normal, offset = np.array([np.cos(0.3), np.sin(0.3)]), 0.4
    # exact share by fine polygon clipping of the triangle with the half-plane, on a dense grid
    g = (np.arange(4000) + 0.5) / 4000
    x, y = np.meshgrid(g, g)
    inside = x + y < 1
    exact = np.mean((x * normal[0] + y * normal[1] < offset)[inside])
    errors = []
    for level in (4, 16, 64):
        p = tri.sample_points(corners, level)[0, :, :2]
        errors.append(abs(np.mean(p @ normal < offset) - exact))
    assert errors[2] < errors[0] and errors[2] < 2e-3


def test_volume_and_centroid_of_an_offset_box():
    import trimesh

    box = trimesh.creation.box(extents=[1.0, 2.0, 3.0])
    box.apply_translation([0.5, -1.0, 2.0])
    corners = box.vertices[box.faces]
    assert np.isclose(tri.signed_volume(corners), 6.0)
    assert np.allclose(tri.volume_centroid(corners), [0.5, -1.0, 2.0])
    assert np.isclose(tri.signed_volume(corners[:, ::-1]), -6.0)
