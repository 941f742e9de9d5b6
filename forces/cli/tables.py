"""``sunwind sweep`` and ``sunwind plot``: attitude tables for simulators, and their pictures."""

from __future__ import annotations

import math
import sys
import time
import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import click
import numpy as np
import xarray as xr
from numpy.typing import NDArray
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    ProgressColumn,
    TextColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from sunwind.forces.cli.earth import earth_request, earth_term_options, refuse_without_earth
from sunwind.forces.cli.free_stream import flow_options
from sunwind.forces.cli.options import (
    Sun,
    SweptSource,
    drag_only,
    group,
    loaded,
    model_options,
    reference_options,
    reflection_options,
    sampling_options,
    sun_options,
)
from sunwind.forces.cli.outputs import check_distinct, check_writable
from sunwind.forces.cli.report import warn_beyond
from sunwind.forces.cli.runs import check_run, interruptible, progress_bar, run_options, sweep_run
from sunwind.forces.cli.sensitivities import sensitivities_option
from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.export import FORMATS, check_request, output_target, write
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.tables import (
    DEFAULT_STEP,
    DragSetup,
    EarthSetup,
    SrpSetup,
    direction_grid,
    read_attitude_csv,
    sweep,
)
from sunwind.forces.tables.checkpoint import check_place
from sunwind.forces.tables.dataset import GRID_DIMS, kinds_of, one_pose, open_table
from sunwind.forces.tables.engine import check_table_memory
from sunwind.geometry.directions import azel_to_vector, checked_azel
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling


class _RateColumn(ProgressColumn):
    """Attitudes per second."""

    def render(self, task) -> Text:
        return Text(f"{task.speed:.1f} att/s" if task.speed else "", style="progress.data.speed")


def _kinds(srp_flag: bool, drag_flag: bool, earth_flag: bool, fmt: str) -> tuple[str, ...]:
    """The quantities to tabulate: those asked for, else SRP and drag as far as the format holds them
    (said when that leaves one out); the Earth's radiation only when asked for."""
    asked = tuple(k for k, on in (("srp", srp_flag), ("drag", drag_flag), ("earth", earth_flag)) if on)
    allowed = tuple(k for k in FORMATS[fmt].kinds if k != "earth" or earth_flag)
    if not asked:
        if len(allowed) == 1:
            other = "drag" if allowed == ("srp",) else "srp"
            warnings.warn(
                f"{fmt} files hold {allowed[0]} only: {other} is not tabulated "
                f"(for it, sweep with --{other} to another format, e.g. -o NAME.nc)",
                stacklevel=2,
            )
        return allowed
    refused = [k for k in asked if k not in allowed]
    if refused:
        raise InputError(
            f"--format {fmt} holds {' and '.join(allowed)} only, not {refused[0]}",
            hint="write the Earth's radiation as netCDF (-o NAME.nc) or CSV" if "earth" in refused else None,
        )
    return asked


_OUTPUT_OPTIONS = [
    click.option("--srp", "srp_flag", is_flag=True, help="Tabulate SRP (over Sun directions)."),
    click.option("--drag", "drag_flag", is_flag=True, help="Tabulate drag (over flow directions)."),
    click.option(
        "--step",
        type=float,
        default=None,
        help="Grid step [deg] in azimuth (-180..180) and elevation (-90..90); must divide 180 "
        f"[default {DEFAULT_STEP:g}].",
    ),
    click.option(
        "--attitudes",
        "attitude_csv",
        type=click.Path(path_type=Path),
        help="CSV list of attitudes instead of a grid (sun_x,sun_y,sun_z / flow_x,... [qw,qx,qy,qz]).",
    ),
    click.option(
        "--output", "-o", type=click.Path(path_type=Path), required=True, help="Table file to write."
    ),
    click.option(
        "--format",
        "fmt",
        type=click.Choice(list(FORMATS)),
        help="nc, csv (these two hold the earth table too), spad, basilisk (SRP) or tudat (drag) "
        "[default: from the extension; a name without "
        "one gets the format's, an extension of another format is refused].",
    ),
    *earth_term_options(place=False),
    click.option(
        "--earth-altitude",
        type=float,
        metavar="H_KM",
        help="With --earth-radiation: height above the Earth [km] of the earth table.",
    ),
    click.option(
        "--earth-sun",
        nargs=3,
        type=float,
        default=None,
        metavar="X Y Z",
        help="With --earth-radiation: the Sun, fixed in the body frame, while the Earth's direction goes "
        "over the grid (a Sun-pointing spacecraft's view).",
    ),
    sensitivities_option,
]
#: The flags of the earth table's settings, by the names :class:`EarthSetup` gives them in its errors.
_EARTH_FLAGS = {"altitude_km": "--earth-altitude", "sun_vector": "--earth-sun", "cell_deg": "--earth-step"}


