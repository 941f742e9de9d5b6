"""The points whose lines of sight are cast: names, positions and optional cones, from a CSV file or
arrays, checked once (METHOD.md "Lines of sight").

A point is a sensor, an antenna or a retroreflector array at ``position_m`` [m] in the body frame of
the mesh. It may have a cone: a unit ``boresight`` (body frame) and a ``half_angle_deg`` in (0, 180]
(a field of view, or a retroreflector's acceptance cone). A point without a cone sees the whole sky.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.columns import Columns, read_rows
from sunwind.geometry.errors import InputError

#: The columns a points file must have, in metres, body frame of the mesh.
REQUIRED = ("name", "x", "y", "z")
#: The optional cone columns: all four given, or none.
CONE = ("boresight_x", "boresight_y", "boresight_z", "half_angle_deg")
_EXAMPLE = "e.g. a header 'name,x,y,z,boresight_x,boresight_y,boresight_z,half_angle_deg'"


@dataclass(frozen=True, eq=False)
class SightPoints:
    """Named points in the body frame, each with an optional cone.

    Parameters
    ----------
    names : tuple of str
        One distinct name per point.
    position_m : (n, 3) float64
        Positions [m], body frame of the mesh.
    boresight : (n, 3) float64
        Unit cone axes, body frame; rows of NaN for points without a cone.
    half_angle_deg : (n,) float64
        Cone half angles [deg] in (0, 180]; NaN for points without a cone.
    source : str
        Where the points came from (a file, or ``"<arrays>"``).

    Examples
    --------
    >>> points = SightPoints.of(["star_tracker", "retro_a"], [[0.5, 0, 1], [0, 0.2, 1]],
    ...                         boresights=[[0, 0, 1], None], half_angles_deg=[30.0, None])
    >>> points.names, points.has_cone.tolist()
    (('star_tracker', 'retro_a'), [True, False])
    """

    names: tuple[str, ...]
    position_m: NDArray[np.float64]
    boresight: NDArray[np.float64]
    half_angle_deg: NDArray[np.float64]
    source: str = "<arrays>"

    @classmethod
    def of(
        cls,
        names: list[str],
        positions_m: NDArray[np.float64] | list,
        boresights: list | None = None,
        half_angles_deg: list | None = None,
    ) -> SightPoints:
        """Check and hold points given as arrays.

        Parameters
        ----------
        names : list of str
            Distinct names.
        positions_m : (n, 3) array_like of float
            Positions [m], body frame.
        boresights : list of (3,) array_like or None, optional
            Cone axes (any non-zero length); None (or a None entry) for no cone.
        half_angles_deg : list of float or None, optional
            Cone half angles [deg] in (0, 180], None where there is no cone.

        Returns
        -------
        SightPoints
            The checked points.

        Raises
        ------
        InputError
            Duplicate or empty names, non-finite positions, a zero boresight, a half angle outside
            (0, 180], or a boresight without a half angle (or the reverse).

        Examples
        --------
        >>> SightPoints.of(["a"], [[0, 0, 1]], boresights=[[0, 0, 0]], half_angles_deg=[10.0])
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: point 'a': the boresight has zero length; ...
        """
        names = [str(n) for n in names]
        n = len(names)
        position = np.asarray(positions_m, dtype=float).reshape(n, 3) if n else np.zeros((0, 3))
        axes = [None] * n if boresights is None else list(boresights)
        angles = [None] * n if half_angles_deg is None else list(half_angles_deg)
        if len(axes) != n or len(angles) != n:
            raise InputError(
                f"{n} names but {len(axes)} boresights and {len(angles)} half angles",
                hint="give one entry per point (None for a point without a cone)",
                parameters=("boresights", "half_angles_deg"),
            )
        boresight = np.full((n, 3), np.nan)
        half = np.full(n, np.nan)
        for k, name in enumerate(names):
            where = f"point {name!r}"
            check_name(name, names[:k], where)
            if not np.all(np.isfinite(position[k])):
                raise InputError(f"{where}: the position {position[k].tolist()} is not three finite numbers")
            boresight[k], half[k] = check_cone(axes[k], angles[k], where)
        return cls(tuple(names), position, boresight, half)

    @property
    def has_cone(self) -> NDArray[np.bool_]:
        """(n,) bool: whether each point has a cone."""
        return np.isfinite(self.half_angle_deg)

    def off_boresight_deg(self, directions: NDArray[np.float64]) -> NDArray[np.float64]:
        """Angle of each direction from its point's boresight [deg]; NaN for points without a cone.

        Parameters
        ----------
        directions : (n, m, 3) float64
            Unit directions from each point, body frame.

        Returns
        -------
        (n, m) float64
            The angles [deg].

        Examples
        --------
        >>> points = SightPoints.of(["a"], [[0, 0, 1]], boresights=[[0, 0, 1]], half_angles_deg=[30.0])
        >>> points.off_boresight_deg(np.array([[[0.0, 1.0, 0.0]]])).round(6).tolist()
        [[90.0]]
        """
        cosine = np.clip(np.einsum("nmk,nk->nm", directions, self.boresight), -1.0, 1.0)
        return np.degrees(np.arccos(cosine))

    def in_cone(self, directions: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Whether each direction lies in its point's cone (always, for a point without one).

        Parameters
        ----------
        directions : (n, m, 3) float64
            Unit directions from each point, body frame.

        Returns
        -------
        (n, m) bool
            True inside the cone (its edge included).

        Examples
        --------
        >>> points = SightPoints.of(["a"], [[0, 0, 1]], boresights=[[0, 0, 1]], half_angles_deg=[30.0])
        >>> points.in_cone(np.array([[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]])).tolist()
        [[True, False]]
        """
        cosine = np.einsum("nmk,nk->nm", directions, np.nan_to_num(self.boresight))
        limit = np.cos(np.radians(np.nan_to_num(self.half_angle_deg, nan=180.0)))
        return (cosine >= limit[:, None] - 1e-12) | ~self.has_cone[:, None]


