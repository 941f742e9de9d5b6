"""Option groups of the commands: each adds its flags and hands the command one checked library object
built from them (a :class:`~sunwind.forces.model.ModelSource`, a Sun direction and flux, sampling,
reflection settings, ...), so every command takes a few arguments and nothing is checked twice.

Checks are the library's own, made when the group builds its object, before any mesh is loaded; the
Python parameter names in their messages become the flags here (:data:`FLAGS`).
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

import click
import numpy as np
from click.core import ParameterSource
from numpy.typing import NDArray

from sunwind.forces.model import Model, ModelSource
from sunwind.forces.radiation import solar_flux
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.reflection.settings import DEFAULT_CUTOFF, DEFAULT_DEPTH, MODES
from sunwind.geometry.directions import azel_to_vector, finite_point, unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GAS_DEFAULTS, GSI_MODELS, GasSurface, Material
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE
from sunwind.geometry.references import check_reference_sizes

#: The flag of each Python parameter the library names in its messages.
FLAGS = {
    "flux_W_m2": "--flux",
    "distance_au": "--distance-au",
    "reference_point_m": "--ref-point",
    "reference_area_m2": "--ref-area",
    "reference_length_m": "--ref-length",
    "samples": "--samples",
    "method": "--cap-method",
    "tolerance": "--tolerance",
    "reflections": "--reflections",
    "cutoff": "--reflection-cutoff",
    "depth": "--reflection-depth",
    "rays_per_side": "--view-rays",
    "sky_rays": "--sky-rays",
    "velocity_m_s": "--velocity",
    "speed_m_s": "--speed",
    "altitude_km": "--altitude",
    "latitude_deg": "--lat",
    "longitude_deg": "--lon",
    "time": "--epoch",
    "f107": "--f107",
    "f107a": "--f107a",
    "ap": "--ap",
    "density_kg_m3": "--density",
    "temperature_K": "--temperature",
    "composition": "--composition",
    "normalise": "--normalise-composition",
    "heading_deg": "--heading",
    "nadir": "--nadir",
    "velocity_direction": "--flow-azel",
    "step_deg": "--step",
    "cell_deg": "--step",
    "albedo": "--albedo",
    "infrared_W_m2": "--earth-ir",
    "albedo_model": "--albedo-model",
    "pole": "--pole",
    "chunk": "--chunk",
    "workers": "--workers",
    "scheduler": "--scheduler",
    "resume": "--resume",
    "format": "--format",
    "triangles": "--triangles",
    "attitudes": "--attitudes",
    "divisions": "--divisions",
    "subdivisions": "--subdivisions",
    "segments": "--segments",
    "rings": "--rings",
    "facet_size": "--facet-size",
    "no_view": "--no-view",
    "two_sided": "--two-sided",
    "articulate": "--articulate",
    "sun_eci": "--sun-eci",
    "moon": "--moon",
    "elements": "--elements",
    "propagator": "--propagator",
    "attitude": "--attitude",
    "interpolation": "--interpolation",
    "eclipse": "--eclipse",
}


def given(name: str) -> bool:
    """Tell whether an option of the running command was given rather than left at its default.

    Parameters
    ----------
    name : str
        The option's keyword (``"step"`` for ``--step``).

    Returns
    -------
    bool
        True when the value came from the command line or the environment, False when it is the
        option's default.

    Raises
    ------
    RuntimeError
        Called outside a running click command.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @click.option("--step", type=float, default=10.0)
    ... def demo(step):
    ...     print(step, given("step"))
    >>> demo.main([], standalone_mode=False)
    10.0 False
    >>> demo.main(["--step", "10"], standalone_mode=False)
    10.0 True
    """
    source = click.get_current_context().get_parameter_source(name)
    return source in (ParameterSource.COMMANDLINE, ParameterSource.ENVIRONMENT)


def group(name: str, options: list[Callable], build: Callable[[dict], object] | None = None) -> Callable:
    """Make a decorator that adds a group of options to a command and hands it one object built from them.

    The command receives, instead of the options' values, the single keyword argument ``name``:
    ``build(values)``, where ``values`` maps each option's keyword to its value.

    Parameters
    ----------
    name : str
        The keyword argument the command receives.
    options : list of callable
        Click option (or argument) decorators, shown in the help in this order.
    build : callable or None, optional
        Makes the object from the dict of the options' values; it raises for values it refuses.
        None (the default) hands the command the dict itself.

    Returns
    -------
    callable
        A decorator for a click command function (apply it below ``@click.command()``).

    Examples
    --------
    >>> import click
    >>> size = [click.option("--width", type=float, default=1.0), click.option("--height", type=float)]
    >>> @click.command()
    ... @group("area", size, lambda values: values["width"] * values["height"])
    ... def demo(area):
    ...     print(f"area {area} m^2")
    >>> demo.main(["--height", "2.5"], standalone_mode=False)
    area 2.5 m^2
    """

    def decorate(command: Callable) -> Callable:
        @functools.wraps(command)
        def run(**kwargs):
            values = {key: kwargs.pop(key) for key in names}
            kwargs[name] = values if build is None else build(values)
            return command(**kwargs)

        run.__click_params__ = list(getattr(command, "__click_params__", []))
        before = len(run.__click_params__)
        for option in reversed(options):
            run = option(run)
        names = [param.name for param in run.__click_params__[before:]]
        return run

    return decorate


# --------------------------------------------------------------------------------------------- model
_GAS_OPTIONS = [
    click.option(
        "--gsi",
        type=click.Choice(GSI_MODELS),
        help="Gas-surface model [default sentman, or the materials file's].",
    ),
    click.option("--energy-accommodation", type=float, help="alpha_E of sentman and dria [default 1]."),
    click.option(
        "--normal-accommodation", type=float, help="sigma_n of schaaf-chambre, alpha_n of cll [default 1]."
    ),
    click.option(
        "--tangential-accommodation", type=float, help="sigma_t of schaaf-chambre and cll [default 1]."
    ),
    click.option("--wall-temperature", type=float, help="Wall temperature T_w [K] [default 300]."),
]
_MODEL_OPTIONS = [
    click.argument("mesh", type=click.Path(path_type=Path)),
    click.option("--materials", "-m", type=click.Path(path_type=Path), help="Materials TOML file."),
    click.option(
        "--reflectivity", type=float, help="Uniform material for parts without one: reflectivity rho."
    ),
    click.option("--specular-fraction", type=float, help="Uniform material: specular share beta."),
    click.option("--transmissivity", type=float, help="Uniform material: transmissivity sigma [default 0]."),
    click.option(
        "--emissivity",
        type=float,
        help="Uniform material: hemispherical infrared emissivity eps, 0 to 1 [default none; the "
        "planet's radiation and temperatures need one].",
    ),
    click.option(
        "--two-sided", multiple=True, metavar="GLOB", help="Treat matching parts as two-sided sheets."
    ),
    click.option("--unit", help="Mesh length unit: m, mm, cm, in [default: the file's own, else m]."),
    click.option(
        "--articulate",
        multiple=True,
        metavar="GLOB=DEG",
        help="Hold the parts of the materials file's hinge [articulation.GLOB] at DEG [deg], whatever its "
        "angle, tracking or schedule there.",
    ),
]


def uniform_material(values: dict, gas: dict | None = None) -> Material | None:
    """Make the uniform material of the command-line optics flags.

    Parameters
    ----------
    values : dict
        The model flags by keyword; ``reflectivity``, ``specular_fraction``, ``transmissivity`` and
        ``emissivity`` are read (None: not given). A missing transmissivity is 0.
    gas : dict or None, optional
        The gas-surface flags given, as materials-file keys (``gsi``, ``wall_temperature``, ...),
        for the material's gas law.

    Returns
    -------
    Material or None
        The material ``"uniform"``; None when no optics flag is given.

    Raises
    ------
    InputError
        An optics flag without both ``--reflectivity`` and ``--specular-fraction``.
    MaterialError
        Values a material refuses (one outside [0, 1], reflectivity and transmissivity summing above
        1, ...).

    Examples
    --------
    >>> flags = {"reflectivity": 0.3, "specular_fraction": 0.5, "transmissivity": None, "emissivity": None}
    >>> material = uniform_material(flags)
    >>> material.name, material.reflectivity, material.transmissivity
    ('uniform', 0.3, 0.0)
    >>> uniform_material({**flags, "specular_fraction": None})
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: a uniform material needs --reflectivity and --specular-fraction; ...
    """
    rho, beta, sigma = values["reflectivity"], values["specular_fraction"], values["transmissivity"]
    eps = values["emissivity"]
    if rho is None and beta is None and sigma is None and eps is None:
        return None
    if rho is None or beta is None:
        raise InputError(
            "a uniform material needs --reflectivity and --specular-fraction",
            hint="e.g. --reflectivity 0.3 --specular-fraction 0.5 [--transmissivity 0] [--emissivity 0.8]",
        )
    optics = {"reflectivity": rho, "specular_fraction": beta, "transmissivity": sigma or 0.0}
    if eps is not None:
        optics["emissivity"] = eps
    return Material.checked("uniform", {**optics, **(gas or {})}, source="command line")


def drag_only(source: ModelSource) -> ModelSource:
    """Adapt a model source to a run that computes drag alone, which needs no optics.

    Without a uniform material on the command line, parts without a material take a uniform material
    with the gas law of the gas flags (their defaults where none is given) and no optics.

    Parameters
    ----------
    source : ModelSource
        The model source of the command's flags.

    Returns
    -------
    ModelSource
        ``source`` itself when it has a uniform material, else a copy with the gas-only one.

    Examples
    --------
    >>> from sunwind.forces.model import ModelSource
    >>> source = drag_only(ModelSource("craft.obj", gas=(("wall_temperature", 250.0),)))
    >>> source.uniform.reflectivity, source.uniform.gas.wall_temperature_K
    (0.0, 250.0)
    """
    if source.uniform is not None:
        return source
    gas = {"reflectivity": 0.0, "specular_fraction": 0.0, **dict(source.gas)}
    return replace(source, uniform=Material.checked("uniform", gas, "command line"))


def _source(values: dict) -> ModelSource:
    """The model source of the mesh, material and gas flags: the gas flags make the uniform material's
    gas law and override the gas law of every material of a materials file."""
    gas = {key: values.pop(key) for key in GAS_DEFAULTS if key in values}
    gas = {key: value for key, value in gas.items() if value is not None}
    if gas:
        GasSurface.checked("command line", gas)
    materials = values["materials"]
    return ModelSource(
        mesh=str(values["mesh"]),
        materials=None if materials is None else str(materials),
        unit=values["unit"],
        uniform=uniform_material(values, gas),
        two_sided=tuple(values["two_sided"]),
        gas=tuple(gas.items()),
        articulate=values["articulate"],
    )


def _angles(words: tuple[str, ...]) -> dict[str, list[float]]:
    """``--articulate GLOB=DEG[,DEG...]`` flags as each glob's angles [deg], each glob once."""
    angles: dict[str, list[float]] = {}
    for word in words:
        glob, _, text = word.rpartition("=")
        try:
            values = [float(v) for v in text.split(",")]
        except ValueError:
            values = []
        if not glob or not values:
            raise InputError(f"--articulate {word!r} is not GLOB=DEG", hint='e.g. --articulate "wing_*=30"')
        if glob in angles:
            raise InputError(f'--articulate gives hinge "{glob}" twice', hint="give each hinge one entry")
        angles[glob] = values
    return angles


