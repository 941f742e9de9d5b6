"""Building the spacecraft model: material assignment, sides, and the mesh checks' outcomes."""

import numpy as np
import pytest
import trimesh

from helpers import ABSORBER, MIXED, mesh_from_trimesh, quad_sheet
from sunwind.geometry.errors import MaterialError, MeshError
from sunwind.geometry.materials import Material, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.sides import ONE_SIDED, SOLID, TWO_SIDED
from sunwind.geometry.spacecraft import BLIND, ESCAPED, build_spacecraft
from sunwind.meshes import primitives

#: SPEC's rules cover the parts of several test meshes: a rule matching no part warns, and that is fine here.
pytestmark = pytest.mark.filterwarnings("ignore:.*matches no part:UserWarning")

SPEC = parse_materials(
    {
        "materials": {
            "paint": {"reflectivity": 0.8, "specular_fraction": 0.1},
            "cell": {"reflectivity": 0.2, "specular_fraction": 0.8},
            "cfrp": {"reflectivity": 0.1, "specular_fraction": 0.0},
            "osr": {"reflectivity": 0.9, "specular_fraction": 0.95},
        },
        "parts": {"wing*": {"front": "cell", "back": "cfrp"}, "shield": {"front": "paint"}},
    },
    source="spec.toml",
)

SQUARE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)


def box_with_wing() -> MeshData:
    """A closed box (part 'bus', faces keyed 'paint' and 'osr') and a detached wing sheet."""
    box = trimesh.creation.box(extents=[1, 1, 1])
    n = len(box.faces)
    bus = MeshData(
        box.vertices,
        box.faces,
        np.zeros(n, np.int32),
        ("bus",),
        np.where(np.arange(n) < 2, 1, 0).astype(np.int32),
        ("paint", "osr"),
    )
    wing = quad_sheet(SQUARE + np.array([1.0, 0.5, 0]), "wing_left", n=2)
    return MeshData.concatenate([bus, wing], source="craft.obj")


def test_sides_get_rule_file_key_and_back_materials():
    craft = build_spacecraft(box_with_wing(), SPEC)
    names = craft.materials.names
    wing = craft.facet_part == craft.part_names.index("wing_left")
    assert (craft.facet_kind[wing] == TWO_SIDED).all() and (craft.facet_kind[~wing] == SOLID).all()
    assert craft.n_sides == craft.n_facets + wing.sum()
    back = craft.side_sign < 0
    assert {names[m] for m in craft.side_material[back]} == {"cfrp"}
    front_wing = (craft.side_sign > 0) & wing[craft.side_facet]
    assert {names[m] for m in craft.side_material[front_wing]} == {"cell"}
    bus_sides = ~wing[craft.side_facet]
    assert sorted({names[m] for m in craft.side_material[bus_sides]}) == ["osr", "paint"]
    assert np.allclose(craft.side_normals[back], -craft.facet_normals[craft.side_facet[back]])
    assert craft.default_reference[1] == "area centroid (default)"


def test_one_sided_sheet_has_only_a_front_side():
    shield = quad_sheet(SQUARE, "shield")
    craft = build_spacecraft(shield, SPEC)
    assert (craft.facet_kind == ONE_SIDED).all() and craft.n_sides == craft.n_facets


def test_file_optics_and_file_two_sided_declarations_are_used():
    sheet = quad_sheet(SQUARE, "/craft/dish")
    mesh = MeshData(
        sheet.vertices,
        sheet.faces,
        sheet.face_part,
        sheet.part_names,
        np.zeros(sheet.n_faces, np.int32),
        ("gold",),
        file_optics={
            "gold": {"reflectivity": 0.9, "specular_fraction": 0.5, "transmissivity": 0.0},
            "kapton": {"reflectivity": 0.5, "specular_fraction": 0.2, "transmissivity": 0.1},
        },
        two_sided_parts=frozenset({"/craft/dish"}),
        part_back_material={"/craft/dish": "kapton"},
    )
    craft = build_spacecraft(mesh)
    assert craft.n_sides == 2 * craft.n_facets
    assert craft.materials[int(craft.side_material[-1])] == Material("kapton", 0.5, 0.2, 0.1)
    assert "back kapton (mesh file)" in craft.part_materials["/craft/dish"]


def test_uniform_material_fills_only_what_is_unassigned():
    craft = build_spacecraft(box_with_wing(), SPEC, uniform=ABSORBER)
    assert "black" not in craft.materials.names
    unkeyed = mesh_from_trimesh(trimesh.creation.box())
    assert build_spacecraft(unkeyed, SPEC, uniform=ABSORBER).materials.names == ("black",)


def test_part_without_material_is_an_error_naming_part_and_fix():
    with pytest.raises(MaterialError) as error:
        build_spacecraft(mesh_from_trimesh(trimesh.creation.box(), source="box.stl"))
    message = str(error.value)
    assert "part 'body'" in message and "--reflectivity" in message and "\n" not in message


def test_open_surface_not_declared_is_an_error_with_the_declaration_to_add():
    with pytest.raises(MeshError) as error:
        build_spacecraft(quad_sheet(SQUARE, "/craft/panel"), uniform=ABSORBER)
    message = str(error.value)
    assert "part '/craft/panel' is an open surface (4 boundary edges)" in message
    assert '[parts] panel = { front = "MATERIAL" }' in message and '--two-sided "panel"' in message
    assert "one-sided" in message and "cavity" in message  # what declaring it two-sided means
    craft = build_spacecraft(quad_sheet(SQUARE, "/craft/panel"), uniform=ABSORBER, two_sided=["panel"])
    assert craft.n_sides == 2 * craft.n_facets


