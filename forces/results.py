"""Results of one attitude: force, torque, their direct and reflected parts, areas and how they were
obtained; body frame, SI units (METHOD.md "Outputs and tables").

:class:`SrpResult` and :class:`DragResult` share :class:`AttitudeResult` (itself a
:class:`~sunwind.forces.result_base.LoadResult`): the same field names for what both have (``force_N``,
``rays``, ``facet_force_N``, ``azel_deg``, ...), the same JSON keys and the same ``to_dataset()``.
A batch (:class:`~sunwind.forces.batches.SrpBatch`, :class:`~sunwind.forces.batches.DragBatch`) holds
one result per attitude and gives every per-attitude field stacked over them, ``(n,)`` or ``(n, 3)``.
Nothing is computed on attribute access that the call did not ask for: ``k_is`` is None when the
reflections asked for needed no view factors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.radiation.law import surface_forces
from sunwind.forces.reflection import PowerBalance, Reflected, ReflectionSettings
from sunwind.forces.result_base import FRAME, LoadResult
from sunwind.forces.sensitivity import Sensitivities
from sunwind.geometry.directions import vector_to_azel
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.sky import OpenSky

__all__ = ["AXES", "FRAME", "NORMALISATION", "VALIDITY", "AttitudeResult", "DragResult", "SrpResult"]

#: How every aerodynamic coefficient is normalised (METHOD.md "Outputs and tables").
NORMALISATION = "C = F / (q A_ref), C_M = M / (q A_ref L_ref), q = rho V^2 / 2 (total density)"
#: The aerodynamic axes the force coefficients are taken along.
AXES = (
    "drag along -v_rel; lift along the body +z axis made normal to v_rel (body +x when v_rel is along z); "
    "side = lift x drag"
)
#: What the panel method is good for, stated in every drag result.
VALIDITY = (
    "free-molecular flow (Knudsen number >> 1, above ~150 km); the incident stream integrated over each "
    "side's open sky at any speed ratio; with reflections full, re-emitted molecules followed from side "
    "to side (diffuse by the exchange, mirrored and CLL by sampled chains)"
)


@dataclass(frozen=True, eq=False)
class AttitudeResult(LoadResult):
    """What a solar-pressure and a free-molecular result of one attitude share; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Totals, direct plus reflected; torque about ``reference_point_m``.
    direct_force_N, direct_torque_Nm : (3,) float64
        The surface law on every side with shadowing, every reflected photon or re-emitted molecule
        leaving to infinity.
    reflected : Reflected
        What inter-reflection (light) or the exchange of re-emitted molecules changes.
    settings : ReflectionSettings
        The inter-reflection settings asked for.
    reference_point_m : (3,) float64
        Point the torque is taken about.
    reference_point : str
        Where it came from: "user" (given), "centre of mass (materials file)", or a default: "volume
        centroid (default)" or "area centroid (default)".
    lit_area_m2 : float
        Area of the side parts the attitude's beam reaches: lit by the Sun, or facing the flow and not
        shadowed from it (the hyperthermal wetted area).
    projected_area_m2 : float
        Lit area projected on the plane normal to the attitude's direction: the shadow the spacecraft
        casts in the Sun or in the flow.
    rays : int
        Shadow rays cast.
    sampling : str
        How sides were sampled for shadowing.
    craft : Spacecraft
        The model evaluated.
    shadow_error : LoadsError or None
        The shadow pass's estimated absolute error in the direct force [N] and torque [N m], from its
        check and each side's load per unit lit area; None with fixed sampling (no check).
        :attr:`error_estimate` states it relative to the totals.
    sensitivities : Sensitivities or None
        d force / d coefficient and d torque / d coefficient of every material, when asked for
        (``sensitivities=True``); None otherwise.

    Both kinds give ``side_force_N`` and ``side_torque_Nm`` (n_sides, 3): the direct force on each side
    and its torque about the reference point, which :attr:`facet_force_N` and :attr:`facet_torque_Nm`
    sum onto the facets.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> result = sw.srp(cube, [1.0, 1.0, 0.0], reflections="none")
    >>> np.allclose(result.facet_force_N.sum(axis=0), result.direct_force_N)
    True
    >>> [round(angle, 6) for angle in result.azel_deg]
    [45.0, 0.0]
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    direct_force_N: NDArray[np.float64]
    direct_torque_Nm: NDArray[np.float64]
    reflected: Reflected
    settings: ReflectionSettings
    reference_point_m: NDArray[np.float64]
    reference_point: str
    lit_area_m2: float
    projected_area_m2: float
    rays: int
    sampling: str
    craft: Spacecraft = field(repr=False)
    shadow_error: LoadsError | None = field(kw_only=True)
    sensitivities: Sensitivities | None = field(default=None, kw_only=True)

    VARIABLES: ClassVar[tuple[str, ...]] = (
        "force_N",
        "torque_Nm",
        "direct_force_N",
        "direct_torque_Nm",
        "reflected_force_N",
        "reflected_torque_Nm",
        "lit_area_m2",
        "projected_area_m2",
        "rays",
    )

    @property
    def direction(self) -> NDArray[np.float64]:
        """Unit vector of the attitude, body frame: toward the Sun, or along ``v_rel``."""
        raise NotImplementedError

    @property
    def azel_deg(self) -> tuple[float, float]:
        """Azimuth ``atan2(y, x)`` and elevation ``asin(z)`` of :attr:`direction` [deg]."""
        return vector_to_azel(self.direction)

    @property
    def reflections(self) -> str:
        """The inter-reflection mode applied ("auto" resolved)."""
        return self.reflected.mode

    @property
    def reflected_force_N(self) -> NDArray[np.float64]:
        """Force inter-reflection adds to the direct force [N], (3,)."""
        return self.reflected.force_N

    @property
    def reflected_torque_Nm(self) -> NDArray[np.float64]:
        """Torque inter-reflection adds to the direct torque [N m], (3,)."""
        return self.reflected.torque_Nm

    @property
    def facet_force_N(self) -> NDArray[np.float64]:
        """Direct force on each facet, both sides summed [N], (n_facets, 3)."""
        return _per_facet(self.craft.side_facet, self.side_force_N, self.craft.n_facets)

    @property
    def facet_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of each facet's direct force about the reference point [N m], (n_facets, 3)."""
        return _per_facet(self.craft.side_facet, self.side_torque_Nm, self.craft.n_facets)

    def to_json(self) -> dict:
        """Plain-JSON summary; keys carry their units (the direction's ``azimuth_deg`` and
        ``elevation_deg`` alike for every kind)."""
        az, el = self.azel_deg
        return {
            **super().to_json(),
            "azimuth_deg": az,
            "elevation_deg": el,
            "direct": {"force_N": self.direct_force_N.tolist(), "torque_Nm": self.direct_torque_Nm.tolist()},
            "reflected": {
                "force_N": self.reflected_force_N.tolist(),
                "torque_Nm": self.reflected_torque_Nm.tolist(),
            },
            "reflections": self.reflections,
            "reflections_requested": self.settings.mode,
            "lit_area_m2": self.lit_area_m2,
            "projected_area_m2": self.projected_area_m2,
            "rays": self.rays,
            "sampling": self.sampling,
        }

    def dataset_attrs(self) -> dict[str, object]:
        """Global attributes of :meth:`to_dataset`: those of every result, the reflections used and
        the direction's azimuth and elevation [deg]."""
        az, el = self.azel_deg
        return {
            **super().dataset_attrs(),
            "reflections": self.reflections,
            "azimuth_deg": az,
            "elevation_deg": el,
        }


