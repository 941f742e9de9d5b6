"""The Earth's albedo and infrared at an orbit step, the power each part absorbs, and (``thermal``) each
step's radiative-equilibrium temperatures and thermal recoil (METHOD.md "Planet radiation", "Orbit
mode").

A step's temperatures are the equilibrium with that step's absorbed power: the limit of parts whose heat
capacity is small against the power they exchange over the step. The transient lumped model
(:meth:`~sunwind.forces.thermal.ThermalModel.step`) is in the Python API.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.earth import DEFAULT_CELL_DEG, Place, check_cell_size, planet_radiation
from sunwind.forces.model import Model
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.spacecraft import infrared_optics

#: Albedo and infrared loads of a step (body frame): record name -> width.
BAND_FIELDS = {
    "albedo_force_body_N": 3,
    "albedo_torque_body_Nm": 3,
    "infrared_force_body_N": 3,
    "infrared_torque_body_Nm": 3,
}
#: Thermal recoil of a step (body frame).
THERMAL_FIELDS = {"thermal_force_body_N": 3, "thermal_torque_body_Nm": 3}
#: Per-part series [W] (absorbed power by source) and [K] (area-weighted mean side temperature).
PART_SOURCES = ("solar", "albedo", "infrared", "reflected")


@dataclass(frozen=True)
class EarthTerms:
    """The Earth's radiation at every step of an orbit.

    Attributes
    ----------
    surface : SrpSetup
        Shadow sampling, reflections and reference point (those of the SRP term); the solar flux is each
        step's (:class:`~sunwind.forces.orbit.steps.OrbitLoads`).
    albedo : float, optional
        Bond albedo instead of the Earth's 0.30.
    infrared_W_m2 : float, optional
        Uniform infrared exitance at the surface [W/m^2] instead of ``(1 - A) S / 4``.
    knocke : bool
        Knocke's zonal, seasonal albedo and emissivity, at each step's date, with latitudes about the
        GCRF z axis.
    cell_deg : float
        Cell size of the Earth's disc [deg].
    thermal : bool
        Each step's equilibrium temperatures and thermal recoil.
    """

    surface: SrpSetup
    albedo: float | None = None
    infrared_W_m2: float | None = None
    knocke: bool = False
    cell_deg: float = DEFAULT_CELL_DEG
    thermal: bool = False

    def __post_init__(self) -> None:
        PlanetLight.of(planet("earth"), 1.0, albedo=self.albedo, infrared_W_m2=self.infrared_W_m2)
        check_cell_size(self.cell_deg)

    def fields(self, n_parts: int) -> dict[str, int]:
        """Record name -> width of a step, for a model of ``n_parts`` parts."""
        out = dict(BAND_FIELDS) | {f"part_{source}_W": n_parts for source in PART_SOURCES}
        if self.thermal:
            out |= THERMAL_FIELDS | {"part_temperature_K": n_parts}
        return out

    def precompute(self, model: Model) -> None:
        """Refuse a model without emissivities before the first step; view factors."""
        infrared_optics(model.craft)
        self.surface.precompute(model)

    def evaluate(
        self, model: Model, place: Place, sunlight_W_m2: float, julian_tt: float
    ) -> tuple[dict[str, NDArray[np.float64]], LoadsError | None]:
        """One step's records, and the shadow passes' estimated error of its albedo and infrared loads
        (:attr:`~sunwind.forces.earth.PlanetResult.shadow_error`): ``place`` (body frame; its solar
        fraction the eclipse), the solar flux at the spacecraft's distance without eclipse [W/m^2], the
        TT Julian date (Knocke's season)."""
        light = PlanetLight.of(
            planet("earth"),
            sunlight_W_m2,
            albedo=self.albedo,
            infrared_W_m2=self.infrared_W_m2,
            knocke_julian_date=julian_tt if self.knocke else None,
        )
        options = self.surface.options()
        result = planet_radiation(model, place, light, cell_deg=self.cell_deg, **options)
        out = {
            "albedo_force_body_N": result.albedo.force_N,
            "albedo_torque_body_Nm": result.albedo.torque_Nm,
            "infrared_force_body_N": result.infrared.force_N,
            "infrared_torque_body_Nm": result.infrared.torque_Nm,
        }
        absorbed = result.absorbed_side_W()
        for source in PART_SOURCES:
            out[f"part_{source}_W"] = result.per_part(absorbed[source])
        if self.thermal:
            state = result.equilibrium(options["reflections"])
            out["thermal_force_body_N"], out["thermal_torque_body_Nm"] = state.force_N, state.torque_Nm
            out["part_temperature_K"] = result.part_temperatures(state.temperature_K)
        return out, result.shadow_error

    def describe(self) -> dict:
        """JSON-ready settings."""
        return asdict(self) | {"surface": self.surface.describe()}
