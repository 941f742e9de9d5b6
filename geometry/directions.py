"""Body-frame directions: checked unit vectors and the azimuth/elevation convention (METHOD.md "Frames,
units and signs").

Azimuth ``az = atan2(d_y, d_x)`` is measured in the body x-y plane from +x toward +y; elevation
``el = asin(d_z)`` is positive toward +z.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError


def unit_vector(vector: Sequence[float] | NDArray, name: str = "vector") -> NDArray[np.float64]:
    """Normalise a vector to unit length.

    Parameters
    ----------
    vector : (3,) array_like of float
        Any non-zero vector.
    name : str
        The parameter that gave it, named in the error.

    Returns
    -------
    (3,) float64
        ``vector / |vector|``.

    Raises
    ------
    InputError
        Not three finite numbers, or zero length.

    Examples
    --------
    >>> unit_vector([3, 0, 4])
    array([0.6, 0. , 0.8])
    """
    v = np.asarray(vector, dtype=np.float64).reshape(-1)
    if v.shape != (3,) or not all(map(math.isfinite, v.tolist())):
        raise InputError(
            f"{name} {_fmt(v)} must be three finite numbers", hint="e.g. 1 0 0", parameters=(name,)
        )
    norm = math.hypot(*v.tolist())
    if norm == 0.0 or not math.isfinite(norm):
        raise InputError(
            f"{name} {_fmt(v)} has zero length", hint="give a direction, e.g. 1 0 0", parameters=(name,)
        )
    return v / norm


def unit_vectors(vectors: Sequence[Sequence[float]] | NDArray, name: str = "vector") -> NDArray[np.float64]:
    """Normalise one vector or a batch of vectors, row by row as :func:`unit_vector` does.

    Parameters
    ----------
    vectors : (3,) or (n, 3) array_like of float
        The vectors.
    name : str
        The parameter that gave them, named in the error.

    Returns
    -------
    (3,) or (n, 3) float64
        Unit vectors, in the shape given.

    Raises
    ------
    InputError
        Not of shape (3,) or (n, 3), or a row that :func:`unit_vector` refuses (named by its index).

    Examples
    --------
    >>> unit_vectors([[2, 0, 0], [0, 0, -5]])
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.]])
    """
    array = np.asarray(vectors, dtype=np.float64)
    if array.ndim == 1:
        return unit_vector(array, name)
    if array.ndim != 2 or array.shape[1] != 3:
        raise InputError(
            f"{name} of shape {array.shape} must be one vector (3,) or a batch (n, 3)", parameters=(name,)
        )
    return np.array([unit_vector(row, f"{name}[{k}]") for k, row in enumerate(array)]).reshape(-1, 3)


def finite_point(point: Sequence[float] | NDArray, name: str) -> NDArray[np.float64]:
    """Check a point: three finite float64 coordinates [m].

    Parameters
    ----------
    point : (3,) array_like of float
        The point [m].
    name : str
        The parameter that gave it, named in the error.

    Returns
    -------
    (3,) float64
        The point.

    Raises
    ------
    InputError
        Not three finite numbers.

    Examples
    --------
    >>> finite_point((0, 0, 0.1), "reference")
    array([0. , 0. , 0.1])
    """
    p = np.asarray(point, dtype=np.float64).reshape(-1)
    if p.shape != (3,) or not np.isfinite(p).all():
        raise InputError(
            f"{name} {_fmt(p)} must be three finite numbers [m]",
            hint=f"e.g. {name} 0 0 0.1",
            parameters=(name,),
        )
    return p


def azel_to_vector(azimuth_deg: float, elevation_deg: float, name: str = "direction") -> NDArray[np.float64]:
    """Turn an azimuth and elevation [deg] into a unit vector, body frame.

    Parameters
    ----------
    azimuth_deg : float
        Azimuth [deg] from +x toward +y, in [-360, 360].
    elevation_deg : float
        Elevation [deg] toward +z, in [-90, 90].
    name : str
        The parameter that gave them, named in the error.

    Returns
    -------
    (3,) float64
        The unit vector.

    Raises
    ------
    InputError
        Non-finite angles, azimuth outside [-360, 360] or elevation outside [-90, 90].

    Examples
    --------
    >>> azel_to_vector(90, 0)
    array([0., 1., 0.])
    >>> np.round(azel_to_vector(45, 30), 4)
    array([0.6124, 0.6124, 0.5   ])
    """
    azimuth, elevation = checked_azel(azimuth_deg, elevation_deg, name)
    return azel_to_vectors(np.array([azimuth]), np.array([elevation]))[0]


def checked_azel(azimuth_deg: float, elevation_deg: float, name: str = "direction") -> tuple[float, float]:
    """Check an azimuth and elevation [deg] and return them as floats.

    Parameters
    ----------
    azimuth_deg : float
        Azimuth [deg], finite and within [-360, 360].
    elevation_deg : float
        Elevation [deg], finite and within [-90, 90].
    name : str
        The parameter that gave them, named in the error.

    Returns
    -------
    azimuth, elevation : float
        The angles [deg].

    Raises
    ------
    InputError
        Non-finite angles, azimuth outside [-360, 360] or elevation outside [-90, 90].

    Examples
    --------
    >>> checked_azel(-60, 45)
    (-60.0, 45.0)
    """
    azimuth, elevation = float(azimuth_deg), float(elevation_deg)
    if not (math.isfinite(azimuth) and math.isfinite(elevation)):
        raise InputError(
            f"{name} azimuth/elevation {azimuth:g} {elevation:g} must be finite numbers", parameters=(name,)
        )
    if abs(azimuth) > 360:
        raise InputError(
            f"{name} azimuth {azimuth:g} deg is outside [-360, 360] (a turn either way of +x; far "
            "beyond it a float keeps no fraction of a turn)",
            hint="give the azimuth in degrees, e.g. -60 or 300",
            parameters=(name,),
        )
    if abs(elevation) > 90:
        raise InputError(f"{name} elevation {elevation:g} deg is outside [-90, 90]", parameters=(name,))
    return azimuth, elevation


def _cos_sin_deg(angle_deg: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Cosine and sine of angles [deg], exact (0, +-1) at whole multiples of 90 deg."""
    radians = np.radians(angle_deg)
    cos, sin = np.cos(radians), np.sin(radians)
    quarter = np.round(angle_deg / 90.0)
    exact = quarter * 90.0 == angle_deg
    turn = np.mod(quarter, 4).astype(np.int64)
    cos = np.where(exact, np.array([1.0, 0.0, -1.0, 0.0])[turn], cos)
    sin = np.where(exact, np.array([0.0, 1.0, 0.0, -1.0])[turn], sin)
    return cos, sin


