"""The direct SRP force law and its evaluation on meshes: limits, twins and invariances."""

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from helpers import ABSORBER, MIXED, mesh_from_trimesh, quad_sheet
from sunwind.forces.radiation.direct import TOTALS, accumulate_forces, block_moments, weight_moments
from sunwind.forces.radiation.law import (
    SOLAR_FLUX_1AU,
    SPEED_OF_LIGHT,
    radiation_pressure,
    solar_flux,
    surface_forces,
)
from sunwind.forces.srp import srp
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.shadows import BLOCK
from sunwind.geometry.spacecraft import build_spacecraft

P = SOLAR_FLUX_1AU / SPEED_OF_LIGHT


def plate_force(rho, beta, sigma, cos):
    """Force on a unit plate with normal +z, Sun in the x-z plane at incidence angle acos(cos)."""
    u = np.array([np.sqrt(1 - cos**2), 0.0, cos])
    one = np.ones(1)
    return surface_forces(
        np.array([[0.0, 0, 1]]), one, np.array([cos]), rho * one, beta * one, sigma * one, u, P
    )[0], u


@pytest.mark.parametrize("cos", [1.0, 0.8, 0.3, 0.01])
def test_force_law_limits(cos):
    n = np.array([0.0, 0, 1])
    absorbed, u = plate_force(0.0, 0.0, 0.0, cos)
    assert np.allclose(absorbed, -P * cos * u)  # all momentum along the beam
    mirror, _ = plate_force(1.0, 1.0, 0.0, cos)
    assert np.allclose(mirror, -2 * P * cos**2 * n)  # normal only: no tangential force
    lambert, _ = plate_force(1.0, 0.0, 0.0, cos)
    assert np.allclose(lambert, -P * cos * (u + 2 / 3 * n))
    clear, _ = plate_force(0.0, 0.0, 1.0, cos)
    assert np.allclose(clear, 0.0)  # fully transmitted light passes unchanged
    # momentum balance of the mixed case: incident - transmitted - specular - diffuse momentum out
    rho, beta, sigma = MIXED.reflectivity, MIXED.specular_fraction, MIXED.transmissivity
    mixed, _ = plate_force(rho, beta, sigma, cos)
    s = -u
    mirror_dir = s - 2 * (s @ n) * n
    expected = P * cos * (s - sigma * s - rho * beta * mirror_dir - rho * (1 - beta) * 2 / 3 * n)
    assert np.allclose(mixed, expected, rtol=1e-13, atol=0)


def test_flux_from_distance_and_pressure():
    assert solar_flux() == SOLAR_FLUX_1AU
    assert np.isclose(solar_flux(distance_au=2.0), SOLAR_FLUX_1AU / 4)
    assert solar_flux(flux_W_m2=1000.0) == 1000.0
    assert np.isclose(radiation_pressure(SOLAR_FLUX_1AU), 4.5398e-6, rtol=1e-4)
    for bad in (
        {"flux_W_m2": np.nan},
        {"flux_W_m2": -1.0},
        {"distance_au": 0.0},
        {"distance_au": np.inf},
        {"flux_W_m2": 1.0, "distance_au": 1.0},
    ):
        with pytest.raises(InputError):
            solar_flux(**bad)


