"""A loaded model: the spacecraft, how it was loaded, its torque reference point and its thread count.

:func:`load` reads a mesh and its materials once; :func:`~sunwind.forces.srp.srp`,
:func:`~sunwind.forces.drag.drag` and :func:`~sunwind.forces.tables.engine.sweep` take the
:class:`Model` (or a bare :class:`~sunwind.geometry.spacecraft.Spacecraft`) and every attitude reuses
what the model keeps in its cache (``model.cache``: ray scene, shadow-ray origins, view and exchange
factors, the adjoint of the diffuse balance). :class:`ModelSource` says how to load it again, which
is what Dask workers and a table's provenance need.
"""

from __future__ import annotations

import hashlib
import json
import os
import threading
from collections import OrderedDict
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TypeVar

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.articulation import Hinge, checked_angle, fixed, schedule_angle, tracking_angle
from sunwind.geometry.cache import ModelCache
from sunwind.geometry.directions import finite_point, unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GAS_DEFAULTS, GasSurface, Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.parallel import checked_threads
from sunwind.geometry.references import check_reference_point, check_reference_sizes
from sunwind.geometry.spacecraft import Spacecraft, articulate, build_spacecraft, load_spacecraft, pose

#: Where a materials-file gas key lands on :class:`~sunwind.geometry.materials.GasSurface`.
_GAS_FIELDS = {"gsi": "model", "wall_temperature": "wall_temperature_K"}
#: Posed models a model keeps (:meth:`Model.posed`); the least recently used goes first.
KEPT_POSES = 8
#: Angles [deg] closer than this are one pose for :meth:`Model.posed`.
POSE_RESOLUTION_DEG = 1e-9
T = TypeVar("T")


