"""``sunwind earth``: the planet's albedo and infrared on the spacecraft at one place and attitude, the
power each part absorbs, and (``--thermal``) temperatures and thermal recoil."""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import click
import numpy as np

from sunwind.forces.cli.free_stream import FreeStream
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
from sunwind.forces.cli.outputs import check_distinct, check_writable
from sunwind.forces.cli.report import about, estimated, print_json, vector, warn_results
from sunwind.forces.earth import (
    DEFAULT_CELL_DEG,
    METHODS,
    PLATES,
    CapSampling,
    Place,
    PlanetResult,
    check_cells_at,
    planet_radiation,
)
from sunwind.forces.model import Model, ModelSource
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.earth_terms import THERMAL_MODES, EarthTerms
from sunwind.forces.planet.bodies import PLANETS, PlanetLight, planet
from sunwind.forces.planet.shadow import ECLIPSE_MODELS, sun_behind
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.forces.thermal import ThermalState
from sunwind.forces.thermal.transient import DEFAULT_TOLERANCE_K
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling


@dataclass(frozen=True)
class Below:
    """The planet below a command: where it is, its albedo and infrared, and how its disc is sampled.

    Parameters
    ----------
    nadir : tuple of 3 float or None
        Direction from the spacecraft to the planet's centre, body frame (``--earth``); needed by
        :func:`place_and_light`.
    altitude_km : float
        Height above the planet's surface [km].
    planet : str
        The planet's name, a key of ``PLANETS`` (its radius, albedo and infrared law).
    albedo : float or None
        Bond albedo; None takes the planet's.
    albedo_model : {"lambert", "knocke"}
        A uniform Lambertian albedo, or Knocke's zonal, seasonal albedo and emissivity of the Earth.
    epoch : str or None
        UTC date and time, ISO 8601: the season of ``"knocke"``.
    pole : tuple of 3 float or None
        The planet's north pole, body frame: the latitudes of ``"knocke"``.
    earth_ir : float or None
        Uniform infrared exitance at the surface [W/m^2]; None takes (1 - A) S / 4.
    eclipse : str
        The model of the planet's shadow on the Sun (``"conical"``, ...).
    cell_deg : float
        Resolution of the shadowing [deg] (``--step``).
    cap_method : {"visibility", "cells"}, optional
        How the shadowed cap is integrated (``--cap-method``).
    plates : bool, optional
        Every side an independent plate seeing the whole planet: no ray cast.

    Examples
    --------
    >>> below = Below(nadir=(0.0, 0.0, -1.0), altitude_km=500.0, planet="earth", albedo=None,
    ...               albedo_model="lambert", epoch=None, pole=None, earth_ir=None, eclipse="conical",
    ...               cell_deg=10.0)
    >>> below.altitude_km, below.plates
    (500.0, False)
    """

    nadir: tuple[float, float, float] | None
    altitude_km: float
    planet: str
    albedo: float | None
    albedo_model: str
    epoch: str | None
    pole: tuple[float, float, float] | None
    earth_ir: float | None
    eclipse: str
    cell_deg: float
    cap_method: str = "visibility"
    plates: bool = False


def _light_options() -> list:
    """The planet's albedo and infrared law."""
    return [
        click.option("--albedo", type=float, help="Bond albedo [default the planet's: Earth 0.30]."),
        click.option("--albedo-model", type=click.Choice(["lambert", "knocke"]), default="lambert",
                     show_default=True,
                     help="knocke: Knocke's zonal, seasonal albedo and emissivity of the Earth."),
        click.option("--earth-ir", type=float, metavar="W_M2",
                     help="Uniform infrared exitance at the surface [W/m^2] [default (1 - A) S / 4]."),
    ]  # fmt: skip


def _earth(name: str) -> click.decorators.FC:
    """``--earth X Y Z`` as keyword ``name``."""
    return click.option("--earth", name, nargs=3, type=float, metavar="X Y Z",
                        help="Direction from the spacecraft to the planet's centre, body frame.")  # fmt: skip


