"""The heat flux each sensor absorbs at a given Sun and nadir direction: sunlight, albedo and
infrared through the sensor response (METHOD.md "Attitude from heat fluxes").

Sunlight is the response to a beam along the Sun times the flux and the solar fraction (the planet's
conical shadow, a function of the angle between the Sun and the nadir). The albedo and the infrared
are the planet's radiance over the visible cap: the plate law by the cap's exact integrals
(:meth:`~sunwind.forces.planet.cap.Cap.side_integrals`, terminator included), and the correction by
the cap's quadrature rule over the interpolated correction. This is
:func:`~sunwind.forces.earth.planet_radiation` condensed: the same physics, no ray cast per call.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.cap import Cap
from sunwind.forces.planet.shadow import unblocked
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, solar_flux
from sunwind.forces.sensing.response import SensorResponse, sensor_response
from sunwind.geometry.errors import InputError

#: One astronomical unit [m]: the Sun's distance for the solar fraction.
AU_M = 1.495978707e11
#: Points of the uniform infrared's table against the cosine of a plane's angle to the nadir (linear
#: interpolation: about 1e-7 of the irradiance).
INFRARED_POINTS = 4097
#: Points of the solar fraction's table against the cosine of the Sun's angle to the nadir (0.003 degrees
#: apart in the penumbra of a low orbit, where the fraction changes over about 0.5 degrees).
FRACTION_POINTS = 40001
#: The caps' quadrature for the correction: rings and azimuths (as the visibility method's).
CAP_RULE = (16, 24)


@dataclass(frozen=True)
class SensorFluxes:
    """The flux each sensor absorbs, by source [W/m^2 of the sensor's area], (p,) each.

    Attributes
    ----------
    solar, albedo, infrared : (p,) float64
        Sunlight (after shadowing and reflections), the planet's reflected sunlight, its infrared.
    solar_fraction : float
        Share of the solar disc in view (0 in the planet's umbra).

    Examples
    --------
    >>> parts = SensorFluxes(np.array([1.0]), np.array([2.0]), np.array([3.0]), 1.0)
    >>> parts.total
    array([6.])
    """

    solar: NDArray[np.float64]
    albedo: NDArray[np.float64]
    infrared: NDArray[np.float64]
    solar_fraction: float

    @property
    def total(self) -> NDArray[np.float64]:
        """All three summed [W/m^2], (p,)."""
        return self.solar + self.albedo + self.infrared


@dataclass(frozen=True, eq=False)
class FluxModel:
    """Sensor fluxes at any Sun and nadir direction, at one altitude above one planet.

    Attributes
    ----------
    response : SensorResponse
        The sensors' response to a parallel beam.
    light : PlanetLight
        The planet, its albedo and infrared laws and the solar flux (uniform over the planet: the pole
        is not known in the body frame).
    altitude_km : float
        Height above the planet's surface [km].

    Examples
    --------
    A cube over the Earth at 500 km with the Sun overhead: the zenith face takes the Sun, the nadir face
    the albedo and infrared.

    >>> import sunwind as sw
    >>> black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    >>> fluxes = flux_model(cube, 500.0).fluxes([0.0, 0.0, 1.0], [0.0, 0.0, -1.0])
    >>> np.round(fluxes.total, 1)  # +x, -x, +y, -y, +z, -z
    array([ 152.7,  152.7,  152.7,  152.7, 1265.7,  492.6])
    """

    response: SensorResponse
    light: PlanetLight
    altitude_km: float

    @functools.cached_property
    def _uniform_infrared(self) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """A uniform infrared's irradiance on a plane against the cosine of its normal to the nadir,
        (cos, i0) on :data:`INFRARED_POINTS` points, from the cap's exact integrals; None when the
        infrared follows the Sun."""
        law = self.light.infrared
        if law.insolation_W_m2:
            return None
        cos = np.linspace(-1.0, 1.0, INFRARED_POINTS)
        normals = np.column_stack([np.sqrt(np.maximum(0.0, 1.0 - cos**2)), np.zeros_like(cos), -cos])
        down = np.array([0.0, 0.0, -1.0])
        cap = Cap(down, down, np.array([1.0, 0.0, 0.0]), self.distance_m, self.light.planet.radius_m, law)
        return cos, cap.side_integrals(normals)[0]

    @functools.cached_property
    def _fraction_table(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The solar fraction against the cosine of the angle between the Sun and the nadir, on
        :data:`FRACTION_POINTS` points (it depends on nothing else)."""
        cos = np.linspace(-1.0, 1.0, FRACTION_POINTS)
        sun = np.column_stack([np.sqrt(np.maximum(0.0, 1.0 - cos**2)), np.zeros_like(cos), cos])
        return cos, self.solar_fraction(sun, np.tile([0.0, 0.0, 1.0], (len(cos), 1)))

    @property
    def distance_m(self) -> float:
        """Distance from the planet's centre [m]."""
        return self.light.planet.radius_m + self.altitude_km * 1e3

    @property
    def half_angle(self) -> float:
        """Angular radius of the planet seen from the spacecraft [rad]."""
        return math.asin(self.light.planet.radius_m / self.distance_m)

    def solar_fraction(self, sun: NDArray[np.float64], nadir: NDArray[np.float64]) -> NDArray[np.float64]:
        """Share of the solar disc in view for unit Sun and nadir directions (n, 3) each: the planet's
        conical shadow, the Sun at the distance of the light's solar flux.

        Parameters
        ----------
        sun, nadir : (n, 3) float64
            Unit directions, any common frame.

        Returns
        -------
        (n,) float64
            0 (umbra) to 1.

        Examples
        --------
        >>> import sunwind as sw
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> up, down = np.array([[0.0, 0, 1], [0, 0, -1]]), np.array([[0.0, 0, -1]] * 2)
        >>> flux_model(cube, 500.0).solar_fraction(up, down)
        array([1., 0.])
        """
        sun_m = AU_M * math.sqrt(SOLAR_FLUX_1AU / self.light.solar_flux_W_m2) * sun  # inverse square
        return unblocked(
            -self.distance_m * nadir, sun_m, np.zeros_like(sun_m), self.light.planet.radius_m, "conical"
        )

    def fluxes(
        self, sun: NDArray[np.float64], nadir: NDArray[np.float64], traced: bool = True
    ) -> SensorFluxes:
        """Each sensor's absorbed flux by source [W/m^2 of its area].

        Parameters
        ----------
        sun, nadir : (3,) array_like of float
            Unit directions toward the Sun and the planet's centre, body frame.
        traced : bool
            Trace sunlight (where the model has a correction: one shadow pass and trace); else take it
            from the interpolated correction, first order across a shadow's kink but faster on a large
            model (the search's first pass).

        Returns
        -------
        SensorFluxes

        Examples
        --------
        >>> import sunwind as sw
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> night = flux_model(cube, 500.0).fluxes([0.0, 0.0, -1.0], [0.0, 0.0, -1.0])
        >>> night.solar_fraction, float(night.albedo.sum()), round(float(night.infrared[5]), 1)
        (0.0, 0.0, 163.8)
        """
        sun = np.asarray(sun, dtype=np.float64)
        nadir = np.asarray(nadir, dtype=np.float64)
        response, light = self.response, self.light
        fraction = float(np.interp(sun @ nadir, *self._fraction_table))
        solar = np.zeros(len(response.sensors))
        if fraction > 0.0:
            along = response.traced("solar", sun) if traced else response.collimated("solar", sun[None, :])[0]
            solar = fraction * light.solar_flux_W_m2 * along
        pole = np.array([1.0, 0.0, 0.0]) if abs(nadir[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        caps = [
            Cap(nadir, sun, pole, self.distance_m, light.planet.radius_m, law)
            for law in (light.albedo, light.infrared)
        ]
        infrared = self._uniform_infrared
        if infrared is None:
            glow = caps[1].side_integrals(response.normals)[0]
        else:  # the same integrals, tabulated once against the one angle they depend on
            glow = np.interp(response.normals @ nadir, *infrared)
        albedo = caps[0].side_integrals(response.normals)[0]
        bands = [response.plate_m2["solar"] @ albedo, response.plate_m2["infrared"] @ glow]
        if response.correction_m2 is not None:
            points, solid = caps[0].quadrature(*CAP_RULE)
            for k, (band, cap) in enumerate(zip(("solar", "infrared"), caps, strict=True)):
                bands[k] = bands[k] + (cap.radiance_along(points) * solid) @ response.correction(band, points)
        area = response.areas_m2
        return SensorFluxes(solar / area, bands[0] / area, bands[1] / area, fraction)


def flux_model(
    model,
    altitude_km: float,
    light: PlanetLight | None = None,
    sensors: tuple[str, ...] | None = None,
    reflections: str = "auto",
) -> FluxModel:
    """The sensor flux model of ``model`` at ``altitude_km`` above the planet of ``light``.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model.
    altitude_km : float
        Height above the surface [km], > 0.
    light : PlanetLight, optional
        Default the Earth at 1 au (albedo 0.30, uniform infrared).
    sensors : tuple of str, optional
        Sensor part patterns; default every part.
    reflections : str
        As for :func:`~sunwind.forces.earth.planet_radiation`.

    Returns
    -------
    FluxModel

    Raises
    ------
    InputError
        An altitude that is not positive, or a light whose albedo or infrared depends on latitude.

    Examples
    --------
    >>> import sunwind as sw
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> round(math.degrees(flux_model(cube, 500.0).half_angle), 2)
    68.02
    """
    if not (math.isfinite(altitude_km) and altitude_km > 0):
        raise InputError(
            f"altitude {altitude_km} km is not a height above the surface", parameters=("altitude",)
        )
    light = PlanetLight.of(planet("earth"), solar_flux()) if light is None else light
    for law in (light.albedo, light.infrared):
        if tuple(law.latitude) != (1.0, 0.0, 0.0):
            raise InputError(
                "attitude from fluxes needs a planet uniform in latitude (the pole is not known in the body "
                "frame)",
                hint="use a uniform albedo and infrared (not Knocke's model)",
                parameters=("light",),
            )
    return FluxModel(sensor_response(model, sensors, reflections), light, float(altitude_km))
