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
    """Raise :class:`InputError` unless every value is a finite number > 0.

    Parameters
    ----------
    **values : float
        The values to check, each by the parameter name the error message gives it.

    Raises
    ------
    InputError
        If a value is not a real number (a bool is not), is not finite, or is <= 0.

    Examples
    --------
    >>> check_positive(width=2.0, depth=0.5)
    >>> check_positive(width=-1.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: width -1.0 must be a finite number > 0
    """
    for name, value in values.items():
        _positive(value, name, name)


def _positive(value: float, shown: str, name: str) -> None:
    """Refuse ``value`` unless a finite number > 0; ``shown`` as the message names it (``size[0]``),
    ``name`` the parameter that gave it."""
    real = isinstance(value, numbers.Real) and not isinstance(value, bool)
    if not (real and math.isfinite(value) and value > 0):
        raise InputError(f"{shown} {value!r} must be a finite number > 0", parameters=(name,))


def check_lengths(**values: float | Sequence[float]) -> None:
    """Raise :class:`InputError` unless every value is a plausible length in metres.

    Each value, or each entry of a sequence of lengths, must be a finite number > 0 (as
    :func:`check_positive`) and at most :data:`MAX_LENGTH_M`.

    Parameters
    ----------
    **values : float or sequence of float
        The lengths [m] to check, each by its parameter name; an entry of a sequence is named
        ``name[k]`` in the message.

    Raises
    ------
    InputError
        If a length is not a finite number > 0, or exceeds :data:`MAX_LENGTH_M` (10 km).

    Examples
    --------
    >>> check_lengths(radius=0.5, size=(1.0, 2.0, 3.0))
    >>> check_lengths(size=(1.0, 2e4))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: size[1] 20000 m is above 10000 m ...
    """
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
    """Raise :class:`InputError` unless every value is an integer >= ``minimum``.

    Parameters
    ----------
    minimum : int
        The smallest count allowed.
    **values : int
        The counts to check, each by its parameter name (a bool is not an integer here).

    Raises
    ------
    InputError
        If a value is not an integer (Python or NumPy) or is below ``minimum``.

    Examples
    --------
    >>> check_count(3, segments=16)
    >>> check_count(3, segments=2)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: segments 2 must be an integer >= 3
    """
    for name, value in values.items():
        if not _is_integer(value) or value < minimum:
            raise InputError(f"{name} {value!r} must be an integer >= {minimum}", parameters=(name,))


def per_axis(name: str, value: int | Sequence[int], n: int) -> tuple[int, ...]:
    """Return an int, or a length-``n`` sequence of ints (each >= 1), as an ``n``-tuple.

    Parameters
    ----------
    name : str
        The parameter name the error message gives ``value``.
    value : int or sequence of int
        One count for every axis, or one per axis.
    n : int
        The number of axes.

    Returns
    -------
    tuple of int
        ``n`` counts, each >= 1.

    Raises
    ------
    InputError
        If ``value`` is neither an integer >= 1 nor ``n`` of them.

    Examples
    --------
    >>> per_axis("divisions", 3, 2)
    (3, 3)
    >>> per_axis("divisions", [2, 5], 2)
    (2, 5)
    """
    values = (value,) * n if _is_integer(value) else tuple(value) if isinstance(value, Sequence) else ()
    if len(values) != n or not all(_is_integer(v) and v >= 1 for v in values):
        raise InputError(f"{name} {value!r} must be an integer >= 1 or {n} of them", parameters=(name,))
    return tuple(int(v) for v in values)


def _is_integer(value: object) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)


def check_triangles(
    triangles: int, fix: str, parameters: tuple[str, ...], per_triangle: int = GRID_TRIANGLE_BYTES
) -> None:
    """Refuse, before building it, a mesh too large for the memory limit.

    A mesh of about ``triangles`` triangles needs about ``triangles * per_triangle`` bytes at its
    peak; :func:`sunwind.geometry.memory.require` refuses it if that exceeds the limit.

    Parameters
    ----------
    triangles : int
        The number of triangles the mesh would have.
    fix : str
        How to make the mesh smaller, appended to the message (which parameters to lower).
    parameters : tuple of str
        The parameters that set the mesh's size.
    per_triangle : int, optional
        Peak bytes per triangle: :data:`GRID_TRIANGLE_BYTES` for a gridded or revolved mesh (the
        default), :data:`HULL_TRIANGLE_BYTES` for a convex hull or a Delaunay triangulation.

    Raises
    ------
    InputError
        If the mesh would need more memory than the limit allows.

    Examples
    --------
    >>> check_triangles(1_000, "lower segments", ("segments",))
    >>> check_triangles(10**15, "lower segments", ("segments",))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: not enough memory: ...; lower segments
    """
    require(int(triangles) * per_triangle, f"a mesh of ~{count(triangles)} facets", fix, parameters)
