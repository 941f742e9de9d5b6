"""``sunwind attitude``: the Sun and nadir directions (and the attitude) that reproduce measured
heat fluxes of sensor parts, row by row (METHOD.md "Attitude from heat fluxes")."""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import click
import numpy as np
from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeRemainingColumn

from sunwind.forces.cli.options import group, json_option, loaded, model_options, reflection_options
from sunwind.forces.cli.outputs import check_distinct, check_writable
from sunwind.forces.cli.runs import check_run, interruptible, progress_bar, run_options, sweep_run
from sunwind.forces.export.atomic import atomic_text
from sunwind.forces.model import ModelSource
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.radiation.law import solar_flux
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensing import AttitudeFit, attitude_from_fluxes, read_flux_rows, smoothed_attitudes
from sunwind.forces.sensing.smoothing import LEAST_ROWS
from sunwind.forces.sensing.solve import mean_motion
from sunwind.forces.tables.checkpoint import check_place
from sunwind.geometry.errors import InputError

#: The flag of each keyword of :func:`~sunwind.forces.sensing.attitude_from_fluxes` its errors name.
FLAGS = {"sigma": "--sigma", "floor_W_m2": "--floor", "smooth_s": "--smooth"}
#: Rows per checkpoint chunk by default (a row takes 0.1 s on a CubeSat, seconds on a large model).
ROWS_PER_CHUNK = 16


def _output(values: dict) -> dict:
    """Check ``-o`` and the run flags before the mesh is loaded."""
    out = values["output"]
    if out is not None:
        if out.suffix not in (".json", ".csv"):
            raise InputError("the rows are written as .json or .csv", path=str(out), hint="name it so")
        check_writable(out)
    return check_run(values)


@click.command()
@model_options()
@click.option(
    "--fluxes",
    "fluxes_path",
    required=True,
    type=click.Path(path_type=Path),
    help="CSV: time_s, one column per sensor part (absorbed W/m^2 of its area); optional sun_eci_x..z and "
    "nadir_eci_x..z (for the quaternion), velocity_eci_x..z (for pitch, yaw, roll).",
)
@click.option("--altitude", type=float, required=True, metavar="KM", help="Height above the Earth [km].")
@click.option(
    "--sensors", multiple=True, metavar="GLOB", help="Use only these sensor columns (repeat; default all)."
)
@click.option(
    "--sigma",
    type=float,
    default=0.01,
    show_default=True,
    metavar="REL",
    help="Relative flux error, 1 sigma.",
)
@click.option(
    "--floor",
    type=float,
    default=1.0,
    show_default=True,
    metavar="W_M2",
    help="Smallest flux error, 1 sigma [W/m^2] (a sensor's resolution).",
)
@click.option("--albedo", type=float, metavar="A", help="Earth's Bond albedo instead of 0.30.")
@click.option("--solar-flux", type=float, metavar="W_M2", help="Solar flux instead of 1361 W/m^2.")
@click.option(
    "--smooth",
    type=float,
    metavar="SECONDS",
    help="Also fit each sunlit row with the rows within SECONDS/2 of it, the body turning at a constant rate "
    "over that window: smoothed directions and the body's rate.",
)
@reflection_options("light")
@group(
    "output",
    [
        click.option(
            "-o",
            "--output",
            type=click.Path(path_type=Path),
            metavar="FILE",
            help="Write the rows to FILE: .json (as --json prints) or .csv (one line per row); finished rows "
            "are kept in FILE.checkpoint until it is written.",
        ),
        *run_options("row", "attitude run (-o)", ROWS_PER_CHUNK),
    ],
    _output,
)
@json_option
def attitude(source: ModelSource, fluxes_path: Path, altitude: float, output: dict, **flags: object) -> None:
    """Attitude from measured heat fluxes: for each row, the body-frame Sun and nadir directions that
    reproduce the sensors' fluxes through the full forward model (self-shadowing, reflections, albedo
    with its terminator, infrared), found over the whole sphere; every minimum within the noise is
    reported, and a row in eclipse gives the nadir alone."""
    if output["output"] is not None:
        check_distinct(output["output"], fluxes_path, source.mesh, source.materials)
    model = loaded(source)
    rows = read_flux_rows(fluxes_path)
    patterns = tuple(flags["sensors"])  # type: ignore[arg-type]
    if patterns:
        rows = rows.selected(patterns)
    flux = solar_flux() if flags["solar_flux"] is None else float(flags["solar_flux"])  # type: ignore[arg-type]
    light = PlanetLight.of(planet("earth"), flux, albedo=flags["albedo"])  # type: ignore[arg-type]
    reflections: ReflectionSettings = flags["reflections"]  # type: ignore[assignment]
    out: Path | None = output["output"]
    checkpoint = None if out is None else out.with_name(out.name + ".checkpoint")
    if checkpoint is not None:
        check_place(checkpoint)
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn())
    smooth: float | None = flags["smooth"]  # type: ignore[assignment]
    try:
        if smooth is not None:
            mean_motion(smooth, light, altitude)  # a bad window said before the rows are solved
        with progress_bar(*columns) as bar:
            task = bar.add_task("attitude", total=len(rows))
            run = sweep_run(output, checkpoint, lambda done: bar.update(task, completed=done))
            with interruptible(bar, checkpoint):
                found = attitude_from_fluxes(
                    model,
                    rows,
                    altitude,
                    sigma=float(flags["sigma"]),  # type: ignore[arg-type]
                    floor_W_m2=float(flags["floor"]),  # type: ignore[arg-type]
                    light=light,
                    reflections=reflections,
                    run=run,
                )
        if smooth is not None:
            found = smoothed_attitudes(found, rows, smooth, light)
    except InputError as error:
        raise error.renamed(FLAGS) from None
    document = {"mesh": str(source.mesh), "fluxes": str(fluxes_path), **found.to_json()}
    if out is not None:
        _write(found, document, out)
        print(f"wrote {out}: {len(found.rows)} rows", file=sys.stderr if flags["as_json"] else sys.stdout)
    if flags["as_json"]:
        print(json.dumps(document, indent=2))
    elif out is None:
        _print(found, str(fluxes_path))
    _say_smoothing(found)
    for row in found.rows:
        if not row.explained:
            print(
                f"sunwind: warning: t = {row.time_s:g} s: the best attitude does not explain the fluxes "
                f"within the noise (misfit {row.best.misfit:.3g}): it may be a wrong basin, or the model or "
                "--sigma may be wrong",
                file=sys.stderr,
            )
        if row.eclipse:
            print(
                f"sunwind: notice: t = {row.time_s:g} s: in eclipse: only the nadir is found", file=sys.stderr
            )
        elif row.ambiguous:
            print(
                f"sunwind: warning: t = {row.time_s:g} s: {len(row.alternatives) + 1} attitudes fit within "
                "the noise (the others are listed as alternatives); add sensors or the inertial directions",
                file=sys.stderr,
            )


