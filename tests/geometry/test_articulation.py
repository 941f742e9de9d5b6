"""Hinges: their ``[articulation]`` tables, binding them to parts, turning parts, and the angle laws."""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest
import tomllib
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from helpers import quad_sheet
from sunwind.geometry.articulation import Hinge, rotation, schedule_angle, tracking_angle, turned
from sunwind.geometry.errors import InputError, MaterialError
from sunwind.geometry.materials import load_materials, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft, pose
from sunwind.geometry.views.sky import open_sky
from sunwind.geometry.views.view_factors import view_factors
from sunwind.meshes import sample_spacecraft
from sunwind.meshes.primitives import box
from sunwind.meshes.samples import materials_toml

PAINT = "[materials.w]\nreflectivity = 0.5\nspecular_fraction = 0.5\n"
#: A closed bus and two sheets: ``wing`` (front -z) and ``flap`` (front +x, sharing an edge with ``wing``).
PARTS = '[parts]\n"wing" = { front = "w" }\n"flap" = { front = "w" }\n"bus" = "w"\n'


def craft_with(articulation: str, source: str = "m.toml"):
    """The bus, wing and flap with the ``[articulation]`` tables ``articulation``."""
    bus = replace(box((1.0, 1.0, 1.0)), part_names=("bus",))
    wing = quad_sheet(np.array([[0, 1, 0], [1, 1, 0], [1, 3, 0], [0, 3, 0.0]]), "wing", 2)
    flap = quad_sheet(np.array([[1, 1, 0], [1, 1, 1], [1, 3, 1], [1, 3, 0.0]]), "flap", 1)
    mesh = MeshData.concatenate([bus, wing, flap])
    return build_spacecraft(mesh, parse_materials(tomllib.loads(PAINT + PARTS + articulation), source))


def hinge(body: str, name: str = "wing") -> str:
    return f'[articulation."{name}"]\n{body}\n'


AXIS_Y = "axis = [0, 1, 0]\norigin_m = [0.5, 0, 0.25]\n"


# ------------------------------------------------------------------------------------------- the file
def test_good_tables_parse_with_axis_and_front_normalised():
    text = (
        '[articulation."wing_*"]\naxis = [0, 2, 0]\norigin_m = [0, 0.8, 0]\nangle_deg = 30\n'
        '[articulation.dish]\naxis = [1, 0, 0]\norigin_m = [0, 0, 1]\ntrack = "sun"\nfront = [0, 0, 3]\n'
        "[articulation.boom]\naxis = [0, 0, 1]\norigin_m = [0, 0, 0]\nschedule = [[0, 0], [3600, 90]]\n"
    )
    wings, dish, boom = parse_materials(tomllib.loads(text)).hinges
    assert wings == Hinge("wing_*", (0.0, 1.0, 0.0), (0.0, 0.8, 0.0), angle_deg=30.0)
    assert (dish.law, dish.track, dish.front) == ("track", "sun", (0.0, 0.0, 1.0))
    assert (boom.law, boom.schedule) == ("schedule", ((0.0, 0.0), (3600.0, 90.0)))
    assert wings.fixed_at(5).law == "fixed" and dish.fixed_at(5) == replace(dish, angle_deg=5.0, track=None)


LAW = "axis = [0, 1, 0]\norigin_m = [0, 0, 0]\n"


