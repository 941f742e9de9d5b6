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
    """Geocentric position of the Sun [m], GCRF, (n, 3), at ``seconds`` [s] after ``epoch``
    (TDB taken as TT: they differ by under 2 ms)."""
    heliocentric, _ = erfa.epv00(*epoch.tt(np.atleast_1d(np.asarray(seconds, dtype=float))))
    return -heliocentric["p"] * AU_M


#: Mean radius of the Moon [m] (IAU).
MOON_RADIUS_M = 1.7374e6


def moon_position(epoch: Epoch, seconds: NDArray[np.float64]) -> NDArray[np.float64]:
    """Geocentric position of the Moon [m], GCRF, (n, 3), at ``seconds`` [s] after ``epoch``."""
    return erfa.moon98(*epoch.tt(np.atleast_1d(np.asarray(seconds, dtype=float))))["p"] * AU_M


def fixed_sun(direction: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """The Sun at 1 au along ``direction`` (GCRF, normalised here) at every one of ``n`` steps [m]."""
    return np.tile(unit_vector(direction, "sun_eci") * AU_M, (n, 1))  # hypot: no overflow at 1e308
