"""What ``sunwind info`` reports about a mesh: size, parts, materials, every check's outcome and the
survey of what its CAD export did (:mod:`sunwind.geometry.survey`)."""

from __future__ import annotations

import os
from collections.abc import Sequence

import numpy as np

from sunwind.geometry import triangles as tri
from sunwind.geometry.checks import check_mesh, size_notice
from sunwind.geometry.errors import MaterialError
from sunwind.geometry.materials import Material, MaterialSpec, load_materials
from sunwind.geometry.sides import ONE_SIDED, SOLID, TWO_SIDED, assign_sides, declared_kinds
from sunwind.geometry.spacecraft import CENTRE_OF_MASS
from sunwind.geometry.survey import survey_mesh

_SURFACE = {SOLID: "closed body", ONE_SIDED: "one-sided sheet", TWO_SIDED: "two-sided sheet"}


def describe(
    path: str | os.PathLike,
    materials: str | os.PathLike | None = None,
    unit: str | None = None,
    uniform: Material | None = None,
    two_sided: Sequence[str] = (),
) -> dict:
    """Load a mesh and report on it without stopping at problems a user needs to see all of.

    A part without material, or an open part not declared a sheet, is listed in ``checks``; a file
    that cannot be read, or a materials file that is invalid, still raises. The survey
    (:func:`sunwind.geometry.survey.survey_mesh`) is of the mesh as read, whether or not it passes
    the checks.

    Parameters
    ----------
    path : str or os.PathLike
        The mesh file.
    materials : str or os.PathLike or None, optional
        A materials TOML file.
    unit : str or None, optional
        Length unit of the mesh file, when it does not say (``"m"``, ``"mm"`` ...).
    uniform : Material or None, optional
        Material for every face nothing else assigns.
    two_sided : sequence of str, optional
        Part globs to treat as two-sided sheets.

    Returns
    -------
    dict
        JSON-ready: mesh, unit, triangles, area_m2, volume_m3, closed, bounds_m, reference_point,
        checks (list of str), parts (list of dict), materials (list of dict), survey (dict,
        :meth:`sunwind.geometry.survey.Survey.to_json`).

    Raises
    ------
    MeshError
        A mesh file that cannot be read.
    MaterialError
        A materials file that is invalid.

    Examples
    --------
    >>> from sunwind.meshes.samples import sample_path
    >>> report = describe(sample_path("sample_spacecraft.usda"))
    >>> report["triangles"], report["checks"], report["survey"]["open_edges"]["count"]
    (19984, ['all passed'], 618)
    """
    from sunwind.geometry.io import load_mesh

    mesh = load_mesh(path, unit=unit)
    spec: MaterialSpec | None = load_materials(materials) if materials is not None else None
    checks: list[str] = []
    try:
        sides = assign_sides(mesh, spec, uniform, two_sided)
        kind, part_materials, table = sides.face_kind, sides.part_summary, sides.table
    except MaterialError as error:
        checks += [f"materials: {problem}" for problem in error.problems or (error,)]
        kind = declared_kinds(mesh, spec, two_sided)
        part_materials, table = {}, None
    check = check_mesh(mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names, kind, mesh.source)
    checks += [n for n in (*check.notices, size_notice(check.vertices, mesh.metadata.get("unit", "m"))) if n]
    for part, count in check.open_edges.items():
        checks.append(f"part '{part}' is open ({count} boundary edges): declare it a sheet to use it")
    for part, (count, others) in check.open_alone.items():
        checks.append(
            f"part '{part}' is open on its own ({count} boundary edges): a closed body only together "
            f"with {', '.join(repr(o) for o in others)}"
        )
    for part, count in check.nonmanifold_edges.items():
        checks.append(f"part '{part}' has {count} non-manifold edges: declare it a sheet or split it")
    corners = check.vertices[check.faces]
    areas = tri.areas(corners)
    facet_part = mesh.face_part[check.kept]
    facet_kind = kind[check.kept]
    closed = check.closed and bool(np.all(facet_kind == SOLID))
    if spec is not None and spec.centre_of_mass_m is not None:
        reference, reference_name = np.array(spec.centre_of_mass_m), CENTRE_OF_MASS
    elif closed:
        reference, reference_name = tri.volume_centroid(corners), "volume centroid (default)"
    else:
        reference, reference_name = areas @ tri.centroids(corners) / areas.sum(), "area centroid (default)"
    keys = (*mesh.material_names, "")
    parts = []
    for index, name in enumerate(mesh.part_names):
        mine = facet_part == index
        if not mine.any():
            continue
        surface = _SURFACE[int(facet_kind[mine][0])]
        if name in check.open_edges or name in check.nonmanifold_edges:
            surface = "open, undeclared"
        elif name in check.open_alone:
            surface = "part of a body"
        file_keys = sorted({keys[k] for k in mesh.face_material[mesh.face_part == index]} - {""})
        parts.append(
            {
                "name": name,
                "triangles": int(mine.sum()),
                "area_m2": float(areas[mine].sum()),
                "surface": surface,
                "materials": part_materials.get(name, ", ".join(file_keys) or "(none)"),
            }
        )
    point = " ".join(f"{x:+.6f}" for x in np.round(reference, 6) + 0)  # + 0: no -0.000000
    return {
        "mesh": mesh.source,
        "unit": str(mesh.metadata.get("unit", "m")),
        "triangles": len(check.faces),
        "area_m2": float(areas.sum()),
        "volume_m3": tri.signed_volume(corners) if closed else None,
        "closed": closed,
        "bounds_m": [check.vertices.min(axis=0).tolist(), check.vertices.max(axis=0).tolist()],
        "reference_point": f"{reference_name} [{point}] m",
        "checks": checks or ["all passed"],
        "parts": parts,
        "materials": [
            {
                "name": m.name,
                "reflectivity": m.reflectivity,
                "specular_fraction": m.specular_fraction,
                "transmissivity": m.transmissivity,
                "absorptivity": m.absorptivity,
            }
            for m in (table[i] for i in range(len(table)))
        ]
        if table is not None
        else [],
        "survey": survey_mesh(mesh, kind).to_json(),
    }
