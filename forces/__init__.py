"""Surface-interaction physics of a spacecraft model: solar-radiation pressure and free-molecular drag
at one attitude or a batch, attitude sweeps into tables, and the file formats simulators read.

Subpackages, each importing only those before it: :mod:`~sunwind.forces.radiation` (the force law and
the direct pass), :mod:`~sunwind.forces.reflection` (beam chains and the diffuse balance),
:mod:`~sunwind.forces.gas` (atmosphere, gas-surface laws, flow shadow, molecular exchange),
:mod:`~sunwind.forces.tables` (attitudes, sweeps, interpolation), :mod:`~sunwind.forces.export`
(netCDF, CSV, SPAD, Basilisk, Tudat) and :mod:`~sunwind.forces.cli` (the ``sunwind`` command).

The user's names are gathered in the top-level namespace, ``import sunwind as sw``; this package holds
them where they are made.

>>> from sunwind.forces import load, srp
>>> from sunwind.meshes import sample_materials_path, sample_path
>>> model = load(sample_path(), sample_materials_path(), threads=1)
>>> srp(model, [0.3, -0.5, 0.8], reflections="none").force_N.shape
(3,)
"""

from sunwind.forces.batches import DragBatch, ResultBatch, SrpBatch
from sunwind.forces.drag import drag
from sunwind.forces.earth import CapSampling, Place, PlanetResult, planet_radiation
from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.gas import (
    Atmosphere,
    circular_speed,
    corotation_speed,
    corotation_velocity,
    explicit,
    nrlmsis,
)
from sunwind.forces.model import Model, ModelSource, load
from sunwind.forces.radiation import (
    SOLAR_FLUX_1AU,
    SPEED_OF_LIGHT,
    radiation_pressure,
    solar_flux,
    surface_forces,
)
from sunwind.forces.reflection import PowerBalance, ReflectionSettings, model_view_factors
from sunwind.forces.result_base import LoadResult, Result
from sunwind.forces.results import AttitudeResult, DragResult, SrpResult
from sunwind.forces.srp import srp
from sunwind.forces.tables import DragSetup, SrpSetup, SweepRun, sweep

__all__ = [
    "SOLAR_FLUX_1AU",
    "SPEED_OF_LIGHT",
    "Atmosphere",
    "AttitudeResult",
    "CapSampling",
    "DragBatch",
    "DragResult",
    "DragSetup",
    "ErrorEstimate",
    "LoadResult",
    "Model",
    "ModelSource",
    "Place",
    "PlanetResult",
    "PowerBalance",
    "ReflectionSettings",
    "Result",
    "ResultBatch",
    "SrpBatch",
    "SrpResult",
    "SrpSetup",
    "SweepRun",
    "circular_speed",
    "corotation_speed",
    "corotation_velocity",
    "drag",
    "explicit",
    "load",
    "model_view_factors",
    "nrlmsis",
    "planet_radiation",
    "radiation_pressure",
    "solar_flux",
    "srp",
    "surface_forces",
    "sweep",
]
