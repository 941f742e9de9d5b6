"""``sunwind sweep`` and ``sunwind plot``: attitude tables for simulators, and their pictures."""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import click
import numpy as np
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    TextColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from sunwind.forces.cli.app import (
    _AIR_FLAGS,
    _FLOW_FLAGS,
    _GAS_FLAGS,
    app,
    flow_options,
    gas_options,
    loaded,
    model_options,
    model_recipe,
    reflection_settings,
    view_factor_options,
)
from sunwind.geometry.errors import InputError

#: Output formats and the file extensions that choose them.
FORMATS = {"nc": ".nc", "csv": ".csv", "spad": ".spo", "basilisk": ".xml", "tudat": None}
#: Quantities each format can hold.
FORMAT_KINDS = {
    "nc": ("srp", "drag"),
    "csv": ("srp", "drag"),
    "spad": ("srp", "drag"),
    "basilisk": ("srp",),
    "tudat": ("drag",),
}
#: Default grid step [deg].
DEFAULT_STEP = 10.0


class _RateColumn(ProgressColumn):
    """Attitudes per second."""

    def render(self, task) -> Text:
        return Text(f"{task.speed:.1f} att/s" if task.speed else "", style="progress.data.speed")


def output_format(path: Path, given: str | None) -> str:
    """The format ``--format`` names, else the one the extension of ``path`` says."""
    if given is not None:
        return given
    by_extension = {ext: name for name, ext in FORMATS.items() if ext}
    if path.suffix.lower() not in by_extension:
        raise InputError(
            f"cannot tell the format from the extension {path.suffix!r}",
            path=str(path),
            hint="use .nc, .csv, .spo (SPAD) or .xml (Basilisk), or give --format nc|csv|spad|basilisk|tudat",
        )
    return by_extension[path.suffix.lower()]


def check_writable(path: Path) -> None:
    """Fail now, before any work, when ``path`` cannot be written."""
    directory = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise InputError("the output is a directory", path=str(path), hint="give a file name")
    if not directory.is_dir():
        raise InputError("the output's directory does not exist", path=str(path), hint="create it first")
    try:
        with tempfile.NamedTemporaryFile(dir=directory, prefix=".sunwind-write-test-"):
            pass
    except OSError as error:
        raise InputError(f"cannot write here: {error.strerror}", path=str(path)) from None


def _kinds(srp_flag: bool, drag_flag: bool, fmt: str) -> tuple[str, ...]:
    asked = tuple(k for k, on in (("srp", srp_flag), ("drag", drag_flag)) if on)
    allowed = FORMAT_KINDS[fmt]
    if not asked:
        return allowed
    refused = [k for k in asked if k not in allowed]
    if refused:
        raise InputError(f"--format {fmt} holds {' and '.join(allowed)} only, not {refused[0]}")
    return asked


def _free_stream(options: dict, drag_wanted: bool):
    """Pop flow, atmosphere and gas flags: ``(speed [m/s], atmosphere, gas flags)``; the first two
    None without drag."""
    from sunwind.forces.gas.flow import AtmosphereOptions, FlowOptions, atmosphere, flow_speed
    from sunwind.geometry.materials import GasSurface

    gas = {key: value for key in _GAS_FLAGS if (value := options.pop(key)) is not None}
    if gas:
        GasSurface.checked("command line", gas)
    flow = FlowOptions(*(options.pop(key) for key in _FLOW_FLAGS))
    air = AtmosphereOptions(**{name: options.pop(flag) for flag, name in _AIR_FLAGS.items()})
    if flow.velocity is not None or flow.azel_deg is not None:
        raise InputError(
            "a sweep takes its flow directions from the grid or the attitude list",
            hint="drop --velocity/--flow-azel; give --speed or --altitude for the speed",
        )
    if not drag_wanted:
        return None, None, gas
    if flow.corotating and flow.speed_m_s is not None:
        raise InputError(
            "--corotating changes the circular-orbit speed at --altitude only", hint="drop --speed"
        )
    return flow_speed(flow, air), atmosphere(air), gas


