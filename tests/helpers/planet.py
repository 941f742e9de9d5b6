"""What the planet-radiation tests share: the Earth's radius, materials files of one finish, a faceted
sphere written with its exact area, and the closed form of a uniform emitter on an absorbing sphere."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from sunwind.forces.radiation.law import SPEED_OF_LIGHT

#: The Earth's radius the tests assume [m] (WGS 84 equatorial).
R_EARTH = 6_378_137.0


def materials_toml(name: str, reflectivity: float, specular_fraction: float, emissivity: float | None) -> str:
    """A materials file giving every part material ``name`` (no emissivity when it is None)."""
    infrared = "" if emissivity is None else f"emissivity = {emissivity}\n"
    return (
        f"[materials.{name}]\nreflectivity = {reflectivity}\nspecular_fraction = {specular_fraction}\n"
        f'{infrared}[parts]\n"*" = "{name}"\n'
    )


#: An absorbing, black-in-the-infrared finish.
BLACK = materials_toml("black", 0.0, 0.0, 1.0)


def write_sphere(path: Path, subdivisions: int) -> float:
    """Write a unit sphere of ``subdivisions`` bands to ``path``; its faceted area [m^2]."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import sphere

    mesh = sphere(1.0, subdivisions)
    save_mesh(mesh, path)
    corners = mesh.vertices[mesh.faces]
    doubled = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    return 0.5 * float(np.linalg.norm(doubled, axis=1).sum())


def infrared_on_black_sphere(area_m2: float, exitance_W_m2: float, altitude_km: float) -> float:
    """|F| [N] of a uniform emitter of exitance M on an absorbing convex body of mean projected area
    ``area / 4`` (a sphere): ``(area / 4) M sin^2(theta_0) / c``, ``sin(theta_0) = R / (R + h)``, pointing
    away from the planet."""
    sin2 = (R_EARTH / (R_EARTH + altitude_km * 1e3)) ** 2
    return area_m2 / 4 * exitance_W_m2 * sin2 / SPEED_OF_LIGHT


#: The Earth's default infrared exitance, (1 - A) S / 4 [W/m^2].
EARTH_EXITANCE = (1 - 0.3) * 1361 / 4
assert math.isclose(EARTH_EXITANCE, 238.175)
