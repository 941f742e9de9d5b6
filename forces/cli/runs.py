"""The flags of a checkpointed run of many entries (a sweep's attitudes, an orbit's steps) and the
:class:`~sunwind.forces.tables.SweepRun` they make."""

from __future__ import annotations

import shlex
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import click
from rich.progress import Progress

from sunwind.forces.tables import DEFAULT_CHUNK, SweepRun
from sunwind.forces.tables.checkpoint import Checkpoint
from sunwind.forces.tables.cluster import require_dask


def run_options(entry: str, run: str) -> list[Callable]:
    """``--resume``, ``--scheduler``, ``--workers`` and ``--chunk`` of a ``run`` (its name in the help)
    of ``entry``s (one attitude, one step)."""
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
            default=DEFAULT_CHUNK,
            show_default=True,
            help=f"{entry.capitalize()}s per checkpoint chunk.",
        ),
    ]


def check_run(values: dict) -> dict:
    """The run flags, Dask checked importable (before the mesh is loaded or a checkpoint made)."""
    if values["scheduler"] is not None:
        require_dask()
    return values


def sweep_run(values: dict, checkpoint: Path | None, progress: Callable[[int], None]) -> SweepRun:
    """The :class:`SweepRun` of the run flags ``values``, keeping its checkpoint at ``checkpoint`` (None:
    none) and reporting entries done to ``progress``; its notices are ``sunwind: notice:`` lines."""
    return SweepRun(
        values["chunk"],
        checkpoint,
        values["resume"],
        values["scheduler"],
        values["workers"],
        progress,
        notice=lambda line: print(f"sunwind: notice: {checkpoint}: {line}", file=sys.stderr),
    )


@contextmanager
def interruptible(bar: Progress, checkpoint: Path | None) -> Iterator[None]:
    """Run the block; on Ctrl-C stop the progress ``bar`` and say what the run's checkpoint kept and
    the command that resumes it (:func:`say_interrupted`), then let the interrupt go on."""
    try:
        yield
    except KeyboardInterrupt:
        bar.stop()
        say_interrupted(checkpoint)
        raise


def say_interrupted(checkpoint: Path | None) -> None:
    """On Ctrl-C in a run of many entries, say what its checkpoint kept and the command that resumes it
    (the command line as given, with ``--resume``)."""
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
