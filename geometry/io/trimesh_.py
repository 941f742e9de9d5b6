"""STL, PLY and glTF/GLB files read through trimesh, and STL and PLY written through it.

Everything is loaded with ``process=False``: trimesh merges no vertices, drops no faces and
fixes no winding, so the model builder sees (and counts) what the file holds.
"""

from __future__ import annotations

import json
from collections.abc import Collection
from dataclasses import replace
from pathlib import Path

import numpy as np
import trimesh

from sunwind.geometry.errors import MeshError
from sunwind.geometry.io.topology import check_transform
from sunwind.geometry.mesh_data import MeshData


def read_stl(path: Path) -> MeshData:
    """Read a binary or ASCII STL file as one part (see :func:`read_single`).

    Parameters
    ----------
    path : Path
        The ``.stl`` file.

    Returns
    -------
    MeshData
        One part named after the file stem, in file units, without material keys.

    Raises
    ------
    MeshError
        The file is neither: a binary STL's size is 84 bytes plus 50 per triangle announced in
        its header, an ASCII STL starts with ``solid``. (trimesh's own message for this case
        is about text encodings.)

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_stl(box(), Path(folder) / "box.stl")
    ...     mesh = read_stl(Path(folder) / "box.stl")
    >>> mesh.n_faces, mesh.part_names
    (12, ('box',))
    """
    size = path.stat().st_size
    with open(path, "rb") as file:
        head = file.read(84)
    announced = int.from_bytes(head[80:84], "little") if size >= 84 else -1
    if size != 84 + 50 * announced and not head.lstrip()[:5].lower() == b"solid":
        raise MeshError(
            f"is neither a binary STL ({size} bytes, not 84 + 50 per triangle) nor an ASCII STL "
            "(starting with 'solid')",
            path=str(path),
            hint="check that the file is complete, e.g. export it again",
        )
    return read_single(path)


def read_single(path: Path) -> MeshData:
    """Read an STL or PLY file as one part named after the file stem, without material keys.

    Parameters
    ----------
    path : Path
        The ``.stl`` or ``.ply`` file.

    Returns
    -------
    MeshData
        Vertices in file units; a binary STL has three unshared vertices per triangle.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_ply(box(), Path(folder) / "cube.ply")
    ...     mesh = read_single(Path(folder) / "cube.ply")
    >>> mesh.n_faces, mesh.part_names, set(mesh.face_material.tolist())
    (12, ('cube',), {-1})
    """
    mesh = trimesh.load_mesh(path, file_type=path.suffix.lower()[1:], process=False)
    faces = getattr(mesh, "faces", np.zeros((0, 3), dtype=np.int64))  # a PLY may be points only
    return MeshData(
        vertices=mesh.vertices,
        faces=faces,
        face_part=np.zeros(len(faces), dtype=np.int32),
        part_names=(path.stem,),
        face_material=np.full(len(faces), -1, dtype=np.int32),
        source=str(path),
    )


