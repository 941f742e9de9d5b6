"""Mesh file reading and writing: round trips, handwritten files, units and every error message."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import trimesh
from pxr import Sdf, UsdUtils

from sunwind.geometry.errors import InputError, MeshError, SunwindError
from sunwind.geometry.io import SUPPORTED_SUFFIXES, UNITS, load_mesh, save_mesh
from sunwind.geometry.mesh_data import MeshData

OPTICS = {
    "gold": {"reflectivity": 0.3, "specular_fraction": 0.5, "transmissivity": 0.0},
    "cell": {"reflectivity": 0.1, "specular_fraction": 0.9, "transmissivity": 0.0},
    "kapton": {"reflectivity": 0.2, "specular_fraction": 0.25, "transmissivity": 0.6},
}
WRITABLE = (".obj", ".stl", ".ply", ".glb", ".gltf", ".usda", ".usdc", ".usd")


def sample_mesh() -> MeshData:
    """Three parts with coordinates exact in float32, as a spacecraft file would carry them.

    A tetrahedron body with two materials, a two-sided wing with a back material, and an
    antenna without a material key.
    """
    body = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    wing = [[1, 1, 0], [2, 1, 0], [2, 1.5, 0], [1, 1.5, 0]]
    antenna = [[0, 0, 2], [0.25, 0, 2], [0, 0.25, 2.5]]
    vertices = body + wing + antenna
    faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [4, 5, 6], [4, 6, 7], [8, 9, 10]]
    return MeshData(
        vertices=np.array(vertices, dtype=float),
        faces=faces,
        face_part=[0, 0, 0, 0, 1, 1, 2],
        part_names=("/sample/body", "/sample/wing", "/sample/antenna"),
        face_material=[0, 1, 0, 1, 2, 2, -1],
        material_names=("gold", "white", "cell"),
        file_optics={"gold": OPTICS["gold"], "cell": OPTICS["cell"], "kapton": OPTICS["kapton"]},
        two_sided_parts=frozenset({"/sample/wing"}),
        part_back_material={"/sample/wing": "kapton"},
    )


def face_table(mesh: MeshData) -> list[tuple]:
    """Each triangle as (part, material key, corner coordinates), sorted: order-free comparison."""
    rows = []
    for face, part, material in zip(mesh.faces, mesh.face_part, mesh.face_material, strict=True):
        key = mesh.material_names[material] if material >= 0 else None
        rows.append((mesh.part_names[part], key or "", tuple(mesh.vertices[face].ravel().tolist())))
    return sorted(rows)


def signed_volume(mesh: MeshData) -> float:
    """Volume enclosed by the triangles, positive when they wind counter-clockwise seen from outside."""
    a, b, c = (mesh.vertices[mesh.faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6)


# ---------------------------------------------------------------------------------------------
# round trips


@pytest.mark.parametrize("suffix", WRITABLE)
def test_round_trip_keeps_triangles_and_what_the_format_carries(tmp_path, suffix):
    mesh = sample_mesh()
    path = tmp_path / f"sample{suffix}"
    save_mesh(mesh, path)
    loaded = load_mesh(path)

    if suffix in (".stl", ".ply"):  # triangles only, one part named after the file
        expected = MeshData(
            mesh.vertices, mesh.faces, np.zeros(mesh.n_faces), ("sample",), np.full(mesh.n_faces, -1)
        )
    else:
        expected = mesh
    assert face_table(loaded) == face_table(expected)
    assert loaded.source == str(path)
    if suffix in (".obj", ".glb", ".gltf") or suffix.startswith(".usd"):
        assert set(loaded.part_names) == set(mesh.part_names)
        assert set(loaded.material_names) == set(mesh.material_names)
    if suffix.startswith(".usd"):
        assert loaded.file_optics == OPTICS
        assert loaded.two_sided_parts == {"/sample/wing"}
        assert loaded.part_back_material == {"/sample/wing": "kapton"}
        assert loaded.metadata["unit"] == "m (USD metersPerUnit)"
    else:
        assert loaded.file_optics == {}
        assert loaded.two_sided_parts == frozenset()


@pytest.mark.parametrize("suffix", WRITABLE)
def test_round_trip_precision(tmp_path, suffix):
    """OBJ is bit-exact (repr of float64); the others store float32 (relative error <= 2**-24)."""
    rng = np.random.default_rng(786654189)
    vertices = rng.normal(scale=3.0, size=(300, 3))
    faces = rng.integers(0, 300, size=(500, 3))
    mesh = MeshData(vertices, faces, np.zeros(500), ("craft",), np.full(500, -1))
    path = tmp_path / f"craft{suffix}"
    save_mesh(mesh, path)
    loaded = load_mesh(path)
    triangles = loaded.vertices[loaded.faces]  # one part, one material: face order is kept
    if suffix == ".obj":
        np.testing.assert_array_equal(loaded.vertices, vertices)
        np.testing.assert_array_equal(loaded.faces, faces)
    else:
        np.testing.assert_allclose(triangles, vertices[faces], rtol=2**-24, atol=0)


def test_obj_round_trip_keeps_vertices_bit_exact_and_part_order(tmp_path):
    mesh = sample_mesh()
    mesh = MeshData(
        mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names,
        np.where(mesh.face_material < 0, 0, mesh.face_material), mesh.material_names,
    )  # fmt: skip
    save_mesh(mesh, tmp_path / "a.obj")
    loaded = load_mesh(tmp_path / "a.obj")
    np.testing.assert_array_equal(loaded.vertices, mesh.vertices)
    assert face_table(loaded) == face_table(mesh)
    assert loaded.part_names == mesh.part_names


def test_usd_writer_makes_valid_distinct_prim_names(tmp_path):
    mesh = MeshData(
        vertices=np.eye(3),
        faces=[[0, 1, 2]] * 4,
        face_part=[0, 1, 2, 3],
        part_names=("a b", "a-b", "Looks", "/other/root/leaf"),
        face_material=[0, 1, 0, 1],
        material_names=("MLI gold", "2nd"),
    )
    path = tmp_path / "my craft.usda"
    save_mesh(mesh, path)
    loaded = load_mesh(path)
    assert loaded.part_names == ("/my_craft/a_b", "/my_craft/a_b_2", "/my_craft/Looks_2", "/my_craft/leaf")
    assert loaded.material_names == ("MLI_gold", "_2nd")
    assert 'defaultPrim = "my_craft"' in path.read_text()
    assert 'upAxis = "Z"' in path.read_text()


def test_usd_writer_uses_given_optics_and_geom_subsets(tmp_path):
    mesh = sample_mesh()
    optics = {"gold": {"reflectivity": 0.9, "specular_fraction": 0.1, "transmissivity": 0.05}}
    path = tmp_path / "sample.usda"
    save_mesh(mesh, path, optics=optics)
    text = path.read_text()
    assert 'def GeomSubset "gold"' in text and 'familyName = "materialBind"' in text
    assert 'subsetFamily:materialBind:familyType = "partition"' in text
    loaded = load_mesh(path)
    assert loaded.file_optics == optics
    assert face_table(loaded) == face_table(mesh)


def test_save_accepts_any_case_suffix_and_pathlike_or_str(tmp_path):
    save_mesh(sample_mesh(), str(tmp_path / "upper.OBJ"))
    assert load_mesh(tmp_path / "upper.OBJ").n_faces == 7


# ---------------------------------------------------------------------------------------------
# handwritten files

HANDWRITTEN_OBJ = """\
# a comment
mtllib craft.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0 1.0
vt 0 0
vn 0 0 1
f 1 2 3
o body
usemtl gold
f 1/1/1 2/1/1 3/1/1 4/1/1   # a quad
g panel
usemtl white
f -4//1 -3//1 -2//1
v 0 0 1
f -5 -4 -1
o boom
f 1/1 2/1 5/1 # material state carries over
"""


def test_handwritten_obj(tmp_path):
    path = tmp_path / "craft.obj"
    path.write_text(HANDWRITTEN_OBJ)
    mesh = load_mesh(path)
    assert mesh.part_names == ("craft", "body", "panel", "boom")
    assert mesh.material_names == ("gold", "white")
    np.testing.assert_array_equal(
        mesh.faces, [[0, 1, 2], [0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 1, 4], [0, 1, 4]]
    )
    np.testing.assert_array_equal(mesh.face_part, [0, 1, 1, 2, 2, 3])
    np.testing.assert_array_equal(mesh.face_material, [-1, 0, 0, 1, 1, 1])
    assert mesh.vertices.shape == (5, 3)
    assert mesh.metadata["unit"] == "m (default)"


def test_obj_loader_keeps_duplicates_degenerates_and_nan(tmp_path):
    path = tmp_path / "raw.obj"
    path.write_text("v 0 0 0\nv 0 0 0\nv 1 0 0\nv nan 0 0\nf 1 2 3\nf 1 3 4\nf 3 2 1\n")
    mesh = load_mesh(path)
    assert mesh.vertices.shape == (4, 3) and mesh.n_faces == 3
    assert np.isnan(mesh.vertices[3, 0])


HANDWRITTEN_USDA = """\
#usda 1.0
(
    defaultPrim = "craft"
    metersPerUnit = 0.01
    upAxis = "Z"
)

