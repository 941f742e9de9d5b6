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
    """Write a sweep table to netCDF, atomically.

    Every variable keeps its units and long name and the global attributes the frame, conventions
    (CF-1.8) and provenance; :func:`sunwind.forces.tables.dataset.open_table` reads it back.

    Parameters
    ----------
    table : xarray.Dataset
        The sweep table (:mod:`sunwind.forces.tables.dataset`).
    path : str or os.PathLike
        The file to write.

    Returns
    -------
    list of Path
        The file written.

    References
    ----------
    .. [1] Eaton, B., Gregory, J., Drach, B., et al. (2020). *NetCDF Climate and Forecast (CF) Metadata
       Conventions*, version 1.8. https://cfconventions.org

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> import xarray as xr
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     (path,) = write(table, Path(folder) / "cube.nc")
    ...     with xr.open_dataset(path) as back:
    ...         print(back["srp_force_N"].attrs["units"], back.attrs["Conventions"])
    N CF-1.8
    """
    target = Path(path)
    temporary = temporary_name(target)
    try:
        table.to_netcdf(temporary)
        os.replace(temporary, target)
    finally:
        temporary.unlink(missing_ok=True)
    return [target]
