"""``sunwind orbit``: forces, torques and the momentum they build along an orbit and an attitude law."""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import click
import numpy as np
from rich.progress import BarColumn, MofNCompleteColumn, TextColumn, TimeRemainingColumn

from sunwind.forces.cli.earth import EarthRequest, check_earth_step, earth_request, earth_term_options
from sunwind.forces.cli.free_stream import WEATHER_OPTIONS
from sunwind.forces.cli.options import (
    drag_only,
    group,
    loaded,
    model_options,
    reference_options,
    reflection_options,
    sampling_options,
)
from sunwind.forces.cli.orbit_path import PATH_OPTIONS, PathRequest, path_request
from sunwind.forces.cli.outputs import check_distinct, check_image, check_writable
from sunwind.forces.cli.report import estimated, print_json, vector, warn_beyond
from sunwind.forces.cli.runs import check_run, interruptible, progress_bar, run_options, sweep_run
from sunwind.forces.cli.sensitivities import print_sensitivities, sensitivities_option
from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.gas import explicit
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.model import ModelSource
from sunwind.forces.orbit import AttitudeLaw, OrbitLoads, SpaceWeather, fly
from sunwind.forces.orbit.attitude import INTERPOLATIONS
from sunwind.forces.orbit.earth_terms import PART_SOURCES
from sunwind.forces.orbit.eclipse import ECLIPSE_MODELS
from sunwind.forces.orbit.flight import check_sun, geodetic
from sunwind.forces.radiation import solar_flux
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensitivity import Sensitivities
from sunwind.forces.tables.checkpoint import check_place
from sunwind.forces.tables.jobs import GasOptions, SrpSetup
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling

#: Drag is computed by default when the orbit dips below this altitude [km] (NRLMSIS's fitted range).
DRAG_DEFAULT_BELOW_KM = 1000.0
_ENVIRONMENT_OPTIONS = [
    click.option("--srp", "srp_flag", is_flag=True, help="Compute SRP [default: on]."),
    click.option(
        "--drag",
        "drag_flag",
        is_flag=True,
        help=f"Compute drag [default: on where the orbit dips below {DRAG_DEFAULT_BELOW_KM:g} km].",
    ),
    click.option(
        "--sun-eci",
        nargs=3,
        type=float,
        default=None,
        metavar="X Y Z",
        help="A fixed Sun direction (GCRF, at 1 au) instead of the ephemeris.",
    ),
    click.option(
        "--eclipse",
        type=click.Choice(ECLIPSE_MODELS),
        default="conical",
        show_default=True,
        help="Earth shadow: conical (with penumbra), cylindrical, or none.",
    ),
    click.option("--moon", is_flag=True, help="The Moon eclipses the Sun too (with the ephemeris Sun)."),
    click.option("--flux", type=float, help="Solar flux at 1 au [W/m^2] [default 1361]."),
    *WEATHER_OPTIONS,
    click.option("--density", type=float, help="Fixed atmosphere: mass density [kg/m^3]."),
    click.option("--temperature", type=float, help="Fixed atmosphere: temperature [K]."),
    click.option("--composition", help='Fixed atmosphere: mole fractions, e.g. "O:0.7,N2:0.3".'),
    click.option("--mass", type=float, help="Spacecraft mass [kg]: ballistic and SRP coefficients per kg."),
    *earth_term_options(place=False, per_side=True, transient=True),
]