def _held(values: dict) -> tuple[tuple[str, float], ...]:
    """The angle of each ``--articulate`` hinge, one each (a list is a sweep's table dimension)."""
    angles = _angles(values.pop("articulate"))
    for glob, listed in angles.items():
        if len(listed) > 1:
            raise InputError(
                f'--articulate "{glob}" lists {len(listed)} angles: a list is a table dimension of '
                "sunwind sweep",
                hint=f'hold the hinge at one angle here, e.g. --articulate "{glob}={listed[0]:g}"',
            )
    return tuple((glob, listed[0]) for glob, listed in angles.items())


@dataclass(frozen=True)
class SweptSource:
    """A sweep's model source and its hinges' angles, each hinge a table dimension.

    Parameters
    ----------
    source : ModelSource
        The mesh and materials, with no hinge held (``articulate`` empty).
    hinge_angles : dict of str to list of float, or None
        The angles [deg] of each ``--articulate`` hinge glob, one table dimension per hinge; None
        when no hinge is swept.

    Examples
    --------
    >>> from sunwind.forces.model import ModelSource
    >>> swept = SweptSource(source=ModelSource("craft.obj"), hinge_angles={"wing_*": [0.0, 30.0, 60.0]})
    >>> swept.hinge_angles["wing_*"]
    [0.0, 30.0, 60.0]
    """

    source: ModelSource
    hinge_angles: dict[str, list[float]] | None


