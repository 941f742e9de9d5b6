"""Mesh files by suffix: the reader and writer of each format, and the checks they all share.

Adding a format is a module with a reader returning :class:`MeshData` in file units (and
optionally ``metadata["declared_unit"] = (metres_per_unit, source)``) plus a line in
``LOADERS`` (and ``WRITERS``). Every problem reaches the user as one :class:`MeshError` or
:class:`InputError` line naming the file and the fix; no library exception escapes.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path

from sunwind.geometry.errors import InputError, MeshError, SunwindError
from sunwind.geometry.io.gltf import write_gltf
from sunwind.geometry.io.obj import read_obj, write_obj
from sunwind.geometry.io.trimesh_ import read_gltf, read_single, read_stl, write_ply, write_stl
from sunwind.geometry.io.units import parse_unit, resolve_unit
from sunwind.geometry.io.usd_ import PXR_NAMESPACE, composed_files, read_usd, write_usd
from sunwind.geometry.mesh_data import OPTICS_KEYS, OPTIONAL_OPTICS_KEYS, MeshData

#: Reader of each file suffix (lower case); it returns the file's data in file units.
LOADERS: dict[str, Callable[[Path], MeshData]] = {
    ".stl": read_stl,
    ".obj": read_obj,
    ".ply": read_single,
    ".gltf": read_gltf,
    ".glb": read_gltf,
    ".usd": read_usd,
    ".usda": read_usd,
    ".usdc": read_usd,
    ".usdz": read_usd,
}
#: Writer of each file suffix (lower case); it takes a mesh in metres.
WRITERS: dict[str, Callable[[MeshData, Path], None]] = {
    ".stl": write_stl,
    ".obj": write_obj,
    ".ply": write_ply,
    ".gltf": write_gltf,
    ".glb": write_gltf,
    ".usd": write_usd,
    ".usda": write_usd,
    ".usdc": write_usd,
}
#: Suffixes whose files hold one body: no parts, no material keys (:func:`save_mesh` merges the parts).
SINGLE_BODY_SUFFIXES: tuple[str, ...] = (".stl", ".ply")
#: Suffixes :func:`load_mesh` reads.
SUPPORTED_SUFFIXES: tuple[str, ...] = tuple(LOADERS)


def mesh_files(path: str | os.PathLike) -> list[Path]:
    """List every file that loading a mesh file reads.

    Parameters
    ----------
    path : str or os.PathLike
        The mesh file.

    Returns
    -------
    list of Path
        For a USD stage the stage and what it composes (references, payloads, sub-layers), sorted;
        else ``[path]``.

    Examples
    --------
    >>> mesh_files("craft.obj")
    [PosixPath('craft.obj')]
    """
    path = Path(path)
    return composed_files(path) if LOADERS.get(path.suffix.lower()) is read_usd else [path]


def load_mesh(path: str | os.PathLike[str], unit: str | None = None) -> MeshData:
    """Read a mesh file, chosen by its suffix (any case), and convert it to metres.

    Nothing is repaired: vertices are not merged, degenerate faces are kept and winding is as
    the file gives it (after USD orientation and mirroring transforms), so the model builder
    can check and count everything.

    Parameters
    ----------
    path : str or PathLike
        A file ending in one of ``SUPPORTED_SUFFIXES``.
    unit : {"m", "mm", "cm", "in"} or None
        Length unit of the file's coordinates. None: the unit the file declares (USD
        ``metersPerUnit`` when authored, metres for glTF), else metres. A given unit wins over
        a declared one.

    Returns
    -------
    MeshData
        Vertices [m] in the file's frame; ``source`` is ``path`` as given;
        ``metadata["unit"]`` says which unit was used and why (e.g. ``"mm (--unit)"``),
        ``metadata["metres_per_unit"]`` the factor applied, ``metadata["format"]`` the format.

    Raises
    ------
    InputError
        Unknown unit.
    MeshError
        Missing file, directory, unknown suffix, unreadable or corrupt content, no triangles.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     save_mesh(box(), Path(folder) / "box.obj")
    ...     mesh = load_mesh(Path(folder) / "box.obj", unit="mm")
    >>> mesh.n_faces, mesh.metadata["unit"], float(mesh.vertices.max())
    (12, 'mm (--unit)', 0.0005)
    """
    name = os.fspath(path)
    file = Path(name)
    unit = None if unit is None else parse_unit(unit, name)
    if not file.exists():
        raise MeshError("file not found", path=name, hint="check the path and its spelling")
    if file.is_dir():
        raise MeshError(
            "is a directory, not a mesh file",
            path=name,
            hint=f"give the path of a mesh file ({', '.join(SUPPORTED_SUFFIXES)})",
        )
    loader = LOADERS.get(file.suffix.lower())
    if loader is None:
        raise MeshError(
            f"unknown mesh format '{file.suffix}'" if file.suffix else "has no file extension",
            path=name,
            hint=f"use one of {', '.join(SUPPORTED_SUFFIXES)}, or convert the file",
        )
    kind = file.suffix[1:].upper()
    try:
        with open(file, "rb"):
            pass
    except OSError as exc:
        raise MeshError(
            f"cannot open the file ({exc.strerror or exc})", path=name, hint="check that you may read it"
        ) from exc
    try:
        mesh = loader(file)
    except SunwindError:
        raise
    except FileNotFoundError as exc:  # a glTF buffer or texture, a USD layer it refers to
        raise MeshError(
            f"refers to a file that is missing ({exc.filename or exc})",
            path=name,
            hint="keep the files it refers to next to it, or export it as one file (.glb, .usdz)",
        ) from exc
    except Exception as exc:  # any library failure on bad content becomes one line
        raise MeshError(
            f"not a readable {kind} file ({_summary(exc)})",
            path=name,
            hint=f"check that it is a complete {kind} file, e.g. export it again",
        ) from exc
    if mesh.n_faces == 0:
        raise MeshError(
            "contains no triangles",
            path=name,
            hint="export the surfaces as triangle or polygon meshes (points, lines, curves, "
            "inactive and guide prims are not read)",
        )
    metadata = dict(mesh.metadata)
    factor, label = resolve_unit(unit, metadata.pop("declared_unit", None))
    metadata.update(unit=label, metres_per_unit=factor, format=kind)
    return replace(mesh.scaled(factor), source=name, metadata=metadata)


def save_mesh(
    mesh: MeshData,
    path: str | os.PathLike[str],
    optics: Mapping[str, Mapping[str, float]] | None = None,
) -> None:
    """Write a mesh in metres to a file whose suffix (any case) chooses the format.

    What each format keeps: OBJ the float64 vertices exactly, parts and material keys; USD
    (``.usd`` binary, ``.usdc``, ``.usda``) parts, material keys, optics, two-sided parts and
    back materials, float32 points, metres; glTF/GLB a node per part and material names,
    float32; STL and PLY the triangles only, float32.

    Parameters
    ----------
    mesh : MeshData
        The mesh, with at least one triangle.
    path : str or PathLike
        The file to create or overwrite; its folder must exist.
    optics : mapping str -> mapping str -> float, optional
        Optics per material key, each with ``reflectivity``, ``specular_fraction`` and
        ``transmissivity``, and optionally ``emissivity``; written to USD only. Default
        ``mesh.file_optics``.

    Raises
    ------
    InputError
        Unwritable suffix, empty mesh, incomplete optics, missing folder, or a write failure.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import plate
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     save_mesh(plate(divisions=2), Path(folder) / "plate.stl")
    ...     load_mesh(Path(folder) / "plate.stl").n_faces
    8
    """
    name = os.fspath(path)
    file = Path(name)
    writer = WRITERS.get(file.suffix.lower())
    if writer is None:
        raise InputError(
            f"cannot write '{file.suffix}' files" if file.suffix else "has no file extension",
            path=name,
            hint=f"use one of {', '.join(WRITERS)}",
        )
    if mesh.n_faces == 0:
        raise InputError("the mesh has no triangles to write", path=name, hint="give a mesh with faces")
    optics = mesh.file_optics if optics is None else optics
    for material, values in optics.items():
        missing = set(OPTICS_KEYS) - set(values)
        unknown = set(values) - {*OPTICS_KEYS, *OPTIONAL_OPTICS_KEYS}
        if missing or unknown:
            wrong = sorted(missing | unknown)[0]
            problem = "lack" if wrong in missing else "have an unknown key"
            raise InputError(
                f"optics of material '{material}' {problem} '{wrong}'",
                path=name,
                hint=f"give exactly {', '.join(OPTICS_KEYS)} (and optionally "
                f"{', '.join(OPTIONAL_OPTICS_KEYS)}) for each material",
            )
    if not file.parent.is_dir():
        raise InputError(f"folder '{file.parent}' does not exist", path=name, hint="create it first")
    try:
        writer(replace(mesh, file_optics=optics), file)
    except OSError as exc:
        raise InputError(
            f"cannot write the file ({exc.strerror or exc})",
            path=name,
            hint="check that you may write to it and its folder",
        ) from exc


def _summary(exc: Exception) -> str:
    """First line of a library's error, without USD's C++ location prefix."""
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    if not lines:
        return type(exc).__name__
    first = lines[0]
    if first.startswith("Error in '") and " : '" in first:  # pxr Tf.ErrorException
        first = first.split(" : '", 1)[1].rstrip("'")
    first = PXR_NAMESPACE.sub("", first)
    return first if len(first) <= 160 else first[:157] + "..."
