"""Disk store of geometry-only precomputations: verified ``.npz`` entries keyed by a hash of their inputs.

An entry is written atomically (a temporary file in the same directory, then ``os.replace``) and holds
its arrays, the key it was made for and a SHA-256 checksum of both. Reading checks key and checksum, and
then the values themselves (shapes, finite, shares in [0, 1], rows that balance), so a truncated,
damaged, stale or forged file is reported (a :class:`CacheWarning`) and rebuilt, never used. Cache keys
hash the model's geometry (triangles, facet kinds and sides) and the caller's settings; materials do not
enter.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import warnings
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import TypeVar

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import Spacecraft

#: Version of the entry layout; part of every key, so a new layout never reads an old file.
FORMAT_VERSION = 1
#: Environment variable naming the cache directory.
CACHE_ENV = "SUNWIND_CACHE_DIR"
#: Largest departure of a stored share from [0, 1], and of a row's balance from 1, that an entry may
#: have (computed entries balance to round-off, ~1e-15).
VALUE_TOLERANCE = 1e-9

_KEY, _CHECKSUM = "key", "checksum"
T = TypeVar("T")


class CacheEntryError(Exception):
    """A cache entry that cannot be used; ``str()`` says why: "was corrupt (...)", "was stale (...)" or
    "could not be read (...)"."""


class CacheWarning(UserWarning):
    """A cache entry could not be used and was rebuilt (the answer is the computed one)."""


def default_cache_dir() -> Path:
    """``$SUNWIND_CACHE_DIR``, else ``$XDG_CACHE_HOME/sunwind``, else ``~/.cache/sunwind``."""
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV])
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "sunwind"


def cache_directory(cache_dir: str | os.PathLike | bool | None) -> Path | None:
    """The directory ``cache_dir`` asks for: None or True -> :func:`default_cache_dir`, False -> None."""
    if cache_dir is False:
        return None
    if cache_dir is None or cache_dir is True:
        return default_cache_dir()
    return Path(cache_dir)


def geometry_key(craft: Spacecraft, settings: Mapping[str, object]) -> str:
    """SHA-256 (hex) of ``FORMAT_VERSION``, the model's geometry and ``settings`` (JSON-serialisable).

    The geometry is the facet corners (float64), facet kinds, and each side's facet and sign, in fixed
    little-endian dtypes so the key is the same on every machine.
    """
    digest = hashlib.sha256()
    digest.update(json.dumps({"format": FORMAT_VERSION, **settings}, sort_keys=True).encode())
    for array, dtype in (
        (craft.triangles, "<f8"),
        (craft.facet_kind, "<i1"),
        (craft.side_facet, "<i8"),
        (craft.side_sign, "<f8"),
    ):
        data = np.ascontiguousarray(array, dtype=dtype)
        digest.update(repr(data.shape).encode())
        digest.update(data.tobytes())
    return digest.hexdigest()


def _checksum(arrays: Mapping[str, NDArray]) -> str:
    """SHA-256 (hex) of the arrays' names, dtypes, shapes and bytes, in name order."""
    digest = hashlib.sha256()
    for name in sorted(arrays):
        data = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}:{data.dtype.str}:{data.shape}".encode())
        digest.update(data.tobytes())
    return digest.hexdigest()


def read_entry(path: Path, key: str) -> dict[str, NDArray]:
    """The arrays of the entry at ``path``, checked against ``key`` and its stored checksum.

    Raises
    ------
    FileNotFoundError
        There is no entry.
    CacheEntryError
        The file is truncated or altered ("was corrupt ..."), was made for other inputs ("was stale
        ..."), or cannot be opened ("could not be read ...").
    """
    if not path.is_file():
        raise FileNotFoundError(path)
    try:
        with np.load(path, allow_pickle=False) as stored:
            arrays = {name: stored[name] for name in stored.files}
    except (ValueError, EOFError, zipfile.BadZipFile) as error:
        raise CacheEntryError(f"was corrupt ({type(error).__name__}: {error})") from error
    except OSError as error:
        raise CacheEntryError(f"could not be read ({error})") from error
    stored_key, checksum = arrays.pop(_KEY, None), arrays.pop(_CHECKSUM, None)
    if stored_key is None or checksum is None:
        raise CacheEntryError("was corrupt (no key or checksum)")
    if str(checksum) != _checksum({_KEY: stored_key, **arrays}):
        raise CacheEntryError("was corrupt (checksum mismatch)")
    if str(stored_key) != key:
        raise CacheEntryError("was stale (made for other geometry or settings)")
    return arrays


