"""Surface-interaction physics: the SRP force law, gas-surface laws, one-attitude evaluation of SRP and
drag, the atmosphere, the CLI and the benchmark."""

from .drag import drag
from .drag_result import DragResult
from .evaluate import srp
from .radiation import SOLAR_FLUX_1AU, SPEED_OF_LIGHT, radiation_pressure, solar_flux, surface_forces
from .reflections import PowerBalance, ReflectionSettings, model_view_factors
from .result import SrpResult

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
