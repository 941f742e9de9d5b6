"""The spacecraft model: checked triangles in the body frame, with parts, sides and their materials."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry import triangles as tri
from sunwind.geometry.articulation import (
    Hinge,
    check_bodies,
    checked_angle,
    detached,
    part_groups,
    turned,
    with_fronts,
)
from sunwind.geometry.cache import ModelCache
from sunwind.geometry.checks import check_mesh, size_notice, undeclared_sheets
from sunwind.geometry.errors import InputError, MaterialError, SunwindError, combine
from sunwind.geometry.materials import (
    Material,
    MaterialSpec,
    MaterialTable,
    ThermalRule,
    load_materials,
    part_matches,
    unmatched_thermal,
)
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.scene import RayScene
from sunwind.geometry.sides import ONE_SIDED, SOLID, TWO_SIDED, assign_sides, declared_kinds

#: :meth:`Spacecraft.struck_sides` of a ray that left the model.
ESCAPED = -1
#: :meth:`Spacecraft.struck_sides` of a ray that met a side the model does not have (a closed body's
#: inside, a one-sided sheet's back): absorbed there.
BLIND = -2


#: Name of the torque reference point that the materials file's ``[model] centre_of_mass_m`` gives.
CENTRE_OF_MASS = "centre of mass (materials file)"


def _frozen(array: NDArray) -> NDArray:
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False, repr=False)
class Spacecraft:
    """Triangulated spacecraft in its body frame, SI units (METHOD.md "Frames, units and signs").

    A facet has one or two *sides* (METHOD.md "Surfaces and sides"). A facet of a closed body, or of a
    one-sided sheet, has one side facing along its outward normal; a two-sided sheet (a solar-array wing of
    zero thickness) has a front side along the facet normal and a back side opposite, each with its own
    material. Physics works on sides; ray casting on facets. Build one with :func:`build_spacecraft` or
    :func:`load_spacecraft`.

    Attributes
    ----------
    vertices : (n_vertices, 3) float64
        Vertex positions [m].
    faces : (n_facets, 3) int64
        Vertex indices, counter-clockwise seen from the front.
    facet_part : (n_facets,) int32
        Index into ``part_names``.
    part_names : tuple of str
        Names of the mesh parts.
    facet_kind : (n_facets,) int8
        ``SOLID``, ``ONE_SIDED`` or ``TWO_SIDED`` (see :mod:`sunwind.geometry.sides`).
    side_facet : (n_sides,) int64
        Facet of each side.
    side_sign : (n_sides,) float64
        +1 for a front side, -1 for a back side.
    side_material : (n_sides,) int32
        Index into ``materials``.
    materials : MaterialTable
        The materials the sides use.
    part_materials : dict of str -> str
        Part name -> its material assignment, in words (for ``sunwind info``).
    source : str
        File the model came from.
    unit : str
        Length unit of the file and how it was chosen, e.g. "mm (--unit)".
    notices : tuple of str
        Repairs made on loading (degenerate triangles dropped, winding fixed, cracks closed) and remarks.
    centre_of_mass_m : (3,) float64 or None
        Centre of mass [m] from the materials file: the default torque reference; hinges do not move it.
    hinges : tuple of Hinge
        Articulations of parts (materials file ``[articulation]``), bound by :func:`articulate`.
    pose_deg : tuple of float
        Angle [deg] of each hinge in this geometry; empty when the model has no hinges.
    drawn_vertices : (n_vertices, 3) float64 or None
        Vertex positions [m] with every hinge at 0, from which every pose is turned; None without hinges.
    materials_source : str or None
        The materials file the model was built with; None without one.
    thermal : tuple of ThermalRule
        The materials file's ``[thermal."GLOB"]`` rules, in order (the first matching a part applies).
    cache : ModelCache
        What is built once for this model and kept (ray scene, view factors, ...): ``cache.entries()``
        lists it, ``cache.clear()`` frees it. A ``dataclasses.replace`` copy or a pickle starts empty.

    Examples
    --------
    >>> from sunwind.geometry import Material
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("paint", 0.3, 0.1))
    >>> craft
    <Spacecraft '<box>': 12 facets, 12 sides, 1 parts, 1 materials>
    >>> craft.total_area, craft.volume, craft.is_closed
    (6.0, 1.0, True)
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    facet_part: NDArray[np.int32]
    part_names: tuple[str, ...]
    facet_kind: NDArray[np.int8]
    side_facet: NDArray[np.int64]
    side_sign: NDArray[np.float64]
    side_material: NDArray[np.int32]
    materials: MaterialTable
    part_materials: dict[str, str]
    source: str = "<memory>"
    unit: str = "m"
    notices: tuple[str, ...] = ()
    centre_of_mass_m: NDArray[np.float64] | None = None
    hinges: tuple[Hinge, ...] = ()
    pose_deg: tuple[float, ...] = ()
    drawn_vertices: NDArray[np.float64] | None = None
    materials_source: str | None = None
    thermal: tuple[ThermalRule, ...] = ()
    cache: ModelCache = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.centre_of_mass_m is not None:
            object.__setattr__(
                self, "centre_of_mass_m", _frozen(np.array(self.centre_of_mass_m, dtype=float))
            )
        for array in (self.vertices, self.faces, self.facet_part, self.facet_kind, self.drawn_vertices):
            if array is not None:
                _frozen(array)
        for array in (self.side_facet, self.side_sign, self.side_material):
            _frozen(array)
        object.__setattr__(self, "cache", ModelCache())

    def __getstate__(self) -> dict:
        """Pickled without the cache: Embree scenes do not pickle, and a copy rebuilds what it needs."""
        return {key: value for key, value in self.__dict__.items() if key != "cache"}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        object.__setattr__(self, "cache", ModelCache())

    def __repr__(self) -> str:
        return (
            f"<Spacecraft {self.source!r}: {self.n_facets} facets, {self.n_sides} sides, "
            f"{len(self.part_names)} parts, {len(self.materials)} materials>"
        )

    # --- facets -------------------------------------------------------------------------------------
    @property
    def n_facets(self) -> int:
        """Number of triangles of the mesh."""
        return len(self.faces)

    @property
    def n_sides(self) -> int:
        """Number of sides: one per facet of a closed part, two per facet of a two-sided sheet."""
        return len(self.side_facet)

    @cached_property
    def triangles(self) -> NDArray[np.float64]:
        """Facet corners [m], (n_facets, 3, 3)."""
        return _frozen(self.vertices[self.faces])

    @cached_property
    def facet_normals(self) -> NDArray[np.float64]:
        """Unit normals of the facets' front sides, (n_facets, 3)."""
        return _frozen(tri.normals(self.triangles))

    @cached_property
    def facet_areas(self) -> NDArray[np.float64]:
        """Facet areas [m^2], (n_facets,)."""
        return _frozen(tri.areas(self.triangles))

    @cached_property
    def facet_centroids(self) -> NDArray[np.float64]:
        """Facet centroids [m], (n_facets, 3)."""
        return _frozen(tri.centroids(self.triangles))

    # --- sides --------------------------------------------------------------------------------------
    @cached_property
    def side_normals(self) -> NDArray[np.float64]:
        """Outward unit normal of each side, ``n_out`` of METHOD.md, (n_sides, 3)."""
        return _frozen(self.facet_normals[self.side_facet] * self.side_sign[:, None])

    @cached_property
    def side_areas(self) -> NDArray[np.float64]:
        """Area of each side [m^2], (n_sides,)."""
        return _frozen(self.facet_areas[self.side_facet])

    @cached_property
    def side_optics(self) -> NDArray[np.float64]:
        """``(rho, beta, sigma)`` of each side's material, (n_sides, 3), contiguous for kernels."""
        m = self.materials
        material = self.side_material
        return _frozen(
            np.ascontiguousarray(np.stack([m.rho[material], m.beta[material], m.sigma[material]], 1))
        )

    @cached_property
    def side_emissivity(self) -> NDArray[np.float64]:
        """Infrared emissivity of each side's material [-], NaN where it has none, (n_sides,)."""
        return _frozen(self.materials.eps[self.side_material])

    @cached_property
    def side_gas(self) -> dict[str, NDArray]:
        """Gas-surface parameters of each side's material, arrays (n_sides,): ``code`` (int8 index into
        :data:`sunwind.geometry.materials.GSI_MODELS`), ``energy_accommodation``, ``normal_accommodation``,
        ``tangential_accommodation`` [-] and ``wall_temperature_K`` [K]."""
        m = self.materials
        fields = ("energy_accommodation", "normal_accommodation", "tangential_accommodation")
        columns = {"code": m.gas_column("code").astype(np.int8)}
        columns.update({f: m.gas_column(f).astype(np.float64) for f in (*fields, "wall_temperature_K")})
        return {name: _frozen(np.ascontiguousarray(col[self.side_material])) for name, col in columns.items()}

    @cached_property
    def side_centroids(self) -> NDArray[np.float64]:
        """Centroid of each side [m], (n_sides, 3)."""
        return _frozen(self.facet_centroids[self.side_facet])

    @cached_property
    def side_neighbours(self) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """Pairs of sides ``(a, b)`` whose facets share an edge and which face the same way, a < b."""
        edges = self.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
        keys = edges.min(axis=1) * len(self.vertices) + edges.max(axis=1)
        owner = np.repeat(np.arange(self.n_facets), 3)
        order = np.argsort(keys, kind="stable")
        keys, owner = keys[order], owner[order]
        runs = np.flatnonzero(np.r_[True, keys[1:] != keys[:-1], True])
        starts, lengths = runs[:-1], np.diff(runs)
        longest = int(lengths.max()) if len(lengths) else 0
        # every pair of facets within a run of equal edge keys (two on a manifold edge)
        pairs = [np.zeros((0, 2), dtype=np.int64)] + [
            np.column_stack([owner[starts[lengths > j] + i], owner[starts[lengths > j] + j]])
            for i in range(longest)
            for j in range(i + 1, longest)
        ]
        facet_pairs = np.unique(np.sort(np.concatenate(pairs), axis=1), axis=0)
        side_of = {sign: np.full(self.n_facets, -1) for sign in (1.0, -1.0)}
        for sign in side_of:
            mask = self.side_sign == sign
            side_of[sign][self.side_facet[mask]] = np.flatnonzero(mask)
        a = np.concatenate([side_of[s][facet_pairs[:, 0]] for s in side_of])
        b = np.concatenate([side_of[s][facet_pairs[:, 1]] for s in side_of])
        keep = (a >= 0) & (b >= 0)
        return _frozen(a[keep]), _frozen(b[keep])

    @cached_property
    def facet_sides(self) -> NDArray[np.int64]:
        """Front and back side of each facet, (n_facets, 2); -1 where the facet has no such side."""
        sides = np.full((self.n_facets, 2), -1, dtype=np.int64)
        sides[self.side_facet, (self.side_sign < 0).astype(np.int64)] = np.arange(self.n_sides)
        return _frozen(sides)

    def struck_sides(self, facets: NDArray, directions: NDArray) -> NDArray[np.int64]:
        """The side that rays travelling along ``directions`` (n, 3) strike on ``facets`` (n,).

        A ray meets the front side where it travels against the facet normal, else the back side.
        Returns ``ESCAPED`` (-1) where ``facets`` is -1 (the ray left the model) and ``BLIND`` (-2)
        where the struck side is no side of the model: the inside of a closed body or the back of a
        one-sided sheet, which absorb whatever reaches them.
        """
        facets = np.asarray(facets, dtype=np.int64)
        hit = facets >= 0
        out = np.full(len(facets), ESCAPED, dtype=np.int64)
        f = facets[hit]
        back = np.einsum("nd,nd->n", self.facet_normals[f], directions[hit]) > 0
        side = self.facet_sides[f, back.astype(np.int64)]
        out[hit] = np.where(side >= 0, side, BLIND)
        return out

    # --- whole body ---------------------------------------------------------------------------------
    @property
    def is_closed(self) -> bool:
        """True when every facet belongs to a closed body (no sheets)."""
        return bool(np.all(self.facet_kind == SOLID))

    @cached_property
    def total_area(self) -> float:
        """Area of all facets, each counted once [m^2]."""
        return float(self.facet_areas.sum())

    @cached_property
    def volume(self) -> float | None:
        """Enclosed volume [m^3] of a closed model, else None."""
        return tri.signed_volume(self.triangles) if self.is_closed else None

    @cached_property
    def default_reference(self) -> tuple[NDArray[np.float64], str]:
        """Default torque reference point [m] and its name (METHOD.md "Frames, units and signs").

        The centre of mass of the materials file ("centre of mass (materials file)"), else the volume
        centroid of a closed model ("volume centroid (default)"), else the area centroid of its facets
        ("area centroid (default)"); the centroids of the mesh as drawn, so that they do not move with
        the hinges.
        """
        if self.centre_of_mass_m is not None:
            return self.centre_of_mass_m, CENTRE_OF_MASS
        drawn = self.triangles if self.drawn_vertices is None else self.drawn_vertices[self.faces]
        if self.is_closed:
            return tri.volume_centroid(drawn), "volume centroid (default)"
        areas = tri.areas(drawn)
        return areas @ tri.centroids(drawn) / areas.sum(), "area centroid (default)"

    @cached_property
    def bounds(self) -> NDArray[np.float64]:
        """Axis-aligned bounding box [m], (2, 3): min and max corner."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @cached_property
    def diagonal_m(self) -> float:
        """The diagonal of the model's axis-aligned box [m]: its size ``L`` where a torque too small to
        be measured against itself is measured against one the force could give, ``|F| L``."""
        return float(np.linalg.norm(np.ptp(self.vertices, axis=0)))

    @property
    def scene(self) -> RayScene:
        """The Embree scene of the facets, built on first use and kept in :attr:`cache`."""
        return self.cache.get("ray scene", lambda: RayScene(self.triangles))

    @property
    def articulation(self) -> dict[str, float]:
        """Angle [deg] of each hinge in this geometry, by its glob."""
        return {hinge.pattern: angle for hinge, angle in zip(self.hinges, self.pose_deg, strict=True)}

    @cached_property
    def facet_hinge(self) -> NDArray[np.int64]:
        """Index into :attr:`hinges` of the hinge that turns each facet, -1 for none, (n_facets,)."""
        return _frozen(_facet_groups(self, self.hinges, None))

    def part_area(self) -> dict[str, float]:
        """Area of each part [m^2]."""
        sums = np.bincount(self.facet_part, weights=self.facet_areas, minlength=len(self.part_names))
        return {name: float(a) for name, a in zip(self.part_names, sums, strict=True)}


def build_spacecraft(
    mesh: MeshData,
    materials: MaterialSpec | str | os.PathLike | None = None,
    uniform: Material | None = None,
    two_sided: Sequence[str] = (),
) -> Spacecraft:
    """Check a mesh, give its sides their materials, and build the model.

    Parameters
    ----------
    mesh : MeshData
        Triangles with parts and material keys [m].
    materials : MaterialSpec or path, optional
        Materials file (see :func:`sunwind.geometry.materials.load_materials`).
    uniform : Material, optional
        Material for every part the materials file and the mesh file leave without one.
    two_sided : sequence of str
        Part-name globs to treat as two-sided sheets, both sides with the part's material.

    Returns
    -------
    Spacecraft
        The checked model; posed at the fixed hinge angles when the materials file has hinges.

    Raises
    ------
    MaterialError
        Parts without a material, an invalid materials file, or a ``[thermal]`` glob matching no part.
    MeshError
        Non-finite coordinates; open or non-manifold surfaces that are not declared sheets. Parts
        without material and such surfaces are reported together, in one error.

    Examples
    --------
    >>> from sunwind.geometry import Material
    >>> from sunwind.meshes import plate
    >>> build_spacecraft(plate(divisions=1), uniform=Material("kapton", 0.4, 0.5), two_sided=["*"])
    <Spacecraft '<plate>': 2 facets, 4 sides, 1 parts, 1 materials>
    """
    spec = load_materials(materials) if isinstance(materials, (str, os.PathLike)) else materials
    problems: list[SunwindError] = []
    try:
        sides = assign_sides(mesh, spec, uniform, two_sided)
        face_kind = sides.face_kind
    except MaterialError as error:
        problems.append(error)
        face_kind = declared_kinds(mesh, spec, two_sided)
    check = check_mesh(mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names, face_kind, mesh.source)
    if not check.closed:
        problems.append(undeclared_sheets(check, mesh.source))
    if spec is not None:
        problems += unmatched_thermal(spec.thermal, mesh.part_names, mesh.source, spec.source)
    if problems:
        raise combine(problems)
    kind = sides.face_kind[check.kept]
    facets = np.arange(len(check.kept))
    back = kind == TWO_SIDED
    side_facet = np.concatenate([facets, facets[back]])
    side_sign = np.concatenate([np.ones(len(facets)), -np.ones(int(back.sum()))])
    side_material = np.concatenate([sides.front_material[check.kept], sides.back_material[check.kept][back]])
    craft = Spacecraft(
        vertices=check.vertices,
        faces=check.faces,
        facet_part=mesh.face_part[check.kept],
        part_names=mesh.part_names,
        facet_kind=kind,
        side_facet=side_facet,
        side_sign=side_sign,
        side_material=side_material.astype(np.int32),
        materials=sides.table,
        part_materials=sides.part_summary,
        source=mesh.source,
        unit=str(mesh.metadata.get("unit", "m")),
        notices=tuple(
            n for n in (*check.notices, size_notice(check.vertices, mesh.metadata.get("unit", "m"))) if n
        ),
        centre_of_mass_m=None if spec is None else spec.centre_of_mass_m,
        materials_source=None if spec is None else spec.source,
        thermal=() if spec is None else spec.thermal,
    )
    return craft if spec is None or not spec.hinges else articulate(craft, spec.hinges, spec.source)


def articulate(craft: Spacecraft, hinges: Sequence[Hinge], path: str | None = None) -> Spacecraft:
    """Bind hinges to the parts of a model and turn the fixed ones to their angles.

    Vertices shared across hinges are split; a tracking hinge without ``front`` gets its sheets'. Tracking
    and scheduled hinges start at 0.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    hinges : sequence of Hinge
        The articulations, e.g. from :func:`sunwind.geometry.articulation.parse_articulation`.
    path : str, optional
        The materials file the hinges come from, named in errors.

    Returns
    -------
    Spacecraft
        A new model carrying ``hinges``.

    Raises
    ------
    MaterialError
        A glob that matches no part, a part two globs match, a closed body turning would open, or a
        tracking hinge without a front.

    Examples
    --------
    >>> from sunwind.geometry import Material
    >>> from sunwind.geometry.articulation import Hinge
    >>> from sunwind.meshes import plate
    >>> craft = build_spacecraft(plate(divisions=1), uniform=Material("m", 0.3, 0.1), two_sided=["*"])
    >>> hinge = Hinge("plate", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), angle_deg=90.0)
    >>> articulate(craft, [hinge]).pose_deg
    (90.0,)
    """
    hinges = tuple(hinges)
    group = _facet_groups(craft, hinges, path)
    names = np.array(craft.part_names, dtype=object)[craft.facet_part]
    check_bodies(craft.faces, craft.facet_kind == SOLID, group, names, hinges, path)
    drawn = craft.vertices if craft.drawn_vertices is None else craft.drawn_vertices
    vertices, faces = detached(drawn, craft.faces, group)
    hinges = with_fronts(hinges, vertices[faces], group, craft.facet_kind != SOLID, path)
    bound = replace(craft, vertices=vertices, faces=faces, hinges=hinges, pose_deg=(), drawn_vertices=None)
    return pose(bound, hinges, {h.pattern: h.angle_deg for h in hinges if h.angle_deg is not None})


def pose(craft: Spacecraft, hinges: Sequence[Hinge], angles: Mapping[str, float]) -> Spacecraft:
    """Turn the parts of each hinge to an angle, from the mesh as drawn.

    Everything else stays as in ``craft``: materials, sides, centre of mass. The same angles give the same
    bits whatever pose ``craft`` is in.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    hinges : sequence of Hinge
        The hinges; ones other than ``craft.hinges`` are bound first (:func:`articulate`).
    angles : mapping of str to float
        Angle [deg] of each hinge by its glob; a hinge not named stays at 0 (as drawn).

    Returns
    -------
    Spacecraft
        A new model in the pose.

    Raises
    ------
    InputError
        An angle of no hinge, or one that is not finite.

    Examples
    --------
    >>> from sunwind.geometry import Material
    >>> from sunwind.geometry.articulation import Hinge
    >>> from sunwind.meshes import plate
    >>> craft = build_spacecraft(plate(divisions=1), uniform=Material("m", 0.3, 0.1), two_sided=["*"])
    >>> hinge = Hinge("plate", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0))
    >>> turned = pose(craft, [hinge], {"plate": 90.0})
    >>> turned.articulation, np.round(turned.facet_normals[0], 6) + 0.0
    ({'plate': 90.0}, array([1., 0., 0.]))
    """
    hinges = tuple(hinges)
    if hinges != craft.hinges:
        craft = articulate(craft, hinges)
    unknown = sorted(set(angles) - {hinge.pattern for hinge in hinges})
    if unknown:
        raise InputError(
            f'angles name "{unknown[0]}", which is no hinge of {craft.source}',
            hint=f"the hinges are: {', '.join(h.pattern for h in hinges) or 'none'}",
            parameters=("angles",),
        )
    values = tuple(
        checked_angle(angles.get(h.pattern, 0.0), f'hinge "{h.pattern}"', "angles") for h in hinges
    )
    drawn = craft.vertices if craft.drawn_vertices is None else craft.drawn_vertices
    vertex_hinge = np.full(len(drawn), -1)
    vertex_hinge[craft.faces] = craft.facet_hinge[:, None]
    vertices = turned(drawn, vertex_hinge, hinges, values)
    return replace(craft, vertices=vertices, pose_deg=values, drawn_vertices=drawn)


def _facet_groups(craft: Spacecraft, hinges: Sequence[Hinge], path: str | None) -> NDArray[np.int64]:
    """The hinge that turns each facet (-1: none); see :func:`part_groups`."""
    hits = np.array(
        [[part_matches(part, h.pattern) for part in craft.part_names] for h in hinges], dtype=bool
    )
    groups = part_groups(hits.reshape(len(hinges), -1), craft.part_names, hinges, craft.source, path)
    return groups[craft.facet_part]


def infrared_optics(craft: Spacecraft) -> NDArray[np.float64]:
    """Infrared ``(rho, beta, sigma) = (1 - eps, 0, 0)`` of each side (Kirchhoff: grey, opaque, diffuse).

    Parameters
    ----------
    craft : Spacecraft
        The model; every material its sides use needs an emissivity.

    Returns
    -------
    (n_sides, 3) float64
        Read-only ``(rho, beta, sigma)`` [-] of each side in the infrared.

    Raises
    ------
    MaterialError
        Naming the materials without an emissivity.

    Examples
    --------
    >>> from sunwind.geometry import Material
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("paint", 0.3, 0.1, emissivity=0.8))
    >>> np.round(infrared_optics(craft)[0], 6)
    array([0.2, 0. , 0. ])
    """
    return _frozen(craft.materials.infrared(craft.side_material, craft.materials_source, craft.source))


def load_spacecraft(
    path: str | os.PathLike,
    materials: MaterialSpec | str | os.PathLike | None = None,
    *,
    unit: str | None = None,
    uniform: Material | None = None,
    two_sided: Sequence[str] = (),
) -> Spacecraft:
    """Load a mesh file (STL, OBJ, PLY, glTF/GLB, USD) and build the model.

    Parameters
    ----------
    path : str or os.PathLike
        The mesh file.
    materials : MaterialSpec or path, optional
        Materials file (see :func:`sunwind.geometry.materials.load_materials`).
    unit : str, optional
        Length unit of the file (m, mm, cm, in); by default the one the file declares, else m.
    uniform : Material, optional
        Material for every part left without one.
    two_sided : sequence of str
        Part-name globs to treat as two-sided sheets.

    Returns
    -------
    Spacecraft
        The checked model, see :func:`build_spacecraft`.

    Raises
    ------
    MeshError
        An unreadable or invalid mesh file.
    MaterialError
        Parts without a material or an invalid materials file.

    Examples
    --------
    >>> from sunwind.meshes import sample_materials_path, sample_path
    >>> load_spacecraft(sample_path(), sample_materials_path())  # doctest: +ELLIPSIS
    <Spacecraft '...': ... facets, ... sides, ... parts, ... materials>
    """
    from sunwind.geometry.io import load_mesh

    return build_spacecraft(load_mesh(path, unit=unit), materials, uniform, two_sided)


__all__ = ["ONE_SIDED", "SOLID", "TWO_SIDED", "Spacecraft", "build_spacecraft", "load_spacecraft"]
