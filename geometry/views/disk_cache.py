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
    """A cache entry that cannot be used.

    ``str()`` says why: "was corrupt (...)", "was stale (...)" or "could not be read (...)".

    Examples
    --------
    >>> str(CacheEntryError("was stale (made for other geometry or settings)"))
    'was stale (made for other geometry or settings)'
    """


class CacheWarning(UserWarning):
    """A cache entry could not be used and was rebuilt (the answer is the computed one).

    Examples
    --------
    >>> issubclass(CacheWarning, UserWarning)
    True
    """


def default_cache_dir() -> Path:
    """Find the default cache directory.

    Returns
    -------
    Path
        ``$SUNWIND_CACHE_DIR``, else ``$XDG_CACHE_HOME/sunwind``, else ``~/.cache/sunwind``.

    Examples
    --------
    >>> import os
    >>> os.environ[CACHE_ENV] = "/tmp/sunwind-cache"
    >>> default_cache_dir()
    PosixPath('/tmp/sunwind-cache')
    >>> del os.environ[CACHE_ENV]
    """
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV])
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "sunwind"


def cache_directory(cache_dir: str | os.PathLike | bool | None) -> Path | None:
    """Find the directory a ``cache_dir`` argument asks for.

    Parameters
    ----------
    cache_dir : str or os.PathLike or bool or None
        None or True for :func:`default_cache_dir`, False for no cache, else the directory.

    Returns
    -------
    Path or None
        The directory, or None for no cache.

    Examples
    --------
    >>> cache_directory(False) is None, cache_directory("here")
    (True, PosixPath('here'))
    """
    if cache_dir is False:
        return None
    if cache_dir is None or cache_dir is True:
        return default_cache_dir()
    return Path(cache_dir)


