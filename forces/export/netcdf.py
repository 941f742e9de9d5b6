"""The sweep table as netCDF, through xarray: every variable with its units and long name, the global
attributes with the frame, conventions and provenance. Read it back with
:func:`sunwind.forces.tables.dataset.open_table`."""

from __future__ import annotations

import os
from pathlib import Path

import xarray as xr

from sunwind.forces.export.atomic import temporary_name

#: File extension that chooses this format.
EXTENSION = ".nc"
#: Quantities a netCDF table holds.
KINDS = ("srp", "drag", "earth")


def write(table: xr.Dataset, path: str | os.PathLike) -> list[Path]:
    """Write ``table`` to netCDF at ``path`` (atomically); the file written."""
    target = Path(path)
    temporary = temporary_name(target)
    try:
        table.to_netcdf(temporary)
        os.replace(temporary, target)
    finally:
        temporary.unlink(missing_ok=True)
    return [target]
