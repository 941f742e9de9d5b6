"""Length units of mesh files: the names users may give and which unit a load ends up using.

A mesh is converted to metres on load (METHOD.md "Frames, units and signs"). The unit comes from the user when
given, else from the file when the format declares one (USD ``metersPerUnit``, glTF by
specification), else it is metres, and the choice is always written down as a short string.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from types import MappingProxyType

from sunwind.geometry.errors import InputError

#: Unit names a user may give, with their length in metres (read-only).
UNITS: Mapping[str, float] = MappingProxyType({"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254})


def parse_unit(unit: str, path: str) -> str:
    """The name in ``UNITS`` of a user's unit, ignoring case and surrounding blanks.

    Parameters
    ----------
    unit : str
        The unit as the user gave it, e.g. ``"mm"``.
    path : str
        The file it is meant for, named in the error.

    Raises
    ------
    InputError
        ``unit`` is not one of ``UNITS``.

    Returns
    -------
    str
        The key of ``UNITS``.

    Examples
    --------
    >>> parse_unit(" MM ", "craft.obj")
    'mm'
    """
    name = unit.strip().lower()
    if name not in UNITS:
        raise InputError(f"unknown unit '{unit}'", path=path, hint=f"use one of {', '.join(UNITS)}")
    return name


def resolve_unit(unit: str | None, declared: tuple[float, str] | None) -> tuple[float, str]:
    """Choose the metres-per-unit factor for a file and describe the choice.

    Parameters
    ----------
    unit : str or None
        The user's unit, a key of ``UNITS`` (see :func:`parse_unit`); it wins over the file's.
    declared : (float, str) or None
        The file's own metres per unit and what declared it, e.g. ``(0.01, "USD metersPerUnit")``.

    Returns
    -------
    factor : float
        Metres per file unit.
    label : str
        What was used and why, e.g. ``"mm (--unit)"``, ``"cm (USD metersPerUnit)"``,
        ``"m (default)"``, ``"mm (--unit; overrides USD metersPerUnit: cm)"``.

    Examples
    --------
    >>> resolve_unit(None, None)
    (1.0, 'm (default)')
    >>> resolve_unit("mm", (0.01, "USD metersPerUnit"))
    (0.001, 'mm (--unit; overrides USD metersPerUnit: cm)')
    """
    if unit is None:
        if declared is None:
            return 1.0, "m (default)"
        factor, source = declared
        return factor, f"{unit_name(factor)} ({source})"
    factor = UNITS[unit]
    if declared is None or math.isclose(declared[0], factor, rel_tol=1e-9):
        return factor, f"{unit} (--unit)"
    return factor, f"{unit} (--unit; overrides {declared[1]}: {unit_name(declared[0])})"


def unit_name(factor: float) -> str:
    """Name a metres-per-unit factor: its key in ``UNITS``, else the factor in metres.

    Parameters
    ----------
    factor : float
        Metres per file unit.

    Returns
    -------
    str
        E.g. ``"cm"`` for 0.01, ``"0.3048 m"`` for a foot.

    Examples
    --------
    >>> unit_name(0.01), unit_name(0.3048)
    ('cm', '0.3048 m')
    """
    for name, metres in UNITS.items():
        if math.isclose(factor, metres, rel_tol=1e-9):
            return name
    return f"{factor:.10g} m"
