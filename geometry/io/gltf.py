"""Writing glTF 2.0 (``.gltf`` with an embedded buffer, or binary ``.glb``): a node per part.

sunwind writes glTF itself because trimesh's exporter gives each mesh one material, while a
part may carry several: here each part is one node with one mesh, and each of the part's
material keys is one primitive of that mesh, so a reader sees the part names as node names and
the material keys as material names. Reading goes through trimesh (``trimesh_.read_gltf``).
"""

from __future__ import annotations

import base64
import json
import struct
from pathlib import Path

import numpy as np

from sunwind.geometry.io.topology import bounds, compact, groups
from sunwind.geometry.mesh_data import MeshData

# glTF enumerations (glTF 2.0 specification, section 5)
_FLOAT, _UNSIGNED_INT = 5126, 5125
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963


def write_gltf(mesh: MeshData, path: Path) -> None:
    """Write the mesh as a glTF 2.0 scene, binary when ``path`` ends in ``.glb``.

    Parameters
    ----------
    mesh : MeshData
        The mesh to write. Coordinates are stored as float32 (the only type glTF allows for
        positions) and taken to be metres, glTF's unit.
    path : Path
        The ``.gltf`` or ``.glb`` file to create or overwrite.

    Notes
    -----
    Optics, two-sided parts and back materials are not written: glTF has no place for them
    (its ``doubleSided`` is a rendering flag of a material, not of a part).

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.geometry.io.trimesh_ import read_gltf
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_gltf(box(), Path(folder) / "box.glb")
    ...     mesh = read_gltf(Path(folder) / "box.glb")
    >>> mesh.n_faces, mesh.part_names
    (12, ('box',))
    """
    buffer = bytearray()
    header: dict = {
        "asset": {"version": "2.0", "generator": "sunwind"},
        "scene": 0,
        "scenes": [{"nodes": []}],
        "nodes": [],
        "meshes": [],
        "materials": [{"name": name} for name in mesh.material_names],
        "accessors": [],
        "bufferViews": [],
    }

    def add(array: np.ndarray, target: int, component: int, kind: str, **extra: object) -> int:
        """Append ``array`` to the buffer with its view and accessor; return the accessor index."""
        header["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(buffer), "byteLength": array.nbytes, "target": target}
        )
        buffer.extend(array.tobytes())
        buffer.extend(b"\0" * (-len(buffer) % 4))
        header["accessors"].append(
            {
                "bufferView": len(header["bufferViews"]) - 1,
                "componentType": component,
                "count": len(array),
                "type": kind,
                **extra,
            }
        )
        return len(header["accessors"]) - 1

    for part, face_ids in groups(mesh.face_part):
        used, faces = compact(mesh.faces[face_ids])
        points = mesh.vertices[used].astype("<f4")
        low, high = bounds(points)
        position = add(points, _ARRAY_BUFFER, _FLOAT, "VEC3", min=low.tolist(), max=high.tolist())
        primitives = []
        for material, chunk in groups(mesh.face_material[face_ids]):
            indices = add(faces[chunk].astype("<u4").ravel(), _ELEMENT_ARRAY_BUFFER, _UNSIGNED_INT, "SCALAR")
            primitive = {"attributes": {"POSITION": position}, "indices": indices}
            if material >= 0:
                primitive["material"] = material
            primitives.append(primitive)
        name = mesh.part_names[part]
        header["meshes"].append({"name": name, "primitives": primitives})
        header["nodes"].append({"name": name, "mesh": len(header["meshes"]) - 1})
        header["scenes"][0]["nodes"].append(len(header["nodes"]) - 1)
    if not header["materials"]:
        del header["materials"]
    if path.suffix.lower() == ".glb":
        header["buffers"] = [{"byteLength": len(buffer)}]
        path.write_bytes(_glb(json.dumps(header).encode(), bytes(buffer)))
    else:
        uri = "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()
        header["buffers"] = [{"byteLength": len(buffer), "uri": uri}]
        path.write_text(json.dumps(header), encoding="utf-8")


def _glb(document: bytes, binary: bytes) -> bytes:
    """A GLB container: 12-byte header, then a JSON chunk and a BIN chunk, each 4-byte aligned."""
    document += b" " * (-len(document) % 4)
    binary += b"\0" * (-len(binary) % 4)
    length = 12 + 8 + len(document) + 8 + len(binary)
    return b"".join(
        [
            struct.pack("<4sII", b"glTF", 2, length),
            struct.pack("<I4s", len(document), b"JSON"),
            document,
            struct.pack("<I4s", len(binary), b"BIN\0"),
            binary,
        ]
    )