@dataclass(frozen=True)
class ModelSource:
    """How to load a spacecraft: enough to load it again in another process.

    Attributes
    ----------
    mesh : str
        Mesh file (STL, OBJ, PLY, glTF/GLB, USD).
    materials : str or None
        Materials TOML file.
    unit : str or None
        Length unit of the mesh file (m, mm, cm, in); None: the file's own, else m.
    uniform : Material or None
        Material of parts the materials leave without one.
    two_sided : tuple of str
        Part globs treated as two-sided sheets.
    gas : tuple of (str, value)
        Gas-surface keys of a materials file (``gsi``, ``energy_accommodation``,
        ``normal_accommodation``, ``tangential_accommodation``, ``wall_temperature``) that override
        every material's gas law.
    articulate : tuple of (str, float)
        Hinges (``[articulation]`` globs of the materials file) held at these angles [deg], whatever
        their law in the file.

    Examples
    --------
    >>> import sunwind as sw
    >>> source = ModelSource(str(sw.meshes.sample_path()), str(sw.meshes.sample_materials_path()))
    >>> model = sw.Model(source.spacecraft(), source)
    >>> model.source.resolved() == source.resolved()
    True
    """

    mesh: str
    materials: str | None = None
    unit: str | None = None
    uniform: Material | None = None
    two_sided: tuple[str, ...] = ()
    gas: tuple[tuple[str, object], ...] = ()
    articulate: tuple[tuple[str, float], ...] = ()

    def __post_init__(self) -> None:
        if self.gas:
            GasSurface.checked("gas", dict(self.gas))
        angles = tuple(
            (str(glob), checked_angle(angle, f'articulate "{glob}"', "articulate"))
            for glob, angle in self.articulate
        )
        object.__setattr__(self, "articulate", angles)

    def spacecraft(self) -> Spacecraft:
        """Read the files into the spacecraft, with the gas overrides applied and its hinges at their
        angles.

        Returns
        -------
        Spacecraft

        Raises
        ------
        SunwindError
            A file that cannot be read, a part without a material, a value out of range.

        Examples
        --------
        >>> import sunwind as sw
        >>> source = ModelSource(str(sw.meshes.sample_path()), str(sw.meshes.sample_materials_path()))
        >>> source.spacecraft().n_facets == sw.load(source.mesh, source.materials).craft.n_facets
        True
        """
        craft = load_spacecraft(
            self.mesh, self.materials, unit=self.unit, uniform=self.uniform, two_sided=self.two_sided
        )
        return self.applied(craft)

    def applied(self, craft: Spacecraft) -> Spacecraft:
        """``craft`` with this source's held hinges (:attr:`articulate`) and gas overrides (:attr:`gas`).

        Parameters
        ----------
        craft : Spacecraft
            The spacecraft as read from the files.

        Returns
        -------
        Spacecraft
            ``craft`` itself when there is nothing to apply.

        Examples
        --------
        >>> import sunwind as sw
        >>> source = ModelSource(str(sw.meshes.sample_path()), str(sw.meshes.sample_materials_path()))
        >>> craft = source.spacecraft()
        >>> source.applied(craft) is craft
        True
        """
        if self.articulate:
            craft = articulate(
                craft, fixed(craft.hinges, dict(self.articulate), self.materials), self.materials
            )
        if not self.gas:
            return craft
        surface = GasSurface.checked("gas", dict(self.gas))
        changes = {
            _GAS_FIELDS.get(key, key): getattr(surface, _GAS_FIELDS.get(key, key)) for key, _ in self.gas
        }
        return replace(craft, materials=craft.materials.with_gas(**changes))

    def digests(self) -> dict[str, str | None]:
        """SHA-256 of the mesh file and of the materials file.

        Returns
        -------
        dict
            ``mesh_sha256`` (:func:`mesh_digest`) and ``materials_sha256`` (None without one), hex.

        Examples
        --------
        >>> import sunwind as sw
        >>> sorted(ModelSource(str(sw.meshes.sample_path())).digests())
        ['materials_sha256', 'mesh_sha256']
        """
        return {
            "mesh_sha256": mesh_digest(self.mesh),
            "materials_sha256": None if self.materials is None else file_digest(self.materials),
        }

    def resolved(self) -> ModelSource:
        """The same source with absolute file paths (for other processes and for provenance).

        Returns
        -------
        ModelSource

        Examples
        --------
        >>> import os
        >>> os.path.isabs(ModelSource("craft.obj").resolved().mesh)
        True
        """
        materials = None if self.materials is None else os.path.abspath(self.materials)
        return replace(self, mesh=os.path.abspath(self.mesh), materials=materials)

    def attributes(self) -> dict[str, object]:
        """The source as table attributes (None dropped by the writers), read back by
        :meth:`from_attributes`.

        Returns
        -------
        dict
            ``mesh``, ``materials``, ``unit``, ``two_sided`` and, when set, ``uniform_material``,
            ``gas_override`` and ``articulate``.

        Examples
        --------
        >>> source = ModelSource("craft.obj", "craft.toml", articulate=(("wing_*", 30.0),))
        >>> ModelSource.from_attributes(source.attributes()) == source
        True
        """
        attrs: dict[str, object] = {
            "mesh": self.mesh,
            "materials": self.materials,
            "unit": self.unit,
            "two_sided": ",".join(self.two_sided),
        }
        if self.uniform is not None:
            attrs["uniform_material"] = {
                "reflectivity": self.uniform.reflectivity,
                "specular_fraction": self.uniform.specular_fraction,
                "transmissivity": self.uniform.transmissivity,
            }
            if self.uniform.emissivity is not None:
                attrs["uniform_material"]["emissivity"] = self.uniform.emissivity
        if self.gas:
            attrs["gas_override"] = dict(self.gas)
        if self.articulate:
            attrs["articulate"] = dict(self.articulate)
        return attrs

    @classmethod
    def from_attributes(cls, attrs: Mapping[str, object]) -> ModelSource:
        """The source a table's attributes record (dicts may come back as JSON text).

        Parameters
        ----------
        attrs : mapping
            A table's global attributes, as :meth:`attributes` wrote them.

        Returns
        -------
        ModelSource

        Examples
        --------
        >>> ModelSource.from_attributes({"mesh": "craft.obj", "unit": "mm"}).unit
        'mm'
        """
        import json

        def mapping(value: object) -> dict:
            return json.loads(value) if isinstance(value, str) else dict(value)  # type: ignore[arg-type]

        uniform = None
        if "uniform_material" in attrs:
            uniform = Material.checked("uniform", mapping(attrs["uniform_material"]), "table")
        two_sided = tuple(glob for glob in str(attrs.get("two_sided", "")).split(",") if glob)
        gas = tuple(mapping(attrs["gas_override"]).items()) if "gas_override" in attrs else ()
        angles = tuple(mapping(attrs["articulate"]).items()) if "articulate" in attrs else ()
        materials = attrs.get("materials")
        unit = attrs.get("unit")
        return cls(
            str(attrs["mesh"]),
            None if materials is None else str(materials),
            None if unit is None else str(unit),
            uniform,
            two_sided,
            gas,
            angles,
        )