@dataclass(frozen=True)
class Environment:
    """The environment of ``sunwind orbit``: terms asked for, Sun, eclipse, air and Earth's radiation.

    Parameters
    ----------
    srp : bool
        Compute SRP.
    drag : bool or None
        Compute drag; None decides by the orbit (on where it dips below ``DRAG_DEFAULT_BELOW_KM``).
    sun_eci : (3,) float ndarray or None
        A fixed Sun direction (GCRF, at 1 au); None takes the ephemeris.
    eclipse : str
        The Earth's shadow: ``"conical"`` (with penumbra), ``"cylindrical"`` or ``"none"``.
    moon : bool
        The Moon eclipses the Sun too.
    flux_1au_W_m2 : float
        Solar flux at 1 au [W/m^2].
    air : Atmosphere or SpaceWeather
        A fixed atmosphere, or the space weather of NRLMSIS along the orbit.
    mass_kg : float or None
        Spacecraft mass [kg], for the ballistic and SRP coefficients per kilogram.
    earth : EarthRequest or None
        The Earth's albedo and infrared (``--earth-radiation``); None: not added.

    Examples
    --------
    >>> from sunwind.forces.orbit import SpaceWeather
    >>> environment = Environment(srp=True, drag=None, sun_eci=None, eclipse="conical", moon=False,
    ...                           flux_1au_W_m2=1361.0, air=SpaceWeather(), mass_kg=None, earth=None)
    >>> environment.drag is None  # drag decided by the orbit's lowest altitude
    True
    """

    srp: bool
    drag: bool | None
    sun_eci: np.ndarray | None
    eclipse: str
    moon: bool
    flux_1au_W_m2: float
    air: object
    mass_kg: float | None
    earth: EarthRequest | None


def _environment(values: dict) -> Environment:
    earth = earth_request(values)
    fixed = [values[k] for k in ("density", "temperature", "composition")]
    if any(v is not None for v in fixed):
        if any(v is None for v in fixed):
            raise InputError("a fixed atmosphere needs --density, --temperature and --composition")
        air = explicit(*fixed)
    else:
        air = SpaceWeather(values["f107"], values["f107a"], values["ap"])
    sun = values["sun_eci"]
    check_sun(sun, values["moon"])
    mass = values["mass"]
    if mass is not None and not (math.isfinite(mass) and 1e-3 <= mass <= 1e7):
        raise InputError(
            f"--mass {mass:g} kg must be from 0.001 kg to 1e7 kg (a gram-sized chip satellite to "
            "twenty International Space Stations)",
            hint="give the spacecraft's mass in kg",
        )
    asked = values["srp_flag"] or values["drag_flag"]
    return Environment(
        values["srp_flag"] or not asked,
        values["drag_flag"] if asked else None,
        None if sun is None else np.array(sun, dtype=float),
        values["eclipse"],
        values["moon"],
        solar_flux(values["flux"]),
        air,
        mass,
        earth,
    )


#: The attitude law's options, shared by `sunwind orbit` and `sunwind visibility --target`.
ATTITUDE_OPTIONS = [
    click.option(
        "--attitude",
        "law",
        default="nadir",
        show_default=True,
        help="nadir, lvlh:P,Y,R, sun[:A,B], inertial:QW,QX,QY,QZ, thrust-sun:X,Y,Z[:A,B] or csv:FILE.",
    ),
    click.option(
        "--interpolation",
        type=click.Choice(INTERPOLATIONS),
        default="slerp",
        show_default=True,
        help="Between the rows of a csv: attitude file.",
    ),
]

_OUTPUT_OPTIONS = [
    click.option("--output", "-o", type=click.Path(path_type=Path), help="Time series file: .nc or .csv."),
    click.option("--plot", type=click.Path(path_type=Path), help="PNG of torque and momentum against time."),
    click.option(
        "--plot-thermal",
        type=click.Path(path_type=Path),
        help="With --earth-radiation: PNG of each part's absorbed power (and temperature with --thermal) and "
        "the power by source against time.",
    ),
    click.option("--json", "as_json", is_flag=True, help="Print one JSON object: the series and summary."),
    click.option(
        "--gas-reflections",
        type=click.Choice(["none", "full", "auto"]),
        default="auto",
        show_default=True,
        help="Re-emitted molecules striking other sides (--reflections is for light).",
    ),
    click.option(
        "--sky-rays", type=int, help="Rays per side of each side's open sky [default: by model size]."
    ),
    click.option(
        "--hinge-step",
        type=float,
        default=1.0,
        show_default=True,
        help="Tracked and scheduled hinge angles rounded to this step [deg] (0: exact): each new angle is "
        "a new pose whose caches (view factors) are made again.",
    ),
    sensitivities_option,
    *run_options("step", "run (-o)"),
]


