"""Surface-interaction physics: the SRP force law, one-attitude evaluation, the CLI and the benchmark."""

from .evaluate import srp
from .radiation import SOLAR_FLUX_1AU, SPEED_OF_LIGHT, radiation_pressure, solar_flux, surface_forces
from .result import SrpResult

__all__ = [
    "SOLAR_FLUX_1AU",
    "SPEED_OF_LIGHT",
    "SrpResult",
    "radiation_pressure",
    "solar_flux",
    "srp",
    "surface_forces",
]
