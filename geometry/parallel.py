"""Data-parallel work over index ranges on one shared thread pool, for kernels that release the GIL.

Embree queries and the numba kernels release the GIL, so threads give real speed-up. Work is cut
into chunks taken by whichever thread is free, the caller included: a pool thread that wakes late or
a chunk that costs more does not leave the others idle. A call made from inside a chunk runs
serially there, so nested calls cannot deadlock the pool. Chunk boundaries may depend on the number
of threads: a caller that sums floating-point results must sum in an order of its own.
"""

from __future__ import annotations

import itertools
import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor, wait
from typing import TypeVar

T = TypeVar("T")

#: Cores of this machine (``os.cpu_count`` reads the system each call, ~20 us).
CORES = os.cpu_count() or 1

_pool: ThreadPoolExecutor | None = None
_lock = threading.Lock()
_inside = threading.local()


def thread_count() -> int:
    """Threads to use: the ``SUNWIND_THREADS`` environment variable, else all cores."""
    return max(1, int(os.environ.get("SUNWIND_THREADS", 0)) or CORES)


def _executor() -> ThreadPoolExecutor:
    global _pool
    with _lock:
        if _pool is None:
            _pool = ThreadPoolExecutor(max(1, CORES - 1), thread_name_prefix="sunwind")
        return _pool


#: Chunks per thread: enough to even out chunks of unequal cost, few enough to keep the per-chunk
#: overhead small.
CHUNKS_PER_THREAD = 2


def map_ranges(function: Callable[[int, int], T], n: int, min_size: int) -> list[T]:
    """``[function(lo, hi) for each chunk]`` over ``range(n)``, in parallel; results in chunk order.

    At most ``CHUNKS_PER_THREAD`` chunks per thread, each of at least ``min_size`` items. Inside a
    chunk of another call, or with one thread, the whole range runs in the calling thread.
    """
    threads = thread_count()
    chunks = min(threads * CHUNKS_PER_THREAD, n // max(1, min_size))
    if chunks <= 1 or threads == 1 or getattr(_inside, "active", False):
        return [function(0, n)]
    bounds = [n * k // chunks for k in range(chunks + 1)]
    results: list = [None] * chunks
    tickets = itertools.count()  # next() on a count is atomic under the GIL

    def drain() -> None:
        _inside.active = True
        try:
            while (k := next(tickets)) < chunks:
                results[k] = function(bounds[k], bounds[k + 1])
        finally:
            _inside.active = False

    helpers = [_executor().submit(drain) for _ in range(min(threads, chunks) - 1)]
    drain()
    wait(helpers)
    for helper in helpers:
        helper.result()  # re-raise a helper's exception
    return results
