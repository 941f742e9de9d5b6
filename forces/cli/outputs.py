"""Checks of a command's output files, made before any work: a picture's suffix, an output that is
also an input or another output, a place that cannot be written."""

from __future__ import annotations

import tempfile
from pathlib import Path

from sunwind.geometry.errors import InputError

#: Picture formats matplotlib writes (its file names' suffixes).
IMAGE_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp")


def check_image(path: Path, *others: str | Path | None) -> None:
    """Refuse a plot file name before any work is done.

    The name must end in a picture suffix matplotlib can write (:data:`IMAGE_SUFFIXES`), must not be
    one of the run's other files, and its place must be writable.

    Parameters
    ----------
    path : pathlib.Path
        The picture to be written.
    *others : str or pathlib.Path or None
        The run's other outputs and its inputs; None entries (a file not asked for) are skipped.

    Raises
    ------
    InputError
        A suffix that is no picture format, a name shared with one of ``others``, or a place that
        cannot be written (see :func:`check_distinct` and :func:`check_writable`).

    Examples
    --------
    >>> from pathlib import Path
    >>> check_image(Path("table.nc"))
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: table.nc: a plot is written as a picture, not .nc; name it ...
    """
    if path.suffix.lower() not in IMAGE_SUFFIXES:
        raise InputError(
            f"a plot is written as a picture, not {path.suffix or 'a file without a suffix'}",
            path=str(path),
            hint=f"name it with one of {', '.join(IMAGE_SUFFIXES)}",
        )
    check_distinct(path, *others)
    check_writable(path)


def check_distinct(output: Path, *others: str | Path | None) -> None:
    """Refuse an output that is the same file as another file of the run.

    Parameters
    ----------
    output : pathlib.Path
        The file to be written.
    *others : str or pathlib.Path or None
        The run's other outputs, and inputs that writing ``output`` would destroy; None is skipped.
        Paths are compared once resolved, so ``a.png`` and ``./a.png`` are one file.

    Raises
    ------
    InputError
        ``output`` resolves to the same path as one of ``others``.

    Examples
    --------
    >>> from pathlib import Path
    >>> check_distinct(Path("loads.csv"), "craft.obj", None)  # distinct: nothing happens
    >>> check_distinct(Path("craft.obj"), "./craft.obj")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: craft.obj: the output is also another file of this run: ...
    """
    for other in others:
        if other is not None and Path(output).resolve() == Path(other).resolve():
            raise InputError(
                "the output is also another file of this run: writing it would overwrite that one",
                path=str(output),
                hint="give each output its own name",
            )


def check_writable(path: Path) -> None:
    """Refuse an output that cannot be written, before any work is done.

    A scratch file is created (and removed) in the output's directory to find out.

    Parameters
    ----------
    path : pathlib.Path
        The file to be written; a bare name is taken in the working directory.

    Raises
    ------
    InputError
        ``path`` is a directory, its directory does not exist, or a file cannot be created there.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     check_writable(Path(folder) / "table.nc")  # writable: nothing happens
    >>> check_writable(Path("no-such-folder") / "table.nc")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: no-such-folder/table.nc: the output's directory does not exist; ...
    """
    directory = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise InputError("the output is a directory", path=str(path), hint="give a file name")
    if not directory.is_dir():
        raise InputError("the output's directory does not exist", path=str(path), hint="create it first")
    try:
        with tempfile.NamedTemporaryFile(dir=directory, prefix=".sunwind-write-test-"):
            pass
    except OSError as error:
        raise InputError(f"cannot write here: {error.strerror}", path=str(path)) from None