def _output(values: dict) -> dict:
    out = values["output"]
    if out is not None:
        if out.suffix not in (".nc", ".csv"):
            raise InputError("the time series is written as .nc or .csv", path=str(out), hint="name it so")
        check_writable(out)
    if values["plot"] is not None:
        check_image(values["plot"], out)
    if values["plot_thermal"] is not None:
        check_image(values["plot_thermal"], out, values["plot"])
    check_run(values)
    step = values["hinge_step"]
    if not (math.isfinite(step) and 0 <= step <= 30):
        raise InputError(f"--hinge-step {step:g} must be 0 to 30 deg")
    return values


@click.command("orbit")
@model_options(gas=True)
@group("path", PATH_OPTIONS, path_request)
@group("environment", _ENVIRONMENT_OPTIONS, _environment)
@group("attitude", ATTITUDE_OPTIONS, lambda v: AttitudeLaw.parse(v["law"], v["interpolation"]))
@reference_options(sizes=True)
@sampling_options
@reflection_options("light")
@group("output", _OUTPUT_OPTIONS, _output)
def orbit(
    source: ModelSource,
    path: PathRequest,
    environment: Environment,
    attitude: AttitudeLaw,
    references: dict,
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    output: dict,
) -> None:
    """Forces, torques and accumulated momentum along an orbit, with eclipse and an attitude law.

    With --sensitivities every step also gives the derivatives of its summed force and torque with
    respect to every material's coefficients (sensitivity_force_N, sensitivity_torque_Nm on time,
    material, coefficient and component): SRP's at the step's eclipsed flux, drag's and the Earth's
    albedo and infrared's (not with --thermal); their orbit means are printed."""
    inputs = (source.mesh, source.materials, path.tle, path.ephemeris, attitude.path)
    for written in (output["output"], output["plot"], output["plot_thermal"]):
        if written is not None:
            check_distinct(written, *inputs)
    _check_heat_outputs(environment.earth, output)
    trajectory = path.trajectory()
    lowest = float(geodetic(trajectory)[:, 0].min())
    drag_on = environment.drag if environment.drag is not None else lowest < DRAG_DEFAULT_BELOW_KM
    if environment.drag is None:
        said = "with" if drag_on else "without"
        print(
            f"sunwind: notice: {said} drag: the orbit's lowest altitude is {lowest:.0f} km "
            f"({'below' if drag_on else 'above'} {DRAG_DEFAULT_BELOW_KM:g} km; --srp/--drag choose)",
            file=sys.stderr,
        )
    shared = {"sampling": sampling, "reference_point_m": references["reference_point_m"]}
    srp = None
    if environment.srp:
        srp = SrpSetup(reflections=reflections, **shared)
    drag = None
    if drag_on:
        molecules = replace(reflections, mode=output["gas_reflections"])
        drag = GasOptions(
            gas_sampling=GasSampling(sky_rays=output["sky_rays"]), reflections=molecules, **shared
        )
    planet = None
    if environment.earth is not None:
        surface = SrpSetup(reflections=reflections, **shared)
        planet = environment.earth.terms(surface)
    loads = OrbitLoads(  # checked before the model is loaded; the Earth's terms sized once it is
        srp,
        drag,
        environment.air,
        output["hinge_step"],
        planet,
        flux_1au_W_m2=environment.flux_1au_W_m2,
        sensitivities=output["sensitivities"],
    )
    light_needed = srp is not None or planet is not None
    model = loaded(source if light_needed else drag_only(source), **references)
    checkpoint = (
        None
        if output["output"] is None
        else output["output"].with_name(output["output"].name + ".checkpoint")
    )
    if checkpoint is not None:
        check_place(checkpoint)
    if planet is not None:  # the largest cap, at the lowest altitude; --step is the time's here
        check_earth_step(max(lowest, 0.0), planet.cell_deg)
        try:
            planet = planet.sized(model, len(trajectory.time_s))
        except InputError as error:
            raise error.renamed({"per_side": "--per-side", "thermal": "--thermal"}) from None
        if planet.transient and planet.initial_temperature_K is None:
            print(
                "sunwind: notice: --thermal transient starts from the equilibrium of the first step "
                "(--initial-temperature K sets one temperature for every node)",
                file=sys.stderr,
            )
    begin = time.perf_counter()
    steps = len(trajectory.time_s)
    # when the steps start (the run's first progress, once precomputes are made) and, with the thermal
    # transient, when its integration after the steps starts (progress past the steps)
    started: list[float] = []
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn())
    with progress_bar(*columns) as bar:
        task = bar.add_task("orbit", total=steps)

        def progress(done: int) -> None:
            if not started or (done > steps and len(started) == 1):
                started.append(time.perf_counter())
            if done > steps:
                bar.update(task, description="thermal transient", completed=done - steps)
            else:
                bar.update(task, completed=done)

        run = sweep_run(output, checkpoint, progress)
        with interruptible(bar, checkpoint):
            result = fly(
                model,
                trajectory,
                attitude,
                replace(loads, earth=planet),
                sun_eci=environment.sun_eci,
                eclipse=environment.eclipse,
                moon=environment.moon,
                run=run,
            )
    start, end = started[0] if started else begin, time.perf_counter()
    seconds = (started[1] if len(started) > 1 else end) - start
    thermal = f", then the thermal transient in {end - started[1]:.1f} s" if len(started) > 1 else ""
    print(
        f"sunwind: notice: {steps} steps in {seconds:.1f} s ({1e3 * seconds / steps:.0f} ms per step) "
        f"after {start - begin:.1f} s of precomputes{thermal}",
        file=sys.stderr,
    )
    written = []
    if output["output"] is not None:
        target = output["output"]
        if target.suffix == ".nc":
            result.to_dataset(environment.mass_kg).to_netcdf(target)
        else:
            result.write_csv(target)
        written.append(target)
    if output["plot"] is not None:
        from sunwind.forces.orbit.plots import plot_orbit

        plot_orbit(result, output["plot"])
        written.append(output["plot"])
    if output["plot_thermal"] is not None:
        from sunwind.forces.orbit.plots import plot_thermal

        plot_thermal(result, output["plot_thermal"])
        written.append(output["plot_thermal"])
    if output["as_json"]:
        print_json(model.craft, result.to_json(environment.mass_kg))
    else:
        _print_summary(model.craft.source, result, environment.mass_kg)
        if result.materials:
            _print_mean_sensitivities(result)
        for target in written:
            print(f"  wrote {target}")
    if "error_estimate_force" in result.series:
        series = (result.series["error_estimate_force"], result.series["error_estimate_torque"])
        warn_beyond({"orbit": series}, sampling.tolerance, "steps")


