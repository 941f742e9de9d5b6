"""Benchmark of a whole attitude sweep: a grid of SRP and drag with full reflections on the generated
sample, its projection to a 1-degree grid with the error of its entries, and the speed-up of a local
Dask cluster (``sunwind bench --sweep``)."""

from __future__ import annotations

import os
import platform
import tempfile
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from sunwind.forces.bench import REFERENCE_TOLERANCE, LoadError, reference_gas
from sunwind.forces.gas import circular_speed, nrlmsis
from sunwind.forces.gas.visible import model_sky
from sunwind.forces.model import load
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.tables import DragSetup, Job, SrpSetup, SweepRun, direction_grid, run_jobs
from sunwind.forces.tables.cluster import timed_on_local_cluster
from sunwind.forces.tables.engine import precompute
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import level_for_samples
from sunwind.meshes.samples import write_sample_files


@dataclass(frozen=True)
class SweepReport:
    """Sweep benchmark figures; times in seconds.

    Attributes
    ----------
    triangles : int
        Facets of the generated sample.
    step_deg : float
        Step of the direction grid [deg].
    grid_nodes, distinct_directions : int
        Nodes of the grid and the distinct directions among them.
    samples_per_side : int or None
        Fixed points per side, or None for the default shadow pass.
    reflections : str
        The reflection mode, ``"full"``.
    precompute_s, sweep_s : float
        Time of the precompute (view factors, open sky, first calls) and of the sweep [s].
    srp_per_attitude_ms, drag_per_attitude_ms : float
        Time per attitude of each [ms].
    projected_1_deg_s : float
        The sweep's time scaled to a 1-degree grid [s].
    checked_directions : int
        Directions at which the entries are checked against the reference.
    srp_error, drag_error : LoadError
        The entries' errors there.
    dask_attitudes : int
        Attitudes timed on the local Dask cluster (both kinds).
    dask_1_worker_s, dask_2_workers_s, dask_speedup : float
        Their time on one and on two one-thread workers [s], and the ratio.
    dask_identical : bool
        Whether both clusters gave the same entries.
    machine : str
        Architecture, cores and Python version.

    Examples
    --------
    >>> from sunwind.forces.bench import LoadError
    >>> exact = LoadError(0.0, 0.0, 0.0, 0.0, 0.0)
    >>> report = SweepReport(1884, 90.0, 15, 6, None, "full", 3.4, 0.33, 17.6, 36.7, 3500.0, 6, exact, exact,
    ...                      4, 0.19, 0.26, 0.72, True, "x86_64, 2 cores")
    >>> report.to_json()["srp_error"]["force_worst"]
    0.0
    """

    triangles: int
    step_deg: float
    grid_nodes: int
    distinct_directions: int
    samples_per_side: int | None
    reflections: str
    precompute_s: float
    sweep_s: float
    srp_per_attitude_ms: float
    drag_per_attitude_ms: float
    projected_1_deg_s: float
    checked_directions: int
    srp_error: LoadError
    drag_error: LoadError
    dask_attitudes: int
    dask_1_worker_s: float
    dask_2_workers_s: float
    dask_speedup: float
    dask_identical: bool
    machine: str

    def to_json(self) -> dict:
        """Return the report as a JSON-ready dict (the errors as nested dicts).

        Returns
        -------
        dict
            Every field by name.
        """
        return asdict(self)


#: Grid directions, spread over the grid, at which a sweep's entries are checked against the reference.
CHECKED_DIRECTIONS = 24


def _setup_error(model, setup: SrpSetup | DragSetup, directions: np.ndarray) -> LoadError:
    """Error of the entries ``setup`` gives at ``directions`` against the same setup with the default
    shadow pass at :data:`REFERENCE_TOLERANCE` (and, for drag, the gas sampled more finely)."""
    reference = replace(setup, sampling=ShadowSampling(tolerance=REFERENCE_TOLERANCE))
    if isinstance(setup, DragSetup):
        sampled = setup.gas_sampling
        sky = model_sky(model.craft, sampled.sky_rays, setup.settings.cache_dir).rays_per_side
        gas = reference_gas(replace(sampled, sky_rays=sky))
        reference = replace(reference, gas_sampling=gas)
    got, exact = (
        list(zip(records["force_N"], records["torque_Nm"], strict=True))
        for records in (setup.evaluate(model, directions), reference.evaluate(model, directions))
    )
    return LoadError.of(got, exact, model.craft.diagonal_m)


