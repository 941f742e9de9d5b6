"""Flight telemetry for :func:`~sunwind.forces.fit.fit`: a CSV file read and checked, one row a sample.

Columns (a header line first; lines starting ``#`` are skipped):

- ``time_s`` [s], strictly increasing;
- the Sun, body frame: ``sun_x, sun_y, sun_z`` (any length, normalised here); or the attitude
  ``qw, qx, qy, qz`` (scalar first, body to ECI/GCRF, unit to within :data:`UNIT_TOLERANCE`) with an
  ``epoch``, the Sun then from the ephemeris (its direction from the Earth's centre; the flux scaled to
  its distance unless ``flux_W_m2`` is given). With both, the ``sun_*`` columns give the Sun and the
  quaternions the inertial frame of the momentum;
- optional ``flux_W_m2`` (default the flux at 1 au, :data:`~sunwind.forces.radiation.law.SOLAR_FLUX_1AU`),
  ``solar_fraction`` (0 to 1; eclipse) and
  ``hinge:GLOB`` [deg], the angle of the materials file's hinge ``GLOB``;
- for drag, optional: ``vel_x, vel_y, vel_z`` [m/s], the spacecraft's velocity relative to the
  atmosphere, body frame, with ``density_kg_m3`` [kg/m^3] and optionally ``temperature_K`` (default
  :data:`DEFAULT_TEMPERATURE_K`); the composition is the fit's (atomic oxygen, ``O:1``, by default);
- measurements, any of: ``torque_x, torque_y, torque_z`` [N m, body frame]; ``momentum_x, momentum_y,
  momentum_z`` [N m s, the angular impulse accumulated since an unknown start: inertial frame of the
  quaternions, else body frame, which is right when the attitude is inertially fixed]; ``accel_x,
  accel_y, accel_z`` [m/s^2, body frame].

>>> import pathlib, tempfile
>>> folder = tempfile.TemporaryDirectory()
>>> path = pathlib.Path(folder.name) / "t.csv"
>>> _ = path.write_text("time_s,sun_x,sun_y,sun_z,torque_x,torque_y,torque_z\\n0,1,0,0,0,0,1e-6\\n")
>>> read_telemetry(path).kinds
('torque',)
>>> folder.cleanup()
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.columns import Columns, check_times, read_rows, unit_rows
from sunwind.forces.orbit.attitude import quaternion_matrix
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.geometry.errors import InputError

#: Largest ``| |q| - 1 |`` of a quaternion accepted.
UNIT_TOLERANCE = 1e-6
#: Measurement kinds: their column prefix, unit, and the name of their sigma.
KINDS = {
    "torque": ("torque", "N m", "sigma_torque"),
    "momentum": ("momentum", "N m s", "sigma_momentum"),
    "accel": ("accel", "m/s^2", "sigma_accel"),
}
SUN, QUATERNION = ("sun_x", "sun_y", "sun_z"), ("qw", "qx", "qy", "qz")
VELOCITY = ("vel_x", "vel_y", "vel_z")
#: Free-stream temperature [K] of drag rows without a ``temperature_K`` column.
DEFAULT_TEMPERATURE_K = 1000.0
HINGE_PREFIX = "hinge:"


@dataclass(frozen=True, eq=False)
class Telemetry:
    """Checked telemetry: the geometry of every sample and what was measured.

    Attributes
    ----------
    time_s : (n,) float64
        Sample times [s], increasing.
    sun_body : (n, 3) float64
        Unit vector toward the Sun, body frame.
    flux_W_m2, solar_fraction : (n,) float64
        Solar flux [W/m^2] and the lit share of the Sun's disc.
    measured : dict of str to (n, 3) float64
        ``torque`` [N m], ``momentum`` [N m s], ``accel`` [m/s^2], those given.
    hinges : dict of str to (n,) float64
        Hinge angles [deg] by glob.
    rotation : (n, 3, 3) float64 or None
        Body-to-inertial rotations of the quaternions; None without them.
    flow : dict of str to ndarray or None
        For drag: ``velocity_m_s`` (n, 3), ``density_kg_m3`` (n,) and ``temperature_K`` (n,); None
        without drag columns.
    source : str
        The file, for messages.

    Examples
    --------
    >>> import numpy as np
    >>> t = Telemetry(np.arange(3.0), np.tile([1.0, 0, 0], (3, 1)), np.full(3, 1361.0), np.ones(3),
    ...               {"torque": np.zeros((3, 3))})
    >>> t.kinds, len(t)
    (('torque',), 3)
    """

    time_s: NDArray[np.float64]
    sun_body: NDArray[np.float64]
    flux_W_m2: NDArray[np.float64]
    solar_fraction: NDArray[np.float64]
    measured: Mapping[str, NDArray[np.float64]]
    hinges: Mapping[str, NDArray[np.float64]] = field(default_factory=dict)
    rotation: NDArray[np.float64] | None = None
    flow: Mapping[str, NDArray[np.float64]] | None = None
    source: str = "<telemetry>"

    def __len__(self) -> int:
        return len(self.time_s)

    @property
    def kinds(self) -> tuple[str, ...]:
        """The measurement kinds given, in the order of :data:`KINDS`."""
        return tuple(kind for kind in KINDS if kind in self.measured)


def read_telemetry(path: str | Path, epoch: str | None = None) -> Telemetry:
    """Read and check a telemetry CSV file (columns as the module says).

    Parameters
    ----------
    path : path
        The CSV file.
    epoch : str, optional
        ISO 8601 UTC instant of ``time_s = 0``; needed for the Sun of the quaternions.

    Returns
    -------
    Telemetry

    Raises
    ------
    InputError
        Naming the file, the line and the column, and the fix: a missing column, a value that is no
        finite number, times unsorted or repeated, a quaternion not of unit length, no measurement.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = pathlib.Path(folder.name) / "t.csv"
    >>> _ = path.write_text("time_s,sun_x,sun_y,sun_z,torque_x,torque_y,torque_z\\n"
    ...                     "0,1,0,0,0,0,1e-6\\n0,1,0,0,0,0,1e-6\\n")
    >>> read_telemetry(path)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: ...t.csv: line 3: time_s 0 repeats the previous row's ...
    >>> folder.cleanup()
    """
    where = str(path)
    header, lines, rows = read_rows(
        Path(path), "telemetry", "columns time_s, sun_x, sun_y, sun_z (or qw, qx, qy, qz) and measurements"
    )
    columns = Columns(header, lines, rows, where)
    time = columns.numbers("time_s", "give each row's time [s]")
    check_times(time, lines, where)
    rotation = None
    if all(name in header for name in QUATERNION):
        rotation = _rotations(columns.block(QUATERNION), lines, where)
    else:
        columns.whole(QUATERNION, "give all of qw, qx, qy, qz (body to ECI, scalar first)")
    flux_given = "flux_W_m2" in header
    if all(name in header for name in SUN):
        sun = unit_rows(
            columns.block(SUN),
            lines,
            where,
            "the Sun direction sun_x, sun_y, sun_z",
            "give the body-frame direction toward the Sun",
        )
        distance_flux = None
    elif rotation is not None:
        sun, distance_flux = _ephemeris_sun(time, rotation, epoch, where)
    else:
        columns.whole(SUN, "give sun_x, sun_y, sun_z (body frame)")
        raise InputError(
            "no Sun: the file has neither sun_x, sun_y, sun_z nor qw, qx, qy, qz",
            path=where,
            hint="add the body-frame Sun direction, or the attitude quaternions with --epoch",
        )
    if flux_given:
        flux = columns.numbers("flux_W_m2", "give the solar flux [W/m^2]", 0.0)
    else:
        flux = distance_flux if distance_flux is not None else np.full(len(time), SOLAR_FLUX_1AU)
    fraction = np.ones(len(time))
    if "solar_fraction" in header:
        fraction = columns.numbers("solar_fraction", "give the lit share of the Sun, 0 to 1", 0.0, 1.0)
    measured = {}
    for kind, (prefix, _, _) in KINDS.items():
        names = tuple(f"{prefix}_{axis}" for axis in "xyz")
        if any(name in header for name in names):
            columns.whole(names, f"give all of {', '.join(names)}")
            measured[kind] = columns.block(names)
    if not measured:
        raise InputError(
            "no measurement columns",
            path=where,
            hint="give torque_x..z [N m], momentum_x..z [N m s] or accel_x..z [m/s^2], body frame",
        )
    hinges = {
        name[len(HINGE_PREFIX) :]: columns.numbers(name, "give the hinge angle [deg]")
        for name in header
        if name.startswith(HINGE_PREFIX)
    }
    return Telemetry(time, sun, flux, fraction, measured, hinges, rotation, _flow(columns, header), where)


def _flow(columns: Columns, header: list[str]) -> dict[str, NDArray] | None:
    """The drag columns, or None."""
    if not any(name in header for name in VELOCITY):
        return None
    columns.whole(VELOCITY, "give all of vel_x, vel_y, vel_z (velocity relative to the air, body frame)")
    temperature = np.full(len(columns.rows), DEFAULT_TEMPERATURE_K)
    if "temperature_K" in header:
        temperature = columns.numbers("temperature_K", "give the free-stream temperature [K]", 0.0)
    return {
        "velocity_m_s": columns.block(VELOCITY),
        "density_kg_m3": columns.numbers("density_kg_m3", "give the air density [kg/m^3] with vel_x..z", 0.0),
        "temperature_K": temperature,
    }


def _rotations(q: NDArray, lines: list[int], where: str) -> NDArray:
    norms = np.linalg.norm(q, axis=1)
    worst = int(np.argmax(np.abs(norms - 1.0)))
    if abs(norms[worst] - 1.0) > UNIT_TOLERANCE:
        raise InputError(
            f"line {lines[worst]}: qw, qx, qy, qz is not a unit quaternion (|q| = {norms[worst]:.9g}, "
            f"more than {UNIT_TOLERANCE:g} from 1)",
            path=where,
            hint="normalise the quaternions (body to ECI, scalar first)",
        )
    return quaternion_matrix(q)


def _ephemeris_sun(
    time: NDArray, rotation: NDArray, epoch: str | None, where: str
) -> tuple[NDArray, NDArray]:
    """The body-frame Sun of the quaternions and the flux at the Sun's distance from the Earth."""
    if epoch is None:
        raise InputError(
            "the Sun of the quaternions qw, qx, qy, qz needs the epoch of time_s = 0",
            path=where,
            hint="give --epoch ISO-UTC (e.g. 2024-03-20T00:00:00Z), or sun_x, sun_y, sun_z columns",
        )
    sun = sun_position(Epoch.of(epoch), time)
    distance = np.linalg.norm(sun, axis=1)
    body = np.einsum("nji,nj->ni", rotation, sun / distance[:, None])
    return body, SOLAR_FLUX_1AU * (AU_M / distance) ** 2