def file_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes, hex.

    Parameters
    ----------
    path : path
        Any file.

    Returns
    -------
    str
        64 hex digits.

    Examples
    --------
    >>> import sunwind as sw
    >>> len(file_digest(sw.meshes.sample_materials_path()))
    64
    """
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def mesh_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a mesh file, hex; for a USD stage that composes other files (references, payloads,
    sub-layers), of every file it reads, each named relative to the stage, so that editing any of them
    changes it.

    Parameters
    ----------
    path : path
        The mesh file.

    Returns
    -------
    str
        64 hex digits.

    Examples
    --------
    >>> import sunwind as sw
    >>> mesh_digest(sw.meshes.sample_path()) == file_digest(sw.meshes.sample_path())  # one file
    True
    """
    from sunwind.geometry.io.registry import mesh_files  # the readers, loaded when a mesh is

    path = Path(path)
    files = mesh_files(path)
    if len(files) <= 1:
        return file_digest(path)
    digest, home = hashlib.sha256(), path.resolve().parent
    for file in files:
        digest.update(f"{os.path.relpath(file, home)}\0{file_digest(file)}\n".encode())
    return digest.hexdigest()


@dataclass(frozen=True, eq=False)
class Model:
    """A spacecraft ready for attitudes: what does not change from one attitude to the next.

    Attributes
    ----------
    craft : Spacecraft
        The checked mesh with its sides and materials; owns the :attr:`cache`.
    source : ModelSource or None
        How it was loaded (None for a model built in memory: it cannot go to Dask workers).
    reference_point_m : (3,) float64 or None
        Torque reference point [m], body frame (the centre of mass); None: the materials file's
        ``[model] centre_of_mass_m``, else by default the volume centroid of a closed model, else the
        area centroid (METHOD.md "Frames, units and signs").
    reference_area_m2, reference_length_m : float or None
        Normalisation of the aerodynamic coefficients; None: a quarter of the total area (the mean
        projected area of a convex body: ``pi R^2`` for a sphere) and the largest extent of the
        bounding box.
    threads : int or None
        Threads each attitude uses; None: every core.

    ``dataclasses.replace(model, reference_point_m=...)`` gives the same model (and cache) with other
    references or threads. A model with hinges (materials file ``[articulation]``) is loaded with its
    fixed hinges at their angles and its tracking and scheduled ones at 0; :meth:`angles_at` gives every
    hinge's angle for a Sun and a time, :meth:`posed` the model at those angles.

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path(), threads=1)
    >>> model.reference()[1], model.craft.unit
    ('area centroid (default)', 'm (default)')
    """

    craft: Spacecraft
    source: ModelSource | None = None
    reference_point_m: NDArray[np.float64] | None = None
    reference_area_m2: float | None = None
    reference_length_m: float | None = None
    threads: int | None = None

    def __post_init__(self) -> None:
        if self.reference_point_m is not None:
            point = finite_point(self.reference_point_m, "reference_point_m")
            object.__setattr__(self, "reference_point_m", point)
            check_reference_point(point, self.craft)
        check_reference_sizes(self.reference_area_m2, self.reference_length_m)
        checked_threads(self.threads)

    @property
    def cache(self) -> ModelCache:
        """What is built once for this model and kept: ``cache.entries()``, ``cache.clear()``.

        Examples
        --------
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> sw.load(sw.meshes.box(), uniform=black).cache.entries()
        []
        """
        return self.craft.cache

    def reference(self, point_m: Sequence[float] | NDArray | None = None) -> tuple[NDArray[np.float64], str]:
        """The torque reference point [m] and where it came from: ``point_m``, else the model's own
        point ("user"), else the materials file's centre of mass ("centre of mass (materials file)"),
        else a default ("volume centroid (default)" or "area centroid (default)").

        Parameters
        ----------
        point_m : (3,) float, optional
            A point asked for by a call [m], body frame.

        Returns
        -------
        point : (3,) float64
        origin : str

        Examples
        --------
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black)
        >>> point, origin = cube.reference()
        >>> point.round(12).tolist(), origin
        ([0.0, 0.0, 0.0], 'volume centroid (default)')
        """
        point = self.reference_point_m if point_m is None else point_m
        if point is None:
            return self.craft.default_reference
        return finite_point(point, "reference_point_m"), "user"

    def digests(self) -> dict[str, str | None]:
        """SHA-256 of the mesh and materials files, or of the model's arrays when built in memory; with
        hinges, ``articulation_deg``: their angles as JSON text.

        Returns
        -------
        dict
            ``mesh_sha256``, ``materials_sha256`` (None in memory) and, with hinges,
            ``articulation_deg``.

        Examples
        --------
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> sw.load(sw.meshes.box(), uniform=black).digests()["materials_sha256"] is None
        True
        """
        craft = self.craft
        if self.source is not None:
            out = self.source.digests()
        else:
            digest = hashlib.sha256()
            gas = [craft.side_gas[name] for name in sorted(craft.side_gas)]
            for array in (craft.vertices, craft.faces, craft.side_facet, craft.side_optics, *gas):
                digest.update(np.ascontiguousarray(array).tobytes())
            out = {"mesh_sha256": digest.hexdigest(), "materials_sha256": None}
        return out | ({"articulation_deg": json.dumps(craft.articulation)} if craft.hinges else {})

    @property
    def hinges(self) -> tuple[Hinge, ...]:
        """The hinges that turn parts of the model (materials file, with ``articulate`` overrides).

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path())
        >>> [(hinge.pattern, hinge.law) for hinge in model.hinges]  # doctest: +ELLIPSIS
        [...]
        """
        return self.craft.hinges

    def angles_at(self, sun_body: NDArray | None = None, time_s: float | None = None) -> dict[str, float]:
        """Every hinge's angle [deg] by glob: a fixed one's own, a tracking one's that turns its front
        closest to ``sun_body`` (body frame, toward the Sun), a scheduled one's at ``time_s`` [s].

        Parameters
        ----------
        sun_body : (3,) float, optional
            Direction toward the Sun, body frame (for tracking hinges).
        time_s : float, optional
            Time [s] (for scheduled hinges).

        Returns
        -------
        dict of str to float

        Raises
        ------
        InputError
            A tracking hinge without ``sun_body``, a scheduled one without ``time_s``.
        """
        sun = None if sun_body is None else unit_vector(sun_body, "sun_body")
        angles = {}
        for hinge in self.hinges:
            if hinge.law == "fixed":
                angles[hinge.pattern] = float(hinge.angle_deg)  # type: ignore[arg-type]
            elif hinge.law == "track":
                toward = _needed(sun, hinge, "sun_body", "tracks the Sun")
                angles[hinge.pattern] = tracking_angle(hinge.axis, hinge.front, toward)  # type: ignore[arg-type]
            else:
                angles[hinge.pattern] = schedule_angle(
                    hinge, _needed(time_s, hinge, "time_s", "follows a schedule")
                )
        return angles

    def posed(self, angles: Mapping[str, float]) -> Model:
        """This model with its hinges turned to ``angles`` [deg] by glob (a hinge not named keeps its
        angle): the same references and threads, a cache of its own, and a source that holds every
        angle (a process that loads it again gets this pose). The last :data:`KEPT_POSES` poses are
        kept, so angles within :data:`POSE_RESOLUTION_DEG` of one of them give its model again, with
        what its cache holds. Without hinges, or at this model's own pose, the model itself.

        Parameters
        ----------
        angles : mapping of str to float
            Hinge globs (as in the materials file) and their angles [deg].

        Returns
        -------
        Model

        Raises
        ------
        InputError
            An angle of no hinge, or one that is not a finite number.
        """
        if not self.hinges:
            return self
        current = self.craft.articulation
        unknown = sorted(set(angles) - set(current))
        if unknown:
            raise InputError(
                f'angles name "{unknown[0]}", which is no hinge of the model',
                hint=f"the hinges are: {', '.join(current)}",
                parameters=("angles",),
            )
        wanted = current | {name: checked_angle(a, f'hinge "{name}"', "angles") for name, a in angles.items()}
        key = tuple(round(angle / POSE_RESOLUTION_DEG) for angle in wanted.values())
        if key == tuple(round(angle / POSE_RESOLUTION_DEG) for angle in current.values()):
            return self
        poses = self.craft.cache.get("posed models", _Poses)
        craft = poses.get(key, lambda: pose(self.craft, self.hinges, wanted))
        source = (
            None
            if self.source is None
            else replace(self.source, articulate=tuple(craft.articulation.items()))
        )
        return replace(self, craft=craft, source=source)

    def held(self, angles: Mapping[str, float]) -> Model:
        """This model with the hinges ``angles`` names (by glob) held at those angles [deg]: their laws,
        tracking or scheduled, become fixed, as ``--articulate`` makes them; the source records them.
        Kept per model (a sweep over hinge angles asks for each pose once per chunk).

        Parameters
        ----------
        angles : mapping of str to float
            Hinge globs and the angles [deg] to hold them at.

        Returns
        -------
        Model

        Raises
        ------
        InputError
            A name that is no hinge's glob, or an angle not finite.
        """
        if not angles:
            return self
        key = ("held model", tuple(sorted((str(k), float(v)) for k, v in angles.items())))

        def build() -> Model:
            hinges = fixed(self.hinges, angles)
            craft = articulate(self.craft, hinges)
            overrides = dict(self.source.articulate) | dict(angles) if self.source is not None else {}
            source = (
                None if self.source is None else replace(self.source, articulate=tuple(overrides.items()))
            )
            return replace(self, craft=craft, source=source)

        return self.craft.cache.get(key, build)

    def check_turnable(self, where: str, *, sun: bool, time: bool = False) -> None:
        """Refuse the hinges ``where`` cannot turn: a scheduled one without a time, a Sun-tracking one
        without a Sun direction (fixed ones always turn).

        Parameters
        ----------
        where : str
            What has no Sun or no time, for the message: ``"sunwind drag"``, ``"a drag table"``.
        sun, time : bool
            Whether ``where`` has a Sun direction and a time for the hinges' laws.

        Raises
        ------
        InputError
            The first hinge that cannot turn, with how to hold it at an angle (``articulate``).

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path(), threads=1)
        >>> model.check_turnable("sunwind srp", sun=True)  # the sample's hinges are fixed or track
        """
        for hinge in self.hinges:
            if hinge.law == "schedule" and not time:
                what, lacks, elsewhere = "follows a schedule", "time", "sunwind orbit flies schedules"
            elif hinge.law == "track" and not sun:
                what, lacks = "tracks the Sun", "Sun" if where.endswith("table") else "Sun direction"
                elsewhere = (
                    "or tabulate SRP alone" if where.endswith("table") else "srp and forces turn it to --sun"
                )
            else:
                continue
            raise InputError(
                f'[articulation] "{hinge.pattern}" {what}: {where} has no {lacks} for it',
                hint=f'hold it at an angle with articulate "{hinge.pattern}=DEG" ({elsewhere})',
                parameters=("articulate",),
            )

    @property
    def reference_sizes(self) -> tuple[float, float]:
        """Coefficient reference area [m^2] and length [m] (:attr:`reference_area_m2`,
        :attr:`reference_length_m`, or their defaults).

        Examples
        --------
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> [round(size, 12) for size in sw.load(sw.meshes.box(), uniform=black).reference_sizes]
        [1.5, 1.0]
        """
        craft = self.craft
        area = craft.total_area / 4 if self.reference_area_m2 is None else float(self.reference_area_m2)
        length = self.reference_length_m
        return area, float(np.ptp(craft.bounds, axis=0).max()) if length is None else float(length)