@pytest.mark.parametrize(
    "body, expected",
    [
        (LAW + "angle_deg = 1\nspeed = 2", "has unknown key 'speed'"),
        ("origin_m = [0, 0, 0]\nangle_deg = 1", "lacks 'axis'"),
        ("axis = [0, 1, 0]\nangle_deg = 1", "lacks 'origin_m'"),
        ("axis = [0, 0, 0]\norigin_m = [0, 0, 0]\nangle_deg = 1", "axis = [0, 0, 0] is not a direction"),
        ("axis = [0, nan, 1]\norigin_m = [0, 0, 0]\nangle_deg = 1", "axis = [0, nan, 1] is not 3 finite"),
        ("axis = [0, 1]\norigin_m = [0, 0, 0]\nangle_deg = 1", "axis = [0, 1] is not 3 finite numbers"),
        ("axis = [0, 1, 0]\norigin_m = 'here'\nangle_deg = 1", "origin_m = 'here' is not 3 finite"),
        (LAW, "has no angle"),
        (LAW + 'angle_deg = 1\ntrack = "sun"', "has angle_deg and track"),
        (LAW + "angle_deg = inf", "angle_deg = inf is not a finite number"),
        (LAW + "angle_deg = '30'", "angle_deg = '30' is not a finite number"),
        (LAW + 'track = "moon"', "track = 'moon' is not a target"),
        (LAW + "schedule = [[0, 0], [60, 5], [60, 9]]", "times do not increase (t = 60 s after t = 60 s)"),
        (LAW + "schedule = [[0, 0], [-1, 5]]", "times do not increase"),
        (LAW + "schedule = [[0, 0, 1]]", "is not [time_s, angle_deg] pairs"),
        (LAW + "schedule = []", "is not [time_s, angle_deg] pairs"),
        (LAW + "angle_deg = 3\nfront = [1, 0, 0]", 'front is for track = "sun" only'),
        (LAW + 'track = "sun"\nfront = [0, 0, 0]', "front = [0, 0, 0] is not a direction"),
    ],
)
def test_bad_tables_fail_with_one_line_naming_the_file_and_the_hinge(tmp_path, body, expected):
    path = tmp_path / "materials.toml"
    path.write_text(PAINT + hinge(body, "wing_*"))
    with pytest.raises(MaterialError) as error:
        load_materials(path)
    message = str(error.value)
    assert expected in message and str(path) in message and '[articulation] "wing_*"' in message
    assert "\n" not in message


def test_every_bad_table_is_listed_at_once_with_the_other_problems():
    text = "[articulation]\na = 1\n" + hinge("axis = [0, 0, 0]\norigin_m = [0, 0, 0]\nangle_deg = 1", "b")
    with pytest.raises(MaterialError) as error:
        parse_materials({**tomllib.loads(text), "model": {"mass": 3}}, "m.toml")
    message = str(error.value)
    assert message.startswith("m.toml: 3 problems") and "must be a table" in message and "[model]" in message


# --------------------------------------------------------------------------------------------- binding
@pytest.mark.parametrize(
    "articulation, expected",
    [
        (hinge(AXIS_Y + "angle_deg = 1", "wnig"), '"wnig" matches no part of <memory>; the parts are: bus'),
        (
            hinge(AXIS_Y + "angle_deg = 1", "*") + hinge(AXIS_Y + "angle_deg = 2"),
            "part 'wing' is turned by two",
        ),
        (
            hinge(AXIS_Y + 'track = "sun"', "bus"),
            '"bus" tracks the Sun, but the parts it turns have no front',
        ),
        (hinge("axis = [0, 0, 1]\norigin_m = [0, 0, 0]\ntrack = 'sun'"), "lies along its axis"),
    ],
)
def test_hinges_that_cannot_be_bound_are_refused(articulation, expected):
    with pytest.raises(MaterialError) as error:
        craft_with(articulation)
    assert str(error.value).startswith("m.toml: ") and expected in str(error.value)


def test_a_hinge_may_not_open_a_closed_body():
    lidded = box((1.0, 1.0, 1.0))
    normals = np.cross(
        *(lidded.vertices[lidded.faces][:, k] - lidded.vertices[lidded.faces][:, 0] for k in (1, 2))
    )
    lid = (normals[:, 2] > 0).astype(np.int32)
    mesh = replace(lidded, part_names=("tub", "lid"), face_part=lid)
    spec = parse_materials(
        tomllib.loads(PAINT + '[parts]\n"*" = "w"\n' + hinge(AXIS_Y + "angle_deg = 9", "lid"))
    )
    with pytest.raises(MaterialError, match="turns part 'lid', which closes a body with part 'tub'"):
        build_spacecraft(mesh, spec)


