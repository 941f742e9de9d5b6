"""Sweep chunks as tasks on a Dask distributed cluster.

Each worker process loads the model once from its :class:`~sunwind.forces.model.ModelSource` (so the
files must be readable at the same paths on every worker: a shared file system, or the same checkout)
and keeps it for every task it is given; view factors come from the disk cache the submitting process
fills first (point ``SUNWIND_CACHE_DIR`` at a shared directory on a real cluster, or each worker
computes them once). A task runs its attitudes on one thread, so start workers with one thread each and
one worker per core: ``dask scheduler`` on one machine, ``dask worker tcp://HOST:8786 --nworkers auto
--nthreads 1`` on every machine. Results do not depend on where or on how many threads they were
computed.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from sunwind.forces.model import Model, ModelSource
from sunwind.forces.tables.jobs import Inputs, Job, Records, Tabulation
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import CORES

#: Seconds to wait for a scheduler before giving up.
CONNECT_TIMEOUT_S = 10
#: A chunk to run: the job, and the range of its inputs.
Pending = tuple[Job, int, int]


def _worker_model(source: ModelSource, references: dict) -> Model:
    """The model of ``source`` in this worker process, loaded on its first task and kept there (on the
    Dask worker object, so it lives as long as the worker), on one thread."""
    from dask.distributed import get_worker

    kept = get_worker().__dict__.setdefault("sunwind_models", {})
    key = (source, tuple(sorted((k, str(v)) for k, v in references.items())))
    if key not in kept:
        kept[key] = Model(source.spacecraft(), source, threads=1, **references)
    return kept[key]


def _remote_chunk(source: ModelSource, references: dict, setup: Tabulation, inputs: Inputs) -> Records:
    """Records of one chunk, in a worker."""
    return setup.evaluate(_worker_model(source, references), inputs)


def _references(model: Model) -> dict:
    return {
        "reference_point_m": model.reference_point_m,
        "reference_area_m2": model.reference_area_m2,
        "reference_length_m": model.reference_length_m,
    }


def require_dask() -> None:
    """Check, before anything is made, that Dask distributed can be imported.

    Raises
    ------
    InputError
        It cannot (the ``dask`` extra is not installed).

    Examples
    --------
    >>> from sunwind.forces.tables.cluster import require_dask
    >>> require_dask()  # installed: nothing said
    """
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        raise InputError(
            "scheduler needs Dask distributed, which is not installed",
            hint='install it: python -m pip install "sunwind[dask]"',
            parameters=("scheduler",),
        ) from None


def connect(scheduler: str, workers: int | None):
    """A Dask client: of a new local cluster for ``"local"``, else of the scheduler at the address.

    Parameters
    ----------
    scheduler : str
        ``"local"`` for a new cluster of one-thread worker processes on this machine, else the address of
        a running scheduler (``tcp://HOST:8786``), waited for at most :data:`CONNECT_TIMEOUT_S` seconds.
    workers : int or None
        Worker processes of a local cluster (default one per core); ignored with an address.

    Returns
    -------
    dask.distributed.Client
        The connected client (close it, and its local cluster, when done).

    Raises
    ------
    InputError
        Dask is not installed, or the scheduler cannot be reached.

    Examples
    --------
    >>> from dask.distributed import LocalCluster
    >>> from sunwind.forces.tables.cluster import connect
    >>> cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0")
    >>> client = connect(cluster.scheduler_address, None)
    >>> len(client.scheduler_info()["workers"])
    1
    >>> client.close(); cluster.close()
    >>> import dask
    >>> connect("nowhere://scheduler", None)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: cannot reach the Dask scheduler at nowhere://scheduler: ...
    >>> dask.config.get("scheduler", None) is None  # the failed client left dask's scheduler alone
    True
    """
    require_dask()
    from dask.distributed import Client, LocalCluster

    if scheduler == "local":
        cluster = LocalCluster(  # the dashboard on a free port: two local clusters may run at once
            n_workers=workers or CORES, threads_per_worker=1, processes=True, dashboard_address=":0"
        )
        return Client(cluster, set_as_default=False)
    try:
        # never dask's default client: a default one sets dask's global scheduler, and its close puts
        # it back only when no other client in the process is open (a failed one waiting for the
        # garbage collector counts), which left every later netCDF write asking for a closed cluster
        return Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s", set_as_default=False)
    except (OSError, TimeoutError, ValueError) as error:
        reason = str(error).splitlines()[0] if str(error) else type(error).__name__
        raise InputError(
            f"cannot reach the Dask scheduler at {scheduler}: {reason}",
            hint="start one with `dask scheduler` and workers with `dask worker ADDRESS --nthreads 1`, "
            "or run on a local cluster",
        ) from None


def _source_of(model: Model) -> ModelSource:
    if model.source is None:
        raise InputError(
            "a model built in memory cannot go to Dask workers: they load it from its files",
            hint="load it with sunwind.forces.load, or run the sweep without a scheduler",
            parameters=("scheduler",),
        )
    return model.source


def run_on_dask(
    model: Model,
    pending: list[Pending],
    scheduler: str,
    workers: int | None,
    finished: Callable[[Job, int, int, Records], None],
) -> None:
    r"""Submit every pending chunk; hand each result to ``finished`` as it arrives.

    Each worker loads the model from its files on its first task and keeps it; the client (and a local
    cluster it started) is closed at the end, whatever happens.

    Parameters
    ----------
    model : Model
        A model loaded from files (its ``source`` is what the workers load).
    pending : list of (Job, int, int)
        The chunks to run: the job and the range ``[lo, hi)`` of its inputs.
    scheduler : str
        ``"local"`` or a scheduler's address, as :func:`connect` takes it.
    workers : int or None
        Worker processes of a local cluster.
    finished : callable
        Called as ``finished(job, lo, hi, records)`` for each chunk, in the order they finish.

    Raises
    ------
    InputError
        A model built in memory (no files for the workers), Dask missing, or the scheduler out of reach.

    Examples
    --------
    On a cluster of one in-process worker (a real one has one-thread worker processes):

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.tables.jobs import Job, SrpSetup
    >>> folder = tempfile.TemporaryDirectory()
    >>> obj = pathlib.Path(folder.name) / "tetra.obj"  # workers load the model from its file
    >>> _ = obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> model = sw.load(obj, uniform=black, threads=1)
    >>> job = Job(SrpSetup(reflections="none"), np.eye(3))
    >>> from dask.distributed import LocalCluster
    >>> from sunwind.forces.tables.cluster import run_on_dask
    >>> cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0")
    >>> done = {}
    >>> keep = lambda job, lo, hi, records: done.update({(lo, hi): records["force_N"]})
    >>> run_on_dask(model, [(job, 0, 2), (job, 2, 3)], cluster.scheduler_address, None, keep)
    >>> sorted(done), done[(2, 3)].shape
    ([(0, 2), (2, 3)], (1, 3))
    >>> cluster.close()
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> run_on_dask(cube, [(job, 0, 3)], "local", 1, keep)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: a model built in memory cannot go to Dask workers: ...
    >>> folder.cleanup()
    """
    source, references = _source_of(model), _references(model)
    client = connect(scheduler, workers)
    from dask.distributed import as_completed  # importable: connect checked it

    try:
        futures = {
            client.submit(_remote_chunk, source, references, job.setup, job.inputs[lo:hi], pure=False): (
                job,
                lo,
                hi,
            )
            for job, lo, hi in pending
        }
        for future in as_completed(futures, loop=client.loop):  # not the default client: it has none
            job, lo, hi = futures[future]
            finished(job, lo, hi, future.result())
    finally:
        _close(client)


def timed_on_local_cluster(model: Model, pending: list[Pending], workers: int) -> tuple[float, list[Records]]:
    r"""Time ``pending`` chunks on a new local cluster of ``workers`` one-thread workers.

    The clock starts once every worker has the model and what each job's first attitude makes
    (one-attitude chunks of every job run on each worker first), so the time is that of the chunks
    alone; ``sunwind bench`` uses it to measure how the work scales.

    Parameters
    ----------
    model : Model
        A model loaded from files.
    pending : list of (Job, int, int)
        The chunks to time.
    workers : int
        Worker processes.

    Returns
    -------
    seconds : float
        Wall time of the chunks [s].
    records : list of Records
        The chunks' records, in the order of ``pending``.

    Raises
    ------
    InputError
        A model built in memory, or Dask missing.

    Examples
    --------
    Starting a worker process takes a few seconds:

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.tables.jobs import Job, SrpSetup
    >>> folder = tempfile.TemporaryDirectory()
    >>> obj = pathlib.Path(folder.name) / "tetra.obj"  # workers load the model from its file
    >>> _ = obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> model = sw.load(obj, uniform=black, threads=1)
    >>> job = Job(SrpSetup(reflections="none"), np.eye(3))
    >>> from sunwind.forces.tables.cluster import timed_on_local_cluster
    >>> seconds, records = timed_on_local_cluster(model, [(job, 0, 3)], 1)
    >>> records[0]["force_N"].shape
    (3, 3)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> timed_on_local_cluster(cube, [(job, 0, 3)], 1)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: a model built in memory cannot go to Dask workers: ...
    >>> folder.cleanup()
    """
    source, references = _source_of(model), _references(model)
    client = connect("local", workers)
    try:
        firsts: dict[int, tuple[Job, int]] = {}
        for job, lo, _ in pending:
            firsts.setdefault(id(job), (job, lo))
        warm = [
            client.submit(
                _remote_chunk,
                source,
                references,
                job.setup,
                job.inputs[lo : lo + 1],
                pure=False,
                workers=[w],
            )
            for w in client.scheduler_info()["workers"]
            for job, lo in firsts.values()
        ]
        client.gather(warm)  # waited for; the one-attitude results are dropped
        start = time.perf_counter()
        futures = [
            client.submit(_remote_chunk, source, references, job.setup, job.inputs[lo:hi], pure=False)
            for job, lo, hi in pending
        ]
        results = client.gather(futures)
        return time.perf_counter() - start, results
    finally:
        _close(client)


def _close(client) -> None:
    cluster = client.cluster
    client.close()
    if cluster is not None:
        cluster.close()
