"""The sweep table as CSV: ``#`` comment lines with the table's attributes, a header row whose column
names carry their units (``srp_force_N_x[N]``), one row per grid node or attitude. SRP and drag on a
grid are on different grids: they go to ``NAME.srp.csv`` and ``NAME.drag.csv`` (and the Earth's radiation
to ``NAME.earth.csv``)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from sunwind.forces.export.atomic import atomic_text
from sunwind.forces.tables.dataset import DIRECTION, attribute_text, kinds_of

#: File extension that chooses this format.
EXTENSION = ".csv"
#: Quantities a CSV table holds.
KINDS = ("srp", "drag", "earth")


def csv_paths(path: Path, table: xr.Dataset) -> dict[str, Path]:
    """The CSV file each quantity of a table goes to.

    A list table, or a table of one quantity, is one file at ``path``; a grid table of several
    quantities (each on its own grid) is one file per quantity, ``NAME.srp.csv``, ``NAME.drag.csv``,
    ``NAME.earth.csv``.

    Parameters
    ----------
    path : Path
        The output path the user gave.
    table : xarray.Dataset
        The sweep table.

    Returns
    -------
    dict of str to Path
        ``{"all": path}`` for one file, else quantity -> file.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> {kind: str(path) for kind, path in csv_paths(Path("cube.csv"), table).items()}  # SRP alone
    {'all': 'cube.csv'}
    """
    kinds = kinds_of(table)
    if "attitude" in table.dims or len(kinds) == 1:
        return {"all": path}
    return {kind: path.with_name(f"{path.stem}.{kind}{path.suffix}") for kind in kinds}


def write(table: xr.Dataset, path: str | os.PathLike) -> list[Path]:
    """Write a sweep table as CSV, atomically.

    ``#`` comment lines hold the table's attributes, a header row names each column with its unit
    (``srp_force_N_x[N]``), and each grid node or attitude is a row (full precision, ``%.17g``).

    Parameters
    ----------
    table : xarray.Dataset
        The sweep table (:mod:`sunwind.forces.tables.dataset`).
    path : str or os.PathLike
        Where to write (:func:`csv_paths` says the files).

    Returns
    -------
    list of Path
        The files written.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     (path,) = write(table, Path(folder) / "cube.csv")
    ...     lines = path.read_text().splitlines()
    >>> header = next(line for line in lines if not line.startswith("#"))
    >>> header.split(",")[:3], len(lines) - lines.index(header) - 1  # one row per grid node
    (['sun_azimuth_deg', 'sun_elevation_deg', 'srp_force_N_x[N]'], 15)
    """
    path = Path(path)
    written = []
    for kind, target in csv_paths(path, table).items():
        part = table if kind == "all" else table[[name for name in table.data_vars if name.startswith(kind)]]
        if kind != "all":
            part[DIRECTION[kind]] = table[DIRECTION[kind]]
        written.append(_write_csv_part(part, table.attrs, target))
    return written


def _write_csv_part(table: xr.Dataset, attrs: Mapping[str, object], path: Path) -> Path:
    dims = [d for d in table[next(iter(table.data_vars))].dims if d != "component"]
    index = np.stack(np.meshgrid(*(table[d].values for d in dims), indexing="ij"), axis=-1).reshape(
        -1, len(dims)
    )
    names = [f"{d}_deg" if d.endswith(("azimuth", "elevation")) else d for d in dims]
    columns = [index.astype(np.float64)]
    for name, variable in table.data_vars.items():
        if any(d not in (*dims, "component", "quaternion_component") for d in variable.dims):
            continue
        values = variable.transpose(*dims, ...).values.reshape(len(index), -1)
        unit = variable.attrs.get("units", "1").replace(" ", "").replace("^", "")
        if values.shape[1] == 1:
            names.append(f"{name}[{unit}]")
        else:
            suffixes = "wxyz" if "quaternion_component" in variable.dims else "xyz"
            names += [f"{name}_{c}[{unit}]" for c in suffixes]
        columns.append(values)
    lines = [f"# {key}: {attribute_text(value)}" for key, value in attrs.items()]
    body = np.hstack(columns)
    with atomic_text(path) as handle:
        handle.write("\n".join(lines) + "\n" + ",".join(names) + "\n")
        np.savetxt(handle, body, delimiter=",", fmt="%.17g")
    return path
