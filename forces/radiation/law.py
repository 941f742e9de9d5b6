"""The solar-radiation-pressure force law on a flat lit surface, eqs. (1)-(4) of the paper (METHOD.md
"Direct solar pressure").

Notes
-----
The paper uses inner normals ``n = -n_out``; here every normal is the outward normal ``n_out`` of the
lit side, and the Sun vector ``u_sun`` points from the spacecraft to the Sun (photons travel along
``s = -u_sun``). With ``rho_s = rho beta`` and ``rho_d = rho (1 - beta)`` the force on a lit area ``A``
at incidence ``cos(theta) = n_out . u_sun > 0`` is

    F = -P A cos(theta) [ (1 - sigma - rho_s) u_sun + (2 rho_s cos(theta) + (2/3) rho_d) n_out ]

which is eq. (4). Eq. (2) as printed has the opposite sign (it is the momentum the specular beam carries
away), and eq. (5) misses a ``cos(theta)`` on ``sigma``; eq. (4) is right and is what is used.
The transmitted share ``sigma`` passes through without changing its momentum.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError

#: Speed of light in vacuum [m/s].
SPEED_OF_LIGHT = 299_792_458.0
#: Total solar irradiance at 1 au [W/m^2] (IAU 2015 Resolution B3 nominal value).
SOLAR_FLUX_1AU = 1361.0
#: The Sun's radius [au] (IAU 2015 nominal 695 700 km over the astronomical unit, 149 597 870.7 km):
#: the closest distance from the Sun accepted.
SUN_RADIUS_AU = 695_700.0 / 149_597_870.7
#: Solar flux at the photosphere [W/m^2] (:data:`SOLAR_FLUX_1AU` at :data:`SUN_RADIUS_AU`, 6.29e7).
PHOTOSPHERE_FLUX = SOLAR_FLUX_1AU / SUN_RADIUS_AU**2
#: The largest flux accepted [W/m^2]: above the photosphere's, so that a flux of c (a pressure of
#: 1 Pa on an absorber, the unit the closed forms use) is taken.
MAX_FLUX = 1e9
#: Lambertian momentum factor ``D(f)`` of the paper: (1/pi) * integral of cos^2 over the hemisphere.
LAMBERT_FACTOR = 2.0 / 3.0


def solar_flux(flux_W_m2: float | None = None, distance_au: float | None = None) -> float:
    """Solar flux [W/m^2] from an explicit value or a distance from the Sun [au] (default 1 au).

    Parameters
    ----------
    flux_W_m2 : float, optional
        Flux [W/m^2], finite, >= 0 and at most :data:`MAX_FLUX`.
    distance_au : float, optional
        Distance from the Sun [au], at least :data:`SUN_RADIUS_AU`; the flux is
        ``SOLAR_FLUX_1AU / distance_au**2``.

    Returns
    -------
    float
        The flux [W/m^2]: ``flux_W_m2`` as given, else from ``distance_au``, else :data:`SOLAR_FLUX_1AU`.

    Raises
    ------
    InputError
        Both given, a value that is not a finite positive number, a flux above :data:`MAX_FLUX` or a
        distance inside the Sun (below :data:`SUN_RADIUS_AU`).

    Examples
    --------
    >>> solar_flux()
    1361.0
    >>> solar_flux(distance_au=2.0)
    340.25
    >>> solar_flux(flux_W_m2=1000.0)
    1000.0
    """
    if flux_W_m2 is not None and distance_au is not None:
        raise InputError("give flux_W_m2 or distance_au, not both", parameters=("flux_W_m2", "distance_au"))
    if flux_W_m2 is not None:
        if not math.isfinite(flux_W_m2) or flux_W_m2 < 0:
            raise InputError(
                f"flux_W_m2 {flux_W_m2} is not a finite non-negative number",
                hint="e.g. 1361 (1 au)",
                parameters=("flux_W_m2",),
            )
        if flux_W_m2 > MAX_FLUX:
            raise InputError(
                f"flux_W_m2 {flux_W_m2:g} W/m^2 is above {MAX_FLUX:g} W/m^2, 16 times the flux at the "
                f"Sun's photosphere ({PHOTOSPHERE_FLUX:.3g})",
                hint=f"give flux_W_m2 of at most {MAX_FLUX:g}, e.g. 1361 (1 au)",
                parameters=("flux_W_m2",),
            )
        return float(flux_W_m2)
    if distance_au is not None:
        if not math.isfinite(distance_au) or distance_au <= 0:
            raise InputError(
                f"distance_au {distance_au} is not a finite positive number",
                hint="e.g. 1.0",
                parameters=("distance_au",),
            )
        if distance_au < SUN_RADIUS_AU:
            raise InputError(
                f"distance_au {distance_au:g} au is inside the Sun, whose radius is {SUN_RADIUS_AU:.3g} au",
                hint="give distance_au beyond the Sun's radius, e.g. 1.0 (Parker Solar Probe comes to 0.046)",
                parameters=("distance_au",),
            )
        return SOLAR_FLUX_1AU / distance_au**2
    return SOLAR_FLUX_1AU


def radiation_pressure(flux_W_m2: float) -> float:
    """Radiation pressure ``P = Phi / c`` [Pa] of a flux fully absorbed at normal incidence.

    Parameters
    ----------
    flux_W_m2 : float
        Flux [W/m^2].

    Returns
    -------
    float
        ``P`` [Pa].

    Examples
    --------
    >>> f"{radiation_pressure(1361.0):.4e}"
    '4.5398e-06'
    """
    return flux_W_m2 / SPEED_OF_LIGHT


def surface_forces(
    normals: NDArray[np.float64],
    lit_areas: NDArray[np.float64],
    cos_theta: NDArray[np.float64],
    rho: NDArray[np.float64],
    beta: NDArray[np.float64],
    sigma: NDArray[np.float64],
    sun_vector: NDArray[np.float64],
    pressure_Pa: float,
) -> NDArray[np.float64]:
    """Direct SRP force on flat lit surfaces, eq. (4).

    Parameters
    ----------
    normals : (n, 3) float64
        Outward unit normals ``n_out`` of the lit sides, body frame.
    lit_areas : (n,) float64
        Lit area of each side [m^2].
    cos_theta : (n,) float64
        ``n_out . u_sun``, positive on lit sides.
    rho, beta, sigma : (n,) float64
        Reflectivity, specular share of the reflected light, transmissivity [-].
    sun_vector : (3,) float64
        Unit vector from the spacecraft toward the Sun, body frame.
    pressure_Pa : float
        ``P = Phi / c`` [Pa].

    Returns
    -------
    (n, 3) float64
        Force on each surface [N], body frame.

    References
    ----------
    .. [1] Shmatov, S. I., Mordvinkin, A. S. (2013). "Joint computation of the aerodynamic and radiation
       force effects on spacecraft" (program AIRSOL); eq. (4), with the sign conventions of METHOD.md
       "Direct solar pressure".

    Examples
    --------
    A black plate and a perfect mirror of 1 m^2, facing the Sun, under ``P = 1`` Pa:

    >>> import numpy as np
    >>> normals = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
    >>> one, zero = np.ones(2), np.zeros(2)
    >>> rho = np.array([0.0, 1.0])
    >>> surface_forces(normals, one, one, rho, one, zero, np.array([0.0, 0.0, 1.0]), 1.0) + 0.0
    array([[ 0.,  0., -1.],
           [ 0.,  0., -2.]])
    """
    rho_s = rho * beta
    rho_d = rho - rho_s
    scale = -pressure_Pa * lit_areas * cos_theta
    along_sun = scale * (1.0 - sigma - rho_s)
    along_normal = scale * (2.0 * rho_s * cos_theta + LAMBERT_FACTOR * rho_d)
    return along_sun[:, None] * sun_vector + along_normal[:, None] * normals
