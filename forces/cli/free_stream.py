"""The free stream as the command line gives it: the flow velocity and the atmosphere.

Either ``--velocity X Y Z`` (``v_rel`` in the body frame, m/s) or ``--flow-azel AZ EL`` with a speed:
``--speed V``, else the circular-orbit speed at ``--altitude``. With ``--corotating``, ``--flow-azel``
is the direction of the orbit's inertial velocity, and ``v_rel`` is that velocity less the air turning
with the Earth, for the ``--heading`` of the orbit at ``--lat``, its crosswind placed by ``--nadir``. Either
NRLMSIS at ``--altitude`` (place, ``--epoch`` and indices optional) or ``--density``, ``--temperature`` and
``--composition`` together. A sweep takes the flow directions from its grid or list: it needs only the
speed.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import click
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.cli.options import given, group
from sunwind.forces.drag import checked_velocities
from sunwind.forces.gas import (
    Atmosphere,
    circular_speed,
    corotation_speed,
    corotation_velocity,
    explicit,
    nrlmsis,
)
from sunwind.forces.gas.flow import flow_speed
from sunwind.forces.gas.msis import DEFAULT_AP, DEFAULT_F107_SFU, DEFAULT_F107A_SFU
from sunwind.forces.gas.sampling import GasSampling
from sunwind.geometry.directions import azel_to_vector
from sunwind.geometry.errors import InputError


@dataclass(frozen=True)
class FreeStream:
    """The flow of a command: relative velocity, speed and atmosphere, and the open-sky sampling.

    Parameters
    ----------
    velocity_m_s : (3,) float ndarray or None
        ``v_rel``, the spacecraft's velocity relative to the air, body frame [m/s]; None for a sweep
        (its directions come from the grid) or where the command computes no drag.
    speed_m_s : float or None
        ``|v_rel|`` [m/s]; None where the command computes no drag.
    atmosphere : Atmosphere or None
        The air's density, temperature and composition; None where the command computes no drag.
    sampling : GasSampling, optional
        How each side's open sky (and the re-emitted molecules) are sampled.
    altitude_km : float or None, optional
        ``--altitude`` [km] as given (it also places the Earth's radiation).
    time : str or None, optional
        ``--epoch`` as given, UTC ISO 8601.

    Examples
    --------
    >>> stream = FreeStream(velocity_m_s=None, speed_m_s=None, atmosphere=None)  # no drag
    >>> stream.atmosphere is None, stream.sampling.sky_rays
    (True, None)
    """

    velocity_m_s: NDArray[np.float64] | None
    speed_m_s: float | None
    atmosphere: Atmosphere | None
    sampling: GasSampling = field(default_factory=GasSampling)
    #: where the spacecraft is, as given (for the Earth's radiation): ``--altitude`` [km], ``--time``
    altitude_km: float | None = None
    time: str | None = None


#: The NRLMSIS date when none is given.
DEFAULT_EPOCH = "2024-01-01T00:00:00Z"


_FLOW = [
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
        help="Direction of v_rel [deg], az = atan2(y, x), el = asin(z); with --speed or --altitude "
        "(with --corotating: of the inertial orbit velocity).",
    ),
]
_SPEED = [
    click.option("--speed", type=float, help="|v_rel| [m/s] [default: circular orbit at --altitude]."),
    click.option(
        "--corotating",
        is_flag=True,
        help="v_rel relative to air turning with the Earth: v - omega x r (speed and direction).",
    ),
    click.option(
        "--heading",
        type=float,
        default=90.0,
        show_default=True,
        help="With --corotating: direction of motion [deg from north, 90 = east].",
    ),
    click.option(
        "--nadir",
        nargs=3,
        type=float,
        default=None,
        metavar="X Y Z",
        help="With --corotating: body-frame direction to the Earth's centre (places the crosswind; "
        "not needed heading east or west, or at a pole).",
    ),
]
#: NRLMSIS's space weather (drag and orbit), its defaults from :mod:`sunwind.forces.gas.msis`.
WEATHER_OPTIONS = [
    click.option(
        "--f107", type=float, default=DEFAULT_F107_SFU, show_default=True, help="Daily F10.7 [sfu]."
    ),
    click.option(
        "--f107a", type=float, default=DEFAULT_F107A_SFU, show_default=True, help="81-day F10.7 [sfu]."
    ),
    click.option("--ap", type=float, default=DEFAULT_AP, show_default=True, help="Daily Ap index."),
]
_AIR = [
    click.option("--altitude", type=float, help="Altitude [km] for NRLMSIS 2.1 (and the orbit speed)."),
    click.option("--lat", type=float, default=0.0, show_default=True, help="Geodetic latitude [deg]."),
    click.option("--lon", type=float, default=0.0, show_default=True, help="Longitude [deg]."),
    click.option(
        "--epoch",
        "time",
        default=DEFAULT_EPOCH,
        show_default=True,
        help="UTC date and time, ISO 8601 (NRLMSIS; with --earth-radiation, the albedo's season).",
    ),
    click.option("--time", "old_time", hidden=True, help="The former name of --epoch."),
    *WEATHER_OPTIONS,
    click.option("--density", type=float, help="Explicit atmosphere: mass density [kg/m^3]."),
    click.option("--temperature", type=float, help="Explicit atmosphere: temperature [K]."),
    click.option("--composition", help='Explicit atmosphere: mole fractions, e.g. "O:0.7,N2:0.3".'),
    click.option(
        "--normalise-composition", is_flag=True, help="Rescale mole fractions that do not sum to 1."
    ),
    click.option(
        "--sky-rays",
        type=int,
        help="Rays per side sampling each side's open sky, once per model and cached "
        "[default: by model size, 36 to 4096].",
    ),
]


def flow_options(directed: bool, optional: bool = False) -> Callable:
    """Make the option group of the flow and the atmosphere.

    The flow is ``--velocity`` or ``--flow-azel`` with a speed (``--speed``, else the circular-orbit
    speed at ``--altitude``; ``--corotating`` subtracts the air turning with the Earth), and the air is
    NRLMSIS at ``--altitude`` or ``--density``, ``--temperature`` and ``--composition`` together.

    Parameters
    ----------
    directed : bool
        The command takes the flow's direction and is handed a :class:`FreeStream`; else (a sweep)
        only the speed, and the command is handed a function ``flow(drag_wanted) -> FreeStream``
        (a sweep of SRP alone needs no atmosphere, and an empty stream is given for it).
    optional : bool, optional
        With ``directed`` (``sunwind forces``): without a flow direction there is no drag, the
        stream has no velocity, speed or atmosphere, and the flow's other flags are refused.

    Returns
    -------
    callable
        A decorator handing the command the keyword ``flow``.

    Examples
    --------
    >>> import click
    >>> @click.command()
    ... @flow_options(directed=True)
    ... def demo(flow):
    ...     print(f"{flow.speed_m_s:.1f} m/s, {flow.atmosphere.density_kg_m3:g} kg/m^3")
    >>> air = ["--density", "1e-12", "--temperature", "1000", "--composition", "O:1"]
    >>> demo.main(["--flow-azel", "0", "0", "--altitude", "400", *air], standalone_mode=False)
    7668.6 m/s, 1e-12 kg/m^3
    """

    def build(values: dict):
        _epoch(values)
        if directed:
            if optional and values["velocity"] is None and values["flow_azel"] is None:
                return _no_flow(values)
            return _free_stream(values, directed)
        return lambda drag_wanted: (
            _free_stream(values, directed) if drag_wanted else FreeStream(None, None, None)
        )

    return group("flow", _FLOW + _SPEED + _AIR, build)


def _epoch(values: dict) -> None:
    """Take ``--time``, the former name of ``--epoch``, into ``values["time"]``, with a warning."""
    old = values.pop("old_time")
    if old is None:
        return
    if given("time"):
        raise InputError("--time is the former name of --epoch: give the date once", hint="drop --time")
    warnings.warn("--time is now called --epoch; it was taken as --epoch", FutureWarning, stacklevel=2)
    values["time"] = old


#: The keywords of the flow flags that mean nothing without a flow direction.
_FLOW_ONLY = (
    "speed", "corotating", "heading", "nadir", "lat", "lon", "f107", "f107a", "ap", "density",
    "temperature", "composition", "normalise_composition", "sky_rays",
)  # fmt: skip


def refuse_without_flow(keywords: list[str]) -> None:
    """Refuse, in one message, the drag's flags given to ``sunwind forces`` without a flow direction.

    Parameters
    ----------
    keywords : list of str
        The keywords of the drag's flags that were given (``sky_rays`` for ``--sky-rays``); an empty
        list is accepted.

    Raises
    ------
    InputError
        ``keywords`` is not empty.

    Examples
    --------
    >>> refuse_without_flow([])  # nothing given: nothing refused
    >>> refuse_without_flow(["density", "sky_rays"])
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --density, --sky-rays set the drag, which needs the flow's ...
    """
    flags = ["--" + key.replace("_", "-") for key in keywords]
    if flags:
        raise InputError(
            f"{', '.join(flags)} {'sets' if len(flags) == 1 else 'set'} the drag, which needs the flow's "
            "direction",
            hint="add --velocity X Y Z or --flow-azel AZ EL, or drop them for SRP alone",
        )


def _no_flow(values: dict) -> FreeStream:
    """The flow of ``forces`` without ``--velocity`` or ``--flow-azel``: none, so no drag;
    ``--altitude`` and ``--epoch`` still place the Earth's radiation."""
    refuse_without_flow([key for key in _FLOW_ONLY if given(key)])
    return FreeStream(None, None, None, altitude_km=values["altitude"], time=values["time"])


def _free_stream(values: dict, directed: bool) -> FreeStream:
    stream = _flow(values, directed)
    where = {"altitude_km": values["altitude"], "time": values["time"]}
    return replace(stream, sampling=GasSampling(sky_rays=values["sky_rays"]), **where)


def _flow(values: dict, directed: bool) -> FreeStream:
    velocity, azel = values["velocity"], values["flow_azel"]
    if values["nadir"] is not None and not (directed and values["corotating"]):
        raise InputError(
            "--nadir places the co-rotating air's crosswind of --corotating --flow-azel",
            hint="drop --nadir" if not directed else "add --corotating, or drop --nadir",
        )
    if not directed:
        if velocity is not None or azel is not None:
            raise InputError(
                "a sweep takes its flow directions from the grid or the attitude list",
                hint="drop --velocity/--flow-azel; give --speed or --altitude for the speed",
            )
        if values["speed"] is None and values["altitude"] is None:
            raise InputError(
                "a drag table needs the flow's speed and the air: --altitude H [km] (NRLMSIS and the "
                "circular-orbit speed), or --speed V with --density, --temperature and --composition",
                hint="or tabulate SRP alone with --srp",
            )
        if values["corotating"] and values["speed"] is not None:
            raise InputError(
                "--corotating changes the circular-orbit speed at --altitude only", hint="drop --speed"
            )
        return FreeStream(None, _speed(values), _atmosphere(values))
    if (velocity is None) == (azel is None):
        raise InputError("give the flow with --velocity X Y Z or --flow-azel AZ EL (one of them)")
    if values["corotating"] and (velocity is not None or values["speed"] is not None):
        raise InputError(
            "--corotating takes v_rel from the circular orbit at --altitude and --flow-azel",
            hint="drop --speed/--velocity, or give the relative velocity itself",
        )
    if velocity is not None:
        v = checked_velocities(velocity)
        return FreeStream(v, float(np.linalg.norm(v)), _atmosphere(values))
    direction = azel_to_vector(*azel, "--flow-azel")
    if values["corotating"]:
        if values["altitude"] is None:
            raise InputError("--corotating needs --altitude, the height of the circular orbit")
        orbit = (values["altitude"], values["lat"], values["heading"])
        v = checked_velocities(corotation_velocity(*orbit, direction, values["nadir"]))
        return FreeStream(v, float(np.linalg.norm(v)), _atmosphere(values))
    speed = _speed(values)
    return FreeStream(speed * direction, speed, _atmosphere(values))


def _speed(values: dict) -> float:
    """``|v_rel|`` [m/s]: ``--speed``, else the circular-orbit speed at ``--altitude`` (relative to a
    co-rotating atmosphere with ``--corotating``)."""
    if values["speed"] is not None:
        return flow_speed(values["speed"], "speed_m_s")
    if values["altitude"] is None:
        raise InputError("a flow direction needs --speed V, or --altitude for the circular-orbit speed")
    speed = circular_speed(values["altitude"])
    if values["corotating"]:
        speed = corotation_speed(values["altitude"], values["lat"], values["heading"], speed)
    return speed


def _atmosphere(values: dict) -> Atmosphere:
    """Explicit when any of density, temperature, composition is given (then all three are needed),
    else NRLMSIS at the altitude."""
    given = {
        "--density": values["density"],
        "--temperature": values["temperature"],
        "--composition": values["composition"],
    }
    if any(value is not None for value in given.values()):
        missing = [flag for flag, value in given.items() if value is None]
        if missing:
            raise InputError(
                f"an explicit atmosphere needs {', '.join(missing)} too",
                hint='e.g. --density 3e-12 --temperature 1000 --composition "O:0.8,N2:0.2"',
            )
        return explicit(
            values["density"], values["temperature"], values["composition"], values["normalise_composition"]
        )
    if values["altitude"] is None:
        raise InputError(
            "give the atmosphere: --altitude H [km] for NRLMSIS, or --density, --temperature, --composition"
        )
    keys = ("altitude", "lat", "lon", "time", "f107", "f107a", "ap")
    return nrlmsis(*(values[key] for key in keys))
