"""The free stream for free-molecular forces: atmospheric composition, temperature and flow speed.

An :class:`Atmosphere` holds the number density of each gas species, the free-stream (kinetic)
temperature and a line saying where they came from. It is made either by NRLMSIS through ``pymsis``
(:func:`nrlmsis`) or from a user-given density, temperature and composition (:func:`explicit`).
:func:`circular_speed` and :func:`corotation_speed` give the speed of the spacecraft relative to the
atmosphere for the common case of a circular orbit in an atmosphere rotating with the Earth.

Notes
-----
Species and their masses. The gas-surface models sum over O, N2, O2, He, H, N, Ar and anomalous O
(METHOD.md, "Free-molecular flow"). Molecular masses are built from the IUPAC/CIAAW 2021 standard
atomic weights (conventional values for the elements whose standard weight is an interval: H 1.008,
N 14.007, O 15.999, Ar 39.95; He 4.002602) times the atomic mass constant (CODATA 2018). Anomalous
oxygen ("O*": hot O and O+ that NRLMSIS lumps together for drag) has the mass of O.

NRLMSIS computes its own total mass density with slightly different masses (CIPM 2007 molar masses
of N2, O2, Ar, halved for N and O, and the rounded values 4.0 for He and 1.0 for H). Here the density
is always ``sum n_k m_k`` with the masses above, so that the force summed over species and the
dynamic pressure ``rho V^2 / 2`` used for coefficients agree. It differs from NRLMSIS's own total by
the mass-weighted mean of the mass ratios (default inputs): 2e-5 at 400 km, 0.1 % at 1000 km, 0.4 % at
2000 km where H and He dominate. NRLMSIS's own total is kept as :attr:`Atmosphere.model_density_kg_m3`.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import date, datetime, timezone
from types import MappingProxyType

import numpy as np

from sunwind.geometry.errors import InputError

#: Boltzmann constant [J/K] (exact, SI 2019).
BOLTZMANN = 1.380649e-23
#: Atomic mass constant [kg] (CODATA 2018).
ATOMIC_MASS = 1.66053906660e-27
#: Earth's gravitational parameter GM [m^3/s^2] (WGS 84 / IERS Conventions 2010).
EARTH_GM = 3.986004418e14
#: Earth's equatorial radius [m] (WGS 84 semi-major axis).
EARTH_RADIUS = 6378.137e3
#: Earth's mean angular velocity [rad/s] (WGS 84 nominal value).
EARTH_ROTATION = 7.292115e-5

#: Standard atomic weights used here (IUPAC/CIAAW 2021; conventional values where the standard weight is
#: an interval) [g/mol, i.e. in units of the atomic mass constant].
ATOMIC_WEIGHT = MappingProxyType({"H": 1.008, "He": 4.002602, "N": 14.007, "O": 15.999, "Ar": 39.95})

#: Species known to sunwind: canonical name -> molecular mass [kg], in the order reports list them.
SPECIES_MASS_KG = MappingProxyType(
    {
        "O": ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
        "N2": 2 * ATOMIC_WEIGHT["N"] * ATOMIC_MASS,
        "O2": 2 * ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
        "He": ATOMIC_WEIGHT["He"] * ATOMIC_MASS,
        "H": ATOMIC_WEIGHT["H"] * ATOMIC_MASS,
        "N": ATOMIC_WEIGHT["N"] * ATOMIC_MASS,
        "Ar": ATOMIC_WEIGHT["Ar"] * ATOMIC_MASS,
        "O*": ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
    }
)

#: Names a user may type for a species (compared without regard to case) -> canonical name.
_ALIASES = {name.lower(): name for name in SPECIES_MASS_KG} | {
    alias: "O*"
    for alias in (
        "anomalous_o",
        "anomalous-o",
        "anomalous o",
        "anomalouso",
        "anomalous_oxygen",
        "ao",
        "o_anom",
    )
}

#: Years NRLMSIS dates are accepted for.
YEAR_RANGE = (1958, 2100)
#: Altitudes [km] NRLMSIS is accepted for; above the fitted limit a warning names the extrapolation.
MSIS_MAX_ALTITUDE_KM = 2000.0
MSIS_FITTED_ALTITUDE_KM = 1000.0
#: Below this altitude [km] a warning says free-molecular flow no longer holds for a metre-sized body.
FREE_MOLECULAR_MIN_ALTITUDE_KM = 150.0
#: Effective collision diameter of air [m] for the hard-sphere mean free path (U.S. Standard Atmosphere 1976).
COLLISION_DIAMETER = 3.65e-10

#: Model versions ``pymsis.calculate`` accepts -> the model's name.
_MSIS_VERSIONS = {"2.1": "NRLMSIS 2.1", "2.0": "NRLMSIS 2.0", "0": "NRLMSISE-00"}
#: Member of ``pymsis.Variable`` (the output columns of ``pymsis.calculate``, pymsis >= 0.10) per species.
_MSIS_VARIABLES = {
    "N2": "N2",
    "O2": "O2",
    "O": "O",
    "He": "HE",
    "H": "H",
    "Ar": "AR",
    "N": "N",
    "O*": "ANOMALOUS_O",
}


class AtmosphereWarning(UserWarning):
    """The atmosphere asked for is usable but outside where its model or free-molecular flow is sound."""


def species_name(name: str) -> str:
    """The canonical name of a species as a user may type it ("o2", "he", "anomalous_O", "O*").

    Raises
    ------
    InputError
        A name that is not one of the known species; the message lists them.
    """
    canonical = _ALIASES.get(str(name).strip().lower())
    if canonical is None:
        raise InputError(
            f"unknown species '{name}'",
            hint=f"known species are {', '.join(SPECIES_MASS_KG)} (O* is anomalous oxygen)",
        )
    return canonical


@dataclass(frozen=True)
class Atmosphere:
    """The free-stream gas: number density of each species and the kinetic temperature.

    Attributes
    ----------
    number_density_m3 : dict[str, float]
        Number density [m^-3] of each species present (only ``n > 0``), keyed by canonical name
        (``SPECIES_MASS_KG``), in table order.
    temperature_K : float
        Free-stream kinetic temperature [K].
    source : str
        Where the values came from, one line, e.g. ``"NRLMSIS 2.1 (pymsis 0.13.0): 400 km, ..."`` or
        ``"user: density ..., temperature ..., composition ..."``.
    altitude_km : float, optional
        Altitude [km] the atmosphere is for, when known.
    inputs : dict[str, float | str]
        The other inputs, kept for reports (latitude, longitude, time, solar and geomagnetic indices).
    model_density_kg_m3 : float, optional
        The source model's own total mass density [kg/m^3] (NRLMSIS's, computed with its own masses).
    """

    number_density_m3: dict[str, float]
    temperature_K: float
    source: str
    altitude_km: float | None = None
    inputs: dict[str, float | str] = field(default_factory=dict)
    model_density_kg_m3: float | None = None

    def __post_init__(self) -> None:
        densities: dict[str, float] = {}
        for name, n in self.number_density_m3.items():
            key = species_name(name)
            if key in densities:
                raise InputError(f"species {key} is given twice")
            n = float(n)
            if not math.isfinite(n) or n <= 0:
                raise InputError(f"number density of {key} is {n} m^-3, not a finite positive number")
            densities[key] = n
        if not densities:
            raise InputError("the atmosphere has no species with a positive number density")
        temperature = float(self.temperature_K)
        if not math.isfinite(temperature) or temperature <= 0:
            raise InputError(f"temperature {temperature} K is not a finite positive number")
        ordered = {k: densities[k] for k in SPECIES_MASS_KG if k in densities}
        object.__setattr__(self, "number_density_m3", ordered)
        object.__setattr__(self, "temperature_K", temperature)
        object.__setattr__(self, "inputs", dict(self.inputs))

    __hash__ = None  # it holds dicts: equal atmospheres compare equal but are not hashable

    @property
    def mass_kg(self) -> dict[str, float]:
        """Molecular mass [kg] of each species present."""
        return {k: SPECIES_MASS_KG[k] for k in self.number_density_m3}

    @property
    def total_number_density_m3(self) -> float:
        """Number density of all species together [m^-3]."""
        return math.fsum(self.number_density_m3.values())

    @property
    def density_kg_m3(self) -> float:
        """Mass density ``rho = sum n_k m_k`` [kg/m^3]."""
        return math.fsum(n * SPECIES_MASS_KG[k] for k, n in self.number_density_m3.items())

    @property
    def mole_fractions(self) -> dict[str, float]:
        """Number (mole) fraction ``n_k / sum n`` of each species; they sum to 1."""
        total = self.total_number_density_m3
        return {k: n / total for k, n in self.number_density_m3.items()}

    @property
    def mean_mass_kg(self) -> float:
        """Mean molecular mass ``rho / sum n`` [kg]."""
        return self.density_kg_m3 / self.total_number_density_m3

    @property
    def mean_free_path_m(self) -> float:
        """Hard-sphere mean free path ``1 / (sqrt(2) pi d^2 n)`` [m], air diameter ``d`` of USSA 1976.

        A rough guide to the Knudsen number ``Kn = lambda / L`` of a body of size ``L``: free-molecular
        flow needs ``Kn`` of about 10 or more.
        """
        return 1.0 / (math.sqrt(2.0) * math.pi * COLLISION_DIAMETER**2 * self.total_number_density_m3)

    def speed_ratio(self, speed_m_s: float) -> dict[str, float]:
        """Molecular speed ratio ``S_k = V / sqrt(2 k T / m_k)`` of each species.

        Parameters
        ----------
        speed_m_s : float
            Speed ``V = |v_rel|`` of the spacecraft relative to the atmosphere [m/s].

        Returns
        -------
        dict[str, float]
            Dimensionless speed ratio per species present.
        """
        speed = _finite(speed_m_s, "speed", "m/s", minimum=0.0)
        return {
            k: speed / math.sqrt(2.0 * BOLTZMANN * self.temperature_K / m) for k, m in self.mass_kg.items()
        }

    def mean_speed_ratio(self, speed_m_s: float) -> float:
        """Speed ratio of the mixture ``V / sqrt(2 k T / m_mean)`` with :attr:`mean_mass_kg`."""
        speed = _finite(speed_m_s, "speed", "m/s", minimum=0.0)
        return speed / math.sqrt(2.0 * BOLTZMANN * self.temperature_K / self.mean_mass_kg)

    @classmethod
    def from_json(cls, document: dict) -> Atmosphere:
        """The atmosphere :meth:`to_json` describes (numbers round-trip exactly through JSON)."""
        return cls(
            document["number_density_m3"],
            document["temperature_K"],
            document["source"],
            document.get("altitude_km"),
            document.get("inputs", {}),
            document.get("model_density_kg_m3"),
        )

    def to_json(self) -> dict:
        """A JSON-ready description: density [kg/m^3], temperature [K], per-species number density [m^-3]."""
        out: dict = {
            "source": self.source,
            "density_kg_m3": self.density_kg_m3,
            "temperature_K": self.temperature_K,
            "mean_mass_kg": self.mean_mass_kg,
            "number_density_m3": dict(self.number_density_m3),
            "mole_fractions": self.mole_fractions,
            "species_mass_kg": self.mass_kg,
        }
        if self.altitude_km is not None:
            out["altitude_km"] = self.altitude_km
        if self.inputs:
            out["inputs"] = dict(self.inputs)
        if self.model_density_kg_m3 is not None:
            out["model_density_kg_m3"] = self.model_density_kg_m3
        return out


def nrlmsis(
    altitude_km: float,
    latitude_deg: float = 0.0,
    longitude_deg: float = 0.0,
    time: str | datetime | date | np.datetime64 = "2024-01-01T00:00:00Z",
    f107: float = 150.0,
    f107a: float = 150.0,
    ap: float = 4.0,
    version: float | str = 2.1,
) -> Atmosphere:
    """The atmosphere of NRLMSIS (through ``pymsis.calculate``) at one place and time.

    Number densities, temperature and NRLMSIS's own total mass density are passed through unchanged
    (``pymsis`` returns them in single precision). Species NRLMSIS leaves undefined (NaN: in NRLMSIS 2.1
    O below 55 km, H below 80 km, N below 95 km, anomalous O in the lower thermosphere) or zero are left
    out. NO, which NRLMSIS 2.1 also gives and leaves out of its total mass density, is not one of the
    species summed and is dropped.

    Parameters
    ----------
    altitude_km : float
        Geodetic altitude [km] above the WGS 84 ellipsoid, 0 to 2000. A warning is given below 150 km
        (free-molecular flow no longer holds for a metre-sized body) and above 1000 km (NRLMSIS is fitted
        to about 1000 km; above, its exosphere is extrapolated).
    latitude_deg, longitude_deg : float
        Geodetic latitude [deg], -90 to 90, and longitude [deg] east. Default 0, 0.
    time : str, datetime, date or numpy.datetime64
        UTC time. A string is ISO 8601 ("2024-01-01", "2024-01-01T12:00:00Z", "...+02:00"); a naive
        datetime is taken as UTC. Years 1958 to 2100. Default 2024-01-01T00:00:00Z, which is local
        midnight at longitude 0 (NRLMSIS uses the day of year and the time of day; the year itself is
        only checked).
    f107 : float
        Daily F10.7 solar radio flux of the previous day [sfu = 1e-22 W m^-2 Hz^-1]. Default 150.
    f107a : float
        81-day centred average of F10.7 [sfu]. Default 150.
    ap : float
        Daily geomagnetic Ap index. Default 4.
    version : float or str
        NRLMSIS version: 2.1 (default), 2.0, or 0 for NRLMSISE-00.

    Returns
    -------
    Atmosphere

    Notes
    -----
    The default indices F10.7 = F10.7a = 150 sfu, Ap = 4 are the reference inputs of NRLMSIS's own check
    values: moderate solar activity, quiet geomagnetic conditions. Space-weather files are never read
    or downloaded: the indices are always passed to ``pymsis``. For mean conditions as ECSS-E-ST-10-04C
    defines them use F10.7 = F10.7a = 140, Ap = 15.

    Raises
    ------
    InputError
        An altitude, latitude, date, index or version outside the ranges above.
    """
    altitude = _finite(altitude_km, "--altitude", "km", minimum=0.0)
    if altitude > MSIS_MAX_ALTITUDE_KM:
        raise InputError(
            f"--altitude {altitude:g} km is above {MSIS_MAX_ALTITUDE_KM:g} km, where NRLMSIS's extrapolated "
            "exosphere cannot be trusted",
            hint="give the density, temperature and composition explicitly instead",
        )
    latitude = _finite(latitude_deg, "--lat", "deg", minimum=-90.0, maximum=90.0)
    longitude = _finite(longitude_deg, "--lon", "deg")
    when = parse_time(time)
    f107 = _finite(f107, "--f107", "sfu", minimum=0.0)
    f107a = _finite(f107a, "--f107a", "sfu", minimum=0.0)
    ap = _finite(ap, "--ap", "", minimum=0.0)
    version_key = _msis_version(version)

    if altitude > MSIS_FITTED_ALTITUDE_KM:
        warnings.warn(
            f"altitude {altitude:g} km is above {MSIS_FITTED_ALTITUDE_KM:g} km, the top of the data "
            "NRLMSIS is fitted to: its exosphere is an extrapolation there",
            AtmosphereWarning,
            stacklevel=2,
        )

    import pymsis

    row = pymsis.calculate(
        np.datetime64(when.replace(tzinfo=None)),
        longitude,
        latitude,
        altitude,
        f107,
        f107a,
        ap,
        version=version_key,
    ).reshape(-1)
    column = pymsis.Variable
    densities = {k: float(row[column[member]]) for k, member in _MSIS_VARIABLES.items()}
    densities = {k: n for k, n in densities.items() if not math.isnan(n) and n > 0}
    model_name = _MSIS_VERSIONS[version_key]
    stamp = when.strftime("%Y-%m-%dT%H:%M:%S") + "Z"
    source = (
        f"{model_name} (pymsis {pymsis.__version__}): {altitude:g} km, lat {latitude:g}, lon {longitude:g}, "
        f"{stamp}, F10.7 {f107:g}, F10.7a {f107a:g}, Ap {ap:g}"
    )
    atmosphere = Atmosphere(
        densities,
        float(row[column.TEMPERATURE]),
        source,
        altitude_km=altitude,
        inputs={
            "model": model_name,
            "latitude_deg": latitude,
            "longitude_deg": longitude,
            "time_utc": stamp,
            "f107_sfu": f107,
            "f107a_sfu": f107a,
            "ap": ap,
        },
        model_density_kg_m3=float(row[column.MASS_DENSITY]),
    )
    if altitude < FREE_MOLECULAR_MIN_ALTITUDE_KM:
        warnings.warn(
            f"altitude {altitude:g} km is below {FREE_MOLECULAR_MIN_ALTITUDE_KM:g} km, the free-molecular "
            f"limit: the mean free path is {atmosphere.mean_free_path_m:.3g} m, so the Knudsen number of a "
            "metre-sized spacecraft is below about 10 and free-molecular forces no longer hold",
            AtmosphereWarning,
            stacklevel=2,
        )
    return atmosphere


def explicit(
    density_kg_m3: float,
    temperature_K: float,
    composition: str | Mapping[str, float],
    normalise: bool = False,
) -> Atmosphere:
    """An atmosphere from a given mass density, temperature and composition.

    Parameters
    ----------
    density_kg_m3 : float
        Mass density [kg/m^3], finite and positive.
    temperature_K : float
        Free-stream kinetic temperature [K], finite and positive.
    composition : str or Mapping[str, float]
        Mole (number) fraction of each species, not mass fraction: ``"O:0.7,N2:0.3"`` means 70 % of the
        molecules are O. Species names as :func:`species_name` accepts them; ``=`` may stand for ``:``.
    normalise : bool
        Rescale the fractions to sum to 1 (``--normalise-composition``). Otherwise they must sum to 1
        within 1e-6 (and are then rescaled exactly).

    Returns
    -------
    Atmosphere
        Number densities ``n_k = x_k rho / m_mean`` with ``m_mean = sum x_k m_k``, so that
        ``sum n_k m_k = rho``.

    Raises
    ------
    InputError
        Unknown species, a fraction that is negative or not finite, fractions that do not sum to 1, or a
        density or temperature that is not finite and positive.
    """
    rho = _finite(density_kg_m3, "--density", "kg/m^3", positive=True)
    temperature = _finite(temperature_K, "--temperature", "K", positive=True)
    fractions = parse_composition(composition)
    total = math.fsum(fractions.values())
    if total <= 0:
        raise InputError(
            "--composition fractions sum to 0", hint="give at least one species a positive fraction"
        )
    if not normalise and abs(total - 1.0) > 1e-6:
        raise InputError(
            f"--composition mole fractions sum to {total:.9g}, not 1",
            hint="correct them, or add --normalise-composition (normalise=True) to rescale them to sum to 1",
        )
    fractions = {k: fractions[k] / total for k in SPECIES_MASS_KG if fractions.get(k, 0.0) > 0}
    mean_mass = math.fsum(x * SPECIES_MASS_KG[k] for k, x in fractions.items())
    n_total = rho / mean_mass
    described = ", ".join(f"{k}:{x:.6g}" for k, x in fractions.items())
    source = (
        f"user: density {rho:.6g} kg/m^3, temperature {temperature:.6g} K, "
        f"composition {described} (mole fractions)"
    )
    return Atmosphere({k: x * n_total for k, x in fractions.items()}, temperature, source)


def parse_composition(composition: str | Mapping[str, float]) -> dict[str, float]:
    """Mole fractions by canonical species name from ``"O:0.7,N2:0.3"`` or a mapping; not normalised.

    Raises
    ------
    InputError
        Unknown or repeated species, an entry that does not read as ``SPECIES:FRACTION``, or a fraction
        that is negative or not finite.
    """
    if isinstance(composition, str):
        pairs: list[tuple[str, object]] = []
        for item in filter(None, (s.strip() for s in re.split(r"[,;]", composition))):
            name, sep, value = item.partition(":") if ":" in item else item.partition("=")
            name, value = name.strip(), value.strip()
            if not sep or not name or not value:
                raise InputError(
                    f"--composition entry '{item}' is not SPECIES:FRACTION",
                    hint="e.g. --composition O:0.7,N2:0.3",
                )
            pairs.append((name, value))
    else:
        pairs = list(composition.items())
    if not pairs:
        raise InputError("--composition is empty", hint="e.g. --composition O:0.7,N2:0.3")
    fractions: dict[str, float] = {}
    for name, value in pairs:
        key = species_name(name)
        if key in fractions:
            raise InputError(f"--composition gives {key} twice")
        try:
            x = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise InputError(f"--composition fraction of {key} '{value}' is not a number") from None
        if not math.isfinite(x) or x < 0:
            raise InputError(f"--composition fraction of {key} is {x}, not a finite non-negative number")
        fractions[key] = x
    return fractions


def parse_time(time: str | datetime | date | np.datetime64) -> datetime:
    """A UTC time (timezone-aware) from an ISO 8601 string, a datetime (naive = UTC), a date or datetime64.

    Raises
    ------
    InputError
        A string that does not parse, or a year outside 1958 to 2100.
    """
    if isinstance(time, np.datetime64):
        if np.isnat(time):
            raise InputError("--time is NaT", hint="give an ISO 8601 UTC time such as 2024-01-01T00:00:00Z")
        text = str(time.astype("datetime64[us]"))
        when = datetime.fromisoformat(text)
    elif isinstance(time, datetime):
        when = time
    elif isinstance(time, date):
        when = datetime(time.year, time.month, time.day)
    else:
        text = str(time).strip()
        iso = text[:-1] + "+00:00" if text[-1:] in ("Z", "z") else text
        try:
            when = datetime.fromisoformat(iso)
        except ValueError:
            raise InputError(
                f"--time '{text}' is not an ISO 8601 date or time",
                hint="e.g. 2024-01-01 or 2024-01-01T12:00:00Z (UTC unless an offset is given)",
            ) from None
    when = when.replace(tzinfo=timezone.utc) if when.tzinfo is None else when.astimezone(timezone.utc)
    low, high = YEAR_RANGE
    if not low <= when.year <= high:
        raise InputError(
            f"--time year {when.year} is outside {low}-{high}: NRLMSIS is fitted to space-age data (since "
            "1958) and has no long-term trend, so a date outside that span is taken as a mistake",
            hint="give a UTC date between 1958 and 2100",
        )
    return when


def circular_speed(altitude_km: float) -> float:
    """Speed [m/s] of a circular orbit ``sqrt(GM / (R + h))`` at an altitude above a spherical Earth.

    ``GM = 3.986004418e14 m^3/s^2`` and ``R = 6378.137 km`` (WGS 84 equatorial radius).

    Raises
    ------
    InputError
        An altitude [km] that is negative or not finite.
    """
    altitude = _finite(altitude_km, "--altitude", "km", minimum=0.0)
    return math.sqrt(EARTH_GM / (EARTH_RADIUS + altitude * 1e3))


def corotation_speed(
    altitude_km: float,
    latitude_deg: float,
    heading_deg: float,
    inertial_speed_m_s: float | None = None,
) -> float:
    """Speed [m/s] of a spacecraft relative to an atmosphere that rotates with the Earth.

    The spacecraft is at radius ``r = R + h`` and latitude ``phi`` (spherical Earth) with a horizontal
    inertial velocity of speed ``V`` and heading ``psi`` (clockwise from north: 90 deg is due east, a
    prograde equatorial orbit). The air moves at ``omega x r``, ``omega r cos(phi)`` due east, so

        |v - omega x r| = sqrt(V^2 - 2 V omega r cos(phi) sin(psi) + (omega r cos(phi))^2)

    with ``omega = 7.292115e-5 rad/s``. Winds are not included.

    Parameters
    ----------
    altitude_km : float
        Altitude [km], at least 0.
    latitude_deg : float
        Latitude [deg], -90 to 90.
    heading_deg : float
        Heading of the inertial velocity [deg], clockwise from north.
    inertial_speed_m_s : float, optional
        Inertial speed ``V`` [m/s]; default the circular speed at that altitude.

    Raises
    ------
    InputError
        An argument out of range or not finite.
    """
    altitude = _finite(altitude_km, "--altitude", "km", minimum=0.0)
    latitude = math.radians(_finite(latitude_deg, "--lat", "deg", minimum=-90.0, maximum=90.0))
    heading = math.radians(_finite(heading_deg, "--heading", "deg"))
    if inertial_speed_m_s is None:
        speed = circular_speed(altitude)
    else:
        speed = _finite(inertial_speed_m_s, "inertial speed", "m/s", minimum=0.0)
    air = EARTH_ROTATION * (EARTH_RADIUS + altitude * 1e3) * math.cos(latitude)
    north = speed * math.cos(heading)
    east = speed * math.sin(heading) - air
    return math.hypot(north, east)


def _finite(
    value: float,
    name: str,
    unit: str,
    *,
    minimum: float | None = None,
    maximum: float | None = None,
    positive: bool = False,
) -> float:
    """``value`` as a float, checked finite and in range; ``name`` is how the user gave it."""
    shown = f"{name} {value}{' ' + unit if unit else ''}"
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{shown} is not a number") from None
    if not math.isfinite(x):
        raise InputError(f"{shown} is not a finite number")
    if positive and x <= 0:
        raise InputError(f"{shown} is not positive", hint=f"give {name} greater than 0")
    if minimum is not None and x < minimum:
        raise InputError(f"{shown} is below {minimum:g}", hint=f"give {name} of at least {minimum:g}")
    if maximum is not None and x > maximum:
        raise InputError(f"{shown} is above {maximum:g}", hint=f"give {name} of at most {maximum:g}")
    return x


def _msis_version(version: float | str) -> str:
    """The ``_MSIS_VERSIONS`` key of a version as given (2.1, "2.1", 2.0, 0, "00")."""
    text = str(version).strip()
    try:
        number = float(text)
    except ValueError:
        number = math.nan
    for key in _MSIS_VERSIONS:
        if math.isclose(number, float(key), abs_tol=1e-9):
            return key
    raise InputError(f"--msis-version {version} is not one of 2.1, 2.0, 0 (NRLMSISE-00)")