_POLE = click.option("--pole", nargs=3, type=float, metavar="X Y Z",
                     help="The planet's north pole, body frame (latitudes for knocke).")  # fmt: skip


def planet_options() -> click.decorators.FC:
    """Make the option group of the planet's place and its albedo and infrared.

    Its flags are ``--earth``, ``--altitude`` (required), ``--planet``, ``--albedo``,
    ``--albedo-model``, ``--earth-ir``, ``--epoch``, ``--pole``, ``--eclipse``, ``--step`` and
    ``--plates``.

    Returns
    -------
    callable
        A decorator handing the command the keyword ``below``: a :class:`Below`.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @planet_options()
    ... def demo(below):
    ...     print(below.nadir, below.altitude_km, below.planet, below.cell_deg)
    >>> demo.main(["--earth", "0", "0", "-1", "--altitude", "500"], standalone_mode=False)
    (0.0, 0.0, -1.0) 500.0 earth 10.0
    """
    options = [
        _earth("nadir"),
        click.option("--altitude", "altitude_km", type=float, required=True, metavar="H_KM",
                     help="Height above the planet's surface [km]."),
        click.option("--planet", type=click.Choice(list(PLANETS)), default="earth", show_default=True,
                     help="The planet below: its radius, albedo and infrared law."),
        *_light_options(),
        click.option("--epoch", help="UTC date and time, ISO 8601 (the season of --albedo-model knocke)."),
        _POLE,
        click.option("--eclipse", type=click.Choice(ECLIPSE_MODELS), default="conical", show_default=True,
                     help="The planet's shadow on the Sun (sunlight in the heat budget)."),
        click.option("--step", "cell_deg", type=float, default=DEFAULT_CELL_DEG, show_default=True,
                     help="Resolution of the shadowing [deg]: the spacing of the visibility's directions "
                     "(10: 642 directions, 5: 2562), or the cells' size with --cap-method cells."),
        click.option("--cap-method", type=click.Choice(METHODS), default=METHODS[0], show_default=True,
                     help="visibility: each side's view past the model along a grid of directions, built "
                     "once per model (cached on disk), then weighted sums; cells: a shadow pass per cell "
                     "of the planet's disc (the reference)."),
        click.option("--plates", is_flag=True,
                     help="Fast mode (--reflections plates): every side an independent plate seeing the "
                     "whole planet (exact plate factors), no self-shadowing or inter-reflection; no ray "
                     "cast."),
    ]  # fmt: skip
    return group("below", options, lambda values: Below(**values))


