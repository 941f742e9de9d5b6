"""The survey of CAD-export properties (geometry/survey.py): each count exact on a small hand-built mesh."""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.geometry.errors import MeshError
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.overlaps import overlap_areas, stacked
from sunwind.geometry.sides import ONE_SIDED, SOLID, TWO_SIDED
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.survey import survey, survey_mesh
from sunwind.meshes.assembly import assemble, label, transform
from sunwind.meshes.primitives import box, plate

PAINT = Material("paint", 0.5, 0.5, 0.0)


def parts(*pieces: MeshData) -> MeshData:
    """Meshes joined, each its own part (already labelled)."""
    return MeshData.concatenate(list(pieces))


def kinds(mesh: MeshData, kind: int) -> np.ndarray:
    return np.full(mesh.n_faces, kind, dtype=np.int8)


def test_a_clean_closed_box_has_nothing_to_report():
    found = survey_mesh(box())
    assert found.facets == 12 and found.corners == 8
    for tally in (found.open_edges, found.nonmanifold_edges, found.mixed_winding, found.seams, found.gaps):
        assert tally.count == 0 and tally.length_m == 0 and tally.parts == {}
    assert found.crossings == () and found.coincident.facets == found.layered.facets == 0
    assert found.slivers.count == found.slivers.degenerate == 0 and found.shells == {"box": 1}
    assert found.slivers.area_min_m2 == found.slivers.area_max_m2 == 0.5


@pytest.mark.parametrize("kind", [SOLID, TWO_SIDED])
def test_a_box_with_three_sides_flipped_has_six_edges_of_mixed_winding(kind):
    mesh = box()
    corners = mesh.vertices[mesh.faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    flip = normal @ np.ones(3) > 0  # the +x, +y and +z sides, which meet at one corner
    faces = np.where(flip[:, None], mesh.faces[:, ::-1], mesh.faces)
    flipped = assemble(mesh.vertices, faces, mesh.face_part, mesh.part_names, {"shape": "flipped"})
    found = survey_mesh(flipped, kinds(flipped, kind))
    # 12 box edges: 3 between flipped sides, 3 between the others, 6 between a flipped side and another
    assert found.mixed_winding.count == 6 and found.mixed_winding.length_m == pytest.approx(6.0)
    assert found.mixed_winding.parts == {"box": 6}
    assert found.mixed_on_sheets == (6 if kind == TWO_SIDED else 0)
    assert found.open_edges.count == 0 and found.nonmanifold_edges.count == 0
    # loading makes a closed body's winding consistent, and keeps a sheet's
    loaded = survey(build_spacecraft(flipped, uniform=PAINT, two_sided=["*"] if kind == TWO_SIDED else ()))
    assert loaded.mixed_winding.count == (6 if kind == TWO_SIDED else 0)


def test_a_box_whose_every_side_has_its_own_vertices_has_twelve_seams():
    mesh = box()
    corners = mesh.vertices[mesh.faces]
    # each of the six sides (two triangles with one normal) gets its own four vertices
    normal = np.round(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), 6)
    side = np.unique(normal, axis=0, return_inverse=True)[1].reshape(-1)
    order = np.argsort(side, kind="stable")
    key = side[order][:, None] * 8 + mesh.faces[order]  # a vertex of a side: (side, vertex)
    own, local = np.unique(key, return_inverse=True)
    vertices, faces = mesh.vertices[own % 8], local.reshape(-1, 3)
    apart = assemble(vertices, faces, np.zeros(12), ["box"], {"shape": "apart"})
    found = survey_mesh(apart)
    assert len(vertices) == 24 and found.corners == 8
    assert found.seams.count == 12 and found.seams.length_m == pytest.approx(12.0)
    assert found.seams.parts == {"box": 12} and found.seams_unmerged == 0
    assert found.open_edges.count == 0 and found.shells == {"box": 1}
    # one side moved 1e-8 m off: welded by position (5e-7 m) but not merged on loading (1e-9 m)
    moved = vertices.copy()
    moved[:4] += 1e-8 * np.array([1.0, 0.3, 0.7])
    found = survey_mesh(assemble(moved, faces, np.zeros(12), ["box"], {"shape": "apart"}))
    assert found.seams.count == 12 and found.seams_unmerged == 4  # the moved side's four edges
    # as loaded, the vertices are merged: no seam left
    assert survey(build_spacecraft(apart, uniform=PAINT)).seams.count == 0


def test_two_boxes_through_each_other_cross_along_a_known_length():
    a = label(box(), "a")
    b = label(transform(box(), translation=(0.3, 0.4, 0.45)), "b")
    found = survey_mesh(parts(a, b))
    # each of a's three faces inside b meets two of b's faces: 2 (3 - 0.3 - 0.4 - 0.45) m
    assert len(found.crossings) == 1
    crossing = found.crossings[0]
    assert crossing.parts == ("a", "b") and crossing.length_m == pytest.approx(3.7, rel=1e-12)
    assert crossing.facet_pairs >= 6
    assert found.shells == {"a": 1, "b": 1} and found.open_edges.count == 0