@dataclass(frozen=True)
class TableRequest:
    """What table a sweep writes, checked before the mesh is loaded.

    Parameters
    ----------
    kinds : tuple of str
        The quantities tabulated: ``"srp"``, ``"drag"``, ``"earth"``.
    step_deg : float or None
        The grid step of the directions [deg]; None for an attitude list.
    attitudes : pathlib.Path or None
        The attitude list (CSV); None for a grid.
    output : pathlib.Path
        The table file, its extension added when it had none.
    format : str
        The file format, a key of ``FORMATS`` (``"nc"``, ``"csv"``, ``"spad"``, ...).
    earth : EarthSetup or None, optional
        The Earth's radiation settings (checked; the flux and sampling are set later); None: no earth
        table.
    sensitivities : bool, optional
        Also tabulate each kind's derivatives with respect to every material's coefficients (netCDF
        only).

    Examples
    --------
    >>> from pathlib import Path
    >>> request = TableRequest(kinds=("srp", "drag"), step_deg=10.0, attitudes=None,
    ...                        output=Path("table.nc"), format="nc")
    >>> request.kinds, request.earth
    (('srp', 'drag'), None)
    """

    kinds: tuple[str, ...]
    step_deg: float | None
    attitudes: Path | None
    output: Path
    format: str
    earth: EarthSetup | None = None
    sensitivities: bool = False


def _table(values: dict) -> TableRequest:
    """The table flags, checked before the mesh is loaded: the output path (its extension added when it
    has none), the format against the extension, the attitudes and the quantities it can hold."""
    earth = _earth_table(values)
    fmt, output = output_target(values["output"], values["fmt"])
    if values["step"] is not None and values["attitude_csv"] is not None:
        raise InputError("give --step or --attitudes, not both")
    if earth is not None and values["attitude_csv"] is not None:
        raise InputError(
            "--attitudes has no Earth direction: --earth-radiation tabulates a grid of Earth directions",
            hint="sweep --earth-radiation over --step, and the attitude list in another sweep",
        )
    step = values["step"]
    if step is None and values["attitude_csv"] is None:
        step = DEFAULT_STEP
    grid = None if step is None else direction_grid(step, "--step")
    check_request(fmt, step)
    kinds = _kinds(values["srp_flag"], values["drag_flag"], earth is not None, fmt)
    if grid is not None:
        check_table_memory(grid, kinds, "--step")
    if values["sensitivities"] and fmt != "nc":
        raise InputError(
            f"--sensitivities go to a netCDF table; --format {fmt} has no place for them",
            hint="write the table as netCDF (-o NAME.nc)",
        )
    check_writable(output)
    return TableRequest(kinds, step, values["attitude_csv"], output, fmt, earth, values["sensitivities"])


def _earth_table(values: dict) -> EarthSetup | None:
    """The earth table's settings of ``--earth-radiation`` and its flags, taken out of ``values`` and
    checked (None without it, whose flags are then refused); its flux and sampling come later."""
    altitude, sun = values.pop("earth_altitude"), values.pop("earth_sun")
    request = earth_request(values)
    if request is None:
        refuse_without_earth((("--earth-altitude", altitude), ("--earth-sun", sun)))
        return None
    if request.albedo_model == "knocke":
        raise InputError(
            "--albedo-model knocke needs a date and the Earth's pole, which a sweep has not (its Earth goes "
            "round a spacecraft that holds the Sun fixed)",
            hint="sweep the Lambertian Earth (--albedo, --earth-ir); sunwind orbit flies Knocke's model",
        )
    missing = [
        flag
        for flag, value in (("--earth-altitude H_KM", altitude), ("--earth-sun X Y Z", sun))
        if value is None
    ]
    if missing:
        raise InputError(
            f"--earth-radiation in a sweep needs {' and '.join(missing)}",
            hint="e.g. --earth-altitude 500 --earth-sun 1 0 0 (the Sun, fixed in the body frame)",
        )
    try:
        return EarthSetup(
            altitude_km=altitude,
            sun_vector=sun,
            albedo=request.albedo,
            infrared_W_m2=request.earth_ir,
            cell_deg=request.cell_deg,
            cap_method="visibility" if request.cap_method == "auto" else request.cap_method,
            thermal=request.thermal,
        )
    except InputError as error:
        raise error.renamed(_EARTH_FLAGS) from None


