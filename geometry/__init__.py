"""The spacecraft model and what it is made from and made into: mesh and material files (``io``), checks,
sides, the model and its cache, ray casting and shadow sampling (``rays``), view and exchange factors
(``views``). Knows nothing of forces."""

from sunwind.geometry.errors import InputError, MaterialError, MeshError, SunwindError
from sunwind.geometry.materials import Material, MaterialSpec, MaterialTable, load_materials, parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.scene import BruteForceScene, RayScene
from sunwind.geometry.rays.shadows import Illumination, SideSampler
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft, load_spacecraft

__all__ = [
    "BruteForceScene",
    "Illumination",
    "InputError",
    "Material",
    "MaterialError",
    "MaterialSpec",
    "MaterialTable",
    "MeshData",
    "MeshError",
    "RayScene",
    "SideSampler",
    "Spacecraft",
    "SunwindError",
    "build_spacecraft",
    "load_materials",
    "load_spacecraft",
    "parse_materials",
]
