"""The flags of a checkpointed run of many entries (a sweep's attitudes, an orbit's steps) and the
:class:`~sunwind.forces.tables.SweepRun` they make."""

from __future__ import annotations

import shlex
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import click
from rich.console import Console
from rich.progress import Progress, ProgressColumn

from sunwind.forces.tables import DEFAULT_CHUNK, SweepRun
from sunwind.forces.tables.checkpoint import Checkpoint
from sunwind.forces.tables.cluster import require_dask
from sunwind.geometry.errors import InputError


def run_options(entry: str, run: str, chunk: int = DEFAULT_CHUNK) -> list[Callable]:
    """Make the flags of a checkpointed run of many entries.

    The flags are ``--resume``, ``--scheduler [ADDRESS]``, ``--workers`` and ``--chunk``; their help
    texts name the run and its entries.

    Parameters
    ----------
    entry : str
        What one entry of the run is, singular (``"attitude"``, ``"step"``).
    run : str
        The run's name in the help texts (``"sweep (-o)"``).
    chunk : int, optional
        Entries per checkpoint chunk by default.

    Returns
    -------
    list of callable
        Click option decorators, in order; apply them to a command or hand them to
        :func:`~sunwind.forces.cli.options.group`.

    Examples
    --------
    >>> import click
    >>> from sunwind.forces.cli.options import group
    >>> @click.command()
    ... @group("run", run_options("step", "run"), check_run)
    ... def demo(run):
    ...     print(run)
    >>> demo.main(["--chunk", "8", "--workers", "2"], standalone_mode=False)
    {'chunk': 8, 'workers': 2, 'scheduler': None, 'resume': False}
    """
    return [
        click.option("--resume", is_flag=True, help=f"Continue an interrupted {run} from its checkpoint."),
        click.option(
            "--scheduler",
            is_flag=False,
            flag_value="local",
            default=None,
            metavar="[ADDRESS]",
            help="Run on Dask: a scheduler address, or alone for a local cluster.",
        ),
        click.option(
            "--workers", type=int, help=f"Threads per {entry}; with --scheduler alone, local Dask workers."
        ),
        click.option(
            "--chunk",
            type=int,
            default=chunk,
            show_default=True,
            help=f"{entry.capitalize()}s per checkpoint chunk.",
        ),
    ]


def check_run(values: dict) -> dict:
    """Check the run flags before the mesh is loaded or a checkpoint is made.

    Parameters
    ----------
    values : dict
        The values of the :func:`run_options` flags, by keyword (``resume``, ``scheduler``,
        ``workers``, ``chunk``), and ``output`` (``-o``) when the command may run without one.

    Returns
    -------
    dict
        ``values`` itself, unchanged.

    Raises
    ------
    InputError
        A ``--scheduler`` is given and Dask distributed cannot be imported, or ``--resume`` without
        the output whose checkpoint it takes up.

    Examples
    --------
    >>> check_run({"resume": False, "scheduler": None, "workers": None, "chunk": 64})
    {'resume': False, 'scheduler': None, 'workers': None, 'chunk': 64}
    >>> check_run({"resume": True, "scheduler": None, "workers": None, "chunk": 64, "output": None})
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: --resume takes up the checkpoint of an output: give -o as before
    """
    if values["resume"] and "output" in values and values["output"] is None:
        raise InputError("--resume takes up the checkpoint of an output: give -o as before")
    if values["scheduler"] is not None:
        require_dask()
    return values


