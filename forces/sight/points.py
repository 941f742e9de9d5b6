"""The points whose lines of sight are cast: names, positions and optional cones, from a CSV file or
arrays, checked once (METHOD.md "Lines of sight").

A point is a sensor, an antenna or a retroreflector array at ``position_m`` [m] in the body frame of
the mesh. It may have a cone: a unit ``boresight`` (body frame) and a ``half_angle_deg`` in (0, 180]
(a field of view, or a retroreflector's acceptance cone). A point without a cone sees the whole sky.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

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
    sunwind.geometry.errors.InputError: bad.csv: line 1: no column 'z'; ...
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("points file not found", path=str(path), hint="check the path and its spelling")
    text = path.read_text(encoding="utf-8-sig", errors="replace")
    rows = [
        (number, row)
        for number, row in enumerate(csv.reader(text.splitlines()), start=1)
        if row and any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#")
    ]
    if not rows:
        raise InputError("the points file is empty", path=str(path), hint=_EXAMPLE)
    header_line, header = rows[0]
    header = [cell.strip().lower() for cell in header]
    column = {name: k for k, name in enumerate(header)}
    for name in REQUIRED:
        if name not in column:
            raise InputError(f"line {header_line}: no column {name!r}", path=str(path), hint=_EXAMPLE)
    cones = [name for name in CONE if name in column]
    if cones and len(cones) != len(CONE):
        missing = [name for name in CONE if name not in column]
        raise InputError(
            f"line {header_line}: a cone needs the columns {', '.join(CONE)}; missing {', '.join(missing)}",
            path=str(path),
            hint="add them, or drop the cone columns",
        )
    names, positions, axes, angles = [], [], [], []
    for number, row in rows[1:]:
        cells = {name: (row[k].strip() if k < len(row) else "") for name, k in column.items()}
        where = f"line {number}"
        try:
            check_name(cells["name"], names, where)
            positions.append([_number(cells, axis, where) for axis in "xyz"])
            given = [cells[name] != "" for name in cones]
            if any(given) and not all(given):
                empty = [name for name, on in zip(cones, given, strict=True) if not on]
                raise InputError(
                    f"{where}: the cone cells {', '.join(empty)} are empty",
                    hint="give all four cone cells, or leave all four empty for no cone",
                )
            axis = [_number(cells, n, where) for n in CONE[:3]] if cones and all(given) else None
            angle = _number(cells, CONE[3], where) if axis is not None else None
            axis, angle = check_cone(axis, angle, f"{where} ({cells['name']})")
        except InputError as error:
            raise InputError(error.message, path=str(path), hint=error.hint) from None
        names.append(cells["name"])
        axes.append(axis)
        angles.append(angle)
    if not names:
        raise InputError("the points file has a header but no points", path=str(path), hint=_EXAMPLE)
    return SightPoints(tuple(names), np.array(positions), np.array(axes), np.array(angles), str(path))


def _number(cells: dict[str, str], name: str, where: str) -> float:
    """The number in column ``name``, or an error naming its line and column."""
    try:
        value = float(cells[name])
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        shown = cells[name] or "an empty cell"
        raise InputError(
            f"{where}, column {name!r}: {shown!r} is not a finite number",
            hint="give metres for x, y, z, a direction for the boresight, degrees for half_angle_deg",
        )
    return value