def _needed(value: T | None, hinge: Hinge, parameter: str, law: str) -> T:
    """``value``, the ``parameter`` the angle of ``hinge`` (which ``law``) needs; refused when None."""
    if value is None:
        raise InputError(
            f'hinge "{hinge.pattern}" {law}: its angle needs {parameter}',
            hint=f'give it, or hold the hinge at an angle (load(..., articulate={{"{hinge.pattern}": DEG}}))',
            parameters=(parameter,),
        )
    return value


class _Poses:
    """The last :data:`KEPT_POSES` posed spacecraft of a model, by their rounded angles."""

    def __init__(self) -> None:
        self._kept: OrderedDict[tuple, Spacecraft] = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key: tuple, build: Callable[[], Spacecraft]) -> Spacecraft:
        """The spacecraft kept under ``key``, else ``build()``'s, kept (dropping the oldest beyond the
        limit)."""
        with self._lock:
            if key not in self._kept:
                self._kept[key] = build()
            self._kept.move_to_end(key)
            while len(self._kept) > KEPT_POSES:
                self._kept.popitem(last=False)
            return self._kept[key]


def as_model(model: Model | Spacecraft) -> Model:
    """``model`` itself, or a :class:`Model` of a bare spacecraft (sharing its cache).

    Parameters
    ----------
    model : Model or Spacecraft

    Returns
    -------
    Model

    Raises
    ------
    InputError
        Anything else.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> model = sw.load(sw.meshes.box(), uniform=black)
    >>> as_model(model) is model, as_model(model.craft).craft is model.craft
    (True, True)
    """
    if isinstance(model, Model):
        return model
    if isinstance(model, Spacecraft):
        return Model(model)
    raise InputError(
        f"model must be a Model (sunwind.forces.load) or a Spacecraft, not {type(model).__name__}",
        parameters=("model",),
    )


