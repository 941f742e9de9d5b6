"""Eclipse by the Earth: the share of the solar disc a spacecraft sees, 0 (umbra) to 1 (full Sun).

``conical`` (Montenbruck & Gill, *Satellite Orbits*, sec. 3.4.2): the Sun and the Earth are discs of
apparent radii ``a = asin(R_sun / |s - r|)`` and ``b = asin(R_earth / |r|)`` whose centres are ``c`` apart
as seen from the spacecraft; the visible share is one minus the overlap of the two discs over the Sun's
(flat discs: the exact area of the lens between two circles). ``cylindrical``: the Earth's shadow is a
cylinder of radius ``R_earth`` behind it along the Sun line, no penumbra. ``none``: always 1.
The Earth is a sphere of radius 6378.137 km (its equatorial radius); refraction and the atmosphere's
own shadow are left out.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS
from sunwind.forces.orbit.sun import SUN_RADIUS_M
from sunwind.geometry.errors import InputError

#: Eclipse models.
ECLIPSE_MODELS = ("conical", "cylindrical", "none")


def solar_fraction(
    position_m: NDArray[np.float64], sun_m: NDArray[np.float64], model: str = "conical"
) -> NDArray[np.float64]:
    """Visible share of the solar disc (n,) at spacecraft positions ``position_m`` (n, 3) with the Sun
    at ``sun_m`` (n, 3), both geocentric [m] in one inertial frame."""
    if model not in ECLIPSE_MODELS:
        raise InputError(
            f"eclipse model {model!r} is not one of {', '.join(ECLIPSE_MODELS)}", parameters=("eclipse",)
        )
    r = np.atleast_2d(np.asarray(position_m, dtype=float))
    s = np.atleast_2d(np.asarray(sun_m, dtype=float))
    if model == "none":
        return np.ones(len(r))
    if model == "cylindrical":
        u = s / np.linalg.norm(s, axis=1, keepdims=True)
        along = np.einsum("ij,ij->i", r, u)
        off_axis = np.linalg.norm(r - along[:, None] * u, axis=1)
        return np.where((along < 0) & (off_axis < EARTH_RADIUS), 0.0, 1.0)
    to_sun = s - r
    d_sun, d_earth = np.linalg.norm(to_sun, axis=1), np.linalg.norm(r, axis=1)
    a = np.arcsin(np.minimum(1.0, SUN_RADIUS_M / d_sun))
    b = np.arcsin(np.minimum(1.0, EARTH_RADIUS / d_earth))
    cos_c = -np.einsum("ij,ij->i", r, to_sun) / (d_earth * d_sun)
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
