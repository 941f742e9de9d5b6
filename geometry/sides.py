"""Which sides of each facet meet light, and with which material: the material assignment rules."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError, MaterialError, combine
from sunwind.geometry.materials import Material, MaterialSpec, MaterialTable, part_matches, toml_key
from sunwind.geometry.mesh_data import MeshData

#: Facet kinds: a facet of a closed body (front side only), an open sheet lit from the front only,
#: and a zero-thickness sheet whose two sides are both lit, each with its own material.
SOLID, ONE_SIDED, TWO_SIDED = 0, 1, 2

UNIFORM_NAME = "uniform"

_NO_MATERIAL_HINT = (
    "add {what} to the materials file, "
    "or give a uniform material (uniform=Material(...); on the command line --reflectivity and "
    "--specular-fraction)"
)


@dataclass(frozen=True, eq=False)
class SideAssignment:
    """Kind and front and back materials of every face.

    Attributes
    ----------
    face_kind : (n_faces,) int8
        ``SOLID``, ``ONE_SIDED`` or ``TWO_SIDED``.
    front_material, back_material : (n_faces,) int32
        Indices into ``table``; ``back_material`` is -1 where the back side is not lit.
    table : MaterialTable
        The materials in use, in index order.
    part_summary : dict
        Part name -> human description of its materials and where they came from.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.meshes import box
    >>> sides = assign_sides(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> sides.face_kind[:3], sides.back_material[:3], sides.table.names
    (array([0, 0, 0], dtype=int8), array([-1, -1, -1], dtype=int32), ('m',))
    """

    face_kind: NDArray[np.int8]
    front_material: NDArray[np.int32]
    back_material: NDArray[np.int32]
    table: MaterialTable
    part_summary: dict[str, str]


class _Catalogue:
    """The materials in use, each given one index, resolved from the user's file, the mesh file or
    the command line, in that order."""

    def __init__(self, mesh: MeshData, spec: MaterialSpec | None, uniform: Material | None) -> None:
        self.mesh, self.spec, self.uniform = mesh, spec, uniform
        self.used: list[Material] = []
        self.origin: list[str] = []
        self.missing: list[MaterialError] = []
        self.missing_keys: list[str | None] = []

    def index(self, material: Material, origin: str) -> int:
        for i, known in enumerate(self.used):
            if known.name == material.name and self.origin[i] == origin:
                return i
        self.used.append(material)
        self.origin.append(origin)
        return len(self.used) - 1

    def resolve(self, key: str | None, part: str) -> tuple[int, str]:
        """Index and description of the material for mesh material ``key`` on ``part``; a key without
        a material is noted in :attr:`missing` (index -1), for :meth:`raise_missing`."""
        if key is not None and self.spec is not None and key in self.spec.materials:
            return self.index(self.spec.materials[key], "materials file"), f"{key} (materials file)"
        if key is not None and key in self.mesh.file_optics:
            material = Material.checked(key, self.mesh.file_optics[key], self.mesh.source)
            return self.index(material, "mesh file"), f"{key} (mesh file)"
        if self.uniform is not None:
            return self.index(self.uniform, "command line"), f"{UNIFORM_NAME} (command line)"
        detail = f"has material key '{key}', which is not defined" if key else "has no material"
        path = self.spec.source if self.spec and self.spec.source else self.mesh.source
        self.missing.append(MaterialError(detail, path=path, part=part))
        self.missing_keys.append(key)
        return -1, "(none)"

    def raise_missing(self) -> None:
        """Raise one error listing every part and key left without a material, with one fix."""
        if not self.missing:
            return
        keys = [f"[materials.{toml_key(k)}]" for k in dict.fromkeys(self.missing_keys) if k is not None]
        if keys:
            what = f"the material table{'s' if len(keys) > 1 else ''} {', '.join(keys)}"
            if None in self.missing_keys:
                what += " and [parts] entries for the parts without a material key"
        else:
            what = "[parts] entries (or [materials.NAME] tables for the mesh file's material keys)"
        raise combine(self.missing, hint=_NO_MATERIAL_HINT.format(what=what))

    def table(self) -> MaterialTable:
        return MaterialTable.from_materials(self.used)


def assign_sides(
    mesh: MeshData,
    spec: MaterialSpec | None = None,
    uniform: Material | None = None,
    two_sided: Sequence[str] = (),
) -> SideAssignment:
    """Give every face its kind and front and back materials.

    Per part, the first matching ``[parts]`` rule of ``spec`` wins. A part no rule matches uses the
    mesh file's material key per face, looked up in ``spec``'s ``[materials]``, then in optics the
    mesh file carries; ``uniform`` (the command-line material) fills whatever is still unassigned.
    A part is two-sided when its rule is a ``{front, back}`` table, when the mesh file declares it
    (USD ``doubleSided``) or when it matches a ``two_sided`` glob.

    Parameters
    ----------
    mesh : MeshData
        The mesh, with its parts and material keys.
    spec : MaterialSpec or None, optional
        The materials file's contents.
    uniform : Material or None, optional
        Material for every face nothing else assigns.
    two_sided : sequence of str, optional
        Part globs to treat as two-sided sheets.

    Returns
    -------
    SideAssignment
        Kinds, material indices and a summary per part.

    Raises
    ------
    MaterialError
        Parts (or some of their faces) without a material, all of them in one error.
    InputError
        A ``two_sided`` glob that matches no part.

    Warns
    -----
    UserWarning
        A ``[parts]`` glob that matches no part (the file may be meant for other models too).

    Examples
    --------
    >>> from sunwind.geometry.materials import parse_materials
    >>> from sunwind.meshes import plate
    >>> spec = parse_materials({"materials": {"foil": {"reflectivity": 0.9, "specular_fraction": 0.9},
    ...     "black": {"reflectivity": 0.1, "specular_fraction": 0.0}},
    ...     "parts": {"plate": {"front": "foil", "back": "black"}}})
    >>> sides = assign_sides(plate(divisions=1), spec)
    >>> sides.face_kind.tolist(), sides.back_material.tolist(), sides.part_summary["plate"]
    ([2, 2], [1, 1], 'front foil, back black ([parts] "plate")')
    """
    _check_globs(mesh, spec, two_sided)
    catalogue = _Catalogue(mesh, spec, uniform)
    n = mesh.n_faces
    kind = np.full(n, SOLID, dtype=np.int8)
    front = np.full(n, -1, dtype=np.int32)
    back = np.full(n, -1, dtype=np.int32)
    summary: dict[str, str] = {}
    keys = np.asarray((*mesh.material_names, None), dtype=object)
    for part_index, part in enumerate(mesh.part_names):
        faces = np.flatnonzero(mesh.face_part == part_index)
        if len(faces) == 0:
            continue
        rule = spec.rule_for(part) if spec is not None else None
        declared_two_sided = part in mesh.two_sided_parts or any(part_matches(part, g) for g in two_sided)
        if rule is not None:
            f_index = catalogue.index(spec.materials[rule.front], "materials file")
            front[faces] = f_index
            if rule.sheet:
                kind[faces] = TWO_SIDED if rule.back is not None else ONE_SIDED
                if rule.back is not None:
                    back[faces] = catalogue.index(spec.materials[rule.back], "materials file")
                    summary[part] = f'front {rule.front}, back {rule.back} ([parts] "{rule.pattern}")'
                else:
                    summary[part] = f'{rule.front}, front side only ([parts] "{rule.pattern}")'
            else:
                summary[part] = f'{rule.front} ([parts] "{rule.pattern}")'
                if declared_two_sided:
                    kind[faces] = TWO_SIDED
                    back[faces] = f_index
                    summary[part] += ", both sides"
            continue
        descriptions = []
        face_keys = keys[mesh.face_material[faces]]
        for key in dict.fromkeys(face_keys.tolist()):
            index, text = catalogue.resolve(key, part)
            front[faces[face_keys == key]] = index
            descriptions.append(text)
        summary[part] = ", ".join(descriptions)
        if declared_two_sided:
            kind[faces] = TWO_SIDED
            back_key = mesh.part_back_material.get(part)
            if back_key is None:
                back[faces] = front[faces]
                summary[part] += ", both sides"
            else:
                back[faces], text = catalogue.resolve(back_key, part)
                summary[part] = f"front {summary[part]}, back {text}"
    catalogue.raise_missing()
    return SideAssignment(kind, front, back, catalogue.table(), summary)


def _check_globs(mesh: MeshData, spec: MaterialSpec | None, two_sided: Sequence[str]) -> None:
    """Refuse a ``two_sided`` glob, and warn of a ``[parts]`` glob, that selects no part of ``mesh``."""
    parts = list(mesh.part_names)
    listed = ", ".join(parts[:20]) + (f", ... ({len(parts)} parts)" if len(parts) > 20 else "")
    for glob in two_sided:
        if not any(part_matches(part, glob) for part in parts):
            raise InputError(
                f"two_sided glob '{glob}' matches no part",
                path=mesh.source,
                hint=f"the parts are: {listed}",
                parameters=("two_sided",),
            )
    for rule in spec.rules if spec is not None else ():
        if not any(rule.matches(part) for part in parts):
            warnings.warn(
                f'{spec.source or "materials"}: [parts] "{rule.pattern}" matches no part of '
                f"{mesh.source} (its parts: {listed})",
                stacklevel=3,
            )


def declared_kinds(mesh: MeshData, spec: MaterialSpec | None, two_sided: Sequence[str]) -> NDArray[np.int8]:
    """Find the face kinds from the sheet declarations alone, for when the materials are incomplete.

    Parameters
    ----------
    mesh : MeshData
        The mesh.
    spec : MaterialSpec or None
        The materials file's contents, for its ``[parts]`` sheet rules.
    two_sided : sequence of str
        Part globs to treat as two-sided sheets.

    Returns
    -------
    (n_faces,) ndarray of int8
        ``SOLID``, ``ONE_SIDED`` or ``TWO_SIDED`` per face.

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> declared_kinds(box(), None, ["box"])[:4]
    array([2, 2, 2, 2], dtype=int8)
    """
    kind = np.full(mesh.n_faces, SOLID, dtype=np.int8)
    for index, part in enumerate(mesh.part_names):
        rule = spec.rule_for(part) if spec is not None else None
        if rule is not None and rule.sheet:
            kind[mesh.face_part == index] = TWO_SIDED if rule.back is not None else ONE_SIDED
        elif part in mesh.two_sided_parts or any(part_matches(part, g) for g in two_sided):
            kind[mesh.face_part == index] = TWO_SIDED
    return kind
