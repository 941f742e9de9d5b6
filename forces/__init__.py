"""Surface-interaction physics: the SRP force law, gas-surface laws, one-attitude evaluation of SRP and
drag, the atmosphere, the CLI and the benchmark."""

from sunwind.forces.drag import drag
from sunwind.forces.drag_result import DragResult
from sunwind.forces.radiation.law import (
    SOLAR_FLUX_1AU,
    SPEED_OF_LIGHT,
    radiation_pressure,
    solar_flux,
    surface_forces,
)
from sunwind.forces.reflection.plan import PowerBalance, ReflectionSettings, model_view_factors
from sunwind.forces.results import SrpResult
from sunwind.forces.srp import srp

__all__ = [
    "SOLAR_FLUX_1AU",
    "SPEED_OF_LIGHT",
    "DragResult",
    "PowerBalance",
    "ReflectionSettings",
    "SrpResult",
    "drag",
    "model_view_factors",
    "radiation_pressure",
    "solar_flux",
    "srp",
    "surface_forces",
]
