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
    """Visible share of the Sun (1 au away along ``sun_vector``) from a spacecraft ``altitude_km`` above a
    sphere of ``radius_m`` whose centre lies along ``nadir`` (both directions in one frame)."""
    position = -(radius_m + altitude_km * 1e3) * unit_vector(nadir, "nadir")
    sun = position + AU_M * unit_vector(sun_vector, "sun_vector")
    return float(sphere_visible(position, sun, radius_m, model)[0])


def sphere_visible(
    position_m: NDArray[np.float64], sun_m: NDArray[np.float64], radius_m: float, model: str = "conical"
) -> NDArray[np.float64]:
    """Visible share of the solar disc (n,) at ``position_m`` (n, 3) with the Sun at ``sun_m`` (n, 3),
    behind a sphere of ``radius_m`` at the origin (any planet), by ``model``."""
    r = np.atleast_2d(np.asarray(position_m, dtype=float))
    if model == "none":
        return np.ones(len(r))
    return unblocked(r, np.atleast_2d(np.asarray(sun_m, dtype=float)), np.zeros_like(r), radius_m, model)


def unblocked(
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
