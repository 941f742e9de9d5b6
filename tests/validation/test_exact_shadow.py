"""The exact lit polygons (validation.exact_shadow) against closed forms, and the default shadow pass
against them on a low-polygon model with a thin strut."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import ABSORBER, quad_sheet
from sunwind.forces.srp import srp
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.validation.cases import LOW_POLY_CASE, LOW_POLY_SUNS
from sunwind.validation.exact_shadow import exact_absorber_srp, exact_sides

C = 299792458.0  # a flux of c W/m^2: a pressure of 1 Pa


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


@pytest.mark.parametrize("sun", LOW_POLY_SUNS, ids=[f"sun{k}" for k in range(len(LOW_POLY_SUNS))])
def test_the_default_shadow_pass_meets_the_exact_answer_to_1e_4_on_a_low_polygon_model(sun):
    """A 12-triangle bus with a wing and a 1 cm strut whose shadows fall across its large triangles:
    lit area, force and torque of the default pass within 1e-4 of exact clipping (measured worst over
    these 23 directions: 2.8e-6 lit area, 4.6e-6 force, 3.3e-6 torque; exact to round-off at 22)."""
    u = np.array(sun) / np.linalg.norm(sun)
    craft = LOW_POLY_CASE.spacecraft()
    force, torque, lit = exact_absorber_srp(craft, u)
    result = srp(craft, u, flux_W_m2=C, reflections="none", reference_point_m=np.zeros(3))
    assert result.lit_area_m2 == pytest.approx(lit, rel=1e-4)
    assert np.linalg.norm(result.force_N - force) <= 1e-4 * np.linalg.norm(force)
    assert np.linalg.norm(result.torque_Nm - torque) <= 1e-4 * np.linalg.norm(torque)
