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

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.earth_terms import EarthTerms
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> earth = EarthTerms(SrpSetup(reflections="none"), thermal=True)
    >>> list(earth.fields(n_parts=1))[-3:]
    ['thermal_force_body_N', 'thermal_torque_body_Nm', 'part_temperature_K']
    >>> painted = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
    >>> cube = sw.load(sw.meshes.box(), uniform=painted, threads=1)
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
    >>> result = sw.fly(cube, path, sw.orbit.AttitudeLaw.parse("nadir"), sw.orbit.OrbitLoads(earth=earth))
    >>> result.terms, result.part_names
    (('albedo', 'infrared', 'thermal'), ('box',))
    >>> EarthTerms(SrpSetup(), albedo=1.5)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: albedo 1.5 is outside [0, 1]...
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
        """Record name -> width of a step, for a model of ``n_parts`` parts.

        Parameters
        ----------
        n_parts : int
            The model's number of parts (the width of the per-part records).

        Returns
        -------
        dict of str to int
            :data:`BAND_FIELDS`, the per-part absorbed powers and, with ``thermal``, :data:`THERMAL_FIELDS`
            and the part temperatures.
        """
        out = dict(BAND_FIELDS) | {f"part_{source}_W": n_parts for source in PART_SOURCES}
        if self.thermal:
            out |= THERMAL_FIELDS | {"part_temperature_K": n_parts}
        return out

    def precompute(self, model: Model) -> None:
        """Refuse a model without emissivities before the first step; make the surface setup's view factors.

        Parameters
        ----------
        model : Model
            The model the steps will pose.

        Raises
        ------
        MaterialError
            A material without an emissivity.
        """
        infrared_optics(model.craft)
        self.surface.precompute(model)

    def evaluate(
        self, model: Model, place: Place, sunlight_W_m2: float, julian_tt: float
    ) -> tuple[dict[str, NDArray[np.float64]], LoadsError | None]:
        """One step's records, and the shadow passes' estimated error of its albedo and infrared loads.

        Parameters
        ----------
        model : Model
            The model, posed at the step's hinge angles.
        place : Place
            Where the Earth and Sun are, body frame; its solar fraction is the eclipse.
        sunlight_W_m2 : float
            Solar flux at the spacecraft's distance, without eclipse [W/m^2].
        julian_tt : float
            TT Julian date (Knocke's season).

        Returns
        -------
        records : dict of str to ndarray
            The step's records (:meth:`fields`), body frame.
        error : LoadsError or None
            :attr:`~sunwind.forces.earth.PlanetResult.shadow_error`; None when the shadow pass gives none.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.earth import Place
        >>> from sunwind.forces.orbit.earth_terms import EarthTerms
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> painted = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
        >>> cube = sw.load(sw.meshes.box(), uniform=painted, threads=1)
        >>> earth = EarthTerms(SrpSetup(reflections="none"))
        >>> earth.precompute(cube)
        >>> records, error = earth.evaluate(cube, Place([0, 0, 1], 700.0, [1, 0, 0]), 1361.0, 2460389.5)
        >>> (records["infrared_force_body_N"] * 1e6).round(2) + 0.0  # micronewtons, away from the Earth (-z)
        array([ 0.  ,  0.  , -1.02])
        """
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
        """JSON-ready settings.

        Returns
        -------
        dict
            The fields, the surface setup by its own ``describe``.
        """
        return asdict(self) | {"surface": self.surface.describe()}
