"""``sunwind earth``: the planet's albedo and infrared on the spacecraft at one place and attitude, the
power each part absorbs, and (``--thermal``) temperatures and thermal recoil."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import click
import numpy as np

from sunwind.forces.cli.options import (
    Sun,
    group,
    json_option,
    loaded,
    model_options,
    posed,
    reference_options,
    reflection_options,
    sampling_options,
    sun_options,
)
from sunwind.forces.cli.report import about, print_json, vector
from sunwind.forces.earth import DEFAULT_STEP_DEG, EarthResult, Place, earth_radiation
from sunwind.forces.model import ModelSource
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.eclipse import ECLIPSE_MODELS, sphere_visible
from sunwind.forces.planet.bodies import PLANETS, PlanetLight, planet
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.thermal import ThermalModel, ThermalState, infrared_exchange
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError

#: One astronomical unit [m].
AU_M = 149_597_870_700.0


@dataclass(frozen=True)
class Below:
    """The planet options of a command."""

    nadir: tuple[float, float, float]
    altitude_km: float
    planet: str
    albedo: float | None
    albedo_model: str
    epoch: str | None
    pole: tuple[float, float, float] | None
    earth_ir: float | None
    eclipse: str
    step_deg: float


def planet_options() -> click.decorators.FC:
    """The planet's place and its albedo and infrared: keyword ``below``, a :class:`Below`."""
    options = [
        click.option("--earth", "nadir", nargs=3, type=float, required=True, metavar="X Y Z",
                     help="Direction from the spacecraft to the planet's centre, body frame."),
        click.option("--altitude", "altitude_km", type=float, required=True, metavar="H_KM",
                     help="Height above the planet's surface [km]."),
        click.option("--planet", type=click.Choice(list(PLANETS)), default="earth", show_default=True,
                     help="The planet below: its radius, albedo and infrared law."),
        click.option("--albedo", type=float, help="Bond albedo [default the planet's: Earth 0.30]."),
        click.option("--albedo-model", type=click.Choice(["lambert", "knocke"]), default="lambert",
                     show_default=True,
                     help="knocke: Knocke's zonal, seasonal albedo and emissivity (needs --epoch, --pole)."),
        click.option("--epoch", help="UTC date and time, ISO 8601 (the season of --albedo-model knocke)."),
        click.option("--pole", nargs=3, type=float, metavar="X Y Z",
                     help="The planet's north pole, body frame (latitudes for knocke)."),
        click.option("--earth-ir", type=float, metavar="W_M2",
                     help="Uniform infrared exitance at the surface [W/m^2] [default (1 - A) S / 4]."),
        click.option("--eclipse", type=click.Choice(ECLIPSE_MODELS), default="conical", show_default=True,
                     help="The planet's shadow on the Sun (sunlight in the heat budget)."),
        click.option("--step", "step_deg", type=float, default=DEFAULT_STEP_DEG, show_default=True,
                     help="Cell size of the planet's disc for shadowing and reflections [deg]."),
    ]  # fmt: skip
    return group("below", options, lambda values: Below(**values))


def place_and_light(below: Below, sun: Sun) -> tuple[Place, PlanetLight]:
    """The :class:`Place` and :class:`PlanetLight` of the options, the Sun's share behind the planet
    from ``--eclipse``."""
    body = planet(below.planet)
    nadir = unit_vector(below.nadir, "--earth")
    julian = None
    if below.albedo_model == "knocke":
        if below.epoch is None or below.pole is None:
            raise InputError("--albedo-model knocke needs --epoch (the season) and --pole (the latitudes)")
        julian = float(sum(Epoch.of(below.epoch).jd_tt))
    distance = body.radius_m + below.altitude_km * 1e3
    position = -distance * nadir
    fraction = float(sphere_visible(position, position + AU_M * sun.vector, body.radius_m, below.eclipse)[0])
    light = PlanetLight.of(
        body, sun.flux_W_m2, albedo=below.albedo, infrared_W_m2=below.earth_ir, knocke_julian_date=julian
    )
    return Place(nadir, below.altitude_km, sun.vector, below.pole, fraction), light


