"""The Sun seen from the Earth's centre, from ERFA's built-in ephemeris (``epv00``, the analytic series
astropy uses offline: Earth's heliocentric position to a few km, its direction to well under an
arcsecond), in GCRF [m]; and the Moon, which can eclipse it (ERFA's ``moon98``, Meeus's series: about
10 arcsec, some 20 km at the Moon's distance).

The geometric direction is used (no light time or aberration, 20 arcsec at most); the solar flux at
the spacecraft scales with its own distance to the Sun, ``(1 au / d)^2``.
"""

from __future__ import annotations

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.planet.shadow import AU_M, SUN_RADIUS_M
from sunwind.geometry.directions import unit_vector

__all__ = ["AU_M", "MOON_RADIUS_M", "SUN_RADIUS_M", "fixed_sun", "moon_position", "sun_position"]


def sun_position(epoch: Epoch, seconds: NDArray[np.float64]) -> NDArray[np.float64]:
    """Geocentric position of the Sun [m], GCRF, at times after an epoch.

    TDB is taken as TT (they differ by under 2 ms). The geometric position is returned: no light time
    and no aberration.

    Parameters
    ----------
    epoch : Epoch
        The start of the times.
    seconds : float or array_like of float, shape (n,)
        Elapsed SI seconds from ``epoch``.

    Returns
    -------
    ndarray of float64, shape (n, 3)
        The Sun's position relative to the Earth's centre [m], GCRF axes.

    References
    ----------
    ERFA's ``epv00`` (IAU SOFA, METHOD.md [48]): the Earth's heliocentric position, here negated.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T03:06:00Z")  # the March equinox
    >>> sun = sw.orbit.sun_position(epoch, [0.0, 86400.0])
    >>> sun.shape
    (2, 3)
    >>> (np.linalg.norm(sun, axis=1) / sw.orbit.AU_M).round(3)  # distance in au, near March's
    array([0.996, 0.996])
    >>> (sun[0] / np.linalg.norm(sun[0])).round(3)  # near +x, off by the precession since J2000
    array([ 1.   , -0.005, -0.002])
    """
    heliocentric, _ = erfa.epv00(*epoch.tt(np.atleast_1d(np.asarray(seconds, dtype=float))))
    return -heliocentric["p"] * AU_M


#: Mean radius of the Moon [m] (IAU).
MOON_RADIUS_M = 1.7374e6


def moon_position(epoch: Epoch, seconds: NDArray[np.float64]) -> NDArray[np.float64]:
    """Geocentric position of the Moon [m], GCRF, at times after an epoch.

    Parameters
    ----------
    epoch : Epoch
        The start of the times.
    seconds : float or array_like of float, shape (n,)
        Elapsed SI seconds from ``epoch``.

    Returns
    -------
    ndarray of float64, shape (n, 3)
        The Moon's position relative to the Earth's centre [m], GCRF axes (about 10 arcsec accuracy).

    References
    ----------
    ERFA's ``moon98`` (IAU SOFA, METHOD.md [48]), the series of Meeus, *Astronomical Algorithms* (METHOD.md
    [52]).

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.orbit.clock import Epoch
    >>> from sunwind.forces.orbit.sun import moon_position
    >>> moon = moon_position(Epoch.of("2024-03-20T03:06:00Z"), [0.0])
    >>> round(float(np.linalg.norm(moon)) / 1e6)  # thousand km
    401
    """
    return erfa.moon98(*epoch.tt(np.atleast_1d(np.asarray(seconds, dtype=float))))["p"] * AU_M


def fixed_sun(direction: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """The Sun at 1 au along a fixed direction at every step.

    Parameters
    ----------
    direction : array_like of float, shape (3,)
        Direction from the Earth's centre to the Sun, GCRF; any length, normalised here.
    n : int
        Number of steps.

    Returns
    -------
    ndarray of float64, shape (n, 3)
        The Sun's position [m], the same row ``n`` times.

    Raises
    ------
    InputError
        A zero or non-finite ``direction``.

    Examples
    --------
    >>> from sunwind.forces.orbit.sun import AU_M, fixed_sun
    >>> (fixed_sun([0.0, 0.0, 2.0], 2) / AU_M).tolist()
    [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]
    """
    return np.tile(unit_vector(direction, "sun_eci") * AU_M, (n, 1))  # hypot: no overflow at 1e308
