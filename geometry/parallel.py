"""Data-parallel work over index ranges on one shared thread pool, for kernels that release the GIL.

Embree queries and the numba kernels release the GIL, so threads give real speed-up. Work is taken
in chunks by whichever thread is free, the caller included, with guided self-scheduling: each chunk
is the remaining work divided by the number of threads (never under a least size), so chunks start
large, which keeps the per-chunk cost low, and shrink toward the end, so threads finish together
even when items cost unequal amounts. A call made from inside a chunk runs serially there, so nested
calls cannot deadlock the pool. Chunk boundaries depend on the number of threads and on timing: a
caller that sums floating-point results must sum in an order of its own.

The number of threads is a parameter of the public calls (``srp(..., threads=2)``), which run their
work inside :func:`using_threads`; by default every core is used.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, wait
from contextlib import contextmanager
from contextvars import ContextVar
from typing import TypeVar

from sunwind.geometry.errors import InputError

T = TypeVar("T")
R = TypeVar("R")

#: Cores of this machine (``os.cpu_count`` reads the system each call, ~20 us).
CORES = os.cpu_count() or 1

_pool: ThreadPoolExecutor | None = None
_lock = threading.Lock()
_inside = threading.local()
#: Threads of the work running in this context (None: every core); set by :func:`using_threads`.
_threads: ContextVar[int | None] = ContextVar("sunwind_threads", default=None)


def checked_threads(threads: int | None, name: str = "threads") -> int | None:
    """Check a thread count: None (every core) or a whole number of at least 1.

    Parameters
    ----------
    threads : int or None
        The thread count as given.
    name : str, optional
        The parameter's name, for the message.

    Returns
    -------
    int or None
        ``threads`` unchanged.

    Raises
    ------
    InputError
        Anything else (a bool, a float, zero or less).

    Examples
    --------
    >>> checked_threads(2), checked_threads(None)
    (2, None)
    >>> checked_threads(0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: threads 0 must be a whole number >= 1
    """
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int) or threads < 1):
        raise InputError(f"{name} {threads!r} must be a whole number >= 1", parameters=(name,))
    return threads


@contextmanager
def using_threads(threads: int | None) -> Iterator[None]:
    """Run the parallel work of a ``with`` block on a given number of threads.

    Parameters
    ----------
    threads : int or None
        Threads to use; None keeps what an enclosing block set, else every core.

    Yields
    ------
    None
        Control to the block, with :func:`thread_count` set.

    Raises
    ------
    InputError
        When ``threads`` is not None or a whole number >= 1.

    Examples
    --------
    >>> with using_threads(1):
    ...     thread_count()
    1
    """
    checked_threads(threads)
    token = _threads.set(threads if threads is not None else _threads.get())
    try:
        yield
    finally:
        _threads.reset(token)


def thread_count() -> int:
    """Count the threads the work running now may use.

    Returns
    -------
    int
        What :func:`using_threads` set, else :data:`CORES`.

    Examples
    --------
    >>> with using_threads(2):
    ...     thread_count()
    2
    >>> thread_count() == CORES
    True
    """
    return _threads.get() or CORES


def _executor() -> ThreadPoolExecutor:
    global _pool
    with _lock:
        if _pool is None:
            _pool = ThreadPoolExecutor(max(1, CORES - 1), thread_name_prefix="sunwind")
        return _pool


def map_ranges(function: Callable[[int, int], T], n: int, min_size: int) -> list[T]:
    """Call ``function(lo, hi)`` on chunks of ``range(n)`` in parallel; results in range order.

    Chunks hold at least ``min_size`` items (the last may hold fewer). Inside a chunk of another
    call, with one thread, or with fewer than ``2 * min_size`` items, the whole range runs in the
    calling thread.

    Parameters
    ----------
    function : callable
        ``function(lo, hi)`` does the work of items ``lo`` to ``hi - 1``; it should release the GIL to
        gain from threads.
    n : int
        Number of items.
    min_size : int
        Least number of items in a chunk.

    Returns
    -------
    list
        The chunks' results, in the order of their ranges.

    Examples
    --------
    >>> chunks = map_ranges(lambda lo, hi: sum(range(lo, hi)), 1000, 100)
    >>> sum(chunks)
    499500
    >>> map_ranges(lambda lo, hi: (lo, hi), 10, 100)
    [(0, 10)]
    """
    threads = thread_count()
    min_size = max(1, min_size)
    if n < 2 * min_size or threads == 1 or getattr(_inside, "active", False):
        return [function(0, n)]
    cursor, lock = [0], threading.Lock()
    results: dict[int, T] = {}

    def next_chunk() -> tuple[int, int] | None:
        with lock:
            lo = cursor[0]
            if lo >= n:
                return None
            hi = min(n, lo + max(min_size, -(-(n - lo) // threads)))
            cursor[0] = hi
            return lo, hi

    def drain() -> None:
        _inside.active = True
        try:
            while (chunk := next_chunk()) is not None:
                results[chunk[0]] = function(*chunk)
        finally:
            _inside.active = False

    helpers = [_executor().submit(drain) for _ in range(threads - 1)]
    drain()
    wait(helpers)
    for helper in helpers:
        helper.result()  # re-raise a helper's exception
    return [results[lo] for lo in sorted(results)]


def map_items(function: Callable[[T], R], items: Sequence[T]) -> list[R]:
    """Call ``function(x)`` on each item, several at once; results in item order.

    The first item runs alone, on every thread (what it builds once per model, it builds in parallel),
    then the rest are shared over the threads, each run serially in its thread (the serial steps of one
    item run beside another's). Each result is what it would be alone: the work of one item sums in an
    order of its own (module docstring).

    Parameters
    ----------
    function : callable
        Called on one item.
    items : sequence
        The items.

    Returns
    -------
    list
        ``[function(x) for x in items]``.

    Examples
    --------
    >>> map_items(lambda x: x * x, [1, 2, 3])
    [1, 4, 9]
    """
    if not len(items):
        return []
    first = function(items[0])
    rest = map_ranges(lambda lo, hi: [function(x) for x in items[1 + lo : 1 + hi]], len(items) - 1, 1)
    return [first, *(r for chunk in rest for r in chunk)]