@app.command()
@model_options
@gas_options
@flow_options
@click.option("--srp", "srp_flag", is_flag=True, help="Tabulate SRP (over Sun directions).")
@click.option("--drag", "drag_flag", is_flag=True, help="Tabulate drag (over flow directions).")
@click.option(
    "--step",
    type=float,
    default=DEFAULT_STEP,
    show_default=True,
    help="Grid step [deg] in azimuth (-180..180) and elevation (-90..90); must divide 180.",
)
@click.option(
    "--attitudes",
    "attitude_csv",
    type=click.Path(path_type=Path),
    help="CSV list of attitudes instead of a grid (sun_x,sun_y,sun_z / flow_x,... [qw,qx,qy,qz]).",
)
@click.option("--flux", type=float, help="Solar flux [W/m^2] [default 1361, i.e. 1 au].")
@click.option("--distance-au", type=float, help="Distance from the Sun [au].")
@click.option(
    "--ref-point", nargs=3, type=float, default=None, metavar="X Y Z", help="Torque reference point [m]."
)
@click.option("--samples", type=int, help="Shadow-ray points per facet side [default: adaptive].")
@click.option("--tolerance", type=float, default=1e-3, show_default=True, help="Adaptive sampling threshold.")
@click.option(
    "--reflections",
    type=click.Choice(["none", "full", "auto"]),
    default="auto",
    show_default=True,
    help="Inter-reflection of light and re-emitted molecules (auto: each by its own K_IS).",
)
@view_factor_options
@click.option("--output", "-o", type=click.Path(path_type=Path), required=True, help="Table file to write.")
@click.option(
    "--format",
    "fmt",
    type=click.Choice(list(FORMATS)),
    help="nc, csv, spad, basilisk (SRP) or tudat (drag) [default: from the extension].",
)
@click.option("--resume", is_flag=True, help="Continue an interrupted sweep from its checkpoint.")
@click.option(
    "--scheduler",
    is_flag=False,
    flag_value="local",
    default=None,
    metavar="[ADDRESS]",
    help="Run on Dask: a scheduler address, or alone for a local cluster.",
)
@click.option("--workers", type=int, help="Threads per attitude; with --scheduler alone, local Dask workers.")
@click.option("--chunk", type=int, default=64, show_default=True, help="Attitudes per checkpoint chunk.")
def sweep(
    srp_flag,
    drag_flag,
    step,
    attitude_csv,
    flux,
    distance_au,
    ref_point,
    samples,
    tolerance,
    reflections,
    view_rays,
    cache_dir,
    no_cache,
    output,
    fmt,
    resume,
    scheduler,
    workers,
    chunk,
    **options,
) -> None:
    """Force and torque over a grid or list of attitudes, written as a table simulators read."""
    from sunwind.forces.radiation.law import radiation_pressure, solar_flux
    from sunwind.forces.tables.attitudes import direction_grid, read_attitude_csv
    from sunwind.forces.tables.dataset import grid_table, list_table
    from sunwind.forces.tables.sweep import DragSetup, Job, SrpSetup, run_sweep
    from sunwind.geometry.directions import finite_point
    from sunwind.geometry.rays.shadows import level_for_samples

    # everything is checked before the mesh is loaded, the output path included
    fmt = output_format(output, fmt)
    kinds = _kinds(srp_flag, drag_flag, fmt)
    check_writable(output)
    flux = solar_flux(flux, distance_au)
    if ref_point is not None:
        finite_point(ref_point, "--ref-point")
    if samples is not None:
        level_for_samples(samples)
    if not 0 < tolerance < 1:
        raise InputError(f"--tolerance {tolerance} must lie in (0, 1)")
    speed, air, gas = _free_stream(options, "drag" in kinds)
    sizes = {"reference_area_m2": options.pop("ref_area"), "reference_length_m": options.pop("ref_length")}
    settings = reflection_settings(reflections, 1e-6, 32, view_rays, cache_dir, no_cache)
    if attitude_csv is not None:
        attitudes, grids = read_attitude_csv(attitude_csv), None
        directions = {"srp": attitudes.sun_vectors, "drag": attitudes.flow_vectors}
        missing = [kind for kind in kinds if directions[kind] is None]
        if missing:
            column = "sun_x,sun_y,sun_z" if missing[0] == "srp" else "flow_x,flow_y,flow_z"
            raise InputError(
                f"the attitude list has no {column} columns for {missing[0]}", path=str(attitude_csv)
            )
    else:
        grid = direction_grid(step)
        grids = dict.fromkeys(kinds, grid)
        directions = {kind: grid.distinct[0] for kind in kinds}
    recipe = model_recipe(options, gas)
    recipe = type(recipe)(**{**recipe.__dict__, "mesh": str(Path(recipe.mesh).resolve())})
    if recipe.materials is not None:
        recipe = type(recipe)(**{**recipe.__dict__, "materials": str(Path(recipe.materials).resolve())})
    craft = loaded(recipe)
    point = None if ref_point is None else tuple(ref_point)
    common = {"reference_point_m": point, "samples": samples, "tolerance": tolerance, "reflections": settings}
    jobs = []
    if "srp" in kinds:
        jobs.append(Job("srp", directions["srp"], SrpSetup(flux, **common)))
    if "drag" in kinds:
        jobs.append(Job("drag", directions["drag"], DragSetup(speed, air, **common, **sizes)))
    total = sum(len(job.directions) for job in jobs)
    checkpoint = output.with_name(output.name + ".checkpoint")
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        _RateColumn(),
        TimeRemainingColumn(),
    )
    start = time.perf_counter()
    with Progress(*columns, transient=True, console=None) as bar:
        task = bar.add_task(f"sweep ({', '.join(kinds)})", total=total)
        records = run_sweep(
            recipe,
            jobs,
            craft=None if scheduler else craft,
            chunk=chunk,
            checkpoint=checkpoint,
            resume=resume,
            scheduler=scheduler,
            workers=workers,
            progress=lambda done: bar.update(task, completed=done),
        )
    seconds = time.perf_counter() - start
    attrs = _table_attributes(craft, recipe, jobs, flux, radiation_pressure(flux), step if grids else None)
    table = grid_table(records, grids, attrs) if grids else list_table(records, attitudes, attrs)
    written = write_table(table, output, fmt)
    print(f"sunwind sweep: {craft.source}: {total} attitudes ({', '.join(kinds)}) in {seconds:.1f} s")
    for path in written:
        print(f"  wrote {path}")


