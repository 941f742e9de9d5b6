"""What ``sunwind info`` reports about a mesh: size, parts, materials and every check's outcome."""

from __future__ import annotations

import os
from collections.abc import Sequence

import numpy as np

from sunwind.geometry import triangles as tri
from sunwind.geometry.checks import check_mesh
from sunwind.geometry.errors import MaterialError
from sunwind.geometry.materials import Material, MaterialSpec, load_materials, part_matches
from sunwind.geometry.sides import ONE_SIDED, SOLID, TWO_SIDED, assign_sides

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
    that cannot be read, or a materials file that is invalid, still raises.

    Returns
    -------
    dict
        JSON-ready: mesh, unit, triangles, area_m2, volume_m3, closed, bounds_m, reference_point,
        checks (list of str), parts (list of dict), materials (list of dict).
    """
    from sunwind.geometry.io import load_mesh

    mesh = load_mesh(path, unit=unit)
    spec: MaterialSpec | None = load_materials(materials) if materials is not None else None
    checks: list[str] = []
    try:
        sides = assign_sides(mesh, spec, uniform, two_sided)
        kind, part_materials, table = sides.face_kind, sides.part_summary, sides.table
    except MaterialError as error:
        checks.append(f"materials: {error}")
        kind = _declared_kinds(mesh, spec, two_sided)
        part_materials, table = {}, None
    check = check_mesh(mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names, kind, mesh.source)
    checks += list(check.notices)
    for part, count in check.open_edges.items():
        checks.append(f"part '{part}' is open ({count} boundary edges): declare it a sheet to use it")
    for part, count in check.nonmanifold_edges.items():
        checks.append(f"part '{part}' has {count} non-manifold edges: declare it a sheet or split it")
    corners = check.vertices[check.faces]
    areas = tri.areas(corners)
    facet_part = mesh.face_part[check.kept]
    facet_kind = kind[check.kept]
    closed = check.closed and bool(np.all(facet_kind == SOLID))
    reference = tri.volume_centroid(corners) if closed else areas @ tri.centroids(corners) / areas.sum()
    keys = (*mesh.material_names, "")
    parts = []
    for index, name in enumerate(mesh.part_names):
        mine = facet_part == index
        if not mine.any():
            continue
        surface = _SURFACE[int(facet_kind[mine][0])]
        if name in check.open_edges or name in check.nonmanifold_edges:
            surface = "open, undeclared"
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
    return {
        "mesh": mesh.source,
        "unit": str(mesh.metadata.get("unit", "m")),
        "triangles": len(check.faces),
        "area_m2": float(areas.sum()),
        "volume_m3": tri.signed_volume(corners) if closed else None,
        "closed": closed,
        "bounds_m": [check.vertices.min(axis=0).tolist(), check.vertices.max(axis=0).tolist()],
        "reference_point": f"{'volume' if closed else 'area'} centroid {np.round(reference, 6).tolist()} m",
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
    }


def _declared_kinds(mesh, spec: MaterialSpec | None, two_sided: Sequence[str]) -> np.ndarray:
    """Face kinds from sheet declarations alone, for a report when materials are incomplete."""
    kind = np.full(mesh.n_faces, SOLID, dtype=np.int8)
    for index, part in enumerate(mesh.part_names):
        rule = spec.rule_for(part) if spec is not None else None
        if rule is not None and rule.sheet:
            kind[mesh.face_part == index] = TWO_SIDED if rule.back is not None else ONE_SIDED
        elif part in mesh.two_sided_parts or any(part_matches(part, g) for g in two_sided):
            kind[mesh.face_part == index] = TWO_SIDED
    return kind