def test_non_manifold_body_is_an_error():
    fin = quad_sheet(np.array([[0.5, 0.5, 0.5], [0.5, -0.5, 0.5], [0.5, -0.5, 1.5], [0.5, 0.5, 1.5]]), "fin")
    box = mesh_from_trimesh(trimesh.creation.box(), part="body")
    fused = MeshData.concatenate([box, fin])
    # fin shares the box's top edge x=0.5,z=0.5; declared solid it makes a non-manifold or open body
    with pytest.raises(MeshError, match="part 'fin'"):
        build_spacecraft(fused, uniform=ABSORBER)
    three = trimesh.creation.box()
    flap = MeshData(  # a third triangle on an edge of the closed box
        np.vstack([three.vertices, [[0.0, 0.0, 2.0]]]),
        np.vstack([three.faces, [[0, 1, len(three.vertices)]]]),
        np.zeros(13, np.int32),
        ("body",),
        -np.ones(13, np.int32),
    )
    with pytest.raises(MeshError, match=r"non-manifold|open surface"):
        build_spacecraft(flap, uniform=ABSORBER)


def test_nan_coordinates_are_an_error():
    box = trimesh.creation.box()
    vertices = box.vertices.copy()
    vertices[3, 1] = np.nan
    mesh = MeshData(
        vertices, box.faces, np.zeros(12, np.int32), ("bus",), -np.ones(12, np.int32), source="b.stl"
    )
    with pytest.raises(MeshError, match=r"b.stl: part 'bus' has 1 vertices with NaN or infinite"):
        build_spacecraft(mesh, uniform=ABSORBER)


def test_inward_winding_is_flipped_with_a_notice():
    box = trimesh.creation.box(extents=[1, 2, 3])
    inverted = MeshData(
        box.vertices, box.faces[:, ::-1], np.zeros(12, np.int32), ("bus",), -np.ones(12, np.int32)
    )
    craft = build_spacecraft(inverted, uniform=ABSORBER)
    assert np.isclose(craft.volume, 6.0)
    assert any("wound inward" in n and "bus" in n for n in craft.notices)
    assert (np.abs(craft.facet_normals) @ [1, 1, 1] > 0).all()


def test_inconsistent_winding_is_made_consistent_with_a_notice():
    sphere = trimesh.creation.icosphere(2)
    faces = sphere.faces.copy()
    faces[::7] = faces[::7, ::-1]
    craft = build_spacecraft(
        mesh_from_trimesh(trimesh.Trimesh(sphere.vertices, faces, process=False)), uniform=ABSORBER
    )
    assert any("consistent" in n for n in craft.notices)
    assert np.allclose(np.einsum("ij,ij->i", craft.facet_normals, craft.facet_centroids) > 0, True)


def test_degenerate_triangles_are_dropped_and_counted_without_opening_the_body():
    box = trimesh.creation.box()
    a, b, c = box.faces[0]
    m = len(box.vertices)
    vertices = np.vstack([box.vertices, (box.vertices[a] + box.vertices[b]) / 2])
    # split face (a, b, c) at the midpoint m of edge ab: a T-junction that a zero-area sliver
    # (a, b, m) closes, as exporters leave it; plus a triangle with a repeated vertex
    faces = np.vstack([box.faces[1:], [[a, m, c], [m, b, c], [a, b, m], [c, c, a]]])
    n = len(faces)
    mesh = MeshData(vertices, faces, np.zeros(n, np.int32), ("bus",), -np.ones(n, np.int32))
    craft = build_spacecraft(mesh, uniform=ABSORBER)
    assert craft.n_facets == 13 and np.isclose(craft.volume, 1.0)
    assert any("dropped 2 degenerate triangles" in n for n in craft.notices)


def test_unmerged_stl_style_vertices_are_merged_for_the_closedness_check():
    box = trimesh.creation.box()
    soup = box.vertices[box.faces].reshape(-1, 3)
    mesh = MeshData(
        soup, np.arange(36).reshape(12, 3), np.zeros(12, np.int32), ("bus",), -np.ones(12, np.int32)
    )
    craft = build_spacecraft(mesh, uniform=ABSORBER)
    assert craft.is_closed and len(craft.vertices) == 8 and not craft.notices


def test_side_neighbours_pair_sides_across_shared_edges():
    craft = build_spacecraft(mesh_from_trimesh(trimesh.creation.icosphere(1)), uniform=ABSORBER)
    a, b = craft.side_neighbours
    assert len(a) == 3 * craft.n_facets // 2
    assert np.bincount(np.r_[a, b]).tolist() == [3] * craft.n_facets


def test_rays_strike_the_side_they_travel_against():
    """Front side against the normal, back side with it; a one-sided back or a body's inside is blind."""
    sheet = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]), "wing", 1)
    craft = build_spacecraft(sheet, uniform=MIXED, two_sided=["wing"])
    front, back = craft.facet_sides[0]
    down, up = np.array([[0.0, 0, -1]]), np.array([[0.0, 0, 1]])
    assert craft.struck_sides(np.array([0]), down)[0] == front
    assert craft.struck_sides(np.array([0]), up)[0] == back
    assert craft.struck_sides(np.array([-1]), up)[0] == ESCAPED
    box = build_spacecraft(primitives.box((1.0, 1.0, 1.0)), uniform=MIXED)
    outward = box.facet_normals[:1]
    assert box.struck_sides(np.array([0]), outward)[0] == BLIND
    assert np.all(box.facet_sides[:, 1] == -1)
