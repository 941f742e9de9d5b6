"""The Earth's albedo and infrared pressure (and thermal recoil) as a sweep's third kind, ``"earth"``:
one table entry per body-frame direction from the spacecraft to the Earth's centre, at a fixed altitude,
with the Sun fixed in the body frame (METHOD.md "Planet radiation", "Outputs and tables").

That slice of the Earth's radiation is what a spacecraft that holds the Sun fixed in its body (a
Sun-pointing one, whatever it does about the Sun line) sees as the Earth goes round it: exact for any
such attitude law at that altitude. Every entry is :func:`~sunwind.forces.earth.planet_radiation` called
as ``sunwind earth`` calls it, the Sun's share behind the Earth from the conical shadow model: where
the Earth hides the Sun the solar fraction is 0 (the albedo of the lit cap the spacecraft still sees
counts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.earth import (
    DEFAULT_CELL_DEG,
    METHODS,
    CapSampling,
    Place,
    check_altitude,
    check_cell_size,
    check_cells_at,
    planet_radiation,
)
from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.model import Model
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.shadow import sun_behind
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, solar_flux
from sunwind.forces.reflection import reflection_plan
from sunwind.forces.tables.jobs import (
    EARTH_FIELDS,
    EARTH_THERMAL_FIELDS,
    Records,
    _Setup,
    empty_records,
    estimate_records,
)
from sunwind.forces.tables.sensitivities import flat
from sunwind.forces.thermal import thermal_model
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import infrared_optics

#: The eclipse model of the Sun's share behind the Earth.
ECLIPSE = "conical"
#: What an earth table is, in its attributes.
SLICE = (
    "Earth radiation over body-frame directions to the Earth's centre (earth_vector) at a fixed altitude, "
    "the Sun fixed in the body frame along earth_sun_vector: exact for any attitude law that holds the "
    "Sun fixed in the body (a Sun-pointing spacecraft); the Sun's share behind the Earth by the conical "
    "shadow model (earth_solar_fraction)"
)


@dataclass(frozen=True)
class EarthSetup(_Setup):
    """Settings of every entry of an earth table.

    Each entry is :func:`~sunwind.forces.earth.planet_radiation` at one Earth direction; the settings
    are those of :class:`~sunwind.forces.tables.jobs._Setup` (``reference_point_m``, ``sampling``,
    ``reflections``) and the slice's (``altitude_km`` and ``sun_vector`` are required).

    Parameters
    ----------
    flux_W_m2 : float
        Solar flux [W/m^2] at the Earth; default 1 au.
    albedo : float, optional
        Bond albedo instead of the Earth's 0.30 (Lambertian).
    infrared_W_m2 : float, optional
        Uniform infrared exitance at the surface [W/m^2] instead of ``(1 - A) S / 4``.
    cell_deg : float
        Resolution of the shadowing [deg], in (0, 90] (:func:`~sunwind.forces.earth.planet_radiation`).
    cap_method : {"visibility", "cells"}
        How the shadowed cap is integrated: the model's directional visibility, built once per pose, or a
        shadow pass per cell of every entry.
    thermal : bool
        Each side's radiative-equilibrium temperature and the recoil of its infrared, added to the
        total and recorded apart (``thermal_force_N``, ``thermal_torque_Nm``).
    reference_point_m : (3,) float, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        The shadow pass's sampling of every cell; None for its defaults.
    reflections : str or ReflectionSettings
        One of :data:`~sunwind.forces.reflection.settings.MODES`, or settings; default ``"auto"``.
    altitude_km : float
        Height above the Earth's surface (WGS 84 equatorial radius) [km].
    sun_vector : (3,) float
        The Sun, fixed in the body frame (spacecraft to Sun); kept normalised.
    sensitivities : bool
        Also record the derivatives of the albedo and infrared force and torque with respect to every
        material's coefficients (``sensitivity_force_N``, ``sensitivity_torque_Nm``); not with thermal.

    Raises
    ------
    InputError
        An altitude, Sun vector, flux, albedo, infrared exitance, cell size, sampling or reflections
        out of range; sensitivities with thermal.

    Examples
    --------
    >>> setup = EarthSetup(altitude_km=500.0, sun_vector=(2.0, 0.0, 0.0), cell_deg=30.0)
    >>> setup.sun_vector, setup.options()["reflections"].mode
    ((1.0, 0.0, 0.0), 'auto')
    """

    kind: ClassVar[str] = "earth"
    altitude_km: float = field(kw_only=True)
    sun_vector: tuple[float, float, float] = field(kw_only=True)
    flux_W_m2: float = SOLAR_FLUX_1AU
    albedo: float | None = None
    infrared_W_m2: float | None = None
    cell_deg: float = DEFAULT_CELL_DEG
    cap_method: str = field(default="visibility", kw_only=True)
    thermal: bool = False

    def __post_init__(self) -> None:
        super().__post_init__()
        check_altitude(self.altitude_km)
        sun = unit_vector(self.sun_vector, "sun_vector")
        object.__setattr__(self, "sun_vector", tuple(float(v) for v in sun))
        solar_flux(self.flux_W_m2)
        self.light()  # the albedo and infrared checked
        check_cell_size(self.cell_deg)
        if self.cap_method not in METHODS:
            raise InputError(
                f"cap_method {self.cap_method!r} is not one of {', '.join(METHODS)}",
                parameters=("cap_method",),
            )
        if self.sensitivities and self.thermal:
            raise InputError(
                "sensitivities of the thermal recoil are not available yet: an earth table's derivatives "
                "are those of the albedo and infrared",
                hint="leave out the thermal recoil or the sensitivities",
                parameters=("sensitivities", "thermal"),
            )

    @property
    def fields(self) -> dict[str, int]:
        """The records of an entry: name -> width (the thermal recoil's with :attr:`thermal`, the error
        estimate with the default shadow pass)."""
        thermal = EARTH_THERMAL_FIELDS if self.thermal else {}
        return EARTH_FIELDS | thermal | self.estimates | self.sensitivity_fields

    @property
    def computes(self) -> Any:
        """The function every entry calls, :func:`~sunwind.forces.earth.planet_radiation`."""
        return planet_radiation

    def light(self) -> PlanetLight:
        """The Earth's albedo and infrared laws under :attr:`flux_W_m2`."""
        return PlanetLight.of(
            planet("earth"), self.flux_W_m2, albedo=self.albedo, infrared_W_m2=self.infrared_W_m2
        )

    def posed(self, model: Model) -> Model:
        """``model`` with Sun-tracking hinges turned to the fixed Sun (one pose for every entry)."""
        return model.posed(model.angles_at(np.asarray(self.sun_vector))) if model.hinges else model

    def check(self, model: Model) -> None:
        """Refuse, before any work, a model whose materials lack an emissivity, and a cell step that cuts
        the planet's disc into too many cells."""
        check_cells_at(self.altitude_km, self.cell_deg)
        infrared_optics(model.craft)

    def precompute(self, model: Model) -> None:
        """The emissivities checked; view factors when it reflects, and the thermal balance."""
        model = self.posed(model)
        self.check(model)
        super().precompute(model)
        if self.thermal:
            thermal_model(model.craft, self.settings)

    def solar_fraction(self, earth_vector: NDArray[np.float64]) -> float:
        """The share of the solar disc the Earth leaves in view with its centre along ``earth_vector``
        (body frame), by the conical shadow model."""
        return sun_behind(
            earth_vector, self.altitude_km, np.asarray(self.sun_vector), planet("earth").radius_m, ECLIPSE
        )

    def evaluate(self, model: Model, directions: NDArray[np.float64]) -> Records:
        """The records of Earth directions ``directions`` (n, 3), body frame."""
        model = self.posed(model)
        light, options, sun = self.light(), self.options() | self.keyword(), np.asarray(self.sun_vector)
        materials = self.materials or model.craft.materials.names
        out = empty_records(self.fields, len(directions))
        estimates = []
        for i, u in enumerate(directions):
            fraction = self.solar_fraction(u)
            place = Place(u, self.altitude_km, sun, None, fraction)
            result = planet_radiation(
                model, place, light, cap=CapSampling(self.cell_deg, self.cap_method), **options
            )
            force, torque = result.force_N, result.torque_Nm
            if self.thermal:
                state = result.equilibrium(options["reflections"])
                out["thermal_force_N"][i], out["thermal_torque_Nm"][i] = state.force_N, state.torque_Nm
                force, torque = force + state.force_N, torque + state.torque_Nm
            out["force_N"][i], out["torque_Nm"][i] = force, torque
            for name, band in (("albedo", result.albedo), ("infrared", result.infrared)):
                out[f"{name}_force_N"][i], out[f"{name}_torque_Nm"][i] = band.force_N, band.torque_Nm
            out["solar_fraction"][i] = fraction
            if self.sensitivities:
                for name, row in flat(result.sensitivities, materials).items():
                    out[name][i] = row
            error = result.shadow_error  # relative to the loads recorded, the thermal recoil's too
            estimates.append(
                None if error is None else ErrorEstimate.of(error, force, torque, model.craft.diagonal_m)
            )
        if self.estimates:
            out |= estimate_records(estimates)
        return out

    def attributes(self, model: Model) -> dict:
        """What a table of this setup states: the slice (altitude, the fixed Sun), the Earth's albedo and
        infrared, the flux, the disc's cells, the thermal recoil and the reflection mode it used."""
        posed = self.posed(model)
        light, earth = self.light(), planet("earth")
        albedo = earth.albedo if self.albedo is None else self.albedo
        distance = earth.radius_m + self.altitude_km * 1e3
        tracking = [hinge.pattern for hinge in model.hinges if hinge.law == "track"]
        return {
            "earth_slice": SLICE,
            "earth_altitude_km": self.altitude_km,
            "earth_sun_vector": list(self.sun_vector),
            "earth_radius_m": earth.radius_m,
            "earth_half_angle_deg": math.degrees(math.asin(earth.radius_m / distance)),
            "earth_flux_W_m2": self.flux_W_m2,
            "earth_model": light.description,
            "earth_albedo": albedo,
            "earth_infrared_W_m2": light.infrared.uniform_W_m2,
            "earth_cell_deg": self.cell_deg,
            "earth_cap_method": self.cap_method,
            "earth_eclipse": ECLIPSE,
            "earth_thermal": self.thermal,
            "earth_reflections": reflection_plan(posed.craft, self.settings).mode,
        } | ({"earth_tracking_hinges": ", ".join(tracking)} if tracking else {})
