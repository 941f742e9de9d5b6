"""Files written whole or not at all: to a temporary name beside the target, then renamed into place."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO


def temporary_name(path: Path) -> Path:
    """The hidden name a file is written under before it is renamed into place.

    Parameters
    ----------
    path : Path
        The file's final path.

    Returns
    -------
    Path
        ``.NAME.tmp`` in the same directory, so the rename stays on one file system.

    Examples
    --------
    >>> from pathlib import Path
    >>> str(temporary_name(Path("out") / "table.csv"))
    'out/.table.csv.tmp'
    """
    return path.with_name(f".{path.name}.tmp")


@contextmanager
def atomic_text(path: str | os.PathLike, encoding: str = "utf-8") -> Iterator[TextIO]:
    r"""A text stream whose file appears at ``path`` only once the block has finished without error.

    The text goes to :func:`temporary_name` and is renamed over ``path`` (``os.replace``) when the
    block ends; on an error the temporary file is removed and ``path`` is left as it was. Lines end in
    ``\n`` on every platform.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.
    encoding : str, default "utf-8"
        Text encoding.

    Yields
    ------
    TextIO
        The stream to write to.

    Examples
    --------
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = os.path.join(folder, "note.txt")
    ...     with atomic_text(path) as stream:
    ...         _ = stream.write("written whole\n")
    ...     try:
    ...         with atomic_text(path) as stream:
    ...             _ = stream.write("half")
    ...             raise RuntimeError("interrupted")
    ...     except RuntimeError:
    ...         pass
    ...     print(open(path).read().strip(), sorted(os.listdir(folder)))
    written whole ['note.txt']
    """
    target = Path(path)
    temporary = temporary_name(target)
    try:
        with temporary.open("w", encoding=encoding, newline="\n") as stream:
            yield stream
        os.replace(temporary, target)
    finally:
        temporary.unlink(missing_ok=True)
