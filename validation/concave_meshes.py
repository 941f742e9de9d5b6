"""Meshes of the concave validation shapes: flat sheets, a V-groove, an L, an open box, a dish and a
box with one wing.

Every plate is a sheet meshed in cells (:func:`sheet`); the dish is the sample spacecraft's; the box-wing's
bus is a closed box. None has materials: :func:`sunwind.validation.concave.finished_spacecraft` and
:mod:`sunwind.validation.concave_drag` give them their finishes.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from sunwind.geometry.mesh_data import MeshData
from sunwind.meshes.assembly import label
from sunwind.meshes.primitives import box
from sunwind.meshes.samples import sample_spacecraft
from sunwind.meshes.triangulation import grid_faces

__all__ = ["box_wing_mesh", "dish_mesh", "l_mesh", "open_box_mesh", "sheet", "v_groove_mesh"]


def sheet(
    corner: ArrayLike, edge_u: ArrayLike, edge_v: ArrayLike, divisions: tuple[int, int], part: str
) -> MeshData:
    """Flat parallelogram ``corner + a edge_u + b edge_v``, ``a, b`` in [0, 1], front along ``u x v``.

    Parameters
    ----------
    corner, edge_u, edge_v : (3,) array_like
        A corner and the two edges from it [m].
    divisions : (int, int)
        Cells along ``edge_u`` and ``edge_v``.
    part : str
        Name of the one part.

    Returns
    -------
    MeshData
        ``2 nu nv`` triangles, no material.

    Examples
    --------
    >>> plate = sheet((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (2, 1), "plate")
    >>> plate.n_faces, plate.part_names
    (4, ('plate',))
    """
    nu, nv = divisions
    a, b = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
    vertices = (
        np.asarray(corner, dtype=np.float64)
        + a.reshape(-1, 1) * np.asarray(edge_u, dtype=np.float64)
        + b.reshape(-1, 1) * np.asarray(edge_v, dtype=np.float64)
    )
    faces = grid_faces(nu, nv)
    n = len(faces)
    return MeshData(vertices, faces, np.zeros(n, np.int32), (part,), np.full(n, -1, np.int32))


def v_groove_mesh(
    width_m: float = 1.0, length_m: float = 3.0, divisions: tuple[int, int] = (8, 16)
) -> MeshData:
    """90 deg V-groove: two plates ``width_m`` (slant) by ``length_m``, apex on the y axis, open to +z.

    The plates run from the apex (the y axis, ``|y| <= length / 2``) up to ``x = -+ w / sqrt(2)``,
    ``z = w / sqrt(2)``; fronts face into the groove. Parts ``"wall_left"`` (x < 0) and
    ``"wall_right"``; ``divisions`` cells across and along each.

    Parameters
    ----------
    width_m : float, optional
        Slant width ``w`` of each plate [m].
    length_m : float, optional
        Length of the groove along y [m].
    divisions : (int, int), optional
        Cells across and along each plate.

    Returns
    -------
    MeshData
        ``4 * divisions[0] * divisions[1]`` triangles in two parts, no material.

    Examples
    --------
    >>> groove = v_groove_mesh(divisions=(1, 2))
    >>> groove.part_names, groove.n_faces
    (('wall_left', 'wall_right'), 8)
    """
    h = width_m / math.sqrt(2)
    apex = (0.0, -length_m / 2, 0.0)
    along = (0.0, length_m, 0.0)
    left = sheet(apex, along, (-h, 0.0, h), divisions[::-1], "wall_left")
    right = sheet(apex, (h, 0.0, h), along, divisions, "wall_right")
    return MeshData.concatenate([left, right], source="<v-groove>")


def l_mesh(
    floor_m: tuple[float, float] = (1.0, 1.2), wall_height_m: float = 0.6, divisions: int = 8
) -> MeshData:
    """An L of two plates at 90 deg: a floor in z = 0 and a wall in x = 0 along its edge.

    The floor spans ``0 <= x <= floor_m[0]``, ``|y| <= floor_m[1] / 2``, front +z; the wall
    ``|y| <= floor_m[1] / 2``, ``0 <= z <= wall_height_m``, front +x. Parts ``"floor"``, ``"wall"``.

    Parameters
    ----------
    floor_m : (float, float), optional
        Floor extent along x and y [m].
    wall_height_m : float, optional
        Height of the wall [m].
    divisions : int, optional
        Cells along each edge of a plate.

    Returns
    -------
    MeshData
        Two parts, no material.

    Examples
    --------
    >>> corner = l_mesh(divisions=1)
    >>> corner.part_names, corner.n_faces
    (('floor', 'wall'), 4)
    """
    a, b = floor_m
    corner = (0.0, -b / 2, 0.0)
    floor = sheet(corner, (a, 0.0, 0.0), (0.0, b, 0.0), (divisions, divisions), "floor")
    wall = sheet(corner, (0.0, b, 0.0), (0.0, 0.0, wall_height_m), (divisions, divisions), "wall")
    return MeshData.concatenate([floor, wall], source="<L>")


def open_box_mesh(edge_m: float = 1.0, divisions: int = 8) -> MeshData:
    """A cube centred at the origin without its top face (z = +edge / 2): five sheets, fronts inward.

    Parts ``"floor"``, ``"wall_+x"``, ``"wall_-x"``, ``"wall_+y"``, ``"wall_-y"``.

    Parameters
    ----------
    edge_m : float, optional
        Cube edge [m].
    divisions : int, optional
        Cells along each edge.

    Returns
    -------
    MeshData
        Five parts, ``10 * divisions**2`` triangles, no material.

    Examples
    --------
    >>> tray = open_box_mesh(divisions=1)
    >>> tray.part_names, tray.n_faces
    (('floor', 'wall_+x', 'wall_-x', 'wall_+y', 'wall_-y'), 10)
    """
    e, g = edge_m / 2, (divisions, divisions)
    pieces = [sheet((-e, -e, -e), (edge_m, 0.0, 0.0), (0.0, edge_m, 0.0), g, "floor")]
    for axis, name in ((0, "x"), (1, "y")):
        other = 1 - axis
        for sign in (1.0, -1.0):
            corner = np.full(3, -e)
            corner[axis] = sign * e
            across = np.zeros(3)
            across[other] = edge_m
            up = np.array([0.0, 0.0, edge_m])
            # front = edge_u x edge_v must point inward, along -sign on this axis
            inward = np.cross(across, up)[axis] * sign < 0
            edges = (across, up) if inward else (up, across)
            pieces.append(sheet(corner, *edges, g, f"wall_{'+' if sign > 0 else '-'}{name}"))
    return MeshData.concatenate(pieces, source="<open box>")


@lru_cache(maxsize=2)
def dish_mesh(triangles: int = 20_000) -> MeshData:
    """The ``"dish"`` part of :func:`sunwind.meshes.samples.sample_spacecraft` alone, where it sits there.

    A paraboloid of diameter 1.2 m and f/D 0.35, concave side +z (its front), vertex at z = 0.904 m.

    Parameters
    ----------
    triangles : int, optional
        Triangle count asked of the whole sample; the dish gets its share.

    Returns
    -------
    MeshData
        One part ``"dish"``, the same object for the same ``triangles`` (cached).

    Examples
    --------
    >>> dish_mesh(2000).part_names
    ('dish',)
    """
    sample = sample_spacecraft(triangles)
    keep = sample.face_part == sample.part_names.index("dish")
    used, faces = np.unique(sample.faces[keep], return_inverse=True)
    n = int(keep.sum())
    return MeshData(
        sample.vertices[used],
        faces.reshape(-1, 3),
        np.zeros(n, np.int32),
        ("dish",),
        np.full(n, -1, np.int32),
        source="<sample dish>",
    )


def box_wing_mesh(
    wing_m: tuple[float, float] = (2.0, 1.0), gap_m: float = 0.2, divisions: int = 8
) -> MeshData:
    """A closed 1 m cube bus centred at the origin and one flat wing in the plane x = 0 beside its +y face.

    The wing spans ``0.5 + gap_m <= y <= 0.5 + gap_m + wing_m[0]`` and ``|z| <= wing_m[1] / 2``, front
    +x, so the bus's +y face and the wing's root see each other across the gap. Parts ``"bus"``
    (``divisions`` cells along each cube edge) and ``"wing"`` (square cells of about the bus's).

    Parameters
    ----------
    wing_m : (float, float), optional
        Wing span along y and chord along z [m].
    gap_m : float, optional
        Gap between the bus's +y face and the wing's root [m].
    divisions : int, optional
        Cells along each cube edge.

    Returns
    -------
    MeshData
        Parts ``"bus"`` (closed) and ``"wing"`` (a sheet), no material.

    Examples
    --------
    >>> model = box_wing_mesh(divisions=1)
    >>> model.part_names, model.n_faces
    (('bus', 'wing'), 16)
    """
    span, width = wing_m
    cells = (max(1, round(span * divisions)), max(1, round(width * divisions)))
    root = (0.0, 0.5 + gap_m, -width / 2)
    wing = sheet(root, (0.0, span, 0.0), (0.0, 0.0, width), cells, "wing")
    return MeshData.concatenate([label(box((1.0, 1.0, 1.0), divisions), "bus"), wing], source="<box-wing>")
