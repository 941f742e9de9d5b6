"""``sunwind visibility``: lines of sight from points of the model toward given directions, maps of
what blocks each point's view, or what each point sees of the Sun, the Earth or a station along an
orbit (METHOD.md "Lines of sight")."""

from __future__ import annotations

import json
import time
from dataclasses import replace
from pathlib import Path

import click
import numpy as np

from sunwind.forces.cli.options import given, group, loaded, model_options, posed, reference_options
from sunwind.forces.cli.orbit import ATTITUDE_OPTIONS
from sunwind.forces.cli.orbit_path import PATH_OPTIONS, path_request
from sunwind.forces.cli.outputs import check_distinct, check_image, check_writable
from sunwind.forces.cli.report import print_json, vector
from sunwind.forces.model import ModelSource
from sunwind.forces.orbit import AttitudeLaw
from sunwind.forces.orbit.eclipse import ECLIPSE_MODELS
from sunwind.forces.sight import (
    FRAME,
    Station,
    blocked_map,
    lines_of_sight,
    range_offsets,
    read_points,
    visibility_along,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material

#: The map's step when ``--step`` is not given [deg] (``--step`` is the orbit's time step otherwise).
MAP_STEP_DEG = 2.0

_SIGHT_OPTIONS = [
    click.option(
        "--points",
        "points_file",
        type=click.Path(path_type=Path),
        required=True,
        help="CSV: name,x,y,z [m, body frame], optional boresight_x,boresight_y,boresight_z,half_angle_deg.",
    ),
    click.option(
        "--direction",
        nargs=3,
        type=float,
        multiple=True,
        metavar="X Y Z",
        help="Direction from the points toward the target, body frame (repeat for several).",
    ),
    click.option(
        "--ranging",
        is_flag=True,
        help="The directions point to a laser-ranging station: range offsets of the points with a cone.",
    ),
    click.option(
        "--map",
        "sky_map",
        is_flag=True,
        help=f"Map each point's blocked view over azimuth, elevation (--step DEG, default {MAP_STEP_DEG:g}).",
    ),
    click.option(
        "--target",
        type=click.Choice(["sun", "earth", "station"]),
        help="Along an orbit (the orbit flags): what each point looks at.",
    ),
    click.option(
        "--station",
        nargs=3,
        type=float,
        default=None,
        metavar="LAT LON ALT",
        help="Ground station: geodetic latitude, longitude [deg] and altitude [km] (WGS 84).",
    ),
    click.option(
        "--min-elevation",
        type=float,
        default=0.0,
        show_default=True,
        help="Lowest elevation above the station's horizon at which it sees the spacecraft [deg].",
    ),
    click.option(
        "--eclipse",
        type=click.Choice(ECLIPSE_MODELS),
        default="conical",
        show_default=True,
        help="The Earth's shadow, for --target sun.",
    ),
    click.option(
        "--clearance",
        type=float,
        help="How far off its point each line starts [m] [default 1e-4 of the model's half-size].",
    ),
    click.option("--json", "as_json", is_flag=True, help="Print one JSON object."),
    click.option(
        "--output", "-o", type=click.Path(path_type=Path), help="Write .json, or .nc (--map, orbit)."
    ),
    click.option("--plot", type=click.Path(path_type=Path), help="With --map: PNG of every point's map."),
]


def _mode(values: dict) -> dict:
    """Check that one mode is asked for and that its outputs fit it; name the mode."""
    target = values["target"]
    if values["station"] is not None and target is None:
        target = values["target"] = "station"
    modes = [
        name
        for name, on in (
            ("--direction", values["direction"]),
            ("--map", values["sky_map"]),
            ("--target", target),
        )
        if on
    ]
    if len(modes) != 1:
        raise InputError(
            f"give one of --direction, --map and --target, not {' and '.join(modes)}"
            if modes
            else "give --direction X Y Z, --map or --target (with the orbit flags)",
            hint="e.g. --direction 0 0 1, --map --step 2, or --target sun --altitude 500 --inclination 97.4",
        )
    values["mode"] = {"--direction": "direction", "--map": "map", "--target": "orbit"}[modes[0]]
    if target == "station" and values["station"] is None:
        raise InputError(
            "--target station needs --station LAT LON ALT", hint="e.g. --station 48.08 11.28 0.6"
        )
    if values["station"] is not None and target != "station":
        raise InputError("--station is for --target station", hint="drop --station or --target")
    if values["ranging"] and values["mode"] != "direction":
        raise InputError(
            "--ranging takes --direction toward the station", hint="along an orbit, give --station"
        )
    out, plot = values["output"], values["plot"]
    if out is not None:
        suffixes = (".json",) if values["mode"] == "direction" else (".json", ".nc")
        if out.suffix not in suffixes:
            raise InputError(
                f"this run is written as {' or '.join(suffixes)}", path=str(out), hint="name the output so"
            )
        check_writable(out)
    if plot is not None:
        if values["mode"] != "map":
            raise InputError("--plot draws the maps of --map", hint="add --map, or drop --plot")
        check_image(plot, out)
    return values


@click.command("visibility")
@model_options()
@reference_options()
@group("sight", _SIGHT_OPTIONS, _mode)
@group("path", PATH_OPTIONS)
@group("attitude", ATTITUDE_OPTIONS)
def visibility(source: ModelSource, references: dict, sight: dict, path: dict, attitude: dict) -> None:
    """Lines of sight from points of the model: toward directions, over the whole sky, or along an orbit.

    Points (--points CSV) are in metres in the body frame of the mesh; a point with a boresight and a
    half angle has a cone (a field of view or a retroreflector's acceptance cone). With --direction,
    each line is clear or blocked (by which part, how far) and in the cone or not; --ranging adds the
    range offsets -u.(p - c) of the arrays seen and their differences. With --map, each point's view is
    mapped over azimuth atan2(y, x) and elevation asin(z) (body frame) at --step DEG (default 2), with
    the blocked fraction of its field of view and its error estimate (-o FILE.nc, --plot FILE.png).
    With --target sun, earth or station (--station LAT LON ALT) and the orbit flags (--step is then the
    time step [s]), what each point sees at each step and the intervals."""
    points = read_points(sight["points_file"])
    inputs = (source.mesh, source.materials, sight["points_file"])
    for written in (sight["output"], sight["plot"]):
        if written is not None:
            check_distinct(written, *inputs)
    mode = sight["mode"]
    orbit_flags = [path[k] for k in ("elements", "altitude", "tle", "ephemeris")]
    if mode != "orbit" and any(v is not None for v in orbit_flags):
        raise InputError("the orbit flags are for --target", hint="add --target sun, earth or station")
    station = None
    if mode == "map":
        step = path["step"] if given("step") else MAP_STEP_DEG
    elif mode == "orbit":
        request = path_request(path)
        law = AttitudeLaw.parse(attitude["law"], attitude["interpolation"])
        if sight["target"] == "station":
            station = Station(*sight["station"], sight["min_elevation"])
    if source.uniform is None:  # lines of sight need no optics: parts without a material take any
        source = replace(source, uniform=Material("any", 0.0, 0.0))
    model = posed(loaded(source, **references), None, "visibility")
    clearance = sight["clearance"]
    if mode == "direction":
        _directions(model, points, sight, clearance)
    elif mode == "map":
        _map(model, points, sight, step, clearance)
    else:
        trajectory = request.trajectory()
        target = station if station is not None else sight["target"]
        passes = visibility_along(
            model, points, trajectory, law, target, eclipse=sight["eclipse"], clearance_m=clearance
        )
        _write(sight, passes.to_json(), passes.to_dataset)
        if sight["as_json"]:
            print_json(model.craft, passes.to_json())
        else:
            _print_passes(model.craft.source, passes, request.step_s, sight["output"])


def _write(sight: dict, document: dict, dataset) -> None:
    """Write ``-o``: the JSON document, or the Dataset as netCDF."""
    out = sight["output"]
    if out is None:
        return
    if out.suffix == ".json":
        out.write_text(json.dumps(document, indent=2))
    else:
        dataset().to_netcdf(out)


def _directions(model, points, sight: dict, clearance: float | None) -> None:
    directions = np.array(sight["direction"], dtype=float)
    try:
        lines = lines_of_sight(model, points, directions, clearance_m=clearance)
    except InputError as error:
        raise error.renamed({"directions": "--direction", "clearance_m": "--clearance"}) from None
    document = lines.to_json()
    ranges = None
    if sight["ranging"]:
        ranges = range_offsets(lines, model.reference()[0])
        cones = points.has_cone
        ranges = replace(ranges, offset_m=np.where(cones[:, None], ranges.offset_m, np.nan))
        document["range_offsets"] = ranges.to_json()
    _write(sight, document, None)
    if sight["as_json"]:
        print_json(model.craft, document)
        return
    print(f"sunwind visibility: {model.craft.source}: {len(points.names)} points from {points.source}")
    print(f"  frame      {FRAME}")
    print(f"  clearance  {lines.clearance_m:.3g} m off each point")
    off = points.off_boresight_deg(lines.directions)
    width = max(12, *(len(n) for n in points.names))
    wide = max(14, *(len(n) for n in lines.part_names)) if lines.part_names else 14
    for j, u in enumerate(lines.directions[0]):
        print(f"  direction  {vector(u, '{:+.4f}')}")
        print(f"    {'point':<{width}}  sight    {'blocked by':<{wide}}  distance [m]  off boresight [deg]")
        for i, name in enumerate(points.names):
            state = "visible" if lines.visible[i, j] else ("outside" if lines.clear[i, j] else "blocked")
            part = lines.blocked_by(i, j) or "-"
            distance = "-" if np.isnan(lines.distance_m[i, j]) else f"{lines.distance_m[i, j]:.4f}"
            angle = f"{off[i, j]:.2f}" if points.has_cone[i] else "- (no cone)"
            print(f"    {name:<{width}}  {state:<7}  {part:<{wide}}  {distance:>12}  {angle}")
        if ranges is not None:
            _print_ranges(ranges, j)
    if sight["output"] is not None:
        print(f"  wrote {sight['output']}")


def _print_ranges(ranges, j: int) -> None:
    seen = {k: v for k, v in ranges.to_json()["directions"][j]["offsets_m"].items()}
    c = vector(ranges.reference_point_m, "{:+.4f}")
    print(
        f"    range offsets -u.(p - c) [m], c = {c} m: "
        + (", ".join(f"{k} {v:+.6f}" for k, v in seen.items()) or "no array seen")
    )
    for a, b, d in ranges.differences(j):
        print(f"      {a} - {b}: {d:+.6f} m")


def _map(model, points, sight: dict, step: float, clearance: float | None) -> None:
    begin = time.perf_counter()
    try:
        view = blocked_map(model, points, step, clearance_m=clearance)
    except InputError as error:
        raise error.renamed({"step_deg": "--step", "clearance_m": "--clearance"}) from None
    seconds = time.perf_counter() - begin
    _write(sight, view.to_json(), lambda: view.to_dataset(model.craft.source))
    if sight["plot"] is not None:
        from sunwind.forces.sight.plots import plot_maps

        plot_maps(view, sight["plot"])
    if sight["as_json"]:
        print_json(model.craft, view.to_json())
        return
    cells = len(view.elevation_deg) * len(view.azimuth_deg)
    print(f"sunwind visibility: {model.craft.source}: {len(points.names)} points from {points.source}")
    print(f"  frame      {FRAME}")
    print(
        f"  grid       {view.step_deg:.4g} deg: {len(view.elevation_deg)} x {len(view.azimuth_deg)} cells, "
        "azimuth atan2(y, x), elevation asin(z), body frame"
    )
    print(
        "  error      estimate: the larger of |F_h - F_2h| (a grid twice as coarse) and 4 edge-cell sigma; "
        f"{cells * 1.25 * len(points.names):.3g} lines in {seconds:.2f} s"
    )
    width = max(12, *(len(n) for n in points.names))
    print(f"  {'point':<{width}}  view [sr]  blocked   estimate  blocked by")
    by_part = view.fraction_by_part
    for i, name in enumerate(points.names):
        fov = float((view.solid_angle_sr[:, None] * view.in_view[i]).sum())
        parts = ", ".join(
            f"{view.part_names[k]} {by_part[i, k]:.4f}" for k in np.argsort(-by_part[i]) if by_part[i, k] > 0
        )
        print(
            f"  {name:<{width}}  {fov:9.4f}  {view.blocked_fraction[i]:.4f}  {view.error_estimate[i]:8.1e}  "
            f"{parts or '-'}"
        )
    for written in (sight["output"], sight["plot"]):
        if written is not None:
            print(f"  wrote {written}")


def _print_passes(name: str, passes, step_s: float, output: Path | None) -> None:
    t = passes.time_s
    print(f"sunwind visibility: {name}: {len(passes.points.names)} points from {passes.points.source}")
    print(f"  frame      {FRAME}")
    print(f"  target     {passes.target}")
    print(f"  run        {passes.epoch}, {len(t)} steps of {step_s:g} s; interval edges to within one step")
    if "solar_fraction" in passes.extra:
        shadow = float(np.mean(passes.extra["solar_fraction"] == 0))
        print(f"  eclipse    the spacecraft is in the Earth's umbra (Sun not seen) {shadow:.4f} of the time")
    width = max(12, *(len(n) for n in passes.points.names))
    print(f"  {'point':<{width}}  seen      intervals: start-end [s] (duration [s])")
    for i, point in enumerate(passes.points.names):
        runs = passes.intervals(i)
        shown = ", ".join(f"{a:g}-{b:g} ({d:g})" for a, b, d in runs[:6]) + (
            f", ... ({len(runs)} in all)" if len(runs) > 6 else ""
        )
        print(f"  {point:<{width}}  {passes.visible[i].mean():.4f}    {shown or 'never seen'}")
    if passes.ranges is not None:
        offsets = passes.ranges.offset_m
        print("  range offsets -u.(p - c) [m] while seen (min to max):")
        for i, point in enumerate(passes.points.names):
            seen = offsets[i][np.isfinite(offsets[i])]
            if passes.points.has_cone[i] and len(seen):
                print(f"    {point:<{width}}  {seen.min():+.4f} to {seen.max():+.4f}")
    if output is not None:
        print(f"  wrote {output}")