@dataclass(frozen=True)
class EarthRequest:
    """The Earth's radiation asked of ``sunwind forces`` or ``sunwind orbit`` (``--earth-radiation``).

    Parameters
    ----------
    albedo : float or None
        Bond albedo; None takes the Earth's.
    albedo_model : {"lambert", "knocke"}
        A uniform Lambertian albedo, or Knocke's zonal, seasonal albedo and emissivity.
    earth_ir : float or None
        Uniform infrared exitance at the surface [W/m^2]; None takes (1 - A) S / 4.
    cell_deg : float
        Cell size of the Earth's disc for shadowing and reflections [deg] (``--earth-step``).
    thermal : bool
        Also each side's equilibrium temperature and the recoil of its infrared.
    nadir : tuple of 3 float or None, optional
        Direction to the Earth's centre, body frame (``--earth``; commands without an orbit).
    pole : tuple of 3 float or None, optional
        The Earth's north pole, body frame (``--pole``; commands without an orbit).
    per_side : bool, optional
        Also each side's absorbed power at every step (``--per-side``; ``sunwind orbit``).
    transient : bool, optional
        With ``thermal``: the lumped transient along the orbit instead of each step's equilibrium
        (``--thermal transient``; ``sunwind orbit``).
    initial_temperature_K : float or None, optional
        The transient's start, every node at this temperature [K] (``--initial-temperature``); None: the
        equilibrium of the first step.
    thermal_tolerance_K : float, optional
        The transient's tolerance per step [K] (``--thermal-tolerance``).
    cap_method : {"auto", "visibility", "cells"}, optional
        How the shadowed cap is integrated (``--earth-cap-method``).

    Examples
    --------
    >>> request = EarthRequest(albedo=None, albedo_model="lambert", earth_ir=None, cell_deg=10.0,
    ...                        thermal=False, nadir=(0.0, 0.0, -1.0))
    >>> request.cell_deg, request.pole
    (10.0, None)
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> lumped = EarthRequest(None, "lambert", None, 10.0, thermal=True, transient=True)
    >>> lumped.terms(SrpSetup()).thermal
    'transient'
    """

    albedo: float | None
    albedo_model: str
    earth_ir: float | None
    cell_deg: float
    thermal: bool
    nadir: tuple[float, float, float] | None = None
    pole: tuple[float, float, float] | None = None
    per_side: bool = False
    transient: bool = False
    initial_temperature_K: float | None = None
    thermal_tolerance_K: float = DEFAULT_TOLERANCE_K
    cap_method: str = "auto"

    def terms(self, surface: SrpSetup) -> EarthTerms:
        """The orbit's settings, with the sampling and reflections of ``surface``."""
        knocke = self.albedo_model == "knocke"
        mode = THERMAL_MODES[self.transient] if self.thermal else None
        lumped = (
            {
                "initial_temperature_K": self.initial_temperature_K,
                "thermal_tolerance_K": self.thermal_tolerance_K,
            }
            if self.transient
            else {}
        )
        return EarthTerms(
            surface,
            self.albedo,
            self.earth_ir,
            knocke,
            self.cell_deg,
            mode,
            self.per_side,
            **lumped,
            cap_method=self.cap_method,
        )


def earth_term_options(*, place: bool, per_side: bool = False, transient: bool = False) -> list:
    """Make ``--earth-radiation`` and its settings, for the commands that add the Earth's radiation.

    :func:`earth_request` makes their values an :class:`EarthRequest`.

    Parameters
    ----------
    place : bool
        Add ``--earth`` and ``--pole``, for a command without an orbit to place the Earth.
    per_side : bool, optional
        Add ``--per-side``, for ``sunwind orbit``: each side's absorbed power at every step.
    transient : bool, optional
        For ``sunwind orbit``: ``--thermal [equilibrium|transient]`` (alone: ``equilibrium``) and the
        transient's ``--initial-temperature`` and ``--thermal-tolerance``.

    Returns
    -------
    list of callable
        Click option decorators, their keywords those of :data:`EARTH_KEYS`.

    Examples
    --------
    >>> import click
    >>> from sunwind.forces.cli.options import group
    >>> @click.command()
    ... @group("earth", earth_term_options(place=True), earth_request)
    ... def demo(earth):
    ...     print(earth)
    >>> demo.main(["--earth-radiation", "--earth", "0", "0", "-1"], standalone_mode=False)
    EarthRequest(albedo=None, albedo_model='lambert', earth_ir=None, cell_deg=10.0, thermal=False,
                 nadir=(0.0, 0.0, -1.0), pole=None, per_side=False, transient=False,
                 initial_temperature_K=None, thermal_tolerance_K=0.01, cap_method='auto')
    >>> demo.main([], standalone_mode=False)
    None
    >>> @click.command()
    ... @group("earth", earth_term_options(place=False, transient=True), earth_request)
    ... def orbit_demo(earth):
    ...     print(earth.thermal, earth.transient, earth.initial_temperature_K)
    >>> orbit_demo.main(["--earth-radiation", "--thermal"], standalone_mode=False)
    True False None
    >>> orbit_demo.main(["--earth-radiation", "--thermal", "transient", "--initial-temperature", "280"],
    ...                 standalone_mode=False)
    True True 280.0
    """
    return [
        click.option("--earth-radiation", "earth_on", is_flag=True,
                     help="Add the Earth's albedo and infrared pressure (materials need an emissivity)."),
        *_light_options(),
        click.option("--earth-step", "cell_deg", type=float, default=DEFAULT_CELL_DEG, show_default=True,
                     help="Resolution of the Earth's shadowing [deg] (as --step of sunwind earth)."),
        click.option("--earth-cap-method", "cap_method", type=click.Choice(["auto", *METHODS]),
                     default="auto", show_default=True,
                     help="As --cap-method of sunwind earth; auto: the visibility, built once, unless a "
                     "hinge moves (it poses the model anew at every step): then cells."),
        *(_TRANSIENT_OPTIONS if transient else [_THERMAL_FLAG]),
        *([_earth("earth_nadir"), _POLE] if place else []),
        *([_PER_SIDE] if per_side else []),
    ]  # fmt: skip