def test_vertices_shared_with_unturned_parts_are_split():
    plain = craft_with("")
    bound = craft_with(hinge(AXIS_Y + "angle_deg = 0", "flap"))
    assert len(bound.vertices) == len(plain.vertices) + 2  # the flap's two corners on the wing's edge
    assert np.array_equal(bound.triangles, plain.triangles)
    moved = pose(bound, bound.hinges, {"flap": 90.0})
    wing = bound.facet_part == bound.part_names.index("wing")
    assert np.array_equal(moved.triangles[wing], plain.triangles[wing])


# ------------------------------------------------------------------------------------------------ pose
@settings(max_examples=25, deadline=None)
@given(
    st.lists(st.floats(-1, 1), min_size=3, max_size=3),
    st.lists(st.floats(-3, 3), min_size=3, max_size=3),
    st.floats(-720, 720),
)
def test_a_turned_part_is_the_analytic_rotation_about_the_hinge_line(axis, origin, angle):
    assume(np.linalg.norm(axis) > 1e-3)
    axis_text = f"axis = {list(axis)}\norigin_m = {list(origin)}\nangle_deg = {angle!r}"
    craft = craft_with(hinge(axis_text))
    drawn = craft_with("")
    a = np.array(axis) / np.linalg.norm(axis)
    expected = Rotation.from_rotvec(math.radians(angle) * a).apply(drawn.triangles.reshape(-1, 3) - origin)
    wing = (craft.facet_part == craft.part_names.index("wing")).repeat(3)
    got = craft.triangles.reshape(-1, 3)
    np.testing.assert_allclose(got[wing], (expected + origin)[wing], rtol=0, atol=1e-12)
    assert np.array_equal(got[~wing], drawn.triangles.reshape(-1, 3)[~wing])
    np.testing.assert_allclose(craft.facet_areas, drawn.facet_areas, rtol=1e-12)
    # points of the hinge line stay; every point keeps its distance from the line and its place along it
    line = np.array(origin) + np.outer([-2.0, 0.0, 1.5], a)
    np.testing.assert_allclose(turned(line, np.zeros(3), craft.hinges, [angle]), line, atol=1e-12)
    offsets = got[wing] - origin
    before = drawn.triangles.reshape(-1, 3)[wing] - origin
    np.testing.assert_allclose(offsets @ a, before @ a, atol=1e-12)
    np.testing.assert_allclose(np.cross(offsets, a), np.cross(before, a) @ rotation(a, angle).T, atol=1e-12)


def test_whole_turns_move_nothing_and_every_pose_turns_from_the_mesh_as_drawn():
    craft = craft_with(hinge(AXIS_Y + "angle_deg = 0"))
    for angle in (360.0, -720.0, 0.0):
        assert np.array_equal(pose(craft, craft.hinges, {"wing": angle}).vertices, craft.vertices)
    once = pose(craft, craft.hinges, {"wing": 37.0})
    twice = pose(pose(craft, craft.hinges, {"wing": -12.0}), craft.hinges, {"wing": 37.0})
    assert np.array_equal(once.vertices, twice.vertices) and twice.articulation == {"wing": 37.0}
    assert once.cache is not craft.cache and not len(once.cache)
    assert np.array_equal(pose(once, craft.hinges, {}).vertices, craft.vertices)
    assert once.default_reference[0].tolist() == craft.default_reference[0].tolist()  # drawn: it stays
    with pytest.raises(InputError, match='angles name "flap", which is no hinge'):
        pose(craft, craft.hinges, {"flap": 1.0})
    with pytest.raises(InputError, match='hinge "wing" angle nan must be a finite number'):
        pose(craft, craft.hinges, {"wing": math.nan})


def test_the_sample_wings_turned_by_a_hinge_are_the_sample_built_turned():
    mesh = sample_spacecraft(2000)
    plain = parse_materials(tomllib.loads(materials_toml(mesh)))
    text = materials_toml(mesh) + hinge("axis = [0, 1, 0]\norigin_m = [0, 0, 0]\nangle_deg = 40", "wing_*")
    turned = build_spacecraft(mesh, parse_materials(tomllib.loads(text)))
    built = build_spacecraft(sample_spacecraft(2000, array_angle_deg=40.0), plain)
    assert np.array_equal(turned.triangles, built.triangles)
    drawn = pose(turned, turned.hinges, {"wing_*": 0.0})
    assert np.array_equal(drawn.triangles, build_spacecraft(mesh, plain).triangles)


