"""File formats of the sweep table, one module each, every one reading only the table (an
``xarray.Dataset``) and writing atomically: netCDF and CSV, GMAT/MONTE SPAD, Basilisk's SRP lookup,
Tudat's aerodynamic coefficient files (METHOD.md "Outputs and tables").

:func:`write` writes any of them; the format is named or read from the file's extension (a name
without one gets the format's; an extension of another format is refused).

The table's torque reference point: netCDF and CSV keep it as an attribute; a SPAD file holds forces only,
and its header says the point does not enter; Basilisk's format fixes the body-frame origin B, so the
torques are moved there, and a point other than the origin gives a :class:`ReferencePointWarning`; Tudat's
files keep the moments about the point, which Tudat is to be given as ``moment_reference_point`` (a
default point gives the warning). Each file states the point.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import xarray as xr

from sunwind.forces.export import basilisk, csv, netcdf, spad, tudat
from sunwind.forces.tables.dataset import kinds_of, one_pose
from sunwind.geometry.errors import InputError, ReferencePointWarning


@dataclass(frozen=True)
class Format:
    """One file format of the sweep table.

    Parameters
    ----------
    extension : str or None
        The extension that chooses it (None: chosen only by name).
    kinds : tuple of str
        The quantities it holds ("srp", "drag", ...).
    write : callable
        ``write(table, path) -> files written``.
    check : callable or None
        ``check(step_deg)``, which refuses before a sweep the attitudes it cannot hold (``step_deg``
        None: a list of attitudes).

    Examples
    --------
    >>> FORMATS["nc"].extension, FORMATS["tudat"].extension
    ('.nc', None)
    """

    extension: str | None
    kinds: tuple[str, ...]
    write: Callable[[xr.Dataset, Path], list[Path]]
    check: Callable[[float | None], None] | None = None


#: Formats by name.
FORMATS: dict[str, Format] = {
    name: Format(module.EXTENSION, module.KINDS, module.write, getattr(module, "check_request", None))
    for name, module in (
        ("nc", netcdf),
        ("csv", csv),
        ("spad", spad),
        ("basilisk", basilisk),
        ("tudat", tudat),
    )
}


def format_of(path: str | os.PathLike, given: str | None = None) -> str:
    """The format ``given`` names, else the one the extension of ``path`` says.

    Parameters
    ----------
    path : str or os.PathLike
        The output path.
    given : str, optional
        A key of :data:`FORMATS`.

    Returns
    -------
    str
        The format's name.

    Raises
    ------
    InputError
        An unknown format name, or an extension that names none.

    Examples
    --------
    >>> format_of("sweep.csv"), format_of("sweep", "spad")
    ('csv', 'spad')
    """
    if given is not None:
        if given not in FORMATS:
            raise InputError(
                f"format {given!r} is not a table format",
                hint=f"use one of {', '.join(FORMATS)}",
                parameters=("format",),
            )
        return given
    suffix = Path(path).suffix.lower()
    by_extension = {spec.extension: name for name, spec in FORMATS.items() if spec.extension}
    if suffix not in by_extension:
        listed = ", ".join(f"{ext} ({name})" for ext, name in by_extension.items())
        raise InputError(
            f"cannot tell the format from the extension {suffix!r}",
            path=str(path),
            hint=f"use {listed}, or name the format: {' | '.join(FORMATS)}",
            parameters=("format",),
        )
    return by_extension[suffix]


def output_target(path: str | os.PathLike, given: str | None = None) -> tuple[str, Path]:
    """The format of an output and the path it is written to.

    A path without an extension gets the format's (``-o table --format nc`` writes ``table.nc``).

    Parameters
    ----------
    path : str or os.PathLike
        The output path.
    given : str, optional
        A key of :data:`FORMATS`; by default the extension of ``path`` says.

    Returns
    -------
    name : str
        The format.
    target : Path
        Where it is written.

    Raises
    ------
    InputError
        What :func:`format_of` refuses, or an extension that names a format other than ``given``.

    Examples
    --------
    >>> name, target = output_target("table", "nc")
    >>> name, target.name
    ('nc', 'table.nc')
    """
    name, target = format_of(path, given), Path(path)
    suffix, extension = target.suffix.lower(), FORMATS[name].extension
    named = {spec.extension: other for other, spec in FORMATS.items() if spec.extension}
    if suffix in named and named[suffix] != name:
        fix = f"name it {target.stem}{extension}" if extension else f"give a prefix without {suffix}"
        raise InputError(
            f"the extension {suffix} says {named[suffix]}, but the table is to be written as {name}",
            path=str(target),
            hint=f"{fix}, or leave out format",
            parameters=("format",),
        )
    if not suffix and extension:
        target = target.with_name(target.name + extension)
    return name, target


def check_request(name: str, step_deg: float | None) -> None:
    """Refuse, before a sweep starts, attitudes format ``name`` cannot hold.

    Parameters
    ----------
    name : str
        A key of :data:`FORMATS`.
    step_deg : float or None
        The grid's step [deg]; None for a list of attitudes.

    Raises
    ------
    InputError
        A list for a grid format (SPAD, Tudat), a step SPAD files cannot hold.

    Examples
    --------
    >>> check_request("nc", None)  # netCDF holds a list as well as a grid
    """
    check = FORMATS[name].check
    if check is not None:
        check(step_deg)


def write(table: xr.Dataset, path: str | os.PathLike, format: str | None = None) -> list[Path]:
    """Write a sweep table in ``format`` (default: from the extension of ``path``).

    Parameters
    ----------
    table : xarray.Dataset
        The sweep table (:mod:`sunwind.forces.tables.dataset`).
    path : str or os.PathLike
        Where to write; a path without an extension gets the format's.
    format : str, optional
        A key of :data:`FORMATS`.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    InputError
        An unknown format, an extension of another format, or a table the format cannot hold (none of
        its quantities, or a list table for a grid format).

    Warns
    -----
    UserWarning
        The table holds a quantity the format has no place for (it is not written).
    ReferencePointWarning
        Basilisk: the reference point is not the body-frame origin, to which the torques were moved;
        Tudat: the reference point is a default, which Tudat is to be given (the formats' writers).

    Examples
    --------
    The format is checked before anything is written:

    >>> write(xr.Dataset(), "sweep.xyz")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: sweep.xyz: cannot tell the format from the extension '.xyz'...
    """
    name, target = output_target(path, format)
    spec = FORMATS[name]
    held = kinds_of(table)
    refused = [kind for kind in held if kind not in spec.kinds]
    if len(refused) == len(held):
        raise InputError(
            f"format {name} holds {' and '.join(spec.kinds)} only, not {refused[0]}", parameters=("format",)
        )
    if refused:
        left = f"{' and '.join(refused)} {'is' if len(refused) == 1 else 'are'} not written"
        warnings.warn(
            f"format {name} holds {' and '.join(spec.kinds)} only: {left}",
            stacklevel=2,
        )
    if name != "nc":
        table = one_pose(table, f"format {name}")
    return spec.write(table, target)


__all__ = [
    "FORMATS",
    "Format",
    "ReferencePointWarning",
    "check_request",
    "format_of",
    "output_target",
    "write",
]
