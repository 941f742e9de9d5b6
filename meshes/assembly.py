"""Assembling meshes: built arrays wrapped as :class:`MeshData`, rigid transforms and part labels.

The builders of :mod:`sunwind.meshes.primitives` wrap their arrays with :func:`assemble`; the sample
spacecraft and the validation cases place and name the pieces with :func:`transform`, :func:`label` and
:func:`rotation_matrix`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData

__all__ = ["assemble", "label", "rotation_matrix", "transform"]


def assemble(
    vertices: ArrayLike,
    faces: ArrayLike,
    face_part: ArrayLike,
    part_names: Sequence[str],
    metadata: dict[str, Any],
) -> MeshData:
    """Wrap built arrays as a :class:`MeshData` without materials.

    Parameters
    ----------
    vertices : (n_vertices, 3) float
        Positions [m].
    faces : (n_faces, 3) int
        Vertex indices, counter-clockwise seen from the front.
    face_part : (n_faces,) int
        Index into ``part_names``.
    part_names : sequence of str
        Names of the parts.
    metadata : dict
        ``{"shape": ..., <parameters>}``.

    Returns
    -------
    MeshData
        The mesh, every face without a material key (-1); ``source`` is ``"<shape>"``.

    Examples
    --------
    >>> mesh = assemble([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], [0], ["tri"], {"shape": "tri"})
    >>> mesh.n_faces, mesh.source, mesh.face_material.tolist()
    (1, '<tri>', [-1])
    """
    faces = np.asarray(faces, dtype=np.int64)
    return MeshData(
        vertices=np.asarray(vertices, dtype=np.float64),
        faces=faces,
        face_part=np.asarray(face_part, dtype=np.int32),
        part_names=tuple(part_names),
        face_material=np.full(len(faces), -1, dtype=np.int32),
        source=f"<{metadata['shape']}>",
        metadata=metadata,
    )


def transform(
    mesh: MeshData, rotation: ArrayLike | None = None, translation: ArrayLike = (0.0, 0.0, 0.0)
) -> MeshData:
    """Rotate a mesh about the origin, then translate it: ``x' = R x + t``.

    Parameters
    ----------
    mesh : MeshData
        The mesh [m].
    rotation : (3, 3) float, optional
        Proper rotation matrix (det +1, so windings stay outward); identity when omitted.
    translation : (3,) float
        Offset [m].

    Returns
    -------
    MeshData
        The moved mesh, parts and materials as in ``mesh``.

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> moved = transform(box((2.0, 1.0, 1.0)), rotation_matrix("z", 90), (0.0, 0.0, 5.0))
    >>> np.round(np.ptp(moved.vertices, axis=0), 6).tolist(), float(moved.vertices[:, 2].min())
    ([1.0, 2.0, 1.0], 4.5)
    """
    vertices = mesh.vertices
    if rotation is not None:
        rotation = np.asarray(rotation, dtype=np.float64)
        if not np.allclose(rotation @ rotation.T, np.eye(3)) or np.linalg.det(rotation) < 0:
            raise InputError("rotation must be a proper rotation matrix (orthonormal, det +1)")
        vertices = vertices @ rotation.T
    return replace(mesh, vertices=vertices + np.asarray(translation, dtype=np.float64))


def label(mesh: MeshData, part: str, material: str | None = None) -> MeshData:
    """Put all faces of a mesh in one part and, when given, one material key.

    Parameters
    ----------
    mesh : MeshData
        The mesh.
    part : str
        New part name for every face.
    material : str, optional
        Material key of every face; without it faces keep no material (-1).

    Returns
    -------
    MeshData
        The relabelled mesh.

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> bus = label(box(), "bus", "mli")
    >>> bus.part_names, bus.material_names
    (('bus',), ('mli',))
    """
    n = mesh.n_faces
    return replace(
        mesh,
        face_part=np.zeros(n, dtype=np.int32),
        part_names=(part,),
        face_material=np.full(n, 0 if material else -1, dtype=np.int32),
        material_names=(material,) if material else (),
    )


def rotation_matrix(axis: str, angle_deg: float) -> NDArray[np.float64]:
    """Build a right-handed rotation by ``angle_deg`` [deg] about the body ``"x"``, ``"y"`` or ``"z"`` axis.

    Parameters
    ----------
    axis : {"x", "y", "z"}
        The axis.
    angle_deg : float
        The angle [deg].

    Returns
    -------
    (3, 3) float64
        The rotation matrix.

    Examples
    --------
    >>> np.round(rotation_matrix("z", 90) @ [1.0, 0.0, 0.0], 12) + 0.0
    array([0., 1., 0.])
    """
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    matrix = np.eye(3)
    matrix[i, i] = matrix[j, j] = c
    matrix[j, i], matrix[i, j] = s, -s
    return matrix
