"""Ray casting on a model: the Embree scene (and a brute-force twin), the box tree of its facets, the
hull clearance that proves rays meet nothing, and the shadow pass that lights the sides
(METHOD.md "Shadowing and sampling"). The tree is built by ``box_tree.box_tree``."""

from sunwind.geometry.rays.box_tree import BoxTree
from sunwind.geometry.rays.hull import Clearance, clearance
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.scene import BruteForceScene, RayScene
from sunwind.geometry.rays.shadows import (
    DEFAULT_TOLERANCE,
    Illumination,
    SideSampler,
    check_sampling,
    side_sampler,
)

__all__ = [
    "DEFAULT_TOLERANCE",
    "BoxTree",
    "BruteForceScene",
    "Clearance",
    "Illumination",
    "RayScene",
    "ShadowSampling",
    "SideSampler",
    "check_sampling",
    "clearance",
    "side_sampler",
]
