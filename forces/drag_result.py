"""The result of one free-molecular attitude: force, torque, coefficients and the flow; body frame, SI."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.reflection.plan import ReflectionSettings
from sunwind.forces.results import FRAME
from sunwind.geometry.directions import vector_to_azel
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import ViewFactors

#: How every coefficient is normalised (METHOD.md "Outputs").
NORMALISATION = "C = F / (q A_ref), C_M = M / (q A_ref L_ref), q = rho V^2 / 2 (total density)"
#: The aerodynamic axes the force coefficients are taken along.
AXES = (
    "drag along -v_rel; lift along the body +z axis made normal to v_rel (body +x when v_rel is along z); "
    "side = lift x drag"
)
#: What the panel method is good for, stated in every result.
VALIDITY = (
    "free-molecular flow (Knudsen number >> 1, above ~150 km); flow shadowing exact on convex shapes "
    "at any speed ratio, approximate on concave ones below speed ratio 3"
)


@dataclass(frozen=True)
class GasReflected:
    """What the exchange of re-emitted molecules between sides adds to the panel law."""

    mode: str
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    view: ViewFactors | None
    k_is: float | None


def aerodynamic_axes(flow_direction: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit drag, side and lift directions (rows) for ``u = v_rel / |v_rel|``; see :data:`AXES`."""
    drag_axis = -flow_direction
    up = np.array([0.0, 0.0, 1.0])
    if abs(up @ flow_direction) > 1 - 1e-9:
        up = np.array([1.0, 0.0, 0.0])
    lift = up - (up @ flow_direction) * flow_direction
    lift /= np.linalg.norm(lift)
    return np.array([drag_axis, np.cross(lift, drag_axis), lift])


@dataclass(frozen=True, eq=False)
class DragResult:
    """Free-molecular aerodynamics at one attitude; body frame, SI units.

    Attributes
    ----------
    velocity_m_s : (3,) float64
        ``v_rel``: the spacecraft's velocity relative to the atmosphere.
    atmosphere : Atmosphere
    force_N, torque_Nm : (3,) float64
        Totals: the panel law with shadowing plus the molecular exchange; torque about
        ``reference_point_m``.
    direct_force_N, direct_torque_Nm : (3,) float64
        The panel law on every side (directed stream on lit shares, thermal stream from the open sky),
        every re-emitted molecule escaping.
    reflected : GasReflected
        What the exchange of re-emitted molecules changes.
    settings : ReflectionSettings
    reference_point_m : (3,) float64
    reference_point : str
    reference_area_m2, reference_length_m : float
        Normalisation of the coefficients.
    projected_area_m2 : float
        Lit area projected on the plane normal to the flow (the flow's shadow of the spacecraft).
    side_force_N : (n_sides, 3) float64
        Panel-law force on each side.
    rays : int
        Shadow rays cast along the flow.
    sampling : str
    craft : Spacecraft
    """

    velocity_m_s: NDArray[np.float64]
    atmosphere: Atmosphere
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    direct_force_N: NDArray[np.float64]
    direct_torque_Nm: NDArray[np.float64]
    reflected: GasReflected
    settings: ReflectionSettings
    reference_point_m: NDArray[np.float64]
    reference_point: str
    reference_area_m2: float
    reference_length_m: float
    projected_area_m2: float
    side_force_N: NDArray[np.float64] = field(repr=False)
    rays: int
    sampling: str
    craft: Spacecraft = field(repr=False)

    @property
    def speed_m_s(self) -> float:
        return float(np.linalg.norm(self.velocity_m_s))

    @property
    def flow_direction(self) -> NDArray[np.float64]:
        """``u = v_rel / |v_rel|``: molecules arrive travelling along ``-u``."""
        return self.velocity_m_s / self.speed_m_s

    @property
    def dynamic_pressure_Pa(self) -> float:
        """``q = rho V^2 / 2`` with the total mass density."""
        return 0.5 * self.atmosphere.density_kg_m3 * self.speed_m_s**2

    @property
    def speed_ratio(self) -> float:
        """``S = V / sqrt(2 k T / m_mean)`` with the number-mean molecular mass."""
        return self.atmosphere.mean_speed_ratio(self.speed_m_s)

    @property
    def reflections(self) -> str:
        """The inter-reflection mode applied (``auto`` resolved)."""
        return self.reflected.mode

    @property
    def reflected_force_N(self) -> NDArray[np.float64]:
        return self.reflected.force_N

    @property
    def reflected_torque_Nm(self) -> NDArray[np.float64]:
        return self.reflected.torque_Nm

    @property
    def force_coefficients(self) -> NDArray[np.float64]:
        """``(C_D, C_S, C_L)`` along :func:`aerodynamic_axes`, normalised as :data:`NORMALISATION`."""
        axes = aerodynamic_axes(self.flow_direction)
        return axes @ self.force_N / (self.dynamic_pressure_Pa * self.reference_area_m2)

    @property
    def moment_coefficients(self) -> NDArray[np.float64]:
        """``C_M`` about the reference point along the body axes x, y, z."""
        scale = self.dynamic_pressure_Pa * self.reference_area_m2 * self.reference_length_m
        return self.torque_Nm / scale

    def to_json(self) -> dict:
        """The result as plain JSON types; keys say units, frame and reference point."""
        az, el = vector_to_azel(self.flow_direction)
        cd, cs, cl = self.force_coefficients
        return {
            "frame": FRAME,
            "force_N": self.force_N.tolist(),
            "torque_Nm": self.torque_Nm.tolist(),
            "reference_point_m": self.reference_point_m.tolist(),
            "reference_point": self.reference_point,
            "velocity_m_s": self.velocity_m_s.tolist(),
            "flow_azel_deg": [az, el],
            "speed_m_s": self.speed_m_s,
            "density_kg_m3": self.atmosphere.density_kg_m3,
            "temperature_K": self.atmosphere.temperature_K,
            "dynamic_pressure_Pa": self.dynamic_pressure_Pa,
            "speed_ratio": self.speed_ratio,
            "species_speed_ratio": self.atmosphere.speed_ratio(self.speed_m_s),
            "atmosphere": self.atmosphere.to_json(),
            "CD": cd,
            "CL": cl,
            "CS": cs,
            "CM": self.moment_coefficients.tolist(),
            "reference_area_m2": self.reference_area_m2,
            "reference_length_m": self.reference_length_m,
            "coefficients": {"normalisation": NORMALISATION, "axes": AXES},
            "projected_area_m2": self.projected_area_m2,
            "direct": {"force_N": self.direct_force_N.tolist(), "torque_Nm": self.direct_torque_Nm.tolist()},
            "reflected": {
                "force_N": self.reflected_force_N.tolist(),
                "torque_Nm": self.reflected_torque_Nm.tolist(),
            },
            "reflections": self.reflections,
            "reflections_requested": self.settings.mode,
            "k_is": self.reflected.k_is,
            "shadow_rays": self.rays,
            "sampling": self.sampling,
            "validity": VALIDITY,
        }