_THERMAL_FLAG = click.option(
    "--thermal",
    is_flag=True,
    help="With --earth-radiation: each side's equilibrium temperature and the recoil of its infrared.",
)
_TRANSIENT_OPTIONS = [
    click.option("--thermal", type=click.Choice(THERMAL_MODES), is_flag=False, flag_value=THERMAL_MODES[0],
                 default=None, metavar="[equilibrium|transient]",
                 help="With --earth-radiation: the parts' temperatures and the recoil of their infrared. "
                 "Alone or equilibrium: each step's radiative equilibrium; transient: the lumped model "
                 "of the materials file's heat capacities ([thermal.\"GLOB\"] heat_capacity_J_K) integrated "
                 "along the orbit."),
    click.option("--initial-temperature", type=float, metavar="K",
                 help="With --thermal transient: every node at this temperature [K] at the first step "
                 "[default: the equilibrium of the first step]."),
    click.option("--thermal-tolerance", type=float, metavar="K",
                 help="With --thermal transient: largest estimated local error of the temperatures over a "
                 f"step [K] [default {DEFAULT_TOLERANCE_K:g}]."),
]  # fmt: skip


_PER_SIDE = click.option(
    "--per-side",
    is_flag=True,
    help="With --earth-radiation: also each side's absorbed power by source at every step, with the side's "
    "part, facet and face (front/back), in -o and --json.",
)


def earth_request(values: dict) -> EarthRequest | None:
    """Make the :class:`EarthRequest` of the :func:`earth_term_options` flags, taking them out of ``values``.

    Without ``--earth-radiation`` its settings are refused when given. With it, the step and the
    albedo and infrared are checked before any work.

    Parameters
    ----------
    values : dict
        The command's values by keyword; the keys of :data:`EARTH_KEYS` are removed from it.

    Returns
    -------
    EarthRequest or None
        The request; None without ``--earth-radiation``.

    Raises
    ------
    InputError
        A setting given without ``--earth-radiation``, an ``--earth-step`` outside (0, 90] deg, or an
        albedo or infrared exitance the planet's light refuses.

    Examples
    --------
    >>> values = {"earth_on": False, "albedo": 0.3, "albedo_model": "lambert", "earth_ir": None,
    ...           "cell_deg": 10.0, "thermal": False, "mass": 100.0}
    >>> earth_request(values)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --albedo needs --earth-radiation; add --earth-radiation
    >>> values  # the earth flags were taken out
    {'mass': 100.0}
    """
    mine = {key: values.pop(key) for key in EARTH_KEYS if key in values}
    if "earth_nadir" in mine:
        mine["nadir"] = mine.pop("earth_nadir")
    mode = mine.pop("thermal")
    start, tolerance = mine.pop("initial_temperature", None), mine.pop("thermal_tolerance", None)
    if not mine.pop("earth_on"):
        refuse_without_earth(
            (
                ("--albedo", mine["albedo"]),
                ("--earth-ir", mine["earth_ir"]),
                ("--thermal", mode or None),
                ("--initial-temperature", start),
                ("--thermal-tolerance", tolerance),
                ("--earth", mine.get("nadir")),
                ("--pole", mine.get("pole")),
                ("--albedo-model knocke", mine["albedo_model"] == "knocke" or None),
                ("--per-side", mine.get("per_side") or None),
                (
                    "--earth-cap-method",
                    None if mine.get("cap_method", "auto") == "auto" else mine["cap_method"],
                ),
            )
        )
        return None
    mine |= _thermal_request(mode, start, tolerance)
    step = mine["cell_deg"]
    if not (math.isfinite(step) and 0.0 < step <= 90.0):
        raise InputError(f"--earth-step {step:g} is not in (0, 90] deg", hint="e.g. --earth-step 10")
    light = {"albedo": mine["albedo"], "infrared_W_m2": mine["earth_ir"]}
    PlanetLight.of(planet("earth"), SOLAR_FLUX_1AU, **light)  # their checks, before any work
    return EarthRequest(**mine)