def sweep_run(values: dict, checkpoint: Path | None, progress: Callable[[int], None]) -> SweepRun:
    """Make the :class:`~sunwind.forces.tables.SweepRun` of the run flags.

    Its notices are printed on stderr as ``sunwind: notice: CHECKPOINT: ...`` lines.

    Parameters
    ----------
    values : dict
        The values of the :func:`run_options` flags, by keyword.
    checkpoint : pathlib.Path or None
        The checkpoint directory the run keeps its finished chunks in; None keeps none.
    progress : callable
        Called with the number of entries finished so far (resumed ones included), after each chunk.

    Returns
    -------
    SweepRun
        The run's chunking, checkpoint, resumption and scheduler.

    Examples
    --------
    >>> values = {"resume": False, "scheduler": None, "workers": 1, "chunk": 16}
    >>> run = sweep_run(values, None, lambda done: None)
    >>> run.chunk, run.checkpoint, run.workers
    (16, None, 1)
    """
    return SweepRun(
        values["chunk"],
        checkpoint,
        values["resume"],
        values["scheduler"],
        values["workers"],
        progress,
        notice=lambda line: print(f"sunwind: notice: {checkpoint}: {line}", file=sys.stderr),
    )


def progress_bar(*columns: ProgressColumn, hidden: bool = False) -> Progress:
    """A run's progress bar on stderr, gone when it ends; drawn only on a terminal (in a log, rich would
    leave an empty line and show nothing meanwhile).

    Parameters
    ----------
    *columns : rich.progress.ProgressColumn
        What it shows.
    hidden : bool, optional
        Never drawn (``--json`` runs of the benchmark).

    Returns
    -------
    rich.progress.Progress

    Examples
    --------
    >>> import contextlib, io
    >>> from rich.progress import BarColumn
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     with progress_bar(BarColumn()) as bar:
    ...         bar.update(bar.add_task("rows", total=2), completed=2)
    >>> err.getvalue()
    ''
    """
    console = Console(stderr=True)
    return Progress(*columns, transient=True, console=console, disable=hidden or not console.is_terminal)


@contextmanager
def interruptible(bar: Progress, checkpoint: Path | None) -> Iterator[None]:
    """Run a block; on Ctrl-C, stop the progress bar and say how to resume before passing the interrupt on.

    Parameters
    ----------
    bar : rich.progress.Progress
        The run's progress bar, stopped on an interrupt so the notice is not drawn over.
    checkpoint : pathlib.Path or None
        The run's checkpoint directory (None: the run keeps nothing), for :func:`say_interrupted`.

    Yields
    ------
    None
        The block runs inside; a :class:`KeyboardInterrupt` in it is re-raised after the notice.

    Examples
    --------
    >>> import contextlib, sys
    >>> from rich.progress import Progress
    >>> bar = Progress(disable=True)
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     try:
    ...         with interruptible(bar, None):
    ...             raise KeyboardInterrupt
    ...     except KeyboardInterrupt:
    ...         print("the interrupt went on")
    sunwind: notice: nothing was kept: a run keeps its finished entries only with -o ...
    the interrupt went on
    """
    try:
        yield
    except KeyboardInterrupt:
        bar.stop()
        say_interrupted(checkpoint)
        raise


def say_interrupted(checkpoint: Path | None) -> None:
    """Say on stderr what an interrupted run kept and the command that resumes it.

    The command is the command line as given, with ``--resume`` added; it is read from the running
    click context, so it is only said when the checkpoint holds finished chunks.

    Parameters
    ----------
    checkpoint : pathlib.Path or None
        The run's checkpoint directory; None when the run keeps nothing (no ``-o``).

    Examples
    --------
    >>> import contextlib, sys
    >>> from pathlib import Path
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     say_interrupted(Path("no-such-checkpoint"))
    sunwind: notice: no chunk had finished: nothing was kept
    """
    if checkpoint is None:
        said = "nothing was kept: a run keeps its finished entries only with -o (a checkpoint beside it)"
    elif not (kept := Checkpoint.kept_chunks(checkpoint)):
        said = "no chunk had finished: nothing was kept"
    else:
        root = click.get_current_context().find_root()
        argv = list((root.obj or {}).get("argv") or sys.argv[1:])
        command = shlex.join(["sunwind", *argv, *([] if "--resume" in argv else ["--resume"])])
        said = f"{kept} finished chunks are kept in {checkpoint}; resume with: {command}"
    print(f"sunwind: notice: {said}", file=sys.stderr)
