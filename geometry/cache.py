"""What is built once per model and kept with it: one named store that can be listed, sized and cleared.

Every precompute that depends on a model alone (its ray scene and shadow-ray origins, the hull
clearance, block moments, view and exchange factors, the adjoint of the diffuse balance, ...) is
made on first use through :meth:`ModelCache.get` and kept in the model's :attr:`Spacecraft.cache
<sunwind.geometry.spacecraft.Spacecraft.cache>` under a key that names it and the settings it was made
with. Nothing is kept in module globals, so a model and everything made for it go away together.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Hashable, Iterator
from dataclasses import dataclass, fields, is_dataclass
from typing import TypeVar

import numpy as np

from sunwind.geometry.progress import step

T = TypeVar("T")


@dataclass(frozen=True)
class CacheEntry:
    """Describe one kept precompute: its key, the type of its value and its size.

    Attributes
    ----------
    key : hashable
        The key it is kept under: a name, then the settings it was made with.
    kind : str
        Type name of the value kept.
    nbytes : int
        Bytes of the arrays it holds (an estimate: arrays reached through attributes, each once).

    Examples
    --------
    >>> import numpy as np
    >>> cache = ModelCache()
    >>> _ = cache.get(("plan", 4), lambda: np.zeros(10))
    >>> cache.entries()
    [CacheEntry(key=('plan', 4), kind='ndarray', nbytes=80)]
    """

    key: Hashable
    kind: str  # the type of the value kept
    nbytes: int  # bytes of the arrays it holds (estimate: arrays reached through attributes)


def step_name(key: Hashable) -> str:
    """Name the progress step that builds the value kept under a key.

    Parameters
    ----------
    key : hashable
        A cache key: a name, or a tuple whose first item is the name.

    Returns
    -------
    str
        The key, or its first item, as a string.

    Examples
    --------
    >>> step_name(("view factors", 128)), step_name("scene")
    ('view factors', 'scene')
    """
    return str(key[0] if isinstance(key, tuple) and key else key)


class ModelCache:
    """Precomputes of one model, by key.

    ``get(key, build)`` returns the value kept under ``key``, building it first if it is not there.
    Builds run one at a time (a build may ask for another, e.g. a reflection plan for the view factors
    it needs), so threads asking for the same value build it once.

    Examples
    --------
    >>> cache = ModelCache()
    >>> cache.get("answer", lambda: 42), cache.get("answer", lambda: 0)
    (42, 42)
    >>> "answer" in cache, len(cache)
    (True, 1)
    """

    def __init__(self) -> None:
        self._values: dict[Hashable, object] = {}
        self._lock = threading.RLock()

    def get(self, key: Hashable, build: Callable[[], T]) -> T:
        """Return the value kept under ``key``, building and keeping it first when it is not there.

        Parameters
        ----------
        key : hashable
            The key: a name, or a tuple of a name and the settings the value depends on.
        build : callable
            Called without arguments to make the value when it is missing; reported as a progress step.

        Returns
        -------
        object
            The kept value.

        Examples
        --------
        >>> cache = ModelCache()
        >>> cache.get(("sum", 3), lambda: sum(range(3)))
        3
        """
        try:
            return self._values[key]  # type: ignore[return-value]
        except KeyError:
            pass
        with self._lock:
            if key not in self._values:
                with step(step_name(key)):
                    self._values[key] = build()
            return self._values[key]  # type: ignore[return-value]

    def __contains__(self, key: Hashable) -> bool:
        return key in self._values

    def __len__(self) -> int:
        return len(self._values)

    def __iter__(self) -> Iterator[Hashable]:
        return iter(list(self._values))

    def entries(self) -> list[CacheEntry]:
        """List every kept value with its key, type and size.

        Returns
        -------
        list of CacheEntry
            One entry per kept value, in the order they were built.

        Examples
        --------
        >>> cache = ModelCache()
        >>> _ = cache.get("names", lambda: ["a", "b"])
        >>> [(e.key, e.kind, e.nbytes) for e in cache.entries()]
        [('names', 'list', 0)]
        """
        return [
            CacheEntry(key, type(value).__name__, _nbytes(value, set()))
            for key, value in self._values.items()
        ]

    @property
    def nbytes(self) -> int:
        """Bytes of all the arrays kept.

        Returns
        -------
        int
            The sum of :attr:`CacheEntry.nbytes` over the entries.

        Examples
        --------
        >>> import numpy as np
        >>> cache = ModelCache()
        >>> _ = cache.get("a", lambda: np.zeros(4)), cache.get("b", lambda: np.zeros((2, 2), np.float32))
        >>> cache.nbytes
        48
        """
        return sum(entry.nbytes for entry in self.entries())

    def clear(self, name: str | None = None) -> None:
        """Drop every kept value, or only those whose key is ``name`` or starts with it.

        Parameters
        ----------
        name : str or None, optional
            The name to drop; None drops everything.

        Examples
        --------
        >>> cache = ModelCache()
        >>> for key in [("plan", 1), ("plan", 2), "scene"]:
        ...     _ = cache.get(key, lambda: 0)
        >>> cache.clear("plan")
        >>> list(cache)
        ['scene']
        """
        with self._lock:
            if name is None:
                self._values.clear()
                return
            for key in list(self._values):
                if key == name or (isinstance(key, tuple) and key and key[0] == name):
                    del self._values[key]

    def __repr__(self) -> str:
        lines = [f"<ModelCache: {len(self)} entries, {self.nbytes / 1e6:.1f} MB>"]
        lines += [f"  {entry.key!r}: {entry.kind}, {entry.nbytes / 1e6:.1f} MB" for entry in self.entries()]
        return "\n".join(lines)


def _nbytes(value: object, seen: set[int]) -> int:
    """Bytes of the numpy arrays (and scipy sparse matrices) reachable from ``value`` through
    containers, dataclass fields and instance attributes, each counted once; the model is not
    followed."""
    if (
        id(value) in seen
        or isinstance(value, ModelCache)
        or isinstance(getattr(value, "cache", None), ModelCache)
    ):
        return 0  # the model itself, reached from a precompute that refers to it, is not the precompute
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        return int(value.nbytes) if value.base is None else _nbytes(value.base, seen)
    if hasattr(value, "data") and hasattr(value, "indices") and hasattr(value, "indptr"):  # CSR/CSC
        return sum(_nbytes(getattr(value, name), seen) for name in ("data", "indices", "indptr"))
    if isinstance(value, dict):
        return sum(_nbytes(v, seen) for v in value.values())
    if isinstance(value, list | tuple):
        return sum(_nbytes(v, seen) for v in value)
    if is_dataclass(value) and not isinstance(value, type):
        return sum(_nbytes(getattr(value, f.name, None), seen) for f in fields(value))
    if hasattr(value, "__dict__") and not isinstance(value, type):
        return sum(_nbytes(v, seen) for v in vars(value).values())
    return 0