def write_entry(path: Path, key: str, arrays: Mapping[str, NDArray]) -> None:
    """Store ``arrays`` under ``key`` at ``path`` atomically, creating the directory.

    Raises
    ------
    OSError
        The directory cannot be created or written; nothing is left behind.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    content = {_KEY: np.array(key), **arrays}
    content[_CHECKSUM] = np.array(_checksum(content))
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}-", suffix=".tmp")
    try:
        with os.fdopen(handle, "wb") as file:
            np.savez(file, **content)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def kept_on_disk(
    directory: Path,
    name: str,
    key: str,
    compute: Callable[[], T],
    encode: Callable[[T], Mapping[str, NDArray]],
    decode: Callable[[Mapping[str, NDArray], str], T],
) -> T:
    """The value the entry ``name-KEY.npz`` in ``directory`` holds (``decode(arrays, origin)``), else
    ``compute()``, stored there (``encode(value)``). ``origin`` says what happened: "cache <path>",
    "computed (stored in cache <path>)", or "computed (...)" naming a corrupt or stale entry that was
    rebuilt or a cache that could not be written; cache trouble is never an error (``value`` is a
    dataclass with an ``origin`` field)."""
    path = directory / f"{name}-{key[:32]}.npz"
    notes = []
    try:
        return decode(read_entry(path, key), f"cache {path}")
    except FileNotFoundError:
        pass
    except CacheEntryError as problem:
        notes.append(f"cache entry {path} {problem}: rebuilt")
        warnings.warn(notes[-1], CacheWarning, stacklevel=2)
    value = compute()
    try:
        write_entry(path, key, encode(value))
        notes.append(f"stored in cache {path}")
    except OSError as error:
        notes.append(f"cache {directory} not writable ({error}): not stored")
    return replace(value, origin=f"computed ({'; '.join(notes)})")


def factor_arrays(
    factors: object, columns: Mapping[str, int], numbers: tuple[str, ...]
) -> dict[str, NDArray]:
    """The arrays of a set of factors (its sparse ``matrix``, the per-side ``columns`` of widths 1 or 3,
    and the ``numbers``) for :func:`write_entry`."""
    matrix = factors.matrix  # type: ignore[attr-defined]
    arrays = {"data": matrix.data, "indices": matrix.indices, "indptr": matrix.indptr}
    arrays |= {column: getattr(factors, column) for column in columns}
    return arrays | {number: np.array(getattr(factors, number)) for number in numbers}


def factor_fields(
    arrays: Mapping[str, NDArray], n_sides: int, columns: Mapping[str, int], numbers: tuple[str, ...]
) -> dict[str, object]:
    """The fields :func:`factor_arrays` stored, checked to fit ``n_sides`` sides: ``matrix`` (CSR), the
    columns, and the numbers as Python scalars. Every value must be finite, the matrix's entries,
    the numbers and the columns of width 1 (shares: escape, blind, truncated) not negative, and the
    shares at most 1 (within :data:`VALUE_TOLERANCE`).

    Raises
    ------
    CacheEntryError
        A missing array, one of the wrong shape, or values out of range.
    """
    try:
        indptr, indices, data = arrays["indptr"], arrays["indices"], arrays["data"]
        shapes = {column: (n_sides,) if width == 1 else (n_sides, width) for column, width in columns.items()}
        fits = indptr.shape == (n_sides + 1,) and indices.shape == data.shape == (indptr[-1],)
        if not fits or any(arrays[column].shape != shape for column, shape in shapes.items()):
            raise CacheEntryError("was corrupt (arrays of the wrong shape)")
        shares = [arrays[column] for column, width in columns.items() if width == 1]
        vectors = [arrays[column] for column, width in columns.items() if width != 1]
        _check_values(
            indptr, indices, n_sides, [data, *shares, *(arrays[n] for n in numbers)], shares, vectors
        )
        matrix = scipy.sparse.csr_matrix((data, indices, indptr), shape=(n_sides, n_sides))
        fields: dict[str, object] = {"matrix": matrix, **{column: arrays[column] for column in columns}}
        return fields | {number: arrays[number].item() for number in numbers}
    except (KeyError, IndexError, ValueError, TypeError) as error:
        raise CacheEntryError(f"was corrupt ({type(error).__name__}: {error})") from error


def _check_values(
    indptr: NDArray,
    indices: NDArray,
    n_sides: int,
    positive: list[NDArray],
    shares: list[NDArray],
    vectors: list[NDArray],
) -> None:
    """Raise :class:`CacheEntryError` unless ``indptr`` and ``indices`` are a CSR structure of
    ``n_sides`` columns, every array is finite, those of ``positive`` not negative and those of
    ``shares`` at most 1."""
    structure = indptr[0] == 0 and np.all(np.diff(indptr) >= 0)
    if not structure or (len(indices) and not (0 <= indices.min() and indices.max() < n_sides)):
        raise CacheEntryError("was corrupt (matrix structure out of range)")
    values = [np.asarray(array, dtype=np.float64) for array in (*positive, *vectors)]
    if not all(np.all(np.isfinite(array)) for array in values):
        raise CacheEntryError("was corrupt (values not finite)")
    if any(np.any(array < -VALUE_TOLERANCE) for array in values[: len(positive)]):
        raise CacheEntryError("was corrupt (negative shares or factors)")
    if any(np.any(np.asarray(share, dtype=np.float64) > 1 + VALUE_TOLERANCE) for share in shares):
        raise CacheEntryError("was corrupt (a share above 1)")


def check_balance(error: NDArray[np.float64]) -> None:
    """Raise :class:`CacheEntryError` if a row's balance ``error`` (n_sides,) exceeds
    :data:`VALUE_TOLERANCE` or is not finite."""
    if not np.all(np.isfinite(error)) or np.any(error > VALUE_TOLERANCE):
        raise CacheEntryError(f"was corrupt (rows do not balance: off by up to {np.nanmax(error):.3g})")
