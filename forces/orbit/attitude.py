"""Attitude laws: the rotation from the body frame to GCRF at every step, ``v_eci = R v_body``.

===================== =====================================================================================
``nadir``             the LVLH frame: body +z to the Earth's centre, +y along the negative orbit normal
                      ``-(r x v)``, +x = y x z (along the velocity on a circular orbit), as the sample's
                      body frame
``lvlh:P,Y,R``        LVLH turned by pitch ``P`` about y, then yaw ``Y`` about the new z, then roll ``R``
                      about the new x [deg] (intrinsic y-z-x): ``R = R_lvlh Ry(P) Rz(Y) Rx(R)``
``sun[:A,B]``         body axis ``A`` (default +z) to the Sun, body axis ``B`` (default +x) as close to the
                      orbit normal ``r x v`` as it can be
``inertial:W,X,Y,Z``  a fixed quaternion, scalar first, body to GCRF (``v_eci = q v_body q*``)
``thrust-sun:X,Y,Z``  body axis ``A`` (default +x) along the GCRF direction ``X, Y, Z`` (a thrust axis),
 ``[:A,B]``           body axis ``B`` (default +z, the array normal) as close to the Sun as it can be
``csv:FILE``          time-tagged quaternions (columns ``time`` ISO 8601 UTC or ``time_s`` from the
                      epoch, then ``qw, qx, qy, qz``: scalar first, body to GCRF), interpolated by SLERP
                      or by a cubic Hermite spline on the quaternion (``interpolation``)
===================== =====================================================================================

Axes are written ``+x``, ``-y``, ... A secondary direction that lines up with the primary (the Sun on
the thrust axis) leaves the roll about the primary free: it is then held at the previous step's.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation, Slerp

from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.geometry.errors import InputError

#: Attitude law names.
LAWS = ("nadir", "lvlh", "sun", "inertial", "thrust-sun", "csv")
#: Interpolations of a quaternion file.
INTERPOLATIONS = ("slerp", "hermite")
#: Largest |1 - |q|| a quaternion file may hold before it is refused as not unit quaternions.
UNIT_TOLERANCE = 1e-3
_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class AttitudeLaw:
    """An attitude law as given (``text``) and parsed (``kind``, ``values``, ``axes``, ``path``).

    Made by :meth:`AttitudeLaw.parse` from the text of the module's table (``nadir``, ``lvlh:P,Y,R``,
    ``sun[:A,B]``, ``inertial:W,X,Y,Z``, ``thrust-sun:X,Y,Z[:A,B]``, ``csv:FILE``).

    Parameters
    ----------
    text : str
        The law as written.
    kind : str
        One of ``LAWS``.
    values : tuple of float
        Pitch, yaw, roll [deg] for ``lvlh``; the quaternion (scalar first) for ``inertial``; the thrust
        direction (GCRF) for ``thrust-sun``; else empty.
    axes : (ndarray, ndarray) or None
        The primary and secondary body axes, shape (3,) each, for ``sun`` and ``thrust-sun``.
    path : str or None
        The quaternion file of ``csv``.
    interpolation : {"slerp", "hermite"}
        How a quaternion file is interpolated between its rows.

    Examples
    --------
    >>> import sunwind as sw
    >>> law = sw.orbit.AttitudeLaw.parse("lvlh:10,0,0")
    >>> law.kind, law.values
    ('lvlh', (10.0, 0.0, 0.0))
    >>> sw.orbit.AttitudeLaw.parse("sun:+x,-y").axes
    (array([1., 0., 0.]), array([ 0., -1.,  0.]))
    """

    text: str
    kind: str
    values: tuple[float, ...] = ()
    axes: tuple[NDArray, NDArray] | None = None
    path: str | None = None
    interpolation: str = "slerp"

    @classmethod
    def parse(cls, text: str, interpolation: str = "slerp") -> AttitudeLaw:
        """The law of ``text`` (see the module's table).

        Parameters
        ----------
        text : str
            ``nadir``, ``lvlh:P,Y,R``, ``sun[:A,B]``, ``inertial:W,X,Y,Z``, ``thrust-sun:X,Y,Z[:A,B]`` or
            ``csv:FILE``; the law's name is case-blind.
        interpolation : {"slerp", "hermite"}
            How a ``csv`` file's quaternions are interpolated.

        Returns
        -------
        AttitudeLaw
            The parsed law (a ``csv`` file is read only when flown).

        Raises
        ------
        InputError
            An unknown law or interpolation, the wrong count of numbers, a quaternion not of unit length,
            ``lvlh`` angles beyond 360 deg, a zero thrust direction, or axes that are not two different body
            axes.

        Examples
        --------
        >>> from sunwind.forces.orbit.attitude import AttitudeLaw
        >>> AttitudeLaw.parse("thrust-sun:1,0,0").axes
        (array([1., 0., 0.]), array([0., 0., 1.]))
        >>> AttitudeLaw.parse("inertial:1,1,0,0")
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: the inertial quaternion 1,1,0,0 is not of unit length...
        """
        if interpolation not in INTERPOLATIONS:
            raise InputError(
                f"interpolation {interpolation!r} is not one of {', '.join(INTERPOLATIONS)}",
                parameters=("interpolation",),
            )
        kind, _, rest = text.strip().partition(":")
        kind = kind.lower()
        if kind not in LAWS:
            raise InputError(
                f"attitude law {kind!r} is not one of {', '.join(LAWS)}",
                hint=f"to fly the attitudes in the file {text.strip()}, give csv:{text.strip()}"
                if Path(text.strip()).is_file()
                else "e.g. nadir, lvlh:10,0,0, sun:+x,-y, inertial:1,0,0,0, thrust-sun:1,0,0, csv:FILE",
                parameters=("attitude",),
            )
        if kind == "csv":
            if not rest:
                raise InputError("csv needs a file: csv:FILE", parameters=("attitude",))
            return cls(text, kind, path=rest, interpolation=interpolation)
        numbers, _, axes = rest.partition(":") if kind == "thrust-sun" else (rest, "", rest)
        if kind == "nadir":
            if rest:
                raise InputError(f"nadir takes no values, not {rest!r}", parameters=("attitude",))
            return cls(text, kind)
        if kind == "sun":
            return cls(text, kind, axes=_axis_pair(axes, ("+z", "+x")))
        count = {"lvlh": 3, "inertial": 4, "thrust-sun": 3}[kind]
        values = _numbers(numbers, count, kind)
        if kind == "inertial" and abs(math.hypot(*values) - 1) > UNIT_TOLERANCE:  # as in an attitude file
            raise InputError(
                f"the inertial quaternion {','.join(f'{v:g}' for v in values)} is not of unit length "
                f"(|q| = {math.hypot(*values):.6g})",
                hint="give qw, qx, qy, qz of unit length, scalar first, body to GCRF (e.g. inertial:1,0,0,0)",
                parameters=("attitude",),
            )
        if kind == "lvlh" and max(abs(v) for v in values) > 360:
            raise InputError(
                f"lvlh angles {','.join(f'{v:g}' for v in values)} must lie within [-360, 360] deg",
                hint="give pitch, yaw, roll in degrees, e.g. lvlh:10,0,0",
                parameters=("attitude",),
            )
        if kind == "thrust-sun":
            if math.hypot(*values) == 0:
                raise InputError("the thrust direction is zero", parameters=("attitude",))
            return cls(text, kind, values, axes=_axis_pair(axes, ("+x", "+z")))
        return cls(text, kind, values)

    def body_to_eci(self, trajectory: Trajectory, sun_m: NDArray[np.float64]) -> NDArray[np.float64]:
        """Rotation matrices, body to GCRF, at the trajectory's steps.

        For every law but ``csv``, whose file :func:`quaternion_file_attitude` reads.

        Parameters
        ----------
        trajectory : Trajectory
            The spacecraft's states, n steps.
        sun_m : ndarray of float64, shape (n, 3)
            The Sun's geocentric position at the steps [m], GCRF.

        Returns
        -------
        ndarray of float64, shape (n, 3, 3)
            ``R`` with ``v_eci = R v_body``.

        Examples
        --------
        With ``sun:+x,-y`` the body's +x points at the Sun (seen from the spacecraft):

        >>> import numpy as np
        >>> import sunwind as sw
        >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
        >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
        >>> sun = sw.orbit.sun_position(epoch, path.time_s)
        >>> rotation = sw.orbit.AttitudeLaw.parse("sun:+x,-y").body_to_eci(path, sun)
        >>> to_sun = sun - path.position_m
        >>> to_sun /= np.linalg.norm(to_sun, axis=1, keepdims=True)
        >>> rotation.shape, bool(np.allclose(rotation[:, :, 0], to_sun))
        ((2, 3, 3), True)
        """
        if self.kind == "csv":
            raise InputError(
                f"attitude csv:{self.path} is read from its file, not computed",
                hint="use quaternion_file_attitude(law, epoch, time_s) (fly does)",
                parameters=("attitude",),
            )
        r, v = trajectory.position_m, trajectory.velocity_m_s
        n = len(r)
        if self.kind == "nadir":
            return lvlh(r, v)
        if self.kind == "lvlh":
            pitch, yaw, roll = self.values
            offset = Rotation.from_euler("YZX", [pitch, yaw, roll], degrees=True).as_matrix()
            return lvlh(r, v) @ offset
        if self.kind == "inertial":
            return np.tile(quaternion_matrix(np.array(self.values))[0], (n, 1, 1))
        primary, secondary = self.axes
        if self.kind == "sun":
            return two_axis(primary, sun_m - r, secondary, np.cross(r, v))
        thrust = np.tile(np.array(self.values), (n, 1))
        return two_axis(primary, thrust, secondary, sun_m - r)

    def describe(self) -> str:
        """The law in words, for the output.

        Returns
        -------
        str
            The law's text, with the interpolation for a ``csv`` law.

        Examples
        --------
        >>> from sunwind.forces.orbit.attitude import AttitudeLaw
        >>> AttitudeLaw.parse("csv:turn.csv", "hermite").describe()
        'csv:turn.csv (hermite)'
        """
        extra = f" ({self.interpolation})" if self.kind == "csv" else ""
        return self.text + extra


def quaternion_file_attitude(
    law: AttitudeLaw, epoch: Epoch, time_s: NDArray[np.float64]
) -> NDArray[np.float64]:
    r"""Rotation matrices of a ``csv:FILE`` law at ``time_s`` [s] after ``epoch``.

    Parameters
    ----------
    law : AttitudeLaw
        A ``csv`` law: its file and interpolation (``slerp`` or ``hermite``).
    epoch : Epoch
        Time zero of the run.
    time_s : ndarray of float64, shape (n,)
        Seconds after ``epoch``, within the file's times.

    Returns
    -------
    ndarray of float64, shape (n, 3, 3)
        Body to GCRF, ``v_eci = R v_body``.

    Raises
    ------
    InputError
        A file :func:`read_quaternions` refuses, or a step outside the file's times.

    References
    ----------
    .. [1] Shoemake, K. (1985). "Animating rotation with quaternion curves". *Computer Graphics
       (Proceedings of SIGGRAPH '85)* 19(3), 245-254 (SLERP).

    Examples
    --------
    Halfway through a quarter turn about z, body +x points 45 deg from GCRF +x:

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.attitude import AttitudeLaw, quaternion_file_attitude, read_quaternions
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = pathlib.Path(folder.name) / "turn.csv"  # a quarter turn about z in a minute
    >>> _ = path.write_text("time_s,qw,qx,qy,qz\n0,1,0,0,0\n60,0.70710678,0,0,0.70710678\n")
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> law = AttitudeLaw.parse(f"csv:{path}")
    >>> rotation = quaternion_file_attitude(law, epoch, np.array([0.0, 30.0]))
    >>> (rotation[1] @ [1.0, 0.0, 0.0]).round(4)
    array([0.7071, 0.7071, 0.    ])
    >>> folder.cleanup()
    """
    times, quaternions = read_quaternions(Path(law.path), epoch)
    time_s = np.asarray(time_s, dtype=float)
    outside = (time_s < times[0] - 1e-9) | (time_s > times[-1] + 1e-9)
    if np.any(outside):
        raise InputError(
            f"the run reaches {time_s[outside][0]:g} s after the epoch, outside the attitude file "
            f"({times[0]:g} to {times[-1]:g} s)",
            path=law.path,
            hint="shorten --duration or cover the run with the file",
        )
    t = np.clip(time_s, times[0], times[-1])
    if law.interpolation == "slerp":
        scalar_last = np.roll(quaternions, -1, axis=1)
        return Slerp(times, Rotation.from_quat(scalar_last))(t).as_matrix()
    return quaternion_matrix(hermite_quaternions(times, quaternions, t))


def read_quaternions(path: Path, epoch: Epoch) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    r"""The times and unit quaternions of an attitude file.

    Parameters
    ----------
    path : Path
        A CSV file with columns ``time`` (ISO 8601 UTC) or ``time_s`` (seconds after ``epoch``) and
        ``qw, qx, qy, qz`` (scalar first, body to GCRF); lines starting ``#`` are skipped.
    epoch : Epoch
        Time zero of the run.

    Returns
    -------
    time_s : ndarray of float64, shape (m,)
        The rows' times [s] after ``epoch``, increasing.
    quaternions : ndarray of float64, shape (m, 4)
        Unit quaternions, scalar first, each on the same hemisphere as the one before (``q`` and ``-q``
        are one rotation; the sign is chosen for interpolation).

    Raises
    ------
    InputError
        An unreadable file, fewer than two rows, missing columns or values, times not increasing, or a
        quaternion whose length is more than ``UNIT_TOLERANCE`` from 1.

    Examples
    --------

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.attitude import AttitudeLaw, quaternion_file_attitude, read_quaternions
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = pathlib.Path(folder.name) / "turn.csv"  # a quarter turn about z in a minute
    >>> _ = path.write_text("time_s,qw,qx,qy,qz\n0,1,0,0,0\n60,0.70710678,0,0,0.70710678\n")
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> times, quaternions = read_quaternions(path, epoch)
    >>> times.tolist(), quaternions.round(4).tolist()
    ([0.0, 60.0], [[1.0, 0.0, 0.0, 0.0], [0.7071, 0.0, 0.0, 0.7071]])
    >>> folder.cleanup()
    """
    try:
        with path.open(newline="", encoding="utf-8-sig") as handle:  # a byte-order mark is no column
            rows = list(csv.DictReader(row for row in handle if not row.lstrip().startswith("#")))
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read the attitude file ({error})", path=str(path)) from None
    names = ("qw", "qx", "qy", "qz")
    if len(rows) < 2 or not set(names) <= set(rows[0]):
        raise InputError(
            "the attitude file needs two or more rows with columns time (or time_s), qw, qx, qy, qz",
            path=str(path),
            hint="quaternions scalar first (qw), body to GCRF",
        )
    try:
        q = np.array([[float(row[name]) for name in names] for row in rows])
        if "time_s" in rows[0]:
            times = np.array([float(row["time_s"]) for row in rows])
        else:
            times = np.array([(Epoch.of(row["time"]).utc - epoch.utc).total_seconds() for row in rows])
    except (KeyError, TypeError, ValueError):
        raise InputError(
            "the attitude file has a row without a number or time where one is due", path=str(path)
        ) from None
    if not np.all(np.isfinite(q)) or not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
        raise InputError("the attitude file's times must increase and its values be finite", path=str(path))
    norms = np.linalg.norm(q, axis=1)
    worst = int(np.argmax(np.abs(norms - 1)))
    if abs(norms[worst] - 1) > UNIT_TOLERANCE:
        raise InputError(
            f"row {worst + 1} of the attitude file is not a unit quaternion (|q| = {norms[worst]:.6g})",
            path=str(path),
            hint="give qw, qx, qy, qz of unit length, scalar first",
        )
    q /= norms[:, None]
    signs = np.sign(np.einsum("ij,ij->i", q[1:], q[:-1]))
    q[1:] *= np.cumprod(np.where(signs == 0, 1.0, signs))[:, None]
    return times, q


def hermite_quaternions(
    times: NDArray[np.float64], quaternions: NDArray[np.float64], t: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Unit quaternions at ``t`` from a cubic Hermite spline through the samples.

    The spline runs componentwise with Catmull-Rom tangents (centred differences, one-sided at the ends),
    then is normalised: the angular rate is continuous at the samples, where SLERP's jumps.

    Parameters
    ----------
    times : ndarray of float64, shape (m,)
        Sample times [s], increasing, m >= 2.
    quaternions : ndarray of float64, shape (m, 4)
        Unit quaternions at the samples, scalar first, on one hemisphere in turn.
    t : ndarray of float64, shape (n,)
        Times to interpolate at [s], within ``times``.

    Returns
    -------
    ndarray of float64, shape (n, 4)
        Unit quaternions, scalar first.

    References
    ----------
    .. [1] Catmull, E., Rom, R. (1974). "A class of local interpolating splines". In *Computer Aided
       Geometric Design*, 317-326. Academic Press.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.orbit.attitude import hermite_quaternions
    >>> half = np.sqrt(0.5)
    >>> samples = np.array([[1.0, 0.0, 0.0, 0.0], [half, 0.0, 0.0, half]])
    >>> hermite_quaternions(np.array([0.0, 60.0]), samples, np.array([30.0])).round(4)
    array([[0.9239, 0.    , 0.    , 0.3827]])
    """
    q = quaternions
    tangents = np.empty_like(q)
    tangents[1:-1] = (q[2:] - q[:-2]) / (times[2:] - times[:-2])[:, None]
    tangents[0] = (q[1] - q[0]) / (times[1] - times[0])
    tangents[-1] = (q[-1] - q[-2]) / (times[-1] - times[-2])
    k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
    h = times[k + 1] - times[k]
    s = ((t - times[k]) / h)[:, None]
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    out = h00 * q[k] + h10 * h[:, None] * tangents[k] + h01 * q[k + 1] + h11 * h[:, None] * tangents[k + 1]
    return out / np.linalg.norm(out, axis=1, keepdims=True)


def quaternion_matrix(q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation matrices of scalar-first quaternions, normalised here.

    Parameters
    ----------
    q : array_like of float, shape (n, 4) or (4,)
        Quaternions ``(w, x, y, z)``, scalar first; any non-zero length.

    Returns
    -------
    ndarray of float64, shape (n, 3, 3)
        The rotations ``v' = q v q*`` as matrices (n = 1 for a single quaternion).

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.orbit.attitude import quaternion_matrix
    >>> quaternion_matrix([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)]).round(6) + 0.0  # 90 deg about z
    array([[[ 0., -1.,  0.],
            [ 1.,  0.,  0.],
            [ 0.,  0.,  1.]]])
    """
    q = np.atleast_2d(q)
    return Rotation.from_quat(np.roll(q / np.linalg.norm(q, axis=1, keepdims=True), -1, axis=1)).as_matrix()


def lvlh(position_m: NDArray[np.float64], velocity_m_s: NDArray[np.float64]) -> NDArray[np.float64]:
    """The LVLH frame (columns x, y, z in GCRF): z to the Earth's centre, y along ``-(r x v)``.

    Parameters
    ----------
    position_m : ndarray of float64, shape (n, 3)
        Positions [m], GCRF.
    velocity_m_s : ndarray of float64, shape (n, 3)
        Velocities [m/s], GCRF.

    Returns
    -------
    ndarray of float64, shape (n, 3, 3)
        Rotations whose columns are the LVLH axes in GCRF (x = y x z, along the velocity on a circular
        orbit): LVLH (body, for ``nadir``) to GCRF.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.orbit.attitude import lvlh
    >>> lvlh(np.array([[7.0e6, 0.0, 0.0]]), np.array([[0.0, 7.5e3, 0.0]])) + 0.0
    array([[[ 0.,  0., -1.],
            [ 1.,  0.,  0.],
            [ 0., -1.,  0.]]])
    """
    z = -position_m / np.linalg.norm(position_m, axis=1, keepdims=True)
    h = np.cross(position_m, velocity_m_s)
    y = -h / np.linalg.norm(h, axis=1, keepdims=True)
    return np.stack([np.cross(y, z), y, z], axis=2)


def two_axis(
    primary: NDArray[np.float64],
    target: NDArray[np.float64],
    secondary: NDArray[np.float64],
    toward: NDArray[np.float64],
) -> NDArray[np.float64]:
    """The rotations that point one body axis and bring a second as near a direction as it can come.

    Body axis ``primary`` goes onto ``target`` and body axis ``secondary`` as close to ``toward`` as the
    first allows. Where ``toward`` lies along ``target`` the roll about it is free: it is held at the
    previous step's.

    Parameters
    ----------
    primary : ndarray of float64, shape (3,)
        The body axis to point.
    target : ndarray of float64, shape (n, 3)
        Where it points, GCRF (any length).
    secondary : ndarray of float64, shape (3,)
        A second body axis, not along ``primary``.
    toward : ndarray of float64, shape (n, 3)
        The direction it should come nearest, GCRF.

    Returns
    -------
    ndarray of float64, shape (n, 3, 3)
        Body to GCRF.

    Examples
    --------
    Body +z to GCRF +x, body +x as near GCRF +y as it can be:

    >>> import numpy as np
    >>> from sunwind.forces.orbit.attitude import two_axis
    >>> z, x = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    >>> two_axis(z, np.array([[2.0, 0.0, 0.0]]), x, np.array([[1.0, 1.0, 0.0]])) + 0.0
    array([[[0., 0., 1.],
            [1., 0., 0.],
            [0., 1., 0.]]])
    """
    body = _triad(primary[None, :], secondary[None, :])[0]
    t = target / np.linalg.norm(target, axis=1, keepdims=True)
    w = toward - np.einsum("ij,ij->i", toward, t)[:, None] * t
    size = np.linalg.norm(w, axis=1)
    free = size < 1e-9 * np.linalg.norm(toward, axis=1)
    for i in np.flatnonzero(free):  # rare: the secondary direction on the primary; hold the roll
        previous = w[i - 1] if i else np.cross(t[i], [1.0, 0.0, 0.0] if abs(t[i, 0]) < 0.9 else [0, 1.0, 0])
        w[i] = previous - (previous @ t[i]) * t[i]
        size[i] = np.linalg.norm(w[i])
    inertial = _triad(t, w / size[:, None])
    return inertial @ body.T


def _triad(first: NDArray, second: NDArray) -> NDArray[np.float64]:
    """Orthonormal frames (n, 3, 3), columns: ``first``, the part of ``second`` normal to it, their cross."""
    a = first / np.linalg.norm(first, axis=1, keepdims=True)
    b = second - np.einsum("ij,ij->i", second, a)[:, None] * a
    b /= np.linalg.norm(b, axis=1, keepdims=True)
    return np.stack([a, b, np.cross(a, b)], axis=2)


def _axis_pair(text: str, default: tuple[str, str]) -> tuple[NDArray, NDArray]:
    words = [w.strip().lower() for w in text.split(",")] if text.strip() else list(default)
    if len(words) != 2:
        raise InputError(f"axes {text!r} must be two body axes such as +z,+x", parameters=("attitude",))
    axes = []
    for word in words:
        sign, letter = (word[0], word[1:]) if word[:1] in "+-" else ("+", word)
        if letter not in _AXES:
            raise InputError(f"{word!r} is not a body axis (+x, -y, ...)", parameters=("attitude",))
        axis = np.zeros(3)
        axis[_AXES[letter]] = -1.0 if sign == "-" else 1.0
        axes.append(axis)
    if abs(axes[0] @ axes[1]) > 0.5:
        raise InputError(f"axes {text!r} must be two different body axes", parameters=("attitude",))
    return axes[0], axes[1]


def _numbers(text: str, count: int, kind: str) -> tuple[float, ...]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise InputError(
            f"{kind} needs {count} numbers separated by commas, not {text!r}", parameters=("attitude",)
        )
    return values