def _write(found: AttitudeFit, document: dict, path: Path) -> None:
    """Write the rows: the JSON document, or CSV with the settings as ``#`` lines above the header."""
    with atomic_text(path) as stream:
        if path.suffix == ".json":
            json.dump(document, stream, indent=2)
            stream.write("\n")
            return
        for key in ("mesh", "fluxes", "frame", "orbital_frame", "sensors", "altitude_km", "relative_sigma"):
            value = document[key]
            stream.write(f"# {key}: {', '.join(value) if isinstance(value, list) else value}\n")
        stream.write(f"# floor_W_m2: {found.floor_W_m2}\n# model_error_W_m2: {found.model_error_W_m2}\n")
        writer = csv.writer(stream, lineterminator="\n")
        smoothing = found.smooth_window_s is not None
        writer.writerow(CSV_COLUMNS + (SMOOTHED_COLUMNS if smoothing else ()))
        writer.writerows(_csv_row(row, smoothing) for row in document["rows"])


#: The columns of the CSV: one line per row, a direction as three, empty where there is none.
CSV_COLUMNS = (
    "time_s",
    *(f"sun_body_{axis}" for axis in "xyz"),
    *(f"nadir_body_{axis}" for axis in "xyz"),
    "sigma_sun_deg",
    "sigma_nadir_deg",
    "misfit",
    "ambiguous",
    "explained",
    "eclipse",
    "alternatives",
    *(f"quaternion_{axis}" for axis in "wxyz"),
    "pitch_deg",
    "yaw_deg",
    "roll_deg",
)


#: The columns the smoothing adds.
SMOOTHED_COLUMNS = (
    *(f"smoothed_sun_body_{axis}" for axis in "xyz"),
    *(f"smoothed_nadir_body_{axis}" for axis in "xyz"),
    "smoothed_sigma_sun_deg",
    "smoothed_sigma_nadir_deg",
    *(f"rate_deg_s_{axis}" for axis in "xyz"),
    "sigma_rate_deg_s",
    "smoothed_rows",
    "smoothed_misfit",
    "smoothed_explained",
    "smoothed_rejected",
    "smoothed_outlier",
    *(f"smoothed_quaternion_{axis}" for axis in "wxyz"),
    "smoothed_pitch_deg",
    "smoothed_yaw_deg",
    "smoothed_roll_deg",
)


def _csv_row(row: dict, smoothing: bool) -> list:
    def cells(values: list[float] | None, n: int) -> list:
        return [""] * n if values is None else values

    def cell(value: float | None) -> float | str:
        return "" if value is None else value

    out = [
        row["time_s"],
        *cells(row["sun_body"], 3),
        *cells(row["nadir_body"], 3),
        cell(row["sigma_deg"]["sun"]),
        cell(row["sigma_deg"]["nadir"]),
        row["misfit"],
        int(row["ambiguous"]),
        int(row["explained"]),
        int(row["eclipse"]),
        len(row["alternatives"]),
        *cells(row["quaternion"], 4),
        *cells(row["pitch_yaw_roll_deg"], 3),
    ]
    if not smoothing:
        return out
    smoothed = row["smoothed"]
    if smoothed is None:
        return out + [""] * len(SMOOTHED_COLUMNS)
    return [
        *out,
        *smoothed["sun_body"],
        *smoothed["nadir_body"],
        cell(smoothed["sigma_deg"]["sun"]),
        cell(smoothed["sigma_deg"]["nadir"]),
        *smoothed["rate_deg_s"],
        cell(smoothed["sigma_rate_deg_s"]),
        smoothed["rows"],
        smoothed["misfit"],
        int(smoothed["explained"]),
        smoothed["rejected"],
        int(smoothed["outlier"]),
        *cells(smoothed["quaternion"], 4),
        *cells(smoothed["pitch_yaw_roll_deg"], 3),
    ]


