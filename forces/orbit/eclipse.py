"""Eclipse by the Earth: the share of the solar disc a spacecraft sees, 0 (umbra) to 1 (full Sun).

``conical`` (Montenbruck & Gill, *Satellite Orbits*, sec. 3.4.2): the Sun and the Earth are discs of
apparent radii ``a = asin(R_sun / |s - r|)`` and ``b = asin(R_earth / |r|)`` whose centres are ``c`` apart
as seen from the spacecraft; the visible share is one minus the overlap of the two discs over the Sun's
(flat discs: the exact area of the lens between two circles). ``cylindrical``: the Earth's shadow is a
cylinder of radius ``R_earth`` behind it along the Sun line, no penumbra. ``none``: always 1.
The Earth is a sphere of radius 6378.137 km (its equatorial radius); refraction and the atmosphere's
own shadow are left out. The Moon (radius 1737.4 km), when asked for, occults by the same rules; the
two shares multiply (exact unless both bodies cover the Sun at once, which a near-Earth orbit sees
only in a lunar eclipse).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS
from sunwind.forces.orbit.sun import MOON_RADIUS_M, SUN_RADIUS_M
from sunwind.geometry.errors import InputError

#: Eclipse models.
ECLIPSE_MODELS = ("conical", "cylindrical", "none")


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
    visible = _unblocked(r, s, np.zeros_like(r), EARTH_RADIUS, model)
    if moon_m is not None:
        visible *= _unblocked(r, s, np.atleast_2d(moon_m), MOON_RADIUS_M, model)
    return visible


def sphere_visible(
    position_m: NDArray[np.float64], sun_m: NDArray[np.float64], radius_m: float, model: str = "conical"
) -> NDArray[np.float64]:
    """Visible share of the solar disc (n,) at ``position_m`` (n, 3) with the Sun at ``sun_m`` (n, 3),
    behind a sphere of ``radius_m`` at the origin (any planet), by ``model``."""
    r = np.atleast_2d(np.asarray(position_m, dtype=float))
    if model == "none":
        return np.ones(len(r))
    return _unblocked(r, np.atleast_2d(np.asarray(sun_m, dtype=float)), np.zeros_like(r), radius_m, model)


def _unblocked(
    r: NDArray[np.float64], s: NDArray[np.float64], centre: NDArray[np.float64], radius: float, model: str
) -> NDArray[np.float64]:
    """Share of the Sun a sphere of ``radius`` at ``centre`` leaves visible from ``r``."""
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