def test_a_duplicated_face_is_coincident_and_a_layer_over_a_face_is_layered():
    body = box()
    duplicate = assemble(body.vertices, body.faces[:1], [0], ["decal"], {"shape": "decal"})
    found = survey_mesh(parts(body, duplicate))
    assert found.coincident.facets == 2 and found.coincident.area_m2 == pytest.approx(0.5)
    assert found.coincident.coplanar_area_m2 == pytest.approx(0.5)  # closer than the rays' offset
    assert found.coincident.parts == {"box": 1, "decal": 1} and found.layered.facets == 0
    assert found.nonmanifold_edges.count == 3  # the copy's three edges carry three facets each
    # a 0.5 m square laid 2e-4 m over the top (+z) side: shades it, counted as layered
    patch = label(transform(plate(0.5, 0.5, divisions=1), translation=(0, 0, 0.5 + 2e-4)), "patch")
    mesh = parts(body, patch)
    kind = kinds(mesh, SOLID)
    kind[-2:] = ONE_SIDED
    found = survey_mesh(mesh, kind)
    assert found.coincident.facets == 0 and found.layered.facets == 4
    assert found.layered.area_m2 == pytest.approx(0.25, rel=1e-9)
    assert found.layered.coplanar_area_m2 == 0 and found.layered.parts == {"box": 2, "patch": 2}
    # a closed body's opposite wall facing away is no layer (a thin solid's two faces)
    thin = label(transform(box((1.0, 1.0, 4e-4)), translation=(0, 0, 2)), "thin")
    assert survey_mesh(parts(body, thin)).layered.facets == 0


def test_slivers_degenerate_facets_and_the_facet_sizes():
    points = [[0, 0, 0], [1, 0, 0], [0.5, 1e-4, 0], [0, 1, 0], [2, 0, 0]]
    # a sliver (aspect 1 / 1e-4), a right triangle and a triangle without area
    faces = [[0, 1, 2], [0, 1, 3], [0, 1, 4]]
    found = survey_mesh(assemble(points, faces, [0, 0, 0], ["fin"], {"shape": "fin"}), np.full(3, TWO_SIDED))
    assert found.slivers.count == 1 and found.slivers.parts == {"fin": 1}
    assert found.slivers.degenerate == 1
    assert found.slivers.area_min_m2 == pytest.approx(5e-5) and found.slivers.area_max_m2 == 0.5


def test_an_open_gap_between_two_sheets_and_no_gap_across_a_narrow_strip():
    left = transform(plate(1.0, 1.0, divisions=1), translation=(-0.5, 0, 0))
    right = transform(plate(1.0, 1.0, divisions=1), translation=(0.5 + 5e-4, 0, 0))
    sheets = parts(label(left, "left"), label(right, "right"))
    found = survey_mesh(sheets, kinds(sheets, TWO_SIDED))
    assert found.open_edges.count == 8 and found.open_edges.length_m == pytest.approx(8.0)
    assert found.gap_m == pytest.approx(2.0005e-3)
    assert found.gaps.count == 2 and found.gaps.length_m == pytest.approx(2.0)
    assert found.gaps.parts == {"left": 1, "right": 1}
    strip = label(plate(1.0, 5e-4, divisions=1), "strip")
    found = survey_mesh(strip, kinds(strip, TWO_SIDED))
    assert found.open_edges.count == 4 and found.gaps.count == 0


def test_loose_pieces_of_one_part_are_counted_as_shells():
    pieces = [transform(box(), translation=(2.0 * k, 0, 0)) for k in range(3)]
    joined = MeshData.concatenate([label(p, "bolts") for p in pieces])
    assert survey_mesh(joined).shells == {"bolts": 3}


def test_a_mesh_that_fails_the_loading_checks_is_surveyed_as_read():
    mesh = box()
    corners = mesh.vertices[mesh.faces]
    top = corners[:, :, 2].min(axis=1) > 0  # the +z side's two triangles
    lidless = assemble(mesh.vertices, mesh.faces[~top], np.zeros(10), ["tub"], {"shape": "tub"})
    with pytest.raises(MeshError, match="open surface"):
        build_spacecraft(lidless, uniform=PAINT)
    found = survey_mesh(lidless)
    assert found.open_edges.count == 4 and found.open_edges.length_m == pytest.approx(4.0)
    assert found.open_edges.parts == {"tub": 4}


def test_a_mesh_with_nan_coordinates_cannot_be_surveyed_and_stray_vertices_do_not_count():
    mesh = box()
    vertices = np.concatenate([mesh.vertices, [[np.nan, 0.0, 0.0], [100.0, 0.0, 0.0]]])  # used by no face
    found = survey_mesh(assemble(vertices, mesh.faces, mesh.face_part, ["box"], {"shape": "box"}))
    assert found.size_m == 1.0 and found.corners == 8
    vertices[0, 1] = np.nan
    with pytest.raises(MeshError, match="nothing to survey"):
        survey_mesh(assemble(vertices, mesh.faces, mesh.face_part, ["box"], {"shape": "box"}))


def test_overlap_of_facets_in_one_plane_and_of_stacked_layers():
    square = np.array([[[0, 0, 0], [2, 0, 0], [2, 2, 0]], [[0, 0, 0], [2, 2, 0], [0, 2, 0]]], float)
    assert overlap_areas(square, np.array([0]), np.array([1])) == pytest.approx([0.0], abs=1e-15)
    # the second triangle moved 1 m along x lies over the first on the band x - 1 < y < x
    shifted = square.copy()
    shifted[1] += [1.0, 0.0, 0.0]
    assert overlap_areas(shifted, np.array([0]), np.array([1])) == pytest.approx([1.0])
    up = np.array([0.0, 0.0, 1.0])
    layers = np.concatenate([square, square + 0.01 * up, square + 0.5 * up])  # only the first two near
    found = stacked(layers, margin=0.02, parallel=0.999)
    assert found.first.tolist() == [0, 1] and found.second.tolist() == [2, 3]
    assert found.area_m2 == pytest.approx([2.0, 2.0]) and found.height_m == pytest.approx([0.01, 0.01])
