"""Files written whole or not at all: to a temporary name beside the target, then renamed into place."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO


def temporary_name(path: Path) -> Path:
    """The hidden name a file is written under before it is renamed to ``path``."""
    return path.with_name(f".{path.name}.tmp")


@contextmanager
def atomic_text(path: str | os.PathLike, encoding: str = "utf-8") -> Iterator[TextIO]:
    """A text stream whose file appears at ``path`` only once the block has finished without error."""
    target = Path(path)
    temporary = temporary_name(target)
    try:
        with temporary.open("w", encoding=encoding, newline="\n") as stream:
            yield stream
        os.replace(temporary, target)
    finally:
        temporary.unlink(missing_ok=True)