@click.command("sweep")
@model_options(gas=True, swept=True)
@sun_options(direction=False)
@flow_options(directed=False)
@reference_options(sizes=True)
@sampling_options
@reflection_options("both")
@group("table", _OUTPUT_OPTIONS, _table)
@group("run", run_options("attitude", "sweep"), check_run)
def sweep_command(
    source: SweptSource,
    sun: Sun,
    flow,
    references: dict,
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    table: TableRequest,
    run: dict,
) -> None:
    """Force and torque over a grid or list of attitudes, written as a table simulators read; with
    --earth-radiation, the Earth's albedo and infrared over Earth directions, the Sun fixed (--earth-sun).

    With --sensitivities each kind also tabulates d force / d coefficient and d torque / d coefficient of
    every material's coefficients (KIND_sensitivity_force_N, KIND_sensitivity_torque_Nm on the
    directions, material, coefficient and component; netCDF tables only)."""
    check_distinct(table.output, source.source.mesh, source.source.materials, table.attitudes)
    stream = flow("drag" in table.kinds)
    point = references["reference_point_m"]
    setups = {"reflections": reflections, "sampling": sampling, "reference_point_m": point}
    setups["sensitivities"] = table.sensitivities
    srp = SrpSetup(flux_W_m2=sun.flux_W_m2, **setups) if "srp" in table.kinds else None
    drag = None
    if "drag" in table.kinds:
        drag = DragSetup(
            speed_m_s=stream.speed_m_s, atmosphere=stream.atmosphere, gas_sampling=stream.sampling, **setups
        )
    earth = None if table.earth is None else replace(table.earth, flux_W_m2=sun.flux_W_m2, **setups)
    attitudes = None if table.attitudes is None else read_attitude_csv(table.attitudes)
    for kind in table.kinds if attitudes is not None else ():
        attitudes.directions(kind)
    hinge_angles = source.hinge_angles
    source = source.source
    several = [glob for glob, angles in (hinge_angles or {}).items() if len(angles) > 1]
    if several and table.format != "nc":
        raise InputError(
            f'--format {table.format} takes one pose; --articulate lists several angles of "{several[0]}"',
            hint="write the table as netCDF (.nc), or sweep one angle per table",
        )
    optics = "srp" in table.kinds or "earth" in table.kinds
    model = loaded((source if optics else drag_only(source)).resolved(), **references)
    if earth is not None:
        try:
            earth.check(model)  # the emissivities and the cells, before any work
        except InputError as error:
            raise error.renamed(_EARTH_FLAGS) from None
    tracking = [hinge.pattern for hinge in model.hinges if hinge.law == "track"]
    if tracking and "srp" in table.kinds and "drag" not in table.kinds:
        print(
            f"sunwind: notice: {', '.join(tracking)} track the Sun: every Sun direction is its own pose "
            "(scene and, with diffuse reflections, view factors made again for each)",
            file=sys.stderr,
        )
    checkpoint = table.output.with_name(table.output.name + ".checkpoint")
    check_place(checkpoint)
    total = _count(table, attitudes) * math.prod(len(a) for a in (hinge_angles or {}).values())
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        _RateColumn(),
        TimeRemainingColumn(),
    )
    start = time.perf_counter()
    with progress_bar(*columns) as bar:
        task = bar.add_task(f"sweep ({', '.join(table.kinds)})", total=total)
        progress = lambda done: bar.update(task, completed=done)  # noqa: E731
        with interruptible(bar, checkpoint):
            result = sweep(
                model,
                srp=srp,
                drag=drag,
                earth=earth,
                step_deg=table.step_deg,
                attitudes=attitudes,
                hinge_angles=hinge_angles,
                run=sweep_run(run, checkpoint, progress),
            )
    seconds = time.perf_counter() - start
    written = write(result, table.output, table.format)
    kinds = ", ".join(table.kinds)
    print(f"sunwind sweep: {model.craft.source}: {total} attitudes ({kinds}) in {seconds:.1f} s")
    estimates = table_estimates(result, table.step_deg)
    for kind, (force, torque) in estimates.items():
        print(f"  shadow error     {kind} worst {ErrorEstimate(float(force.max()), float(torque.max()))}")
    for path in written:
        print(f"  wrote {path}")
    warn_beyond(estimates, sampling.tolerance, "attitudes")


