"""Wavefront OBJ text files: objects and groups are parts, ``usemtl`` names are material keys.

sunwind reads OBJ itself because trimesh's reader merges groups, reorders faces and drops
``usemtl`` names when no ``.mtl`` file is present. The reader handles ``v``, ``f``, ``o``, ``g``
and ``usemtl`` statements, ``v/vt/vn`` corner forms, negative (relative) indices and polygons
(fan-triangulated); everything else (``vt``, ``vn``, ``mtllib``, ``s``, ``l``, ...) is skipped.
Material state persists across ``o`` and ``g`` lines, as the OBJ specification says.
"""

from __future__ import annotations

import re
from itertools import pairwise
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import MeshError
from sunwind.geometry.io.topology import fan_triangles
from sunwind.geometry.mesh_data import MeshData

#: A comment to the end of its line.
_COMMENT = re.compile(r"#[^\n]*")
#: Everything from the first slash of a ``v/vt/vn`` corner on, or a comment.
_CORNER_TAIL_OR_COMMENT = re.compile(r"/\S*|#[^\n]*")

_HINT = "fix that line or re-export the OBJ file"


def read_obj(path: Path) -> MeshData:
    r"""Read an OBJ file as it is: no vertex merging, no face removal, no winding changes.

    Parameters
    ----------
    path : Path
        The ``.obj`` file.

    Returns
    -------
    MeshData
        Vertices in file units. Part of a face: the last ``g`` name inside the current ``o``,
        else the ``o`` name, else the file stem. Material key: the last ``usemtl`` name, -1 before
        any. Parts and materials are listed in order of first declaration; ones without faces
        are left out.

    Raises
    ------
    MeshError
        Binary content, an unreadable number, a face with fewer than 3 corners or a face
        referring to a vertex that does not exist; the message gives the line number.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "tri.obj"
    ...     _ = path.write_text("o panel\nusemtl white\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    ...     mesh = read_obj(path)
    >>> mesh.faces.tolist(), mesh.part_names, mesh.material_names
    ([[0, 1, 2]], ('panel',), ('white',))
    """
    data = path.read_bytes()
    if b"\x00" in data:
        raise MeshError(
            "contains binary data, not OBJ text",
            path=str(path),
            hint="check that the file is a Wavefront OBJ text file",
        )
    v_rows: list[str] = []
    v_lines: list[int] = []
    f_rows: list[str] = []
    f_lines: list[int] = []
    # (faces read so far, part, material) at each o, g or usemtl statement
    states: list[tuple[int, int, int]] = []
    parts: dict[str, int] = {path.stem: 0}
    materials: dict[str, int] = {}
    object_name = group_name = ""
    part, material = 0, -1
    for number, line in enumerate(data.decode("utf-8", errors="replace").splitlines(), 1):
        head = line[:2]
        if head == "v ":  # fast path for the bulk of the file
            v_rows.append(line[2:])
            v_lines.append(number)
            continue
        if head == "f ":
            f_rows.append(line[2:])
            f_lines.append(number)
            continue
        if head in ("vt", "vn") or head[:1] == "#":
            continue
        fields = line.split(None, 1)
        if not fields:
            continue
        tag = fields[0]
        rest = fields[1].partition("#")[0].strip() if len(fields) > 1 else ""
        if tag == "v":
            v_rows.append(rest)
            v_lines.append(number)
        elif tag == "f":
            f_rows.append(rest)
            f_lines.append(number)
        elif tag in ("o", "g", "usemtl"):
            if tag == "o":
                object_name, group_name = rest, ""
            elif tag == "g":
                group_name = rest
            else:
                material = materials.setdefault(rest, len(materials)) if rest else -1
            part = parts.setdefault(group_name or object_name or path.stem, len(parts))
            states.append((len(f_rows), part, material))
    vertices = _parse_vertices(v_rows, v_lines, path)
    preceding = np.searchsorted(np.asarray(v_lines), np.asarray(f_lines))
    counts, corners = _parse_faces(f_rows, f_lines, preceding, len(vertices), path)
    state = np.array([(0, 0, -1), *states], dtype=np.int64).reshape(-1, 3)
    f_state = np.searchsorted(state[:, 0], np.arange(len(f_rows)), side="right") - 1
    f_part, f_material = state[f_state, 1], state[f_state, 2]
    triangles, polygon = fan_triangles(counts, corners)
    used_parts, face_part = np.unique(f_part[polygon], return_inverse=True)
    face_material = f_material[polygon]
    used_materials = np.unique(face_material[face_material >= 0])
    renumber = np.full(len(materials) + 1, -1, dtype=np.int64)  # last entry serves -1
    renumber[used_materials] = np.arange(len(used_materials))
    part_names, material_names = list(parts), list(materials)
    return MeshData(
        vertices=vertices,
        faces=triangles,
        face_part=face_part,
        part_names=tuple(part_names[i] for i in used_parts),
        face_material=renumber[face_material],
        material_names=tuple(material_names[i] for i in used_materials),
        source=str(path),
    )


def _parse_vertices(rows: list[str], lines: list[int], path: Path) -> NDArray[np.float64]:
    """Coordinates of ``v`` statements, ignoring a fourth ``w`` or trailing colour values."""
    tokens, counts = _split_rows(rows, _COMMENT)
    if np.any(counts < 3):
        line = lines[int(np.argmax(counts < 3))]
        raise MeshError(f"line {line}: vertex has fewer than 3 coordinates", path=str(path), hint=_HINT)
    try:
        values = np.array(tokens, dtype=np.float64)
    except ValueError:  # find the culprit among the coordinates; colour values may be anything
        values = np.array(
            [
                _numbers(row.partition("#")[0].split()[:3], float, line, path)
                for row, line in zip(rows, lines, strict=True)
            ]
        ).ravel()
        counts = np.full(len(rows), 3)
    if np.all(counts == 3):
        return values.reshape(-1, 3)
    position = np.arange(len(values)) - np.repeat(np.cumsum(counts) - counts, counts)
    return values[position < 3].reshape(-1, 3)


