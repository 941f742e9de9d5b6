"""Numeric CSV files with a header line: rows read with their file lines, columns read as checked numbers,
so that every bad cell is one error line naming the file, the line and the column."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError


def read_rows(path: Path, what: str, columns_hint: str) -> tuple[list[str], list[int], list[list[str]]]:
    """The header, the file line of each data row, and the rows' fields of a CSV file; lines starting
    ``#`` and blank lines are skipped.

    Parameters
    ----------
    path : Path
        The file.
    what : str
        What it holds, for messages ("telemetry").
    columns_hint : str
        The columns it needs, for the message when it has no row.

    Returns
    -------
    header : list of str
        Column names, stripped.
    lines : list of int
        The file line of each row.
    rows : list of list of str
        The rows' fields.

    Raises
    ------
    InputError
        A missing or unreadable file, no row, or a column named twice.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = Path(folder.name) / "t.csv"
    >>> _ = path.write_text("# a comment\\ntime_s,a\\n0,1.5\\n")
    >>> read_rows(path, "fluxes", "time_s and one column per sensor")
    (['time_s', 'a'], [3], [['0', '1.5']])
    >>> folder.cleanup()
    """
    try:
        with path.open(newline="", encoding="utf-8-sig") as handle:
            numbered = [(k + 1, line) for k, line in enumerate(handle) if not line.lstrip().startswith("#")]
    except FileNotFoundError:
        raise InputError("file not found", path=str(path), hint="check the path and its spelling") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read the {what} ({error})", path=str(path)) from None
    numbered = [(k, line) for k, line in numbered if line.strip()]
    if len(numbered) < 2:
        raise InputError(
            f"the {what} needs a header line and at least one row",
            path=str(path),
            hint=columns_hint,
        )
    parsed = list(csv.reader(line for _, line in numbered))
    header = [name.strip() for name in parsed[0]]
    repeated = sorted({name for name in header if header.count(name) > 1})
    if repeated:
        raise InputError(f"column {repeated[0]} appears twice", path=str(path), hint="keep one")
    return header, [k for k, _ in numbered[1:]], parsed[1:]


class Columns:
    """Columns of a CSV file's rows (:func:`read_rows`), read as numbers with messages naming the file,
    line and column.

    Parameters
    ----------
    header : list of str
    lines : list of int
    rows : list of list of str
        As :func:`read_rows` gives them.
    where : str
        The file, for messages.

    Examples
    --------
    >>> columns = Columns(["time_s", "a"], [2, 3], [["0", "1"], ["1", "x"]], "f.csv")
    >>> columns.numbers("time_s", "give times")
    array([0., 1.])
    >>> columns.numbers("a", "give a")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: f.csv: line 3: column a is 'x', not a finite number; ...
    """

    def __init__(self, header: list[str], lines: list[int], rows: list[list[str]], where: str) -> None:
        self.header, self.lines, self.rows, self.where = header, lines, rows, where

    def numbers(self, name: str, fix: str, low: float = -math.inf, high: float = math.inf) -> NDArray:
        """Column ``name`` as finite numbers in [``low``, ``high``]; ``fix`` ends the messages."""
        if name not in self.header:
            raise InputError(f"no column {name}", path=self.where, hint=f"add it: {fix}")
        column = self.header.index(name)
        out = np.empty(len(self.rows))
        for k in range(len(self.rows)):
            text = self._cell(k, column)
            try:
                value = float(text)
            except ValueError:
                value = math.nan
            if not math.isfinite(value) or not low <= value <= high:
                bounds = "" if math.isinf(low) else f" in [{low:g}, {high:g}]"
                raise InputError(
                    f"line {self.lines[k]}: column {name} is {text or 'empty'!r}, "
                    f"not a finite number{bounds}",
                    path=self.where,
                    hint=f"{fix}, or drop the row",
                )
            out[k] = value
        return out

    def text(self, row: int, name: str) -> str:
        """The stripped cell of column ``name`` in row ``row`` (empty past the row's end)."""
        return self._cell(row, self.header.index(name))

    def _cell(self, row: int, column: int) -> str:
        cells = self.rows[row]
        return cells[column].strip() if column < len(cells) else ""

    def block(self, names: tuple[str, ...]) -> NDArray:
        """Columns ``names`` side by side, (n, len(names))."""
        return np.stack([self.numbers(name, f"give {name}") for name in names], axis=1)

    def whole(self, names: tuple[str, ...], fix: str) -> None:
        """Refuse a group of columns given in part."""
        present = [name for name in names if name in self.header]
        if present and len(present) < len(names):
            missing = [name for name in names if name not in self.header]
            raise InputError(
                f"column {missing[0]} missing (the file has {present[0]})", path=self.where, hint=fix
            )


def check_times(time: NDArray, lines: list[int], where: str) -> None:
    """Refuse times that do not increase, naming the line.

    Parameters
    ----------
    time : (n,) float64
    lines : list of int
        The file line of each row.
    where : str
        The file.

    Raises
    ------
    InputError
        A time that repeats or comes before the previous row's.

    Examples
    --------
    >>> check_times(np.array([0.0, 1.0]), [2, 3], "f.csv")
    """
    steps = np.diff(time)
    bad = np.flatnonzero(steps <= 0)
    if len(bad):
        k = int(bad[0]) + 1
        how = "repeats" if steps[k - 1] == 0 else "comes before"
        raise InputError(
            f"line {lines[k]}: time_s {time[k]:g} {how} the previous row's {time[k - 1]:g}",
            path=where,
            hint="sort the rows by time_s and drop repeated rows",
        )


def unit_rows(vectors: NDArray, lines: list[int], where: str, shown: str, hint: str) -> NDArray:
    """Each row of ``vectors`` normalised; a zero row refused, naming its line.

    Parameters
    ----------
    vectors : (n, 3) float64
        Directions read from the file, any length.
    lines : list of int
        The file line of each row.
    where : str
        The file.
    shown : str
        What the columns hold, for the message ("the Sun direction sun_x, sun_y, sun_z").
    hint : str
        The fix.

    Returns
    -------
    (n, 3) float64
        Unit vectors.

    Raises
    ------
    InputError
        A zero row.

    Examples
    --------
    >>> unit_rows(np.array([[3.0, 0.0, 4.0]]), [2], "f.csv", "d_x, d_y, d_z", "give a direction")
    array([[0.6, 0. , 0.8]])
    """
    norms = np.linalg.norm(vectors, axis=1)
    if np.any(norms == 0):
        k = int(np.flatnonzero(norms == 0)[0])
        raise InputError(f"line {lines[k]}: {shown} is zero", path=where, hint=hint)
    return vectors / norms[:, None]