def model_options(gas: bool = False, swept: bool = False) -> Callable:
    """Make the option group of the mesh and its materials.

    Its flags are the ``MESH`` argument, ``--materials``, the uniform material's optics, ``--two-sided``,
    ``--unit`` and ``--articulate`` (and, with ``gas``, the gas-surface flags). Nothing is loaded: the
    mesh is read when the command loads the source (:func:`loaded`).

    Parameters
    ----------
    gas : bool, optional
        Add the gas-surface flags (``--gsi``, the accommodations, ``--wall-temperature``), which set the
        uniform material's gas law and override every material's.
    swept : bool, optional
        Hand a :class:`SweptSource`, whose ``--articulate`` angles (one or a list per hinge) are table
        dimensions; else each hinge is held at one angle.

    Returns
    -------
    callable
        A decorator handing the command the keyword ``source``: a
        :class:`~sunwind.forces.model.ModelSource`, or with ``swept`` a :class:`SweptSource`.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @model_options(gas=True)
    ... def demo(source):
    ...     print(source.mesh, source.uniform.reflectivity, dict(source.gas), source.articulate)
    >>> demo.main(["craft.obj", "--reflectivity", "0.3", "--specular-fraction", "0.5",
    ...            "--wall-temperature", "250", "--articulate", "wing_*=30"], standalone_mode=False)
    craft.obj 0.3 {'wall_temperature': 250.0} (('wing_*', 30.0),)
    """

    def build(values: dict) -> ModelSource | SweptSource:
        if swept:
            angles = _angles(values.pop("articulate")) or None
            return SweptSource(_source({**values, "articulate": ()}), angles)
        held = _held(values)
        return _source({**values, "articulate": held})

    return group("source", _MODEL_OPTIONS + (_GAS_OPTIONS if gas else []), build)


