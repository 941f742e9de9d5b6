"""Knocke's zonal, seasonal Earth albedo and infrared emissivity (Knocke, Ries & Tapley 1988, "Earth
radiation pressure effects on satellites", AIAA 88-4292).

Both are second-degree zonal expansions in the sine of the latitude ``phi`` with an annual first-degree
term::

    a(phi, t) = a0 + a1(t) P1(sin phi) + a2 P2(sin phi),   a1(t) = c0 + c1 cos w(t - t0) + c2 sin w(t - t0)
    e(phi, t) = e0 + e1(t) P1(sin phi) + e2 P2(sin phi),   e1(t) = k0 + k1 cos w(t - t0) + k2 sin w(t - t0)

with ``P1(x) = x``, ``P2(x) = (3 x^2 - 1) / 2``, ``w = 2 pi / 365.25 d`` and ``t0`` = 1981 December 22,
0h (JD 2444960.5), the northern winter solstice: at ``t0`` the northern hemisphere is the brighter
(snow and ice) and the colder (lower emissivity), half a year later the southern. The coefficients are
:data:`ALBEDO` (a0, c0, c1, c2, a2 = 0.34, 0, 0.10, 0, 0.29) and :data:`EMISSIVITY` (e0, k0, k1, k2, e2
= 0.68, 0, -0.07, 0, -0.18). Since P1 and P2 average to zero over the sphere, the area-weighted global
means are a0 and e0 at every instant.

Coefficients, period and epoch as implemented, identically, by Orekit (CS-SI/Orekit,
``src/main/java/org/orekit/forces/radiation/KnockeRediffusedForceModel.java``: ``A0 C0 C1 C2 A2``,
``E0 K0 K1 K2 E2``, a Julian year, 1981-12-22 0h UTC), Tudat (tudat-team/tudatpy,
``src/simulation/environment_setup/createSurfacePropertyDistribution.cpp``: ``albedo_knocke``,
``emissivity_knocke``, ``JULIAN_YEAR_IN_DAYS``, "1981-12-22 00:00:00 UTC") and PATRIUS (CNES/patrius,
``fr/cnes/sirius/patrius/forces/radiation/KnockeRiesModel.java``: ``REFDAY`` = 1950-01-01 TT + 11678
days = JD 2444960.5).

Conventions of a surface element, as in Orekit's ``computeElementaryFlux`` (after Knocke et al.): the
albedo is a Lambertian (diffuse) reflectance, so a sunlit element with the Sun at zenith angle
``theta_s`` leaves with exitance ``a S cos(theta_s)`` (radiance ``a S cos(theta_s) / pi``), and none at
night; the emissivity scales the Earth's mean thermal emission, a Lambertian exitance ``e S / 4`` by
day and by night, ``S`` the solar flux at the Earth (``S / 4``: the solar power intercepted by the disc
spread over the sphere).

Time: the Julian date is taken in TT. Orekit and Tudat put ``t0`` at 0h UTC, PATRIUS at 0h TT: the 52 s
between them (TT - UTC = 52.184 s in 1981) move the seasonal phase by 1.0e-5 rad and ``a``, ``e`` by
1.0e-6 at most, so TT, UTC or UT1 are alike at this model's precision (its coefficients are given to 0.01).

Latitude: geocentric, the angle between the element's radius vector and the equator (the model lives on
a sphere; Orekit evaluates it on a sphere, PATRIUS documents geocentric latitude).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: The reference epoch ``t0`` of the seasonal term, 1981 December 22, 0h [Julian date, TT].
REFERENCE_EPOCH_JD = 2444960.5
#: The period of the seasonal term, a Julian year [days].
YEAR_DAYS = 365.25


class ZonalSeasonal(NamedTuple):
    """Coefficients of a second-degree zonal expansion with an annual first-degree term.

    The quantity is ``mean + (p1 + p1_cos cos w(t - t0) + p1_sin sin w(t - t0)) P1(sin phi) +
    p2 P2(sin phi)``, ``w = 2 pi / YEAR_DAYS`` and ``t0 = REFERENCE_EPOCH_JD``
    (:func:`zonal_seasonal`).

    Parameters
    ----------
    mean : float
        The global mean, the degree-0 term [-].
    p1 : float
        Constant part of the degree-1 coefficient [-].
    p1_cos, p1_sin : float
        Annual cosine and sine parts of the degree-1 coefficient [-].
    p2 : float
        The degree-2 coefficient [-].

    References
    ----------
    .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
       satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

    Examples
    --------
    >>> ALBEDO.mean, ALBEDO.p1_cos, ALBEDO.p2
    (0.34, 0.1, 0.29)
    >>> ZonalSeasonal(mean=0.3, p1=0.0, p1_cos=0.0, p1_sin=0.0, p2=0.0).mean
    0.3
    """

    mean: float
    p1: float
    p1_cos: float
    p1_sin: float
    p2: float


#: Knocke's albedo: a0, c0, c1, c2, a2.
ALBEDO = ZonalSeasonal(mean=0.34, p1=0.0, p1_cos=0.10, p1_sin=0.0, p2=0.29)
#: Knocke's infrared emissivity: e0, k0, k1, k2, e2.
EMISSIVITY = ZonalSeasonal(mean=0.68, p1=0.0, p1_cos=-0.07, p1_sin=0.0, p2=-0.18)


def zonal_seasonal(
    coefficients: ZonalSeasonal, latitude_rad: ArrayLike, julian_date_tt: float
) -> NDArray[np.float64]:
    """Evaluate a :class:`ZonalSeasonal` expansion at given latitudes and date.

    Parameters
    ----------
    coefficients : ZonalSeasonal
        The expansion, e.g. :data:`ALBEDO` or :data:`EMISSIVITY`.
    latitude_rad : array_like of float
        Geocentric latitudes [rad].
    julian_date_tt : float or array_like of float
        Julian date in TT [days], broadcasting with ``latitude_rad``.

    Returns
    -------
    ndarray of float64
        The expansion at each latitude and date, of the broadcast shape [-].

    References
    ----------
    .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
       satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

    Examples
    --------
    Half a year after the northern winter solstice the southern pole is the brighter:

    >>> import numpy as np
    >>> poles = np.radians([-90.0, 90.0])
    >>> zonal_seasonal(ALBEDO, poles, REFERENCE_EPOCH_JD).round(3)
    array([0.53, 0.73])
    >>> zonal_seasonal(ALBEDO, poles, REFERENCE_EPOCH_JD + YEAR_DAYS / 2).round(3)
    array([0.73, 0.53])
    """
    phase = 2.0 * np.pi * (np.asarray(julian_date_tt, dtype=float) - REFERENCE_EPOCH_JD) / YEAR_DAYS
    first = coefficients.p1 + coefficients.p1_cos * np.cos(phase) + coefficients.p1_sin * np.sin(phase)
    x = np.sin(np.asarray(latitude_rad, dtype=float))
    return np.asarray(coefficients.mean + first * x + coefficients.p2 * (1.5 * x * x - 0.5))


def knocke_albedo(latitude_rad: NDArray, julian_date_tt: float) -> NDArray:
    """The Earth albedo of Knocke's model, a Lambertian reflectance in [0, 1].

    Parameters
    ----------
    latitude_rad : array_like of float
        Geocentric latitudes [rad].
    julian_date_tt : float or array_like of float
        Julian date in TT [days], broadcasting with ``latitude_rad``.

    Returns
    -------
    ndarray of float64
        The albedo at each latitude and date [-]: a sunlit element leaves with exitance
        ``a S cos(theta_s)``.

    References
    ----------
    .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
       satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

    Examples
    --------
    >>> import numpy as np
    >>> knocke_albedo(np.radians([-90.0, 0.0, 90.0]), REFERENCE_EPOCH_JD).round(3)
    array([0.53 , 0.195, 0.73 ])
    """
    return zonal_seasonal(ALBEDO, latitude_rad, julian_date_tt)


def knocke_emissivity(latitude_rad: NDArray, julian_date_tt: float) -> NDArray:
    """The Earth infrared emissivity of Knocke's model, in [0, 1].

    Parameters
    ----------
    latitude_rad : array_like of float
        Geocentric latitudes [rad].
    julian_date_tt : float or array_like of float
        Julian date in TT [days], broadcasting with ``latitude_rad``.

    Returns
    -------
    ndarray of float64
        The emissivity at each latitude and date [-]: the element emits ``e S / 4`` as a Lambertian
        exitance, day and night.

    References
    ----------
    .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
       satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

    Examples
    --------
    >>> import numpy as np
    >>> knocke_emissivity(np.radians([-90.0, 0.0, 90.0]), REFERENCE_EPOCH_JD).round(3)
    array([0.57, 0.77, 0.43])
    """
    return zonal_seasonal(EMISSIVITY, latitude_rad, julian_date_tt)
