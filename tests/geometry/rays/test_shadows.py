"""Shadow passes: no false shadows on convex bodies, exact lit shares in a partial shadow."""

import numpy as np
import pytest
import trimesh

from helpers import ABSORBER, mesh_from_trimesh, quad_sheet, shaded_floor
from sunwind.geometry.rays.certificate import CHECK_POINTS, CHECK_ROUNDS, LEAST_CHECKED
from sunwind.geometry.rays.shadows import level_for_samples, side_sampler
from sunwind.geometry.spacecraft import build_spacecraft


@pytest.mark.parametrize("samples", [None, 1, 4, 9])
def test_a_convex_body_has_no_shadow_on_any_side_facing_the_sun(samples):
    craft = build_spacecraft(mesh_from_trimesh(trimesh.creation.icosphere(3)), uniform=ABSORBER)
    rng = np.random.default_rng(11)
    for u in rng.normal(size=(5, 3)):
        u /= np.linalg.norm(u)
        light = side_sampler(craft).illuminate(u, samples)
        facing = light.cos_incidence > 0
        assert np.array_equal(light.lit_fraction, facing.astype(float))
        assert np.array_equal(np.sort(light.facing), np.flatnonzero(facing))
        if samples is None:  # a centroid ray per side and the outline's probes (all escaping); the check
            checked = light.check.rays
            assert light.check.wrong == 0
            assert facing.sum() < light.rays - checked < 2 * facing.sum()
            least = CHECK_ROUNDS * LEAST_CHECKED * CHECK_POINTS
            assert checked <= max(1.5 * least, 0.2 * (light.rays - checked))  # a Poisson draw
        else:
            assert light.rays == facing.sum() * level_for_samples(samples) ** 2


@pytest.mark.parametrize("samples, level", [(1, 1), (2, 2), (4, 2), (5, 3), (16, 4), (17, 5)])
def test_sample_counts_round_up_to_squares(samples, level):
    assert level_for_samples(samples) == level


@pytest.mark.parametrize("n", [8, 2])
@pytest.mark.parametrize("tolerance", [0.1, 1e-3])
def test_a_straight_shadow_edge_is_located_exactly_at_any_tolerance(n, tolerance):
    """The blind's shadow on the floor is a square (a closed form): the default pass cuts the sides its
    outline crosses along that outline, so lit area and lit centroid are exact to round-off, on an
    8 x 8 grid and on a 2 x 2 grid whose triangles hold the shadow's corners."""
    craft, c, h = shaded_floor(n)
    u = np.array([0.3, -0.2, 1.0])
    u /= np.linalg.norm(u)
    shift = -0.5 * u[:2] / u[2]  # the blind's shadow is the blind moved along -u onto z = 0
    lo, hi = c[:2] + shift - h, c[:2] + shift + h
    shadow = np.prod(np.clip(hi, 0, 1) - np.clip(lo, 0, 1))
    shadow_centroid = (np.clip(lo, 0, 1) + np.clip(hi, 0, 1)) / 2
    exact_centroid = (np.array([0.5, 0.5]) - shadow * shadow_centroid) / (1 - shadow)
    floor = (craft.facet_part[craft.side_facet] == craft.part_names.index("floor")) & (craft.side_sign > 0)
    light = side_sampler(craft).illuminate(u, tolerance=tolerance)
    areas = craft.side_areas[floor] * light.lit_fraction[floor]
    centroid = areas @ light.lit_centroid[floor][:, :2] / areas.sum()
    assert abs(areas.sum() - (1 - shadow)) < 1e-12
    assert np.allclose(centroid, exact_centroid, rtol=0, atol=1e-12)
    # on the fine grid only sides near the shadow edge are refined, with a few rays each
    assert n < 8 or light.rays < 10 * (light.cos_incidence > 0).sum()
    # with one sample per facet the error is that of the facet size, far larger
    coarse = side_sampler(craft).illuminate(u, samples=1)
    assert abs(craft.side_areas[floor] @ coarse.lit_fraction[floor] - (1 - shadow)) > 1e-3


def test_a_two_sided_sheet_is_lit_on_the_side_facing_the_sun():
    sheet = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float), "wing", 2)
    craft = build_spacecraft(sheet, uniform=ABSORBER, two_sided=["wing"])
    for u, lit_sign in (([0.2, 0.1, 1.0], 1), ([0.2, 0.1, -1.0], -1)):
        light = side_sampler(craft).illuminate(np.array(u) / np.linalg.norm(u))
        assert np.array_equal(light.lit_fraction, (craft.side_sign == lit_sign).astype(float))


@pytest.mark.parametrize("samples", [None, 1, 9])
def test_models_too_large_to_keep_origins_give_the_same_lit_shares(samples, monkeypatch):
    """Above ``_KEEP_POINTS`` origins are made on the fly in batches: the rays, and so the answer,
    are the same."""
    import sunwind.geometry.rays.shadows as illumination

    craft, _, _ = shaded_floor(n=6)
    u = np.array([0.2, 0.3, 1.0]) / np.linalg.norm([0.2, 0.3, 1.0])
    kept = side_sampler(craft).illuminate(u, samples)
    monkeypatch.setattr(illumination, "_KEEP_POINTS", 10)
    streamed = illumination.SideSampler(craft).illuminate(u, samples)
    assert np.array_equal(kept.lit_fraction, streamed.lit_fraction)
    assert np.allclose(kept.lit_centroid, streamed.lit_centroid, rtol=0, atol=1e-15)
    assert kept.rays == streamed.rays


def test_sampler_origins_equal_the_scene_transform_of_the_sample_points():
    """The numba origin kernel and RayScene.origins are two routes to the same float32 origins."""
    from sunwind.geometry import triangles as tri

    craft, _, _ = shaded_floor(n=3)
    sides = np.arange(craft.n_sides)
    for level in (1, 2, 5):
        points = tri.sample_points(craft.triangles[craft.side_facet], level)
        expected = craft.scene.origins(points, craft.side_normals[:, None, :])
        assert np.allclose(side_sampler(craft)._origins_of(sides, level), expected, rtol=0, atol=2e-7)
