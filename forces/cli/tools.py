"""``sunwind bench`` and ``sunwind validate``: how fast, and how right, on this machine."""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path

import click
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

from sunwind.forces.bench import REFERENCE_GAS_FACTORS, REFERENCE_TOLERANCE, benchmark
from sunwind.forces.cli.options import given, group
from sunwind.forces.cli.runs import progress_bar
from sunwind.forces.sweep_bench import sweep_benchmark
from sunwind.forces.tables import direction_grid
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import build_spacecraft, load_spacecraft
from sunwind.meshes.samples import sample_spacecraft


@click.command()
@click.option(
    "--mesh",
    "mesh_path",
    type=click.Path(path_type=Path),
    help="Benchmark this mesh instead of the generated sample (give its materials too).",
)
@click.option("--materials", "-m", type=click.Path(path_type=Path), help="Materials file for --mesh.")
@click.option(
    "--triangles",
    type=int,
    default=100_000,
    show_default=True,
    help="Size of the generated sample spacecraft.",
)
@click.option("--attitudes", type=int, default=50, show_default=True, help="Sun directions timed.")
@click.option(
    "--samples",
    type=int,
    help="Fixed shadow-ray points per side timed beside the default pass [default: 1]; with --sweep, the "
    "sweep's sampling [default: the default pass].",
)
@group("what", [
    click.option("--sweep", "sweep_flag", is_flag=True,
                 help="Time a whole grid sweep (SRP and drag, full reflections) and Dask 2 workers over 1 "
                 "instead."),
    click.option("--step", type=float, default=5.0, show_default=True, help="Grid step of --sweep [deg]."),
    click.option("--orbit", "orbit_flag", is_flag=True,
                 help="Time orbit steps instead: LEO with SRP and drag, each alone, and GEO."),
    click.option("--earth", "earth_flag", is_flag=True,
                 help="Time the Earth's albedo and infrared instead (full reflections): the visibility's "
                 "build, time per attitude against SRP, and the error against 2.5 deg cells."),
    click.option("--places", type=int, default=20, show_default=True, help="Places of --earth."),
], lambda values: _benchmark(**values))  # fmt: skip
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def bench(mesh_path, materials, triangles, attitudes, samples, what: Benchmark, as_json) -> None:
    """Time SRP per attitude (direct against raw Embree on the same rays, then with full reflections)
    and free-molecular drag per attitude against SRP with the same reflection setting; or, with
    --sweep, a whole attitude sweep of the generated sample."""
    _check_model(mesh_path, materials, attitudes, what)
    if what.kind == "sweep":
        _bench_sweep(triangles, what.step, samples, as_json)
        return
    start = time.perf_counter()
    if mesh_path is not None:
        craft = load_spacecraft(mesh_path, materials)
    else:
        craft = build_spacecraft(sample_spacecraft(triangles))
    load_s = time.perf_counter() - start
    if what.kind == "orbit":
        _bench_orbit(craft, as_json)
        return
    if what.kind == "earth":
        _bench_earth(craft, what.places, as_json)
        return
    with _progress_bar(as_json) as bar:
        task = bar.add_task("timing attitudes", total=attitudes)
        report = benchmark(
            craft,
            attitudes,
            1 if samples is None else samples,
            load_s=load_s,
            progress=lambda stage, done, total: bar.update(
                task, description=stage, completed=done, total=total
            ),
        )
    if as_json:
        print(json.dumps({"mesh": craft.source, **report.to_json()}, indent=2))
        return
    print(f"sunwind bench: {craft.source} ({report.triangles} triangles, {report.sides} sides)")
    print(f"  machine                 {report.machine}; Embree on {report.threads} threads")
    print(f"  load / scene build      {report.load_s:.2f} s / {report.scene_build_s:.3f} s")
    print(f"  first call (compile)    {report.first_call_s:.2f} s")
    fixed = f"{report.samples_per_side} pt/side"
    print(
        f"  direct SRP, default     {report.default_ms:.2f} ms per attitude (median "
        f"{report.default_median_ms:.2f}), {report.attitudes} attitudes, "
        f"{report.default_rays_per_attitude:.0f} rays"
    )
    print(f"{'':26}{report.default_error}")
    print(
        f"  direct SRP, {fixed:<12}{report.fixed_ms:.2f} ms per attitude "
        f"(median {report.fixed_median_ms:.2f}), {report.fixed_rays_per_attitude:.0f} rays, "
        f"{report.fixed_rays_per_s / 1e6:.2f} M rays/s"
    )
    print(f"{'':26}{report.fixed_error}")
    print(f"  default / {fixed:<14}{report.default_over_fixed:.2f}x (medians)")
    same = "the same results" if report.batch_identical else "results that DIFFER from"
    print(
        f"  batch of {report.attitudes:<15}{report.default_batch_ms:.2f} ms per attitude, {fixed} "
        f"{report.fixed_batch_ms:.2f} ms: {report.batch_default_over_fixed:.2f}x; attitudes side by "
        f"side, {same} one at a time"
    )
    print(
        f"  raw Embree, {fixed:<12}{report.raw_embree_ms:.2f} ms per attitude, "
        f"{report.raw_embree_rays_per_s / 1e6:.2f} M rays/s; overhead {report.overhead:.2f}x"
    )
    print(
        f"  view factors            {report.view_factor_s:.1f} s once per model "
        f"({report.view_factor_rays_per_side} rays per side), {report.view_factor_MB:.0f} MB, "
        f"peak memory {report.view_factor_peak_MB:.0f} MB"
    )
    print(f"  diffuse balance setup   {report.exchange_setup_s:.2f} s once per model and materials")
    print(
        f"  full reflections        {report.full_ms:.2f} ms per attitude "
        f"(median {report.full_median_ms:.2f}), {report.full_over_direct:.2f}x direct-only, "
        f"{report.beam_rays_per_attitude:.0f} beam rays"
    )
    print(f"{'':26}{report.full_error}")
    print(f"  full refl., {fixed:<12}{report.fixed_full_ms:.2f} ms per attitude")
    print(f"{'':26}{report.fixed_full_error}")
    print(
        f"  open sky (drag)         {report.sky_s:.1f} s once per model "
        f"({report.sky_rays_per_side} rays per side), {report.sky_MB:.0f} MB"
    )
    print(
        f"  drag, no re-emission    {report.drag_ms:.2f} ms per attitude (median), "
        f"{report.drag_over_srp:.2f}x SRP direct-only"
    )
    print(f"{'':26}{report.drag_error}")
    print(f"  drag, {fixed:<18}{report.fixed_drag_ms:.2f} ms per attitude (median)")
    print(f"{'':26}{report.fixed_drag_error}")
    print(
        f"  drag, full re-emission  {report.drag_full_ms:.2f} ms per attitude (median), "
        f"{report.drag_full_over_srp_full:.2f}x SRP with full reflections"
    )
    print(f"{'':26}{report.drag_full_error}")
    print(f"  errors against          the default at tolerance {REFERENCE_TOLERANCE:g} (10x tighter)")
    sky, core, chains = REFERENCE_GAS_FACTORS
    print(f"{'':26}drag: also {sky}x the sky rays, {core}x the core rays, {chains}x the chain molecules")
    print(f"  peak memory             {report.peak_memory_MB:.0f} MB")