@click.command()
@model_options()
@sun_options()
@planet_options()
@reference_options()
@sampling_options
@reflection_options("light")
@group("heat", [
    click.option("--thermal", is_flag=True, help="Face temperatures and the recoil of their infrared."),
    click.option("--sides", "sides_csv", type=click.Path(dir_okay=False, path_type=Path),
                 help="Write every facet side's absorbed power (and temperature) to this CSV file."),
])  # fmt: skip
@json_option
def earth(
    source: ModelSource,
    sun: Sun,
    below: Below,
    references: dict,
    sampling: dict,
    reflections: ReflectionSettings,
    heat: dict,
    as_json: bool,
) -> None:
    """Albedo and infrared pressure from the planet below, per-part absorbed power and temperatures."""
    model = posed(loaded(source, **references), sun.vector, "earth")
    place, light = place_and_light(below, sun)
    result = earth_radiation(
        model, place, light, reflections=reflections, step_deg=below.step_deg, **sampling
    )
    state = None
    if heat["thermal"]:
        craft = model.craft
        nodes = ThermalModel(craft, infrared_exchange(craft, reflections))
        state = nodes.equilibrium(sum(result.absorbed_side_W().values()), result.reference_point_m)
    if heat["sides_csv"] is not None:
        _write_sides(heat["sides_csv"], result, state)
    if as_json:
        document = result.to_json()
        if state is not None:
            document["thermal"] = state.to_json()
            _add_temperatures(document["parts"], result, state)
        print_json(model.craft, document)
    else:
        _print(result, state)


def _part_temperatures(result: EarthResult, state: ThermalState) -> dict[str, float]:
    """Area-weighted mean temperature of each part [K]."""
    areas = result.craft.side_areas
    mean = result.per_part(areas * state.temperature_K) / result.per_part(areas)
    return dict(zip(result.craft.part_names, mean.tolist(), strict=True))


def _add_temperatures(parts: dict, result: EarthResult, state: ThermalState) -> None:
    for name, temperature in _part_temperatures(result, state).items():
        parts[name]["temperature_K"] = temperature


def _write_sides(path: Path, result: EarthResult, state: ThermalState | None) -> None:
    """One row per facet side: where it is, its area and the power it absorbs by source [W]."""
    craft = result.craft
    columns = result.absorbed_side_W()
    names = ["side", "facet", "part", "face", "area[m^2]", *(f"{k}[W]" for k in columns)]
    rows = [
        craft.side_facet.tolist(),
        [craft.part_names[p] for p in craft.facet_part[craft.side_facet]],
        np.where(craft.side_sign > 0, "front", "back").tolist(),
        craft.side_areas.tolist(),
        *(values.tolist() for values in columns.values()),
    ]
    if state is not None:
        names.append("temperature[K]")
        rows.append(state.temperature_K.tolist())
    try:
        with path.open("w", newline="") as handle:
            writer = csv.writer(handle)
            writer.writerow(names)
            writer.writerows(zip(range(craft.n_sides), *rows, strict=True))
    except OSError as error:
        raise InputError(f"cannot write the sides file ({error.strerror})", path=str(path)) from None


def _print(result: EarthResult, state: ThermalState | None) -> None:
    """The human-readable report."""
    craft, place = result.craft, result.place
    print(f"sunwind earth: {craft.source} ({craft.n_facets} triangles, {len(craft.part_names)} parts)")
    print("  frame            body frame of the mesh; SI units")
    print(f"  planet           {result.light.description}")
    print(f"  nadir            {vector(place.nadir, '{:+.6f}')}  altitude {place.altitude_km:g} km  "
          f"(disc radius {result.half_angle_deg:.3f} deg)")  # fmt: skip
    flux = result.light.solar_flux_W_m2
    print(f"  sun vector       {vector(place.sun_vector, '{:+.6f}')}  flux {flux:.6g} W/m^2, "
          f"{place.solar_fraction:.4f} of the disc in view")  # fmt: skip
    for band in (result.albedo, result.infrared):
        print(
            f"  {band.name:<9}force  [N]   {vector(band.force_N)}  |F| = {np.linalg.norm(band.force_N):.6e}"
        )
        print(f"           torque [N m] {vector(band.torque_Nm)}")
    if state is not None:
        print(f"  thermal  force  [N]   {vector(state.force_N)}  |F| = {np.linalg.norm(state.force_N):.6e}")
        print(f"           torque [N m] {vector(state.torque_Nm)}")
    print(f"  about   [m]      {about(result.reference_point_m, result.reference_point)}")
    print(f"  reflections      {result.reflections}; {result.cells} cells, {result.rays} rays")
    temperatures = {} if state is None else _part_temperatures(result, state)
    print(
        "  absorbed [W]     part: solar, albedo, infrared, reflected" + (", temperature [K]" if state else "")
    )
    for name, row in result.parts().items():
        line = ", ".join(f"{row[k]:.4g}" for k in ("solar_W", "albedo_W", "infrared_W", "reflected_W"))
        extra = (
            f", {temperatures[name]:.1f}"
            if name in temperatures and math.isfinite(temperatures[name])
            else ""
        )
        print(f"    {name}: {line}{extra}")
