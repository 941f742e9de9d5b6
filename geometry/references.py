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
    """Refuse a torque reference ``point`` [m] no model's reaches; a :class:`UnitWarning` when it lies
    farther than :data:`FAR_REFERENCE` model sizes from the model's box: a point in mm for a model in m,
    or the reverse, gives torques a thousand times off without an error.

    Raises
    ------
    InputError
        A coordinate beyond :data:`FARTHEST_REFERENCE_M`, which no model's reference point reaches.
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
    """Refuse coefficient reference sizes that are given but not positive numbers within
    :data:`REFERENCE_SIZES` (a square micrometre to a million square kilometres, a micrometre to a
    thousand kilometres: a subnormal area would make every coefficient infinite)."""
    for name, value in (("reference_area_m2", area_m2), ("reference_length_m", length_m)):
        low, high, unit = REFERENCE_SIZES[name]
        if value is not None and not (
            isinstance(value, int | float) and math.isfinite(value) and low <= value <= high
        ):
            raise InputError(
                f"{name} {value} must be a positive number from {low:g} to {high:g} {unit}",
                parameters=(name,),
            )
