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
    """CSV file of each quantity: ``path`` itself for a list table or one quantity, else
    ``NAME.srp.csv``, ``NAME.drag.csv``, ``NAME.earth.csv`` (each on its own grid)."""
    kinds = kinds_of(table)
    if "attitude" in table.dims or len(kinds) == 1:
        return {"all": path}
    return {kind: path.with_name(f"{path.stem}.{kind}{path.suffix}") for kind in kinds}


def write(table: xr.Dataset, path: str | os.PathLike) -> list[Path]:
    """Write ``table`` as CSV (see :func:`csv_paths`), atomically; returns the files written."""
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
