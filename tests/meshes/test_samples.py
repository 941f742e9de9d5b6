"""The sample spacecraft: counts, parts, closed bodies, free-standing sheets, materials and files."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from scipy.spatial import cKDTree

from sunwind.geometry.checks import check_mesh
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material, load_materials
from sunwind.geometry.sides import SOLID, TWO_SIDED
from sunwind.geometry.triangles import cross, signed_volume
from sunwind.meshes import (
    SAMPLE_OPTICS,
    materials_toml,
    sample_materials_path,
    sample_path,
    sample_spacecraft,
)
from sunwind.meshes.samples import DIMENSIONS, SAMPLE_EMISSIVITY, SHEETS, main, write_sample_files

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

PARTS = {
    "bus",
    "yoke_left",
    "yoke_right",
    "wing_left",
    "wing_right",
    "mast",
    "dish",
    "boom",
    "boom_tip",
    "nozzle",
}


@pytest.fixture(scope="module", params=[20_000, 100_000])
def sample(request):
    return sample_spacecraft(request.param)


def test_triangle_count_follows_the_target(sample):
    target = sample.metadata["triangles"]
    assert abs(sample.n_faces / target - 1) < 0.05
    assert sample_spacecraft(3_000).n_faces == pytest.approx(3_000, rel=0.1)


def test_parts_and_metadata(sample):
    assert set(sample.part_names) == PARTS
    assert sample.two_sided_parts == set(SHEETS)
    assert dict(sample.part_back_material) == {part: back for part, (_, back) in SHEETS.items()}
    meta = sample.metadata
    assert meta["shape"] == "sample_spacecraft" and meta["array_angle_deg"] == 0.0
    assert meta["dimensions_m"]["bus_size"] == (1.6, 1.4, 1.2) and 0 < meta["facet_size_m"] < 0.1


def test_closed_parts_are_watertight_outward_and_pass_the_model_checks(sample):
    sheet = np.isin(sample.face_part, [sample.part_names.index(p) for p in SHEETS])
    kind = np.where(sheet, TWO_SIDED, SOLID).astype(np.int8)
    check = check_mesh(sample.vertices, sample.faces, sample.face_part, sample.part_names, kind, "sample")
    assert check.closed and check.notices == () and check.dropped_degenerate == 0
    for index, part in enumerate(sample.part_names):
        if part not in SHEETS:
            assert signed_volume(sample.vertices[sample.faces[sample.face_part == index]]) > 0, part


def test_sheets_share_and_touch_no_vertex_of_another_part(sample):
    owner = np.full(len(sample.vertices), -1)
    for index in range(len(sample.part_names)):
        used = np.unique(sample.faces[sample.face_part == index])
        assert (owner[used] == -1).all()  # every vertex belongs to one part
        owner[used] = index
    for part in SHEETS:
        mine = owner == sample.part_names.index(part)
        distance, _ = cKDTree(sample.vertices[~mine]).query(sample.vertices[mine])
        assert distance.min() >= DIMENSIONS.clearance * 0.999, part


def test_sheet_fronts_face_the_documented_way():
    mesh = sample_spacecraft(5_000, array_angle_deg=90.0)
    normals = cross(mesh.vertices[mesh.faces])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    for part, expected in (("wing_left", [0, 0, -1]), ("wing_right", [0, 0, -1])):
        assert np.allclose(normals[mesh.face_part == mesh.part_names.index(part)], expected, atol=1e-12)
    dish_normals = normals[mesh.face_part == mesh.part_names.index("dish")]
    assert (dish_normals[:, 2] > 0).all()  # concave side toward +z (Earth)
    flat = sample_spacecraft(5_000)
    wing = flat.face_part == flat.part_names.index("wing_right")
    assert np.allclose(cross(flat.vertices[flat.faces[wing]])[:, 1:], 0)  # front +x at angle 0


def test_every_face_has_a_material_with_valid_optics(sample):
    assert (sample.face_material >= 0).all()
    used = {sample.material_names[i] for i in np.unique(sample.face_material)}
    assert used | set(sample.part_back_material.values()) == set(SAMPLE_OPTICS)
    for name, optics in SAMPLE_OPTICS.items():
        material = Material.checked(name, optics)
        assert material.reflectivity + material.transmissivity <= 1
    assert sample.file_optics == {
        name: {**optics, "emissivity": SAMPLE_EMISSIVITY[name]} for name, optics in SAMPLE_OPTICS.items()
    }
    bus = sample.face_part == sample.part_names.index("bus")
    normals = cross(sample.vertices[sample.faces[bus]])
    osr = np.array(sample.material_names)[sample.face_material[bus]] == "osr"
    assert np.array_equal(osr, np.abs(normals[:, 1]) > 0.5 * np.linalg.norm(normals, axis=1))


def test_materials_toml_covers_every_material_and_sheet(sample):
    document = tomllib.loads(materials_toml(sample))
    assert document["materials"] == {
        name: {**optics, "emissivity": SAMPLE_EMISSIVITY[name]} for name, optics in SAMPLE_OPTICS.items()
    }
    for part, (front, back) in SHEETS.items():
        assert document["parts"][part] == {"front": front, "back": back}


def test_bad_arguments():
    with pytest.raises(InputError, match="at least 2000"):
        sample_spacecraft(500)
    with pytest.raises(InputError, match="integer"):
        sample_spacecraft(2.5e4)
    with pytest.raises(InputError) as missing:
        sample_path("missing.stl")
    assert str(missing.value) == (
        "no sample file 'missing.stl'; shipped: "
        "sample_spacecraft.obj, sample_spacecraft.toml, sample_spacecraft.usda, "
        "sample_spacecraft_tracking.toml, sample_telemetry.csv, sensor_cube.obj, sensor_cube_fluxes.csv"
    )


def test_write_sample_files_and_command_line(tmp_path):
    paths = write_sample_files(tmp_path / "a", triangles=3_000)
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == sorted(p.name for p in paths.values())
    main(["--triangles", "3000", "-o", str(tmp_path / "b")])
    for path in paths.values():
        assert (tmp_path / "b" / path.name).read_bytes() == path.read_bytes()


def labelled_faces(mesh) -> set[tuple]:
    """Each face as (its vertex indices from the smallest on, part leaf name, material key)."""
    first = mesh.faces.argmin(axis=1)
    rolled = mesh.faces[np.arange(mesh.n_faces)[:, None], (first[:, None] + np.arange(3)) % 3]
    parts = np.array([name.rsplit("/", 1)[-1] for name in mesh.part_names])[mesh.face_part]
    materials = np.array(mesh.material_names)[mesh.face_material]
    return set(zip(map(tuple, rolled.tolist()), parts, materials, strict=True))


@pytest.fixture(scope="module")
def reference():
    return sample_spacecraft(20_000)


class TestShippedFiles:
    """The files in meshes/data are this module's output at 20 000 triangles."""

    def test_toml_parses_and_matches(self, reference):
        text = sample_materials_path().read_text(encoding="utf-8")
        assert text == materials_toml(reference)
        spec = load_materials(sample_materials_path())
        assert set(spec.materials) == set(SAMPLE_OPTICS)

    def test_obj_loads_back_identical(self, reference):
        load_mesh = pytest.importorskip("sunwind.geometry.io").load_mesh
        mesh = load_mesh(sample_path("sample_spacecraft.obj"))
        assert mesh.n_faces == reference.n_faces
        assert np.array_equal(mesh.vertices, reference.vertices)
        assert labelled_faces(mesh) == labelled_faces(reference)

    def test_usd_carries_geometry_and_optics(self, reference):
        load_mesh = pytest.importorskip("sunwind.geometry.io").load_mesh
        mesh = load_mesh(sample_path("sample_spacecraft.usda"))
        assert mesh.n_faces == reference.n_faces
        assert np.abs(mesh.vertices - reference.vertices).max() < 1e-6  # float32 points
        assert labelled_faces(mesh) == labelled_faces(reference)
        leaf = {name: name.rsplit("/", 1)[-1] for name in mesh.part_names}
        assert {leaf[p] for p in mesh.two_sided_parts} == set(SHEETS)
        assert {leaf[p]: m for p, m in mesh.part_back_material.items()} == dict(reference.part_back_material)
        for name, optics in SAMPLE_OPTICS.items():
            assert mesh.file_optics[name] == pytest.approx({**optics, "emissivity": SAMPLE_EMISSIVITY[name]})

    def test_obj_with_toml_builds_a_spacecraft(self):
        spacecraft = pytest.importorskip("sunwind.geometry.spacecraft")
        model = spacecraft.load_spacecraft(sample_path(), sample_materials_path())
        assert model.notices == ()
        assert model.n_sides == model.n_facets + sum(
            int((model.facet_part == model.part_names.index(p)).sum()) for p in SHEETS
        )
