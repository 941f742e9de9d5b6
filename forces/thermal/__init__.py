"""Face temperatures and thermal recoil (issue 21): thermal nodes from the ``[thermal]`` rules, the
infrared the spacecraft sends itself (the diffuse balance with the infrared optics), node temperatures
in equilibrium and in time, and the force and torque of the emitted infrared."""

from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN, InfraredBalance, solve_joined
from sunwind.forces.thermal.model import ThermalModel, infrared_exchange, thermal_model
from sunwind.forces.thermal.nodes import ThermalNodes, thermal_nodes
from sunwind.forces.thermal.state import ThermalState

__all__ = [
    "STEFAN_BOLTZMANN",
    "InfraredBalance",
    "ThermalModel",
    "ThermalNodes",
    "ThermalState",
    "infrared_exchange",
    "solve_joined",
    "thermal_model",
    "thermal_nodes",
]