def sweep_benchmark(
    triangles: int = 100_000,
    step_deg: float = 5.0,
    dask_attitudes: int = 64,
    samples: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> SweepReport:
    """Time a whole grid sweep of SRP and drag with full reflections on the generated sample, and Dask.

    Then the speed-up of a local Dask cluster of 2 one-thread workers over 1 on ``dask_attitudes`` of
    the grid's directions (timed once every worker has the model; results checked identical).

    Parameters
    ----------
    triangles : int, optional
        Facets asked of the generated sample.
    step_deg : float, optional
        Step of the direction grid [deg].
    dask_attitudes : int, optional
        Directions of each kind timed on the Dask clusters.
    samples : int, optional
        Fixed points per side; default the default shadow pass.
    progress : callable, optional
        ``progress(done, total)`` hears each attitude of the sweep.

    Returns
    -------
    SweepReport
        The figures.

    Examples
    --------
    The smallest run still starts two local Dask clusters (ten seconds or so):

    >>> report = sweep_benchmark(triangles=2000, step_deg=90.0, dask_attitudes=2)
    >>> report.distinct_directions, report.dask_identical
    (6, True)
    """
    grid = direction_grid(step_deg)
    directions = grid.distinct[0]
    with tempfile.TemporaryDirectory(prefix="sunwind-bench-") as directory:
        files = write_sample_files(Path(directory), triangles)
        model = load(files["obj"], files["toml"])
        craft = model.craft
        full, sampling = ReflectionSettings("full"), ShadowSampling(samples=samples)
        jobs = [
            Job(
                SrpSetup(flux_W_m2=1361.0, sampling=sampling, reflections=full),
                directions,
            ),
            Job(
                DragSetup(
                    speed_m_s=circular_speed(400.0),
                    atmosphere=nrlmsis(400.0),
                    sampling=sampling,
                    reflections=full,
                ),
                directions,
            ),
        ]
        start = time.perf_counter()
        precompute(model, jobs)
        for job in jobs:
            job.setup.evaluate(model, directions[:1])  # compiles what the first attitude compiles
        precompute_s = time.perf_counter() - start
        total = 2 * len(directions)
        timings: dict[str, float] = {}
        start = time.perf_counter()
        for job in jobs:
            began = time.perf_counter()
            offset = len(directions) if job.kind == "drag" else 0
            counted = progress and (lambda done, offset=offset: progress(done + offset, total))
            run_jobs(model, [job], SweepRun(progress=counted))
            timings[job.kind] = time.perf_counter() - began
        sweep_s = time.perf_counter() - start
        checked = directions[:: max(1, len(directions) // CHECKED_DIRECTIONS)][:CHECKED_DIRECTIONS]
        errors = {f"{job.kind}_error": _setup_error(model, job.setup, checked) for job in jobs}
        subset = [Job(job.setup, directions[:dask_attitudes]) for job in jobs]
        pending = [(job, lo, hi) for job in subset for lo, hi in job.chunks(8)]
        one, first = timed_on_local_cluster(model, pending, 1)
        two, second = timed_on_local_cluster(model, pending, 2)
    return SweepReport(
        triangles=craft.n_facets,
        step_deg=grid.step_deg,
        grid_nodes=grid.vectors.shape[0] * grid.vectors.shape[1],
        distinct_directions=len(directions),
        samples_per_side=None if samples is None else level_for_samples(samples) ** 2,
        reflections="full",
        precompute_s=precompute_s,
        sweep_s=sweep_s,
        srp_per_attitude_ms=1e3 * timings["srp"] / len(directions),
        drag_per_attitude_ms=1e3 * timings["drag"] / len(directions),
        projected_1_deg_s=sweep_s * len(direction_grid(1.0).distinct[0]) / len(directions),
        checked_directions=len(checked),
        **errors,
        dask_attitudes=2 * min(dask_attitudes, len(directions)),
        dask_1_worker_s=one,
        dask_2_workers_s=two,
        dask_speedup=one / two,
        dask_identical=all(
            np.array_equal(a[name], b[name]) for a, b in zip(first, second, strict=True) for name in a
        ),
        machine=f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
    )
