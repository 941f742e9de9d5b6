"""The references of a result: the torque reference point, said when it lies so far from the model that
it looks like a slip of unit, and the coefficient reference area and length, checked to a range."""

from __future__ import annotations

import math
import warnings

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError, UnitWarning
from sunwind.geometry.spacecraft import Spacecraft

#: The range of each coefficient reference size: (least, largest, unit).
REFERENCE_SIZES = {"reference_area_m2": (1e-12, 1e12, "m^2"), "reference_length_m": (1e-6, 1e6, "m")}
#: Model sizes (box diagonals) from the model's box beyond which a reference point looks like a slip.
FAR_REFERENCE = 10.0
#: The farthest coordinate [m] of a reference point accepted.
FARTHEST_REFERENCE_M = 1e7


def check_reference_point(point: NDArray[np.float64], craft: Spacecraft) -> None:
    """Refuse a torque reference point no model's reaches, and warn of one far outside the model.

    A :class:`UnitWarning` is given when the point lies farther than :data:`FAR_REFERENCE` model sizes
    from the model's box: a point in mm for a model in m, or the reverse, gives torques a thousand times
    off without an error.

    Parameters
    ----------
    point : (3,) ndarray of float64
        The torque reference point [m], body frame.
    craft : Spacecraft
        The model, for its box and size.

    Raises
    ------
    InputError
        A coordinate beyond :data:`FARTHEST_REFERENCE_M`, which no model's reference point reaches.

    Warns
    -----
    UnitWarning
        A point farther than :data:`FAR_REFERENCE` model sizes from the model's box.

    Examples
    --------
    >>> import warnings
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> check_reference_point(np.array([0.1, 0.0, 0.0]), craft)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     check_reference_point(np.array([100.0, 0.0, 0.0]), craft)
    >>> caught[0].category.__name__
    'UnitWarning'
    """
    if np.abs(point).max() > FARTHEST_REFERENCE_M:
        x, y, z = point
        raise InputError(
            f"reference_point_m ({x:g}, {y:g}, {z:g}) m has a coordinate beyond {FARTHEST_REFERENCE_M:g} m "
            "(10 000 km): no spacecraft's reference point lies there",
            hint="give the centre of mass in the mesh's frame, in metres",
            parameters=("reference_point_m",),
        )
    low, high = craft.bounds
    distance = float(np.linalg.norm(np.maximum(0.0, np.maximum(low - point, point - high))))
    size = craft.diagonal_m
    if distance > FAR_REFERENCE * size:
        x, y, z = point
        warnings.warn(
            UnitWarning(
                f"reference_point_m ({x:g}, {y:g}, {z:g}) m lies {distance:.3g} m outside the model, "
                f"{distance / size:.0f} times its size ({size:.3g} m across, unit {craft.unit}): check "
                "the point's unit; the torques are about it as given",
                ("reference_point_m",),
            ),
            stacklevel=3,
        )


def check_reference_sizes(area_m2: float | None, length_m: float | None) -> None:
    """Refuse coefficient reference sizes that are given but out of range.

    Each, when not None, must be a finite number within :data:`REFERENCE_SIZES`: a square micrometre to
    a million square kilometres, a micrometre to a thousand kilometres (a subnormal area would make every
    coefficient infinite).

    Parameters
    ----------
    area_m2 : float or None
        Reference area [m^2], or None when not given.
    length_m : float or None
        Reference length [m], or None when not given.

    Raises
    ------
    InputError
        A size that is not a number within its range.

    Examples
    --------
    >>> check_reference_sizes(1.0, None)
    >>> check_reference_sizes(0.0, 1.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: reference_area_m2 0.0 must be a positive number from 1e-12 ...
    """
    for name, value in (("reference_area_m2", area_m2), ("reference_length_m", length_m)):
        low, high, unit = REFERENCE_SIZES[name]
        if value is not None and not (
            isinstance(value, int | float) and math.isfinite(value) and low <= value <= high
        ):
            raise InputError(
                f"{name} {value} must be a positive number from {low:g} to {high:g} {unit}",
                parameters=(name,),
            )