def _direct_sums_twin(u, spread, shares, flags, weighted):
    """The kernel's block sums and the numpy sums of eq. (4) over the same random sides.

    Normals of even blocks lie within ``spread`` of ``u`` (1 or more: any direction); each side is
    dark, wholly lit or lit in part with the probabilities ``shares``, a part-lit side's force acting
    at a point off its centroid. Blocks are runs of ``BLOCK`` sides, as the sampler's. With
    ``flags`` (and no part-lit side) the kernel gets lit flags instead of shares. ``weighted``: two
    random weights per side are summed with the lit projected area, as inter-reflection's channels are.
    """
    rng = np.random.default_rng(5)
    n_blocks = 10
    n = n_blocks * BLOCK - 7  # the last block is short, as the sampler's may be
    block = np.arange(n) // BLOCK
    # odd blocks take any direction, so blocks summed side by side come between the others
    normals = rng.normal(size=(n, 3)) + u / np.where(block % 2 == 0, spread, 10.0)[:, None]
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    state = rng.choice(3, size=n, p=shares)
    fraction = np.select([state == 0, state == 1], [0.0, 1.0], rng.random(n))
    areas, centroids = rng.random(n), rng.normal(size=(n, 3))
    lit_centroid = np.where((state == 2)[:, None], centroids + 0.1 * rng.normal(size=(n, 3)), centroids)
    material = rng.integers(0, 3, n)
    rho, beta, sigma = np.array([0.1, 0.6, 0.9]), np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.1, 0.05])
    optics = np.stack([rho[material], beta[material], sigma[material]], axis=1)
    cos = normals @ u
    facing = np.flatnonzero(cos > 0)
    ref = np.array([0.1, 0.2, -0.3])
    low = np.array([normals[block == b].min(axis=0) for b in range(n_blocks)])
    high = np.array([normals[block == b].max(axis=0) for b in range(n_blocks)])
    moments = block_moments(normals, areas, optics, centroids, block, n_blocks)
    weights = rng.normal(size=(n, 2 if weighted else 0))
    partials = np.zeros((n_blocks, TOTALS + weights.shape[1]))
    accumulate_forces(
        facing,
        fraction[facing] > 0 if flags else fraction[facing],
        lit_centroid,
        centroids,
        normals,
        areas,
        optics,
        u,
        ref,
        block,
        low,
        high,
        moments,
        weights if weighted else None,
        weight_moments(weights, normals, areas, block, n_blocks) if weighted else None,
        partials,
    )
    lit = facing[fraction[facing] > 0]
    m = material[lit]
    lit_area = areas[lit] * fraction[lit]
    forces = surface_forces(normals[lit], lit_area, cos[lit], rho[m], beta[m], sigma[m], u, 1.0)
    twin = np.concatenate(
        [
            forces.sum(axis=0),
            np.cross(lit_centroid[lit] - ref, forces).sum(axis=0),
            [
                lit_area.sum(),
                (lit_area * cos[lit]).sum(),
                (lit_area * cos[lit] * (1 - rho[m] - sigma[m])).sum(),
            ],
            (lit_area * cos[lit]) @ weights[lit],
        ]
    )
    whole = np.minimum(low * u, high * u).sum(axis=1) > 0
    return partials.sum(axis=0), twin, whole


@pytest.mark.parametrize(
    "spread, shares, flags",
    [
        (10.0, (0.3, 0.4, 0.3), False),
        (0.2, (0.3, 0.4, 0.3), False),
        (0.2, (0.0, 1.0, 0.0), False),
        (0.2, (0.8, 0.1, 0.1), False),
        (0.2, (0.4, 0.6, 0.0), True),
    ],
    ids=["any-normals", "whole-blocks-mixed-light", "whole-blocks-all-lit", "whole-blocks-dark", "flags"],
)
@pytest.mark.parametrize("weighted", [False, True], ids=["", "weighted"])
def test_direct_sums_equal_their_numpy_twin(spread, shares, flags, weighted):
    """Side by side, and from block moments with corrections for sides not wholly lit: the same sums
    to round-off (1e-12 of the largest total of each kind)."""
    u = np.array([0.2, -0.5, 0.84])
    u /= np.linalg.norm(u)
    totals, twin, whole = _direct_sums_twin(u, spread, shares, flags, weighted)
    assert whole.any() == (spread < 1)  # the moment path is taken where it should be
    assert len(totals) == len(twin) == TOTALS + (2 if weighted else 0)
    for kind in (slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 10), slice(10, 11))[: len(twin) - 6]:
        scale = np.abs(twin[kind]).max()
        assert np.allclose(totals[kind], twin[kind], rtol=0, atol=1e-12 * scale)


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
    assert result.reference_point == "volume centroid"


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
    base = srp(dumbbell, u, samples=64, reference_point_m=ref)
    new = srp(turned, rotation.apply(u), samples=64, reference_point_m=rotation.apply(ref) + shift)
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
    with pytest.raises(InputError, match="ref-point"):
        srp(dumbbell, [1, 0, 0], reference_point_m=[0, np.nan, 0])
    with pytest.raises(InputError, match="samples"):
        srp(dumbbell, [1, 0, 0], samples=0)


def test_results_are_the_same_bits_whatever_the_number_of_threads(monkeypatch):
    """Force sums run in blocks added in a fixed order, so threads cannot change the last bit."""
    from sunwind.meshes.samples import sample_spacecraft

    craft = build_spacecraft(sample_spacecraft(30_000))
    u = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    results = {}
    for threads in ("1", "2", "3"):
        monkeypatch.setenv("SUNWIND_THREADS", threads)
        results[threads] = [
            np.concatenate([r.force_N, r.torque_Nm, [r.lit_area_m2, r.projected_area_m2]])
            for r in (srp(craft, u, samples=1), srp(craft, u, samples=4), srp(craft, u))
        ]
    for threads in ("2", "3"):
        for a, b in zip(results["1"], results[threads], strict=True):
            assert np.array_equal(a, b)