def check_earth_step(altitude_km: float, cell_deg: float) -> None:
    """Refuse an ``--earth-step`` that cuts the Earth's disc into too many cells at this altitude.

    This is :func:`~sunwind.forces.earth.check_cells_at` with its message naming ``--earth-step``.

    Parameters
    ----------
    altitude_km : float
        Height above the Earth's surface [km].
    cell_deg : float
        Cell size of the Earth's disc [deg].

    Raises
    ------
    InputError
        The disc would have more cells than the limit.

    Examples
    --------
    >>> check_earth_step(500.0, 10.0)  # about a hundred cells: accepted
    >>> check_earth_step(500.0, 0.1)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --earth-step 0.1 cuts the planet's disc (68.0 deg half-angle) into ...
    """
    try:
        check_cells_at(altitude_km, cell_deg)
    except InputError as error:
        raise error.renamed({"cell_deg": "--earth-step"}) from None


def refuse_without_earth(flags: Sequence[tuple[str, object]]) -> None:
    """Refuse, in one message, the Earth's settings given without ``--earth-radiation``.

    Parameters
    ----------
    flags : sequence of (str, object)
        Each setting's flag and value; a value of None is a flag not given.

    Raises
    ------
    InputError
        Any flag has a value.

    Examples
    --------
    >>> refuse_without_earth([("--albedo", None), ("--thermal", None)])  # none given
    >>> refuse_without_earth([("--albedo", 0.3), ("--pole", (0.0, 0.0, 1.0))])
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --albedo, --pole need --earth-radiation; add --earth-radiation
    """
    given = [flag for flag, value in flags if value is not None]
    if given:
        verb = "needs" if len(given) == 1 else "need"
        raise InputError(f"{', '.join(given)} {verb} --earth-radiation", hint="add --earth-radiation")


def _thermal_request(mode: bool | str | None, start: float | None, tolerance: float | None) -> dict:
    """The :class:`EarthRequest` fields of ``--thermal [MODE]``, ``--initial-temperature`` and
    ``--thermal-tolerance``, checked."""
    transient = mode == THERMAL_MODES[1]
    given = [flag for flag, value in (("--initial-temperature", start), ("--thermal-tolerance", tolerance))
             if value is not None]  # fmt: skip
    if given and not transient:
        verb = "needs" if len(given) == 1 else "need"
        raise InputError(f"{', '.join(given)} {verb} --thermal transient", hint="add --thermal transient")
    for flag, value in (("--initial-temperature", start), ("--thermal-tolerance", tolerance)):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise InputError(f"{flag} {value:g} K is not a temperature above 0 K", hint=f"e.g. {flag} 0.01"
                             if flag == "--thermal-tolerance" else f"e.g. {flag} 290")  # fmt: skip
    return {
        "thermal": bool(mode),
        "transient": transient,
        "initial_temperature_K": start,
        "thermal_tolerance_K": DEFAULT_TOLERANCE_K if tolerance is None else tolerance,
    }


