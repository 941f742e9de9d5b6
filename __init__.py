"""sunwind: solar-radiation pressure, free-molecular drag, planetary albedo and infrared and thermal
recoil on a spacecraft mesh, with ray-cast self-shadowing and inter-reflection.

``import sunwind as sw`` gives the user's vocabulary, and nothing else:

>>> import sunwind as sw
>>> model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path(), threads=1)
>>> sw.srp(model, [0.3, -0.5, 0.8], reflections="none").force_N.shape  # [N], body frame
(3,)

Subpackages, each importing only those before it:

- :mod:`sunwind.geometry`: the spacecraft model, mesh and material files, ray casting, view factors.
- :mod:`sunwind.meshes`: parametric meshes and the sample spacecraft.
- :mod:`sunwind.forces`: the force laws and solvers, attitude tables, their file formats, the CLI.
- :mod:`sunwind.validation`: closed forms, brute-force tracers and the validation runner.

The names below are imported on first use, so ``import sunwind`` (and the ``sunwind`` command) stays
quick. The method, frames and signs are in METHOD.md; ``python -m sunwind`` runs the command line.
"""

import importlib as _importlib
from importlib.metadata import PackageNotFoundError as _PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("sunwind")
except _PackageNotFoundError:  # imported from a checkout that was never installed
    __version__ = "unknown"

#: The public names, each ``module:attribute`` (a module alone for a namespace).
_PUBLIC = {
    # the model
    "load": "sunwind.forces.model:load",
    "Model": "sunwind.forces.model:Model",
    "Material": "sunwind.geometry.materials:Material",
    "MeshData": "sunwind.geometry.mesh_data:MeshData",
    "meshes": "sunwind.meshes",
    # one attitude or a batch
    "srp": "sunwind.forces.srp:srp",
    "fit": "sunwind.forces.fit:fit",
    "drag": "sunwind.forces.drag:drag",
    "planet_radiation": "sunwind.forces.earth:planet_radiation",
    "Place": "sunwind.forces.earth:Place",
    "CapSampling": "sunwind.forces.earth:CapSampling",
    # the environment
    "nrlmsis": "sunwind.forces.gas.msis:nrlmsis",
    "explicit_atmosphere": "sunwind.forces.gas.atmosphere:explicit",
    "Atmosphere": "sunwind.forces.gas.atmosphere:Atmosphere",
    "circular_speed": "sunwind.forces.gas.flow:circular_speed",
    "corotation_velocity": "sunwind.forces.gas.flow:corotation_velocity",
    "PlanetLight": "sunwind.forces.planet.bodies:PlanetLight",
    # settings, one per concern
    "ShadowSampling": "sunwind.geometry.rays.sampling:ShadowSampling",
    "ReflectionSettings": "sunwind.forces.reflection.settings:ReflectionSettings",
    "GasSampling": "sunwind.forces.gas.sampling:GasSampling",
    "SrpSetup": "sunwind.forces.tables.jobs:SrpSetup",
    "DragSetup": "sunwind.forces.tables.jobs:DragSetup",
    "EarthSetup": "sunwind.forces.tables.earth_setup:EarthSetup",
    # tables and files
    "sweep": "sunwind.forces.tables.engine:sweep",
    "SweepRun": "sunwind.forces.tables.engine:SweepRun",
    "write": "sunwind.forces.export:write",
    "TableInterpolator": "sunwind.forces.tables.interpolation:TableInterpolator",
    # orbits
    "orbit": "sunwind.forces.orbit",
    "fly": "sunwind.forces.orbit.flight:fly",
    "OrbitLoads": "sunwind.forces.orbit.steps:OrbitLoads",
    # attitude from heat fluxes
    "attitude_from_fluxes": "sunwind.forces.sensing:attitude_from_fluxes",
    "smoothed_attitudes": "sunwind.forces.sensing:smoothed_attitudes",
    "FluxRows": "sunwind.forces.sensing:FluxRows",
    "AttitudeFit": "sunwind.forces.sensing:AttitudeFit",
    # lines of sight
    "lines_of_sight": "sunwind.forces.sight:lines_of_sight",
    "SightPoints": "sunwind.forces.sight:SightPoints",
    "LinesOfSight": "sunwind.forces.sight:LinesOfSight",
    # results
    "Result": "sunwind.forces.result_base:Result",
    "LoadResult": "sunwind.forces.result_base:LoadResult",
    "SrpResult": "sunwind.forces.results:SrpResult",
    "DragResult": "sunwind.forces.results:DragResult",
    "PlanetResult": "sunwind.forces.earth:PlanetResult",
    "Sensitivities": "sunwind.forces.sensitivity:Sensitivities",
    "FitResult": "sunwind.forces.fit:FitResult",
    "ResultBatch": "sunwind.forces.batches:ResultBatch",
    "SrpBatch": "sunwind.forces.batches:SrpBatch",
    "DragBatch": "sunwind.forces.batches:DragBatch",
    "OrbitResult": "sunwind.forces.orbit.results:OrbitResult",
    "ErrorEstimate": "sunwind.forces.error_estimate:ErrorEstimate",
    # errors and checks
    "SunwindError": "sunwind.geometry.errors:SunwindError",
    "validate": "sunwind.validation.runner:run",
}

__all__ = sorted(_PUBLIC)


def __getattr__(name: str) -> object:
    target = _PUBLIC.get(name)
    if target is None:
        raise AttributeError(f"module 'sunwind' has no attribute {name!r}")
    module_name, _, attribute = target.partition(":")
    module = _importlib.import_module(module_name)
    value = getattr(module, attribute) if attribute else module
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*__all__, "__version__"])
