"""A trajectory from a two-line element set, propagated by SGP4 (the ``sgp4`` package, Vallado's code)
and turned from its TEME frame into GCRF.

TEME's x axis is the mean equinox of date measured along the true equator: ``r_TOD = R3(-Eq) r_TEME``
with the equation of the equinoxes ``Eq`` (IAU 1994, ``erfa.eqeq94``), then ``r_GCRF = NPB^T r_TOD``
with the IAU 1976/1980 precession-nutation matrix (``erfa.pnm80``), as Vallado et al. (2006,
"Revisiting Spacetrack Report #3", sec. VI) do. Velocities are rotated alike (the frame's own slow
rotation, under 1e-11 rad/s, is left out).
"""

from __future__ import annotations

from pathlib import Path

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.geometry.errors import InputError

#: Characters of a TLE's element line, its checksum the last.
LINE_LENGTH = 69


def read_tle(path: str | Path) -> tuple[str, str]:
    r"""The two element lines of a TLE file, checked.

    An optional name line before them is skipped. Each line must have 69 characters and its checksum
    (:func:`checksum`), line 1 then line 2 of one satellite, and line 1 a readable epoch.

    Parameters
    ----------
    path : str or Path
        The TLE file (two-line or three-line format; the first element set is read).

    Returns
    -------
    tuple of (str, str)
        Line 1 and line 2, trailing blanks removed.

    Raises
    ------
    InputError
        An unreadable file, no element set, a truncated or altered line, or lines of two satellites.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from sunwind.forces.orbit.tle import read_tle
    >>> l1 = "1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927"
    >>> l2 = "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537"
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "iss.tle"
    ...     _ = path.write_text(f"ISS (ZARYA)\n{l1}\n{l2}\n")
    ...     read_tle(path) == (l1, l2)
    True
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "typo.tle"
    ...     _ = path.write_text(f"{l1}\n{l2[:-1]}8\n")
    ...     read_tle(path)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: ...line 2 of the element set fails its checksum...
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise InputError(f"cannot read the TLE file ({error.strerror})", path=str(path)) from None
    # the element lines are ASCII; a name line in another encoding is only a name
    text = raw.decode("utf-8-sig", errors="replace")
    lines = [line.rstrip() for line in text.splitlines() if line.strip()]
    ones = [i for i, line in enumerate(lines) if line.startswith("1 ")]
    if not ones or ones[0] + 1 >= len(lines) or not lines[ones[0] + 1].startswith("2 "):
        raise InputError(
            "no two-line element set: a line starting '1 ' followed by one starting '2 '",
            path=str(path),
            hint="give the two 69-character lines of a TLE (a name line before them is allowed)",
        )
    pair = lines[ones[0]], lines[ones[0] + 1]
    for number, line in enumerate(pair, start=1):
        if len(line) != LINE_LENGTH:
            raise InputError(
                f"line {number} of the element set has {len(line)} characters, not {LINE_LENGTH}",
                path=str(path),
                hint="the line was cut or wrapped: copy both lines whole from their source",
            )
        expected = checksum(line)
        if line[-1] != str(expected):
            raise InputError(
                f"line {number} of the element set fails its checksum (last digit {line[-1]!r}, the "
                f"line's digits give {expected})",
                path=str(path),
                hint="a character was altered or mistyped: copy the line again from its source",
            )
    if pair[0][2:7] != pair[1][2:7]:
        raise InputError(
            f"the element lines are of two satellites ({pair[0][2:7].strip()} and {pair[1][2:7].strip()})",
            path=str(path),
            hint="give lines 1 and 2 of one satellite",
        )
    _epoch_field(pair[0], path)
    return pair


def checksum(line: str) -> int:
    """The TLE checksum of a line.

    The sum of its first 68 characters' digits, each minus sign counting 1, modulo 10.

    Parameters
    ----------
    line : str
        An element line (its 69th character, the checksum itself, is not counted).

    Returns
    -------
    int
        The checksum digit, 0 to 9.

    References
    ----------
    .. [1] Hoots, F. R., Roehrich, R. L. (1980). *Models for Propagation of NORAD Element Sets*,
       Spacetrack Report No. 3 (the element set's format).

    Examples
    --------
    >>> checksum("1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927")
    7
    """
    return sum(int(c) if c.isdigit() else c == "-" for c in line[: LINE_LENGTH - 1]) % 10


def _epoch_field(line1: str, path: Path) -> tuple[int, float]:
    """Year and day of year (1-based, with its fraction) of line 1's epoch, checked."""
    field = line1[18:32]
    try:
        two_digits, day = int(field[:2]), float(field[2:])
    except ValueError:
        two_digits, day = -1, float("nan")
    year = two_digits + (1900 if two_digits >= 57 else 2000)
    days = 366 if year % 4 == 0 and (year % 100 != 0 or year % 400 == 0) else 365
    if two_digits < 0 or not 1.0 <= day < days + 1:
        raise InputError(
            f"line 1's epoch {field.strip()!r} is not a year and day of the year (YYDDD.DDDDDDDD)",
            path=str(path),
            hint="copy the line again from its source",
        )
    return year, day


def tle_period_s(line1: str, line2: str) -> float:
    """The orbital period [s] of an element set: a day over its mean motion.

    Parameters
    ----------
    line1 : str
        Line 1 of the element set (not read; taken for symmetry with :func:`tle_epoch`).
    line2 : str
        Line 2; its columns 53-63 hold the mean motion [revolutions per day].

    Returns
    -------
    float
        ``86400 / mean motion`` [s].

    Raises
    ------
    InputError
        A mean motion that is not a positive number.

    Examples
    --------
    >>> round(tle_period_s("", "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537"), 1)
    5495.7
    """
    try:
        revolutions = float(line2[52:63])
    except ValueError:
        revolutions = 0.0
    if not revolutions > 0:
        raise InputError(
            f"line 2's mean motion {line2[52:63].strip()!r} is not a number of revolutions a day"
        )
    return 86400.0 / revolutions


def tle_epoch(line1: str, line2: str) -> Epoch:
    """The epoch of the element set (UTC).

    Parameters
    ----------
    line1, line2 : str
        The two element lines.

    Returns
    -------
    Epoch
        The instant the elements hold at, from line 1's year and day of year (two-digit years 57-99 are
        1957-1999).

    Raises
    ------
    InputError
        Lines that SGP4's reader does not parse.

    Examples
    --------
    >>> import sunwind as sw
    >>> l1 = "1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927"
    >>> l2 = "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537"
    >>> sw.orbit.tle_epoch(l1, l2).iso()
    '2008-09-20T12:25:40.104Z'
    """
    from sgp4.api import Satrec
    from sgp4.conveniences import sat_epoch_datetime

    try:
        return Epoch.of(sat_epoch_datetime(Satrec.twoline2rv(line1, line2)))
    except (ValueError, IndexError) as error:
        raise InputError(f"the TLE's epoch does not parse ({error})") from None


def tle_trajectory(path: str | Path, epoch: Epoch, time_s: NDArray[np.float64]) -> Trajectory:
    r"""The states at ``time_s`` [s] after ``epoch`` from the TLE in ``path``, GCRF.

    SGP4 gives position and velocity in TEME; :func:`teme_to_gcrf` turns them into GCRF.

    Parameters
    ----------
    path : str or Path
        The TLE file, read by :func:`read_tle`.
    epoch : Epoch
        Time zero of the run (need not be the elements' epoch; SGP4's error grows away from it).
    time_s : ndarray of float64, shape (n,)
        Seconds after ``epoch``.

    Returns
    -------
    Trajectory
        Positions [m] and velocities [m/s] in GCRF, and a ``source`` naming the file and satellite.

    Raises
    ------
    InputError
        A file :func:`read_tle` refuses, elements SGP4 does not parse, or a step where SGP4 fails (a
        decayed orbit or elements out of range).

    References
    ----------
    .. [1] Vallado, D. A., Crawford, P., Hujsak, R., Kelso, T. S. (2006). "Revisiting Spacetrack Report
       #3". AIAA Paper 2006-6753 (SGP4 as the ``sgp4`` package implements it).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> l1 = "1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927"
    >>> l2 = "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537"
    >>> epoch = sw.orbit.tle_epoch(l1, l2)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "iss.tle"
    ...     _ = path.write_text(f"{l1}\n{l2}\n")
    ...     iss = sw.orbit.tle_trajectory(path, epoch, np.array([0.0, 60.0]))
    >>> iss.altitude_km.round(0), iss.source
    (array([342., 342.]), 'sgp4: TLE iss.tle (catalogue number 25544)')
    """
    from sgp4.api import Satrec

    line1, line2 = read_tle(path)
    try:
        satellite = Satrec.twoline2rv(line1, line2)
    except (ValueError, IndexError) as error:
        raise InputError(f"the TLE does not parse ({error})", path=str(path)) from None
    time_s = np.asarray(time_s, dtype=float)
    jd, fraction = epoch.ut1(time_s)  # SGP4 takes UTC Julian dates
    codes, r_km, v_km_s = satellite.sgp4_array(jd, fraction)
    failed = np.flatnonzero(codes)
    if failed.size:
        raise InputError(
            f"SGP4 fails {time_s[failed[0]]:g} s after the epoch (error code {codes[failed[0]]}: the "
            "orbit has decayed or the elements are out of range)",
            path=str(path),
            hint="shorten --duration, or use newer elements",
        )
    rotation = teme_to_gcrf(epoch, time_s)
    position = np.einsum("nij,nj->ni", rotation, r_km * 1e3)
    velocity = np.einsum("nij,nj->ni", rotation, v_km_s * 1e3)
    name = f"sgp4: TLE {Path(path).name} (catalogue number {satellite.satnum_str})"
    return Trajectory(epoch, time_s, position, velocity, name)


def teme_to_gcrf(epoch: Epoch, time_s: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrices taking TEME vectors to GCRF at ``time_s`` [s] after ``epoch``.

    ``r_GCRF = NPB^T R3(-Eq) r_TEME``: the equation of the equinoxes ``Eq`` (IAU 1994) takes TEME to the
    true equator and equinox of date, and the IAU 1976/1980 precession-nutation matrix ``NPB`` takes that
    to GCRF.

    Parameters
    ----------
    epoch : Epoch
        Time zero.
    time_s : ndarray of float64, shape (n,)
        Seconds after ``epoch``.

    Returns
    -------
    ndarray of float64, shape (n, 3, 3)
        One rotation per time: a TEME vector ``v`` becomes ``matrix @ v``.

    References
    ----------
    .. [1] Vallado, D. A., Crawford, P., Hujsak, R., Kelso, T. S. (2006). "Revisiting Spacetrack Report
       #3". AIAA Paper 2006-6753, sec. VI.
    .. [2] IAU SOFA Board. *IAU SOFA Software Collection*, through ERFA (``eqeq94``, ``pnm80``).

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.orbit.clock import Epoch
    >>> from sunwind.forces.orbit.tle import teme_to_gcrf
    >>> rotation = teme_to_gcrf(Epoch.of("2008-09-20T12:25:40Z"), np.array([0.0]))
    >>> rotation.shape, bool(np.allclose(rotation[0] @ rotation[0].T, np.eye(3)))
    ((1, 3, 3), True)
    >>> round(float(np.degrees(np.arccos(rotation[0, 0, 0]))), 2)  # about 8.7 years of precession
    0.12
    """
    tt1, tt2 = epoch.tt(time_s)
    equinoxes = erfa.eqeq94(tt1, tt2)
    c, s = np.cos(equinoxes), np.sin(equinoxes)
    to_true = np.zeros((len(c), 3, 3))
    to_true[:, 0, 0], to_true[:, 0, 1], to_true[:, 1, 0], to_true[:, 1, 1] = c, -s, s, c
    to_true[:, 2, 2] = 1.0
    npb = erfa.pnm80(tt1, tt2)
    return np.transpose(npb, (0, 2, 1)) @ to_true