def loaded(source: ModelSource, **model: object) -> Model:
    """Load the model of a source, printing its repair notices on stderr.

    Parameters
    ----------
    source : ModelSource
        The mesh and materials to read.
    **model : object
        :class:`~sunwind.forces.model.Model` fields: the references (``reference_point_m``, ...),
        ``threads``.

    Returns
    -------
    Model
        The loaded model; each repair made on loading is one ``sunwind: notice:`` line on stderr.

    Raises
    ------
    SunwindError
        A mesh or materials file that cannot be read or is refused.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> from sunwind.forces.model import ModelSource
    >>> from sunwind.geometry.io import save_mesh
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     mesh = Path(folder) / "box.obj"
    ...     save_mesh(sw.meshes.box(), mesh)
    ...     model = loaded(ModelSource(str(mesh), uniform=sw.Material("black", 0.0, 0.0)), threads=1)
    >>> model.craft.n_facets, model.threads
    (12, 1)
    """
    craft = source.spacecraft()
    for notice in craft.notices:
        print(f"sunwind: notice: {craft.source}: {notice}", file=sys.stderr)
    return Model(craft, source, **model)


def posed(model: Model, sun_vector: NDArray[np.float64] | None, command: str) -> Model:
    """Turn a model's hinges to the angles of ``sunwind COMMAND``.

    Fixed hinges take their angles and Sun-tracking ones turn to ``sun_vector``. A hinge that follows
    a schedule (it needs a time: ``sunwind orbit``), or one that tracks the Sun where there is no Sun
    (``drag``, and ``sweep``, which turns nothing from one attitude to the next), is refused.

    Parameters
    ----------
    model : Model
        The loaded model.
    sun_vector : (3,) float ndarray or None
        Unit vector to the Sun, body frame; None for a command without one.
    command : str
        The command's name, for the message.

    Returns
    -------
    Model
        ``model`` posed; the model itself when it has no hinges.

    Raises
    ------
    InputError
        A hinge the command cannot turn, with how to hold it at an angle (``--articulate``).

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> posed(model, None, "drag") is model  # no hinges: nothing to turn
    True
    """
    model.check_turnable(f"sunwind {command}", sun=sun_vector is not None)
    return model.posed(model.angles_at(sun_vector))


# ----------------------------------------------------------------------------------------- reference
def _references(values: dict) -> dict:
    point = values.pop("ref_point")
    out = {"reference_point_m": None if point is None else finite_point(point, "--ref-point")}
    if "ref_area" in values:
        out |= {"reference_area_m2": values["ref_area"], "reference_length_m": values["ref_length"]}
        check_reference_sizes(out["reference_area_m2"], out["reference_length_m"])
    return out