#: Most attitudes ``bench`` times (a minute or two on a large model).
MOST_ATTITUDES = 10_000


@dataclass(frozen=True)
class Benchmark:
    """What ``sunwind bench`` times.

    Parameters
    ----------
    kind : {"attitudes", "sweep", "orbit", "earth"}
        Single attitudes under every setting, a sweep, an orbit, or the Earth's radiation.
    step : float
        The sweep's grid step [deg] (``--step``; read by ``"sweep"`` only).
    places : int
        Places of ``"earth"`` (``--places``).

    Examples
    --------
    >>> Benchmark(kind="sweep", step=15.0, places=20)
    Benchmark(kind='sweep', step=15.0, places=20)
    """

    kind: str
    step: float
    places: int


def _benchmark(sweep_flag: bool, step: float, orbit_flag: bool, earth_flag: bool, places: int) -> Benchmark:
    """The :class:`Benchmark` of ``--sweep``, ``--step``, ``--orbit``, ``--earth`` and ``--places``, checked
    together."""
    if sweep_flag + orbit_flag + earth_flag > 1:
        raise InputError("--sweep, --orbit and --earth are three benchmarks", hint="give one of them")
    if given("step") and not sweep_flag:
        raise InputError("--step is the grid step of --sweep", hint="add --sweep, or drop --step")
    if given("places") and not earth_flag:
        raise InputError("--places is the place count of --earth", hint="add --earth, or drop --places")
    if not 1 <= places <= 1000:
        raise InputError(f"--places {places} must be from 1 to 1000")
    kind = "sweep" if sweep_flag else "orbit" if orbit_flag else "earth" if earth_flag else "attitudes"
    return Benchmark(kind, step, places)


def _check_model(mesh_path: Path | None, materials: Path | None, attitudes: int, what: Benchmark) -> None:
    """Refuse a model or an attitude count ``bench`` would not use or could not time."""
    if not 1 <= attitudes <= MOST_ATTITUDES:
        raise InputError(f"--attitudes {attitudes} must be from 1 to {MOST_ATTITUDES}")
    if what.kind == "sweep" and mesh_path is not None:
        raise InputError(
            "--sweep times the generated sample", hint="drop --mesh, or --sweep to time the mesh"
        )
    if (mesh_path is None) != (materials is None):
        raise InputError(
            "--mesh and its materials -m go together", hint="give both, or neither for the sample"
        )


def _progress_bar(as_json: bool) -> Progress:
    """The benchmark's progress bar on stderr (stage, bar, count, time left); none with ``--json``."""
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeRemainingColumn(),
    )
    return progress_bar(*columns, hidden=as_json)


