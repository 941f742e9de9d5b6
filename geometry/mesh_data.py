"""The triangle soup with part and material labels that every mesh loader returns and every writer takes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

#: Solar-band optical keys a mesh file may carry per material (USD ``sunwind:*`` attributes), all three
#: or none; METHOD.md "Surfaces and sides".
OPTICS_KEYS = ("reflectivity", "specular_fraction", "transmissivity")
#: Keys a mesh file may carry beside ``OPTICS_KEYS``: the infrared emissivity (USD ``sunwind:emissivity``).
OPTIONAL_OPTICS_KEYS = ("emissivity",)


@dataclass(frozen=True, eq=False)
class MeshData:
    """Triangles with part and material labels, in metres, as read from a file or built in memory.

    Nothing here is checked beyond shapes: degenerate triangles, winding, closedness and
    non-finite coordinates are judged when a :class:`sunwind.geometry.Spacecraft` is built.

    Attributes
    ----------
    vertices : (n_vertices, 3) float64
        Vertex positions [m], body frame.
    faces : (n_faces, 3) int64
        Vertex indices; counter-clockwise seen from the front (the outward side of a closed body).
    face_part : (n_faces,) int32
        Index into ``part_names`` for each face.
    part_names : tuple of str
        OBJ object/group, glTF node/mesh name, or USD prim path.
    face_material : (n_faces,) int32
        Index into ``material_names`` of the material key the file gives the face, -1 for none.
    material_names : tuple of str
        Material keys named by the file (OBJ ``usemtl``, glTF material, USD bound Material).
    file_optics : mapping str -> mapping str -> float
        Optics a file carries for some of its material keys (USD ``sunwind:reflectivity``,
        ``sunwind:specularFraction``, ``sunwind:transmissivity`` and optionally ``sunwind:emissivity``),
        keyed by ``OPTICS_KEYS`` and ``OPTIONAL_OPTICS_KEYS``.
    two_sided_parts : frozenset of str
        Parts the file itself declares as zero-thickness sheets lit on both sides (USD ``doubleSided``).
    part_back_material : mapping str -> str
        For two-sided parts, the material key of the back side when the file names one
        (USD relationship ``sunwind:backMaterial``); otherwise both sides use the face's key.
    source : str
        The file the data came from, named in every message about it.
    metadata : mapping
        Free-form provenance, e.g. a builder's parameters ``{"shape": "cylinder", "radius": 1.0}``.

    Raises
    ------
    ValueError
        When ``face_part`` or ``face_material`` has not one entry per face.

    Examples
    --------
    >>> import numpy as np
    >>> mesh = MeshData(vertices=np.eye(3), faces=[[0, 1, 2]], face_part=[0], part_names=["tri"],
    ...                 face_material=[-1])
    >>> mesh.n_faces, mesh.faces.dtype, mesh.part_names
    (1, dtype('int64'), ('tri',))
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    face_part: NDArray[np.int32]
    part_names: tuple[str, ...]
    face_material: NDArray[np.int32]
    material_names: tuple[str, ...] = ()
    file_optics: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    two_sided_parts: frozenset[str] = frozenset()
    part_back_material: Mapping[str, str] = field(default_factory=dict)
    source: str = "<memory>"
    metadata: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        vertices = np.asarray(self.vertices, dtype=np.float64).reshape(-1, 3)
        faces = np.asarray(self.faces, dtype=np.int64).reshape(-1, 3)
        object.__setattr__(self, "vertices", vertices)
        object.__setattr__(self, "faces", faces)
        object.__setattr__(self, "face_part", np.asarray(self.face_part, dtype=np.int32))
        object.__setattr__(self, "face_material", np.asarray(self.face_material, dtype=np.int32))
        object.__setattr__(self, "part_names", tuple(self.part_names))
        object.__setattr__(self, "material_names", tuple(self.material_names))
        object.__setattr__(self, "two_sided_parts", frozenset(self.two_sided_parts))
        n = len(faces)
        if self.face_part.shape != (n,) or self.face_material.shape != (n,):
            raise ValueError("face_part and face_material need one entry per face")

    @property
    def n_faces(self) -> int:
        """Number of triangles.

        Returns
        -------
        int
            ``len(faces)``.

        Examples
        --------
        >>> from sunwind.meshes import box
        >>> box().n_faces
        12
        """
        return len(self.faces)

    def scaled(self, factor: float) -> MeshData:
        """Return the same mesh with its vertex coordinates multiplied by a factor (unit conversion).

        Parameters
        ----------
        factor : float
            Scale factor, e.g. 1e-3 for a mesh drawn in millimetres.

        Returns
        -------
        MeshData
            A new mesh; everything but the vertices is shared.

        Examples
        --------
        >>> from sunwind.meshes import box
        >>> float(box().scaled(1e-3).vertices.max())
        0.0005
        """
        return MeshData(
            vertices=self.vertices * factor,
            faces=self.faces,
            face_part=self.face_part,
            part_names=self.part_names,
            face_material=self.face_material,
            material_names=self.material_names,
            file_optics=self.file_optics,
            two_sided_parts=self.two_sided_parts,
            part_back_material=self.part_back_material,
            source=self.source,
            metadata=self.metadata,
        )

    @staticmethod
    def concatenate(pieces: list[MeshData], source: str = "<memory>") -> MeshData:
        """Join meshes into one, merging part and material names; the metadata of the first is kept.

        Parameters
        ----------
        pieces : list of MeshData
            The meshes to join, in order.
        source : str, optional
            What to name the joined mesh's source.

        Returns
        -------
        MeshData
            One mesh with all the pieces' faces; parts and material keys of the same name are merged.

        Examples
        --------
        >>> from sunwind.meshes import box, plate
        >>> joined = MeshData.concatenate([box(), plate(divisions=1), box()])
        >>> joined.n_faces, joined.part_names
        (26, ('box', 'plate'))
        """
        part_names: list[str] = []
        material_names: list[str] = []
        vertices, faces, face_part, face_material = [], [], [], []
        offset = 0
        optics: dict[str, Mapping[str, float]] = {}
        two_sided: set[str] = set()
        back: dict[str, str] = {}
        for piece in pieces:
            part_map = np.array([_index_of(part_names, name) for name in piece.part_names], dtype=np.int32)
            mat_map = np.array(
                [_index_of(material_names, name) for name in piece.material_names] + [-1],
                dtype=np.int32,
            )
            vertices.append(piece.vertices)
            faces.append(piece.faces + offset)
            face_part.append(part_map[piece.face_part] if len(part_map) else piece.face_part)
            face_material.append(mat_map[piece.face_material])
            offset += len(piece.vertices)
            optics.update(piece.file_optics)
            two_sided |= piece.two_sided_parts
            back.update(piece.part_back_material)
        return MeshData(
            vertices=np.concatenate(vertices) if vertices else np.zeros((0, 3)),
            faces=np.concatenate(faces) if faces else np.zeros((0, 3), dtype=np.int64),
            face_part=np.concatenate(face_part) if face_part else np.zeros(0, dtype=np.int32),
            part_names=tuple(part_names),
            face_material=(np.concatenate(face_material) if face_material else np.zeros(0, dtype=np.int32)),
            material_names=tuple(material_names),
            file_optics=optics,
            two_sided_parts=frozenset(two_sided),
            part_back_material=back,
            source=source,
            metadata=dict(pieces[0].metadata) if pieces else {},
        )


def _index_of(names: list[str], name: str) -> int:
    """Index of ``name`` in ``names``, appending it when new."""
    if name not in names:
        names.append(name)
    return names.index(name)