@dataclass(frozen=True, eq=False)
class SrpResult(AttitudeResult):
    """Solar-radiation pressure at one attitude; body frame, SI units (fields of
    :class:`AttitudeResult`, and those below).

    Attributes
    ----------
    sun_vector : (3,) float64
        Unit vector from the spacecraft toward the Sun.
    flux_W_m2 : float
        Solar flux at the spacecraft.
    pressure_Pa : float
        ``P = flux / c``.
    illumination : Illumination
        Lit share and lit centroid of every side.

    Per-side and per-facet forces and torques (of the direct law) are computed on first access.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> result = sw.srp(cube, [0.0, 0.0, 1.0], flux_W_m2=1361.0, reflections="none")
    >>> f"{result.pressure_Pa:.4e} Pa, {result.force_N[2]:.4e} N"  # a black square face: F = -P A
    '4.5398e-06 Pa, -4.5398e-06 N'
    >>> result.k_is is None  # no view factors were asked for
    True
    """

    sun_vector: NDArray[np.float64] = field(kw_only=True)
    flux_W_m2: float = field(kw_only=True)
    pressure_Pa: float = field(kw_only=True)
    illumination: Illumination = field(kw_only=True, repr=False)

    KIND: ClassVar[str] = "srp"
    VARIABLES: ClassVar[tuple[str, ...]] = (
        *AttitudeResult.VARIABLES,
        "sun_vector",
        "flux_W_m2",
        "pressure_Pa",
        "k_is",
    )

    @property
    def direction(self) -> NDArray[np.float64]:
        """The Sun vector (:attr:`sun_vector`)."""
        return self.sun_vector

    @property
    def power(self) -> PowerBalance:
        """Incident, absorbed and escaped power [W]."""
        return self.reflected.power

    @property
    def k_is(self) -> float | None:
        """Interference criterion ``K_IS`` of eq. (7) when the call computed it (reflections ``auto``
        or ``full``), else None: ask :func:`~sunwind.forces.reflection.interference` for it."""
        return self.reflected.k_is

    @property
    def side_lit_fraction(self) -> NDArray[np.float64]:
        """Lit share of each side's area, (n_sides,)."""
        return self.illumination.lit_fraction

    @cached_property
    def side_force_N(self) -> NDArray[np.float64]:
        """Direct force on each side [N], (n_sides, 3), by eq. (4) on its lit area."""
        craft, light = self.craft, self.illumination
        lit = np.flatnonzero(light.lit_fraction > 0)
        rho, beta, sigma = craft.side_optics[lit].T
        forces = np.zeros((craft.n_sides, 3))
        forces[lit] = surface_forces(
            craft.side_normals[lit],
            craft.side_areas[lit] * light.lit_fraction[lit],
            light.cos_incidence[lit],
            rho,
            beta,
            sigma,
            self.sun_vector,
            self.pressure_Pa,
        )
        return forces

    @cached_property
    def side_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of each side's direct force about the reference point [N m], (n_sides, 3)."""
        return np.cross(self.illumination.lit_centroid - self.reference_point_m, self.side_force_N)

    def to_json(self) -> dict:
        """Plain-JSON summary; keys carry their units; ``k_is`` null when the reflections asked for
        (``none``, ``specular``) needed no view factors."""
        out = {
            **super().to_json(),
            "sun_vector": self.sun_vector.tolist(),
            "flux_W_m2": self.flux_W_m2,
            "pressure_Pa": self.pressure_Pa,
            "k_is": self.k_is,
            "power": self.power.to_json(),
        }
        chains, view = self.reflected.chains, self.reflected.view
        if chains is not None:
            out["reflection_rays"] = chains.rays
            out["reflection_depth"] = chains.depth
            out["reflection_cutoff"] = self.settings.cutoff
        if view is not None and self.reflections == "full":
            out["view_factors"] = {
                "rays_per_side": view.rays_per_side,
                "seed": view.seed,
                "origin": view.origin,
                "seconds": view.seconds,
            }
        return out