def _check_heat_outputs(earth: EarthRequest | None, output: dict) -> None:
    """Refuse ``--plot-thermal`` without the Earth's radiation, and ``--per-side`` with nowhere to write."""
    if output["plot_thermal"] is not None and earth is None:
        raise InputError("--plot-thermal needs --earth-radiation", hint="add --earth-radiation")
    if earth is not None and earth.per_side and output["output"] is None and not output["as_json"]:
        raise InputError(
            "--per-side records go to the time series: without -o or --json they would be lost",
            hint="add -o FILE.nc (the sides as coordinates), -o FILE.csv or --json",
        )


def _print_mean_sensitivities(result) -> None:
    """The orbit means of the derivatives of the summed force and torque, every nonzero one."""
    t, s = result.series["time_s"], result.series
    if len(t) < 2:
        force, torque = s["sensitivity_force_N"][0], s["sensitivity_torque_Nm"][0]
    else:
        span = t[-1] - t[0]
        force = np.trapezoid(s["sensitivity_force_N"], t, axis=0) / span
        torque = np.trapezoid(s["sensitivity_torque_Nm"], t, axis=0) / span
    point = np.asarray(result.attributes["reference_point_m"], dtype=float)
    print("  orbit means of the derivatives:")
    print_sensitivities(Sensitivities(result.materials, force, torque, point))


