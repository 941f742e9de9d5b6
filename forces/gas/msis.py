"""The atmosphere of NRLMSIS at one place and time, through ``pymsis`` (METHOD.md "Atmosphere").

NRLMSIS computes its own total mass density with slightly different masses (CIPM 2007 molar masses of
N2, O2, Ar, halved for N and O, and the rounded values 4.0 for He and 1.0 for H). Here the density is
always ``sum n_k m_k`` with the masses of :mod:`.atmosphere`. It differs from NRLMSIS's own total by
the mass-weighted mean of the mass ratios (default inputs): 2e-5 at 400 km, 0.1 % at 1000 km, 0.4 %
at 2000 km where H and He dominate. NRLMSIS's own total is kept as
:attr:`~sunwind.forces.gas.atmosphere.Atmosphere.model_density_kg_m3`.
"""

from __future__ import annotations

import math
import warnings
from datetime import date, datetime, timezone

import numpy as np

from sunwind.forces.gas.atmosphere import Atmosphere, AtmosphereWarning, finite_number
from sunwind.geometry.errors import InputError

#: Years NRLMSIS dates are accepted for.
YEAR_RANGE = (1958, 2100)
#: Altitudes [km] NRLMSIS is accepted for; above the fitted limit a warning names the extrapolation.
MSIS_MAX_ALTITUDE_KM = 2000.0
MSIS_FITTED_ALTITUDE_KM = 1000.0
#: Below this altitude [km] a warning says free-molecular flow no longer holds for a metre-sized body.
FREE_MOLECULAR_MIN_ALTITUDE_KM = 150.0
#: Largest F10.7 and F10.7a [sfu] accepted: above the highest daily value on record (about 450 sfu).
MAX_F107_SFU = 500.0
#: Largest Ap accepted: the top of its scale (Ap 400, from ap 400 every three hours).
MAX_AP = 400.0
#: Longitudes [deg] accepted: one turn either way of the prime meridian.
LONGITUDE_RANGE_DEG = (-360.0, 360.0)
#: Temperatures [K] NRLMSIS gives for real conditions, with a margin: 111 K (the summer mesopause) to
#: 2600 K (F10.7 500 sfu, Ap 400). Outside, its fit has run away (inf, 1e7 K or below 0 K where F10.7a
#: is far above F10.7, or both near 0) and the indices are refused.
MSIS_TEMPERATURE_RANGE_K = (50.0, 5000.0)
#: Space weather NRLMSIS is given by default (the reference inputs of NRLMSIS's own check values):
#: the daily F10.7 of the day before and its 81-day centred mean [sfu] of moderate solar activity, and the
#: daily Ap of a quiet field. Every default of these indices (``nrlmsis``, the orbit's ``SpaceWeather``,
#: the CLI flags) reads them here.
DEFAULT_F107_SFU = 150.0
DEFAULT_F107A_SFU = 150.0
DEFAULT_AP = 4.0
#: NRLMSIS version used by default.
DEFAULT_MSIS_VERSION = 2.1
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


