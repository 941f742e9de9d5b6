"""Checks of a command's output files, made before any work: a picture's suffix, an output that is
also an input or another output, a place that cannot be written."""

from __future__ import annotations

import tempfile
from pathlib import Path

from sunwind.geometry.errors import InputError

#: Picture formats matplotlib writes (its file names' suffixes).
IMAGE_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp")


def check_image(path: Path, *others: str | Path | None) -> None:
    """Fail now, before any work, when ``path`` is no picture name matplotlib writes, is one of the
    ``others`` (the run's other outputs and its inputs), or cannot be written."""
    if path.suffix.lower() not in IMAGE_SUFFIXES:
        raise InputError(
            f"a plot is written as a picture, not {path.suffix or 'a file without a suffix'}",
            path=str(path),
            hint=f"name it with one of {', '.join(IMAGE_SUFFIXES)}",
        )
    check_distinct(path, *others)
    check_writable(path)


def check_distinct(output: Path, *others: str | Path | None) -> None:
    """Fail when ``output`` is the same file as one of ``others`` (another output, or an input that
    writing it would destroy)."""
    for other in others:
        if other is not None and Path(output).resolve() == Path(other).resolve():
            raise InputError(
                "the output is also another file of this run: writing it would overwrite that one",
                path=str(output),
                hint="give each output its own name",
            )


def check_writable(path: Path) -> None:
    """Fail now, before any work, when ``path`` cannot be written."""
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
