"""Where ``sunwind orbit``'s spacecraft goes: the orbit's flags (elements, a circular orbit, a TLE or an
ephemeris; the epoch, duration and step) and the :class:`PathRequest` they make, checked before any work."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import click
import numpy as np

from sunwind.forces.orbit import Elements, Epoch, Trajectory, propagate
from sunwind.forces.orbit.ephemeris_csv import ephemeris_trajectory, read_ephemeris
from sunwind.forces.orbit.tle import read_tle, tle_epoch, tle_period_s, tle_trajectory
from sunwind.forces.orbit.trajectory import PROPAGATORS, TrajectoryWarning
from sunwind.geometry import memory
from sunwind.geometry.errors import InputError

#: Estimated bytes per step (inputs, records, series, rotations, output).
STEP_BYTES = 2000
#: Default step between outputs [s].
DEFAULT_STEP_S = 60.0
#: Most steps a run takes unless ``--max-steps`` says more.
DEFAULT_MAX_STEPS = 100_000
#: A TLE used further than this from its epoch [days] is said to be stale.
STALE_ELEMENTS_DAYS = 30.0

PATH_OPTIONS = [
    click.option(
        "--elements",
        nargs=6,
        type=float,
        default=None,
        metavar="A_KM E I RAAN ARGP NU",
        help="Keplerian elements at the epoch: semi-major axis [km], eccentricity, angles [deg].",
    ),
    click.option("--altitude", type=float, help="Circular orbit: altitude [km] above 6378.137 km."),
    click.option("--inclination", type=float, help="Circular orbit: inclination [deg]."),
    click.option("--raan", type=float, default=0.0, show_default=True, help="Circular orbit: RAAN [deg]."),
    click.option(
        "--arg-latitude",
        type=float,
        default=0.0,
        show_default=True,
        help="Circular orbit: argument of latitude at the epoch [deg].",
    ),
    click.option(
        "--propagator",
        type=click.Choice(PROPAGATORS),
        default="kepler",
        show_default=True,
        help="Elements propagated by two-body motion or with J2.",
    ),
    click.option("--tle", type=click.Path(path_type=Path), help="TLE file, propagated by SGP4."),
    click.option(
        "--ephemeris",
        type=click.Path(path_type=Path),
        help="CSV of time, x_m, y_m, z_m, vx_m_s, vy_m_s, vz_m_s (GCRF).",
    ),
    click.option("--epoch", help="Start, UTC ISO 8601 [default: the TLE's or the ephemeris' first time]."),
    click.option("--duration", type=float, help="Run length [s] [default: one orbital period]."),
    click.option(
        "--step", type=float, default=DEFAULT_STEP_S, show_default=True, help="Time between steps [s]."
    ),
    click.option(
        "--max-steps",
        type=click.IntRange(min=1),
        default=DEFAULT_MAX_STEPS,
        show_default=True,
        help="Refuse a run of more steps than this (a run of days at short steps takes hours).",
    ),
]


@dataclass(frozen=True)
class PathRequest:
    """Where ``sunwind orbit``'s spacecraft goes: one source of states, the epoch, duration and step.

    Exactly one of ``elements``, ``tle`` and ``ephemeris`` is set (:func:`path_request` checks it).

    Parameters
    ----------
    elements : Elements or None
        Keplerian elements at the epoch (``--elements``, or a circular orbit).
    propagator : str
        How elements are propagated: one of ``PROPAGATORS`` (two-body ``"kepler"``, or with J2).
    tle : pathlib.Path or None
        A two-line element file, propagated by SGP4.
    ephemeris : pathlib.Path or None
        A CSV of GCRF states, interpolated.
    epoch : Epoch or None
        The run's start; None takes the TLE's epoch or the ephemeris' first time.
    duration_s : float or None
        The run's length [s]; None is one orbital period (or the whole ephemeris).
    step_s : float
        The time between steps [s].
    max_steps : int, optional
        The most steps a run may take.

    Examples
    --------
    >>> from sunwind.forces.orbit import Elements, Epoch
    >>> orbit = Elements.circular(500.0, 97.4, 0.0, 0.0)
    >>> request = PathRequest(elements=orbit, propagator="kepler", tle=None, ephemeris=None,
    ...                       epoch=Epoch.of("2024-03-20T00:00:00Z"), duration_s=600.0, step_s=60.0)
    >>> request.step_count(600.0)
    11
    >>> float(request.trajectory().time_s[-1])  # the last step's time [s]
    600.0
    """

    elements: Elements | None
    propagator: str
    tle: Path | None
    ephemeris: Path | None
    epoch: Epoch | None
    duration_s: float | None
    step_s: float
    max_steps: int = DEFAULT_MAX_STEPS

    def trajectory(self) -> Trajectory:
        """The states at every step, their count checked against the memory limit first."""
        epoch = self.epoch
        if self.tle is not None:
            epoch = epoch or tle_epoch(*read_tle(self.tle))
        if self.ephemeris is not None:
            epoch, times, _, _ = read_ephemeris(self.ephemeris, epoch)
            default = times[-1]
        elif self.elements is not None:
            default = self.elements.period_s
        else:
            default = tle_period_s(*read_tle(self.tle))
        if epoch is None:
            raise InputError(
                "give --epoch: the UTC start of the run", hint="e.g. --epoch 2024-03-20T00:00:00Z"
            )
        duration = self.duration_s if self.duration_s is not None else default
        count = self.step_count(duration)
        memory.require(count * STEP_BYTES, f"{count:.3g} steps", "raise --step or shorten --duration")
        time_s = np.arange(count) * self.step_s
        if self.tle is not None:
            _warn_elements_age(tle_epoch(*read_tle(self.tle)), epoch, time_s[-1])
            return tle_trajectory(self.tle, epoch, time_s)
        if self.ephemeris is not None:
            return ephemeris_trajectory(self.ephemeris, epoch, time_s)
        return propagate(self.elements, epoch, time_s, self.propagator)

    def step_count(self, duration_s: float) -> int:
        """Steps of a run of ``duration_s`` [s]: one at the start and one per whole step after it.

        Raises
        ------
        InputError
            A step longer than the run, or more steps than ``max_steps``.
        """
        if self.step_s > duration_s * (1 + 1e-9):
            raise InputError(
                f"--step {self.step_s:g} s is longer than the run ({duration_s:g} s): it would be one step",
                hint="give a --step at most the --duration, or a longer --duration",
            )
        steps = duration_s / self.step_s + 1  # may overflow to inf for a step of 1e-300 s
        if not steps <= self.max_steps:
            cost = (
                f"{_span(steps * 0.01)} to {_span(steps * 0.1)}" if math.isfinite(steps) else "never ending"
            )
            many = f"{steps:.6g}" if math.isfinite(steps) else "over 1e308"
            raise InputError(
                f"{many} steps ({duration_s:g} s every {self.step_s:g} s) are more than --max-steps "
                f"{self.max_steps}: at 10-100 ms per step on a model of 10 000-100 000 triangles, {cost}",
                hint="raise --step or shorten --duration"
                + (f", or give --max-steps {math.ceil(steps)}" if steps < 1e9 else ""),
            )
        return math.floor(steps - 1 + 1e-9) + 1


def _span(seconds: float) -> str:
    """A duration for a person: minutes, hours or days."""
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    if seconds < 172800:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:.1f} days" if seconds < 3.15576e8 else f"{seconds / 3.15576e7:.3g} years"


def _warn_elements_age(elements_epoch: Epoch, start: Epoch, run_s: float) -> None:
    """A warning when the run lies more than ``STALE_ELEMENTS_DAYS`` from the TLE's epoch: SGP4's error
    grows by about a kilometre a day away from it."""
    offset = (start.utc - elements_epoch.utc).total_seconds()
    days = max(abs(offset), abs(offset + run_s)) / 86400
    if days > STALE_ELEMENTS_DAYS:
        warnings.warn(
            f"the run reaches {days:.0f} days from the TLE's epoch ({elements_epoch.iso()}): SGP4's "
            "position error grows by about a kilometre a day; use elements of the run's dates",
            TrajectoryWarning,
            stacklevel=2,
        )


def path_request(values: dict) -> PathRequest:
    """Make the checked :class:`PathRequest` of the orbit flags (:data:`PATH_OPTIONS`).

    Parameters
    ----------
    values : dict
        The flags' values by keyword: ``elements`` (six numbers: a [km], e, i, RAAN, argp, nu
        [deg]), ``altitude`` [km], ``inclination``, ``raan`` and ``arg_latitude`` [deg],
        ``propagator``, ``tle``, ``ephemeris``, ``epoch`` (UTC ISO 8601), ``duration`` and ``step``
        [s], ``max_steps``; None where not given.

    Returns
    -------
    PathRequest
        The orbit's source of states, epoch, duration and step.

    Raises
    ------
    InputError
        No orbit or more than one, a circular orbit without both altitude and inclination, a
        duration or step that is not a positive number, or an epoch that cannot be read.

    Examples
    --------
    >>> flags = {"elements": None, "altitude": 500.0, "inclination": 97.4, "raan": 0.0,
    ...          "arg_latitude": 0.0, "propagator": "kepler", "tle": None, "ephemeris": None,
    ...          "epoch": "2024-03-20T00:00:00Z", "duration": None, "step": 60.0, "max_steps": 1000}
    >>> request = path_request(flags)
    >>> round(request.elements.a_m / 1e3, 3), request.duration_s
    (6878.137, None)
    >>> path_request({**flags, "altitude": None, "inclination": None})
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: give an orbit; --elements, --altitude with --inclination, ...
    """
    elements = None
    if values["elements"] is not None:
        a_km, e, i, raan, argp, nu = values["elements"]
        elements = Elements(a_km * 1e3, e, i, raan, argp, nu)
    if values["altitude"] is not None or values["inclination"] is not None:
        if values["altitude"] is None or values["inclination"] is None:
            raise InputError("a circular orbit needs --altitude and --inclination")
        elements = Elements.circular(
            values["altitude"], values["inclination"], values["raan"], values["arg_latitude"]
        )
    given = [
        flag
        for flag, on in (
            ("--elements", values["elements"] is not None),
            ("--altitude/--inclination", values["altitude"] is not None),
            ("--tle", values["tle"] is not None),
            ("--ephemeris", values["ephemeris"] is not None),
        )
        if on
    ]
    if len(given) != 1:
        raise InputError(
            f"give one orbit, not {' and '.join(given)}" if given else "give an orbit",
            hint="--elements, --altitude with --inclination, --tle FILE or --ephemeris FILE",
        )
    for name in ("duration", "step"):
        value = values[name]
        if value is not None and not (math.isfinite(value) and value > 0):
            raise InputError(f"--{name} {value:g} s must be a positive number of seconds")
    try:
        epoch = None if values["epoch"] is None else Epoch.of(values["epoch"])
    except InputError as error:
        raise error.renamed({"time": "--epoch"}) from None
    return PathRequest(
        elements,
        values["propagator"],
        values["tle"],
        values["ephemeris"],
        epoch,
        values["duration"],
        values["step"],
        values["max_steps"],
    )
