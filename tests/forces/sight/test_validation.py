"""Lines of sight against closed forms: a point behind a box is blocked exactly where the box's
projection says; blocked fractions against the solid angle of a square and a dense Monte Carlo; the
retroreflector range differences against their closed forms (METHOD.md "Lines of sight")."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import sunwind as sw
from sunwind.forces.sight import SightPoints, blocked_map, lines_of_sight, range_offsets

BLACK = sw.Material("black", 0.0, 0.0)


@pytest.fixture(scope="module")
def cube():
    return sw.load(sw.meshes.box(), uniform=BLACK, threads=2)


def _slab(point, directions, half):
    """Entry distance of rays into the box [-half, half]^3 (inf where they miss): the slab method."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = (-half - point) / directions
        t2 = (half - point) / directions
    near = np.nanmax(np.minimum(t1, t2), axis=1)
    far = np.nanmin(np.maximum(t1, t2), axis=1)
    return np.where((near <= far) & (far > 0), near, np.inf)


def _sphere(n, seed):
    d = np.random.default_rng(seed).normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def test_a_point_behind_a_box_is_blocked_exactly_where_its_projection_says(cube):
    """20 000 random directions from a point off the unit cube: blocked exactly where the ray enters
    the box (slab method), except within 1e-5 m of its edges (float32 scene), at the entry distance
    within 1e-6 m, by the part 'box'."""
    point = np.array([1.7, 0.23, -0.31])
    d = _sphere(20_000, 1)
    inner, outer = _slab(point, d, 0.5 - 1e-5), _slab(point, d, 0.5 + 1e-5)
    sure = np.isfinite(inner) == np.isfinite(outer)
    lines = lines_of_sight(cube, SightPoints.of(["p"], [point]), d)
    assert sure.sum() > 19_900
    assert np.array_equal(~lines.clear[0][sure], np.isfinite(inner)[sure])
    hit = sure & np.isfinite(inner)
    assert 0.03 < hit.mean() < 0.2
    assert np.max(np.abs(lines.distance_m[0][hit] - _slab(point, d, 0.5)[hit])) < 1e-6
    assert {lines.blocked_by(0, j) for j in np.flatnonzero(hit)} == {"box"}


