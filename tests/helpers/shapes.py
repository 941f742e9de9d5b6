"""Concave test shapes and materials that several test modules share, and a closed-form view factor."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from helpers import quad_sheet
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, SPEED_OF_LIGHT
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft

P = SOLAR_FLUX_1AU / SPEED_OF_LIGHT
MIRROR = Material("mirror", 1.0, 1.0, 0.0)
WHITE = Material("white", 1.0, 0.0, 0.0)
SHEER = Material("sheer", 0.2, 0.5, 0.3)


def groove(material: Material, n: int = 4, length: float = 4.0):
    """A 90 degree V-groove along y, opening up (+z), aperture 2 m wide: two-sided sheets."""
    a = quad_sheet(np.array([[-1, 0, 1], [0, 0, 0], [0, length, 0], [-1, length, 1.0]]), "a", n)
    b = quad_sheet(np.array([[0, 0, 0], [1, 0, 1], [1, length, 1], [0, length, 0.0]]), "b", n)
    return build_spacecraft(MeshData.concatenate([a, b]), uniform=material, two_sided=["*"])


def open_box(material: Material, n: int = 4):
    """A unit cube without its top face, made of two-sided sheets: a cavity lit through its mouth."""
    faces = [
        [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]],
        [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]],
        [[1, 1, 0], [0, 1, 0], [0, 1, 1], [1, 1, 1]],
        [[0, 1, 0], [0, 0, 0], [0, 0, 1], [0, 1, 1]],
        [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]],
    ]
    sheets = [quad_sheet(np.array(f, dtype=float), f"wall{k}", n) for k, f in enumerate(faces)]
    return build_spacecraft(MeshData.concatenate(sheets), uniform=material, two_sided=["*"])


def parallel_squares(x: float) -> float:
    """View factor between directly opposed squares of side x at unit distance (Incropera, Table 13.2)."""
    root = np.sqrt(1 + x * x)
    bracket = np.log(root**2 / np.sqrt(1 + 2 * x * x)) + 2 * x * (root * np.arctan(x / root) - np.arctan(x))
    return float(2 / (np.pi * x * x) * bracket)


#: Materials of :func:`hinged_box_wing`: both wings on one drive about body y, tracking the Sun.
HINGED_MATERIALS = """
[materials.paint]
reflectivity = 0.5
specular_fraction = 0.4
[parts]
"wing_*" = { front = "paint", back = "paint" }
bus = "paint"
[articulation."wing_*"]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
track = "sun"
"""


def hinged_box_wing(folder: Path) -> tuple[Path, Path]:
    """A coarse box-wing (:func:`~sunwind.meshes.primitives.box_wing`) whose wings track the Sun about
    body y, written to ``folder``: the OBJ and materials paths."""
    from sunwind.geometry.io.obj import write_obj
    from sunwind.meshes.primitives import box_wing

    write_obj(box_wing(facet_size=0.25), folder / "craft.obj")
    (folder / "craft.toml").write_text(HINGED_MATERIALS)
    return folder / "craft.obj", folder / "craft.toml"


def plate_over_plate():
    """A 1 m plate facing the planet, a 0.4 m plate 0.3 m below it (toward the planet): two-sided."""
    big = np.array([[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0.0]])[::-1]
    small = np.array([[-0.2, -0.2, -0.3], [0.2, -0.2, -0.3], [0.2, 0.2, -0.3], [-0.2, 0.2, -0.3]])
    material = Material("grey", 0.0, 0.0, 0.0, emissivity=1.0)
    mesh = MeshData.concatenate([quad_sheet(big, "big", 1), quad_sheet(small, "small", 1)])
    return build_spacecraft(mesh, uniform=material, two_sided=["*"]), big, small
