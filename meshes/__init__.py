"""Parametric meshes of the validation shapes and the sample spacecraft, with provenance."""

from typing import Any

from sunwind.meshes.assembly import label, rotation_matrix, transform
from sunwind.meshes.primitives import (
    PRIMITIVES,
    box,
    box_wing,
    build,
    cone,
    cylinder,
    dish,
    plate,
    sensor_cube,
    sphere,
)

#: Names of :mod:`sunwind.meshes.samples`, imported on first use so ``python -m sunwind.meshes.samples`` runs
# the
#: module once, not after an import of it.
_SAMPLE_NAMES = (
    "SAMPLE_OPTICS",
    "SAMPLE_OPTICS_NOTES",
    "materials_toml",
    "sample_materials_path",
    "sample_path",
    "sample_spacecraft",
    "write_sample_files",
)

__all__ = [
    "PRIMITIVES",
    "box",
    "box_wing",
    "build",
    "cone",
    "cylinder",
    "dish",
    "label",
    "plate",
    "rotation_matrix",
    "sensor_cube",
    "sphere",
    "transform",
    *_SAMPLE_NAMES,
]


def __getattr__(name: str) -> Any:
    if name in _SAMPLE_NAMES:
        from sunwind.meshes import samples

        return getattr(samples, name)
    raise AttributeError(f"module 'meshes' has no attribute '{name}'")