def check_name(name: str, before: list[str], where: str) -> None:
    """Refuse an empty name or one already given.

    Parameters
    ----------
    name : str
        The point's name.
    before : list of str
        The names of the points before it.
    where : str
        Where it was given, for the message.

    Raises
    ------
    InputError
        An empty or repeated name.

    Examples
    --------
    >>> check_name("a", ["a"], "line 3")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: line 3: the name 'a' is given twice; give each point its own name
    """
    if not name.strip():
        raise InputError(f"{where}: the name is empty", hint="give each point a name")
    if name in before:
        raise InputError(f"{where}: the name {name!r} is given twice", hint="give each point its own name")


def check_cone(axis: object, half_angle_deg: object, where: str) -> tuple[NDArray[np.float64], float]:
    """Check one point's cone: a finite non-zero axis and a half angle in (0, 180], both or neither.

    Parameters
    ----------
    axis : (3,) array_like or None
        The boresight, any length; None for no cone.
    half_angle_deg : float or None
        The half angle [deg]; None for no cone.
    where : str
        The point, for the message.

    Returns
    -------
    boresight : (3,) float64
        The unit axis; NaN without a cone.
    half_angle_deg : float
        The half angle; NaN without a cone.

    Raises
    ------
    InputError
        One given without the other, a zero or non-finite axis, a half angle outside (0, 180].

    Examples
    --------
    >>> check_cone([0, 0, 2], 45, "point 'a'")
    (array([0., 0., 1.]), 45.0)
    >>> check_cone([0, 0, 1], 0, "point 'a'")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: point 'a': half_angle_deg 0 must be in (0, 180] degrees; ...
    """
    if axis is None and half_angle_deg is None:
        return np.full(3, np.nan), math.nan
    if axis is None or half_angle_deg is None:
        raise InputError(
            f"{where}: a cone needs both a boresight and half_angle_deg",
            hint="give both, or neither for a point that sees the whole sky",
        )
    vector = np.asarray(axis, dtype=float).reshape(-1)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)):
        raise InputError(f"{where}: the boresight is not three finite numbers", hint="e.g. 0 0 1")
    norm = float(np.linalg.norm(vector))
    if norm == 0.0:
        raise InputError(f"{where}: the boresight has zero length", hint="give the cone's axis, e.g. 0 0 1")
    angle = float(half_angle_deg)
    if not (math.isfinite(angle) and 0.0 < angle <= 180.0):
        raise InputError(
            f"{where}: half_angle_deg {angle:g} must be in (0, 180] degrees",
            hint="give the cone's half angle; 180 is the whole sky",
        )
    return vector / norm, angle


