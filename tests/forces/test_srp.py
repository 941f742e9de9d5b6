"""Solar-radiation pressure on meshes: invariances, shadowing, sheets, bad input, threads and batches."""

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from helpers import ABSORBER, MIXED, mesh_from_trimesh, quad_sheet
from sunwind.forces.batches import SrpBatch
from sunwind.forces.model import Model
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, SPEED_OF_LIGHT
from sunwind.forces.srp import srp
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft

P = SOLAR_FLUX_1AU / SPEED_OF_LIGHT


@pytest.fixture(scope="module")
def dumbbell():
    """Two boxes, one shading the other for many Sun directions, and a one-sided sheet."""
    a = trimesh.creation.box(extents=[1.0, 0.6, 0.4])
    b = trimesh.creation.box(extents=[0.5, 0.5, 0.5])
    b.apply_translation([0.3, 0.9, 0.35])
    mesh = MeshData.concatenate([mesh_from_trimesh(a, "a"), mesh_from_trimesh(b, "b")])
    return build_spacecraft(mesh, uniform=MIXED)


def test_absorbing_convex_body_force_is_pressure_times_projected_area():
    craft = build_spacecraft(mesh_from_trimesh(trimesh.creation.box(extents=[1, 2, 3])), uniform=ABSORBER)
    u = np.array([1.0, 2.0, -2.0]) / 3
    result = srp(craft, u)
    projected = 2 * 3 * u[0] + 1 * 3 * u[1] + 1 * 2 * abs(u[2])
    assert np.isclose(result.projected_area_m2, projected)
    assert np.allclose(result.force_N, -P * projected * u, rtol=1e-12)
    assert np.allclose(result.torque_Nm, 0.0, atol=1e-18)
    assert result.reference_point == "volume centroid (default)"


@settings(max_examples=20, deadline=None)
@given(
    st.lists(st.floats(-1, 1), min_size=3, max_size=3).filter(lambda v: np.linalg.norm(v) > 0.1),
    st.lists(st.floats(-np.pi, np.pi), min_size=3, max_size=3),
    st.lists(st.floats(-5, 5), min_size=3, max_size=3),
)
def test_rotating_and_moving_body_and_sun_together_rotates_the_result(dumbbell, sun, angles, shift):
    """Force and torque are vectors of the body frame: rotate everything, and they rotate too."""
    rotation = Rotation.from_euler("xyz", angles)
    moved = MeshData(
        rotation.apply(dumbbell.vertices.copy()) + shift,  # scipy wants a writable array
        dumbbell.faces,
        dumbbell.facet_part,
        dumbbell.part_names,
        -np.ones(dumbbell.n_facets, np.int32),
    )
    turned = build_spacecraft(moved, uniform=MIXED)
    u = np.asarray(sun) / np.linalg.norm(sun)
    ref = np.array([0.1, -0.2, 0.3])
    base = srp(dumbbell, u, sampling=ShadowSampling(samples=64), reference_point_m=ref)
    new = srp(
        turned,
        rotation.apply(u),
        sampling=ShadowSampling(samples=64),
        reference_point_m=rotation.apply(ref) + shift,
    )
    scale = P * 3.0  # pressure times the largest projected area
    assert np.linalg.norm(new.force_N - rotation.apply(base.force_N)) < 2e-3 * scale
    assert np.linalg.norm(new.torque_Nm - rotation.apply(base.torque_Nm)) < 2e-3 * scale * 1.5
    assert np.isclose(new.projected_area_m2, base.projected_area_m2, rtol=2e-3)


def test_torque_about_another_point_obeys_the_moment_transfer_law(dumbbell):
    u = np.array([0.3, -0.8, 0.52]) / np.linalg.norm([0.3, -0.8, 0.52])
    a, b = np.zeros(3), np.array([0.5, -1.0, 2.0])
    at_a = srp(dumbbell, u, reference_point_m=a)
    at_b = srp(dumbbell, u, reference_point_m=b)
    assert np.allclose(at_b.force_N, at_a.force_N)
    assert np.allclose(at_b.torque_Nm, at_a.torque_Nm - np.cross(b - a, at_a.force_N), rtol=1e-10, atol=1e-20)