def geometry_key(craft: Spacecraft, settings: Mapping[str, object]) -> str:
    """Hash ``FORMAT_VERSION``, a model's geometry and some settings into a cache key.

    The geometry is the facet corners (float64), facet kinds, and each side's facet and sign, in fixed
    little-endian dtypes so the key is the same on every machine.

    Parameters
    ----------
    craft : Spacecraft
        The model; its materials do not enter.
    settings : mapping of str to object
        The caller's settings, JSON-serialisable.

    Returns
    -------
    str
        SHA-256, hex.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> key = geometry_key(craft, {"rays_per_side": 64})
    >>> len(key), key == geometry_key(craft, {"rays_per_side": 128})
    (64, False)
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
    """Read the arrays of the entry at ``path``, checked against ``key`` and its stored checksum.

    Parameters
    ----------
    path : Path
        The ``.npz`` file.
    key : str
        The key the entry must have been made for.

    Returns
    -------
    dict of str to ndarray
        The arrays stored, without the key and checksum.

    Raises
    ------
    FileNotFoundError
        There is no entry.
    CacheEntryError
        The file is truncated or altered ("was corrupt ..."), was made for other inputs ("was stale
        ..."), or cannot be opened ("could not be read ...").

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = Path(folder.name) / "entry.npz"
    >>> write_entry(path, "abc", {"x": np.arange(3)})
    >>> read_entry(path, "abc")
    {'x': array([0, 1, 2])}
    >>> read_entry(path, "other")
    Traceback (most recent call last):
    ...
    sunwind.geometry.views.disk_cache.CacheEntryError: was stale (made for other geometry or settings)
    >>> folder.cleanup()
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
    """Store arrays under a key at ``path`` atomically, creating the directory.

    Parameters
    ----------
    path : Path
        The ``.npz`` file to write.
    key : str
        The key the entry is made for.
    arrays : mapping of str to ndarray
        The arrays to store.

    Raises
    ------
    OSError
        The directory cannot be created or written; nothing is left behind.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = Path(folder.name) / "entry.npz"
    >>> write_entry(path, "abc", {"x": np.ones(2)})
    >>> sorted(np.load(path).files)
    ['checksum', 'key', 'x']
    >>> folder.cleanup()
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
    """Read a value from its disk entry, or compute it and store it there.

    The entry is ``name-KEY.npz`` in ``directory``. The value's ``origin`` says what happened: "cache
    <path>", "computed (stored in cache <path>)", or "computed (...)" naming a corrupt or stale entry
    that was rebuilt or a cache that could not be written; cache trouble is never an error.

    Parameters
    ----------
    directory : Path
        The cache directory.
    name : str
        What the entry holds, the start of its file name.
    key : str
        Its key (:func:`geometry_key`).
    compute : callable
        ``compute()`` makes the value: a dataclass with an ``origin`` field.
    encode : callable
        ``encode(value)`` gives the arrays to store.
    decode : callable
        ``decode(arrays, origin)`` makes the value from stored arrays.

    Returns
    -------
    object
        The value, with its ``origin`` set.

    Warns
    -----
    CacheWarning
        An entry that is corrupt or stale, rebuilt.

    Examples
    --------
    >>> import tempfile
    >>> from dataclasses import dataclass
    >>> from pathlib import Path
    >>> import numpy as np
    >>> @dataclass
    ... class Value:
    ...     x: np.ndarray
    ...     origin: str = ""
    >>> folder = tempfile.TemporaryDirectory()
    >>> def keep():
    ...     return kept_on_disk(Path(folder.name), "demo", "k" * 64, lambda: Value(np.arange(2)),
    ...         lambda v: {"x": v.x}, lambda arrays, origin: Value(arrays["x"], origin))
    >>> keep().origin
    'computed (stored in cache .../demo-kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk.npz)'
    >>> keep().origin
    'cache .../demo-kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk.npz'
    >>> folder.cleanup()
    """
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
    """Collect the arrays of a set of factors for :func:`write_entry`.

    Parameters
    ----------
    factors : object
        Has a sparse ``matrix`` and the attributes named by ``columns`` and ``numbers``.
    columns : mapping of str to int
        Per-side arrays to store, with their widths (1 or 3).
    numbers : tuple of str
        Scalars to store.

    Returns
    -------
    dict of str to ndarray
        ``data``, ``indices``, ``indptr`` of the matrix, the columns and the numbers.

    Examples
    --------
    >>> import numpy as np
    >>> import scipy.sparse
    >>> from types import SimpleNamespace
    >>> factors = SimpleNamespace(matrix=scipy.sparse.csr_matrix(np.array([[0.0, 0.5], [0.25, 0.0]])),
    ...     escape=np.array([0.5, 0.75]), rays=64)
    >>> arrays = factor_arrays(factors, {"escape": 1}, ("rays",))
    >>> sorted(arrays)
    ['data', 'escape', 'indices', 'indptr', 'rays']
    """
    matrix = factors.matrix  # type: ignore[attr-defined]
    arrays = {"data": matrix.data, "indices": matrix.indices, "indptr": matrix.indptr}
    arrays |= {column: getattr(factors, column) for column in columns}
    return arrays | {number: np.array(getattr(factors, number)) for number in numbers}


def factor_fields(
    arrays: Mapping[str, NDArray], n_sides: int, columns: Mapping[str, int], numbers: tuple[str, ...]
) -> dict[str, object]:
    """Rebuild and check the fields :func:`factor_arrays` stored.

    Every value must be finite; the matrix's entries, the numbers and the columns of width 1 (shares:
    escape, blind, truncated) not negative, and the shares at most 1 (within :data:`VALUE_TOLERANCE`).

    Parameters
    ----------
    arrays : mapping of str to ndarray
        The arrays read.
    n_sides : int
        Sides of the model they must fit.
    columns : mapping of str to int
        Per-side arrays stored, with their widths.
    numbers : tuple of str
        Scalars stored.

    Returns
    -------
    dict of str to object
        ``matrix`` (CSR), the columns, and the numbers as Python scalars.

    Raises
    ------
    CacheEntryError
        A missing array, one of the wrong shape, or values out of range.

    Examples
    --------
    >>> import numpy as np
    >>> import scipy.sparse
    >>> from types import SimpleNamespace
    >>> factors = SimpleNamespace(matrix=scipy.sparse.csr_matrix(np.array([[0.0, 0.5], [0.25, 0.0]])),
    ...     escape=np.array([0.5, 0.75]), rays=64)
    >>> arrays = factor_arrays(factors, {"escape": 1}, ("rays",))
    >>> fields = factor_fields(arrays, 2, {"escape": 1}, ("rays",))
    >>> fields["matrix"].toarray(), fields["rays"]
    (array([[0.  , 0.5 ],
           [0.25, 0.  ]]), 64)
    >>> factor_fields(arrays, 3, {"escape": 1}, ("rays",))
    Traceback (most recent call last):
    ...
    sunwind.geometry.views.disk_cache.CacheEntryError: was corrupt (arrays of the wrong shape)
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
    """Refuse rows whose balance error exceeds :data:`VALUE_TOLERANCE` or is not finite.

    Parameters
    ----------
    error : (n_sides,) ndarray of float64
        Each row's departure from balance.

    Raises
    ------
    CacheEntryError
        When any row is off.

    Examples
    --------
    >>> import numpy as np
    >>> check_balance(np.array([0.0, 1e-15]))
    >>> check_balance(np.array([0.0, 0.01]))
    Traceback (most recent call last):
    ...
    sunwind.geometry.views.disk_cache.CacheEntryError: was corrupt (rows do not balance: off by up to 0.01)
    """
    if not np.all(np.isfinite(error)) or np.any(error > VALUE_TOLERANCE):
        raise CacheEntryError(f"was corrupt (rows do not balance: off by up to {np.nanmax(error):.3g})")
