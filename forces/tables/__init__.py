"""Attitude tables: grids and lists of attitudes, what each attitude records, the sweep engine with its
checkpoints and Dask, the table as an ``xarray.Dataset``, and its interpolation (METHOD.md "Outputs and
tables"). Plots of a table are :mod:`sunwind.forces.tables.plots` (matplotlib is loaded there only)."""

from sunwind.forces.tables.attitudes import AttitudeList, DirectionGrid, direction_grid, read_attitude_csv
from sunwind.forces.tables.dataset import grid_table, kinds_of, list_table, open_table, table_attributes
from sunwind.forces.tables.earth_setup import EarthSetup
from sunwind.forces.tables.engine import DEFAULT_CHUNK, DEFAULT_STEP, SweepRun, run_jobs, sweep
from sunwind.forces.tables.interpolation import InterpolatedLoads, TableInterpolator
from sunwind.forces.tables.jobs import (
    DRAG_FIELDS,
    EARTH_FIELDS,
    ESTIMATE_FIELDS,
    FIELDS,
    KINDS,
    SRP_FIELDS,
    DragSetup,
    Job,
    SrpSetup,
)

__all__ = [
    "DEFAULT_CHUNK",
    "DEFAULT_STEP",
    "DRAG_FIELDS",
    "EARTH_FIELDS",
    "ESTIMATE_FIELDS",
    "FIELDS",
    "KINDS",
    "SRP_FIELDS",
    "AttitudeList",
    "DirectionGrid",
    "DragSetup",
    "EarthSetup",
    "InterpolatedLoads",
    "Job",
    "SrpSetup",
    "SweepRun",
    "TableInterpolator",
    "direction_grid",
    "grid_table",
    "kinds_of",
    "list_table",
    "open_table",
    "read_attitude_csv",
    "run_jobs",
    "sweep",
    "table_attributes",
]