def test_shadowing_is_visible_and_per_side_arrays_sum_to_the_totals(dumbbell):
    u = np.array([0.0, -1.0, 0.2]) / np.linalg.norm([0.0, -1.0, 0.2])  # box a shades part of box b
    result = srp(dumbbell, u)
    partly = (result.side_lit_fraction > 0) & (result.side_lit_fraction < 1)
    assert partly.any()
    assert np.allclose(result.side_force_N.sum(axis=0), result.force_N, rtol=1e-12)
    assert np.allclose(result.facet_torque_Nm.sum(axis=0), result.torque_Nm, rtol=1e-12)
    # the shadow removes lit area compared with the two boxes apart: -y faces and +z faces
    apart = (1.0 * 0.4 + 0.5 * 0.5) * -u[1] + (1.0 * 0.6 + 0.5 * 0.5) * u[2]
    # a's +y face (y = 0.3, z < 0.2) shades b's -y face (y = 0.65, z > 0.1) below z = 0.2 - 0.35 u_z/|u_y|,
    # over the x range both share (0.05 to 0.5)
    shadow = 0.45 * (0.2 - 0.35 * u[2] / -u[1] - 0.1) * -u[1]
    # the strip crosses two coarse sides, each converged to ~1e-3 of its lit share
    assert np.isclose(result.projected_area_m2, apart - shadow, rtol=1e-3)


def test_one_sided_sheet_feels_nothing_from_behind_and_two_sided_feels_its_back_material():
    square = np.array([[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]], float)
    sheet = quad_sheet(square, "panel", 3)
    from sunwind.geometry.materials import parse_materials

    spec = parse_materials(
        {
            "materials": {
                "front": {"reflectivity": 0.5, "specular_fraction": 1.0},
                "back": {"reflectivity": 0.0, "specular_fraction": 0.0},
            },
            "parts": {"panel": {"front": "front"}},
        }
    )
    one = build_spacecraft(sheet, spec)
    u = np.array([0.6, 0.0, -0.8])
    assert np.allclose(srp(one, u).force_N, 0.0)
    two = build_spacecraft(sheet, uniform=Material("b", 0.0, 0.0), two_sided=["panel"])
    assert np.allclose(srp(two, u).force_N, -P * 0.8 * u)


def test_bad_directions_and_reference_points_are_input_errors(dumbbell):
    for bad in ([0, 0, 0], [np.nan, 0, 1], [np.inf, 0, 0], [1, 0]):
        with pytest.raises(InputError):
            srp(dumbbell, bad)
    with pytest.raises(InputError, match="reference_point_m"):
        srp(dumbbell, [1, 0, 0], reference_point_m=[0, np.nan, 0])
    with pytest.raises(InputError, match="samples"):
        srp(dumbbell, [1, 0, 0], sampling=ShadowSampling(samples=0))


@pytest.mark.slow
def test_results_are_the_same_bits_whatever_the_number_of_threads():
    """Force sums run in blocks added in a fixed order, so threads cannot change the last bit."""
    from sunwind.meshes.samples import sample_spacecraft

    craft = build_spacecraft(sample_spacecraft(30_000))
    u = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    results = {}
    for threads in (1, 2, 3):
        model = Model(craft, threads=threads)
        results[threads] = [
            np.concatenate([r.force_N, r.torque_Nm, [r.lit_area_m2, r.projected_area_m2]])
            for r in (
                srp(model, u, sampling=ShadowSampling(samples=1)),
                srp(model, u, sampling=ShadowSampling(samples=4)),
                srp(model, u),
            )
        ]
    for threads in (2, 3):
        for a, b in zip(results[1], results[threads], strict=True):
            assert np.array_equal(a, b)


