"""Attitude sweeps: one model, many Sun, flow or Earth directions, in checkpointed chunks, locally or on
Dask, into a table (an ``xarray.Dataset`` with its provenance).

:func:`sweep` is the one call: the model, what to tabulate (:class:`~sunwind.forces.tables.jobs.SrpSetup`,
:class:`~sunwind.forces.tables.jobs.DragSetup`, :class:`~sunwind.forces.tables.earth_setup.EarthSetup`),
over which attitudes (a grid step or an attitude list), and how to run (:class:`SweepRun`). **Local
runs** use the model as loaded, its precomputes made once (view factors, the diffuse balance) and every
core per attitude. **Checkpoints** keep every finished chunk at once (:mod:`.checkpoint`); ``resume``
takes the chunks already there and computes the rest. **Dask** (:mod:`.cluster`) runs chunks as tasks
on workers that load the model from its files.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import xarray as xr

from sunwind.forces.model import Model, as_model
from sunwind.forces.tables.attitudes import GRID_BYTES, AttitudeList, DirectionGrid, direction_grid
from sunwind.forces.tables.checkpoint import Checkpoint, fingerprint
from sunwind.forces.tables.cluster import require_dask, run_on_dask
from sunwind.forces.tables.dataset import grid_table, list_table, table_attributes
from sunwind.forces.tables.earth_setup import EarthSetup
from sunwind.forces.tables.jobs import FIELDS, DragSetup, Job, PosedSetup, Records, SrpSetup, empty_records
from sunwind.forces.tables.sensitivities import labelled
from sunwind.geometry import memory
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import checked_threads
from sunwind.geometry.spacecraft import Spacecraft

#: Attitudes per checkpoint chunk (and per Dask task) by default.
DEFAULT_CHUNK = 64
#: Default grid step [deg].
DEFAULT_STEP = 10.0


@dataclass(frozen=True)
class SweepRun:
    """How a sweep runs (not what it computes).

    Attributes
    ----------
    chunk : int
        Attitudes per chunk (checkpoint granularity and Dask task size), >= 1.
    checkpoint : Path or None
        Directory keeping finished chunks until the table is made; None keeps nothing.
    resume : bool
        Take up the chunks a checkpoint of the same sweep holds.
    scheduler : str or None
        Dask scheduler address, or ``"local"`` for a local cluster of ``workers`` processes.
    workers : int or None
        Local runs: threads per attitude (default the model's, else every core). Local Dask cluster:
        worker processes (default one per core), each on one thread.
    progress : callable or None
        Called with the number of attitudes finished so far (resumed ones included): first once the
        precomputes are made, before the first chunk is computed, then after each chunk.
    notice : callable or None
        Called with one line when a resumed checkpoint was read: the chunks kept and recomputed.

    Raises
    ------
    InputError
        A chunk that is not a whole number >= 1, a thread count out of range, or a scheduler without
        Dask installed.

    Examples
    --------
    Report progress after every chunk of four attitudes (a 90 deg grid has six distinct directions):

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.engine import SweepRun
    >>> done = []
    >>> run = SweepRun(chunk=4, progress=done.append)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0, run=run)
    >>> done
    [0, 4, 6]
    """

    chunk: int = DEFAULT_CHUNK
    checkpoint: Path | None = None
    resume: bool = False
    scheduler: str | None = None
    workers: int | None = None
    progress: Callable[[int], None] | None = None
    notice: Callable[[str], None] | None = None

    def __post_init__(self) -> None:
        if isinstance(self.chunk, bool) or not isinstance(self.chunk, int) or self.chunk < 1:
            raise InputError(f"chunk {self.chunk} must be a whole number >= 1", parameters=("chunk",))
        checked_threads(self.workers, "workers")
        if self.scheduler is not None:
            require_dask()


#: Bytes per node of the direction variable of a grid table.
_DIRECTION_BYTES = 24


def check_table_memory(
    grid: DirectionGrid, kinds: tuple[str, ...], name: str = "step_deg", extra: int = 0
) -> None:
    """Refuse a grid sweep that would not fit in memory, before any of it is made.

    The grid, the records and the table (float64, each field at every distinct direction and again at
    every node) of ``kinds`` are counted against the memory limit
    (:mod:`sunwind.geometry.memory`).

    Parameters
    ----------
    grid : DirectionGrid
        The grid.
    kinds : tuple of str
        The kinds tabulated, one entry per job (a kind repeated once per hinge pose).
    name : str
        The parameter that set the step, named in the error.
    extra : int
        Numbers per distinct direction recorded besides the kinds' fields (the sensitivities').

    Raises
    ------
    InputError
        The table would exceed the memory limit.

    Examples
    --------
    >>> from sunwind.forces.tables.attitudes import DirectionGrid
    >>> from sunwind.forces.tables.engine import check_table_memory
    >>> check_table_memory(DirectionGrid(10.0), ("srp", "drag"))  # small: nothing said
    >>> check_table_memory(DirectionGrid(0.001), ("srp",))
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: not enough memory: needs ~29.8 TiB for a table of 6.48e+10 grid...
    """
    per_node = sum(2 * 8 * sum(FIELDS[kind].values()) + _DIRECTION_BYTES for kind in kinds) + 2 * 8 * extra
    nodes = grid.nodes
    what = f"a table of {memory.count(nodes)} grid nodes ({', '.join(kinds)})"
    memory.require((GRID_BYTES + per_node) * nodes, what, f"raise {name}", (name,))


def sweep(
    model: Model | Spacecraft,
    *,
    srp: SrpSetup | None = None,
    drag: DragSetup | None = None,
    earth: EarthSetup | None = None,
    step_deg: float | None = None,
    attitudes: AttitudeList | None = None,
    hinge_angles: Mapping[str, Sequence[float]] | None = None,
    run: SweepRun | None = None,
) -> xr.Dataset:
    """Tabulate SRP, drag and/or the Earth's radiation over a grid or a list of attitudes.

    The table carries its provenance: units, frame, reference point, environment, model digests.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model (:func:`sunwind.forces.load`; Dask needs one loaded from files).
    srp, drag : SrpSetup, DragSetup, optional
        What to tabulate (at least one of these and ``earth``): the settings of every SRP attitude, of
        every drag attitude. A setup with ``sensitivities=True`` adds ``KIND_sensitivity_force_N`` and
        ``KIND_sensitivity_torque_Nm`` on the attitude dimensions and ``(material, coefficient,
        component)`` (:mod:`~sunwind.forces.tables.sensitivities`).
    earth : EarthSetup, optional
        The Earth's albedo and infrared (and thermal recoil) over Earth directions, at the setup's
        altitude with its Sun fixed in the body frame: grid tables only.
    step_deg : float, optional
        Grid step [deg] in azimuth (-180..180) and elevation (-90..90); must divide 180. Default
        :data:`DEFAULT_STEP` unless ``attitudes`` is given.
    attitudes : AttitudeList, optional
        A list of attitudes instead of a grid (:func:`~sunwind.forces.tables.attitudes.read_attitude_csv`).
    hinge_angles : mapping of str to sequence of float, optional
        Hinges (materials-file globs) held at each of these angles [deg]: every combination is a pose,
        and each hinge a table dimension ``hinge_deg[GLOB]`` (length 1 for one angle).
    run : SweepRun, optional
        Chunks, checkpoint, Dask, threads, progress.

    Returns
    -------
    xarray.Dataset
        Grid or list table (:mod:`sunwind.forces.tables.dataset`), with units, frame, reference
        point, environment and provenance in its attributes.

    Raises
    ------
    InputError
        Nothing to tabulate; both ``step_deg`` and ``attitudes``; the Earth over an attitude list; a grid
        step that does not divide 180 deg or a table beyond the memory limit; hinge angles that are not
        distinct finite numbers or hinges that cannot turn so; what a setup or the checkpoint refuses.

    Examples
    --------
    SRP and drag of a black 1 m cube on a 90 deg grid:

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> table = sw.sweep(
    ...     cube,
    ...     srp=sw.SrpSetup(reflections="none"),
    ...     drag=sw.DragSetup(speed_m_s=7600.0, atmosphere=air, reflections="none"),
    ...     step_deg=90.0,
    ... )
    >>> dict(table.sizes)
    {'sun_azimuth': 5, 'sun_elevation': 3, 'component': 3, 'flow_azimuth': 5, 'flow_elevation': 3}
    >>> face_on = table.sel(sun_azimuth=0.0, sun_elevation=0.0, flow_azimuth=0.0, flow_elevation=0.0)
    >>> (face_on["srp_force_N"] * 1e6).round(2).values.tolist(), round(float(face_on["drag_CD"]), 3)
    ([-4.54, 0.0, 0.0], 1.634)
    """
    model, run = as_model(model), run or SweepRun()
    setups = [setup for setup in (srp, drag, earth) if setup is not None]
    if not setups:
        raise InputError(
            "give srp, drag or earth (one or more): what the sweep tabulates",
            parameters=("srp", "drag", "earth"),
        )
    poses = hinge_poses(hinge_angles)
    # a schedule has no time in a sweep; a Sun-tracking hinge has no Sun in a drag table (an SRP table
    # turns it to each entry's Sun, an earth table to its one fixed Sun)
    with_drag = drag is not None
    model.held(dict(poses[0])).check_turnable("a drag table" if with_drag else "a table", sun=not with_drag)
    if attitudes is not None and step_deg is not None:
        raise InputError("give step_deg or attitudes, not both", parameters=("step_deg", "attitudes"))
    if attitudes is not None and earth is not None:
        raise InputError(
            "an attitude list has no Earth direction: the Earth's radiation is tabulated on a grid",
            hint="sweep earth over a grid (step_deg) and the attitudes without it",
            parameters=("attitudes", "step_deg"),
        )
    if earth is not None:
        earth.check(model)
    setups = [setup.sized(model) for setup in setups]  # with sensitivities: per material of the model
    grid = None
    if attitudes is None:
        grid = direction_grid(DEFAULT_STEP if step_deg is None else step_deg, "step_deg")
        derivatives = sum(sum(setup.sensitivity_fields.values()) for setup in setups)
        check_table_memory(
            grid, tuple(setup.kind for setup in setups) * len(poses), extra=derivatives * len(poses)
        )
    directions = {
        setup.kind: grid.distinct[0] if grid is not None else attitudes.directions(setup.kind)
        for setup in setups
    }
    if hinge_angles is None:
        jobs = [Job(setup, directions[setup.kind]) for setup in setups]
    else:
        jobs = [
            Job(PosedSetup(setup, pose, k), directions[setup.kind])
            for k, pose in enumerate(poses)
            for setup in setups
        ]
    records = run_jobs(model, jobs, run)
    tables = []
    for k, pose in enumerate(poses):
        held = model.held(dict(pose))
        own = {
            setup.kind: records[setup.kind if hinge_angles is None else f"{setup.kind}@{k}"]
            for setup in setups
        }
        attrs = table_attributes(held, setups, None if grid is None else grid.step_deg)
        if grid is not None:
            table = grid_table(own, dict.fromkeys(own, grid), attrs)
        else:
            table = list_table(own, attitudes, attrs)
        tables.append(labelled(table, held.craft.materials.names))
    return tables[0] if hinge_angles is None else by_hinge_angle(tables, poses)


def hinge_poses(hinge_angles: Mapping[str, Sequence[float]] | None) -> list[tuple[tuple[str, float], ...]]:
    """Every combination of the listed hinge angles, as (glob, deg) pairs; ``[()]`` without any.

    Parameters
    ----------
    hinge_angles : mapping of str to sequence of float, or None
        Hinge glob -> the angles [deg] it is held at (a single number is one angle).

    Returns
    -------
    list of tuple of (str, float)
        One pose per combination, the globs in the mapping's order, the last glob varying slowest.

    Raises
    ------
    InputError
        A glob without angles, or angles that are not distinct finite numbers.

    Examples
    --------
    >>> from sunwind.forces.tables.engine import hinge_poses
    >>> hinge_poses(None)
    [()]
    >>> hinge_poses({"wing*": [0, 30], "antenna": 5})
    [(('wing*', 0.0), ('antenna', 5.0)), (('wing*', 30.0), ('antenna', 5.0))]
    """
    if hinge_angles is None:
        return [()]
    names, lists = list(hinge_angles), []
    for name in names:
        values = [float(v) for v in np.atleast_1d(np.asarray(hinge_angles[name], dtype=float))]
        if not values or not all(math.isfinite(v) for v in values) or len(set(values)) != len(values):
            raise InputError(
                f'hinge_angles "{name}" {values} must be distinct finite angles [deg], at least one',
                parameters=("hinge_angles",),
            )
        lists.append(values)
    return [tuple(zip(names, combo, strict=True)) for combo in itertools.product(*lists)]


def by_hinge_angle(tables: list[xr.Dataset], poses: list[tuple[tuple[str, float], ...]]) -> xr.Dataset:
    """One table of the poses' tables, a dimension ``hinge_deg[GLOB]`` per hinge.

    The attributes the poses share are kept, and ``hinge_angles_deg`` (JSON: each hinge's angles) added;
    direction variables, the same at every pose, keep no hinge dimension.

    Parameters
    ----------
    tables : list of xarray.Dataset
        One table per pose, in the order of ``poses``.
    poses : list of tuple of (str, float)
        The poses (:func:`hinge_poses`).

    Returns
    -------
    xarray.Dataset
        The tables combined along the hinge dimensions.

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.engine import by_hinge_angle
    >>> one = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> both = by_hinge_angle([one, one], [(("wing*", 0.0),), (("wing*", 30.0),)])
    >>> both["srp_force_N"].dims, both.attrs["hinge_angles_deg"]
    (('hinge_deg[wing*]', 'sun_azimuth', 'sun_elevation', 'component'), '{"wing*": [0.0, 30.0]}')
    """
    dimensioned = [
        table.expand_dims({hinge_dimension(name): [angle] for name, angle in pose})
        for table, pose in zip(tables, poses, strict=True)
    ]
    table = xr.combine_by_coords(dimensioned, combine_attrs="drop_conflicts")
    dimensions = [hinge_dimension(name) for name, _ in poses[0]]
    for name in [str(v) for v in table.data_vars if str(v).endswith("_vector")]:  # the same at every pose
        table[name] = table[name].isel(dict.fromkeys(dimensions, 0), drop=True)
    angles = {
        name: sorted({angle for pose in poses for n, angle in pose if n == name}) for name, _ in poses[0]
    }
    for name in angles:
        table[hinge_dimension(name)].attrs = {"units": "degree", "long_name": f'angle of hinge "{name}"'}
    table.attrs["hinge_angles_deg"] = json.dumps(angles)
    return table


def hinge_dimension(glob: str) -> str:
    """The table dimension of the angles of the hinge ``glob``.

    Parameters
    ----------
    glob : str
        The hinge's materials-file glob.

    Returns
    -------
    str
        ``hinge_deg[GLOB]``.

    Examples
    --------
    >>> from sunwind.forces.tables.engine import hinge_dimension
    >>> hinge_dimension("wing*")
    'hinge_deg[wing*]'
    """
    return f"hinge_deg[{glob}]"


def run_jobs(
    model: Model,
    jobs: list[Job],
    run: SweepRun,
    *,
    finish: Callable[[dict[str, Records]], dict[str, Records]] | None = None,
) -> dict[str, Records]:
    """Evaluate every job in chunks, here or on Dask.

    Each setup's precomputes are made once, then the chunks the checkpoint does not hold are computed.

    Parameters
    ----------
    model : Model
        The model every job evaluates.
    jobs : list of Job
        Each a :class:`~sunwind.forces.tables.jobs.Tabulation` over its inputs; kinds distinct.
    run : SweepRun
        Chunks, checkpoint, resume, Dask, threads and progress.
    finish : callable, optional
        A pass over the finished records (e.g. the orbit's thermal transient), run before the
        checkpoint is removed: stopped or failed, it leaves the checkpoint for a resume, which
        computes no chunk again. Its result is returned.

    Returns
    -------
    dict of str to Records
        Records per kind, rows in the order of the job's inputs (``finish``'s, with it).

    Raises
    ------
    InputError
        A checkpoint that cannot be taken (see :meth:`~.checkpoint.Checkpoint.open`), or what a
        setup refuses.

    Examples
    --------
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.forces import load
    >>> from sunwind.meshes import box
    >>> model = load(box(), uniform=Material("paint", 0.4, 0.5, 0.1))
    >>> job = Job(SrpSetup(reflections="none"), np.eye(3))
    >>> run_jobs(model, [job], SweepRun(chunk=2))["srp"]["force_N"].shape
    (3, 3)
    """
    store = None
    if run.checkpoint is not None:
        store = Checkpoint.open(Path(run.checkpoint), fingerprint(model, jobs, run.chunk), run.resume)
    records = {job.kind: empty_records(job.fields, len(job.inputs)) for job in jobs}
    pending: list[tuple[Job, int, int]] = []
    done = 0
    for job in jobs:
        for lo, hi in job.chunks(run.chunk):
            kept = None if store is None else store.load(job, lo, hi)
            if kept is None:
                pending.append((job, lo, hi))
            else:
                _fill(records[job.kind], lo, hi, kept)
                done += hi - lo
    said = None if store is None else store.summary(len(pending))
    if said and run.notice:
        run.notice(said)
    finished = _Finished(records, store, done, run.progress)
    try:
        precompute(model, list({id(job): job for job, _, _ in pending}.values()))
        if run.progress:
            run.progress(done)
        if pending:
            _evaluate(model, pending, run, finished)
        if finish is not None:
            records = finish(records)
        if store is not None:
            store.remove()
    except BaseException:
        if store is not None and store.created and not store.saved:
            store.remove()  # a failed start leaves nothing behind
        raise
    finally:
        if store is not None:
            store.release()  # kept for a resume, free to be taken up
    return records


def _evaluate(model: Model, pending: list[tuple[Job, int, int]], run: SweepRun, finished: _Finished) -> None:
    """Compute the pending chunks (their jobs precomputed), here or on Dask, handing each to ``finished``."""
    if run.scheduler is None:
        local = model if run.workers is None else replace(model, threads=run.workers)
        for job, lo, hi in pending:
            finished(job, lo, hi, job.setup.evaluate(local, job.inputs[lo:hi]))
    else:
        run_on_dask(model, pending, run.scheduler, run.workers, finished)


class _Finished:
    """Takes each finished chunk: into the records, into the checkpoint, and onto the progress count."""

    def __init__(self, records: dict[str, Records], store: Checkpoint | None, done: int, progress) -> None:
        self.records, self.store, self.done, self.progress = records, store, done, progress

    def __call__(self, job: Job, lo: int, hi: int, values: Records) -> None:
        _fill(self.records[job.kind], lo, hi, values)
        if self.store is not None:
            self.store.save(job, lo, values)
        self.done += hi - lo
        if self.progress:
            self.progress(self.done)


def _fill(records: Records, lo: int, hi: int, values: Records) -> None:
    for name, array in records.items():
        array[lo:hi] = values[name]


def precompute(model: Model, jobs: list[Job]) -> None:
    """Make what every input of ``jobs`` reuses, once, before the first chunk.

    Dask workers then read it from the disk cache: the view factors when a job reflects, each side's
    open sky when it computes drag, the thermal balance of the Earth's radiation with its thermal
    recoil. :func:`run_jobs` calls it for the jobs it computes; nothing else needs to.

    Parameters
    ----------
    model : Model
        The model the jobs evaluate.
    jobs : list of Job
        The jobs.

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> import numpy as np
    >>> from sunwind.forces.tables.engine import precompute
    >>> from sunwind.forces.tables.jobs import Job
    >>> precompute(cube, [Job(sw.SrpSetup(reflections="full"), np.eye(3))])  # the view factors, once
    """
    for job in jobs:
        job.setup.precompute(model)
