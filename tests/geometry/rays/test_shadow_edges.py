"""The default shadow pass: its clipping kernel against closed forms, its lit polygons against exact
clipping (validation.exact_shadow) on curved and thin occluders, and the sides it refines on the
100 000-triangle sample against dense fixed sampling."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from helpers import ABSORBER, mesh_from_trimesh, quad_sheet
from sunwind import meshes
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.edge_kernels import clip_moments
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives
from sunwind.validation.exact_shadow import lit_side


def exact_lit_areas(craft, u):
    triangles = craft.vertices[craft.faces]
    sides = zip(craft.side_facet, craft.side_normals, strict=True)
    return np.array([lit_side(triangles, f, n, u).area_m2 for f, n in sides])


def test_clipping_a_triangle_by_two_lines_gives_the_closed_form_area_and_centroid():
    corners = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    out, scratch = np.empty(3), np.empty((2, 5, 2))
    clip_moments(corners, np.zeros((0, 3)), 0, scratch, out)
    assert out == pytest.approx([0.5, 0.5 / 3, 0.5 / 3], abs=1e-15)
    # w1 <= 1/2 and w2 <= 1/2: the unit triangle less its two corner triangles of area 1/8
    lines = np.array([[-1.0, 0.0, 0.5], [0.0, -1.0, 0.5]])
    clip_moments(corners, lines, 2, scratch, out)
    area = 0.5 - 2 * 0.125
    assert out[0] == pytest.approx(area, abs=1e-15)
    # that part is the square [0, 1/2]^2 (w1 + w2 <= 1 holds on all of it): centroid (1/4, 1/4)
    assert out[1:] / out[0] == pytest.approx([0.25, 0.25], abs=1e-15)
    clip_moments(corners, np.array([[1.0, 1.0, -2.0]]), 1, scratch, out)  # w1 + w2 >= 2: nothing
    assert out == pytest.approx([0.0, 0.0, 0.0], abs=0)


def sphere_over_plate(subdivisions: int) -> object:
    """A faceted sphere of radius 0.3 m, 0.5 m above a 2 m plate of two triangles."""
    ball = mesh_from_trimesh(trimesh.creation.icosphere(subdivisions, radius=0.3), part="ball")
    ball = meshes.transform(ball, translation=(0.1, -0.2, 0.5))
    plate = quad_sheet(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float), "plate")
    return build_spacecraft(MeshData.concatenate([ball, plate]), uniform=ABSORBER, two_sided=["plate"])


@pytest.mark.parametrize(
    "sun",
    [
        pytest.param((0.0, 0.0, 1.0), marks=pytest.mark.slow),
        pytest.param((0.4, 0.3, 1.0), marks=pytest.mark.slow),
        pytest.param((-0.9, 0.2, 0.5), marks=pytest.mark.slow),
        (0.2, -1.5, 0.4),
    ],
)
def test_a_faceted_sphere_shadow_on_one_large_triangle_is_exact(sun):
    """The sphere's shadow on the plate is the projection of its silhouette: a polygon with one corner
    per silhouette edge, lying inside the plate's two triangles. Cut along those edges, the plate's
    lit area equals exact clipping to round-off, at a tolerance of 0.1."""
    craft = sphere_over_plate(1)
    u = np.array(sun) / np.linalg.norm(sun)
    light = side_sampler(craft).illuminate(u, tolerance=0.1)
    exact = exact_lit_areas(craft, u)
    plate = craft.facet_part[craft.side_facet] == craft.part_names.index("plate")
    ours = light.lit_fraction * craft.side_areas
    assert ours[plate].sum() == pytest.approx(exact[plate].sum(), rel=1e-10)
    assert ours == pytest.approx(exact, abs=1e-10)


@pytest.mark.parametrize("sun", [(0.3, 0.1, 1.0), (-0.6, 0.25, 0.7), (1.5, -0.4, 0.3)])
def test_a_1_mm_wire_across_a_two_triangle_plate_is_found_and_cut_exactly(sun):
    """A 1 mm square wire 2.4 m long, 0.3 m over a 2 m plate of two triangles: its shadow is a strip
    crossing the plate without touching any triangle corner or centroid."""
    wire = meshes.transform(primitives.box((2.4, 0.001, 0.001)), translation=(0.05, 0.13, 0.3))
    wire = meshes.transform(wire, rotation=meshes.rotation_matrix("z", 20.0))
    plate = quad_sheet(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float), "plate")
    parts = MeshData.concatenate([meshes.label(wire, "wire"), plate])
    craft = build_spacecraft(parts, uniform=ABSORBER, two_sided=["plate"])
    u = np.array(sun) / np.linalg.norm(sun)
    light = side_sampler(craft).illuminate(u)
    exact = exact_lit_areas(craft, u)
    plate_sides = craft.facet_part[craft.side_facet] == craft.part_names.index("plate")
    ours = light.lit_fraction * craft.side_areas
    shadow = craft.side_areas[plate_sides & (light.cos_incidence > 0)].sum() - exact[plate_sides].sum()
    assert shadow > 1e-3  # the strip is there
    assert ours[plate_sides].sum() == pytest.approx(exact[plate_sides].sum(), abs=1e-6 * shadow)


@pytest.mark.slow
def test_on_the_sample_no_partly_lit_side_of_dense_sampling_is_left_whole():
    """Against 256 stratified points on every side of the 100 000-triangle sample, the sides the default
    pass leaves wholly lit or dark hold no shadow edge: their area that dense sampling finds of the
    other state is below 1e-5 of the lit area (stratified sampling's own error on such a side is a
    few per cent of the side)."""
    from sunwind.forces.bench import sun_directions
    from sunwind.meshes.samples import sample_spacecraft

    craft = build_spacecraft(sample_spacecraft(100_000))
    sampler = side_sampler(craft)
    for u in sun_directions(3, seed=7):
        ours = sampler.illuminate(u)
        dense = sampler.illuminate(u, samples=256)
        whole = (ours.lit_fraction == 0) | (ours.lit_fraction == 1)
        missed = np.abs(ours.lit_fraction - dense.lit_fraction)[whole] @ craft.side_areas[whole]
        lit = ours.lit_fraction @ craft.side_areas
        assert missed < 1e-5 * lit


@pytest.mark.parametrize("sun", [(0.0, 0.0, 1.0), (0.3, -0.2, 1.0), (-0.5, 0.4, 0.8)])
def test_a_lit_sliver_on_a_large_mostly_shadowed_triangle_is_found(sun):
    """Two blinds 0.3 m over a 2 m plate of two triangles leave a 1 cm slit between them: the plate's
    only light is a strip through the slit, inside triangles whose corners and centroids are all dark
    (the case of facets that came out wholly dark though a few per cent lit)."""
    plate = quad_sheet(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float), "plate")
    left = quad_sheet(np.array([[-3, -3, 0.3], [0.0, -3, 0.3], [0.0, 3, 0.3], [-3, 3, 0.3]]), "left")
    right = quad_sheet(np.array([[0.01, -3, 0.3], [3, -3, 0.3], [3, 3, 0.3], [0.01, 3, 0.3]]), "right")
    parts = MeshData.concatenate([plate, left, right])
    craft = build_spacecraft(parts, uniform=ABSORBER, two_sided=["plate", "left", "right"])
    u = np.array(sun) / np.linalg.norm(sun)
    light = side_sampler(craft).illuminate(u)
    exact = exact_lit_areas(craft, u)
    plate_sides = craft.facet_part[craft.side_facet] == craft.part_names.index("plate")
    ours = (light.lit_fraction * craft.side_areas)[plate_sides].sum()
    sliver = exact[plate_sides].sum()
    assert 0.01 < sliver < 0.05  # a 1 cm strip across the plate, stretched by the slant
    assert ours == pytest.approx(sliver, rel=1e-6)


@pytest.mark.parametrize("sun", [(1.0, 1e-13, 0.0), (0.7, 1e-15, 0.7), (1.0, -1e-12, 0.2)])
def test_a_sun_a_hair_off_an_axis_gives_the_exact_force_and_torque(sun):
    """Faces then face the Sun at a cosine of 1e-13: a silhouette edge lies on a face grazed by the
    light, and its probes must neither run along that face nor be taken as shadowed by it. Force and
    torque against exact clipping; the lit area of the grazed faces is left out (their rays start an
    origin offset off the face, where a sheet touching it can block them: they carry no force)."""
    from sunwind.forces.srp import srp
    from sunwind.validation.cases import LOW_POLY_CASE
    from sunwind.validation.exact_shadow import exact_absorber_srp

    craft = LOW_POLY_CASE.spacecraft()
    u = np.array(sun) / np.linalg.norm(sun)
    force, torque, _ = exact_absorber_srp(craft, u)
    result = srp(craft, u, flux_W_m2=299792458.0, reflections="none", reference_point_m=np.zeros(3))
    assert np.linalg.norm(result.force_N - force) <= 1e-9 * np.linalg.norm(force)
    assert np.linalg.norm(result.torque_Nm - torque) <= 1e-9 * np.linalg.norm(torque)


def crossing_struts(count: int = 8, seed: int = 3):
    """``count`` 1 cm x 1 cm x 2.6 m struts at seeded heights (0.1-0.6 m) and headings over a 2 m plate
    of two triangles: their shadows cross one another on the plate, and they shadow one another's
    1 cm faces."""
    rng = np.random.default_rng(seed)
    parts = [quad_sheet(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float), "plate")]
    for k in range(count):
        turn = meshes.rotation_matrix("z", float(rng.uniform(0, 180)))
        at = (float(rng.uniform(-0.5, 0.5)), float(rng.uniform(-0.5, 0.5)), float(rng.uniform(0.1, 0.6)))
        parts.append(meshes.label(meshes.transform(primitives.box((2.6, 0.01, 0.01)), turn, at), f"strut{k}"))
    return build_spacecraft(MeshData.concatenate(parts), uniform=ABSORBER, two_sided=["plate"])


@pytest.mark.parametrize(
    "sun",
    [
        (0.0, 0.0, 1.0),
        pytest.param((0.3, 0.2, 1.0), marks=pytest.mark.slow),
        pytest.param((0.9, -0.8, 0.4), marks=pytest.mark.slow),
    ],
)
def test_crossing_thin_struts_over_a_plate_against_exact_clipping(sun):
    """A truss: strip shadows crossing inside one large triangle (cut by splitting where the strips
    cross, down to nodes of a few millimetres) and strut faces 1 cm wide, which only probes spaced by
    the narrow sides' width find. Measured: force within 3e-7, torque within 3e-8 of |F| x 2 m; with
    the Sun along the plate's normal every shadow edge lies on an outline line, and the lit area is
    exact to round-off (5e-14; 5.4e-7 while a thin cell's ray could start in the next cell)."""
    from sunwind.forces.srp import srp
    from sunwind.validation.exact_shadow import exact_absorber_srp

    craft = crossing_struts()
    u = np.array(sun) / np.linalg.norm(sun)
    force, torque, lit = exact_absorber_srp(craft, u)
    result = srp(craft, u, flux_W_m2=299792458.0, reflections="none", reference_point_m=np.zeros(3))
    assert result.lit_area_m2 == pytest.approx(lit, rel=1e-4)
    assert np.linalg.norm(result.force_N - force) <= 1e-4 * np.linalg.norm(force)
    assert np.linalg.norm(result.torque_Nm - torque) <= 1e-4 * 2.0 * np.linalg.norm(force)
    if sun == (0.0, 0.0, 1.0):
        assert result.lit_area_m2 == pytest.approx(lit, rel=1e-11)
