"""The planet's shadow on the Sun: the share of the solar disc a spacecraft sees past a spherical body,
0 (umbra) to 1 (full Sun).

``conical`` (Montenbruck & Gill, *Satellite Orbits*, sec. 3.4.2): the Sun and the body are discs of
apparent radii ``a = asin(R_sun / |s - r|)`` and ``b = asin(R / |c - r|)`` whose centres are ``c`` apart as
seen from the spacecraft; the visible share is one minus the overlap of the two discs over the Sun's
(flat discs: the exact area of the lens between two circles; a uniform solar disc). ``cylindrical``:
the body's shadow is a cylinder of radius ``R`` behind it along the Sun line, no penumbra. ``none``:
always 1. Refraction and an atmosphere's own shadow are left out.
"""

from __future__ import annotations

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.directions import unit_vector

#: Shadow models.
ECLIPSE_MODELS = ("conical", "cylindrical", "none")
#: The astronomical unit [m] (IAU 2012).
AU_M = float(erfa.DAU)
#: Radius of the solar disc [m], as Montenbruck & Gill take it for shadows (sec. 3.4): 696 000 km.
SUN_RADIUS_M = 6.96e8


def sun_behind(
    nadir: NDArray[np.float64],
    altitude_km: float,
    sun_vector: NDArray[np.float64],
    radius_m: float,
    model: str,
) -> float:
    """The visible share of the Sun from a spacecraft above a spherical planet.

    The spacecraft is placed ``altitude_km`` above the sphere, whose centre lies along ``nadir``, and
    the Sun 1 au from it along ``sun_vector``; both directions are in one (any) frame.

    Parameters
    ----------
    nadir : (3,) float64
        Direction from the spacecraft to the planet's centre (need not be unit).
    altitude_km : float
        Height above the sphere [km].
    sun_vector : (3,) float64
        Direction from the spacecraft to the Sun (need not be unit).
    radius_m : float
        Radius of the sphere [m].
    model : str
        One of :data:`ECLIPSE_MODELS`: ``"conical"``, ``"cylindrical"`` or ``"none"``.

    Returns
    -------
    float
        The share of the solar disc in view, 0 (umbra) to 1 (full Sun).

    Raises
    ------
    InputError
        A zero or non-finite ``nadir`` or ``sun_vector``.

    References
    ----------
    .. [1] Montenbruck, O., Gill, E. (2000). *Satellite Orbits: Models, Methods and Applications*,
       sec. 3.4.2. Springer.

    Examples
    --------
    >>> import numpy as np
    >>> down = np.array([0.0, 0.0, -1.0])
    >>> sun_behind(down, 500.0, -down, 6_378_137.0, "conical")  # the Sun overhead
    1.0
    >>> sun_behind(down, 500.0, down, 6_378_137.0, "conical")  # behind the Earth
    0.0
    """
    position = -(radius_m + altitude_km * 1e3) * unit_vector(nadir, "nadir")
    sun = position + AU_M * unit_vector(sun_vector, "sun_vector")
    return float(sphere_visible(position, sun, radius_m, model)[0])


def sphere_visible(
    position_m: NDArray[np.float64], sun_m: NDArray[np.float64], radius_m: float, model: str = "conical"
) -> NDArray[np.float64]:
    """The visible share of the solar disc at points behind a sphere at the origin.

    Parameters
    ----------
    position_m : array_like of float, shape (n, 3) or (3,)
        Positions of the spacecraft relative to the sphere's centre [m].
    sun_m : array_like of float, shape (n, 3) or (3,)
        Positions of the Sun in the same frame [m].
    radius_m : float
        Radius of the sphere [m] (any planet).
    model : str, default "conical"
        One of :data:`ECLIPSE_MODELS`.

    Returns
    -------
    ndarray of float64, shape (n,)
        The share of the solar disc in view, 0 (umbra) to 1 (full Sun).

    References
    ----------
    .. [1] Montenbruck, O., Gill, E. (2000). *Satellite Orbits: Models, Methods and Applications*,
       sec. 3.4.2. Springer.

    Examples
    --------
    Through the Earth's penumbra, 500 km up, the Sun along -x:

    >>> import numpy as np
    >>> r, angle = 6_878_137.0, np.radians([60.0, 67.9, 68.0, 68.1, 75.0])
    >>> positions = r * np.stack([np.cos(angle), np.sin(angle), 0 * angle], axis=1)
    >>> sun = [-AU_M, 0.0, 0.0]
    >>> sphere_visible(positions, sun, 6_378_137.0).round(3)
    array([0.   , 0.221, 0.45 , 0.686, 1.   ])
    >>> sphere_visible(positions, sun, 6_378_137.0, "cylindrical")
    array([0., 0., 0., 1., 1.])
    """
    r = np.atleast_2d(np.asarray(position_m, dtype=float))
    if model == "none":
        return np.ones(len(r))
    return unblocked(r, np.atleast_2d(np.asarray(sun_m, dtype=float)), np.zeros_like(r), radius_m, model)


