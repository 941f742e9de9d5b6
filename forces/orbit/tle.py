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


def read_tle(path: str | Path) -> tuple[str, str]:
    """The two element lines of a TLE file (an optional name line before them is skipped)."""
    path = Path(path)
    try:
        lines = [line.rstrip() for line in path.read_text().splitlines() if line.strip()]
    except OSError as error:
        raise InputError(f"cannot read the TLE file ({error.strerror})", path=str(path)) from None
    ones = [i for i, line in enumerate(lines) if line.startswith("1 ")]
    if not ones or ones[0] + 1 >= len(lines) or not lines[ones[0] + 1].startswith("2 "):
        raise InputError(
            "no two-line element set: a line starting '1 ' followed by one starting '2 '",
            path=str(path),
            hint="give the two 69-character lines of a TLE (a name line before them is allowed)",
        )
    return lines[ones[0]], lines[ones[0] + 1]


def tle_epoch(line1: str, line2: str) -> Epoch:
    """The epoch of the element set (UTC)."""
    from sgp4.api import Satrec
    from sgp4.conveniences import sat_epoch_datetime

    return Epoch.of(sat_epoch_datetime(Satrec.twoline2rv(line1, line2)))


def tle_trajectory(path: str | Path, epoch: Epoch, time_s: NDArray[np.float64]) -> Trajectory:
    """States at ``time_s`` [s] after ``epoch`` from the TLE in ``path``, GCRF."""
    from sgp4.api import Satrec

    line1, line2 = read_tle(path)
    try:
        satellite = Satrec.twoline2rv(line1, line2)
    except (ValueError, IndexError) as error:
        raise InputError(f"the TLE does not parse ({error})", path=str(path)) from None
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
    return Trajectory(epoch, np.asarray(time_s, dtype=float), position, velocity, name)


def teme_to_gcrf(epoch: Epoch, time_s: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrices (n, 3, 3) taking TEME vectors to GCRF at ``time_s`` [s] after ``epoch``."""
    tt1, tt2 = epoch.tt(time_s)
    equinoxes = erfa.eqeq94(tt1, tt2)
    c, s = np.cos(equinoxes), np.sin(equinoxes)
    to_true = np.zeros((len(c), 3, 3))
    to_true[:, 0, 0], to_true[:, 0, 1], to_true[:, 1, 0], to_true[:, 1, 1] = c, -s, s, c
    to_true[:, 2, 2] = 1.0
    npb = erfa.pnm80(tt1, tt2)
    return np.transpose(npb, (0, 2, 1)) @ to_true
