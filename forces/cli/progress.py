"""The command line's view of precompute steps (:mod:`sunwind.geometry.progress`): one stderr line when a
step has run for :data:`DELAY` seconds, one every :data:`INTERVAL` seconds while it goes on (with how
much is done), and one when it ends; a quick step prints nothing. Lines, not a redrawn bar, so they read
the same in a log and pass above the sweep's progress bar."""

from __future__ import annotations

import contextlib
import sys
import threading
import time

from numba.core import event
from numba.core.dispatcher import Dispatcher

#: Seconds a step runs before it is shown.
DELAY = 1.0
#: Least seconds between two lines of one step.
INTERVAL = 5.0


class StepLines:
    """A :class:`~sunwind.geometry.progress.Reporter` printing ``sunwind: <step> ...`` lines on stderr."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._shown: dict[str, float] = {}  # step -> time its last line was printed
        self._timers: dict[str, threading.Timer] = {}

    def begin(self, name: str) -> None:
        """Show ``name`` once it has run for :data:`DELAY` seconds."""
        if DELAY <= 0:
            self._show(name)
            return
        timer = threading.Timer(DELAY, self._show, (name,))
        timer.daemon = True
        self._timers[name] = timer
        timer.start()

    def advance(self, name: str, done: int, total: int) -> None:
        """A line with ``done`` of ``total`` when the step is shown and :data:`INTERVAL` has passed."""
        with self._lock:
            last = self._shown.get(name)
            if last is None or time.perf_counter() - last < INTERVAL:
                return
            self._shown[name] = time.perf_counter()
        self._print(f"{name}: {done} of {total} ({100 * done / max(total, 1):.0f} %)")

    def end(self, name: str, seconds: float) -> None:
        """The closing line of a step that was shown."""
        timer = self._timers.pop(name, None)
        if timer is not None:
            timer.cancel()
            timer.join()  # a line it is printing comes before the closing one
        with self._lock:
            shown = self._shown.pop(name, None) is not None
        if shown:
            self._print(f"{name} done in {seconds:.1f} s")

    def _show(self, name: str) -> None:
        with self._lock:
            self._shown[name] = time.perf_counter()
        self._print(f"{name} ...")

    @staticmethod
    def _print(text: str) -> None:
        with _PRINTING:  # one write per line: steps shown from timer threads never share a line
            sys.stderr.write(f"sunwind: {text}\n")
            sys.stderr.flush()


_PRINTING = threading.Lock()

#: Seconds numba takes to compile one of sunwind's kernels, on average: the quick-start sweep
#: compiled 92 in about 70 s on a 2-core machine (docs/getting_started.md).
COMPILE_S = 0.75


class CompileNotice(event.Listener):
    """A numba event listener saying, once, on the first compilation of a run (a kernel with no
    compiled copy on disk: a first run, or a new version), that kernels are being compiled and about
    how long it takes at most, so the wait is not taken for a hang."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._said = False

    def on_start(self, happening: event.Event) -> None:
        """A compilation starts (in any thread): the notice, the first time only."""
        with self._lock:
            if self._said:
                return
            self._said = True
        missing = uncompiled_kernels()
        print(
            f"sunwind: notice: compiling numba kernels on first use ({missing} not on disk yet; about "
            f"{max(1, round(missing * COMPILE_S))} s at most, once: later runs load them from disk)",
            file=sys.stderr,
            flush=True,
        )

    def on_end(self, happening: event.Event) -> None:
        """A compilation ends: nothing to say."""


def compile_notices() -> contextlib.AbstractContextManager:
    """A context in which numba's first compilation prints the :class:`CompileNotice`."""
    return event.install_listener("numba:compile", CompileNotice())


def uncompiled_kernels() -> int:
    """How many numba kernels of the imported sunwind modules have no valid compiled copy in numba's
    on-disk cache (0 when numba's cache layout is not the one known here)."""
    kernels = {
        id(value): value
        for name, module in list(sys.modules.items())
        if name.startswith("sunwind.") and module is not None
        for value in vars(module).values()
        if isinstance(value, Dispatcher) and value.__module__ == name
    }
    try:
        return sum(1 for kernel in kernels.values() if not kernel._cache._cache_file._load_index())
    except AttributeError:  # numba internals of another version: say nothing rather than guess
        return 0