def read_gltf(path: Path) -> MeshData:
    """Read a glTF or GLB scene: every node's triangles with its world transform applied.

    Parameters
    ----------
    path : Path
        The ``.gltf`` or ``.glb`` file.

    Returns
    -------
    MeshData
        Vertices in metres (glTF's unit by specification, recorded in
        ``metadata["declared_unit"]``). Part name: the node name, or the mesh name for an
        unnamed node. Material key: the name of the primitive's material, -1 when it has none
        or an unnamed one. A node whose transform mirrors (negative determinant) has its
        triangles' winding reversed, as the glTF specification prescribes.

    Notes
    -----
    trimesh names an unnamed node by its index, so a node named only with digits is taken as
    unnamed. It loads each primitive of a multi-primitive mesh as a child node called
    ``<node>_<6 characters>`` under the (geometry-less) node; such a child is reported under
    its parent's name (an unnamed parent gives a part per primitive, named as trimesh names
    the primitives: ``hull``, ``hull_1``). Points and lines primitives are skipped.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.geometry.io.gltf import write_gltf
    >>> from sunwind.meshes import plate
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_gltf(plate(divisions=1), Path(folder) / "plate.gltf")
    ...     mesh = read_gltf(Path(folder) / "plate.gltf")
    >>> mesh.n_faces, mesh.part_names, mesh.metadata["declared_unit"]
    (2, ('plate',), (1.0, 'glTF specification'))
    """
    if path.suffix.lower() == ".gltf":  # trimesh reports bad JSON as a missing file
        try:
            json.loads(path.read_bytes())
        except ValueError as exc:
            raise MeshError(
                f"is not glTF JSON text ({exc})",
                path=str(path),
                hint="check that it is a complete glTF file, e.g. export it again",
            ) from None
    scene = trimesh.load_scene(path, file_type=path.suffix.lower()[1:], process=False)
    graph = scene.graph
    mesh_order = {name: i for i, name in enumerate(scene.geometry)}
    pieces = []
    # in the file's mesh order, then by node name: trimesh's graph order is not the file's
    for node in sorted(graph.nodes_geometry, key=lambda n: (mesh_order[graph[n][1]], n)):
        matrix, geometry_name = graph[node]
        geometry = scene.geometry[geometry_name]
        if not isinstance(geometry, trimesh.Trimesh):
            continue
        parent = graph.transforms.parents.get(node, "")
        if _is_primitive_child(node, parent, graph.nodes_geometry):
            node = parent
        faces = np.asarray(geometry.faces, dtype=np.int64)
        check_transform(matrix[:3, :3], str(path), geometry_name if node.isdigit() else node)
        if np.linalg.det(matrix[:3, :3]) < 0:
            faces = faces[:, ::-1]
        material = getattr(getattr(geometry.visual, "material", None), "name", None)
        pieces.append(
            MeshData(
                vertices=geometry.vertices @ matrix[:3, :3].T + matrix[:3, 3],
                faces=faces,
                face_part=np.zeros(len(faces), dtype=np.int32),
                part_names=(geometry_name if node.isdigit() else node,),
                face_material=np.full(len(faces), 0 if material else -1, dtype=np.int32),
                material_names=(material,) if material else (),
            )
        )
    mesh = MeshData.concatenate(pieces, source=str(path))
    return replace(mesh, metadata={"declared_unit": (1.0, "glTF specification")})


def _is_primitive_child(node: str, parent: str, with_geometry: Collection[str]) -> bool:
    """Whether trimesh made ``node`` for one primitive of its parent's multi-primitive mesh."""
    return len(node) == len(parent) + 7 and node.startswith(f"{parent}_") and parent not in with_geometry


def write_stl(mesh: MeshData, path: Path) -> None:
    """Write a binary STL: float32 coordinates, three vertices per triangle, no parts.

    Parameters
    ----------
    mesh : MeshData
        The mesh to write [m].
    path : Path
        The ``.stl`` file to create or overwrite.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_stl(box(), Path(folder) / "box.stl")
    ...     (Path(folder) / "box.stl").stat().st_size == 84 + 50 * 12
    True
    """
    _trimesh(mesh).export(path, file_type="stl")


def write_ply(mesh: MeshData, path: Path) -> None:
    """Write a binary PLY: float32 coordinates with shared vertices, no parts.

    Parameters
    ----------
    mesh : MeshData
        The mesh to write [m].
    path : Path
        The ``.ply`` file to create or overwrite.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_ply(box(), Path(folder) / "box.ply")
    ...     len(read_single(Path(folder) / "box.ply").vertices)
    8
    """
    _trimesh(mesh).export(path, file_type="ply")


def _trimesh(mesh: MeshData) -> trimesh.Trimesh:
    """The mesh as an unprocessed trimesh, for its exporters."""
    return trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=False)