def read_points(path: str | Path) -> SightPoints:
    """Read a points file: a CSV with a header ``name,x,y,z`` and optionally the four cone columns.

    Positions are metres in the body frame of the mesh; ``boresight_x,boresight_y,boresight_z`` (any
    length, body frame) and ``half_angle_deg`` (0, 180] make a cone, all four given or all four left
    empty in a row. Blank lines and lines starting with ``#`` are skipped.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.

    Returns
    -------
    SightPoints
        The points, ``source`` the file.

    Raises
    ------
    InputError
        A missing file, a missing column, a cell that is not a number (with its line and column),
        a duplicate name, a zero boresight, a half angle outside (0, 180], or no points.

    Examples
    --------
    >>> from pathlib import Path
    >>> _ = Path("points.csv").write_text("name,x,y,z,boresight_x,boresight_y,boresight_z,half_angle_deg\\n"
    ...                                   "tracker,0.5,0,1,0,0,1,30\\nretro,0,0.2,1,,,,\\n")
    >>> points = read_points("points.csv")
    >>> points.names, points.half_angle_deg.tolist()
    (('tracker', 'retro'), [30.0, nan])
    >>> _ = Path("bad.csv").write_text("name,x,y\\na,1,2\\n")
    >>> read_points("bad.csv")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: bad.csv: no column 'z'; ...
    """
    path = Path(path)
    header, lines, rows = read_rows(path, "points file", _EXAMPLE)
    header = [name.lower() for name in header]
    for name in REQUIRED:
        if name not in header:
            raise InputError(f"no column {name!r}", path=str(path), hint=_EXAMPLE)
    cones = [name for name in CONE if name in header]
    if cones and len(cones) != len(CONE):
        missing = [name for name in CONE if name not in header]
        raise InputError(
            f"a cone needs the columns {', '.join(CONE)}; missing {', '.join(missing)}",
            path=str(path),
            hint="add them, or drop the cone columns",
        )
    columns = Columns(header, lines, rows, str(path))
    position = np.stack([columns.numbers(axis, "give metres, body frame of the mesh") for axis in "xyz"], 1)
    names = [columns.text(k, "name") for k in range(len(rows))]
    boresight, half = np.full((len(rows), 3), np.nan), np.full(len(rows), np.nan)
    given = np.array([[columns.text(k, name) != "" for name in cones] for k in range(len(rows))])
    try:  # the checks of a name and a cone say the line; the file is added here
        for k, name in enumerate(names):
            check_name(name, names[:k], f"line {lines[k]}")
            if given[k].any() and not given[k].all():
                empty = [c for c, on in zip(cones, given[k], strict=True) if not on]
                raise InputError(
                    f"line {lines[k]}: the cone cells {', '.join(empty)} are empty",
                    hint="give all four cone cells, or leave all four empty for no cone",
                )
        coned = np.flatnonzero(given.all(axis=1)) if cones else np.zeros(0, dtype=int)
        if len(coned):
            some = Columns(header, [lines[k] for k in coned], [rows[k] for k in coned], str(path))
            axes = some.block(CONE[:3])
            angles = some.numbers(CONE[3], "give the cone's half angle [deg]")
            for j, k in enumerate(coned):
                boresight[k], half[k] = check_cone(axes[j], angles[j], f"line {lines[k]} ({names[k]})")
    except InputError as error:
        raise InputError(error.message, path=str(path), hint=error.hint) from None
    return SightPoints(tuple(names), position, boresight, half, str(path))
