"""The exact lit polygons (validation.exact_shadow) against closed forms, and the ray-cast shadows of
the default sampling against them on a low-polygon model with a thin strut."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import ABSORBER, quad_sheet
from sunwind import meshes
from sunwind.forces.srp import srp
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.validation.exact_shadow import lit_side

C = 299792458.0  # a flux of c W/m^2: a pressure of 1 Pa


def exact_sides(craft, sun):
    """Exact lit area (n_sides,) and lit centroid (n_sides, 3) of every side."""
    triangles = craft.vertices[craft.faces]
    lit = [lit_side(triangles, f, n, sun) for f, n in zip(craft.side_facet, craft.side_normals, strict=True)]
    return np.array([s.area_m2 for s in lit]), np.array([s.centroid_m for s in lit])


def square(centre, size, z, part):
    x, y = centre
    h = size / 2
    corners = np.array([[x - h, y - h, z], [x + h, y - h, z], [x + h, y + h, z], [x - h, y + h, z]])
    return quad_sheet(corners, part)


@pytest.mark.parametrize("sun", [(0.0, 0.0, 1.0), (0.3, 0.0, 1.0), (-0.2, 0.45, 1.0), (2.0, 0.0, 1.0)])
def test_a_square_shading_a_plate_leaves_the_closed_form_lit_area_and_centroid(sun):
    """A 0.5 m square 1 m above a 1 m plate: its shadow is the square shifted by -(u_x, u_y)/u_z."""
    u = np.array(sun) / np.linalg.norm(sun)
    craft = build_spacecraft(
        MeshData.concatenate([square((0, 0), 1.0, 0.0, "plate"), square((0.1, 0.05), 0.5, 1.0, "cover")]),
        uniform=ABSORBER,
        two_sided=["*"],
    )
    area, centre = exact_sides(craft, u)
    plate = (craft.facet_part[craft.side_facet] == craft.part_names.index("plate")) & (
        craft.side_normals[:, 2] > 0
    )
    shift = -u[:2] / u[2]
    low = np.maximum(np.array([0.1, 0.05]) - 0.25 + shift, -0.5)
    high = np.minimum(np.array([0.1, 0.05]) + 0.25 + shift, 0.5)
    overlap = np.prod(np.clip(high - low, 0, None))
    assert area[plate].sum() == pytest.approx(1.0 - overlap, abs=1e-12)
    shade_centre = (low + high) / 2
    lit_centre = -overlap * shade_centre / (1.0 - overlap)  # the plate's own centroid is the origin
    got = (area[plate, None] * centre[plate]).sum(axis=0) / area[plate].sum()
    assert got[:2] == pytest.approx(lit_centre, abs=1e-12) and got[2] == pytest.approx(0.0, abs=1e-12)


def test_a_convex_body_is_lit_wherever_it_faces_the_sun():
    craft = build_spacecraft(primitives.box((1.0, 2.0, 3.0)), uniform=ABSORBER)
    u = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    area, centre = exact_sides(craft, u)
    facing = craft.side_normals @ u > 0
    assert area == pytest.approx(np.where(facing, craft.side_areas, 0.0), abs=1e-12)
    sides = craft.vertices[craft.faces[craft.side_facet]].mean(axis=1)
    assert centre[facing] == pytest.approx(sides[facing], abs=1e-12)


def strut_model():
    """A 12-triangle 1 m bus, a 1 cm strut 0.2 m off its +x face and a two-sided wing."""
    bus = meshes.label(primitives.box((1.0, 1.0, 1.0)), "bus")
    strut = meshes.transform(primitives.box((0.01, 0.01, 1.6)), translation=(0.7, 0.0, 0.3))
    wing = np.array([[0.55, -0.5, -0.5], [0.55, -0.5, 0.5], [0.55, -2.5, 0.5], [0.55, -2.5, -0.5]])
    parts = [bus, meshes.label(strut, "strut"), quad_sheet(wing, "wing")]
    return build_spacecraft(MeshData.concatenate(parts), uniform=ABSORBER, two_sided=["wing"])


def exact_loads(craft, u):
    area, centre = exact_sides(craft, u)
    force = -(area * np.clip(craft.side_normals @ u, 0, None))[:, None] * u
    return force.sum(axis=0), np.cross(centre, force).sum(axis=0), area.sum()


@pytest.mark.parametrize("sun", [(1.0, 0.05, 0.3), (1.0, 0.4, 0.1), (0.6, -0.2, 0.8), (1.0, -1.0, 0.2)])
def test_default_sampling_finds_shadows_cast_across_large_sides(sun):
    """The strut's and the wing's shadows cross the bus's big triangles (at (1, 0.05, 0.3) the strut's
    touches none of their starting points: the outline probes find it); the default converges to its
    tolerance (1e-3 of each side's lit share) against the exact answer."""
    u = np.array(sun) / np.linalg.norm(sun)
    craft = strut_model()
    force, torque, lit = exact_loads(craft, u)
    result = srp(craft, u, flux_W_m2=C, reflections="none", reference_point_m=np.zeros(3))
    assert result.lit_area_m2 == pytest.approx(lit, rel=1e-3)
    assert np.linalg.norm(result.force_N - force) <= 1e-3 * np.linalg.norm(force)
    assert np.linalg.norm(result.torque_Nm - torque) <= 1e-3 * np.linalg.norm(torque)


@pytest.mark.xfail(
    strict=True,
    reason="issue 18: sampling converges to its tolerance (1e-3 of a side's lit share), not to the 1e-4 "
    "of exact clipping the issue asks for on low-polygon models (measured 7e-4 of the force here)",
)
def test_default_sampling_meets_the_exact_answer_to_1e_4_on_a_thin_shadow():
    u = np.array([1.0, 0.05, 0.3]) / np.linalg.norm([1.0, 0.05, 0.3])
    craft = strut_model()
    force, _torque, lit = exact_loads(craft, u)
    result = srp(craft, u, flux_W_m2=C, reflections="none", reference_point_m=np.zeros(3))
    assert result.lit_area_m2 == pytest.approx(lit, rel=1e-4)
    assert np.linalg.norm(result.force_N - force) <= 1e-4 * np.linalg.norm(force)
