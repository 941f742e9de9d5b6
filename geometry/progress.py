"""Progress of precomputes that can take seconds: view and exchange factors, K_IS, the molecular
exchange, the reflection plan and every other value a model builds once (:mod:`sunwind.geometry.cache`).

Each is a named :func:`step`; work inside it reports what is done with :func:`advance`. Nothing is
shown unless a caller installs a :class:`Reporter` with :func:`reporting` (the command line does, on
stderr); the library is silent by default.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Protocol


class Reporter(Protocol):
    """Receives the steps; its methods may be called from any thread, one at a time."""

    def begin(self, name: str) -> None:
        """Step ``name`` started."""

    def advance(self, name: str, done: int, total: int) -> None:
        """``done`` of the ``total`` units of step ``name`` (sides, rows ...) are done."""

    def end(self, name: str, seconds: float) -> None:
        """Step ``name`` ended after ``seconds`` [s]."""


class _Step:
    def __init__(self, name: str) -> None:
        self.name, self.start, self.done = name, time.perf_counter(), 0


_lock = threading.RLock()
_reporters: list[Reporter] = []
_running: list[_Step] = []


@contextmanager
def reporting(reporter: Reporter) -> Iterator[Reporter]:
    """Steps run inside the block report to ``reporter`` (the innermost one installed)."""
    with _lock:
        _reporters.append(reporter)
    try:
        yield reporter
    finally:
        with _lock:
            _reporters.remove(reporter)


@contextmanager
def step(name: str) -> Iterator[None]:
    """A precompute step called ``name``; nothing happens unless a reporter is installed."""
    if not _reporters:
        yield
        return
    current = _Step(name)
    with _lock:
        _running.append(current)
        _reporters[-1].begin(name)
    try:
        yield
    finally:
        with _lock:
            _running.remove(current)
            if _reporters:
                _reporters[-1].end(name, time.perf_counter() - current.start)


def advance(units: int, total: int) -> None:
    """``units`` more of ``total`` of the innermost running step are done (any thread)."""
    if not _reporters:
        return
    with _lock:
        if _running and _reporters:
            current = _running[-1]
            current.done += units
            _reporters[-1].advance(current.name, min(current.done, total), total)
