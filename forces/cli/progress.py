"""The command line's view of precompute steps (:mod:`sunwind.geometry.progress`): one stderr line when a
step has run for :data:`DELAY` seconds, one every :data:`INTERVAL` seconds while it goes on (with how
much is done), and one when it ends; a quick step prints nothing. Lines, not a redrawn bar, so they read
the same in a log and pass above the sweep's progress bar."""

from __future__ import annotations

import sys
import threading
import time

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
        print(f"sunwind: {text}", file=sys.stderr, flush=True)