def unblocked(
    r: NDArray[np.float64], s: NDArray[np.float64], centre: NDArray[np.float64], radius: float, model: str
) -> NDArray[np.float64]:
    """The share of the Sun that a sphere anywhere leaves visible from each position.

    ``"cylindrical"`` tests whether the point lies in the sphere's shadow cylinder along the Sun line;
    any other model is ``"conical"``: the Sun's and the sphere's apparent discs and the area of their
    overlap.

    Parameters
    ----------
    r : ndarray of float64, shape (n, 3)
        Positions of the spacecraft [m].
    s : ndarray of float64, shape (n, 3)
        Positions of the Sun [m].
    centre : ndarray of float64, shape (n, 3)
        Centres of the occulting sphere [m].
    radius : float
        Radius of the sphere [m].
    model : str
        ``"conical"`` or ``"cylindrical"``.

    Returns
    -------
    ndarray of float64, shape (n,)
        The share of the solar disc in view, 0 to 1.

    References
    ----------
    .. [1] Montenbruck, O., Gill, E. (2000). *Satellite Orbits: Models, Methods and Applications*,
       sec. 3.4.2. Springer.

    Examples
    --------
    The Moon at its mean distance in front of the Sun is too small to hide it: an annular eclipse.

    >>> import numpy as np
    >>> here, sun = np.zeros((1, 3)), np.array([[AU_M, 0.0, 0.0]])
    >>> unblocked(here, sun, np.array([[3.844e8, 0.0, 0.0]]), 1.7374e6, "conical").round(3)
    array([0.056])
    """
    if model == "cylindrical":
        u = (s - centre) / np.linalg.norm(s - centre, axis=1, keepdims=True)
        relative = r - centre
        along = np.einsum("ij,ij->i", relative, u)
        off_axis = np.linalg.norm(relative - along[:, None] * u, axis=1)
        return np.where((along < 0) & (off_axis < radius), 0.0, 1.0)
    to_sun, to_body = s - r, centre - r
    d_sun, d_body = np.linalg.norm(to_sun, axis=1), np.linalg.norm(to_body, axis=1)
    a = np.arcsin(np.minimum(1.0, SUN_RADIUS_M / d_sun))
    b = np.arcsin(np.minimum(1.0, radius / d_body))
    cos_c = np.einsum("ij,ij->i", to_body, to_sun) / (d_body * d_sun)
    c = np.arccos(np.clip(cos_c, -1.0, 1.0))
    return _disc_visible(a, b, c)


def _disc_visible(a: NDArray, b: NDArray, c: NDArray) -> NDArray[np.float64]:
    """Share of a disc of radius ``a`` left uncovered by a disc of radius ``b`` whose centre is ``c``
    away (all angles [rad])."""
    visible = np.ones_like(c)
    covered_all = c <= b - a
    annular = (c <= a - b) & ~covered_all
    partial = (c < a + b) & ~covered_all & ~annular
    visible[covered_all] = 0.0
    visible[annular] = 1.0 - (b[annular] / a[annular]) ** 2
    ap, bp, cp = a[partial], b[partial], c[partial]
    x = (cp**2 + ap**2 - bp**2) / (2 * cp)
    y = np.sqrt(np.maximum(ap**2 - x**2, 0.0))
    overlap = (
        ap**2 * np.arccos(np.clip(x / ap, -1, 1)) + bp**2 * np.arccos(np.clip((cp - x) / bp, -1, 1)) - cp * y
    )
    visible[partial] = 1.0 - overlap / (np.pi * ap**2)
    return visible
