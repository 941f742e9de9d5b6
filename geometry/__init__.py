"""The spacecraft model: mesh and material loading, checks, ray casting and shadow sampling."""

from .errors import InputError, MaterialError, MeshError, SunwindError
from .illumination import Illumination, SideSampler
from .materials import Material, MaterialSpec, MaterialTable, load_materials, parse_materials
from .mesh_data import MeshData
from .raycast import BruteForceScene, RayScene
from .spacecraft import Spacecraft, build_spacecraft, load_spacecraft

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
