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
    """A :class:`~sunwind.geometry.progress.Reporter` printing ``sunwind: <step> ...`` lines on stderr.

    A step is shown once it has run for :data:`DELAY` seconds, then given a line with how much is done
    at most every :data:`INTERVAL` seconds, and a closing line with its time; a quicker step prints
    nothing. Lines come from timer threads, each written whole.

    Examples
    --------
    >>> import contextlib, sys
    >>> lines = StepLines()
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     lines.begin("view factors")
    ...     lines.end("view factors", 0.01)  # ended before DELAY: nothing shown
    >>> import sunwind.forces.cli.progress as progress
    >>> delay, progress.DELAY = progress.DELAY, 0.0  # show every step at once
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     lines.begin("view factors")
    ...     lines.end("view factors", 2.5)
    sunwind: view factors ...
    sunwind: view factors done in 2.5 s
    >>> progress.DELAY = delay
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._shown: dict[str, float] = {}  # step -> time its last line was printed
        self._timers: dict[str, threading.Timer] = {}

    def begin(self, name: str) -> None:
        """Start the step ``name``, shown once it has run for :data:`DELAY` seconds.

        Parameters
        ----------
        name : str
            The step, as its lines name it.
        """
        if DELAY <= 0:
            self._show(name)
            return
        timer = threading.Timer(DELAY, self._show, (name,))
        timer.daemon = True
        self._timers[name] = timer
        timer.start()

    def advance(self, name: str, done: int, total: int) -> None:
        """Report ``done`` of ``total``, in a line when the step is shown and :data:`INTERVAL` has passed.

        Parameters
        ----------
        name : str
            The step.
        done, total : int
            Units of work done so far, and in all.
        """
        with self._lock:
            last = self._shown.get(name)
            if last is None or time.perf_counter() - last < INTERVAL:
                return
            self._shown[name] = time.perf_counter()
        self._print(f"{name}: {done} of {total} ({100 * done / max(total, 1):.0f} %)")

    def end(self, name: str, seconds: float) -> None:
        """End the step ``name``, with a closing line when it was shown.

        Parameters
        ----------
        name : str
            The step.
        seconds : float
            Its running time [s].
        """
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
    """A numba event listener announcing, once per run, that kernels are being compiled.

    On the first compilation of a run (a kernel with no compiled copy on disk: a first run, or a new
    version) it says on stderr how many kernels are missing and about how long compiling them takes at
    most (:data:`COMPILE_S` each), so the wait is not taken for a hang.

    Examples
    --------
    >>> import contextlib, sys
    >>> from numba.core import event
    >>> notice = CompileNotice()
    >>> start = event.Event("numba:compile", event.EventStatus.START)
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     notice.on_start(start)
    ...     notice.on_start(start)  # said once only
    sunwind: notice: compiling numba kernels on first use (... not on disk yet; about ... s at most, ...)
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._said = False

    def on_start(self, happening: event.Event) -> None:
        """Print the notice when a compilation starts (in any thread), the first time only.

        Parameters
        ----------
        happening : numba.core.event.Event
            The compilation's start event (not read).
        """
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
        """Do nothing when a compilation ends.

        Parameters
        ----------
        happening : numba.core.event.Event
            The compilation's end event (not read).
        """


def compile_notices() -> contextlib.AbstractContextManager:
    """Open a context in which numba's first compilation prints the :class:`CompileNotice`.

    Returns
    -------
    contextlib.AbstractContextManager
        A context installing a :class:`CompileNotice` for numba's ``"numba:compile"`` events while it
        lasts.

    Examples
    --------
    >>> import sunwind as sw
    >>> with compile_notices():  # nothing is compiled here, so nothing is said
    ...     sw.meshes.box().n_faces
    12
    """
    return event.install_listener("numba:compile", CompileNotice())


def uncompiled_kernels() -> int:
    """Count the numba kernels of the imported sunwind modules that have no valid compiled copy on disk.

    Returns
    -------
    int
        The kernels (numba dispatchers defined in an imported ``sunwind.`` module) whose on-disk cache
        index is missing or stale; 0 when numba's cache layout is not the one known here.

    Examples
    --------
    >>> missing = uncompiled_kernels()
    >>> isinstance(missing, int) and missing >= 0
    True
    """
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