def table_estimates(table: xr.Dataset, step_deg: float | None) -> dict[str, tuple[NDArray, NDArray]]:
    """Collect the shadow error estimates of a sweep's table, per quantity that has them.

    Parameters
    ----------
    table : xarray.Dataset
        The sweep's table.
    step_deg : float or None
        Its grid step [deg] (each direction the grid shares between nodes is taken once); None for an
        attitude list (every row).

    Returns
    -------
    dict of str to (ndarray, ndarray)
        By quantity, the relative force and torque error estimates of each distinct attitude (every
        pose's), (n,) each.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> force, torque = table_estimates(table, 90.0)["srp"]
    >>> force.shape  # the six distinct directions of a 90-degree grid
    (6,)
    """
    out = {}
    for kind in kinds_of(table):
        if f"{kind}_error_estimate_force" in table:
            force, torque = (table[f"{kind}_error_estimate_{what}"] for what in ("force", "torque"))
            out[kind] = (_distinct(force, kind, step_deg), _distinct(torque, kind, step_deg))
    return out


def _distinct(values: xr.DataArray, kind: str, step_deg: float | None) -> NDArray:
    """``values`` of a table's ``kind`` at its distinct attitudes, flat (a list's rows are all distinct)."""
    if step_deg is None:
        return values.values.ravel()
    grid = direction_grid(step_deg)
    _, first = np.unique(grid.distinct[1], return_index=True)
    return values.transpose(..., *GRID_DIMS[kind]).values.reshape(-1, grid.nodes)[:, first].ravel()


def _count(table: TableRequest, attitudes) -> int:
    """Attitudes the sweep evaluates (distinct grid directions per quantity, or list rows)."""
    per_kind = len(attitudes) if attitudes is not None else len(direction_grid(table.step_deg).distinct[0])
    return per_kind * len(table.kinds)


@click.command()
@click.argument("table_path", metavar="TABLE", type=click.Path(path_type=Path))
@click.option(
    "--output",
    "-o",
    type=click.Path(path_type=Path, file_okay=False),
    help="Directory for the PNGs [default: TABLE's].",
)
@click.option(
    "--at-azel",
    nargs=2,
    type=float,
    default=None,
    metavar="AZ EL",
    help="Sun / flow direction of the 3-D pressure views [default: where each force is largest].",
)
@click.option(
    "--view-azel",
    nargs=2,
    type=float,
    default=None,
    metavar="AZ EL",
    help="Camera azimuth and elevation [deg] of the 3-D views, body frame [default: from the Sun / "
    "upstream, the loaded side facing you].",
)
@click.option("--no-view", is_flag=True, help="Maps only, no 3-D views (which reload the mesh).")
def plot(table_path: Path, output: Path | None, at_azel, view_azel, no_view: bool) -> None:
    """PNG maps of every force and torque component of a table, and 3-D views of facet pressure."""
    from sunwind.forces.tables.plots import plot_table
    from sunwind.forces.tables.pressure_views import plot_pressure_views, view_model

    direction = None if at_azel is None else azel_to_vector(*at_azel, "--at-azel")
    camera = None if view_azel is None else checked_azel(*view_azel, "--view-azel")
    table = one_pose(
        open_table(table_path),
        "sunwind plot",
        "plot one angle: table.sel({DIMENSION: ANGLE}) with xarray, written by sunwind.forces.export.write",
    )
    model = None if no_view else view_model(table)  # its checks before any file is drawn
    directory = output if output is not None else (table_path.parent if str(table_path.parent) else Path("."))
    directory.mkdir(parents=True, exist_ok=True)
    written = list(plot_table(table, directory, table_path.stem))
    if model is not None:
        written += plot_pressure_views(table, directory, table_path.stem, direction, model, camera)
    print(f"sunwind plot: {table_path}")
    for path in written:
        print(f"  wrote {path}")
