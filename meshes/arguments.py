"""Checks of the mesh builders' arguments: each bad value is an :class:`InputError` naming it."""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import Any

import numpy as np

from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import count, require

__all__ = [
    "HULL_TRIANGLE_BYTES",
    "MAX_LENGTH_M",
    "check_count",
    "check_lengths",
    "check_positive",
    "check_triangles",
    "per_axis",
]

#: Peak bytes per triangle of building a gridded or revolved mesh and writing it (measured 197 to 251).
GRID_TRIANGLE_BYTES = 250
#: The same for a mesh made by a convex hull or a Delaunay triangulation (measured 398 to 422).
HULL_TRIANGLE_BYTES = 420
#: Longest length a builder takes [m]: 10 km, a hundred times the largest structure flown (the
#: International Space Station's truss, about 110 m); a longer one is a slip of unit or of typing.
MAX_LENGTH_M = 1e4


def check_positive(**values: float) -> None:
    """Raise :class:`InputError` unless every value is a finite number > 0."""
    for name, value in values.items():
        _positive(value, name, name)


def _positive(value: float, shown: str, name: str) -> None:
    """Refuse ``value`` unless a finite number > 0; ``shown`` as the message names it (``size[0]``),
    ``name`` the parameter that gave it."""
    real = isinstance(value, numbers.Real) and not isinstance(value, bool)
    if not (real and math.isfinite(value) and value > 0):
        raise InputError(f"{shown} {value!r} must be a finite number > 0", parameters=(name,))


def check_lengths(**values: float | Sequence[float]) -> None:
    """Raise :class:`InputError` unless every value, or every entry of a sequence of lengths, is a
    length [m]: a finite number > 0 (as :func:`check_positive`) and at most :data:`MAX_LENGTH_M`."""
    for name, value in values.items():
        many = isinstance(value, Sequence)
        for k, length in enumerate(value if many else (value,)):
            shown = f"{name}[{k}]" if many else name
            _positive(length, shown, name)
            if length > MAX_LENGTH_M:
                raise InputError(
                    f"{shown} {length:g} m is above {MAX_LENGTH_M:g} m (10 km, a hundred times the "
                    "largest spacecraft structure, the ISS's ~110 m truss)",
                    hint=f"give {name} in metres, at most {MAX_LENGTH_M:g}",
                    parameters=(name,),
                )


def check_count(minimum: int, **values: Any) -> None:
    """Raise :class:`InputError` unless every value is an integer >= ``minimum``."""
    for name, value in values.items():
        if not _is_integer(value) or value < minimum:
            raise InputError(f"{name} {value!r} must be an integer >= {minimum}", parameters=(name,))


def per_axis(name: str, value: int | Sequence[int], n: int) -> tuple[int, ...]:
    """An int or a length-``n`` sequence of ints (each >= 1) as an ``n``-tuple."""
    values = (value,) * n if _is_integer(value) else tuple(value) if isinstance(value, Sequence) else ()
    if len(values) != n or not all(_is_integer(v) and v >= 1 for v in values):
        raise InputError(f"{name} {value!r} must be an integer >= 1 or {n} of them", parameters=(name,))
    return tuple(int(v) for v in values)


def _is_integer(value: object) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)


def check_triangles(
    triangles: int, fix: str, parameters: tuple[str, ...], per_triangle: int = GRID_TRIANGLE_BYTES
) -> None:
    """Refuse, before building it, a mesh of about ``triangles`` triangles that exceeds the memory limit
    (:func:`sunwind.geometry.memory.require`); ``fix`` names the ``parameters`` that set its size."""
    require(int(triangles) * per_triangle, f"a mesh of ~{count(triangles)} facets", fix, parameters)