#: The keyword names of :func:`earth_term_options`.
EARTH_KEYS = (
    "earth_on", "albedo", "albedo_model", "earth_ir", "cell_deg", "cap_method", "thermal",
    "initial_temperature", "thermal_tolerance", "earth_nadir", "pole", "per_side",
)  # fmt: skip


def place_and_light(below: Below, sun: Sun) -> tuple[Place, PlanetLight]:
    """Make the :class:`Place` and :class:`PlanetLight` of the planet options and the Sun.

    The share of the Sun's disc in view comes from the ``--eclipse`` model.

    Parameters
    ----------
    below : Below
        The planet options.
    sun : Sun
        The Sun's direction (body frame) and flux [W/m^2].

    Returns
    -------
    place : Place
        Nadir, altitude [km], Sun direction, pole and the Sun's share in view.
    light : PlanetLight
        The planet's albedo and infrared.

    Raises
    ------
    InputError
        No ``--earth`` direction, ``--albedo-model knocke`` without ``--epoch`` and ``--pole``, or a
        value the place or light refuses.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.cli.options import Sun
    >>> grey = sw.Material("grey", reflectivity=0.0, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> below = Below(nadir=(0.0, 0.0, -1.0), altitude_km=500.0, planet="earth", albedo=None,
    ...               albedo_model="lambert", epoch=None, pole=None, earth_ir=None, eclipse="conical",
    ...               cell_deg=10.0)
    >>> sun = Sun(vector=np.array([0.0, 0.0, 1.0]), flux_W_m2=1361.0)  # overhead: daylight below
    >>> place, light = place_and_light(below, sun)
    >>> place.solar_fraction, light.planet.name
    (1.0, 'earth')
    """
    body = planet(below.planet)
    if below.nadir is None:
        raise InputError("give --earth X Y Z: the body-frame direction to the planet's centre")
    nadir = unit_vector(below.nadir, "--earth")
    julian = None
    if below.albedo_model == "knocke":
        if below.epoch is None or below.pole is None:
            raise InputError("--albedo-model knocke needs --epoch (the season) and --pole (the latitudes)")
        julian = float(sum(Epoch.of(below.epoch).jd_tt))
    place = Place(nadir, below.altitude_km, sun.vector, below.pole)
    fraction = sun_behind(place.nadir, place.altitude_km, place.sun_vector, body.radius_m, below.eclipse)
    light = PlanetLight.of(
        body, sun.flux_W_m2, albedo=below.albedo, infrared_W_m2=below.earth_ir, knocke_julian_date=julian
    )
    return replace(place, solar_fraction=fraction), light


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
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    heat: dict,
    as_json: bool,
) -> None:
    """Albedo and infrared pressure from the planet below, per-part absorbed power and temperatures."""
    if heat["sides_csv"] is not None:
        check_distinct(heat["sides_csv"], source.mesh, source.materials)
        check_writable(heat["sides_csv"])
    model = posed(loaded(source, **references), sun.vector, "earth")
    result, state = radiation(model, below, sun, reflections, sampling, thermal=heat["thermal"])
    if heat["sides_csv"] is not None:
        _write_sides(heat["sides_csv"], result, state)
    if as_json:
        print_json(model.craft, earth_document(result, state))
    else:
        print_earth(result, state)
    warn_results({"earth": result.error_estimate}, sampling.tolerance)