def nrlmsis(
    altitude_km: float,
    latitude_deg: float = 0.0,
    longitude_deg: float = 0.0,
    time: str | datetime | date | np.datetime64 = "2024-01-01T00:00:00Z",
    f107: float = DEFAULT_F107_SFU,
    f107a: float = DEFAULT_F107A_SFU,
    ap: float = DEFAULT_AP,
    version: float | str = DEFAULT_MSIS_VERSION,
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
        Geodetic latitude [deg], -90 to 90, and longitude [deg] east, -360 to 360. Default 0, 0.
    time : str, datetime, date or numpy.datetime64
        UTC time. A string is ISO 8601 ("2024-01-01", "2024-01-01T12:00:00Z", "...+02:00"); a naive
        datetime is taken as UTC. Years 1958 to 2100. Default 2024-01-01T00:00:00Z, which is local
        midnight at longitude 0 (NRLMSIS uses the day of year and the time of day; the year itself is
        only checked).
    f107 : float
        Daily F10.7 solar radio flux of the previous day [sfu = 1e-22 W m^-2 Hz^-1], 0 to 500 (the
        highest on record is about 450). Default :data:`DEFAULT_F107_SFU` (150).
    f107a : float
        81-day centred average of F10.7 [sfu], 0 to 500. Indices for which NRLMSIS's fit runs away (a
        temperature outside :data:`MSIS_TEMPERATURE_RANGE_K`: F10.7a far above F10.7, or both near 0)
        are refused. Default :data:`DEFAULT_F107A_SFU` (150).
    ap : float
        Daily geomagnetic Ap index, 0 to 400 (the top of its scale). Default :data:`DEFAULT_AP` (4).
    version : float or str
        NRLMSIS version: 2.1 (default, :data:`DEFAULT_MSIS_VERSION`), 2.0, or 0 for NRLMSISE-00.

    Returns
    -------
    Atmosphere
        Number density of each species and the temperature at the place and time.

    Raises
    ------
    InputError
        An altitude, latitude, date, index or version outside the ranges above.

    Notes
    -----
    The default indices F10.7 = F10.7a = 150 sfu, Ap = 4 are the reference inputs of NRLMSIS's own check
    values: moderate solar activity, quiet geomagnetic conditions. Space-weather files are never read
    or downloaded: the indices are always passed to ``pymsis``. For mean conditions as ECSS-E-ST-10-04C
    defines them use F10.7 = F10.7a = 140, Ap = 15.

    References
    ----------
    Emmert et al. (2022), NRLMSIS 2.1; Emmert et al. (2021), NRLMSIS 2.0; Picone et al. (2002),
    NRLMSISE-00; evaluated through pymsis (SWx TREC).

    Examples
    --------
    >>> import sunwind as sw
    >>> air = sw.nrlmsis(400.0)
    >>> sorted(air.number_density_m3)
    ['Ar', 'H', 'He', 'N', 'N2', 'O', 'O*', 'O2']
    >>> 800 < air.temperature_K < 1100, 1e-12 < air.model_density_kg_m3 < 5e-12  # moderate activity
    (True, True)
    """
    altitude = finite_number(altitude_km, "altitude_km", "km", minimum=0.0)
    if altitude > MSIS_MAX_ALTITUDE_KM:
        raise InputError(
            f"altitude_km {altitude:g} km is above {MSIS_MAX_ALTITUDE_KM:g} km, where NRLMSIS's extrapolated "
            "exosphere cannot be trusted",
            hint="give the density, temperature and composition explicitly instead",
            parameters=("altitude_km",),
        )
    latitude = finite_number(latitude_deg, "latitude_deg", "deg", minimum=-90.0, maximum=90.0)
    low, high = LONGITUDE_RANGE_DEG
    longitude = finite_number(longitude_deg, "longitude_deg", "deg", minimum=low, maximum=high)
    when = parse_time(time)
    f107, f107a, ap = _indices(f107, f107a, ap)
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
    _check_fit(float(row[column.TEMPERATURE]), f107, f107a, ap)
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


def _indices(f107: float, f107a: float, ap: float) -> tuple[float, float, float]:
    """F10.7, F10.7a and Ap as finite floats, each from 0 to its largest physical value."""
    record = "the highest daily F10.7 on record is about 450 sfu"
    out = []
    for name, value, unit, high, why, example in (
        ("f107", f107, "sfu", MAX_F107_SFU, record, "150 (moderate activity)"),
        ("f107a", f107a, "sfu", MAX_F107_SFU, record, "150 (moderate activity)"),
        ("ap", ap, "", MAX_AP, "the top of the Ap scale", "4 (quiet) or 15 (mean)"),
    ):
        x = finite_number(value, name, unit, minimum=0.0)
        if x > high:
            units = f" {unit}" if unit else ""
            raise InputError(
                f"{name} {x:g}{units} is above {high:g}{units} ({why})",
                hint=f"give {name} from 0 to {high:g}, e.g. {example}",
                parameters=(name,),
            )
        out.append(x)
    return out[0], out[1], out[2]


def _check_fit(temperature_K: float, f107: float, f107a: float, ap: float) -> None:
    """Refuse the indices when NRLMSIS's temperature for them is outside :data:`MSIS_TEMPERATURE_RANGE_K`."""
    low, high = MSIS_TEMPERATURE_RANGE_K
    if not low <= temperature_K <= high:  # NaN too
        raise InputError(
            f"NRLMSIS gives {temperature_K:.3g} K for f107 {f107:g}, f107a {f107a:g}, ap {ap:g}: indices "
            "outside its fit (it runs away where F10.7a is far above F10.7, or both are near 0)",
            hint="give the indices of real conditions, F10.7a near F10.7, e.g. f107 150 and f107a 150",
            parameters=("f107", "f107a", "ap"),
        )


def parse_time(time: str | datetime | date | np.datetime64) -> datetime:
    """A UTC time (timezone-aware) from an ISO 8601 string, a datetime (naive = UTC), a date or datetime64.

    Parameters
    ----------
    time : str, datetime, date or numpy.datetime64
        The time. A string is ISO 8601, UTC unless it carries an offset (a trailing ``Z`` is UTC); a
        naive datetime or a date is taken as UTC.

    Returns
    -------
    datetime
        The time in UTC, timezone-aware.

    Raises
    ------
    InputError
        A string that does not parse, a NaT, or a year outside 1958 to 2100.

    Examples
    --------
    >>> parse_time("2024-01-01T12:00:00+02:00")
    datetime.datetime(2024, 1, 1, 10, 0, tzinfo=datetime.timezone.utc)
    >>> parse_time("1900-01-01")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: time year 1900 is outside 1958-2100: ...
    """
    if isinstance(time, np.datetime64):
        if np.isnat(time):
            raise InputError(
                "time is NaT",
                hint="give an ISO 8601 UTC time such as 2024-01-01T00:00:00Z",
                parameters=("time",),
            )
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
                f"time '{text}' is not an ISO 8601 date",
                hint="e.g. 2024-01-01 or 2024-01-01T12:00:00Z (UTC unless an offset is given)",
                parameters=("time",),
            ) from None
    when = when.replace(tzinfo=timezone.utc) if when.tzinfo is None else when.astimezone(timezone.utc)
    low, high = YEAR_RANGE
    if not low <= when.year <= high:
        raise InputError(
            f"time year {when.year} is outside {low}-{high}: NRLMSIS is fitted to space-age data (since "
            "1958) and has no long-term trend, so a date outside that span is taken as a mistake",
            hint="give a UTC date between 1958 and 2100",
            parameters=("time",),
        )
    return when


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
    raise InputError(f"version {version} is not one of 2.1, 2.0, 0 (NRLMSISE-00)", parameters=("version",))
