"""A trajectory from the user's ephemeris file: time-tagged GCRF positions and velocities, interpolated
to the steps by a cubic Hermite spline on position and velocity: off by up to ``h^4 |r''''| / 384`` for
rows ``h`` apart, on a low orbit (``|r''''| = n^4 r``) about 0.3 m for rows a minute apart, 0.3 mm for
10 s.

The file is CSV with a header naming ``time`` (ISO 8601 UTC) or ``time_s`` (seconds after the run's
epoch), ``x_m, y_m, z_m`` and ``vx_m_s, vy_m_s, vz_m_s`` (GCRF/ECI); ``_km`` and ``_km_s`` columns
are taken too. Rows must be in time order; the steps must lie within the file's span.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import CubicHermiteSpline

from sunwind.forces.gas.flow import EARTH_RADIUS
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.geometry.errors import InputError

_AXES = ("x", "y", "z")


def read_ephemeris(path: str | Path, epoch: Epoch | None) -> tuple[Epoch, NDArray, NDArray, NDArray]:
    r"""The contents of an ephemeris file, checked: epoch, times, positions and velocities.

    Parameters
    ----------
    path : str or Path
        A CSV file with a header naming ``time`` (ISO 8601 UTC) or ``time_s`` (seconds after ``epoch``),
        ``x_m, y_m, z_m`` and ``vx_m_s, vy_m_s, vz_m_s`` (GCRF), or ``_km`` and ``_km_s`` columns; rows in
        time order, lines starting ``#`` skipped.
    epoch : Epoch or None
        Time zero; ``None`` takes the file's first ``time``.

    Returns
    -------
    epoch : Epoch
        The given epoch, else the file's first time.
    time_s : ndarray of float64, shape (m,)
        The rows' times [s] after ``epoch``, increasing.
    position_m : ndarray of float64, shape (m, 3)
        Positions [m], GCRF.
    velocity_m_s : ndarray of float64, shape (m, 3)
        Velocities [m/s], GCRF.

    Raises
    ------
    InputError
        An unreadable file, fewer than two rows, missing or non-numeric columns, ``time_s`` without an
        epoch, times not increasing, or a position inside the Earth.

    Examples
    --------
    A file of three rows, a minute apart, from a two-body orbit:

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> truth = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0, 120.0], "kepler")
    >>> lines = ["time,x_km,y_km,z_km,vx_km_s,vy_km_s,vz_km_s"] + [
    ...     epoch.at(t).isoformat() + "," + ",".join(f"{x:.9f}" for x in [*r, *v])
    ...     for t, r, v in zip(truth.time_s, truth.position_m / 1e3, truth.velocity_m_s / 1e3)
    ... ]
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = pathlib.Path(folder.name) / "orbit.csv"
    >>> _ = path.write_text("\n".join(lines) + "\n")
    >>> start, times, position, velocity = sw.orbit.ephemeris_csv.read_ephemeris(path, None)
    >>> start.iso(), times.tolist(), position.shape
    ('2024-03-20T00:00:00.000Z', [0.0, 60.0, 120.0], (3, 3))
    >>> folder.cleanup()
    """
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as handle:  # a byte-order mark is no column
            rows = list(csv.DictReader(row for row in handle if not row.lstrip().startswith("#")))
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read the ephemeris file ({error})", path=str(path)) from None
    if len(rows) < 2:
        raise InputError("the ephemeris file has fewer than two rows", path=str(path))
    header = set(rows[0])
    position, p_scale = _columns(rows, path, header, "{}_m", "{}_km")
    velocity, v_scale = _columns(rows, path, header, "v{}_m_s", "v{}_km_s")
    if "time_s" in header:
        if epoch is None:
            raise InputError(
                "the ephemeris gives time_s (seconds after the epoch) but no --epoch was given",
                path=str(path),
                hint="give --epoch, or a time column of ISO 8601 UTC times",
            )
        times = _numbers(rows, "time_s", path)
    elif "time" in header:
        stamps = [Epoch.of(row["time"]) for row in rows]
        epoch = epoch or stamps[0]
        times = np.array([(stamp.utc - epoch.utc).total_seconds() for stamp in stamps])
    else:
        raise InputError(
            "the ephemeris file has no time or time_s column",
            path=str(path),
            hint="name the columns time (ISO 8601 UTC) or time_s, x_m, ..., vz_m_s",
        )
    if np.any(np.diff(times) <= 0):
        raise InputError("the ephemeris times are not increasing", path=str(path))
    position, velocity = position * p_scale, velocity * v_scale
    radius = np.linalg.norm(position, axis=1)
    if np.any(radius <= EARTH_RADIUS):
        row = int(np.argmax(radius <= EARTH_RADIUS))
        kilometres = p_scale == 1.0 and radius[row] * 1e3 > EARTH_RADIUS
        raise InputError(
            f"row {row + 1}'s position is {radius[row]:.6g} m from the Earth's centre, inside the Earth"
            + (": the positions look like km in metre columns" if kilometres else ""),
            path=str(path),
            hint="name the columns x_km, y_km, z_km and vx_km_s, ... for km and km/s"
            if kilometres
            else "give GCRF positions from the Earth's centre, not altitudes",
        )
    return epoch, times, position, velocity


def ephemeris_trajectory(path: str | Path, epoch: Epoch | None, time_s: NDArray[np.float64]) -> Trajectory:
    r"""The states at ``time_s`` [s] after the epoch, interpolated in an ephemeris file.

    A cubic Hermite spline through the rows' positions and velocities gives the states between them.

    Parameters
    ----------
    path : str or Path
        The ephemeris file, as :func:`read_ephemeris` reads it.
    epoch : Epoch or None
        Time zero; ``None`` takes the file's first ``time``.
    time_s : ndarray of float64, shape (n,)
        Seconds after the epoch, within the file's span.

    Returns
    -------
    Trajectory
        Positions [m] and velocities [m/s] in GCRF at ``time_s``.

    Raises
    ------
    InputError
        A file :func:`read_ephemeris` refuses, or a step outside the file's times.

    Examples
    --------
    Between two rows a minute apart on a low orbit, the spline is some 0.3 m off:

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> truth = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0, 120.0], "kepler")
    >>> lines = ["time,x_km,y_km,z_km,vx_km_s,vy_km_s,vz_km_s"] + [
    ...     epoch.at(t).isoformat() + "," + ",".join(f"{x:.9f}" for x in [*r, *v])
    ...     for t, r, v in zip(truth.time_s, truth.position_m / 1e3, truth.velocity_m_s / 1e3)
    ... ]
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = pathlib.Path(folder.name) / "orbit.csv"
    >>> _ = path.write_text("\n".join(lines) + "\n")
    >>> between = sw.orbit.ephemeris_trajectory(path, None, np.array([90.0]))
    >>> exact = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [90.0], "kepler")
    >>> round(float(np.linalg.norm(between.position_m - exact.position_m)), 1)
    0.3
    >>> sw.orbit.ephemeris_trajectory(path, None, np.array([300.0]))
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: ...outside the ephemeris (0 to 120 s)...
    >>> folder.cleanup()
    """
    epoch, times, position, velocity = read_ephemeris(path, epoch)
    time_s = np.asarray(time_s, dtype=float)
    outside = (time_s < times[0] - 1e-9) | (time_s > times[-1] + 1e-9)
    if np.any(outside):
        raise InputError(
            f"the run's steps reach {time_s[outside][0]:g} s after the epoch, outside the ephemeris "
            f"({times[0]:g} to {times[-1]:g} s)",
            path=str(path),
            hint="shorten --duration or start --epoch within the file",
        )
    spline = CubicHermiteSpline(times, position, velocity, axis=0)
    return Trajectory(
        epoch, np.asarray(time_s, dtype=float), spline(time_s), spline(time_s, 1), f"ephemeris {path}"
    )


def _columns(rows, path, header, metres: str, kilometres: str) -> tuple[NDArray, float]:
    for pattern, scale in ((metres, 1.0), (kilometres, 1e3)):
        names = [pattern.format(axis) for axis in _AXES]
        if header.issuperset(names):
            return np.stack([_numbers(rows, name, path) for name in names], axis=1), scale
    raise InputError(
        f"the ephemeris file has no columns {', '.join(metres.format(a) for a in _AXES)}",
        path=str(path),
        hint="name the columns time, x_m, y_m, z_m, vx_m_s, vy_m_s, vz_m_s (or _km, _km_s)",
    )


def _numbers(rows, name: str, path) -> NDArray[np.float64]:
    try:
        values = np.array([float(row[name]) for row in rows])
    except (TypeError, ValueError):
        raise InputError(f"column {name} holds a value that is not a number", path=str(path)) from None
    if not np.all(np.isfinite(values)):
        raise InputError(f"column {name} holds a value that is not finite", path=str(path))
    return values
