"""The planets a spacecraft can orbit and the albedo and infrared each sends (METHOD.md "Planet
radiation").

Each planet is a sphere. Sunlight it reflects is Lambertian with its Bond albedo ``A``; its infrared
follows one of the dissertation's three laws (eqs. 1.25-1.27): a uniform emitter of exitance
``(1 - A) S / 4`` (Earth, Venus: the absorbed sunlight spread over the whole sphere), emission that
follows the insolation, ``(1 - A) S cos(z)`` on the day side and nothing at night (the Moon, Mercury),
or a night-side floor plus a part that follows the insolation (Mars), ``C_1 + C_2 cos(z)+`` with
``C_2 = (1 - A) S - 4 C_1`` so that the planet emits what it absorbs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sunwind.forces.planet.cap import Radiance
from sunwind.forces.planet.knocke import ALBEDO, EMISSIVITY, REFERENCE_EPOCH_JD, YEAR_DAYS, ZonalSeasonal
from sunwind.geometry.errors import InputError

#: Infrared laws of :class:`Planet`.
INFRARED_LAWS = ("uniform", "insolation", "night-floor")
#: Largest uniform infrared exitance accepted [W/m^2]: a black surface at about 1150 K, six times
#: Venus's surface (737 K, 1.7e4 W/m^2), the hottest of the planets.
MAX_INFRARED_W_M2 = 1e5


@dataclass(frozen=True)
class Planet:
    """A planet as a radiation source.

    Parameters
    ----------
    name : str
        Lower-case name, the key of :data:`PLANETS`.
    radius_m : float
        Mean (Earth: equatorial) radius [m].
    albedo : float
        Bond albedo [-], Lambertian.
    infrared : str
        One of :data:`INFRARED_LAWS`.
    night_exitance_W_m2 : float
        ``C_1`` of the ``night-floor`` law [W/m^2].
    source : str
        Where the numbers come from.

    Examples
    --------
    >>> Planet(name="venus", radius_m=6_051_800.0, albedo=0.76, infrared="uniform").albedo
    0.76
    """

    name: str
    radius_m: float
    albedo: float
    infrared: str
    night_exitance_W_m2: float = 0.0
    source: str = ""


PLANETS = {
    "earth": Planet(
        name="earth",
        radius_m=6_378_137.0,
        albedo=0.30,
        infrared="uniform",
        source="WGS 84 equatorial radius; Bond albedo 0.30, the usual mean (Earth radiation budget)",
    ),
    "moon": Planet(
        name="moon",
        radius_m=1_737_400.0,
        albedo=0.12,
        infrared="insolation",
        source="IAU mean radius 1737.4 km; Bond albedo 0.12 (Vasavada et al. 2012, Diviner); "
        "emission follows insolation, none at night (dissertation eq. 1.26)",
    ),
    "mars": Planet(
        name="mars",
        radius_m=3_389_500.0,
        albedo=0.25,
        infrared="night-floor",
        night_exitance_W_m2=50.0,
        source="IAU mean radius 3389.5 km; Bond albedo 0.25; night surface near 172 K (sigma T^4 = 50 "
        "W/m^2) plus a day-side part following the insolation, balanced to the absorbed power "
        "(dissertation eq. 1.27)",
    ),
}


def planet(name: str) -> Planet:
    """The planet called ``name`` (case-insensitive), else an error listing the choices.

    Parameters
    ----------
    name : str
        A key of :data:`PLANETS`, in any case.

    Returns
    -------
    Planet
        That planet.

    Raises
    ------
    InputError
        An unknown name; the message lists the known ones.

    Examples
    --------
    >>> planet("Mars").radius_m
    3389500.0
    """
    try:
        return PLANETS[name.lower()]
    except KeyError:
        raise InputError(
            f"planet {name!r} is not known",
            hint=f"use one of {', '.join(PLANETS)}",
            parameters=("planet",),
        ) from None


@dataclass(frozen=True)
class PlanetLight:
    """The albedo and infrared radiance laws of a planet under a given solar flux.

    Build with :meth:`of`.

    Parameters
    ----------
    planet : Planet
        The planet.
    solar_flux_W_m2 : float
        Solar flux at the planet [W/m^2].
    albedo, infrared : Radiance
        The reflected and emitted radiance laws (:class:`~sunwind.forces.planet.cap.Radiance`, for
        :class:`~sunwind.forces.planet.cap.Cap`).
    description : str
        One line saying which laws these are.

    Examples
    --------
    >>> PlanetLight.of(planet("earth"), 1361.0).description
    'earth: albedo 0.3 Lambertian, infrared (1 - A) S / 4 = 238.2 W/m^2 uniform'
    """

    planet: Planet
    solar_flux_W_m2: float
    albedo: Radiance
    infrared: Radiance
    description: str

    @classmethod
    def of(
        cls,
        body: Planet | str,
        solar_flux_W_m2: float,
        *,
        albedo: float | None = None,
        infrared_W_m2: float | None = None,
        knocke_julian_date: float | None = None,
    ) -> PlanetLight:
        """The laws of ``body`` under ``solar_flux_W_m2`` [W/m^2] at the planet.

        Parameters
        ----------
        body : Planet or str
            The planet, or its name (:data:`PLANETS`).
        solar_flux_W_m2 : float
            Solar flux at the planet [W/m^2].
        albedo : float, optional
            Bond albedo in [0, 1] instead of the planet's.
        infrared_W_m2 : float, optional
            A uniform infrared exitance at the surface [W/m^2], 0 to :data:`MAX_INFRARED_W_M2`,
            instead of the planet's law.
        knocke_julian_date : float, optional
            Earth only: Knocke's latitude- and season-dependent albedo and emissivity at this TT
            Julian date (:mod:`~sunwind.forces.planet.knocke`); ``albedo`` and ``infrared_W_m2`` may
            still replace either.

        Returns
        -------
        PlanetLight
            The two laws and their description.

        Raises
        ------
        InputError
            An albedo outside [0, 1], an infrared exitance out of range, or Knocke's model for a planet
            other than the Earth.

        References
        ----------
        .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
           satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

        Examples
        --------
        >>> light = PlanetLight.of("moon", 1361.0, albedo=0.1)
        >>> light.albedo.insolation_W_m2
        136.1
        """
        flux = solar_flux_W_m2
        if isinstance(body, str):
            body = planet(body)
        if albedo is not None and not (math.isfinite(albedo) and 0.0 <= albedo <= 1.0):
            raise InputError(f"albedo {albedo} is outside [0, 1]", hint="e.g. 0.30", parameters=("albedo",))
        if infrared_W_m2 is not None and not (math.isfinite(infrared_W_m2) and infrared_W_m2 >= 0.0):
            raise InputError(
                f"infrared_W_m2 {infrared_W_m2} is not a finite non-negative number",
                hint="e.g. 239 (the Earth's mean outgoing longwave flux)",
                parameters=("infrared_W_m2",),
            )
        if infrared_W_m2 is not None and infrared_W_m2 > MAX_INFRARED_W_M2:
            raise InputError(
                f"infrared_W_m2 {infrared_W_m2:g} W/m^2 is above {MAX_INFRARED_W_M2:g} W/m^2, the exitance "
                "of a black surface at about 1150 K (Venus's surface, the planets' hottest, emits 1.7e4)",
                hint=f"give infrared_W_m2 of at most {MAX_INFRARED_W_M2:g}, e.g. 239 (the Earth's mean)",
                parameters=("infrared_W_m2",),
            )
        if knocke_julian_date is not None and body.name != "earth":
            raise InputError(
                f"Knocke's albedo model is the Earth's, not that of "
                f"{'the Moon' if body.name == 'moon' else body.name.capitalize()}",
                hint="drop the Knocke model or use the Earth",
                parameters=("albedo_model",),
            )
        a = body.albedo if albedo is None else albedo
        words = []
        if knocke_julian_date is not None and albedo is None:
            reflected = Radiance(insolation_W_m2=flux, latitude=_zonal(ALBEDO, knocke_julian_date))
            words.append("albedo Knocke (1988)")
        else:
            reflected = Radiance(insolation_W_m2=a * flux)
            words.append(f"albedo {a:g} Lambertian")
        if infrared_W_m2 is not None:
            emitted = Radiance(uniform_W_m2=infrared_W_m2)
            words.append(f"infrared {infrared_W_m2:g} W/m^2 uniform")
        elif knocke_julian_date is not None:
            emitted = Radiance(uniform_W_m2=flux / 4, latitude=_zonal(EMISSIVITY, knocke_julian_date))
            words.append("infrared Knocke (1988)")
        elif body.infrared == "uniform":
            emitted = Radiance(uniform_W_m2=(1 - a) * flux / 4)
            words.append(f"infrared (1 - A) S / 4 = {(1 - a) * flux / 4:.4g} W/m^2 uniform")
        elif body.infrared == "insolation":
            emitted = Radiance(insolation_W_m2=(1 - a) * flux)
            words.append("infrared (1 - A) S cos z on the day side")
        else:
            floor = body.night_exitance_W_m2
            emitted = Radiance(uniform_W_m2=floor, insolation_W_m2=max((1 - a) * flux - 4 * floor, 0.0))
            words.append(f"infrared {floor:g} W/m^2 + day side following the insolation")
        return cls(body, flux, reflected, emitted, f"{body.name}: " + ", ".join(words))


def _zonal(coefficients: ZonalSeasonal, julian_date: float) -> tuple[float, float, float]:
    """``(q_0, q_1, q_2)`` of a Knocke expansion on ``julian_date`` (TT)."""
    phase = 2.0 * math.pi * (julian_date - REFERENCE_EPOCH_JD) / YEAR_DAYS
    first = coefficients.p1 + coefficients.p1_cos * math.cos(phase) + coefficients.p1_sin * math.sin(phase)
    return (coefficients.mean, first, coefficients.p2)
