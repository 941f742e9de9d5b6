"""Attitude sets of a sweep: body-frame Sun and flow directions on an az/el grid or from a CSV list.

Conventions (METHOD.md "Frames, units and signs"): directions are unit vectors in the body frame; the
Sun vector points from the spacecraft to the Sun, the flow vector ``u = v_rel / |v_rel|`` along the
spacecraft's velocity relative to the atmosphere; azimuth ``az = atan2(y, x)`` from +x toward +y,
elevation ``el = asin(z)``.

**Grid.** Azimuth from -180 to 180 deg and elevation from -90 to 90 deg, both ends present, in steps
that divide 180 deg: the layout simulators' tables use (SPAD, for one). Its 73 x 37 = 2701 nodes at
5 deg hold fewer distinct directions (every azimuth at a pole is the pole, az -180 is az 180); each
distinct direction is evaluated once and copied to the nodes that share it.

**List.** A CSV file with a header row naming its columns: ``sun_x, sun_y, sun_z`` and/or
``flow_x, flow_y, flow_z`` (any non-zero length; normalised). With quaternion columns
``qw, qx, qy, qz`` (scalar first; the body frame's attitude relative to the inertial frame, so a
vector's body components are ``d_B = R(q)^T d_I``) the direction columns are inertial and are turned
into the body frame row by row. One row is one attitude: Sun and flow tied as the user's orbit ties
them.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sunwind.geometry import memory
from sunwind.geometry.directions import azel_to_vectors
from sunwind.geometry.errors import InputError

#: Peak bytes per node of a grid's vectors and distinct directions while they are made (measured 129).
GRID_BYTES = 130

#: Columns of a direction in an attitude CSV file.
SUN_COLUMNS = ("sun_x", "sun_y", "sun_z")
FLOW_COLUMNS = ("flow_x", "flow_y", "flow_z")
QUATERNION_COLUMNS = ("qw", "qx", "qy", "qz")
#: How far from 1 a quaternion's length may be (rounding of printed digits); further is refused.
QUATERNION_NORM_TOLERANCE = 1e-3


@dataclass(frozen=True)
class DirectionGrid:
    """The regular azimuth/elevation grid of one direction (Sun or flow) [deg].

    Attributes
    ----------
    step_deg : float
        Step of both angles [deg]; it divides 180 deg (:func:`direction_grid` checks it).

    Examples
    --------
    >>> grid = DirectionGrid(45.0)
    >>> grid.nodes, grid.vectors.shape, len(grid.distinct[0])  # the poles and az +-180 are shared
    (45, (9, 5, 3), 26)
    >>> grid.elevation_deg.tolist()
    [-90.0, -45.0, 0.0, 45.0, 90.0]
    """

    step_deg: float

    @property
    def nodes(self) -> int:
        """Number of grid nodes, ``n_az * n_el``, without making the grid."""
        n = round(180.0 / self.step_deg)
        return (2 * n + 1) * (n + 1)

    @cached_property
    def azimuth_deg(self) -> NDArray[np.float64]:
        """Azimuths -180 to 180 inclusive, (n_az,)."""
        return self._axis(180.0)

    @cached_property
    def elevation_deg(self) -> NDArray[np.float64]:
        """Elevations -90 to 90 inclusive, (n_el,)."""
        return self._axis(90.0)

    def _axis(self, half_range: float) -> NDArray[np.float64]:
        count = round(2 * half_range / self.step_deg)
        return np.linspace(-half_range, half_range, count + 1)

    @cached_property
    def vectors(self) -> NDArray[np.float64]:
        """Unit vector of every node, (n_az, n_el, 3); shared directions have the same bits."""
        return azel_to_vectors(self.azimuth_deg[:, None], self.elevation_deg[None, :])

    @cached_property
    def distinct(self) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """The distinct directions (k, 3) in node order and, for each node (n_az * n_el,), its index
        among them."""
        flat = self.vectors.reshape(-1, 3)
        _, first, inverse = np.unique(flat, axis=0, return_index=True, return_inverse=True)
        order = np.argsort(first)  # keep node order: the sweep runs the grid as a user reads it
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        return flat[first[order]], rank[inverse.reshape(-1)]


def direction_grid(step_deg: float, name: str = "step_deg") -> DirectionGrid:
    """A :class:`DirectionGrid` of ``step_deg``, checked.

    Raises
    ------
    InputError
        A step that is not positive or does not divide 180 deg.

    Parameters
    ----------
    step_deg : float
        Step of azimuth and elevation [deg].
    name : str, optional
        The parameter the error message names.

    Returns
    -------
    DirectionGrid
        The grid.

    Examples
    --------
    >>> direction_grid(45.0).azimuth_deg.tolist()
    [-180.0, -135.0, -90.0, -45.0, 0.0, 45.0, 90.0, 135.0, 180.0]
    >>> direction_grid(7.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: step_deg 7 deg does not divide ...
    """
    if not math.isfinite(step_deg) or step_deg <= 0 or step_deg > 90:
        raise InputError(
            f"{name} {step_deg} deg must be a positive angle of at most 90 deg", parameters=(name,)
        )
    count = round(180.0 / step_deg)
    if abs(count * step_deg - 180.0) > 1e-9 * 180.0:
        raise InputError(
            f"{name} {step_deg:g} deg does not divide the azimuth and elevation ranges (-180..180, -90..90)",
            hint=f"{step_advice(step_deg)} (SPAD files: whole degrees)",
            parameters=(name,),
        )
    grid = DirectionGrid(180.0 / count)
    nodes = grid.nodes
    memory.require(GRID_BYTES * nodes, f"{memory.count(nodes)} grid nodes", f"raise {name}", (name,))
    return grid


def step_advice(step_deg: float, whole_degrees: bool = False) -> str:
    """Suggest the grid steps [deg] nearest ``step_deg`` that a sweep grid takes, as a hint.

    Steps are divisors of 180 deg in half degrees (with ``whole_degrees``, as SPAD files need, whole
    degrees); every check of a grid step gives this advice.

    Parameters
    ----------
    step_deg : float
        The step asked for [deg].
    whole_degrees : bool, optional
        Suggest whole degrees only.

    Returns
    -------
    str
        ``"use a step that divides 180 deg, e.g. ..."``.

    Examples
    --------
    >>> step_advice(7.0)
    'use a step that divides 180 deg, e.g. 5, 6, 7.5, 9'
    >>> step_advice(7.0, whole_degrees=True)
    'use a whole number of degrees that divides 180 deg, e.g. 5, 6, 9, 10'
    """
    unit = 1.0 if whole_degrees else 0.5
    steps = [180 / n for n in range(2, 361) if (180 / n / unit).is_integer()]
    near = sorted(steps, key=lambda s: abs(s - step_deg) if math.isfinite(step_deg) else abs(s - 10))[:4]
    kind = "a whole number of degrees" if whole_degrees else "a step"
    return f"use {kind} that divides 180 deg, e.g. {', '.join(f'{s:g}' for s in sorted(near))}"


@dataclass(frozen=True, eq=False)
class AttitudeList:
    r"""Attitudes read from a CSV file, one per row; body-frame unit vectors.

    Attributes
    ----------
    sun_vectors, flow_vectors : (n, 3) float64 or None
        Sun and flow directions of every row, where the file gives them.
    quaternions : (n, 4) float64 or None
        The rows' attitude quaternions ``(w, x, y, z)`` when the file gives them.
    source : str
        The file.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = os.path.join(folder, "attitudes.csv")
    ...     with open(path, "w") as file:
    ...         _ = file.write("sun_x,sun_y,sun_z\n0,0,2\n1,0,0\n")
    ...     attitudes = read_attitude_csv(path)
    >>> attitudes.directions("srp").tolist(), attitudes.flow_vectors
    ([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], None)
    """

    sun_vectors: NDArray[np.float64] | None
    flow_vectors: NDArray[np.float64] | None
    quaternions: NDArray[np.float64] | None
    source: str

    def __len__(self) -> int:
        present = self.sun_vectors if self.sun_vectors is not None else self.flow_vectors
        return len(present)

    def directions(self, kind: str) -> NDArray[np.float64]:
        """The Sun (``kind`` "srp") or flow ("drag") directions of every row.

        Raises
        ------
        InputError
            The file has no columns for them.
        """
        directions = self.sun_vectors if kind == "srp" else self.flow_vectors
        if directions is None:
            column = ", ".join(SUN_COLUMNS if kind == "srp" else FLOW_COLUMNS)
            raise InputError(f"the attitude list has no {column} columns for {kind}", path=self.source)
        return directions


def read_attitude_csv(path: str | Path) -> AttitudeList:
    r"""Read an attitude list (see the module notes for its columns).

    Raises
    ------
    InputError
        Missing or unreadable file (a UTF-8 byte-order mark is fine), a column name that is unknown or
        given twice, no direction columns, a column set given in part, a value that is not a finite
        number, a zero direction or quaternion.

    Parameters
    ----------
    path : str or Path
        The CSV file.

    Returns
    -------
    AttitudeList
        Body-frame unit vectors of every row.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = os.path.join(folder, "attitudes.csv")
    ...     with open(path, "w") as file:
    ...         _ = file.write("sun_x,sun_y,sun_z\n0,0,2\n1,0,0\n")
    ...     attitudes = read_attitude_csv(path)
    >>> attitudes.sun_vectors.tolist()  # normalised
    [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
    """
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as handle:  # -sig: a byte-order mark is skipped
            rows = [row for row in csv.reader(handle) if row and not row[0].lstrip().startswith("#")]
    except OSError as error:
        raise InputError(f"cannot read the attitude list: {error.strerror}", path=path) from None
    except (UnicodeDecodeError, csv.Error) as error:
        raise InputError(f"the attitude list is not UTF-8 CSV text ({error})", path=path) from None
    if len(rows) < 2:
        raise InputError("the attitude list needs a header row and at least one attitude", path=path)
    header = _header(rows[0], path)
    table = _numbers(rows[1:], len(header), path)
    columns = {name: table[:, k] for k, name in enumerate(header)}
    sun = _vectors(columns, SUN_COLUMNS, path)
    flow = _vectors(columns, FLOW_COLUMNS, path)
    if sun is None and flow is None:
        raise InputError(
            "the attitude list has no direction columns",
            path=path,
            hint=f"name them {', '.join(SUN_COLUMNS)} and/or {', '.join(FLOW_COLUMNS)} in the header row",
        )
    quaternions = _columns(columns, QUATERNION_COLUMNS, path)
    if quaternions is not None:
        norms = np.linalg.norm(quaternions, axis=1)
        off = np.abs(norms - 1.0)
        if np.any(off > QUATERNION_NORM_TOLERANCE):
            row = int(np.argmax(off))
            raise InputError(
                f"row {row + 2}: the quaternion has length {norms[row]:.6g}, not 1",
                path=path,
                hint="give unit quaternions, scalar first (qw, qx, qy, qz); a length off 1 by more than "
                f"{QUATERNION_NORM_TOLERANCE:g} is a wrong column or convention, not rounding",
            )
        body_from_inertial = Rotation.from_quat(quaternions[:, [1, 2, 3, 0]]).inv()
        sun = None if sun is None else body_from_inertial.apply(sun)
        flow = None if flow is None else body_from_inertial.apply(flow)
        quaternions = quaternions / norms[:, None]
    return AttitudeList(sun, flow, quaternions, str(path))


def _header(row: list[str], path: Path) -> list[str]:
    """The column names of the header row (trimmed, lower case), each one known and given once."""
    header = [name.strip().lower() for name in row]
    known = (*SUN_COLUMNS, *FLOW_COLUMNS, *QUATERNION_COLUMNS)
    expected = (
        f"{','.join(SUN_COLUMNS)} and/or {','.join(FLOW_COLUMNS)}, optionally {','.join(QUATERNION_COLUMNS)}"
    )
    for k, name in enumerate(header):
        if name in header[:k]:
            raise InputError(
                f"column {name!r} is given twice in the header",
                path=path,
                hint=f"the header names {expected}",
            )
        if name not in known:
            raise InputError(
                f"unexpected column {name!r} in the header (column {k + 1})",
                path=path,
                hint=f"the header names {expected}, each once",
            )
    return header


def _numbers(rows: list[list[str]], width: int, path: Path) -> NDArray[np.float64]:
    """The data rows as a float array (n, width)."""
    values = np.empty((len(rows), width))
    for r, row in enumerate(rows):
        if len(row) != width:
            raise InputError(f"row {r + 2} has {len(row)} values, the header {width}", path=path)
        try:
            values[r] = [float(x) for x in row]
        except ValueError:
            raise InputError(f"row {r + 2}: {','.join(row)} is not all numbers", path=path) from None
    if not np.isfinite(values).all():
        row = int(np.flatnonzero(~np.isfinite(values).all(axis=1))[0]) + 2
        raise InputError(f"row {row} holds a NaN or infinite value", path=path)
    return values


def _columns(columns: dict, names: tuple[str, ...], path: Path) -> NDArray[np.float64] | None:
    """The named columns side by side, None when none of them is there."""
    present = [name in columns for name in names]
    if not any(present):
        return None
    if not all(present):
        missing = [name for name in names if name not in columns]
        raise InputError(
            f"the attitude list lacks column {', '.join(missing)}",
            path=path,
            hint=f"give all of {','.join(names)} in the header row",
        )
    return np.column_stack([columns[name] for name in names])


def _vectors(columns: dict, names: tuple[str, ...], path: Path) -> NDArray[np.float64] | None:
    """Unit vectors from three named columns, None when absent."""
    vectors = _columns(columns, names, path)
    if vectors is None:
        return None
    lengths = np.linalg.norm(vectors, axis=1)
    if np.any(lengths == 0):
        row = int(np.argmin(lengths)) + 2
        raise InputError(f"row {row}: the {names[0][:-2]} direction is zero", path=path)
    return vectors / lengths[:, None]