def aerodynamic_axes(flow_direction: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit drag, side and lift directions (rows) for ``u = v_rel / |v_rel|``; see :data:`AXES`.

    Parameters
    ----------
    flow_direction : (3,) float64
        ``u``, the unit flow direction, body frame.

    Returns
    -------
    (3, 3) float64
        Rows: the drag axis ``-u``, the side axis ``lift x drag``, the lift axis (body +z made normal
        to ``u``; body +x when ``u`` is along z).

    Examples
    --------
    >>> import numpy as np
    >>> aerodynamic_axes(np.array([1.0, 0.0, 0.0])).tolist()
    [[-1.0, -0.0, -0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    drag_axis = -flow_direction
    up = np.array([0.0, 0.0, 1.0])
    if abs(up @ flow_direction) > 1 - 1e-9:
        up = np.array([1.0, 0.0, 0.0])
    lift = up - (up @ flow_direction) * flow_direction
    lift /= np.linalg.norm(lift)
    return np.array([drag_axis, np.cross(lift, drag_axis), lift])


@dataclass(frozen=True, eq=False)
class DragResult(AttitudeResult):
    """Free-molecular aerodynamics at one attitude; body frame, SI units (fields of
    :class:`AttitudeResult`, and those below).

    Attributes
    ----------
    velocity_m_s : (3,) float64
        ``v_rel``: the spacecraft's velocity relative to the atmosphere.
    atmosphere : Atmosphere
    reference_area_m2, reference_length_m : float
        Normalisation of the coefficients.
    side_force_N, side_torque_Nm : (n_sides, 3) float64
        Panel-law force on each side, and its torque about the reference point.
    open_sky : OpenSky
        The model's sampled open sky the incident stream was integrated over.
    core_half_angle_rad : float
        Half-angle of the core cone about the flow followed by rays per attitude [rad].

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> result = sw.drag(cube, [7500.0, 0.0, 0.0], air, reflections="none")
    >>> round(result.CD, 2), round(result.speed_ratio, 2)  # a cube face-on, C_D on A_ref = area / 4 = 1.5 m²
    (1.64, 7.36)
    """

    velocity_m_s: NDArray[np.float64] = field(kw_only=True)
    atmosphere: Atmosphere = field(kw_only=True)
    reference_area_m2: float = field(kw_only=True)
    reference_length_m: float = field(kw_only=True)
    side_force_N: NDArray[np.float64] = field(kw_only=True, repr=False)
    side_torque_Nm: NDArray[np.float64] = field(kw_only=True, repr=False)
    open_sky: OpenSky = field(kw_only=True, repr=False)
    core_half_angle_rad: float = field(kw_only=True)

    KIND: ClassVar[str] = "drag"
    VARIABLES: ClassVar[tuple[str, ...]] = (
        *AttitudeResult.VARIABLES,
        "velocity_m_s",
        "speed_ratio",
        "dynamic_pressure_Pa",
        "CD",
        "CS",
        "CL",
        "CM",
        "k_is",
    )

    @property
    def direction(self) -> NDArray[np.float64]:
        """The flow direction (:attr:`flow_direction`)."""
        return self.flow_direction

    @property
    def speed_m_s(self) -> float:
        """``|v_rel|`` [m/s]."""
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
    def k_is(self) -> float | None:
        """Molecular interference criterion ``K_IS`` (None when the reflections asked for none)."""
        return self.reflected.k_is

    @property
    def force_coefficients(self) -> NDArray[np.float64]:
        """``(C_D, C_S, C_L)`` along :func:`aerodynamic_axes`, normalised as :data:`NORMALISATION`."""
        axes = aerodynamic_axes(self.flow_direction)
        return axes @ self.force_N / (self.dynamic_pressure_Pa * self.reference_area_m2)

    @property
    def CD(self) -> float:
        """Drag coefficient (:attr:`force_coefficients`)."""
        return float(self.force_coefficients[0])

    @property
    def CS(self) -> float:
        """Side-force coefficient."""
        return float(self.force_coefficients[1])

    @property
    def CL(self) -> float:
        """Lift coefficient."""
        return float(self.force_coefficients[2])

    @property
    def CM(self) -> NDArray[np.float64]:
        """Moment coefficients ``C_M`` about the reference point along the body axes x, y, z, (3,),
        normalised as :data:`NORMALISATION`."""
        scale = self.dynamic_pressure_Pa * self.reference_area_m2 * self.reference_length_m
        return self.torque_Nm / scale

    def to_json(self) -> dict:
        """The result as plain JSON types; keys say units, frame and reference point."""
        cd, cs, cl = self.force_coefficients
        return {
            **super().to_json(),
            "velocity_m_s": self.velocity_m_s.tolist(),
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
            "CM": self.CM.tolist(),
            "reference_area_m2": self.reference_area_m2,
            "reference_length_m": self.reference_length_m,
            "coefficients": {"normalisation": NORMALISATION, "axes": AXES},
            "k_is": self.k_is,
            "open_sky": self.open_sky.to_json(),
            "core_half_angle_deg": math.degrees(self.core_half_angle_rad),
            **({} if self.reflected.chains is None else {"chains": self.reflected.chains.to_json()}),
            "validity": VALIDITY,
        }


def _per_facet(side_facet: NDArray[np.int64], values: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """Sum per-side vectors (n_sides, 3) onto their facets, (n, 3)."""
    return np.stack([np.bincount(side_facet, weights=values[:, k], minlength=n) for k in range(3)], axis=-1)