def _parse_faces(
    rows: list[str],
    lines: list[int],
    preceding: NDArray[np.int64],
    n_vertices: int,
    path: Path,
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Corner counts and zero-based vertex indices of ``f`` statements.

    ``preceding`` is the number of vertices defined before each face, which negative indices
    count back from.
    """
    tokens, counts = _split_rows(rows, _CORNER_TAIL_OR_COMMENT)
    if np.any(counts < 3):
        row = int(np.argmax(counts < 3))
        raise MeshError(
            f"line {lines[row]}: face has {counts[row]} vertices, a face needs at least 3",
            path=str(path),
            hint=_HINT,
        )
    try:
        raw = np.array(tokens, dtype=np.int64)
    except ValueError:
        for row, line in zip(rows, lines, strict=True):
            _numbers([c.split("/")[0] for c in row.partition("#")[0].split()], int, line, path)
        raise  # no single row is at fault: the registry reports numpy's own complaint
    before = np.repeat(preceding, counts)
    index = np.where(raw < 0, raw + before, raw - 1)
    bad = (raw == 0) | (index < 0) | (index >= n_vertices)
    if np.any(bad):
        corner = int(np.argmax(bad))
        row = int(np.searchsorted(np.cumsum(counts), corner, side="right"))
        if raw[corner] > 0:
            problem = f"but the file has {n_vertices} vertices"
        elif raw[corner] < 0:
            problem = f"but only {before[corner]} vertices precede it"
        else:
            problem = "but OBJ indices start at 1"
        raise MeshError(
            f"line {lines[row]}: face refers to vertex {raw[corner]}, {problem}",
            path=str(path),
            hint=_HINT,
        )
    return counts, index


def _split_rows(rows: list[str], drop: re.Pattern[str]) -> tuple[list[str], NDArray[np.int64]]:
    """Whitespace-separated tokens of all rows, after removing ``drop``, and each row's count."""
    text = drop.sub("", "\n".join(rows))
    tokens = text.split()
    raw = np.frombuffer(text.encode(), dtype=np.uint8)
    blank = np.isin(raw, np.frombuffer(b" \t\n", dtype=np.uint8))
    start = ~blank
    start[1:] &= blank[:-1]
    row = np.searchsorted(np.flatnonzero(raw == ord("\n")), np.flatnonzero(start))
    counts = np.bincount(row, minlength=len(rows))
    if counts.sum() != len(tokens):  # other whitespace characters: count row by row
        counts = np.array([len(row.split()) for row in text.split("\n")], dtype=np.int64)
    return tokens, counts


def _numbers(fields: list[str], kind: type, line: int, path: Path) -> list:
    """``fields`` converted by ``kind`` (``int`` or ``float``), or a MeshError naming the line."""
    try:
        return [kind(field) for field in fields]
    except ValueError:
        what = "face vertex indices are not integers" if kind is int else "vertex coordinates are not numbers"
        raise MeshError(f"line {line}: {what}", path=str(path), hint=_HINT) from None


def write_obj(mesh: MeshData, path: Path) -> None:
    """Write an OBJ file: all vertices once, then an ``o <part>`` block per part.

    Coordinates are written with Python's shortest round-trip ``repr``, so reading the file
    back gives bit-identical float64 vertices. Faces without a material key come first (an OBJ
    cannot unset a material once ``usemtl`` is given), then faces sorted by part and material
    with ``usemtl`` written at each switch. No ``.mtl`` file is written: material keys are
    names for the user's material file, and OBJ cannot carry sunwind optics.

    Parameters
    ----------
    mesh : MeshData
        The mesh to write; part and material names must not contain line breaks.
    path : Path
        The ``.obj`` file to create or overwrite.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_obj(box(), Path(folder) / "box.obj")
    ...     again = read_obj(Path(folder) / "box.obj")
    >>> bool(np.array_equal(again.vertices, box().vertices)), again.part_names
    (True, ('box',))
    """
    order = np.lexsort((mesh.face_material, mesh.face_part, mesh.face_material >= 0))
    part, material = mesh.face_part[order], mesh.face_material[order]
    faces = mesh.faces[order] + 1
    switch = np.flatnonzero((np.diff(part) != 0) | (np.diff(material) != 0)) + 1
    with open(path, "w", encoding="utf-8", newline="\n") as out:
        out.write(f"# sunwind mesh: {len(mesh.vertices)} vertices, {mesh.n_faces} triangles\n")
        out.write(("v %r %r %r\n" * len(mesh.vertices)) % tuple(mesh.vertices.ravel().tolist()))
        previous_part = previous_material = -1
        for start, stop in pairwise([0, *switch.tolist(), len(order)]):
            if part[start] != previous_part:
                out.write(f"o {mesh.part_names[part[start]]}\n")
                previous_part = part[start]
                previous_material = -1
            if material[start] >= 0 and material[start] != previous_material:
                out.write(f"usemtl {mesh.material_names[material[start]]}\n")
                previous_material = material[start]
            out.write(("f %d %d %d\n" * (stop - start)) % tuple(faces[start:stop].ravel().tolist()))