def _print_summary(name: str, result, mass_kg: float | None) -> None:
    summary = result.summary(mass_kg)
    attrs = result.attributes
    steps = summary["steps"]
    print(f"sunwind orbit: {name}: {steps} steps over {summary['duration_s']:g} s")
    print(f"  orbit      {attrs['trajectory']}")
    print(f"  attitude   {attrs['attitude']}; terms: {attrs['terms']}")
    for pattern, angles in result.hinge_angles_deg.items():
        print(f"  hinge      {pattern} {angles.min():+.1f} to {angles.max():+.1f} deg")
    point = vector(np.array(attrs["reference_point_m"]), "{:+.4f}")
    print(f"  reference  {point} m ({attrs['reference_point']})")
    sunlit, shadow, count = (
        summary["sunlit_fraction"],
        summary["shadow_equivalent_s"],
        len(summary["eclipses_s"]),
    )
    print(
        f"  sunlit     {sunlit:.4f} of the time; eclipses: {count}, {shadow:.0f} s of full-shadow equivalent"
    )
    print(f"  mean force body {vector(np.array(summary['mean_force_body_N']))} N")
    print(f"  mean torque body {vector(np.array(summary['mean_torque_body_Nm']))} N m")
    for term in ("albedo", "infrared", "thermal"):
        if f"mean_{term}_force_body_N" in summary:
            print(f"    of it {term:<9}{vector(np.array(summary[f'mean_{term}_force_body_N']))} N")
    for name, part in summary.get("parts", {}).items():
        heat = ", ".join(f"{part[f'mean_{k}_W']:.4g}" for k in PART_SOURCES)
        span = (
            f"; {part['min_temperature_K']:.1f} to {part['max_temperature_K']:.1f} K"
            if "min_temperature_K" in part
            else ""
        )
        print(f"  part {name}: mean absorbed solar, albedo, infrared, reflected {heat} W{span}")
    if attrs.get("thermal") == "transient":
        start = attrs["thermal_initial_temperature_K"]
        start = f"{start:g} K" if isinstance(start, float) else f"the {start}"
        print(
            f"  thermal    transient from {start}, tolerance {attrs['thermal_tolerance_K']:g} K per step; "
            f"estimated error at most {summary['thermal_error_worst_K']:.2g} K"
        )
    print(f"  largest torque {summary['max_torque_Nm']:.4e} N m at t = {summary['max_torque_time_s']:g} s")
    worst = summary.get("error_estimate_worst")
    estimate = None if worst is None else ErrorEstimate(worst["force"], worst["torque"])
    print(f"  shadow error   {'' if worst is None else 'worst step: '}{estimated(estimate)}")
    print(f"  angular impulse body {vector(np.array(summary['angular_impulse_body_Nms']))} N m s")
    print(f"  angular impulse ECI  {vector(np.array(summary['angular_impulse_eci_Nms']))} N m s")
    if "momentum_per_orbit_Nms" in summary:
        print(f"  momentum per orbit {summary['momentum_per_orbit_Nms']:.4e} N m s (ECI, secular)")
    for key, label, unit in (
        ("drag_area_m2", "C_D A", "m^2"),
        ("srp_area_m2", "C_R A", "m^2"),
        ("ballistic_coefficient_m2_kg", "C_D A / m", "m^2/kg"),
        ("srp_coefficient_m2_kg", "C_R A / m", "m^2/kg"),
    ):
        if key in summary:
            print(f"  {label:<10} {summary[key]:.5g} {unit} (orbit mean)")
