"""Measured sensor fluxes, row by row, with the optional inertial directions that turn two body-frame
directions into an attitude (METHOD.md "Attitude from heat fluxes").

The file is CSV: ``time_s``, then one column per sensor part named as the part, holding the absorbed heat
flux in W/m^2 of that part's area; optionally ``sun_eci_x,y,z`` and ``nadir_eci_x,y,z`` (directions from
the spacecraft in any inertial frame, normalised here) for a quaternion, and ``velocity_eci_x,y,z`` as
well for pitch, yaw and roll in the orbital frame.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.columns import Columns, check_times, read_rows, unit_rows
from sunwind.geometry.errors import InputError

#: The optional groups of inertial columns, in their file names.
GROUPS = {
    "sun": ("sun_eci_x", "sun_eci_y", "sun_eci_z"),
    "nadir": ("nadir_eci_x", "nadir_eci_y", "nadir_eci_z"),
    "velocity": ("velocity_eci_x", "velocity_eci_y", "velocity_eci_z"),
}
#: What the file needs, for messages.
COLUMNS_HINT = (
    "time_s, then one column per sensor part (W/m^2), optionally sun_eci_*, nadir_eci_*, velocity_eci_*"
)


@dataclass(frozen=True)
class FluxRows:
    """Measured fluxes and, optionally, each row's inertial directions.

    Attributes
    ----------
    time_s : (n,) float64
        Row times [s], increasing.
    sensors : tuple of str
        The sensor parts, in column order.
    fluxes_W_m2 : (n, p) float64
        Absorbed flux of each sensor [W/m^2 of its area].
    sun_eci, nadir_eci, velocity_eci : (n, 3) float64 or None
        Unit directions to the Sun and the planet's centre and of the velocity, one inertial frame.
    source : str
        Where the rows came from, for messages.

    Examples
    --------
    >>> rows = FluxRows(np.array([0.0, 10.0]), ("a", "b"), np.array([[1.0, 2.0], [3.0, 4.0]]))
    >>> rows.selected(("b",)).fluxes_W_m2.tolist(), rows.inertial(0) is None
    ([[2.0], [4.0]], True)
    """

    time_s: NDArray[np.float64]
    sensors: tuple[str, ...]
    fluxes_W_m2: NDArray[np.float64]
    sun_eci: NDArray[np.float64] | None = None
    nadir_eci: NDArray[np.float64] | None = None
    velocity_eci: NDArray[np.float64] | None = None
    source: str = "<fluxes>"

    def __len__(self) -> int:
        """The number of rows."""
        return len(self.time_s)

    def __getitem__(self, rows: slice) -> FluxRows:
        """The rows of a slice (a chunk of a run), with their inertial directions.

        Parameters
        ----------
        rows : slice

        Returns
        -------
        FluxRows

        Examples
        --------
        >>> rows = FluxRows(np.array([0.0, 10.0, 20.0]), ("a",), np.ones((3, 1)))
        >>> len(rows), rows[1:].time_s.tolist()
        (3, [10.0, 20.0])
        """

        def cut(values: NDArray[np.float64] | None) -> NDArray[np.float64] | None:
            return None if values is None else values[rows]

        return replace(
            self,
            time_s=self.time_s[rows],
            fluxes_W_m2=self.fluxes_W_m2[rows],
            sun_eci=cut(self.sun_eci),
            nadir_eci=cut(self.nadir_eci),
            velocity_eci=cut(self.velocity_eci),
        )

    def inertial(self, k: int) -> tuple[NDArray, NDArray, NDArray | None] | None:
        """Row ``k``'s inertial (Sun, nadir, velocity or None), or None without them.

        Parameters
        ----------
        k : int

        Returns
        -------
        tuple or None

        Examples
        --------
        >>> up = np.array([[0.0, 0.0, 1.0]])
        >>> FluxRows(np.zeros(1), ("a",), np.ones((1, 1)), up, -up).inertial(0)[1] + 0.0
        array([ 0.,  0., -1.])
        """
        if self.sun_eci is None or self.nadir_eci is None:
            return None
        velocity = None if self.velocity_eci is None else self.velocity_eci[k]
        return self.sun_eci[k], self.nadir_eci[k], velocity

    def selected(self, patterns: tuple[str, ...]) -> FluxRows:
        """Only the sensors matching ``patterns`` (shell-style; each must match one).

        Parameters
        ----------
        patterns : tuple of str

        Returns
        -------
        FluxRows

        Raises
        ------
        InputError
            A pattern that matches no sensor column.

        Examples
        --------
        >>> rows = FluxRows(np.zeros(1), ("s1", "s2", "t"), np.ones((1, 3)))
        >>> rows.selected(("s*",)).sensors
        ('s1', 's2')
        """
        for pattern in patterns:
            if not fnmatch.filter(self.sensors, pattern):
                raise InputError(
                    f"--sensors {pattern!r} matches no sensor column",
                    path=self.source,
                    hint=f"the sensor columns are {', '.join(self.sensors)}",
                )
        keep = [
            k for k, name in enumerate(self.sensors) if any(fnmatch.fnmatchcase(name, p) for p in patterns)
        ]
        return replace(
            self, sensors=tuple(self.sensors[k] for k in keep), fluxes_W_m2=self.fluxes_W_m2[:, keep]
        )

    def reordered(self, sensors: tuple[str, ...]) -> FluxRows:
        """The same rows with the sensor columns in the order of ``sensors`` (the same names).

        Parameters
        ----------
        sensors : tuple of str

        Returns
        -------
        FluxRows

        Examples
        --------
        >>> FluxRows(np.zeros(1), ("a", "b"), np.array([[1.0, 2.0]])).reordered(("b", "a")).fluxes_W_m2
        array([[2., 1.]])
        """
        order = [self.sensors.index(name) for name in sensors]
        return replace(self, sensors=tuple(sensors), fluxes_W_m2=self.fluxes_W_m2[:, order])

    def check_parts(self, part_names: tuple[str, ...]) -> None:
        """Refuse a sensor column that names no part of the model, or fewer than two sensors.

        Parameters
        ----------
        part_names : tuple of str
            The model's parts.

        Raises
        ------
        InputError

        Examples
        --------
        >>> FluxRows(np.zeros(1), ("a", "b"), np.ones((1, 2))).check_parts(("a", "b", "c"))
        """
        unknown = [name for name in self.sensors if name not in part_names]
        if unknown:
            raise InputError(
                f"column {unknown[0]} is not a part of the model",
                path=self.source,
                hint=f"name each sensor column as a part: {', '.join(part_names)}",
            )
        if len(self.sensors) < 2:
            raise InputError(
                f"{len(self.sensors)} sensor column: the attitude needs at least two sensors (six are usual)",
                path=self.source,
                hint="add the other sensors' columns",
            )


def read_flux_rows(path: str | Path) -> FluxRows:
    """Read a fluxes file (module docstring), every cell checked.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    FluxRows

    Raises
    ------
    InputError
        A missing file, no rows, no ``time_s``, times that do not increase, a cell that is not a finite
        number (a measured flux may be negative: an offset's noise), a group of inertial columns given
        in part, the velocity without the nadir, or a zero direction; each names the file, the line
        and the column.

    Examples
    --------
    >>> import tempfile
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = Path(folder.name) / "fluxes.csv"
    >>> _ = path.write_text("time_s,sensor_px,sensor_mx\\n0,1200.5,85.0\\n10,1190.0,86.1\\n")
    >>> rows = read_flux_rows(path)
    >>> rows.sensors, rows.fluxes_W_m2[1].tolist()
    (('sensor_px', 'sensor_mx'), [1190.0, 86.1])
    >>> folder.cleanup()
    """
    where = str(path)
    header, lines, raw = read_rows(Path(path), "fluxes file", COLUMNS_HINT)
    columns = Columns(header, lines, raw, where)
    time = columns.numbers("time_s", "give each row's time in seconds")
    check_times(time, lines, where)
    grouped = {name for names in GROUPS.values() for name in names}
    sensors = tuple(name for name in header if name != "time_s" and name not in grouped)
    if not sensors:
        raise InputError("no sensor column", path=where, hint=COLUMNS_HINT)
    fluxes = np.stack([columns.numbers(name, "give the absorbed flux in W/m^2") for name in sensors], axis=1)
    vectors = {}
    for group, names in GROUPS.items():
        columns.whole(names, f"give all three of {', '.join(names)}")
        if names[0] in header:
            vectors[group] = unit_rows(
                columns.block(names), lines, where, f"{group}_eci_*", "give a direction"
            )
    if "velocity" in vectors and "nadir" not in vectors:
        raise InputError(
            "velocity_eci_* without nadir_eci_*", path=where, hint="give nadir_eci_* and sun_eci_* too"
        )
    if ("sun" in vectors) != ("nadir" in vectors):
        given, missing = ("sun", "nadir") if "sun" in vectors else ("nadir", "sun")
        raise InputError(
            f"{given}_eci_* without {missing}_eci_*: both are needed for the attitude",
            path=where,
            hint=f"give {missing}_eci_x, {missing}_eci_y, {missing}_eci_z, or drop {given}_eci_*",
        )
    return FluxRows(
        time, sensors, fluxes, vectors.get("sun"), vectors.get("nadir"), vectors.get("velocity"), where
    )
