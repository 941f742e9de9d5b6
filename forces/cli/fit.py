"""``sunwind fit``: the surface coefficients that make the model match flight telemetry (torque, wheel
momentum, acceleration), with their uncertainties and what the data cannot separate."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click

from sunwind.forces.cli.options import (
    json_option,
    loaded,
    model_options,
    reference_options,
    reflection_options,
    sampling_options,
)
from sunwind.forces.cli.outputs import check_distinct, check_image, check_writable
from sunwind.forces.fit import FitOptions, read_telemetry, write_materials
from sunwind.forces.fit import fit as fit_telemetry
from sunwind.forces.fit.forward import RESOLUTION_DEG
from sunwind.forces.fit.solve import LOSSES
from sunwind.forces.model import ModelSource
from sunwind.forces.reflection import ReflectionSettings
from sunwind.geometry.rays.sampling import ShadowSampling


@click.command()
@model_options()
@click.option(
    "--data",
    "data",
    required=True,
    type=click.Path(path_type=Path),
    help="Telemetry CSV: time_s; sun_x..z (body) or qw..qz (body to ECI, with --epoch); optional "
    "flux_W_m2, solar_fraction, hinge:GLOB [deg], and for drag vel_x..z [m/s, body] with density_kg_m3 "
    "(and temperature_K); torque_x..z [N m], momentum_x..z [N m s], accel_x..z [m/s^2].",
)
@click.option(
    "--free",
    "free",
    multiple=True,
    required=True,
    metavar="MATERIAL.COEFFICIENT",
    help="A coefficient to fit: reflectivity, specular_fraction or transmissivity of a material, or "
    "with drag columns energy_accommodation, normal_accommodation or tangential_accommodation "
    "(repeat the flag).",
)
@click.option("--epoch", help="ISO UTC time of time_s = 0, for the Sun of quaternion telemetry.")
@click.option(
    "--composition",
    default="O:1",
    show_default=True,
    help="Mole fractions of the air of drag rows (vel_x..z, density_kg_m3 columns), e.g. O:0.7,N2:0.3.",
)
@reference_options()
@click.option("--bias-torque", is_flag=True, help="Fit a constant body-frame torque too.")
@click.option("--scale", "scale", is_flag=True, help="Fit one global factor of SRP too.")
@click.option("--sigma-torque", type=float, metavar="NM", help="Torque noise, one sigma [N m].")
@click.option("--sigma-momentum", type=float, metavar="NMS", help="Momentum noise, one sigma [N m s].")
@click.option("--sigma-accel", type=float, metavar="M_S2", help="Acceleration noise, one sigma [m/s^2].")
@click.option("--mass", type=float, metavar="KG", help="Spacecraft mass [kg], for acceleration data.")
@click.option(
    "--loss", type=click.Choice(LOSSES), default="linear", show_default=True, help="soft_l1: robust."
)
@click.option(
    "--resolution-deg",
    type=float,
    default=RESOLUTION_DEG,
    show_default=True,
    help="Rows whose Sun directions and hinge angles agree within this [deg] share one model run.",
)
@sampling_options
@reflection_options("light")
@click.option(
    "--write-materials",
    type=click.Path(path_type=Path),
    metavar="FITTED.toml",
    help="Write the materials file again with the fitted values.",
)
@click.option("--plot", "plot_path", type=click.Path(path_type=Path), metavar="FIT.png", help="Plot the fit.")
@json_option
def fit(source: ModelSource, data: Path, free: tuple[str, ...], **flags: object) -> None:
    """Fit surface coefficients to telemetry: bounded weighted least squares with the model's
    sensitivities; estimates with one-sigma uncertainties, correlations, and a warning for each
    combination the data cannot separate."""
    references = flags.pop("references")
    materials_out, plot_out = flags["write_materials"], flags["plot_path"]
    inputs = (source.mesh, source.materials, data)
    if materials_out is not None:  # before any work: an output over an input, or one that cannot be written
        check_distinct(Path(materials_out), *inputs, plot_out)  # type: ignore[arg-type]
        check_writable(Path(materials_out))  # type: ignore[arg-type]
    if plot_out is not None:
        check_image(Path(plot_out), *inputs, materials_out)  # type: ignore[arg-type]
    model = loaded(source, **references)  # type: ignore[arg-type]
    telemetry = read_telemetry(data, flags["epoch"])  # type: ignore[arg-type]
    sigmas = {
        kind: flags[f"sigma_{kind}"]
        for kind in ("torque", "momentum", "accel")
        if flags[f"sigma_{kind}"] is not None
    }
    sampling: ShadowSampling = flags["sampling"]  # type: ignore[assignment]
    reflections: ReflectionSettings = flags["reflections"]  # type: ignore[assignment]
    options = FitOptions(
        bias_torque=bool(flags["bias_torque"]),
        scale=bool(flags["scale"]),
        sigmas=sigmas,  # type: ignore[arg-type]
        mass_kg=flags["mass"],  # type: ignore[arg-type]
        loss=str(flags["loss"]),
        reflections=reflections,
        sampling=sampling,
        resolution_deg=float(flags["resolution_deg"]),  # type: ignore[arg-type]
        composition=str(flags["composition"]),
    )
    result = fit_telemetry(model, telemetry, list(free), options)
    for notice in result.notices:
        print(f"sunwind: notice: {notice}", file=sys.stderr)
    written = None
    if flags["write_materials"] is not None:
        written = write_materials(result, source.materials, flags["write_materials"])  # type: ignore[arg-type]
    if flags["plot_path"] is not None:
        from sunwind.forces.fit.plot import plot_fit

        plot_fit(result, flags["plot_path"])  # type: ignore[arg-type]
    if flags["as_json"]:
        document = {"mesh": str(source.mesh), "data": str(data), **result.to_json()}
        print(json.dumps(document, indent=2))
    else:
        print(f"sunwind fit: {model.craft.source} to {data}")
        for line in result.lines():
            print(line)
        if written is not None:
            print(f"  materials written to {written}")
        if flags["plot_path"] is not None:
            print(f"  plot written to {flags['plot_path']}")
    for warning in result.warnings:
        print(f"sunwind: warning: {warning}", file=sys.stderr)