def _table_attributes(craft, recipe, jobs, flux: float, pressure: float, step: float | None) -> dict:
    """The table's global attributes: frame, reference point, environment, provenance."""
    from importlib.metadata import version

    from sunwind.forces.drag import reference_sizes
    from sunwind.forces.results import FRAME
    from sunwind.forces.srp import reference_point

    setup = jobs[0].setup
    point, name = reference_point(craft, setup.reference_point_m)
    attrs = {
        "title": f"sunwind attitude table of {Path(recipe.mesh).name}",
        "frame": FRAME,
        "reference_point_m": point,
        "reference_point": name,
        "grid_step_deg": step,
        "samples": "adaptive" if setup.samples is None else setup.samples,
        "tolerance": setup.tolerance,
        "reflections": setup.reflections.mode,
        "mesh": recipe.mesh,
        "materials": recipe.materials,
        "unit": recipe.unit,
        "length_unit": craft.unit,
        "two_sided": ",".join(recipe.two_sided),
        **recipe.digests(),
        "sunwind_version": version("sunwind"),
    }
    if recipe.uniform is not None:
        attrs["uniform_material"] = {
            "reflectivity": recipe.uniform.reflectivity,
            "specular_fraction": recipe.uniform.specular_fraction,
            "transmissivity": recipe.uniform.transmissivity,
        }
    if recipe.gas:
        attrs["gas_override"] = dict(recipe.gas)
    for job in jobs:
        if job.kind == "srp":
            attrs |= {"flux_W_m2": flux, "pressure_Pa": pressure}
        else:
            drag_setup = job.setup
            air = drag_setup.atmosphere
            area, length = reference_sizes(craft, drag_setup.reference_area_m2, drag_setup.reference_length_m)
            attrs |= {
                "speed_m_s": drag_setup.speed_m_s,
                "density_kg_m3": air.density_kg_m3,
                "temperature_K": air.temperature_K,
                "dynamic_pressure_Pa": 0.5 * air.density_kg_m3 * drag_setup.speed_m_s**2,
                "atmosphere": air.to_json(),
                "reference_area_m2": area,
                "reference_length_m": length,
            }
    return attrs


def write_table(table, output: Path, fmt: str) -> list[Path]:
    """Write ``table`` in ``fmt``; the files written."""
    from sunwind.forces.tables.dataset import kinds_of, write_csv, write_netcdf

    if fmt == "nc":
        return [write_netcdf(table, output)]
    if fmt == "csv":
        return write_csv(table, output)
    if fmt == "spad":
        from sunwind.forces.export.spad import spad_paths, write_spad

        paths = spad_paths(output, kinds_of(table))
        return [write_spad(table, paths[kind], kind) for kind in kinds_of(table)]
    if fmt == "basilisk":
        from sunwind.forces.export.basilisk import write_basilisk

        return [write_basilisk(table, output)]
    from sunwind.forces.export.tudat import write_tudat

    return list(write_tudat(table, output))


