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
    """Visible share of the solar disc at spacecraft positions, 0 (umbra) to 1 (full Sun).

    The Earth (a sphere of its equatorial radius) and, if given, the Moon occult the Sun; their two
    shares multiply.

    Parameters
    ----------
    position_m : array_like of float, shape (n, 3)
        Spacecraft positions relative to the Earth's centre [m].
    sun_m : array_like of float, shape (n, 3)
        Sun positions relative to the Earth's centre [m], same inertial frame.
    model : {"conical", "cylindrical", "none"}
        Shadow model: ``"conical"`` with the penumbra (overlap of the apparent discs), ``"cylindrical"``
        (in or out of the shadow cylinder), ``"none"`` (always full Sun).
    moon_m : array_like of float, shape (n, 3), optional
        Moon positions relative to the Earth's centre [m]; ``None`` leaves the Moon out.

    Returns
    -------
    ndarray of float64, shape (n,)
        The share of the solar disc in view.

    Raises
    ------
    InputError
        ``model`` is not one of :data:`ECLIPSE_MODELS`.

    References
    ----------
    .. [1] Montenbruck, O., Gill, E. (2000). *Satellite Orbits: Models, Methods and Applications*,
       sec. 3.4.2 (the conical shadow model). Springer.

    Examples
    --------
    A spacecraft at 7000 km on the sunlit side, behind the Earth, and in the penumbra just past the
    Earth's limb:

    >>> import sunwind as sw
    >>> sun = [[sw.orbit.AU_M, 0.0, 0.0]] * 3
    >>> here = [[7.0e6, 0.0, 0.0], [-7.0e6, 0.0, 0.0], [-7.0e6, 6.38e6, 0.0]]
    >>> sw.orbit.solar_fraction(here, sun).round(2)
    array([1.  , 0.  , 0.53])
    >>> sw.orbit.solar_fraction(here, sun, "cylindrical").tolist()
    [1.0, 0.0, 1.0]
    """
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