def load(
    mesh: str | os.PathLike | MeshData,
    materials: str | os.PathLike | None = None,
    *,
    unit: str | None = None,
    uniform: Material | None = None,
    two_sided: Sequence[str] = (),
    gas: Mapping[str, object] | None = None,
    articulate: Mapping[str, float] | None = None,
    **model: object,
) -> Model:
    """Load a mesh file (or a mesh built in memory) and its materials as a :class:`Model`.

    Parameters
    ----------
    mesh : path or MeshData
        STL, OBJ, PLY, glTF/GLB or USD file; or a mesh of :mod:`sunwind.meshes` (in metres), whose
        model then has no ``source`` (it cannot go to Dask workers).
    materials : path, optional
        Materials TOML file (parts, materials, sheets).
    unit : str, optional
        Length unit of the file: m, mm, cm, in; default the file's own, else m.
    uniform : Material, optional
        Material of every part the materials leave without one.
    two_sided : sequence of str
        Part globs to treat as two-sided sheets.
    gas : mapping, optional
        Gas-surface keys of a materials file that override every material's gas law, e.g.
        ``{"gsi": "cll", "normal_accommodation": 0.3}``; unknown keys are refused (defaults:
        :data:`~sunwind.geometry.materials.GAS_DEFAULTS`).
    articulate : mapping, optional
        Hinges (``[articulation]`` globs of the materials file, as written) held at these angles [deg],
        whatever their law in the file, e.g. ``{"wing_*": 30.0}``.
    **model
        Fields of the :class:`Model`: ``reference_point_m``, the torque reference point [m] (the
        centre of mass; default the materials file's ``[model] centre_of_mass_m``, else as
        :class:`Model`); ``threads`` each attitude uses (default every core); ``reference_area_m2``
        and ``reference_length_m``.

    Returns
    -------
    Model

    Raises
    ------
    SunwindError
        The file cannot be read, a part has no material, or a value is out of range.

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path(), threads=1)
    >>> model.craft.n_facets > 10000
    True
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box((1.0, 1.0, 1.0)), uniform=black, threads=1)
    >>> cube.craft.n_facets, cube.source is None
    (12, True)
    """
    unknown = sorted(set(gas or {}) - set(GAS_DEFAULTS))
    if unknown:
        raise InputError(
            f"gas has no key {unknown[0]!r}",
            hint=f"the keys are {', '.join(GAS_DEFAULTS)}",
            parameters=("gas",),
        )
    in_memory = isinstance(mesh, MeshData)
    if in_memory and unit is not None:
        raise InputError("unit is the length unit of a mesh file", hint="drop unit", parameters=("unit",))
    source = ModelSource(
        "<mesh in memory>" if in_memory else str(mesh),
        None if materials is None else str(materials),
        unit,
        uniform,
        tuple(two_sided),
        tuple((gas or {}).items()),
        tuple((articulate or {}).items()),
    )
    if in_memory:
        craft = build_spacecraft(mesh, source.materials, uniform, source.two_sided)
        return Model(source.applied(craft), None, **model)  # type: ignore[arg-type]
    return Model(source.spacecraft(), source, **model)  # type: ignore[arg-type]
