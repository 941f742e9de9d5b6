"""The ``sunwind`` command line: parse arguments, make one API call, print text or ``--json``."""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from pathlib import Path

import click
import numpy as np

from sunwind.geometry.errors import InputError, SunwindError
from sunwind.geometry.materials import GSI_MODELS, GasSurface, Material
from sunwind.geometry.spacecraft import Spacecraft, load_spacecraft


@click.group(context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(package_name="sunwind", message="%(prog)s %(version)s")
def app() -> None:
    """Solar-radiation-pressure forces and torques on a spacecraft mesh, with ray-cast shadowing.

    Body frame of the mesh, SI units. Run `sunwind COMMAND --help` for each command.
    """


def model_options(command: Callable) -> Callable:
    """The options that say how to load a mesh and give it materials."""
    options = [
        click.argument("mesh", type=click.Path(path_type=Path)),
        click.option("--materials", "-m", type=click.Path(path_type=Path), help="Materials TOML file."),
        click.option(
            "--reflectivity", type=float, help="Uniform material for parts without one: reflectivity rho."
        ),
        click.option("--specular-fraction", type=float, help="Uniform material: specular share beta."),
        click.option(
            "--transmissivity", type=float, help="Uniform material: transmissivity sigma [default 0]."
        ),
        click.option(
            "--two-sided", multiple=True, metavar="GLOB", help="Treat matching parts as two-sided sheets."
        ),
        click.option("--unit", help="Mesh length unit: m, mm, cm, in [default: the file's own, else m]."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def view_factor_options(command: Callable) -> Callable:
    """The options that say how view factors are sampled and cached."""
    options = [
        click.option(
            "--view-rays",
            type=int,
            help="Hemisphere rays per side for view factors [default: more on small models, at least 256].",
        ),
        click.option(
            "--cache-dir",
            type=click.Path(path_type=Path, file_okay=False),
            help="Where view factors are kept [default: $SUNWIND_CACHE_DIR, else the user cache].",
        ),
        click.option("--no-cache", is_flag=True, help="Neither read nor write the view-factor cache."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def reflection_settings(mode: str, cutoff: float, depth: int, view_rays, cache_dir, no_cache: bool):
    """:class:`sunwind.forces.reflection.plan.ReflectionSettings` from the command line."""
    from sunwind.forces.reflection.plan import ReflectionSettings

    cache = False if no_cache else cache_dir
    return ReflectionSettings(mode, cutoff, depth, view_rays, cache)


def uniform_material(
    rho: float | None, beta: float | None, sigma: float | None, gas: dict | None = None
) -> Material | None:
    """The command-line uniform material, or None when no flag is given.

    ``gas`` holds the gas-surface flags given (keys of :data:`sunwind.geometry.materials.GAS_DEFAULTS`); a
    drag-only run may give them without optics, and the optics are then not used (all zero).
    """
    if rho is None and beta is None and sigma is None:
        if not gas:
            return None
        return Material.checked(
            "uniform", {"reflectivity": 0.0, "specular_fraction": 0.0, **gas}, "command line"
        )
    if rho is None or beta is None:
        raise InputError(
            "a uniform material needs --reflectivity and --specular-fraction",
            hint="e.g. --reflectivity 0.3 --specular-fraction 0.5 [--transmissivity 0]",
        )
    values = {"reflectivity": rho, "specular_fraction": beta, "transmissivity": sigma or 0.0, **(gas or {})}
    return Material.checked("uniform", values, source="command line")


def model_recipe(options: dict, gas: dict | None = None):
    """Pop the :func:`model_options` from ``options``: a :class:`sunwind.forces.tables.sweep.ModelRecipe`.

    Gas-surface flags (``gas``) make the uniform material's gas law and override the gas law of every
    material of a materials file.
    """
    from sunwind.forces.tables.sweep import ModelRecipe

    optics = options.pop("reflectivity"), options.pop("specular_fraction"), options.pop("transmissivity")
    materials = options.pop("materials")
    return ModelRecipe(
        mesh=str(options.pop("mesh")),
        materials=None if materials is None else str(materials),
        unit=options.pop("unit"),
        uniform=uniform_material(*optics, gas),
        two_sided=tuple(options.pop("two_sided")),
        gas=tuple((gas or {}).items()),
    )


def load_model(options: dict, gas: dict | None = None) -> Spacecraft:
    """Load the mesh named by :func:`model_options` (see :func:`model_recipe`); print repairs made as
    notices on stderr."""
    return loaded(model_recipe(options, gas))


def loaded(recipe) -> Spacecraft:
    """The spacecraft of a :class:`sunwind.forces.tables.sweep.ModelRecipe`, its repair notices printed on
    stderr."""
    craft = recipe.load()
    for notice in craft.notices:
        print(f"sunwind: notice: {craft.source}: {notice}", file=sys.stderr)
    return craft


def _vec(v: np.ndarray, fmt: str = "{:+.6e}") -> str:
    return "[" + "  ".join(fmt.format(x) for x in v) + "]"


@app.command()
@model_options
@click.option(
    "--sun",
    nargs=3,
    type=float,
    default=None,
    metavar="X Y Z",
    help="Sun direction in the body frame, spacecraft to Sun.",
)
@click.option(
    "--sun-azel",
    nargs=2,
    type=float,
    default=None,
    metavar="AZ EL",
    help="Sun azimuth and elevation [deg]: az = atan2(y, x), el = asin(z).",
)
@click.option("--flux", type=float, help="Solar flux [W/m^2] [default 1361, i.e. 1 au].")
@click.option("--distance-au", type=float, help="Distance from the Sun [au]: flux = 1361 / r^2.")
@click.option(
    "--ref-point",
    nargs=3,
    type=float,
    default=None,
    metavar="X Y Z",
    help="Torque reference point [m] [default: volume centroid if closed, else area centroid].",
)
@click.option(
    "--samples",
    type=int,
    help="Shadow-ray points per facet side, rounded up to a square [default: adaptive].",
)
@click.option(
    "--tolerance",
    type=float,
    default=1e-3,
    show_default=True,
    help="Adaptive sampling: convergence threshold on a side's lit share.",
)
@click.option(
    "--reflections",
    type=click.Choice(["none", "specular", "full", "auto"]),
    default="auto",
    show_default=True,
    help="Inter-reflection: none; specular beams only; full (beams and diffuse balance); "
    "auto = full when K_IS >= 0.1, else none.",
)
@click.option(
    "--reflection-cutoff",
    type=float,
    default=1e-6,
    show_default=True,
    help="Drop a reflected beam below this share of the power its chain started with.",
)
@click.option(
    "--reflection-depth", type=int, default=32, show_default=True, help="Most surfaces a beam chain meets."
)
@view_factor_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def srp(
    sun,
    sun_azel,
    flux,
    distance_au,
    ref_point,
    samples,
    tolerance,
    reflections,
    reflection_cutoff,
    reflection_depth,
    view_rays,
    cache_dir,
    no_cache,
    as_json,
    **model,
) -> None:
    """Solar-radiation force and torque for one Sun direction, with self-shadowing and inter-reflection."""
    from sunwind.forces.radiation.law import solar_flux
    from sunwind.forces.srp import srp as evaluate_srp
    from sunwind.geometry.directions import azel_to_vector, finite_point, unit_vector
    from sunwind.geometry.rays.shadows import level_for_samples

    # arguments are checked before the mesh is loaded, so a typo costs no wait
    if (sun is None) == (sun_azel is None):
        raise InputError("give the Sun direction with --sun X Y Z or --sun-azel AZ EL (one of them)")
    sun_vector = unit_vector(sun, "--sun") if sun is not None else azel_to_vector(*sun_azel, "--sun-azel")
    solar_flux(flux, distance_au)
    if ref_point is not None:
        finite_point(ref_point, "--ref-point")
    if samples is not None:
        level_for_samples(samples)
    if not 0 < tolerance < 1:
        raise InputError(f"--tolerance {tolerance} must lie in (0, 1)")
    settings = reflection_settings(
        reflections, reflection_cutoff, reflection_depth, view_rays, cache_dir, no_cache
    )
    craft = load_model(model)
    result = evaluate_srp(
        craft,
        sun_vector,
        flux_W_m2=flux,
        distance_au=distance_au,
        reference_point_m=ref_point,
        samples=samples,
        tolerance=tolerance,
        reflections=settings,
    )
    if as_json:
        header = {"mesh": craft.source, "unit": craft.unit, "triangles": craft.n_facets}
        print(json.dumps({**header, **result.to_json(), "notices": list(craft.notices)}, indent=2))
        return
    az, el = result.sun_azel_deg
    parts = f"{craft.n_facets} triangles, {len(craft.part_names)} parts, unit {craft.unit}"
    print(f"sunwind srp: {craft.source} ({parts})")
    print("  frame            body frame of the mesh; SI units")
    print(f"  sun vector       {_vec(result.sun_vector, '{:+.6f}')}  az {az:.3f} deg  el {el:.3f} deg")
    print(f"  flux             {result.flux_W_m2:.6g} W/m^2   pressure P = {result.pressure_Pa:.6e} Pa")
    print(f"  force   [N]      {_vec(result.force_N)}  |F| = {np.linalg.norm(result.force_N):.6e}")
    print(f"    direct         {_vec(result.direct_force_N)}")
    print(f"    reflected      {_vec(result.reflected_force_N)}")
    print(f"  torque  [N m]    {_vec(result.torque_Nm)}  |M| = {np.linalg.norm(result.torque_Nm):.6e}")
    print(f"    direct         {_vec(result.direct_torque_Nm)}")
    print(f"    reflected      {_vec(result.reflected_torque_Nm)}")
    print(f"  about   [m]      {_vec(result.reference_point_m, '{:+.6f}')}  ({result.reference_point})")
    print(f"  lit area         {result.lit_area_m2:.6f} m^2")
    print(f"  projected area   {result.projected_area_m2:.6f} m^2")
    print(f"  shadow rays      {result.rays} ({result.sampling})")
    print(
        f"  reflections      {result.reflections} (asked: {result.settings.mode}); "
        f"K_IS = {result.k_is:.4f} (eq. 7; inter-reflection matters from 0.1)"
    )
    power = result.power
    print(
        f"  power   [W]      incident {power.incident_W:.6g}, absorbed {power.absorbed_W:.6g}, "
        f"escaped {power.escaped_W:.6g}, cut off {power.truncated_W:.3g} (imbalance {power.imbalance:.1e})"
    )
    chains, view = result.reflected.chains, result.reflected.view
    if chains is not None:
        print(f"  beam rays        {chains.rays}, chains up to {chains.depth} surfaces")
    if view is not None and result.reflections == "full":
        print(f"  view factors     {view.rays_per_side} rays per side, {view.origin}")


def gas_options(command: Callable) -> Callable:
    """Gas-surface flags: the uniform material's gas law, or an override of every material's."""
    options = [
        click.option(
            "--gsi",
            type=click.Choice(GSI_MODELS),
            help="Gas-surface model [default sentman, or the materials file's].",
        ),
        click.option("--energy-accommodation", type=float, help="alpha_E of sentman and dria [default 1]."),
        click.option(
            "--normal-accommodation",
            type=float,
            help="sigma_n of schaaf-chambre, alpha_n of cll [default 1].",
        ),
        click.option(
            "--tangential-accommodation", type=float, help="sigma_t of schaaf-chambre and cll [default 1]."
        ),
        click.option("--wall-temperature", type=float, help="Wall temperature T_w [K] [default 300]."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def flow_options(command: Callable) -> Callable:
    """The flow velocity and the atmosphere (see :mod:`sunwind.forces.gas.flow`)."""
    options = [
        click.option(
            "--velocity",
            nargs=3,
            type=float,
            default=None,
            metavar="X Y Z",
            help="v_rel: spacecraft velocity relative to the atmosphere, body frame [m/s].",
        ),
        click.option(
            "--flow-azel",
            nargs=2,
            type=float,
            default=None,
            metavar="AZ EL",
            help="Direction of v_rel [deg], az = atan2(y, x), el = asin(z); with --speed or --altitude.",
        ),
        click.option("--speed", type=float, help="|v_rel| [m/s] [default: circular orbit at --altitude]."),
        click.option(
            "--corotating", is_flag=True, help="Subtract the Earth-rotating atmosphere from the orbit speed."
        ),
        click.option(
            "--heading",
            type=float,
            default=90.0,
            show_default=True,
            help="With --corotating: direction of motion [deg from north, 90 = east].",
        ),
        click.option("--altitude", type=float, help="Altitude [km] for NRLMSIS 2.1 (and the orbit speed)."),
        click.option("--lat", type=float, default=0.0, show_default=True, help="Geodetic latitude [deg]."),
        click.option("--lon", type=float, default=0.0, show_default=True, help="Longitude [deg]."),
        click.option("--time", default="2024-01-01T00:00:00Z", show_default=True, help="UTC time, ISO 8601."),
        click.option("--f107", type=float, default=150.0, show_default=True, help="Daily F10.7 [sfu]."),
        click.option("--f107a", type=float, default=150.0, show_default=True, help="81-day F10.7 [sfu]."),
        click.option("--ap", type=float, default=4.0, show_default=True, help="Daily Ap index."),
        click.option("--density", type=float, help="Explicit atmosphere: mass density [kg/m^3]."),
        click.option("--temperature", type=float, help="Explicit atmosphere: temperature [K]."),
        click.option("--composition", help='Explicit atmosphere: mole fractions, e.g. "O:0.7,N2:0.3".'),
        click.option(
            "--normalise-composition", is_flag=True, help="Rescale mole fractions that do not sum to 1."
        ),
        click.option(
            "--ref-area", type=float, help="Coefficient reference area [m^2] [default total area / 4]."
        ),
        click.option(
            "--ref-length",
            type=float,
            help="Moment-coefficient reference length [m] [default largest extent].",
        ),
    ]
    for option in reversed(options):
        command = option(command)
    return command


_GAS_FLAGS = (
    "gsi",
    "energy_accommodation",
    "normal_accommodation",
    "tangential_accommodation",
    "wall_temperature",
)
_FLOW_FLAGS = ("velocity", "flow_azel", "speed", "corotating", "heading")
_AIR_FLAGS = {
    "altitude": "altitude_km",
    "lat": "latitude_deg",
    "lon": "longitude_deg",
    "time": "time",
    "f107": "f107",
    "f107a": "f107a",
    "ap": "ap",
    "density": "density_kg_m3",
    "temperature": "temperature_K",
    "composition": "composition",
    "normalise_composition": "normalise_composition",
}


def free_stream(options: dict):
    """Pop the flow, atmosphere and gas flags from ``options``: ``(v_rel, atmosphere, gas flags)``.

    Everything is checked here, before a mesh is loaded.
    """
    from sunwind.forces.gas.flow import AtmosphereOptions, FlowOptions, atmosphere, flow_velocity

    gas = {key: value for key in _GAS_FLAGS if (value := options.pop(key)) is not None}
    if gas:
        GasSurface.checked("command line", gas)
    flow = FlowOptions(*(options.pop(key) for key in _FLOW_FLAGS))
    air = AtmosphereOptions(**{field: options.pop(flag) for flag, field in _AIR_FLAGS.items()})
    return flow_velocity(flow, air), atmosphere(air), gas


def _print_drag(result, heading: str) -> None:
    """The human-readable drag report."""
    from sunwind.forces.drag_result import VALIDITY

    air = result.atmosphere
    cd, cs, cl = result.force_coefficients
    az, el = result.to_json()["flow_azel_deg"]
    print(heading)
    print("  frame            body frame of the mesh; SI units")
    print(f"  v_rel   [m/s]    {_vec(result.velocity_m_s, '{:+.3f}')}  az {az:.3f} deg  el {el:.3f} deg")
    print(f"  atmosphere       {air.source}")
    print(
        f"                   rho {air.density_kg_m3:.6e} kg/m^3, T {air.temperature_K:.1f} K, "
        f"q = {result.dynamic_pressure_Pa:.6e} Pa, speed ratio {result.speed_ratio:.3f}"
    )
    print(f"  force   [N]      {_vec(result.force_N)}  |F| = {np.linalg.norm(result.force_N):.6e}")
    print(f"    panel law      {_vec(result.direct_force_N)}")
    print(f"    re-emission    {_vec(result.reflected_force_N)}")
    print(f"  torque  [N m]    {_vec(result.torque_Nm)}  |M| = {np.linalg.norm(result.torque_Nm):.6e}")
    print(f"  about   [m]      {_vec(result.reference_point_m, '{:+.6f}')}  ({result.reference_point})")
    print(
        f"  coefficients     CD {cd:.6f}  CL {cl:+.6f}  CS {cs:+.6f}  CM {_vec(result.moment_coefficients)}"
    )
    print(
        f"{'':19}A_ref {result.reference_area_m2:.6g} m^2, L_ref {result.reference_length_m:.6g} m; "
        "C = F/(q A_ref), C_M = M/(q A_ref L_ref)"
    )
    print(f"  projected area   {result.projected_area_m2:.6f} m^2 (normal to the flow)")
    k_is = "n/a" if result.reflected.k_is is None else f"{result.reflected.k_is:.4f}"
    print(f"  re-emission      {result.reflections} (asked: {result.settings.mode}); molecular K_IS = {k_is}")
    print(f"  shadow rays      {result.rays} ({result.sampling})")
    print(f"  validity         {VALIDITY}")


@app.command()
@model_options
@gas_options
@flow_options
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
    help="Re-emitted molecules striking other sides: none; full; auto = full when K_IS >= 0.1.",
)
@view_factor_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def drag(
    ref_point, samples, tolerance, reflections, view_rays, cache_dir, no_cache, as_json, **options
) -> None:
    """Free-molecular force and torque for one flow direction: gas-surface law, shadowing, re-emission."""
    from sunwind.forces.drag import drag as evaluate_drag

    velocity, air, gas = free_stream(options)
    settings = reflection_settings(reflections, 1e-6, 32, view_rays, cache_dir, no_cache)
    craft = load_model(options, gas)
    result = evaluate_drag(
        craft,
        velocity,
        air,
        reference_point_m=ref_point,
        samples=samples,
        tolerance=tolerance,
        reflections=settings,
        reference_area_m2=options.pop("ref_area"),
        reference_length_m=options.pop("ref_length"),
    )
    if as_json:
        header = {"mesh": craft.source, "unit": craft.unit, "triangles": craft.n_facets}
        print(json.dumps({**header, **result.to_json(), "notices": list(craft.notices)}, indent=2))
        return
    _print_drag(result, f"sunwind drag: {craft.source} ({craft.n_facets} triangles, unit {craft.unit})")


@app.command()
@model_options
@gas_options
@flow_options
@click.option("--sun", nargs=3, type=float, default=None, metavar="X Y Z", help="Sun direction, body frame.")
@click.option(
    "--sun-azel", nargs=2, type=float, default=None, metavar="AZ EL", help="Sun azimuth, elevation [deg]."
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
    help="Inter-reflection of light and of re-emitted molecules (auto: each by its own K_IS).",
)
@view_factor_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object: srp, drag, total.")
def forces(
    sun,
    sun_azel,
    flux,
    distance_au,
    ref_point,
    samples,
    tolerance,
    reflections,
    view_rays,
    cache_dir,
    no_cache,
    as_json,
    **options,
) -> None:
    """Solar-radiation pressure and free-molecular drag together for one attitude, and their total."""
    from sunwind.forces.drag import drag as evaluate_drag
    from sunwind.forces.radiation.law import solar_flux
    from sunwind.forces.srp import srp as evaluate_srp
    from sunwind.geometry.directions import azel_to_vector, unit_vector

    if (sun is None) == (sun_azel is None):
        raise InputError("give the Sun direction with --sun X Y Z or --sun-azel AZ EL (one of them)")
    sun_vector = unit_vector(sun, "--sun") if sun is not None else azel_to_vector(*sun_azel, "--sun-azel")
    solar_flux(flux, distance_au)
    velocity, air, gas = free_stream(options)
    settings = reflection_settings(reflections, 1e-6, 32, view_rays, cache_dir, no_cache)
    sizes = {"reference_area_m2": options.pop("ref_area"), "reference_length_m": options.pop("ref_length")}
    craft = load_model(options, gas)
    common = {
        "reference_point_m": ref_point,
        "samples": samples,
        "tolerance": tolerance,
        "reflections": settings,
    }
    light = evaluate_srp(craft, sun_vector, flux_W_m2=flux, distance_au=distance_au, **common)
    gas_result = evaluate_drag(craft, velocity, air, **common, **sizes)
    force = light.force_N + gas_result.force_N
    torque = light.torque_Nm + gas_result.torque_Nm
    if as_json:
        total = {
            "force_N": force.tolist(),
            "torque_Nm": torque.tolist(),
            "reference_point_m": light.reference_point_m.tolist(),
            "frame": "body frame of the mesh",
        }
        header = {"mesh": craft.source, "unit": craft.unit, "triangles": craft.n_facets}
        document = {**header, "srp": light.to_json(), "drag": gas_result.to_json(), "total": total}
        print(json.dumps({**document, "notices": list(craft.notices)}, indent=2))
        return
    print(f"sunwind forces: {craft.source} ({craft.n_facets} triangles, unit {craft.unit})")
    print(f"  total force  [N]    {_vec(force)}  |F| = {np.linalg.norm(force):.6e}")
    print(f"  total torque [N m]  {_vec(torque)}  about {_vec(light.reference_point_m, '{:+.6f}')} m")
    print(f"  srp force    [N]    {_vec(light.force_N)}  (sun {_vec(light.sun_vector, '{:+.4f}')})")
    print(f"  srp torque   [N m]  {_vec(light.torque_Nm)}")
    _print_drag(gas_result, "  drag:")


def _interference_report(model: dict, uniform: Material | None, settings) -> dict:
    """``k_is`` and view-factor figures of the mesh for ``sunwind info``; a note where it cannot load."""
    from sunwind.forces.reflection.plan import interference, model_view_factors

    try:
        craft = load_spacecraft(
            model["mesh"],
            model["materials"],
            unit=model["unit"],
            uniform=uniform,
            two_sided=model["two_sided"],
        )
    except SunwindError:
        return {"k_is": "not available until the checks pass"}
    view = model_view_factors(craft, settings)
    return {
        "k_is": interference(craft, settings),
        "view_factors": {
            "rays_per_side": view.rays_per_side,
            "origin": view.origin,
            "seconds": view.seconds,
            "open_sky_share": float(craft.side_areas @ view.escape_fraction / craft.side_areas.sum()),
            "reciprocity_error": view.reciprocity_error(craft.side_areas),
        },
    }


def main(argv: list[str] | None = None) -> None:
    """Entry point: run the app; report a bad input as one line on stderr with a non-zero exit, and a
    warning (a result outside a model's range, still given) as one line."""
    import warnings

    def one_line(message, category, filename, lineno, file=None, line=None) -> None:
        print(f"sunwind: warning: {message}", file=sys.stderr)

    shown = warnings.showwarning
    warnings.showwarning = one_line
    try:
        app.main(args=argv, prog_name="sunwind", standalone_mode=False)
    except SunwindError as error:
        print(f"sunwind: error: {error}", file=sys.stderr)
        sys.exit(1)
    except click.UsageError as error:
        if isinstance(error, getattr(click.exceptions, "NoArgsIsHelpError", ())):
            print(error.format_message())  # click >= 8.2 raises this for a bare `sunwind`
            return
        command = error.ctx.command_path if error.ctx else "sunwind"
        print(f"{command}: error: {error.format_message()} (see --help)", file=sys.stderr)
        sys.exit(2)
    except click.exceptions.Abort:
        print("sunwind: aborted", file=sys.stderr)
        sys.exit(130)
    except KeyboardInterrupt:
        print("sunwind: interrupted", file=sys.stderr)
        sys.exit(130)
    finally:
        warnings.showwarning = shown


@app.command()
@model_options
@view_factor_options
@click.option("--no-k-is", is_flag=True, help="Skip the view factors and K_IS (quick look at a large mesh).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def info(view_rays, cache_dir, no_cache, no_k_is, as_json, **model) -> None:
    """Describe a mesh: triangles, parts, materials, area, bounds, closed or not, checks, and K_IS."""
    from sunwind.geometry.summary import describe

    uniform = uniform_material(model["reflectivity"], model["specular_fraction"], model["transmissivity"])
    report = describe(model["mesh"], model["materials"], model["unit"], uniform, model["two_sided"])
    if not no_k_is:
        settings = reflection_settings("full", 1e-6, 1, view_rays, cache_dir, no_cache)
        report.update(_interference_report(model, uniform, settings))
    if as_json:
        print(json.dumps(report, indent=2))
        return
    print(f"sunwind info: {report['mesh']}")
    for key in ("unit", "triangles", "area_m2", "volume_m3", "closed", "reference_point", "k_is"):
        if key in report:
            print(f"  {key:<17}{report[key]}")
    if "view_factors" in report:
        view = report["view_factors"]
        print(
            f"  {'open sky':<17}{view['open_sky_share']:.4f} of diffusely reflected light escapes "
            f"(area-weighted); view factors: {view['rays_per_side']} rays per side, {view['origin']}"
        )
    low, high = report["bounds_m"]
    print(f"  {'bounds_m':<17}min {np.round(low, 6).tolist()}  max {np.round(high, 6).tolist()}")
    print("  checks:")
    for line in report["checks"]:
        print(f"    {line}")
    print("  parts:")
    for part in report["parts"]:
        print(
            f"    {part['name']:<28} {part['triangles']:>7} tri {part['area_m2']:>10.4f} m^2  "
            f"{part['surface']:<16}  {part['materials']}"
        )
    if report["materials"]:
        print(f"  materials:{'':<18}rho    beta   sigma  alpha")
        for m in report["materials"]:
            print(
                f"    {m['name']:<24}{m['reflectivity']:.3f}  {m['specular_fraction']:.3f}  "
                f"{m['transmissivity']:.3f}  {m['absorptivity']:.3f}"
            )


@app.command()
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
@click.option("--samples", type=int, default=1, show_default=True, help="Shadow-ray points per side.")
@click.option(
    "--sweep",
    is_flag=True,
    help="Time a whole grid sweep (SRP and drag, full reflections) and Dask 2 workers over 1 instead.",
)
@click.option("--step", type=float, default=5.0, show_default=True, help="Grid step of --sweep [deg].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def bench(mesh_path, materials, triangles, attitudes, samples, sweep, step, as_json) -> None:
    """Time SRP per attitude (direct against raw Embree on the same rays, then with full reflections)
    and free-molecular drag per attitude against SRP with the same reflection setting; or, with
    --sweep, a whole attitude sweep of the generated sample."""
    import time

    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    from sunwind.forces.bench import benchmark
    from sunwind.geometry.spacecraft import build_spacecraft

    if attitudes < 1:
        raise InputError(f"--attitudes {attitudes} must be at least 1")
    if sweep:
        _bench_sweep(triangles, step, samples, as_json)
        return
    start = time.perf_counter()
    if mesh_path is not None:
        craft = load_spacecraft(mesh_path, materials)
    else:
        from sunwind.meshes.samples import sample_spacecraft

        craft = build_spacecraft(sample_spacecraft(triangles))
    load_s = time.perf_counter() - start
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, transient=True, disable=as_json) as bar:
        task = bar.add_task("timing attitudes", total=attitudes)
        report = benchmark(
            craft, attitudes, samples, load_s=load_s, progress=lambda done: bar.update(task, completed=done)
        )
    if as_json:
        print(json.dumps({"mesh": craft.source, **report.to_json()}, indent=2))
        return
    print(f"sunwind bench: {craft.source} ({report.triangles} triangles, {report.sides} sides)")
    print(f"  machine                 {report.machine}; Embree on {report.threads} threads")
    print(f"  load / scene build      {report.load_s:.2f} s / {report.scene_build_s:.3f} s")
    print(f"  first call (compile)    {report.first_call_s:.2f} s")
    print(
        f"  direct SRP, {report.samples_per_side} pt/side   {report.per_attitude_ms:.2f} ms per attitude "
        f"(median {report.per_attitude_median_ms:.2f}), {report.attitudes} attitudes"
    )
    print(
        f"  rays                    {report.rays_per_attitude:.0f} per attitude, "
        f"{report.rays_per_s / 1e6:.2f} M rays/s"
    )
    print(
        f"  raw Embree, same rays   {report.raw_embree_ms:.2f} ms per attitude, "
        f"{report.raw_embree_rays_per_s / 1e6:.2f} M rays/s"
    )
    print(f"  overhead                {report.overhead:.2f}x raw Embree")
    print(
        f"  view factors            {report.view_factor_s:.1f} s once per model "
        f"({report.view_factor_rays_per_side} rays per side), {report.view_factor_MB:.0f} MB, "
        f"peak memory {report.view_factor_peak_MB:.0f} MB"
    )
    print(f"  diffuse balance setup   {report.exchange_setup_s:.2f} s once per model and materials")
    print(
        f"  full reflections        {report.full_per_attitude_ms:.2f} ms per attitude "
        f"(median {report.full_per_attitude_median_ms:.2f}), {report.full_over_direct:.2f}x direct-only, "
        f"{report.beam_rays_per_attitude:.0f} beam rays"
    )
    print(
        f"  drag, no re-emission    {report.drag_per_attitude_ms:.2f} ms per attitude (median), "
        f"{report.drag_over_srp:.2f}x SRP direct-only"
    )
    print(
        f"  drag, full re-emission  {report.drag_full_per_attitude_ms:.2f} ms per attitude (median), "
        f"{report.drag_full_over_srp_full:.2f}x SRP with full reflections"
    )
    print(
        f"  adaptive sampling       {report.adaptive_per_attitude_ms:.1f} ms per attitude, "
        f"{report.adaptive_rays_per_attitude:.0f} rays; with full reflections "
        f"{report.adaptive_full_per_attitude_ms:.1f} ms, {report.adaptive_full_over_direct:.2f}x"
    )
    print(f"  peak memory             {report.peak_memory_MB:.0f} MB")


def _bench_sweep(triangles: int, step: float, samples: int, as_json: bool) -> None:
    """``sunwind bench --sweep``: run and print :func:`sunwind.forces.bench.sweep_benchmark`."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    from sunwind.forces.bench import sweep_benchmark
    from sunwind.forces.tables.attitudes import direction_grid

    direction_grid(step)
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeRemainingColumn(),
    )
    with Progress(*columns, transient=True, disable=as_json) as bar:
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
        f"{report.distinct_directions} distinct directions, {report.samples_per_side} pt/side, "
        f"reflections {report.reflections}"
    )
    print(f"  precompute              {report.precompute_s:.1f} s (view factors, exchange, first calls)")
    print(
        f"  sweep SRP + drag        {report.sweep_s:.1f} s ({report.srp_per_attitude_ms:.1f} ms SRP, "
        f"{report.drag_per_attitude_ms:.1f} ms drag per attitude)"
    )
    print(
        f"  Dask, {report.dask_attitudes} attitudes      1 worker {report.dask_1_worker_s:.1f} s, "
        f"2 workers {report.dask_2_workers_s:.1f} s: speed-up {report.dask_speedup:.2f}x "
        f"(results identical: {report.dask_identical})"
    )


def _builder_params(kind: str, builder, words: list[str]) -> dict:
    """``--name value`` words after ``sunwind mesh KIND`` as keyword arguments of ``builder``.

    Types follow the builder's defaults: numbers, ``--flag/--no-flag`` for booleans, and several
    numbers for a sequence (``--size 1 2 3``).
    """
    import inspect

    signature = inspect.signature(builder).parameters
    params: dict = {}
    i = 0
    while i < len(words):
        word = words[i]
        if not word.startswith("--"):
            raise InputError(f"unexpected '{word}' for mesh {kind}", hint="give parameters as --name value")
        name = word[2:].replace("-", "_")
        negated = name.startswith("no_") and name[3:] in signature
        key = name[3:] if negated else name
        if key not in signature:
            valid = ", ".join("--" + p.replace("_", "-") for p in signature)
            raise InputError(f"mesh {kind} has no parameter --{name.replace('_', '-')}", hint=f"use {valid}")
        values = []
        i += 1
        while i < len(words) and not words[i].startswith("--"):
            values.append(words[i])
            i += 1
        default = signature[key].default
        try:
            if isinstance(default, bool):
                if values:
                    raise ValueError
                params[key] = not negated
            elif isinstance(default, (tuple, list)) or (len(values) > 1):
                params[key] = tuple(float(v) if "." in v or "e" in v.lower() else int(v) for v in values)
            elif len(values) == 1:
                params[key] = int(values[0]) if isinstance(default, int) else float(values[0])
            else:
                raise ValueError
        except ValueError:
            raise InputError(
                f"mesh {kind}: bad value for --{key.replace('_', '-')}: {' '.join(values)!r}",
                hint="give a number (or several for a size)",
            ) from None
    return params


@app.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True})
@click.argument("kind")
@click.option(
    "--output",
    "-o",
    type=click.Path(path_type=Path),
    required=True,
    help="File to write: .obj .stl .ply .glb .gltf .usda .usdc",
)
@click.pass_context
def mesh(ctx: click.Context, kind: str, output: Path) -> None:
    """Write a parametric mesh: plate, sphere, cylinder, cone, dish, box, box_wing, or sample.

    Parameters follow the kind, e.g. `sunwind mesh cylinder --radius 0.5 --length 2 --no-caps -o c.obj`,
    `sunwind mesh sample --triangles 100000 -o big.usda`. Frames: METHOD.md and README.
    """
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes import primitives

    if kind == "sample":
        from sunwind.meshes.samples import materials_toml, sample_spacecraft

        built = sample_spacecraft(**_builder_params(kind, sample_spacecraft, ctx.args))
    elif kind in primitives.PRIMITIVES:
        built = primitives.build(kind, **_builder_params(kind, primitives.PRIMITIVES[kind], ctx.args))
    else:
        kinds = ", ".join([*primitives.PRIMITIVES, "sample"])
        raise InputError(f"unknown mesh kind '{kind}'", hint=f"choose one of {kinds}")
    save_mesh(built, output)
    print(f"wrote {output}: {built.n_faces} triangles, parts {', '.join(built.part_names)}")
    if kind == "sample" and not output.suffix.lower().startswith(".usd"):
        materials = output.with_suffix(".toml")
        materials.write_text(materials_toml(built))
        print(f"wrote {materials}: its materials and two-sided sheets (use with --materials)")
    elif built.two_sided_parts:
        print(
            f"two-sided sheets: {', '.join(sorted(built.two_sided_parts))} (declare them, e.g. --two-sided)"
        )


@app.command()
def validate() -> None:
    """Run the validation cases against closed forms and print case, reference, computed, error."""
    from sunwind.validation.runner import main as run_validation

    if run_validation():
        raise SystemExit(1)


# the sweep and plot commands live in their own module; importing it registers them on ``app``
from sunwind.forces.cli import tables  # noqa: E402, F401