def _bench_orbit(craft, as_json: bool) -> None:
    """``sunwind bench --orbit``: run and print :func:`sunwind.forces.orbit.bench.orbit_benchmark`."""
    from sunwind.forces.model import Model
    from sunwind.forces.orbit.bench import EPOCH, orbit_benchmark

    report = orbit_benchmark(Model(craft))
    if as_json:
        print(json.dumps({"mesh": craft.source, **report.to_json()}, indent=2))
        return
    print(f"sunwind bench --orbit: {craft.source} ({report.triangles} triangles); {report.machine}")
    print(f"  nadir pointing from {EPOCH}, defaults of sunwind orbit, {report.steps} steps timed after two")
    for name, ms in report.ms_per_step.items():
        print(f"  {name:<22}  {ms:.1f} ms per step")
    print("  error of a step         that of srp and drag at one attitude (sunwind bench)")


def _bench_earth(craft, places: int, as_json: bool) -> None:
    """``sunwind bench --earth``: run and print :func:`sunwind.forces.planet_bench.earth_benchmark`."""
    from sunwind.forces.model import Model
    from sunwind.forces.planet_bench import REFERENCE_STEP_DEG, earth_benchmark

    with _progress_bar(as_json) as bar:
        task = bar.add_task("building the visibility", total=None)
        report = earth_benchmark(
            Model(craft),
            places,
            progress=lambda stage, done, total: bar.update(
                task, description=stage, completed=done, total=total
            ),
        )
    if as_json:
        print(json.dumps({"mesh": craft.source, **report.to_json()}, indent=2))
        return
    print(f"sunwind bench --earth: {craft.source} ({report.triangles} triangles, {report.sides} sides)")
    print(f"  machine                 {report.machine}; full reflections, {report.places} places 500 km up")
    print(
        f"  visibility              {report.build_s:.1f} s ({report.visibility_origin}), {report.grid_nodes} "
        f"directions, {report.visibility_MB:.0f} MB"
    )
    print(
        f"  albedo + infrared       {report.earth_ms:.1f} ms per attitude (median), "
        f"{report.earth_over_srp:.1f}x SRP ({report.srp_ms:.1f} ms)"
    )
    print(f"{'':26}{report.error}")
    print(f"{'':26}torque {report.torque_scaled_worst:.1e} worst of max(|M|, 0.01 |F| L)")
    low, high = report.estimate_over_error
    print(f"  error estimate          {low:.1f} to {high:.1f} times the force error")
    seconds = report.reference_ms / 1e3
    print(f"  errors against          cells of {REFERENCE_STEP_DEG:g} deg, {seconds:.1f} s per attitude")


def _bench_sweep(triangles: int, step: float, samples: int | None, as_json: bool) -> None:
    """``sunwind bench --sweep``: run and print :func:`sunwind.forces.sweep_bench.sweep_benchmark`."""
    direction_grid(step)
    with _progress_bar(as_json) as bar:
        task = bar.add_task("sweeping", total=None)
        report = sweep_benchmark(
            triangles,
            step,
            samples=samples,
            progress=lambda done, total: bar.update(task, completed=done, total=total),
        )
    if as_json:
        print(json.dumps(report.to_json(), indent=2))
        return
    print(f"sunwind bench --sweep: generated sample, {report.triangles} triangles; {report.machine}")
    print(
        f"  grid                    {report.step_deg:g} deg: {report.grid_nodes} nodes, "
        f"{report.distinct_directions} distinct directions, "
        f"{'default shadows' if report.samples_per_side is None else f'{report.samples_per_side} pt/side'}, "
        f"reflections {report.reflections}"
    )
    print(f"  precompute              {report.precompute_s:.1f} s (view factors, exchange, first calls)")
    print(
        f"  sweep SRP + drag        {report.sweep_s:.1f} s ({report.srp_per_attitude_ms:.1f} ms SRP, "
        f"{report.drag_per_attitude_ms:.1f} ms drag per attitude)"
    )
    minutes = report.projected_1_deg_s / 60
    print(f"  1-degree grid           {minutes:.0f} min projected (same time per direction)")
    print(f"  SRP entries             {report.srp_error}")
    print(f"  drag entries            {report.drag_error}")
    print(
        f"  errors against          the default at tolerance {REFERENCE_TOLERANCE:g} at "
        f"{report.checked_directions} grid directions"
    )
    print(
        f"  Dask, {report.dask_attitudes} attitudes      1 worker {report.dask_1_worker_s:.1f} s, "
        f"2 workers {report.dask_2_workers_s:.1f} s: speed-up {report.dask_speedup:.2f}x "
        f"(results identical: {report.dask_identical})"
    )


@click.command()
@click.option(
    "--quick", is_flag=True, help="A subset of the cases, the tracers at fewer particles (same limits)."
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object: every check and its measures.")
def validate(quick: bool, as_json: bool) -> None:
    """Run every validation case (SRP, shadows, reflections, drag, TPMC) against its reference and print
    each case's worst check; ends with 'N passed, M failed' and exits 1 if any failed."""
    from sunwind.validation.runner import report  # the validation sits above forces

    if report(quick, as_json):
        raise SystemExit(1)
