"""A checkpointed run stopped part way and taken up again, for the resume tests of sweeps and orbits."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import pytest

from sunwind.forces.tables import SweepRun

T = TypeVar("T")


def stopped_then_resumed(
    compute: Callable[[SweepRun], T], checkpoint: Path, chunk: int
) -> tuple[T, list[str]]:
    """``compute(run)`` interrupted once its first chunk of ``chunk`` entries is kept in ``checkpoint``,
    then again with ``resume``: the resumed result and the notices the resumed run gave."""

    def stop(done: int) -> None:
        if done >= chunk:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        compute(SweepRun(chunk=chunk, checkpoint=checkpoint, progress=stop))
    notices: list[str] = []
    resumed = compute(SweepRun(chunk=chunk, checkpoint=checkpoint, resume=True, notice=notices.append))
    return resumed, notices
