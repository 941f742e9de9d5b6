"""Sweep chunks as tasks on a Dask distributed cluster (``sunwind sweep --scheduler``).

Each worker process loads the model once from the recipe's files (so they must be readable at the
same paths on every worker: a shared file system, or the same checkout) and keeps it for every task
it is given; view factors come from the disk cache the submitting process fills first (point
``SUNWIND_CACHE_DIR`` at a shared directory on a real cluster, or each worker computes them once). A
task runs its attitudes on one thread, so start workers with one thread each and one worker per
core: ``dask scheduler`` on one machine, ``dask worker tcp://HOST:8786 --nworkers auto --nthreads 1``
on every machine. Results do not depend on where or on how many threads they were computed.
"""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.tables.sweep import Job, ModelRecipe, Setup, evaluate_chunk, precompute
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import CORES
from sunwind.geometry.spacecraft import Spacecraft

#: Seconds to wait for a scheduler before giving up.
CONNECT_TIMEOUT_S = 10
#: Models loaded in this worker process, by recipe.
_MODELS: dict[ModelRecipe, Spacecraft] = {}


def _remote_chunk(recipe: ModelRecipe, setup: Setup, directions: NDArray[np.float64]) -> NDArray[np.float64]:
    """Records of one chunk, in a worker: the model loaded once per process, one thread per task."""
    os.environ["SUNWIND_THREADS"] = "1"
    if recipe not in _MODELS:
        _MODELS[recipe] = recipe.load()
    return evaluate_chunk(_MODELS[recipe], setup, directions)


def connect(scheduler: str, workers: int | None):
    """A Dask client: of a new local cluster for ``"local"``, else of the scheduler at the address.

    Raises
    ------
    InputError
        Dask is not installed, or the scheduler cannot be reached.
    """
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError(
            "--scheduler needs Dask distributed", hint="install it: python -m pip install 'sunwind[dask]'"
        ) from None
    if scheduler == "local":
        cluster = LocalCluster(
            n_workers=workers or CORES, threads_per_worker=1, processes=True, dashboard_address=None
        )
        return Client(cluster)
    try:
        return Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s")
    except (OSError, TimeoutError, ValueError) as error:
        reason = str(error).splitlines()[0] if str(error) else type(error).__name__
        raise InputError(
            f"cannot reach the Dask scheduler at {scheduler}: {reason}",
            hint="start one with `dask scheduler` and workers with `dask worker ADDRESS --nthreads 1`, "
            "or give --scheduler alone for a local cluster",
        ) from None


def run_on_dask(
    recipe: ModelRecipe,
    craft: Spacecraft | None,
    pending: list[tuple[Job, int, int]],
    scheduler: str,
    workers: int | None,
    finished: Callable[[Job, int, int, NDArray[np.float64]], None],
) -> None:
    """Submit every pending chunk; hand each result to ``finished`` as it arrives."""
    from dask.distributed import as_completed

    client = connect(scheduler, workers)
    try:
        # fill the view-factor cache once here, so that workers read it instead of each computing it
        precompute(recipe.load() if craft is None else craft, [job for job, _, _ in pending])
        futures = {
            client.submit(_remote_chunk, recipe, job.setup, job.directions[lo:hi], pure=False): (job, lo, hi)
            for job, lo, hi in pending
        }
        for future in as_completed(futures):
            job, lo, hi = futures[future]
            finished(job, lo, hi, future.result())
    finally:
        cluster = client.cluster
        client.close()
        if cluster is not None:
            cluster.close()


def timed_on_local_cluster(
    recipe: ModelRecipe, pending: list[tuple[Job, int, int]], workers: int
) -> tuple[float, list[NDArray[np.float64]]]:
    """Seconds a local cluster of ``workers`` one-thread workers takes for ``pending`` chunks once every
    worker has the model and what each job's first attitude makes (one-attitude chunks of every job run
    on each worker first), and the chunks' records."""
    import time

    from dask.distributed import wait

    client = connect("local", workers)
    try:
        firsts: dict[int, tuple[Job, int]] = {}
        for job, lo, _ in pending:
            firsts.setdefault(id(job), (job, lo))
        warm = [
            client.submit(
                _remote_chunk, recipe, job.setup, job.directions[lo : lo + 1], pure=False, workers=[w]
            )
            for w in client.scheduler_info()["workers"]
            for job, lo in firsts.values()
        ]
        wait(warm)
        start = time.perf_counter()
        futures = [
            client.submit(_remote_chunk, recipe, job.setup, job.directions[lo:hi], pure=False)
            for job, lo, hi in pending
        ]
        results = client.gather(futures)
        return time.perf_counter() - start, results
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
