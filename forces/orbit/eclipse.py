"""Eclipse by the Earth: the share of the solar disc a spacecraft sees, 0 (umbra) to 1 (full Sun),
by the shadow models of :mod:`sunwind.forces.planet.shadow` (``conical`` with the penumbra,
``cylindrical``, ``none``). The Earth is a sphere of radius 6378.137 km (its equatorial radius);
refraction and the atmosphere's own shadow are left out. The Moon (radius 1737.4 km), when asked for,
occults by the same rules; the two shares multiply (exact unless both bodies cover the Sun at once,
which a near-Earth orbit sees only in a lunar eclipse).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS
from sunwind.forces.orbit.sun import MOON_RADIUS_M
from sunwind.forces.planet.shadow import ECLIPSE_MODELS, unblocked
from sunwind.geometry.errors import InputError


def solar_fraction(
    position_m: NDArray[np.float64],
    sun_m: NDArray[np.float64],
    model: str = "conical",
    moon_m: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Visible share of the solar disc (n,) at spacecraft positions ``position_m`` (n, 3) with the Sun
    at ``sun_m`` (n, 3) and, if given, the Moon at ``moon_m`` (n, 3), all geocentric [m] in one
    inertial frame."""
    if model not in ECLIPSE_MODELS:
        raise InputError(
            f"eclipse model {model!r} is not one of {', '.join(ECLIPSE_MODELS)}", parameters=("eclipse",)
        )
    r = np.atleast_2d(np.asarray(position_m, dtype=float))
    s = np.atleast_2d(np.asarray(sun_m, dtype=float))
    if model == "none":
        return np.ones(len(r))
    visible = unblocked(r, s, np.zeros_like(r), EARTH_RADIUS, model)
    if moon_m is not None:
        visible *= unblocked(r, s, np.atleast_2d(moon_m), MOON_RADIUS_M, model)
    return visible