def _say_smoothing(found: AttitudeFit) -> None:
    """The smoothing's notice (rows it could not smooth) and warnings (windows one rate cannot explain, rows
    whose own solution the motion of the rows around them leaves out)."""
    if found.smooth_window_s is None:
        return
    window = found.smooth_window_s
    alone = [
        row.time_s
        for row, smoothed in zip(found.rows, found.smoothed, strict=True)
        if smoothed is None and not row.eclipse
    ]
    if alone:
        print(
            f"sunwind: notice: {len(alone)} sunlit rows (the first at t = {alone[0]:g} s) have fewer than "
            f"{LEAST_ROWS} sunlit rows within --smooth {window:g} s: not smoothed",
            file=sys.stderr,
        )
    leaving = [s for s in found.smoothed if s is not None and s.rejected]
    if leaving:
        print(
            f"sunwind: notice: {len(leaving)} windows (the first at t = {leaving[0].time_s:g} s) leave out "
            'rows that disagree with the motion most of their rows agree with ("rejected")',
            file=sys.stderr,
        )
    for smoothed in found.smoothed:
        if smoothed is not None and not smoothed.explained:
            print(
                f"sunwind: warning: t = {smoothed.time_s:g} s: the {smoothed.rows} rows within "
                f"--smooth {window:g} s do not fit one constant rate (misfit {smoothed.misfit:.3g}): "
                "shorten the window",
                file=sys.stderr,
            )
        elif smoothed is not None and smoothed.outlier:
            print(
                f"sunwind: warning: t = {smoothed.time_s:g} s: the row's own solution disagrees with the "
                f"motion of the {smoothed.rows - smoothed.rejected} rows around it: its smoothed "
                "directions come from them alone",
                file=sys.stderr,
            )


def _print(found: AttitudeFit, source: str) -> None:
    """The text report: one block per row."""
    print(f"sunwind attitude: {source}, {len(found.rows)} rows, sensors {', '.join(found.sensors)}")
    print(f"  body frame of the mesh, unit vectors from the spacecraft; altitude {found.altitude_km:g} km")
    error = found.model_error_W_m2
    if error is not None:
        shown = f"{error:.3g} W/m^2" if error >= 1e-3 else "below 0.001 W/m^2"  # below: rounding's
        print(f"  flux model against the full forward model: {shown} at worst")
    for k, row in enumerate(found.rows):
        best = row.best
        flag = " (eclipse)" if row.eclipse else " (ambiguous)" if row.ambiguous else ""
        print(f"t = {row.time_s:g} s{flag}: misfit {best.misfit:.3g}")
        if best.sun is not None:
            print(f"  sun   {_vector(best.sun)}  1-sigma {_degrees(best.sigma_sun_deg)}")
        print(f"  nadir {_vector(best.nadir)}  1-sigma {_degrees(best.sigma_nadir_deg)}")
        if row.quaternion is not None:
            print(f"  quaternion (w, x, y, z; body to inertial) {_vector(row.quaternion)}")
        if row.pitch_yaw_roll_deg is not None:
            pitch, yaw, roll = row.pitch_yaw_roll_deg
            print(f"  pitch {pitch:.2f}, yaw {yaw:.2f}, roll {roll:.2f} deg (orbital frame)")
        for other in row.alternatives:
            sun = "-" if other.sun is None else _vector(other.sun)
            print(f"  also: sun {sun}, nadir {_vector(other.nadir)}, misfit {other.misfit:.3g}")
        smoothed = found.smoothed[k] if found.smoothed else None
        if smoothed is not None:
            left = f", {smoothed.rejected} left out" if smoothed.rejected else ""
            own = "; the row's own solution left out" if smoothed.outlier else ""
            print(f"  smoothed over {smoothed.rows} rows{left} (misfit {smoothed.misfit:.3g}){own}:")
            print(f"    sun   {_vector(smoothed.sun)}  1-sigma {_degrees(smoothed.sigma_sun_deg)}")
            print(f"    nadir {_vector(smoothed.nadir)}  1-sigma {_degrees(smoothed.sigma_nadir_deg)}")
            spread = (
                ""
                if smoothed.sigma_rate_deg_s is None
                else f"  1-sigma {smoothed.sigma_rate_deg_s:.3g} deg/s"
            )
            print(f"    body rate {_vector(smoothed.rate_deg_s)} deg/s (body axes){spread}")


def _vector(values: np.ndarray) -> str:
    return "(" + ", ".join(f"{v:+.4f}" for v in values) + ")"


def _degrees(value: float | None) -> str:
    return "not observable" if value is None else f"{value:.2f} deg"
