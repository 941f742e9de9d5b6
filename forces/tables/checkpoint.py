"""Finished chunks of a sweep kept on disk, so that an interrupted sweep resumes where it stopped.

A checkpoint directory holds ``manifest.json`` — what the sweep is, field by field (:func:`fingerprint`:
the mesh and materials digests, every setting, the attitudes, the sunwind version and a digest of its
code) — and one ``.npz`` file per finished chunk with its records by field name, the SHA-256 of the
manifest and a checksum of its data. Every file is written to a temporary name and renamed into place.
A checkpoint of a different sweep is refused with the fields that differ, never mixed in; a chunk whose
signature does not match (a removed manifest, an edited file) is computed again.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import zipfile
from dataclasses import asdict, fields
from importlib.metadata import version
from pathlib import Path
from typing import IO

import numpy as np

from sunwind.forces.model import Model
from sunwind.forces.tables.jobs import Inputs, Job, Records, record_shape
from sunwind.geometry.errors import InputError


def code_digest() -> str:
    """SHA-256 over the source of the packages that compute forces.

    A checkpoint made by other code (an upgrade, a local edit) is not resumed: the digest covers every
    ``.py`` file of ``geometry`` and ``forces``, by path and content.

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> from sunwind.forces.tables.checkpoint import code_digest
    >>> digest = code_digest()
    >>> len(digest), digest == code_digest()
    (64, True)
    """
    top = Path(__file__).resolve().parents[2]  # the sunwind package: this is forces/tables/checkpoint.py
    digest = hashlib.sha256()
    for package in ("geometry", "forces"):
        for path in sorted((top / package).rglob("*.py")):
            digest.update(path.relative_to(top).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def jsonable(value):
    """Turn settings into plain JSON types (paths and arrays into text and lists).

    Parameters
    ----------
    value : object
        A dict, list, tuple, array, number, string, bool or None, nested as deep as need be; anything
        else becomes its ``str``.

    Returns
    -------
    object
        The same structure of dicts (keys as text), lists, numbers, strings, bools and None.

    Examples
    --------
    >>> from pathlib import PurePosixPath
    >>> import numpy as np
    >>> from sunwind.forces.tables.checkpoint import jsonable
    >>> jsonable({"mesh": PurePosixPath("craft/bus.stl"), 1: (np.arange(2), None, 2.5)})
    {'mesh': 'craft/bus.stl', '1': [[0, 1], None, 2.5]}
    """
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, float | int | str | bool) or value is None:
        return value
    return str(value)


def fingerprint(model: Model, jobs: list[Job], chunk: int) -> dict:
    """What a sweep is, field by field: a checkpoint is resumed only by a sweep with the same one.

    Parameters
    ----------
    model : Model
        The model swept: its mesh and materials digests, how it was loaded and its reference point and
        sizes.
    jobs : list of Job
        The sweep's jobs: each one's settings (``describe``) and a digest of its inputs.
    chunk : int
        Inputs per chunk (a checkpoint's chunk files are of one size).

    Returns
    -------
    dict
        JSON-ready: ``sunwind_version``, ``code_sha256`` (:func:`code_digest`), the model's digests,
        ``chunk``, ``model``, ``references`` and, per job kind, ``KIND_settings`` and
        ``KIND_attitudes_sha256``.

    Examples
    --------

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.tables.checkpoint import Checkpoint, fingerprint
    >>> from sunwind.forces.tables.jobs import Job, SrpSetup
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> job = Job(SrpSetup(reflections="none"), np.eye(3))  # three Sun directions
    >>> manifest = fingerprint(cube, [job], chunk=2)
    >>> folder = tempfile.TemporaryDirectory()
    >>> place = pathlib.Path(folder.name) / "sweep.checkpoint"
    >>> list(manifest)[-3:]
    ['references', 'srp_settings', 'srp_attitudes_sha256']
    >>> manifest == fingerprint(cube, [job], chunk=2), manifest == fingerprint(cube, [job], chunk=3)
    (True, False)
    >>> folder.cleanup()
    """
    out: dict = {"sunwind_version": version("sunwind"), "code_sha256": code_digest(), **model.digests()}
    out["chunk"] = chunk
    source = {} if model.source is None else asdict(model.source)
    out["model"] = jsonable({key: value for key, value in source.items() if key not in ("mesh", "materials")})
    out["references"] = jsonable(
        {"reference_point_m": model.reference_point_m, "reference_sizes": model.reference_sizes}
    )
    for job in jobs:
        out[f"{job.kind}_settings"] = jsonable(job.setup.describe())
        out[f"{job.kind}_attitudes_sha256"] = inputs_digest(job.inputs)
    return out


def inputs_digest(inputs: Inputs) -> str:
    """SHA-256 of a job's inputs.

    An array is digested by its bytes; a record of arrays (an orbit's steps) by the name, shape and
    float64 bytes of every column, its other fields (the epoch) by their text.

    Parameters
    ----------
    inputs : Inputs
        An (n, 3) array of directions, or a dataclass of column arrays such as
        :class:`~sunwind.forces.orbit.inputs.StepInputs`.

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.tables.checkpoint import inputs_digest
    >>> same = inputs_digest(np.eye(3))
    >>> same == inputs_digest(np.eye(3)), same == inputs_digest(-np.eye(3))
    (True, False)
    """
    if isinstance(inputs, np.ndarray):
        return hashlib.sha256(np.ascontiguousarray(inputs).tobytes()).hexdigest()
    digest = hashlib.sha256(type(inputs).__name__.encode())
    for item in fields(inputs):
        value = getattr(inputs, item.name)
        if isinstance(value, np.ndarray):
            column = np.ascontiguousarray(value, dtype=np.float64)
            digest.update(f"{item.name}{column.shape}".encode())
            digest.update(column.tobytes())
        else:
            digest.update(f"{item.name}={value!r}".encode())
    return digest.hexdigest()


def check_place(directory: Path) -> None:
    """Refuse, before any work, a checkpoint directory whose place a file holds.

    Parameters
    ----------
    directory : Path
        Where the checkpoint is to be kept (need not exist yet).

    Raises
    ------
    InputError
        ``directory`` is a file.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from sunwind.forces.tables.checkpoint import check_place
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     check_place(pathlib.Path(folder) / "new.checkpoint")  # free: nothing said
    ...     taken = pathlib.Path(folder) / "taken"
    ...     _ = taken.write_text("")
    ...     check_place(taken)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: ...a file is where the run keeps its checkpoint directory...
    """
    if directory.exists() and not directory.is_dir():
        raise InputError(
            "a file is where the run keeps its checkpoint directory",
            path=str(directory),
            hint="move or delete that file, or name the output otherwise",
        )


class Checkpoint:
    """Finished chunks of one sweep on disk: ``manifest.json`` and one ``.npz`` per chunk.

    Every chunk file carries the SHA-256 of the sweep's manifest (:attr:`settings_sha256`) and of its
    own kind, range and data: a chunk is taken up only when both match, whether or not the manifest is
    there, so a chunk of another sweep or an edited one is computed again. :attr:`kept` and
    :attr:`refused` count the chunks taken up and those found but not taken. Open one with
    :meth:`Checkpoint.open`, which holds the directory's lock until :meth:`release` or :meth:`remove`.

    Parameters
    ----------
    directory : Path
        The checkpoint directory.
    manifest : dict
        What the sweep is (:func:`fingerprint`).
    created : bool
        Whether this run made the directory.
    lock : file object, optional
        The open, locked ``.lock`` file, held while this run writes there.

    Attributes
    ----------
    settings_sha256 : str
        SHA-256 of the manifest as canonical JSON, stamped on every chunk.
    kept, refused, saved : int
        Chunks taken up, found but not taken (damaged, edited or of other settings), and written.

    Examples
    --------
    Keep the first chunk of two, then take it up again as a resumed run would:

    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.tables.checkpoint import Checkpoint, fingerprint
    >>> from sunwind.forces.tables.jobs import Job, SrpSetup
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> job = Job(SrpSetup(reflections="none"), np.eye(3))  # three Sun directions
    >>> manifest = fingerprint(cube, [job], chunk=2)
    >>> folder = tempfile.TemporaryDirectory()
    >>> place = pathlib.Path(folder.name) / "sweep.checkpoint"
    >>> checkpoint = Checkpoint.open(place, manifest, resume=False)
    >>> checkpoint.save(job, 0, job.setup.evaluate(cube, job.inputs[0:2]))
    >>> checkpoint.release()
    >>> resumed = Checkpoint.open(place, manifest, resume=True)
    >>> resumed.load(job, 0, 2)["force_N"].shape, resumed.load(job, 2, 3)
    ((2, 3), None)
    >>> resumed.summary(computed=1)
    'checkpoint: kept 1 chunks, recomputing 1'
    >>> resumed.remove()
    >>> place.exists()
    False
    >>> folder.cleanup()
    """

    def __init__(self, directory: Path, manifest: dict, created: bool, lock: IO | None = None) -> None:
        self.directory = directory
        self._lock = lock  # held while this run writes here (see _lock)
        self.manifest = manifest
        self.created = created  # the directory was made by this run
        self.settings_sha256 = hashlib.sha256(json.dumps(manifest, sort_keys=True).encode()).hexdigest()
        self.kept = self.refused = self.saved = 0

    @classmethod
    def open(cls, directory: Path, manifest: dict, resume: bool) -> Checkpoint:
        """Start a checkpoint, or take up the one there when ``resume``.

        The directory is made if need be and locked for this run before anything else.

        Parameters
        ----------
        directory : Path
            The checkpoint directory.
        manifest : dict
            What the sweep is (:func:`fingerprint`); written as ``manifest.json``, or compared with the one
            there when resuming.
        resume : bool
            Take up a checkpoint already there.

        Returns
        -------
        Checkpoint
            The checkpoint, its lock held.

        Raises
        ------
        InputError
            A file where the directory should be; another run writing there; a checkpoint there while
            ``resume`` is off; or one of a different sweep (the fields that differ are named), or whose
            manifest cannot be read.

        Examples
        --------

        >>> import pathlib, tempfile
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.tables.checkpoint import Checkpoint, fingerprint
        >>> from sunwind.forces.tables.jobs import Job, SrpSetup
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> job = Job(SrpSetup(reflections="none"), np.eye(3))  # three Sun directions
        >>> manifest = fingerprint(cube, [job], chunk=2)
        >>> folder = tempfile.TemporaryDirectory()
        >>> place = pathlib.Path(folder.name) / "sweep.checkpoint"
        >>> first = Checkpoint.open(place, manifest, resume=False)
        >>> Checkpoint.open(place, manifest, resume=True)  # the first still holds the lock
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: ...another sunwind run is writing this checkpoint now...
        >>> first.release()
        >>> Checkpoint.open(place, manifest | {"chunk": 5}, resume=True)
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: ...the checkpoint is of a different sweep: chunk differ...
        >>> folder.cleanup()
        """
        check_place(directory)
        created = not directory.exists()
        directory.mkdir(parents=True, exist_ok=True)
        lock = _lock(directory)  # first: a checkpoint another run is writing is not "unfinished"
        try:
            if not (created or resume):
                raise InputError(
                    "a checkpoint of an unfinished sweep is there",
                    path=str(directory),
                    hint="continue it with resume, or delete the directory to start over",
                    parameters=("resume",),
                )
            return cls._taken_up(directory, manifest, resume, created, lock)
        except BaseException:
            lock.close()
            raise

    @classmethod
    def _taken_up(cls, directory: Path, manifest: dict, resume: bool, created: bool, lock: IO) -> Checkpoint:
        """The checkpoint of :meth:`open` once its lock is held."""
        found = directory / "manifest.json"
        if resume and found.exists():
            try:
                previous = json.loads(found.read_text())
            except (OSError, ValueError) as error:
                raise InputError(
                    f"the checkpoint manifest cannot be read ({error})",
                    path=str(found),
                    hint="delete the checkpoint directory to start over",
                ) from None
            differ = [
                key for key in sorted(set(manifest) | set(previous)) if manifest.get(key) != previous.get(key)
            ]
            if differ:
                raise InputError(
                    f"the checkpoint is of a different sweep: {', '.join(differ)} differ",
                    path=str(directory),
                    hint="resume with the same mesh, materials, settings and attitudes, or delete it",
                )
            return cls(directory, manifest, created=False, lock=lock)
        write_atomic(found, json.dumps(manifest, indent=1).encode())
        return cls(directory, manifest, created, lock=lock)

    @staticmethod
    def kept_chunks(directory: Path) -> int:
        """Finished chunks a checkpoint directory holds (0 where there is none).

        Parameters
        ----------
        directory : Path
            The checkpoint directory.

        Returns
        -------
        int
            The number of ``.npz`` chunk files, checked or not.
        """
        return len(list(directory.glob("*.npz"))) if directory.is_dir() else 0

    def _path(self, kind: str, lo: int) -> Path:
        return self.directory / f"{kind}-{lo:08d}.npz"

    def load(self, job: Job, lo: int, hi: int) -> Records | None:
        """The records of a finished chunk of this sweep, or None.

        None when the chunk is not there, or is damaged, of other settings or edited (counted in
        :attr:`refused`); a chunk taken up is counted in :attr:`kept`.

        Parameters
        ----------
        job : Job
            The job the chunk belongs to (its kind and fields).
        lo, hi : int
            The chunk's index range ``[lo, hi)``.

        Returns
        -------
        Records or None
            One array per field of ``job``, ``hi - lo`` rows.
        """
        path = self._path(job.kind, lo)
        if not path.exists():
            return None
        records = self._read(path, job, lo, hi)
        if records is None:
            self.refused += 1
        else:
            self.kept += 1
        return records

    def _read(self, path: Path, job: Job, lo: int, hi: int) -> Records | None:
        try:
            with path.open("rb") as handle, np.load(handle, allow_pickle=False) as kept:
                stored = {name: kept[name] for name in kept.files}
        except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
            return None
        records = {name: stored[name] for name in job.fields if name in stored}
        for name, width in job.fields.items():
            shape = record_shape(width, hi - lo)
            if name not in records or records[name].shape != shape or records[name].dtype != np.float64:
                return None
        signature = (str(stored.get("settings_sha256", "")), str(stored.get("data_sha256", "")))
        if signature != (self.settings_sha256, data_digest(job, lo, records)):
            return None
        return records

    def save(self, job: Job, lo: int, records: Records) -> None:
        """Keep a finished chunk with its signature (written to a temporary file, then renamed).

        Parameters
        ----------
        job : Job
            The job the chunk belongs to.
        lo : int
            The chunk's first index.
        records : Records
            The chunk's records, one array per field of ``job``.
        """
        path = self._path(job.kind, lo)
        temporary = path.with_name(f".{path.stem}.tmp.npz")
        signature = {"settings_sha256": self.settings_sha256, "data_sha256": data_digest(job, lo, records)}
        np.savez(temporary, **records, **{key: np.array(value) for key, value in signature.items()})
        os.replace(temporary, path)
        self.saved += 1

    def summary(self, computed: int) -> str | None:
        """What a resumed checkpoint gave, one line (None when it gave nothing and refused nothing).

        Parameters
        ----------
        computed : int
            Chunks the run computes afresh.

        Returns
        -------
        str or None
            ``"checkpoint: kept K chunks, recomputing C"``, with the count refused.
        """
        if not (self.kept or self.refused):
            return None
        refused = f" ({self.refused} of them found but of other settings or edited)" if self.refused else ""
        return f"checkpoint: kept {self.kept} chunks, recomputing {computed}{refused}"

    def remove(self) -> None:
        """Delete the checkpoint and let it go (the table is made, or a start saved nothing)."""
        shutil.rmtree(self.directory, ignore_errors=True)
        self.release()

    def release(self) -> None:
        """Let the checkpoint go: another run may take it up (resume) from now on."""
        if self._lock is not None:
            self._lock.close()  # closing the file drops its lock
            self._lock = None


def _lock(directory: Path) -> IO:
    """The checkpoint's lock file, open and exclusively locked (``flock``) for as long as this run writes
    there; the system drops the lock when the file is closed or the process ends, killed or not, so a
    lock is never left behind. Where ``fcntl`` is missing (Windows) the file is opened, not locked.

    Raises
    ------
    InputError
        Another run holds it: two sweeps writing one checkpoint would take each other's chunks and
        delete the directory under each other.
    """
    handle = (directory / ".lock").open("a")
    try:
        import fcntl
    except ImportError:  # Windows
        return handle
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        handle.close()
        raise InputError(
            "another sunwind run is writing this checkpoint now",
            path=str(directory),
            hint="wait for it to end, or give this run another output (-o)",
        ) from None
    return handle


def data_digest(job: Job, lo: int, records: Records) -> str:
    """SHA-256 of a chunk: its kind, first index, and every field's name, shape and float64 bytes.

    Parameters
    ----------
    job : Job
        The chunk's job (its kind and fields, in order).
    lo : int
        The chunk's first index.
    records : Records
        The chunk's records.

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.tables.checkpoint import data_digest
    >>> from sunwind.forces.tables.jobs import Job, SrpSetup, empty_records
    >>> job = Job(SrpSetup(), np.eye(3))
    >>> records = {name: np.zeros_like(values) for name, values in empty_records(job.fields, 2).items()}
    >>> data_digest(job, 0, records) == data_digest(job, 2, records)  # the place counts
    False
    """
    digest = hashlib.sha256(f"{job.kind}:{lo}".encode())
    for name in job.fields:
        values = np.ascontiguousarray(records[name], dtype=np.float64)
        digest.update(f"{name}{values.shape}".encode())
        digest.update(values.tobytes())
    return digest.hexdigest()


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path`` and rename it into place.

    A reader sees the old file or the whole new one, never a part.

    Parameters
    ----------
    path : Path
        The file to write (replaced if it exists).
    data : bytes
        Its new content.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from sunwind.forces.tables.checkpoint import write_atomic
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "manifest.json"
    ...     write_atomic(path, b"{}")
    ...     path.read_bytes(), [p.name for p in pathlib.Path(folder).iterdir()]
    (b'{}', ['manifest.json'])
    """
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_bytes(data)
    os.replace(temporary, path)
