"""Solar radiation on the surface: the force law of a lit surface (eq. 4), the solar flux, and the
direct pass of an attitude with its block moments (METHOD.md "Direct solar pressure")."""

from sunwind.forces.radiation.direct import ChannelWeights, DirectPower, DirectTotals, direct_pass
from sunwind.forces.radiation.law import (
    LAMBERT_FACTOR,
    SOLAR_FLUX_1AU,
    SPEED_OF_LIGHT,
    radiation_pressure,
    solar_flux,
    surface_forces,
)

__all__ = [
    "LAMBERT_FACTOR",
    "SOLAR_FLUX_1AU",
    "SPEED_OF_LIGHT",
    "ChannelWeights",
    "DirectPower",
    "DirectTotals",
    "direct_pass",
    "radiation_pressure",
    "solar_flux",
    "surface_forces",
]
