"""Attitude from the heat fluxes that sensor parts absorb (METHOD.md "Attitude from heat fluxes").

The forward model is the planet's radiation on the whole model (:func:`~sunwind.forces.earth
.planet_radiation`: self-shadowing, inter-reflection, the albedo with its terminator, the infrared),
condensed once per model into each sensor's response to a parallel beam from every direction
(:mod:`~sunwind.forces.sensing.response`); a row's fluxes are then matched over the whole sphere of
Sun and nadir directions (:mod:`~sunwind.forces.sensing.search`).
"""

from sunwind.forces.sensing.flux_rows import FluxRows, read_flux_rows
from sunwind.forces.sensing.forward import FluxModel, SensorFluxes, flux_model
from sunwind.forces.sensing.response import SensorResponse, sensor_response
from sunwind.forces.sensing.search import Minimum
from sunwind.forces.sensing.smoothing import SmoothedRow
from sunwind.forces.sensing.solve import (
    AttitudeFit,
    AttitudeSolution,
    attitude_from_fluxes,
    smoothed_attitudes,
)

__all__ = [
    "AttitudeFit",
    "AttitudeSolution",
    "FluxModel",
    "FluxRows",
    "Minimum",
    "SensorFluxes",
    "SensorResponse",
    "SmoothedRow",
    "attitude_from_fluxes",
    "flux_model",
    "read_flux_rows",
    "sensor_response",
    "smoothed_attitudes",
]
