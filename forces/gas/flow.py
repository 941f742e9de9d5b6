"""The free stream a user describes on the command line: the flow velocity and the atmosphere.

Either ``--velocity X Y Z`` (``v_rel`` in the body frame, m/s) or ``--flow-azel AZ EL`` with a speed:
``--speed V``, else the circular-orbit speed at ``--altitude`` (relative to an atmosphere rotating
with the Earth with ``--corotating``, for the ``--heading`` of the orbit at ``--lat``). Either
NRLMSIS at ``--altitude`` (place, time and indices optional) or ``--density``, ``--temperature`` and
``--composition`` together.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere, circular_speed, corotation_speed, explicit, nrlmsis
from sunwind.geometry.directions import azel_to_vector
from sunwind.geometry.errors import InputError


@dataclass(frozen=True)
class FlowOptions:
    """How the flow velocity was given (one of ``velocity`` or ``azel``)."""

    velocity: Sequence[float] | None = None
    azel_deg: Sequence[float] | None = None
    speed_m_s: float | None = None
    corotating: bool = False
    heading_deg: float = 90.0


@dataclass(frozen=True)
class AtmosphereOptions:
    """How the atmosphere was given: NRLMSIS inputs, or density, temperature and composition."""

    altitude_km: float | None = None
    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    time: str = "2024-01-01T00:00:00Z"
    f107: float = 150.0
    f107a: float = 150.0
    ap: float = 4.0
    density_kg_m3: float | None = None
    temperature_K: float | None = None
    composition: str | None = None
    normalise_composition: bool = False

    @property
    def explicit(self) -> bool:
        return any(v is not None for v in (self.density_kg_m3, self.temperature_K, self.composition))


def flow_velocity(flow: FlowOptions, air: AtmosphereOptions) -> NDArray[np.float64]:
    """``v_rel`` in the body frame [m/s] from the flow options (the altitude gives the default speed)."""
    if (flow.velocity is None) == (flow.azel_deg is None):
        raise InputError("give the flow with --velocity X Y Z or --flow-azel AZ EL (one of them)")
    if flow.corotating and (flow.velocity is not None or flow.speed_m_s is not None):
        raise InputError(
            "--corotating changes the circular-orbit speed at --altitude only",
            hint="drop --speed/--velocity, or give the relative velocity itself",
        )
    if flow.velocity is not None:
        return np.asarray(flow.velocity, dtype=np.float64)
    direction = azel_to_vector(*flow.azel_deg, "--flow-azel")
    return flow_speed(flow, air) * direction


def flow_speed(flow: FlowOptions, air: AtmosphereOptions) -> float:
    """``|v_rel|`` [m/s]: ``--speed``, else the circular-orbit speed at ``--altitude`` (relative to a
    co-rotating atmosphere with ``--corotating``)."""
    if flow.speed_m_s is not None:
        speed = float(flow.speed_m_s)
        if not np.isfinite(speed) or speed <= 0:
            raise InputError(f"--speed {speed} must be a positive number of m/s")
        return speed
    if air.altitude_km is None:
        raise InputError("a flow direction needs --speed V, or --altitude for the circular-orbit speed")
    speed = circular_speed(air.altitude_km)
    if flow.corotating:
        speed = corotation_speed(air.altitude_km, air.latitude_deg, flow.heading_deg, speed)
    return speed


def atmosphere(air: AtmosphereOptions) -> Atmosphere:
    """The atmosphere the options describe: explicit when any of density, temperature, composition
    is given (then all three are needed), else NRLMSIS at the altitude."""
    if air.explicit:
        missing = [
            name
            for name, value in (
                ("--density", air.density_kg_m3),
                ("--temperature", air.temperature_K),
                ("--composition", air.composition),
            )
            if value is None
        ]
        if missing:
            raise InputError(
                f"an explicit atmosphere needs {', '.join(missing)} too",
                hint='e.g. --density 3e-12 --temperature 1000 --composition "O:0.8,N2:0.2"',
            )
        return explicit(air.density_kg_m3, air.temperature_K, air.composition, air.normalise_composition)
    if air.altitude_km is None:
        raise InputError(
            "give the atmosphere: --altitude H [km] for NRLMSIS, or --density, --temperature, --composition"
        )
    return nrlmsis(
        air.altitude_km, air.latitude_deg, air.longitude_deg, air.time, air.f107, air.f107a, air.ap
    )
