"""Mesh file reading and writing: the suffix picks the format, loads return metres.

Formats: STL, OBJ, PLY, glTF/GLB, USD (``.usd``, ``.usda``, ``.usdc``; ``.usdz`` read only).
See :func:`load_mesh` and :func:`save_mesh` for what each format carries.
"""

from sunwind.geometry.io.registry import SUPPORTED_SUFFIXES, load_mesh, save_mesh
from sunwind.geometry.io.units import UNITS

__all__ = ["SUPPORTED_SUFFIXES", "UNITS", "load_mesh", "save_mesh"]
