"""Face temperatures and thermal recoil (issue 21): thermal nodes from the ``[thermal]`` rules and the
``[[conductance]]`` tables, the infrared the spacecraft sends itself (the diffuse balance with the
infrared optics), node temperatures in equilibrium and in time (a step, or a series integrated with
error control: :func:`integrate`), and the force and torque of the emitted infrared. With few nodes the
infrared exchange is reduced to node-level factors once per model (:class:`NodeExchange`)."""

from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN, InfraredBalance, solve_joined
from sunwind.forces.thermal.factors import NodeExchange, node_exchange
from sunwind.forces.thermal.model import ThermalModel, infrared_exchange, thermal_model
from sunwind.forces.thermal.nodes import ThermalNodes, thermal_nodes
from sunwind.forces.thermal.state import ThermalState
from sunwind.forces.thermal.transient import TransientHistory, integrate

__all__ = [
    "STEFAN_BOLTZMANN",
    "InfraredBalance",
    "NodeExchange",
    "ThermalModel",
    "ThermalNodes",
    "ThermalState",
    "TransientHistory",
    "infrared_exchange",
    "integrate",
    "node_exchange",
    "solve_joined",
    "thermal_model",
    "thermal_nodes",
]
