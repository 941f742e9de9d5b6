"""Test helpers: small meshes built in memory, shapes and materials the tests share."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from sunwind.geometry.materials import Material, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft

#: The repository's root: README.md, METHOD.md, meshes/data/.
REPO = Path(__file__).resolve().parents[2]


def mesh_from_trimesh(mesh: trimesh.Trimesh, part: str = "body", source: str = "<memory>") -> MeshData:
    """A one-part MeshData from a trimesh mesh, no material keys."""
    n = len(mesh.faces)
    return MeshData(
        mesh.vertices, mesh.faces, np.zeros(n, np.int32), (part,), -np.ones(n, np.int32), source=source
    )


def quad_sheet(corners: np.ndarray, part: str, n: int = 1) -> MeshData:
    """A flat quadrilateral ``corners`` (4, 3), counter-clockwise seen from the front, as 2 n^2 triangles."""
    s, t = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1), indexing="ij")
    a, b, c, d = corners
    points = (
        (1 - s)[..., None] * (1 - t)[..., None] * a
        + s[..., None] * (1 - t)[..., None] * b
        + s[..., None] * t[..., None] * c
        + (1 - s)[..., None] * t[..., None] * d
    ).reshape(-1, 3)
    idx = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    v00, v10, v11, v01 = idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]
    faces = np.concatenate(
        [np.stack([v00, v10, v11], -1).reshape(-1, 3), np.stack([v00, v11, v01], -1).reshape(-1, 3)]
    )
    m = len(faces)
    return MeshData(points, faces, np.zeros(m, np.int32), (part,), -np.ones(m, np.int32))


ABSORBER = Material("black", 0.0, 0.0, 0.0)
MIXED = Material("mixed", 0.6, 0.3, 0.1)


def shaded_floor(n: int = 8) -> tuple:
    """A unit floor (one-sided, z = 0) under a 0.37 m square blind at z = 0.5, offset off the grid."""
    floor = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float), "floor", n)
    c = np.array([0.41, 0.53, 0.5])
    h = 0.37 / 2
    blind = quad_sheet(c + np.array([[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]]), "blind", 1)
    mesh = MeshData.concatenate([floor, blind])
    spec = parse_materials(
        {
            "materials": {"black": {"reflectivity": 0, "specular_fraction": 0}},
            "parts": {"floor": {"front": "black"}, "blind": {"front": "black", "back": "black"}},
        }
    )
    craft = build_spacecraft(mesh, spec)
    return craft, c, h
