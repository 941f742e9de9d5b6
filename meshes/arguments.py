"""Checks of the mesh builders' arguments: each bad value is an :class:`InputError` naming it."""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import Any

import numpy as np

from sunwind.geometry.errors import InputError

__all__ = ["check_count", "check_positive", "per_axis"]


def check_positive(**values: float) -> None:
    """Raise :class:`InputError` unless every value is a finite number > 0."""
    for name, value in values.items():
        real = isinstance(value, numbers.Real) and not isinstance(value, bool)
        if not (real and math.isfinite(value) and value > 0):
            raise InputError(f"{name} = {value!r} must be a finite number > 0")


def check_count(minimum: int, **values: Any) -> None:
    """Raise :class:`InputError` unless every value is an integer >= ``minimum``."""
    for name, value in values.items():
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
            raise InputError(f"{name} = {value!r} must be an integer >= {minimum}")


def per_axis(name: str, value: int | Sequence[int], n: int) -> tuple[int, ...]:
    """An int or a length-``n`` sequence of ints (each >= 1) as an ``n``-tuple."""
    values = (value,) * n if isinstance(value, (int, np.integer)) else tuple(value)
    if len(values) != n:
        raise InputError(f"{name} = {value!r} must be an integer or {n} integers")
    check_count(1, **{f"{name}[{i}]": v for i, v in enumerate(values)})
    return tuple(int(v) for v in values)