def azel_to_vectors(azimuth_deg: NDArray, elevation_deg: NDArray) -> NDArray[np.float64]:
    """Turn azimuths and elevations [deg] (broadcast together) into unit vectors, body frame.

    Whole multiples of 90 deg are exact, so every azimuth at elevation +-90 gives the pole
    ``(0, 0, +-1)`` and azimuths -180 and 180 give the same vector: grid rows that are one direction
    give one answer. Angles are not checked here (see :func:`azel_to_vector`).

    Parameters
    ----------
    azimuth_deg : array_like of float
        Azimuths [deg] from +x toward +y.
    elevation_deg : array_like of float
        Elevations [deg] toward +z, broadcastable against ``azimuth_deg``.

    Returns
    -------
    (..., 3) float64
        Unit vectors, in the broadcast shape.

    Examples
    --------
    >>> azel_to_vectors(np.array([0.0, 180.0, -180.0]), np.array([0.0, 0.0, 0.0]))
    array([[ 1.,  0.,  0.],
           [-1.,  0.,  0.],
           [-1.,  0.,  0.]])
    """
    cos_az, sin_az = _cos_sin_deg(np.asarray(azimuth_deg, dtype=np.float64))
    cos_el, sin_el = _cos_sin_deg(np.asarray(elevation_deg, dtype=np.float64))
    # + 0.0 turns -0.0 into 0.0: the pole is the same bits from every azimuth
    return np.stack(np.broadcast_arrays(cos_el * cos_az + 0.0, cos_el * sin_az + 0.0, sin_el + 0.0), axis=-1)


def vector_to_azel(direction: Sequence[float] | NDArray) -> tuple[float, float]:
    """Find the azimuth and elevation [deg] of a unit vector.

    Parameters
    ----------
    direction : (3,) array_like of float
        A unit vector, body frame.

    Returns
    -------
    azimuth, elevation : float
        Azimuth in (-180, 180] and elevation in [-90, 90] [deg].

    Examples
    --------
    >>> vector_to_azel([0.0, -1.0, 0.0])
    (-90.0, 0.0)
    """
    x, y, z = np.asarray(direction, dtype=np.float64)
    return math.degrees(math.atan2(y, x)), math.degrees(math.asin(max(-1.0, min(1.0, z))))


def _fmt(v: NDArray) -> str:
    return "(" + " ".join(f"{x:g}" for x in v) + ")"