def Xform "craft"
{
    double3 xformOp:translate = (100, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def Xform "arm"
    {
        float xformOp:rotateZ = 90
        uniform token[] xformOpOrder = ["xformOp:rotateZ"]

        def Mesh "plate" (
            prepend apiSchemas = ["MaterialBindingAPI"]
        )
        {
            uniform token orientation = "leftHanded"
            point3f[] points = [(0, 0, 0), (10, 0, 0), (10, 10, 0), (0, 10, 0)]
            int[] faceVertexCounts = [4]
            int[] faceVertexIndices = [0, 1, 2, 3]
            rel material:binding = </craft/Looks/gold>
        }
    }

    def Mesh "body" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        point3f[] points = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, 0, 10)]
        int[] faceVertexCounts = [3, 3, 3, 3]
        int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
        rel material:binding = </craft/Looks/gold>

        def GeomSubset "radiator" (
            prepend apiSchemas = ["MaterialBindingAPI"]
        )
        {
            uniform token elementType = "face"
            uniform token familyName = "materialBind"
            int[] indices = [1, 3]
            rel material:binding = </craft/Looks/white>
        }
    }

    def Mesh "wing" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        uniform bool doubleSided = 1
        point3f[] points = [(0, 20, 0), (30, 20, 0), (30, 25, 0)]
        int[] faceVertexCounts = [3]
        int[] faceVertexIndices = [0, 1, 2]
        rel material:binding = </craft/Looks/cell>
        rel sunwind:backMaterial = </craft/Looks/kapton>
    }

    def Mesh "helper" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        uniform token purpose = "guide"
        point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
        int[] faceVertexCounts = [3]
        int[] faceVertexIndices = [0, 1, 2]
    }

    def Mesh "spare" (
        active = false
    )
    {
        point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
        int[] faceVertexCounts = [3]
        int[] faceVertexIndices = [0, 1, 2]
    }

    def Scope "Looks"
    {
        def Material "gold"
        {
            float sunwind:reflectivity = 0.3
            float sunwind:specularFraction = 0.5
            float sunwind:transmissivity = 0
        }

        def Material "white"
        {
        }

        def Material "cell"
        {
            double sunwind:reflectivity = 0.1
            double sunwind:specularFraction = 0.9
            double sunwind:transmissivity = 0
        }

        def Material "kapton"
        {
            float sunwind:reflectivity = 0.2
            float sunwind:specularFraction = 0.25
            float sunwind:transmissivity = 0.6
        }
    }
}
"""


@pytest.fixture
def handwritten_usda(tmp_path) -> Path:
    path = tmp_path / "craft.usda"
    path.write_text(HANDWRITTEN_USDA)
    return path


def test_handwritten_usda(handwritten_usda):
    mesh = load_mesh(handwritten_usda)
    assert mesh.part_names == ("/craft/arm/plate", "/craft/body", "/craft/wing")
    assert mesh.metadata["unit"] == "cm (USD metersPerUnit)"
    assert mesh.metadata["metres_per_unit"] == 0.01

    plate = mesh.faces[mesh.face_part == 0]
    assert len(plate) == 2  # the quad, fan-triangulated
    # rotated 90 degrees about z, moved 100 cm along x, then converted to metres
    corners = mesh.vertices[np.unique(plate)]
    np.testing.assert_allclose(
        sorted(map(tuple, corners)), [(0.9, 0, 0), (0.9, 0.1, 0), (1.0, 0, 0), (1.0, 0.1, 0)], atol=1e-12
    )
    a, b, c = mesh.vertices[plate[0]]
    normal = np.cross(b - a, c - a)
    assert normal[2] < 0  # leftHanded: the front faces -z once wound counter-clockwise

    body = mesh.face_part == 1
    assert signed_volume(MeshData(mesh.vertices, mesh.faces[body], np.zeros(4), ("b",), np.zeros(4))) > 0
    names = np.array(mesh.material_names)[mesh.face_material]
    assert names.tolist() == ["gold", "gold", "gold", "white", "gold", "white", "cell"]
    assert mesh.file_optics == OPTICS  # float32 values read back as the decimals written
    assert mesh.two_sided_parts == {"/craft/wing"}
    assert mesh.part_back_material == {"/craft/wing": "kapton"}


def test_usd_unit_given_by_user_wins_and_says_so(handwritten_usda):
    mesh = load_mesh(handwritten_usda, unit="mm")
    assert mesh.metadata["unit"] == "mm (--unit; overrides USD metersPerUnit: cm)"
    np.testing.assert_allclose(mesh.vertices[mesh.faces[-1]][1], [0.13, 0.02, 0])


def test_usd_rereads_a_file_rewritten_while_its_layer_is_held(tmp_path):
    path = tmp_path / "sample.usdc"
    save_mesh(sample_mesh(), path)
    held = Sdf.Layer.FindOrOpen(str(path))  # e.g. a viewer or a builder keeping the stage open
    one = MeshData(np.eye(3), [[0, 1, 2]], [0], ("/sample/one",), [-1])
    save_mesh(one, path)
    assert load_mesh(path).part_names == ("/sample/one",)
    assert held


def test_usdz_package_is_read(tmp_path):
    save_mesh(sample_mesh(), tmp_path / "sample.usdc")
    assert UsdUtils.CreateNewUsdzPackage(
        Sdf.AssetPath(str(tmp_path / "sample.usdc")), str(tmp_path / "s.usdz")
    )
    loaded = load_mesh(tmp_path / "s.usdz")
    assert face_table(loaded) == face_table(sample_mesh())
    assert loaded.file_optics == OPTICS


def test_usd_without_meters_per_unit_is_metres(tmp_path):
    path = tmp_path / "plain.usda"
    path.write_text(HANDWRITTEN_USDA.replace("    metersPerUnit = 0.01\n", ""))
    assert load_mesh(path).metadata["unit"] == "m (default)"


def test_gltf_node_transforms_and_mirroring(tmp_path):
    """A mirrored node keeps its box closed and outward-wound; a plain node is translated."""
    box = trimesh.creation.box()
    scene = trimesh.Scene()
    mirror = np.diag([-1.0, 1.0, 1.0, 1.0])
    mirror[:3, 3] = [5, 0, 0]
    scene.add_geometry(box, node_name="left", geom_name="box_mesh", transform=mirror)
    move = np.eye(4)
    move[:3, 3] = [0, 7, 0]
    scene.add_geometry(box, node_name="right", geom_name="box_mesh", transform=move)
    path = tmp_path / "scene.glb"
    scene.export(path)
    mesh = load_mesh(path)
    assert set(mesh.part_names) == {"left", "right"}
    assert mesh.metadata["unit"] == "m (glTF specification)"
    for index, name in enumerate(mesh.part_names):
        faces = mesh.faces[mesh.face_part == index]
        part = MeshData(mesh.vertices, faces, np.zeros(len(faces)), (name,), np.zeros(len(faces)))
        assert signed_volume(part) == pytest.approx(1.0)
        centre = mesh.vertices[np.unique(faces)].mean(axis=0)
        np.testing.assert_allclose(centre, [5, 0, 0] if name == "left" else [0, 7, 0], atol=1e-12)


def test_gltf_unnamed_node_takes_its_mesh_name(tmp_path):
    path = tmp_path / "unnamed.gltf"
    save_mesh(sample_mesh(), path)
    document = json.loads(path.read_text())
    for node in document["nodes"]:
        del node["name"]
    document["meshes"][0]["name"] = "hull"
    path.write_text(json.dumps(document))
    assert load_mesh(path).part_names[0] == "hull"


def test_stl_loader_merges_no_vertices(tmp_path):
    save_mesh(sample_mesh(), tmp_path / "a.stl")
    mesh = load_mesh(tmp_path / "a.stl")
    assert mesh.vertices.shape == (3 * mesh.n_faces, 3)


def test_writers_do_not_crash_on_nan(tmp_path):
    mesh = sample_mesh()
    vertices = mesh.vertices.copy()
    vertices[0] = np.nan
    broken = MeshData(vertices, mesh.faces, mesh.face_part, mesh.part_names, mesh.face_material,
                      mesh.material_names)  # fmt: skip
    for suffix in WRITABLE:
        save_mesh(broken, tmp_path / f"nan{suffix}")
        assert np.isnan(load_mesh(tmp_path / f"nan{suffix}").vertices).any()


# ---------------------------------------------------------------------------------------------
# units


@pytest.mark.parametrize("unit", UNITS)
def test_unit_scaling(tmp_path, unit):
    mesh = sample_mesh()
    save_mesh(mesh, tmp_path / "a.obj")
    loaded = load_mesh(tmp_path / "a.obj", unit=unit)
    np.testing.assert_array_equal(loaded.vertices, mesh.vertices * UNITS[unit])
    assert loaded.metadata["unit"] == f"{unit} (--unit)"
    assert loaded.metadata["metres_per_unit"] == UNITS[unit]


def test_unit_table():
    assert UNITS == {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254}
    assert SUPPORTED_SUFFIXES == (".stl", ".obj", ".ply", ".gltf", ".glb", ".usd", ".usda", ".usdc", ".usdz")


def test_unknown_unit(tmp_path):
    save_mesh(sample_mesh(), tmp_path / "a.obj")
    error = raised(InputError, load_mesh, tmp_path / "a.obj", unit="ft")
    assert (error.message, error.hint) == ("unknown unit 'ft'", "use one of m, mm, cm, in")


# ---------------------------------------------------------------------------------------------
# errors: each is one line naming the file, what is wrong and the fix


def raised(kind: type[SunwindError], function, path: Path, **kwargs) -> SunwindError:
    """The error ``function(path, **kwargs)`` raises; checks it is one line naming the file."""
    with pytest.raises(kind) as caught:
        function(path, **kwargs)
    error = caught.value
    assert error.path == str(path) and error.hint
    text = str(error)
    assert text.startswith(str(path)) and "\n" not in text
    assert error.message in text and error.hint in text
    return error


def load_error(path: Path) -> MeshError:
    """The error ``load_mesh`` raises for ``path``."""
    return raised(MeshError, load_mesh, path)


def test_missing_file(tmp_path):
    error = load_error(tmp_path / "nope.obj")
    assert (error.message, error.hint) == ("file not found", "check the path and its spelling")


def test_directory(tmp_path):
    (tmp_path / "meshes.obj").mkdir()
    error = load_error(tmp_path / "meshes.obj")
    assert error.message == "is a directory, not a mesh file"
    assert error.hint == f"give the path of a mesh file ({', '.join(SUPPORTED_SUFFIXES)})"


@pytest.mark.parametrize(("name", "problem"), [("craft.step", "unknown mesh format '.step'"),
                                               ("craft", "has no file extension")])  # fmt: skip
def test_unknown_extension(tmp_path, name, problem):
    path = tmp_path / name
    path.write_text("solid")
    error = load_error(path)
    assert error.message == problem
    assert (
        error.hint
        == "use one of .stl, .obj, .ply, .gltf, .glb, .usd, .usda, .usdc, .usdz, or convert the file"
    )


@pytest.mark.parametrize("suffix", [".glb", ".usdc", ".usda", ".ply", ".usdz"])
def test_garbage_content(tmp_path, suffix):
    path = tmp_path / f"junk{suffix}"
    path.write_bytes(np.random.default_rng(1).bytes(700))
    error = load_error(path)
    kind = suffix[1:].upper()
    assert error.message.startswith(f"not a readable {kind} file (")
    assert error.hint == f"check that it is a complete {kind} file, e.g. export it again"
    assert "pxrInternal" not in error.message and "Error in" not in error.message


def test_garbage_stl(tmp_path):
    path = tmp_path / "junk.stl"
    path.write_bytes(np.random.default_rng(1).bytes(700))
    error = load_error(path)
    assert error.message == (
        "is neither a binary STL (700 bytes, not 84 + 50 per triangle) nor an ASCII STL "
        "(starting with 'solid')"
    )
    assert error.hint == "check that the file is complete, e.g. export it again"


def test_garbage_gltf(tmp_path):
    path = tmp_path / "junk.gltf"
    path.write_bytes(b"{not json")
    error = load_error(path)
    assert error.message == (
        "is not glTF JSON text (Expecting property name enclosed in double quotes: line 1 column 2 (char 1))"
    )
    assert error.hint == "check that it is a complete glTF file, e.g. export it again"


def test_gltf_missing_buffer(tmp_path):
    path = tmp_path / "split.gltf"
    save_mesh(sample_mesh(), path)
    document = json.loads(path.read_text())
    document["buffers"][0]["uri"] = "split.bin"
    path.write_text(json.dumps(document))
    error = load_error(path)
    assert error.message == "refers to a file that is missing (split.bin)"
    assert error.hint == "keep the files it refers to next to it, or export it as one file (.glb, .usdz)"


def test_binary_obj(tmp_path):
    path = tmp_path / "junk.obj"
    path.write_bytes(b"v 0 0 0\x00\x01\x02")
    error = load_error(path)
    assert error.message == "contains binary data, not OBJ text"
    assert error.hint == "check that the file is a Wavefront OBJ text file"


THREE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        (THREE + "f 1 2 9\n", "line 4: face refers to vertex 9, but the file has 3 vertices"),
        ("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n",
         "line 3: face refers to vertex -3, but only 2 vertices precede it"),
        (THREE + "f 0 1 2\n", "line 4: face refers to vertex 0, but OBJ indices start at 1"),
        (THREE + "f 1 2.5 3\n", "line 4: face vertex indices are not integers"),
        ("v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex coordinates are not numbers"),
        ("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex has fewer than 3 coordinates"),
        (THREE + "\nf 1 2\n", "line 5: face has 2 vertices, a face needs at least 3"),
    ],
)  # fmt: skip
def test_corrupt_obj(tmp_path, text, problem):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    error = load_error(path)
    assert (error.message, error.hint) == (problem, "fix that line or re-export the OBJ file")


@pytest.mark.parametrize(
    ("name", "content"),
    [
        ("points.obj", b"v 0 0 0\nv 1 0 0\nl 1 2\n"),
        ("empty.stl", b"\0" * 84),
        ("nothing.usda", b'#usda 1.0\ndef Xform "craft"\n{\n}\n'),
        ("lines.glb", None),
    ],
)
def test_empty_mesh(tmp_path, name, content):
    path = tmp_path / name
    if content is None:
        trimesh.Scene([trimesh.load_path(np.array([[0.0, 0, 0], [1, 0, 0]]))]).export(path)
    else:
        path.write_bytes(content)
    error = load_error(path)
    assert error.message == "contains no triangles"
    assert error.hint == (
        "export the surfaces as triangle or polygon meshes "
        "(points, lines, curves, inactive and guide prims are not read)"
    )


def usd_error(tmp_path: Path, old: str, new: str) -> MeshError:
    """The error for the handwritten stage with ``old`` replaced by ``new``."""
    assert old in HANDWRITTEN_USDA
    path = tmp_path / "broken.usda"
    path.write_text(HANDWRITTEN_USDA.replace(old, new))
    return load_error(path)


def test_usd_partial_optics(tmp_path):
    error = usd_error(tmp_path, "float sunwind:transmissivity = 0.6", "")
    assert (
        error.message
        == "Material /craft/Looks/kapton has some sunwind optics but lacks sunwind:transmissivity"
    )
    assert error.hint == (
        "author all of sunwind:reflectivity, sunwind:specularFraction, sunwind:transmissivity, or none"
    )


def test_usd_optics_not_a_number(tmp_path):
    error = usd_error(tmp_path, "float sunwind:reflectivity = 0.2", 'string sunwind:reflectivity = "high"')
    assert error.message == "sunwind:reflectivity on Material /craft/Looks/kapton is 'high', not a number"
    assert error.hint == "author it as 'float sunwind:reflectivity = 0.5'"


def test_usd_same_material_name_different_optics(tmp_path):
    error = usd_error(
        tmp_path,
        "rel material:binding = </craft/Looks/cell>",
        'rel material:binding = </craft/wing/gold>\n        def Material "gold"\n        {\n        }',
    )
    assert error.message == (
        "Materials /craft/Looks/gold and /craft/wing/gold share the name 'gold' but carry "
        "different sunwind optics"
    )


def test_usd_holes(tmp_path):
    error = usd_error(
        tmp_path,
        "        uniform bool doubleSided = 1\n",
        "        uniform bool doubleSided = 1\n        int[] holeIndices = [0]\n",
    )
    assert error.part == "/craft/wing"
    assert error.message == "has polygons with holes (holeIndices), which sunwind does not read"
    assert error.hint == "triangulate the mesh in the authoring tool and re-export"


def test_usd_back_material_not_a_material(tmp_path):
    error = usd_error(
        tmp_path, "sunwind:backMaterial = </craft/Looks/kapton>", "sunwind:backMaterial = </craft/body>"
    )
    assert error.part == "/craft/wing"
    assert error.message == "has sunwind:backMaterial targeting ['/craft/body'], not one Material prim"


@pytest.mark.parametrize(
    ("old", "new", "problem"),
    [
        ("int[] indices = [1, 3]", "int[] indices = [1, 4]",
         "has GeomSubset 'radiator' listing faces outside 0..3"),
        ("[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]", "[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 7]",
         "has faceVertexIndices referring to point 7 but only 4 points"),
        ("[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]", "[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2]",
         "has faceVertexCounts adding up to 12 but 11 faceVertexIndices"),
        ("int[] faceVertexCounts = [3, 3, 3, 3]", "int[] faceVertexCounts = [3, 3, 4, 2]",
         "has face 3 with 2 vertices, but a face needs at least 3"),
    ],
)  # fmt: skip
def test_usd_bad_topology(tmp_path, old, new, problem):
    error = usd_error(tmp_path, old, new)
    assert (error.part, error.message) == ("/craft/body", problem)
    assert error.hint == "re-export the mesh from the authoring tool"


def test_unreadable_file(tmp_path, monkeypatch):
    path = tmp_path / "locked.obj"
    path.write_text("v 0 0 0\n")

    def refuse(file, mode="r"):
        raise PermissionError(13, "Permission denied", str(file))

    monkeypatch.setattr("sunwind.geometry.io.registry.open", refuse, raising=False)  # root reads anything
    error = load_error(path)
    assert (error.message, error.hint) == (
        "cannot open the file (Permission denied)",
        "check that you may read it",
    )


def save_error(mesh: MeshData, path: Path, **kwargs) -> InputError:
    """The error ``save_mesh`` raises for ``mesh`` and ``path``."""
    return raised(InputError, lambda p, **k: save_mesh(mesh, p, **k), path, **kwargs)


def test_save_unwritable_suffix(tmp_path):
    error = save_error(sample_mesh(), tmp_path / "a.usdz")
    assert error.message == "cannot write '.usdz' files"
    assert error.hint == "use one of .stl, .obj, .ply, .gltf, .glb, .usd, .usda, .usdc"


def test_save_missing_folder(tmp_path):
    error = save_error(sample_mesh(), tmp_path / "no" / "a.obj")
    assert (error.message, error.hint) == (f"folder '{tmp_path / 'no'}' does not exist", "create it first")


def test_save_empty_mesh(tmp_path):
    empty = MeshData(np.zeros((0, 3)), np.zeros((0, 3)), [], (), [])
    error = save_error(empty, tmp_path / "a.obj")
    assert (error.message, error.hint) == ("the mesh has no triangles to write", "give a mesh with faces")


@pytest.mark.parametrize(
    ("optics", "problem"),
    [
        ({"gold": {"reflectivity": 0.3, "specular_fraction": 0.5}}, "lack 'transmissivity'"),
        ({"gold": {**OPTICS["gold"], "rho": 0.3}}, "have an unknown key 'rho'"),
    ],
)
def test_save_bad_optics(tmp_path, optics, problem):
    error = save_error(sample_mesh(), tmp_path / "a.usda", optics=optics)
    assert error.message == f"optics of material 'gold' {problem}"
    assert error.hint == (
        "give exactly reflectivity, specular_fraction, transmissivity (and optionally emissivity) for each "
        "material"
    )


def test_save_onto_a_directory(tmp_path):
    (tmp_path / "taken.obj").mkdir()
    error = save_error(sample_mesh(), tmp_path / "taken.obj")
    assert error.message == "cannot write the file (Is a directory)"
    assert error.hint == "check that you may write to it and its folder"
