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
    """SHA-256 over the source of the packages that compute forces: a checkpoint made by other code
    (an upgrade, a local edit) is not resumed."""
    top = Path(__file__).resolve().parents[2]  # the sunwind package: this is forces/tables/checkpoint.py
    digest = hashlib.sha256()
    for package in ("geometry", "forces"):
        for path in sorted((top / package).rglob("*.py")):
            digest.update(path.relative_to(top).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def jsonable(value):
    """Settings as plain JSON types (paths and arrays as text and lists)."""
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
    """What a sweep is, field by field: a checkpoint is resumed only by a sweep with the same one."""
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
    """SHA-256 of a job's inputs: the bytes of an array, or the name, shape and float64 bytes of every
    column of a record of arrays (an orbit's steps), its other fields (the epoch) by their text.

    Examples
    --------
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

    Raises
    ------
    InputError
        ``directory`` is a file.
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
    :attr:`refused` count the chunks taken up and those found but not taken.
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

        Raises
        ------
        InputError
            A checkpoint is there and ``resume`` is off; or it is of a different sweep, or unreadable.
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
        """Finished chunks a checkpoint directory holds (0 where there is none)."""
        return len(list(directory.glob("*.npz"))) if directory.is_dir() else 0

    def _path(self, kind: str, lo: int) -> Path:
        return self.directory / f"{kind}-{lo:08d}.npz"

    def load(self, job: Job, lo: int, hi: int) -> Records | None:
        """The records of a finished chunk of this sweep; None when it is not there, damaged, of other
        settings or edited (counted in :attr:`refused`)."""
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
        """Keep a finished chunk with its signature (written to a temporary file, then renamed)."""
        path = self._path(job.kind, lo)
        temporary = path.with_name(f".{path.stem}.tmp.npz")
        signature = {"settings_sha256": self.settings_sha256, "data_sha256": data_digest(job, lo, records)}
        np.savez(temporary, **records, **{key: np.array(value) for key, value in signature.items()})
        os.replace(temporary, path)
        self.saved += 1

    def summary(self, computed: int) -> str | None:
        """What a resumed checkpoint gave, one line (None when it gave nothing and refused nothing)."""
        if not (self.kept or self.refused):
            return None
        refused = f" ({self.refused} of them found but of other settings or edited)" if self.refused else ""
        return f"checkpoint: kept {self.kept} chunks, recomputing {computed}{refused}"

    def remove(self) -> None:
        """Delete the checkpoint (once the table is made, or after a start that saved nothing) and
        let it go."""
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
    """SHA-256 of a chunk: its kind, first index, and every field's name, shape and float64 bytes."""
    digest = hashlib.sha256(f"{job.kind}:{lo}".encode())
    for name in job.fields:
        values = np.ascontiguousarray(records[name], dtype=np.float64)
        digest.update(f"{name}{values.shape}".encode())
        digest.update(values.tobytes())
    return digest.hexdigest()


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path`` and rename it into place."""
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_bytes(data)
    os.replace(temporary, path)