def reference_options(sizes: bool = False) -> Callable:
    """Make the option group of the torque reference point and, with ``sizes``, the coefficient references.

    Parameters
    ----------
    sizes : bool, optional
        Add ``--ref-area`` [m^2] and ``--ref-length`` [m] (for drag's coefficients) to ``--ref-point``
        [m].

    Returns
    -------
    callable
        A decorator handing the command the keyword ``references``: a dict of the
        :class:`~sunwind.forces.model.Model` fields they set (``reference_point_m``, and with ``sizes``
        ``reference_area_m2`` and ``reference_length_m``; None where not given).

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @reference_options(sizes=True)
    ... def demo(references):
    ...     print(references["reference_point_m"], references["reference_area_m2"])
    >>> demo.main(["--ref-point", "0", "0", "0.5", "--ref-area", "2"], standalone_mode=False)
    [0.  0.  0.5] 2.0
    """
    options = [
        click.option(
            "--ref-point",
            nargs=3,
            type=float,
            default=None,
            metavar="X Y Z",
            help="Torque reference point [m] [default: the materials file's [model] centre_of_mass_m, "
            "else the volume centroid if closed, else the area centroid].",
        )
    ]
    if sizes:
        options += [
            click.option(
                "--ref-area", type=float, help="Coefficient reference area [m^2] [default total area / 4]."
            ),
            click.option(
                "--ref-length",
                type=float,
                help="Moment-coefficient reference length [m] [default largest extent].",
            ),
        ]
    return group("references", options, _references)


# ------------------------------------------------------------------------------------------------ sun
@dataclass(frozen=True)
class Sun:
    """The Sun of a command: its direction and flux.

    Parameters
    ----------
    vector : (3,) float ndarray or None
        Unit vector from the spacecraft to the Sun, body frame; None when the command does not ask
        for one.
    flux_W_m2 : float
        Solar flux at the spacecraft [W/m^2].

    Examples
    --------
    >>> import numpy as np
    >>> sun = Sun(vector=np.array([0.0, 0.0, 1.0]), flux_W_m2=1361.0)
    >>> sun.flux_W_m2
    1361.0
    """

    vector: NDArray[np.float64] | None
    flux_W_m2: float


_FLUX_OPTIONS = [
    click.option("--flux", type=float, help="Solar flux [W/m^2] [default 1361, i.e. 1 au]."),
    click.option("--distance-au", type=float, help="Distance from the Sun [au]: flux = 1361 / r^2."),
]


def _sun(values: dict) -> Sun:
    flux = solar_flux(values["flux"], values["distance_au"])
    if "sun" not in values:
        return Sun(None, flux)
    sun, azel = values["sun"], values["sun_azel"]
    if (sun is None) == (azel is None):
        raise InputError("give the Sun direction with --sun X Y Z or --sun-azel AZ EL (one of them)")
    vector = unit_vector(sun, "--sun") if sun is not None else azel_to_vector(*azel, "--sun-azel")
    return Sun(vector, flux)


def sun_options(direction: bool = True) -> Callable:
    """Make the option group of the Sun direction and the solar flux.

    Parameters
    ----------
    direction : bool, optional
        Add ``--sun X Y Z`` and ``--sun-azel AZ EL`` [deg] (one of them is then needed); else only the
        flux flags ``--flux`` [W/m^2] and ``--distance-au``.

    Returns
    -------
    callable
        A decorator handing the command the keyword ``sun``: a :class:`Sun`.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @sun_options()
    ... def demo(sun):
    ...     print(sun.vector.round(6), round(sun.flux_W_m2, 1))
    >>> demo.main(["--sun-azel", "90", "0", "--distance-au", "2"], standalone_mode=False)
    [0. 1. 0.] 340.2
    >>> demo.main(["--distance-au", "2"], standalone_mode=False)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: give the Sun direction with --sun X Y Z or --sun-azel AZ EL ...
    """
    options = [
        click.option(
            "--sun",
            nargs=3,
            type=float,
            default=None,
            metavar="X Y Z",
            help="Sun direction in the body frame, spacecraft to Sun.",
        ),
        click.option(
            "--sun-azel",
            nargs=2,
            type=float,
            default=None,
            metavar="AZ EL",
            help="Sun azimuth and elevation [deg]: az = atan2(y, x), el = asin(z).",
        ),
    ]
    return group("sun", (options if direction else []) + _FLUX_OPTIONS, _sun)


# ------------------------------------------------------------------------------------------- sampling
def _sampling(values: dict) -> ShadowSampling:
    return ShadowSampling(values["samples"], values["tolerance"])