# ------------------------------------------------------------------------------------------ angle laws
unit = (
    st.lists(st.floats(-1, 1), min_size=3, max_size=3).map(np.array).filter(lambda v: np.linalg.norm(v) > 0.1)
)


def angle_between(u: np.ndarray, v: np.ndarray) -> float:
    return math.atan2(np.linalg.norm(np.cross(u, v)), u @ v)


@settings(max_examples=200, deadline=None)
@given(unit, unit, unit, st.booleans())
def test_tracking_turns_the_front_as_close_to_the_sun_as_the_hinge_allows(axis, front, sun, across):
    a, s, n0 = axis / np.linalg.norm(axis), sun / np.linalg.norm(sun), front / np.linalg.norm(front)
    assume(np.linalg.norm(n0 - (n0 @ a) * a) > 1e-3 and np.linalg.norm(s - (s @ a) * a) > 1e-3)
    n0 = n0 - (n0 @ a) * a if across else n0
    n0 = n0 / np.linalg.norm(n0)
    theta = tracking_angle(axis, n0, sun)
    tracked = rotation(a, theta) @ n0
    # the best achievable: the front sweeps a cone about the axis; for a front across the axis, the
    # angle between the Sun and the hinge plane
    best = abs(angle_between(n0, a) - angle_between(s, a))
    assert angle_between(tracked, s) == pytest.approx(best, abs=1e-7)
    if across:
        assert angle_between(tracked, s) == pytest.approx(math.asin(min(1.0, abs(a @ s))), abs=1e-7)
    others = np.array([rotation(a, t) @ n0 for t in np.linspace(-180, 180, 73)])
    assert np.all(others @ s <= tracked @ s + 1e-12)


def test_a_sun_along_the_axis_keeps_the_angle_at_zero_and_says_so():
    with pytest.warns(UserWarning, match="along a tracking hinge's axis"):
        assert tracking_angle([0, 1, 0], [1, 0, 0], [0, -2, 0]) == 0.0


def test_a_schedule_is_linear_between_its_points_and_held_outside():
    boom = Hinge(
        "boom", (0.0, 0.0, 1.0), (0.0, 0.0, 0.0), schedule=((0.0, 10.0), (100.0, 30.0), (200.0, 0.0))
    )
    times = [-50.0, 0.0, 25.0, 100.0, 150.0, 200.0, 1e9]
    assert [schedule_angle(boom, t) for t in times] == [10.0, 10.0, 15.0, 30.0, 15.0, 0.0, 0.0]
    with pytest.raises(InputError, match="time_s nan must be a finite number"):
        schedule_angle(boom, math.nan)


# -------------------------------------------------------------------------------------- disk caches
def test_a_posed_model_never_reads_the_disk_cache_of_another_pose(tmp_path):
    craft = craft_with(hinge(AXIS_Y + "angle_deg = 0"))
    first, other = (pose(craft, craft.hinges, {"wing": angle}) for angle in (0.0, 60.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no stale entry read, rebuilt or warned of
        for compute, share in ((view_factors, "escape_fraction"), (open_sky, "blocked_fraction")):
            a, b = (compute(c, 16, cache_dir=tmp_path) for c in (first, other))
            assert a.origin.startswith("computed") and b.origin.startswith("computed")
            again = compute(pose(other, craft.hinges, {"wing": 0.0}), 16, cache_dir=tmp_path)
            assert again.origin.startswith("cache ") and again.origin.removeprefix("cache ") in a.origin
            assert np.array_equal(getattr(again, share), getattr(a, share))
            assert not np.array_equal(getattr(a, share), getattr(b, share))
    assert len(list(tmp_path.glob("view_factors-*.npz"))) == len(list(tmp_path.glob("open_sky-*.npz"))) == 2