@app.command()
@click.argument("table_path", metavar="TABLE", type=click.Path(path_type=Path))
@click.option(
    "--output",
    "-o",
    type=click.Path(path_type=Path, file_okay=False),
    help="Directory for the PNGs [default: TABLE's].",
)
@click.option(
    "--view-azel",
    nargs=2,
    type=float,
    default=None,
    metavar="AZ EL",
    help="Attitude of the 3-D pressure view [default: where the table's force is largest].",
)
@click.option("--no-view", is_flag=True, help="Maps only, no 3-D view (which reloads the mesh).")
def plot(table_path, output, view_azel, no_view) -> None:
    """PNG maps of every force and torque component of a table, and a 3-D view of facet pressure."""
    from sunwind.forces.tables.dataset import open_table
    from sunwind.forces.tables.plots import plot_table

    table = open_table(table_path)
    directory = output if output is not None else (table_path.parent if str(table_path.parent) else Path("."))
    directory.mkdir(parents=True, exist_ok=True)
    written = list(plot_table(table, directory))
    if not no_view:
        written.append(_pressure_view(table, table_path, directory, view_azel))
    print(f"sunwind plot: {table_path}")
    for path in written:
        print(f"  wrote {path}")


def _pressure_view(table, table_path: Path, directory: Path, view_azel) -> Path:
    """3-D view of the spacecraft coloured by facet pressure at one attitude of the table's first quantity."""
    import json

    from sunwind.forces.tables.dataset import DIRECTION, kinds_of
    from sunwind.forces.tables.plots import plot_facet_pressure
    from sunwind.forces.tables.sweep import ModelRecipe
    from sunwind.geometry.directions import azel_to_vector, vector_to_azel
    from sunwind.geometry.materials import Material

    kind = kinds_of(table)[0]
    if not Path(table.attrs["mesh"]).exists():
        raise InputError(
            f"the table's mesh {table.attrs['mesh']} is not there for the 3-D view", hint="use --no-view"
        )
    uniform = None
    if "uniform_material" in table.attrs:
        uniform = Material.checked("uniform", json.loads(table.attrs["uniform_material"]), "table")
    two_sided = tuple(g for g in str(table.attrs.get("two_sided", "")).split(",") if g)
    gas = tuple(json.loads(table.attrs["gas_override"]).items()) if "gas_override" in table.attrs else ()
    recipe = ModelRecipe(
        table.attrs["mesh"], table.attrs.get("materials"), table.attrs.get("unit"), uniform, two_sided, gas
    )
    craft = loaded(recipe)
    if view_azel is None:
        force = np.linalg.norm(table[f"{kind}_force_N"].values, axis=-1)
        at = np.unravel_index(int(np.argmax(force)), force.shape)
        direction = table[DIRECTION[kind]].values[at]
    else:
        direction = azel_to_vector(*view_azel, "--view-azel")
    reference = np.asarray(table.attrs["reference_point_m"], dtype=np.float64)
    if kind == "srp":
        from sunwind.forces.srp import srp

        result = srp(
            craft,
            direction,
            flux_W_m2=float(table.attrs["flux_W_m2"]),
            reference_point_m=reference,
            reflections="none",
        )
        force_N = result.facet_force_N
    else:
        from sunwind.forces.drag import drag
        from sunwind.forces.gas.atmosphere import Atmosphere

        air = Atmosphere.from_json(json.loads(table.attrs["atmosphere"]))
        result = drag(
            craft,
            float(table.attrs["speed_m_s"]) * direction,
            air,
            reference_point_m=reference,
            reflections="none",
        )
        force_N = np.zeros((craft.n_facets, 3))
        np.add.at(force_N, craft.side_facet, result.side_force_N)
    pressure = np.linalg.norm(force_N, axis=1) / craft.facet_areas
    az, el = vector_to_azel(direction)
    path = directory / f"{table_path.stem}.{kind}.pressure_az{az:+.0f}_el{el:+.0f}.png"
    return plot_facet_pressure(craft, pressure, direction, path)
