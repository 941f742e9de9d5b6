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
    """Receive the progress of steps; its methods may be called from any thread, one at a time.

    Install one with :func:`reporting`; any object with these three methods will do.

    Parameters
    ----------
    *args, **kwargs
        Not used: a protocol is not made itself; any object with these methods is a reporter.

    Examples
    --------
    >>> class Printer:
    ...     def begin(self, name):
    ...         print("begin", name)
    ...     def advance(self, name, done, total):
    ...         print(name, done, "of", total)
    ...     def end(self, name, seconds):
    ...         print("end", name)
    >>> with reporting(Printer()):
    ...     with step("view factors"):
    ...         advance(3, 4)
    begin view factors
    view factors 3 of 4
    end view factors
    """

    def begin(self, name: str) -> None:
        """Note that a step has started.

        Parameters
        ----------
        name : str
            The step's name.

        Examples
        --------
        >>> class Printer:
        ...     def begin(self, name):
        ...         print("begin", name)
        ...     def advance(self, name, done, total):
        ...         print(name, done, "of", total)
        ...     def end(self, name, seconds):
        ...         print("end", name)
        >>> with reporting(Printer()):
        ...     with step("view factors"):
        ...         advance(3, 4)
        begin view factors
        view factors 3 of 4
        end view factors
        """

    def advance(self, name: str, done: int, total: int) -> None:
        """Note that part of a step is done.

        Parameters
        ----------
        name : str
            The step's name.
        done : int
            Units done so far (sides, rows ...), at most ``total``.
        total : int
            Units of the whole step.

        Examples
        --------
        >>> class Printer:
        ...     def begin(self, name):
        ...         print("begin", name)
        ...     def advance(self, name, done, total):
        ...         print(name, done, "of", total)
        ...     def end(self, name, seconds):
        ...         print("end", name)
        >>> with reporting(Printer()):
        ...     with step("view factors"):
        ...         advance(3, 4)
        begin view factors
        view factors 3 of 4
        end view factors
        """

    def end(self, name: str, seconds: float) -> None:
        """Note that a step has ended.

        Parameters
        ----------
        name : str
            The step's name.
        seconds : float
            How long it ran [s].

        Examples
        --------
        >>> class Printer:
        ...     def begin(self, name):
        ...         print("begin", name)
        ...     def advance(self, name, done, total):
        ...         print(name, done, "of", total)
        ...     def end(self, name, seconds):
        ...         print("end", name)
        >>> with reporting(Printer()):
        ...     with step("view factors"):
        ...         advance(3, 4)
        begin view factors
        view factors 3 of 4
        end view factors
        """


class _Step:
    def __init__(self, name: str) -> None:
        self.name, self.start, self.done = name, time.perf_counter(), 0


_lock = threading.RLock()
_reporters: list[Reporter] = []
_running: list[_Step] = []


@contextmanager
def reporting(reporter: Reporter) -> Iterator[Reporter]:
    """Report the steps run inside the block to a reporter (the innermost one installed).

    Parameters
    ----------
    reporter : Reporter
        Receives :meth:`~Reporter.begin`, :meth:`~Reporter.advance` and :meth:`~Reporter.end`.

    Yields
    ------
    Reporter
        ``reporter`` itself.

    Examples
    --------
    >>> class Printer:
    ...     def begin(self, name):
    ...         print("begin", name)
    ...     def advance(self, name, done, total):
    ...         print(name, done, "of", total)
    ...     def end(self, name, seconds):
    ...         print("end", name)
    >>> with reporting(Printer()):
    ...     with step("view factors"):
    ...         advance(3, 4)
    begin view factors
    view factors 3 of 4
    end view factors
    """
    with _lock:
        _reporters.append(reporter)
    try:
        yield reporter
    finally:
        with _lock:
            _reporters.remove(reporter)


@contextmanager
def step(name: str) -> Iterator[None]:
    """Mark a named precompute step; nothing happens unless a reporter is installed.

    Parameters
    ----------
    name : str
        The step's name, as shown to the user.

    Yields
    ------
    None
        Control to the step's work.

    Examples
    --------
    >>> class Printer:
    ...     def begin(self, name):
    ...         print("begin", name)
    ...     def advance(self, name, done, total):
    ...         print(name, done, "of", total)
    ...     def end(self, name, seconds):
    ...         print("end", name)
    >>> with reporting(Printer()):
    ...     with step("view factors"):
    ...         advance(3, 4)
    begin view factors
    view factors 3 of 4
    end view factors
    """
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
    """Report that more units of the innermost running step are done; any thread may call it.

    Parameters
    ----------
    units : int
        Units just finished.
    total : int
        Units of the whole step.

    Examples
    --------
    >>> class Printer:
    ...     def begin(self, name):
    ...         print("begin", name)
    ...     def advance(self, name, done, total):
    ...         print(name, done, "of", total)
    ...     def end(self, name, seconds):
    ...         print("end", name)
    >>> with reporting(Printer()):
    ...     with step("view factors"):
    ...         advance(3, 4)
    begin view factors
    view factors 3 of 4
    end view factors
    """
    if not _reporters:
        return
    with _lock:
        if _running and _reporters:
            current = _running[-1]
            current.done += units
            _reporters[-1].advance(current.name, min(current.done, total), total)
