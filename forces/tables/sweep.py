"""Attitude sweeps: one model, many Sun or flow directions, in checkpointed chunks, locally or on Dask.

A sweep is a set of *jobs*, one per quantity (``"srp"`` over Sun directions, ``"drag"`` over flow
directions), each a list of body-frame unit vectors cut into chunks of ``chunk`` attitudes. Every
attitude is :func:`sunwind.forces.srp.srp` or :func:`sunwind.forces.drag.drag` called exactly as the
single-attitude
commands call them, so a table entry is the same bits as ``sunwind srp``/``sunwind drag`` at that
attitude (the results do not depend on the thread count).

**Local runs** load the model once, compute the geometry precompute (view factors) once, and run the
chunks in turn; each attitude uses every core (Embree and the numba kernels are threaded).

**Checkpoints.** Every finished chunk is written at once (atomically) to a checkpoint directory with a
manifest of what the sweep is: the mesh and materials digests, every setting, the attitudes, the
sunwind version and a digest of its code. ``resume`` takes the chunks already there and computes the
rest; a checkpoint of a different sweep is refused with the reason, never mixed in.

**Dask.** With a scheduler address, or ``"local"`` for a local cluster, chunks are tasks on Dask
workers; each worker loads the model once from the same files (they must be readable there) and runs
its attitudes on one thread. Results come back to this process, which keeps the checkpoint.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field, replace
from importlib.metadata import version
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.reflection.plan import ReflectionSettings, model_view_factors
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.spacecraft import Spacecraft, load_spacecraft

#: Quantities a sweep can tabulate, each over its own direction.
KINDS = ("srp", "drag")
#: Attitudes per checkpoint chunk (and per Dask task) by default.
DEFAULT_CHUNK = 64
#: Per-attitude values a sweep records: (name, width), in record order.
SRP_FIELDS: tuple[tuple[str, int], ...] = (
    ("force_N", 3),
    ("torque_Nm", 3),
    ("direct_force_N", 3),
    ("direct_torque_Nm", 3),
    ("reflected_force_N", 3),
    ("reflected_torque_Nm", 3),
    ("lit_area_m2", 1),
    ("projected_area_m2", 1),
)
DRAG_FIELDS: tuple[tuple[str, int], ...] = (
    ("force_N", 3),
    ("torque_Nm", 3),
    ("direct_force_N", 3),
    ("direct_torque_Nm", 3),
    ("reflected_force_N", 3),
    ("reflected_torque_Nm", 3),
    ("CD", 1),
    ("CS", 1),
    ("CL", 1),
    ("CM", 3),
)
FIELDS = {"srp": SRP_FIELDS, "drag": DRAG_FIELDS}


@dataclass(frozen=True)
class ModelRecipe:
    """How to load the spacecraft: enough to rebuild it in another process.

    Attributes
    ----------
    mesh : str
        Mesh file.
    materials : str or None
        Materials TOML file.
    unit : str or None
        Length unit of the mesh file.
    uniform : Material or None
        Material of parts the materials do not cover (command-line flags).
    two_sided : tuple of str
        Part globs treated as two-sided sheets.
    gas : tuple of (str, value)
        Gas-surface flags overriding every material's gas law (keys of the TOML file).
    """

    mesh: str
    materials: str | None = None
    unit: str | None = None
    uniform: Material | None = None
    two_sided: tuple[str, ...] = ()
    gas: tuple[tuple[str, object], ...] = ()

    def load(self) -> Spacecraft:
        """The spacecraft, with the gas overrides applied."""
        craft = load_spacecraft(
            self.mesh, self.materials, unit=self.unit, uniform=self.uniform, two_sided=self.two_sided
        )
        if self.gas:
            flags = dict(self.gas)
            surface = GasSurface.checked("command line", flags)
            names = {"gsi": "model", "wall_temperature": "wall_temperature_K"}
            changes = {names.get(key, key): getattr(surface, names.get(key, key)) for key in flags}
            craft = replace(craft, materials=craft.materials.with_gas(**changes))
        return craft

    def digests(self) -> dict[str, str | None]:
        """SHA-256 of the mesh file and of the materials file."""
        return {
            "mesh_sha256": file_digest(self.mesh),
            "materials_sha256": None if self.materials is None else file_digest(self.materials),
        }


def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes, hex."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _settle_reflections(setup: SrpSetup | DragSetup) -> None:
    """A mode name given for ``reflections`` becomes :class:`ReflectionSettings`."""
    if isinstance(setup.reflections, str):
        object.__setattr__(setup, "reflections", ReflectionSettings(setup.reflections))


@dataclass(frozen=True)
class SrpSetup:
    """Settings of every SRP attitude (see :func:`sunwind.forces.srp.srp`)."""

    flux_W_m2: float
    reference_point_m: tuple[float, float, float] | None = None
    samples: int | None = None
    tolerance: float = 1e-3
    reflections: ReflectionSettings | str = field(default_factory=ReflectionSettings)

    def __post_init__(self) -> None:
        _settle_reflections(self)

    def evaluate(self, craft: Spacecraft, direction: NDArray[np.float64]) -> NDArray[np.float64]:
        """The record of :data:`SRP_FIELDS` at one Sun direction."""
        from sunwind.forces.srp import srp

        result = srp(
            craft,
            direction,
            flux_W_m2=self.flux_W_m2,
            reference_point_m=self.reference_point_m,
            samples=self.samples,
            tolerance=self.tolerance,
            reflections=self.reflections,
        )
        return np.concatenate(
            [
                result.force_N,
                result.torque_Nm,
                result.direct_force_N,
                result.direct_torque_Nm,
                result.reflected_force_N,
                result.reflected_torque_Nm,
                [result.lit_area_m2, result.projected_area_m2],
            ]
        )


@dataclass(frozen=True)
class DragSetup:
    """Settings of every drag attitude (see :func:`sunwind.forces.drag.drag`); ``v_rel = speed * u``."""

    speed_m_s: float
    atmosphere: Atmosphere
    reference_point_m: tuple[float, float, float] | None = None
    samples: int | None = None
    tolerance: float = 1e-3
    reflections: ReflectionSettings | str = field(default_factory=ReflectionSettings)
    reference_area_m2: float | None = None
    reference_length_m: float | None = None

    def __post_init__(self) -> None:
        _settle_reflections(self)

    def evaluate(self, craft: Spacecraft, direction: NDArray[np.float64]) -> NDArray[np.float64]:
        """The record of :data:`DRAG_FIELDS` at one flow direction ``u``."""
        from sunwind.forces.drag import drag

        result = drag(
            craft,
            self.speed_m_s * direction,
            self.atmosphere,
            reference_point_m=self.reference_point_m,
            samples=self.samples,
            tolerance=self.tolerance,
            reflections=self.reflections,
            reference_area_m2=self.reference_area_m2,
            reference_length_m=self.reference_length_m,
        )
        return np.concatenate(
            [
                result.force_N,
                result.torque_Nm,
                result.direct_force_N,
                result.direct_torque_Nm,
                result.reflected_force_N,
                result.reflected_torque_Nm,
                result.force_coefficients,
                result.moment_coefficients,
            ]
        )

    def describe(self) -> dict:
        """JSON-ready settings, the atmosphere in full."""
        out = asdict(replace(self, atmosphere=None))
        out["atmosphere"] = self.atmosphere.to_json()
        return out


Setup = SrpSetup | DragSetup


@dataclass(frozen=True)
class Job:
    """One quantity over its directions: ``kind`` in :data:`KINDS`, ``directions`` (n, 3) unit vectors."""

    kind: str
    directions: NDArray[np.float64]
    setup: Setup

    def chunks(self, size: int) -> list[tuple[int, int]]:
        """Index ranges ``[lo, hi)`` of the chunks."""
        n = len(self.directions)
        return [(lo, min(n, lo + size)) for lo in range(0, n, size)]


def evaluate_chunk(craft: Spacecraft, setup: Setup, directions: NDArray[np.float64]) -> NDArray[np.float64]:
    """Records (n, width) of ``directions`` (n, 3), attitude by attitude."""
    return np.array([setup.evaluate(craft, d) for d in directions])


def code_digest() -> str:
    """SHA-256 over the source of the packages that compute forces: a checkpoint made by other code
    (an upgrade, a local edit) is not resumed."""
    from sunwind import forces, geometry

    digest = hashlib.sha256()
    for package in (geometry, forces):
        root = Path(package.__file__).parent
        for path in sorted(root.rglob("*.py")):
            digest.update(path.relative_to(root.parent).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def _jsonable(value):
    """Settings as plain JSON types (paths and arrays as text and lists)."""
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, float | int | str | bool) or value is None:
        return value
    return str(value)


def fingerprint(recipe: ModelRecipe, jobs: list[Job], chunk: int) -> dict:
    """What a sweep is, field by field: a checkpoint is resumed only by a sweep with the same one."""
    out: dict = {"sunwind_version": version("sunwind"), "code_sha256": code_digest(), **recipe.digests()}
    out["chunk"] = chunk
    model = asdict(recipe)
    out["model"] = _jsonable({k: v for k, v in model.items() if k not in ("mesh", "materials")})
    for job in jobs:
        settings = job.setup.describe() if isinstance(job.setup, DragSetup) else asdict(job.setup)
        settings["reflections"] = asdict(job.setup.reflections)
        settings["reflections"].pop("cache_dir")  # where a cache lives does not change the answer
        out[f"{job.kind}_settings"] = _jsonable(settings)
        out[f"{job.kind}_attitudes_sha256"] = hashlib.sha256(job.directions.tobytes()).hexdigest()
    return out


class Checkpoint:
    """Finished chunks of one sweep on disk: ``manifest.json`` and one ``.npy`` per chunk."""

    def __init__(self, directory: Path, manifest: dict) -> None:
        self.directory = directory
        self.manifest = manifest

    @classmethod
    def open(cls, directory: Path, manifest: dict, resume: bool) -> Checkpoint:
        """Start a checkpoint, or take up the one there when ``resume``.

        Raises
        ------
        InputError
            A checkpoint is there and ``resume`` is off; or it is of a different sweep, or unreadable.
        """
        found = directory / "manifest.json"
        if directory.exists() and not resume:
            raise InputError(
                "a checkpoint of an unfinished sweep is there",
                path=str(directory),
                hint="add --resume to continue it, or delete the directory to start over",
            )
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
            return cls(directory, manifest)
        directory.mkdir(parents=True, exist_ok=True)
        _write_atomic(found, json.dumps(manifest, indent=1).encode())
        return cls(directory, manifest)

    def _path(self, kind: str, lo: int) -> Path:
        return self.directory / f"{kind}-{lo:08d}.npy"

    def load(self, kind: str, lo: int, hi: int, width: int) -> NDArray[np.float64] | None:
        """The records of a finished chunk, None when it is not there (or is damaged)."""
        path = self._path(kind, lo)
        if not path.exists():
            return None
        try:
            records = np.load(path, allow_pickle=False)
        except (OSError, ValueError):
            return None
        return records if records.shape == (hi - lo, width) else None

    def save(self, kind: str, lo: int, records: NDArray[np.float64]) -> None:
        """Keep a finished chunk (written to a temporary file, then renamed into place)."""
        path = self._path(kind, lo)
        temporary = path.with_suffix(".tmp.npy")
        np.save(temporary, records, allow_pickle=False)
        os.replace(temporary, path)

    def remove(self) -> None:
        """Delete the checkpoint once the table is written."""
        shutil.rmtree(self.directory, ignore_errors=True)


def _write_atomic(path: Path, data: bytes) -> None:
    temporary = path.with_name(path.name + ".tmp")
    temporary.write_bytes(data)
    os.replace(temporary, path)


Progress = Callable[[int], None]


def run_sweep(
    recipe: ModelRecipe,
    jobs: list[Job],
    *,
    craft: Spacecraft | None = None,
    chunk: int = DEFAULT_CHUNK,
    checkpoint: Path | None = None,
    resume: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: Progress | None = None,
) -> dict[str, NDArray[np.float64]]:
    """Evaluate every job; records (n, width) per kind, rows in the order of the job's directions.

    Parameters
    ----------
    recipe : ModelRecipe
        The model's files and options (Dask workers load it from them).
    jobs : list of Job
    craft : Spacecraft, optional
        The model already loaded from ``recipe`` (loaded here otherwise).
    chunk : int
        Attitudes per chunk (checkpoint granularity and Dask task size).
    checkpoint : Path, optional
        Directory keeping finished chunks; None keeps nothing.
    resume : bool
        Take up the chunks a checkpoint of the same sweep holds.
    scheduler : str, optional
        Dask scheduler address, or ``"local"`` for a local cluster of ``workers`` processes.
    workers : int, optional
        Local runs: threads per attitude (default every core). Local Dask cluster: worker processes
        (default one per core), each on one thread.
    progress : callable, optional
        Called with the number of attitudes finished so far (resumed ones included).
    """
    if chunk < 1:
        raise InputError(f"--chunk {chunk} must be at least 1")
    if workers is not None and workers < 1:
        raise InputError(f"--workers {workers} must be at least 1")
    store = (
        None if checkpoint is None else Checkpoint.open(checkpoint, fingerprint(recipe, jobs, chunk), resume)
    )
    records = {job.kind: np.empty((len(job.directions), _width(job.kind))) for job in jobs}
    pending: list[tuple[Job, int, int]] = []
    done = 0
    for job in jobs:
        for lo, hi in job.chunks(chunk):
            kept = None if store is None else store.load(job.kind, lo, hi, _width(job.kind))
            if kept is None:
                pending.append((job, lo, hi))
            else:
                records[job.kind][lo:hi] = kept
                done += hi - lo
    if progress:
        progress(done)

    def finished(job: Job, lo: int, hi: int, values: NDArray[np.float64]) -> None:
        nonlocal done
        records[job.kind][lo:hi] = values
        if store is not None:
            store.save(job.kind, lo, values)
        done += hi - lo
        if progress:
            progress(done)

    if pending:
        if scheduler is None:
            _run_local(recipe, craft, pending, workers, finished)
        else:
            from sunwind.forces.tables.cluster import run_on_dask

            run_on_dask(recipe, craft, pending, scheduler, workers, finished)
    if store is not None:
        store.remove()
    return records


def _width(kind: str) -> int:
    return sum(width for _, width in FIELDS[kind])


def precompute(craft: Spacecraft, jobs: list[Job]) -> None:
    """The geometry precompute every attitude reuses (view factors, when a job may reflect), once."""
    for job in jobs:
        if job.setup.reflections.mode in ("full", "auto"):
            model_view_factors(craft, job.setup.reflections)


def _run_local(
    recipe: ModelRecipe,
    craft: Spacecraft | None,
    pending: list[tuple[Job, int, int]],
    workers: int | None,
    finished: Callable[[Job, int, int, NDArray[np.float64]], None],
) -> None:
    saved = os.environ.get("SUNWIND_THREADS")
    if workers is not None:
        os.environ["SUNWIND_THREADS"] = str(workers)
    try:
        craft = recipe.load() if craft is None else craft
        precompute(craft, [job for job, _, _ in pending])
        for job, lo, hi in pending:
            finished(job, lo, hi, evaluate_chunk(craft, job.setup, job.directions[lo:hi]))
    finally:
        if saved is None:
            os.environ.pop("SUNWIND_THREADS", None)
        else:
            os.environ["SUNWIND_THREADS"] = saved


def records_by_field(kind: str, records: NDArray[np.float64]) -> Mapping[str, NDArray[np.float64]]:
    """Split records (n, width) into named arrays, (n,) or (n, 3)."""
    out, start = {}, 0
    for name, width in FIELDS[kind]:
        block = records[:, start : start + width]
        out[name] = block[:, 0] if width == 1 else block
        start += width
    return out
