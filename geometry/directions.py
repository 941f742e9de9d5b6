"""Body-frame directions: checked unit vectors and the azimuth/elevation convention (METHOD.md "Frames").

Azimuth ``az = atan2(d_y, d_x)`` is measured in the body x-y plane from +x toward +y; elevation
``el = asin(d_z)`` is positive toward +z.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from .errors import InputError


def unit_vector(vector: Sequence[float] | NDArray, name: str = "vector") -> NDArray[np.float64]:
    """``vector`` normalised to unit length.

    Raises
    ------
    InputError
        Not three finite numbers, or zero length.
    """
    v = np.asarray(vector, dtype=np.float64).reshape(-1)
    if v.shape != (3,) or not np.isfinite(v).all():
        raise InputError(f"{name} {_fmt(v)} must be three finite numbers", hint="e.g. 1 0 0")
    norm = float(np.linalg.norm(v))
    if norm == 0.0 or not math.isfinite(norm):
        raise InputError(f"{name} {_fmt(v)} has zero length", hint="give a direction, e.g. 1 0 0")
    return v / norm


def finite_point(point: Sequence[float] | NDArray, name: str) -> NDArray[np.float64]:
    """A point as three finite float64 coordinates [m].

    Raises
    ------
    InputError
        Not three finite numbers.
    """
    p = np.asarray(point, dtype=np.float64).reshape(-1)
    if p.shape != (3,) or not np.isfinite(p).all():
        raise InputError(f"{name} {_fmt(p)} must be three finite numbers [m]", hint=f"e.g. {name} 0 0 0.1")
    return p


def azel_to_vector(azimuth_deg: float, elevation_deg: float, name: str = "direction") -> NDArray[np.float64]:
    """Unit vector of an azimuth and elevation [deg], body frame.

    Raises
    ------
    InputError
        Non-finite angles, or elevation outside [-90, 90].
    """
    if not (math.isfinite(azimuth_deg) and math.isfinite(elevation_deg)):
        raise InputError(f"{name} azimuth/elevation {azimuth_deg} {elevation_deg} must be finite numbers")
    if abs(elevation_deg) > 90:
        raise InputError(f"{name} elevation {elevation_deg} deg is outside [-90, 90]")
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


def vector_to_azel(direction: Sequence[float] | NDArray) -> tuple[float, float]:
    """Azimuth and elevation [deg] of a unit vector."""
    x, y, z = np.asarray(direction, dtype=np.float64)
    return math.degrees(math.atan2(y, x)), math.degrees(math.asin(max(-1.0, min(1.0, z))))


def _fmt(v: NDArray) -> str:
    return "(" + " ".join(f"{x:g}" for x in v) + ")"