def radiation(
    model: Model,
    below: Below,
    sun: Sun,
    reflections: ReflectionSettings,
    sampling: ShadowSampling,
    *,
    thermal: bool,
) -> tuple[PlanetResult, ThermalState | None]:
    """Compute the planet's radiation on a model at the place of the planet options.

    Parameters
    ----------
    model : Model
        The posed model.
    below : Below
        The planet options (``plates`` replaces the reflections by independent plates).
    sun : Sun
        The Sun's direction (body frame) and flux [W/m^2].
    reflections : ReflectionSettings
        The command's inter-reflection settings.
    sampling : ShadowSampling
        The shadow-ray sampling.
    thermal : bool
        Also the equilibrium temperatures and their infrared recoil.

    Returns
    -------
    result : PlanetResult
        Albedo and infrared forces [N] and torques [N m], and the power each side absorbs.
    state : ThermalState or None
        The temperatures and recoil; None unless ``thermal``.

    Raises
    ------
    InputError
        A place or light the computation refuses.
    MaterialError
        A material without an emissivity (the planet's infrared, absorbed and re-emitted, needs one).

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.cli.options import Sun
    >>> grey = sw.Material("grey", reflectivity=0.0, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> below = Below(nadir=(0.0, 0.0, -1.0), altitude_km=500.0, planet="earth", albedo=None,
    ...               albedo_model="lambert", epoch=None, pole=None, earth_ir=None, eclipse="conical",
    ...               cell_deg=10.0)
    >>> sun = Sun(vector=np.array([0.0, 0.0, 1.0]), flux_W_m2=1361.0)  # overhead: daylight below
    >>> none = sw.ReflectionSettings("none")
    >>> result, state = radiation(cube, below, sun, none, sw.ShadowSampling(), thermal=True)
    >>> print(f"{result.infrared.force_N[2]:.3e} N")  # the infrared pushes away from the planet: +z
    1.131e-06 N
    >>> print(f"{state.temperature_K.mean():.0f} K")  # the sides' mean equilibrium temperature
    286 K
    """
    place, light = place_and_light(below, sun)
    mode = replace(reflections, mode=PLATES) if below.plates else reflections
    result = planet_radiation(
        model,
        place,
        light,
        reflections=mode,
        sampling=sampling,
        cap=CapSampling(below.cell_deg, below.cap_method),
    )
    return result, result.equilibrium("none" if mode.mode == PLATES else reflections) if thermal else None


def earth_below(request: EarthRequest, where: FreeStream) -> Below:
    """Place the Earth of ``sunwind forces``, checked before any work.

    The Earth lies along ``--earth``, at ``--altitude`` and ``--epoch`` of the flow options; the Sun's
    share behind it follows the conical model.

    Parameters
    ----------
    request : EarthRequest
        The ``--earth-radiation`` settings.
    where : FreeStream
        The flow options, whose ``altitude_km`` and ``time`` place the spacecraft.

    Returns
    -------
    Below
        The planet options of the Earth.

    Raises
    ------
    InputError
        No ``--earth`` direction or no ``--altitude``, or an ``--earth-step`` too fine for the altitude.

    Examples
    --------
    >>> from dataclasses import replace
    >>> from sunwind.forces.cli.free_stream import FreeStream
    >>> request = EarthRequest(albedo=None, albedo_model="lambert", earth_ir=None, cell_deg=10.0,
    ...                        thermal=False, nadir=(0.0, 0.0, -1.0))
    >>> no_flow = FreeStream(velocity_m_s=None, speed_m_s=None, atmosphere=None)
    >>> below = earth_below(request, replace(no_flow, altitude_km=400.0))
    >>> below.planet, below.altitude_km, below.eclipse
    ('earth', 400.0, 'conical')
    >>> earth_below(request, no_flow)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --earth-radiation needs --earth X Y Z (body-frame direction ...
    """
    if request.nadir is None or where.altitude_km is None:
        raise InputError(
            "--earth-radiation needs --earth X Y Z (body-frame direction to the Earth's centre) and "
            "--altitude H_KM",
            hint="e.g. --earth 0 0 1 --altitude 500",
        )
    check_earth_step(where.altitude_km, request.cell_deg)
    return Below(
        nadir=request.nadir,
        altitude_km=where.altitude_km,
        planet="earth",
        albedo=request.albedo,
        albedo_model=request.albedo_model,
        epoch=where.time,
        pole=request.pole,
        earth_ir=request.earth_ir,
        eclipse="conical",
        cell_deg=request.cell_deg,
        cap_method="visibility" if request.cap_method == "auto" else request.cap_method,
    )