def test_a_point_on_a_face_does_not_block_itself_and_one_inside_is_warned(cube):
    d = _sphere(20_000, 2)
    d = d[np.abs(d[:, 0]) > 1e-3]
    face = SightPoints.of(["on_face", "corner"], [[0.5, 0.1, -0.2], [0.5, 0.5, 0.5]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lines = lines_of_sight(cube, face, d)
    assert np.array_equal(lines.clear[0], d[:, 0] > 0)  # out of the face: clear; into it: the box
    outward = (d[:, 0] > 1e-3) & (d[:, 1] > 1e-3) & (d[:, 2] > 1e-3)
    assert lines.clear[1][outward].all()  # the octant the corner opens on
    with pytest.warns(UserWarning, match="inside a closed body"):
        inside = lines_of_sight(cube, SightPoints.of(["in"], [[0.1, 0.2, 0.0]]), d[:10])
    assert not inside.clear.any() and inside.blocked_by(0, 0) == "(inside a closed body)"


def _square_fraction(a, h):
    """Share of the sky a square of side 2a fills seen from height h above its centre."""
    return 4 * np.arcsin(a * a / (a * a + h * h)) / (4 * np.pi)


@pytest.mark.parametrize("step", [2.0, 1.0])
def test_the_blocked_fraction_matches_the_solid_angle_of_a_square_within_its_estimate(step):
    """A plate of 2 m x 2 m seen from 0.7 m above its centre fills ``4 asin(a^2 / (a^2 + h^2))`` of the
    sky's 4 pi; the estimate |F_h - F_2h| covers the error."""
    model = sw.load(sw.meshes.plate(2.0, 2.0, 4), uniform=BLACK, two_sided=["plate"], threads=2)
    points = SightPoints.of(["above"], [[0.0, 0.0, 0.7]])
    view = blocked_map(model, points, step)
    exact = _square_fraction(1.0, 0.7)
    error = abs(view.blocked_fraction[0] - exact)
    assert error <= view.error_estimate[0]
    assert error < 2e-3 * step


@pytest.fixture(scope="module")
def box_wing():
    return sw.load(sw.meshes.box_wing(), uniform=BLACK, two_sided=["wing*"], threads=2)


def _in_cone(axis, half_angle_deg, n, seed):
    """Uniform directions in a cone, by solid angle."""
    rng = np.random.default_rng(seed)
    cos_t = 1 - rng.random(n) * (1 - np.cos(np.radians(half_angle_deg)))
    phi = rng.random(n) * 2 * np.pi
    sin_t = np.sqrt(1 - cos_t**2)
    local = np.stack([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t], axis=1)
    z = axis / np.linalg.norm(axis)
    x = np.cross(z, [0.0, 0.0, 1.0] if abs(z[2]) < 0.9 else [1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    return local @ np.stack([x, np.cross(z, x), z])


#: Sensors on the box-wing: on the bus's +z face looking past a wing, on its +x face, on a wing.
SENSORS = (
    ("tilted", [0.3, 0.4, 0.5], [0.2, 0.8, 0.4], 60.0),
    ("side", [0.5, 0.1, 0.0], [1.0, 0.6, 0.3], 80.0),
    ("wide", [0.0, -0.45, 0.5], [0.0, -1.0, 0.3], 120.0),
)


@pytest.mark.parametrize("step", [2.0, 1.0])
def test_the_blocked_fraction_of_a_field_of_view_matches_a_dense_monte_carlo(box_wing, step):
    """400 000 directions uniform in each cone (sigma about 7e-4): the map's fraction within its
    estimate plus 4 sigma (measured against 4 million: worst error 7.5e-4 at 2 deg, 1.7e-4 at 1 deg)."""
    names, positions, axes, halves = zip(*SENSORS, strict=True)
    points = SightPoints.of(list(names), positions, list(axes), list(halves))
    view = blocked_map(box_wing, points, step)
    for k in range(len(names)):
        d = _in_cone(np.array(axes[k]), halves[k], 400_000, seed=k)
        lines = lines_of_sight(box_wing, SightPoints.of([names[k]], [positions[k]]), d)
        mc = 1 - lines.clear.mean()
        sigma = np.sqrt(mc * (1 - mc) / len(d))
        assert 0.05 < mc < 0.95
        assert abs(view.blocked_fraction[k] - mc) <= view.error_estimate[k] + 4 * sigma, names[k]
    assert view.error_estimate.max() < 5e-3 * step  # and not uselessly loose


def test_two_arrays_at_plus_minus_l_differ_by_2l_cos_of_the_angle():
    """Arrays at (+-L, 0, 0.5) on the top face of the unit cube, acceptance cones +z of 60 deg, station
    direction u = (cos t, 0, sin t): offsets -u.p = -+L cos t - 0.5 sin t, difference -2 L cos t; for
    t < 30 deg the station is outside both cones and neither array is seen."""
    model = sw.load(sw.meshes.box(), uniform=BLACK, threads=1)
    L = 0.4
    arrays = SightPoints.of(["plus", "minus"], [[L, 0, 0.5], [-L, 0, 0.5]], [[0, 0, 1]] * 2, [60.0] * 2)
    angles = np.radians([35.0, 60.0, 90.0, 120.0, 145.0, 20.0])
    u = np.stack([np.cos(angles), np.zeros_like(angles), np.sin(angles)], axis=1)
    ranges = range_offsets(lines_of_sight(model, arrays, u), [0.0, 0.0, 0.0])
    for j, t in enumerate(angles[:-1]):
        ((a, b, difference),) = ranges.differences(j)
        assert (a, b) == ("plus", "minus")
        assert abs(difference + 2 * L * np.cos(t)) < 1e-6
        assert abs(ranges.offset_m[0, j] - (-L * np.cos(t) - 0.5 * np.sin(t))) < 1e-12
    assert ranges.differences(5) == [] and np.isnan(ranges.offset_m[:, 5]).all()


def test_three_arrays_give_the_station_direction_where_all_are_seen():
    """Arrays at c, c + L x and c + L y on the top face: -(o_x - o_c) / L and -(o_y - o_c) / L are the
    direction's x and y components (the attitude a station measures), while all three are seen."""
    model = sw.load(sw.meshes.box(), uniform=BLACK, threads=1)
    L = 0.3
    arrays = SightPoints.of(
        ["c", "x", "y"], [[-0.1, -0.1, 0.5], [0.2, -0.1, 0.5], [-0.1, 0.2, 0.5]], [[0, 0, 1]] * 3, [70.0] * 3
    )
    u = _in_cone(np.array([0.0, 0.0, 1.0]), 65.0, 50, seed=7)
    ranges = range_offsets(lines_of_sight(model, arrays, u), [0.0, 0.0, 0.0])
    o = ranges.offset_m
    assert np.isfinite(o).all()
    assert np.max(np.abs(-(o[1] - o[0]) / L - u[:, 0])) < 1e-12
    assert np.max(np.abs(-(o[2] - o[0]) / L - u[:, 1])) < 1e-12


def test_an_array_blocked_by_another_part_is_left_out(box_wing):
    """An array on the bus's +y face looking +y sees the station past the wing (in the plane x = 0, from
    y = 1 to 4 m) on one side and not through it."""
    positions = [[0.3, 0.5, 0.3], [0.3, -0.5, 0.3]]
    arrays = SightPoints.of(["a", "b"], positions, [[0, 1, 0], [0, -1, 0]], [90, 90])
    lines = lines_of_sight(box_wing, arrays, [[-0.3, 1.0, 0.0], [0.3, 1.0, 0.0]])
    ranges = range_offsets(lines, [0.0, 0.0, 0.0])
    assert lines.blocked_by(0, 0) == "wing_right" and abs(lines.distance_m[0, 0] - np.sqrt(1.09)) < 1e-5
    assert np.isnan(ranges.offset_m[0, 0]) and np.isfinite(ranges.offset_m[0, 1])
    assert np.isnan(ranges.offset_m[1]).all()  # the station is behind array b's face