def sampling_options(command: Callable) -> Callable:
    """Add the shadow-ray sampling flags ``--samples`` and ``--tolerance`` to a command.

    Parameters
    ----------
    command : callable
        The command function (a decorator is applied directly, without a call).

    Returns
    -------
    callable
        ``command``, handed the keyword ``sampling``: a
        :class:`~sunwind.geometry.rays.sampling.ShadowSampling`.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @sampling_options
    ... def demo(sampling):
    ...     print(sampling.samples, sampling.tolerance)
    >>> demo.main(["--samples", "16", "--tolerance", "0.01"], standalone_mode=False)
    16 0.01
    """
    options = [
        click.option(
            "--samples",
            type=int,
            help="Fixed shadow-ray points per facet side, rounded up to a square [default: edges located].",
        ),
        click.option(
            "--tolerance",
            type=float,
            default=DEFAULT_TOLERANCE,
            show_default=True,
            help="Default shadow pass: share of a side's area its lit part is found to.",
        ),
    ]
    return group("sampling", options, _sampling)(command)


# ---------------------------------------------------------------------------------------- reflections
_MODE_HELP = {
    "light": "Inter-reflection: none; specular beams only; full (beams and diffuse balance); "
    "auto = full when K_IS >= 0.1, else none; plates = every side alone, no shadowing.",
    "gas": "Re-emitted molecules striking other sides: none; specular = unaccommodated molecules "
    "followed, no diffuse exchange; full; auto = full when K_IS >= 0.1; plates = every side alone, "
    "no shadowing.",
    "both": "Inter-reflection of light and of re-emitted molecules (auto: each by its own K_IS; plates: "
    "every side alone, no shadowing).",
}
_VIEW_FACTOR_OPTIONS = [
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


def _settings(values: dict) -> ReflectionSettings:
    cache = False if values["no_cache"] else values["cache_dir"]
    cutoff = values.get("reflection_cutoff", DEFAULT_CUTOFF)
    depth = values.get("reflection_depth", DEFAULT_DEPTH)
    return ReflectionSettings(values.get("reflections", "full"), cutoff, depth, values["view_rays"], cache)


def reflection_options(of: str) -> Callable:
    """Make the option group of inter-reflection and view-factor sampling.

    Parameters
    ----------
    of : {"light", "gas", "both"}
        What is reflected, for the help of ``--reflections``; with ``"light"`` also
        ``--reflection-cutoff`` and ``--reflection-depth``.

    Returns
    -------
    callable
        A decorator handing the command the keyword ``reflections``: a
        :class:`~sunwind.forces.reflection.ReflectionSettings`.

    Raises
    ------
    KeyError
        ``of`` is none of the three.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @reflection_options("light")
    ... def demo(reflections):
    ...     print(reflections.mode, reflections.depth, reflections.rays_per_side)
    >>> demo.main(["--reflections", "full", "--view-rays", "512"], standalone_mode=False)
    full ... 512
    """
    options = [
        click.option(
            "--reflections",
            type=click.Choice(MODES),
            default="auto",
            show_default=True,
            help=_MODE_HELP[of],
        )
    ]
    if of == "light":
        options += [
            click.option(
                "--reflection-cutoff",
                type=float,
                default=DEFAULT_CUTOFF,
                show_default=True,
                help="Drop a reflected beam below this share of the power its chain started with.",
            ),
            click.option(
                "--reflection-depth",
                type=int,
                default=DEFAULT_DEPTH,
                show_default=True,
                help="Most surfaces a beam chain meets.",
            ),
        ]
    return group("reflections", options + _VIEW_FACTOR_OPTIONS, _settings)


def view_factor_options(command: Callable) -> Callable:
    """Add the view-factor sampling and cache flags alone to a command (for K_IS).

    Parameters
    ----------
    command : callable
        The command function (a decorator is applied directly, without a call).

    Returns
    -------
    callable
        ``command``, handed the keyword ``reflections``: full
        :class:`~sunwind.forces.reflection.ReflectionSettings` with the default cutoff and depth.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @view_factor_options
    ... def demo(reflections):
    ...     print(reflections.mode, reflections.rays_per_side, reflections.cache_dir)
    >>> demo.main(["--view-rays", "300", "--no-cache"], standalone_mode=False)
    full 300 False
    """
    return group("reflections", _VIEW_FACTOR_OPTIONS, _settings)(command)


json_option = click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