def earth_document(result: PlanetResult, state: ThermalState | None) -> dict:
    """Make the JSON document of ``sunwind earth``.

    Parameters
    ----------
    result : PlanetResult
        The planet's radiation.
    state : ThermalState or None
        The temperatures and recoil, when asked for.

    Returns
    -------
    dict
        The result's JSON; with a thermal state also ``thermal`` and each part's area-weighted mean
        ``temperature_K``.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.cli.options import Sun
    >>> grey = sw.Material("grey", reflectivity=0.0, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> below = Below(nadir=(0.0, 0.0, -1.0), altitude_km=500.0, planet="earth", albedo=None,
    ...               albedo_model="lambert", epoch=None, pole=None, earth_ir=None, eclipse="conical",
    ...               cell_deg=10.0)
    >>> sun = Sun(vector=np.array([0.0, 0.0, 1.0]), flux_W_m2=1361.0)  # overhead: daylight below
    >>> none = sw.ReflectionSettings("none")
    >>> result, state = radiation(cube, below, sun, none, sw.ShadowSampling(), thermal=True)
    >>> document = earth_document(result, state)
    >>> sorted(document["parts"]["box"])
    ['albedo_W', 'area_m2', 'infrared_W', 'reflected_W', 'solar_W', 'temperature_K']
    """
    document = result.to_json()
    if state is not None:
        document["thermal"] = state.to_json()
        _add_temperatures(document["parts"], result, state)
    return document


def _part_temperatures(result: PlanetResult, state: ThermalState) -> dict[str, float]:
    """Area-weighted mean temperature of each part [K]."""
    mean = result.part_temperatures(state.temperature_K)
    return dict(zip(result.craft.part_names, mean.tolist(), strict=True))


def _add_temperatures(parts: dict, result: PlanetResult, state: ThermalState) -> None:
    for name, temperature in _part_temperatures(result, state).items():
        parts[name]["temperature_K"] = temperature


def _write_sides(path: Path, result: PlanetResult, state: ThermalState | None) -> None:
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


def print_earth(result: PlanetResult, state: ThermalState | None, title: str | None = None) -> None:
    """Print the human-readable report of ``sunwind earth``.

    Parameters
    ----------
    result : PlanetResult
        The planet's radiation.
    state : ThermalState or None
        The temperatures and recoil, when asked for.
    title : str or None, optional
        The first line; None gives the command's header.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.cli.options import Sun
    >>> grey = sw.Material("grey", reflectivity=0.0, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> below = Below(nadir=(0.0, 0.0, -1.0), altitude_km=500.0, planet="earth", albedo=None,
    ...               albedo_model="lambert", epoch=None, pole=None, earth_ir=None, eclipse="conical",
    ...               cell_deg=10.0)
    >>> sun = Sun(vector=np.array([0.0, 0.0, 1.0]), flux_W_m2=1361.0)  # overhead: daylight below
    >>> none = sw.ReflectionSettings("none")
    >>> result, state = radiation(cube, below, sun, none, sw.ShadowSampling(), thermal=True)
    >>> print_earth(result, state)  # doctest: +ELLIPSIS
    sunwind earth: <box> (12 triangles, 1 parts)
      frame            body frame of the mesh; SI units
      planet           earth: albedo 0.3 Lambertian, infrared (1 - A) S / 4 = 238.2 W/m^2 uniform
      nadir            [+0.000000  +0.000000  -1.000000]  altitude 500 km  (disc radius 68.019 deg)
    ...
      absorbed [W]     part: solar, albedo, infrared, reflected, temperature [K]
        box: 1361, ...
    """
    craft, place = result.craft, result.place
    parts = f"({craft.n_facets} triangles, {len(craft.part_names)} parts)"
    print(title or f"sunwind earth: {craft.source} {parts}")
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
    without = "plates: no shadowing" if result.reflections == PLATES else "fixed points per side, --samples"
    print(f"  shadow error     albedo + infrared: {estimated(result.error_estimate, without)}")
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