def test_a_batch_is_its_attitudes_one_by_one(dumbbell):
    """A batch of Sun vectors gives, attitude by attitude, the bits of one call each, and every field
    stacked under the same name."""
    suns = np.array([[1.0, 0.2, 0.3], [-0.3, 0.9, 0.1], [0.0, 0.0, -1.0]])
    batch = srp(dumbbell, suns, sampling=ShadowSampling(samples=4), reflections="none")
    assert isinstance(batch, SrpBatch) and len(batch) == 3
    assert batch.force_N.shape == batch.torque_Nm.shape == batch.sun_vector.shape == (3, 3)
    assert batch.lit_area_m2.shape == batch.rays.shape == batch.azel_deg.shape[:1] == (3,)
    for k, sun in enumerate(suns):
        one = srp(dumbbell, sun, sampling=ShadowSampling(samples=4), reflections="none")
        assert np.array_equal(batch[k].force_N, one.force_N)
        assert np.array_equal(batch.torque_Nm[k], one.torque_Nm)
        assert batch.rays[k] == one.rays
        assert batch.to_json()[k]["force_N"] == one.to_json()["force_N"]
    with pytest.raises(InputError, match=r"sun_vector\[1\]"):
        srp(dumbbell, [[1, 0, 0], [0, 0, 0]])
    with pytest.raises(InputError, match="shape"):
        srp(dumbbell, np.ones((2, 2)))


def test_the_model_reference_point_applies_unless_the_call_gives_one(dumbbell):
    point = np.array([0.1, -0.2, 0.3])
    model = Model(dumbbell, reference_point_m=point)
    own = srp(model, [1.0, 0.2, 0.3], sampling=ShadowSampling(samples=1), reflections="none")
    given = srp(
        dumbbell,
        [1.0, 0.2, 0.3],
        sampling=ShadowSampling(samples=1),
        reflections="none",
        reference_point_m=point,
    )
    assert own.reference_point == given.reference_point == "user"
    assert np.array_equal(own.torque_Nm, given.torque_Nm)
    other = srp(
        model,
        [1.0, 0.2, 0.3],
        sampling=ShadowSampling(samples=1),
        reflections="none",
        reference_point_m=[0, 0, 0],
    )
    assert np.array_equal(other.reference_point_m, [0, 0, 0])
    with pytest.raises(InputError, match="threads"):
        Model(dumbbell, threads=0)


def test_plates_light_every_facing_side_whole_and_cast_no_ray(dumbbell):
    box = build_spacecraft(mesh_from_trimesh(trimesh.creation.box(extents=[1, 2, 3])), uniform=MIXED)
    sun = [0.3, -0.5, 0.8]
    plates, exact = srp(box, sun, reflections="plates"), srp(box, sun, reflections="none")
    assert plates.reflections == "plates" and plates.rays == 0 and plates.error_estimate is None
    assert np.allclose(plates.force_N, exact.force_N, rtol=1e-12, atol=1e-20)  # convex: nothing shadowed
    assert np.allclose(plates.torque_Nm, exact.torque_Nm, rtol=1e-12, atol=1e-20)
    shaded = [0.0, 1.0, 0.3]  # box b shades part of box a
    alone, shadowed = srp(dumbbell, shaded, reflections="plates"), srp(dumbbell, shaded, reflections="none")
    assert alone.lit_area_m2 > shadowed.lit_area_m2
    assert alone.power.incident_W == pytest.approx(alone.power.absorbed_W + alone.power.escaped_W, rel=1e-12)


def test_sampling_must_be_shadow_sampling(dumbbell):
    with pytest.raises(InputError, match="is not a ShadowSampling"):
        srp(dumbbell, [1, 0, 0], sampling=4)
    with pytest.raises(InputError, match="tolerance"):
        srp(dumbbell, [1, 0, 0], sampling=ShadowSampling(tolerance=0.0))
