"""Triangulations the builders share: cell grids, rings of revolution and the gridded box surface.

Shapes of revolution are built from rings of vertices about the z axis, each with vertices in
proportion to its radius (a pole is one vertex; rings one facet apart then hold 1, ~6, ~12, ...
vertices, so triangles are nearly equilateral, without the slivers of a fan). :func:`revolve`
zips neighbouring rings into triangles in order of angle (cylinder, cone, flat discs);
:func:`sunwind.meshes.primitives.sphere` takes the convex hull of its rings and
:func:`sunwind.meshes.primitives.dish` the Delaunay triangulation of its rings' (x, y), so both curve
one way everywhere.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData
from sunwind.meshes.arguments import check_triangles
from sunwind.meshes.assembly import assemble

__all__ = [
    "box_surface",
    "equal_pieces",
    "grid_faces",
    "oriented",
    "revolve",
    "revolved_parts",
    "ring_counts",
    "ring_vertices",
]


def grid_faces(nu: int, nv: int) -> NDArray[np.int64]:
    """Return the triangles of an ``nu`` x ``nv`` cell grid, counter-clockwise in the (u, v) plane.

    Vertices are numbered ``i * (nv + 1) + j`` for ``i`` along u in ``0..nu`` and ``j`` along v in
    ``0..nv``; each cell is split along its (i, j)-(i+1, j+1) diagonal.

    Parameters
    ----------
    nu, nv : int
        Cells along u and along v, >= 1.

    Returns
    -------
    (2 nu nv, 3) int64
        Vertex indices of each triangle; face normal along ``u x v``.

    Examples
    --------
    >>> grid_faces(1, 1).tolist()  # one cell, corners 0 (0, 0), 1 (0, 1), 2 (1, 0), 3 (1, 1)
    [[0, 2, 3], [0, 3, 1]]
    """
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = (i * (nv + 1) + j).ravel()
    b, c, d = a + nv + 1, a + nv + 2, a + 1  # (i+1, j), (i+1, j+1), (i, j+1)
    return np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])


def _zip_rings(starts: NDArray[np.int64], counts: NDArray[np.int64]) -> tuple[NDArray, NDArray]:
    """Triangles joining each ring to the next, ordered by angle; and the strip of each.

    Ring ``k`` has ``counts[k]`` vertices numbered from ``starts[k]`` at angles ``2 pi i / counts[k]``.
    Walking once round the strip between rings A (lower) and B (upper), every step to the next
    vertex of A or of B, taken in order of angle, closes one triangle; a ring of one vertex (a
    pole) takes no steps, so its strip is a fan. Triangles face ``t_phi x t_profile``.

    Returns
    -------
    faces : (n_faces, 3) int64
    strip : (n_faces,) int64
        Index ``k`` of the strip between rings ``k`` and ``k + 1``.
    """
    p, q = counts[:-1], counts[1:]
    steps_a, steps_b = np.where(p > 1, p, 0), np.where(q > 1, q, 0)

    def events(steps: NDArray[np.int64], n: NDArray[np.int64]) -> tuple[NDArray, NDArray]:
        strip = np.repeat(np.arange(len(steps)), steps)
        first = np.repeat(np.cumsum(steps) - steps, steps)
        return strip, (np.arange(len(strip)) - first + 1) / n[strip]

    strip_a, t_a = events(steps_a, p)
    strip_b, t_b = events(steps_b, q)
    strip = np.concatenate([strip_a, strip_b])
    is_b = np.concatenate([np.zeros(len(strip_a), bool), np.ones(len(strip_b), bool)])
    order = np.lexsort((is_b, np.concatenate([t_a, t_b]), strip))
    strip, is_b = strip[order], is_b[order]
    first = np.cumsum(steps_a + steps_b) - (steps_a + steps_b)  # first event of each strip
    a_before = np.cumsum(~is_b) - ~is_b
    b_before = np.cumsum(is_b) - is_b
    ia = a_before - a_before[first][strip]
    ib = b_before - b_before[first][strip]
    pa, qb = p[strip], q[strip]
    a0 = starts[:-1][strip] + ia % pa
    a1 = starts[:-1][strip] + (ia + 1) % pa
    b0 = starts[1:][strip] + ib % qb
    b1 = starts[1:][strip] + (ib + 1) % qb
    faces = np.where(is_b[:, None], np.stack([a0, b1, b0], 1), np.stack([a0, a1, b0], 1))
    return faces, strip


def ring_counts(r: ArrayLike, segments: int) -> NDArray[np.int64]:
    """Count vertices per ring in proportion to its radius: ``max(3, round(segments r / max(r)))``.

    A ring of radius 0 (a pole) gets one vertex. Rings spaced one rim facet width apart then get
    1, ~6, ~12, ... vertices: nearly equilateral triangles, no fan of slivers.

    Parameters
    ----------
    r : (n_rings,) float
        Ring radii [m], >= 0.
    segments : int
        Vertices on the widest ring.

    Returns
    -------
    (n_rings,) int64
        Vertices of each ring.

    Examples
    --------
    >>> ring_counts([0.0, 0.5, 1.0], segments=12).tolist()
    [1, 6, 12]
    """
    r = np.asarray(r, dtype=np.float64)
    return np.where(r > 0, np.maximum(3, np.rint(segments * r / r.max())), 1).astype(np.int64)


def ring_vertices(
    r: ArrayLike, z: ArrayLike, counts: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Place vertices on coaxial rings about the z axis, ring ``k`` at angles ``2 pi i / counts[k]`` from +x.

    Parameters
    ----------
    r, z : (n_rings,) float
        Ring radius (>= 0; a ring of radius 0 has one vertex) and height [m].
    counts : (n_rings,) int
        Vertices of each ring.

    Returns
    -------
    vertices : (sum(counts), 3) float64
        [m], ring by ring.
    starts : (n_rings,) int64
        Index of each ring's first vertex.

    Examples
    --------
    >>> vertices, starts = ring_vertices([0.0, 1.0], [1.0, 0.0], [1, 4])  # a pole over a ring of 4
    >>> vertices.shape, starts.tolist()
    ((5, 3), [0, 1])
    """
    r, z = np.asarray(r, dtype=np.float64), np.asarray(z, dtype=np.float64)
    counts = np.asarray(counts, dtype=np.int64)
    starts = np.cumsum(counts) - counts
    ring = np.repeat(np.arange(len(r)), counts)
    phi = 2 * np.pi * (np.arange(len(ring)) - starts[ring]) / counts[ring]
    vertices = np.column_stack([r[ring] * np.cos(phi), r[ring] * np.sin(phi), z[ring]])
    return vertices, starts


def revolve(
    r: ArrayLike, z: ArrayLike, counts: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]]:
    """Sweep a profile about the z axis into a triangulated surface of revolution.

    Profile point ``k`` becomes a ring of ``counts[k]`` vertices (:func:`ring_vertices`);
    consecutive rings are zipped by :func:`_zip_rings`. The front (right-hand) normal is
    ``t_phi x t_profile``: outward for a profile that runs with the body on its left in the (r, z)
    half-plane, e.g. bottom to top for a cylinder's side. Rings of equal count give planar strips
    between generators, as on a cylinder or a cone; on a doubly curved surface rings of unequal
    count give a surface that is not exactly convex (see :func:`sunwind.meshes.primitives.sphere`).

    Parameters
    ----------
    r, z : (n_points,) float
        Profile radius (>= 0) and height [m]; no two poles in a row.
    counts : (n_points,) int
        Vertices of each ring, 1 where ``r = 0``.

    Returns
    -------
    vertices : (n_vertices, 3) float64
        [m].
    faces : (n_faces, 3) int64
        Vertex indices of each triangle.
    strip : (n_faces,) int64
        Profile segment ``k`` (between points ``k`` and ``k + 1``) each face belongs to.

    Examples
    --------
    >>> vertices, faces, strip = revolve([1.0, 1.0], [0.0, 1.0], [4, 4])  # the side of a square prism
    >>> vertices.shape, faces.shape, strip.tolist()
    ((8, 3), (8, 3), [0, 0, 0, 0, 0, 0, 0, 0])
    """
    vertices, starts = ring_vertices(r, z, counts)
    faces, strip = _zip_rings(starts, np.asarray(counts, dtype=np.int64))
    return vertices, faces, strip


def revolved_parts(
    corners: Sequence[tuple[float, float]],
    pieces: Sequence[int],
    leg_parts: Sequence[str],
    segments: int,
    metadata: dict[str, Any],
    generator_legs: Sequence[int] = (),
) -> MeshData:
    """Revolve a profile polyline, each corner-to-corner leg cut into equal pieces and named a part.

    Parameters
    ----------
    corners : sequence of (r, z)
        Profile corners [m], in the order :func:`revolve` needs for an outward front.
    pieces : sequence of int
        Number of equal pieces of each leg (``len(corners) - 1`` of them).
    leg_parts : sequence of str
        Part name of each leg.
    segments : int
        Vertices on the widest ring.
    metadata : dict
        Provenance of the mesh (its ``metadata``).
    generator_legs : sequence of int, optional
        Legs whose rings all get ``segments`` vertices on the same generators, so the facets are
        planar strips of the inscribed pyramid (a cone's side); other rings get
        :func:`ring_counts`.

    Returns
    -------
    MeshData
        The surface of revolution, the faces of leg ``k`` in part ``leg_parts[k]``.

    Raises
    ------
    InputError
        If the mesh would exceed the memory limit (:func:`sunwind.meshes.arguments.check_triangles`).

    Examples
    --------
    >>> can = revolved_parts(
    ...     [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], [1, 1, 1], ["bottom", "side", "top"], 8,
    ...     {"shape": "can"}, generator_legs=(1,),
    ... )
    >>> can.part_names, can.n_faces
    (('bottom', 'side', 'top'), 32)
    """
    widest = max(r for r, _ in corners)
    triangles = 0  # two per ring vertex of each band; a leg's rings have vertices in proportion to r
    for k, piece in enumerate(pieces):
        share = 1.0 if k in generator_legs else (corners[k][0] + corners[k + 1][0]) / (2 * widest)
        triangles += 2 * int(segments) * int(piece) * math.ceil(1000 * share) // 1000
    check_triangles(triangles, "lower segments or rings", ("segments", "rings"))
    points = np.asarray(corners, dtype=np.float64)
    pieces_arr = np.asarray(pieces, dtype=np.int64)
    leg = np.repeat(np.arange(len(pieces_arr)), pieces_arr)
    t = (np.arange(len(leg)) - np.repeat(np.cumsum(pieces_arr) - pieces_arr, pieces_arr)) / pieces_arr[leg]
    profile = np.vstack([points[leg] + t[:, None] * (points[leg + 1] - points[leg]), points[-1]])
    counts = ring_counts(profile[:, 0], segments)
    on_generator = np.isin(np.append(leg, leg[-1]), generator_legs) & (profile[:, 0] > 0)
    counts[on_generator] = segments
    vertices, faces, strip = revolve(profile[:, 0], profile[:, 1], counts)
    return assemble(vertices, faces, leg[strip], leg_parts, metadata)


def oriented(faces: NDArray[np.int64], normals: ArrayLike, vertices: NDArray) -> NDArray[np.int64]:
    """Return ``faces`` with each row reversed where its right-hand normal opposes ``normals``.

    Parameters
    ----------
    faces : (n, 3) int
        Vertex indices of each triangle.
    normals : (n, 3) or (3,) float
        The wanted side of each face, or one direction for all.
    vertices : (n_vertices, 3) float
        Vertex positions [m].

    Returns
    -------
    (n, 3) int64
        The faces, each wound so its right-hand normal has a non-negative dot product with its
        ``normals`` row.

    Examples
    --------
    >>> import numpy as np
    >>> corners = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    >>> oriented(np.array([[0, 2, 1]]), [0.0, 0.0, 1.0], corners).tolist()  # now facing +z
    [[1, 2, 0]]
    """
    corners = vertices[faces]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    flip = (cross * np.asarray(normals)).sum(axis=1) < 0
    return np.where(flip[:, None], faces[:, ::-1], faces).astype(np.int64)


def equal_pieces(length: float, step: float) -> int:
    """Fewest equal pieces of ``length`` no longer than ``step`` (at least one).

    Parameters
    ----------
    length : float
        Length to cut [m], > 0.
    step : float
        Longest piece [m], > 0.

    Returns
    -------
    int
        ``ceil(length / step)`` (an exact multiple is not rounded up by round-off), at least 1.

    Raises
    ------
    InputError
        More pieces than a float counts (``step`` far too small).

    Examples
    --------
    >>> equal_pieces(1.0, 0.3), equal_pieces(1.0, 0.25), equal_pieces(0.1, 1.0)
    (4, 4, 1)
    """
    pieces = length / step - 1e-9
    if not math.isfinite(pieces):
        raise InputError(f"{length:g} m in pieces of {step:g} m are too many to count")
    return max(1, math.ceil(pieces))


def box_surface(size: Sequence[float], cells: tuple[int, int, int]) -> tuple[NDArray, NDArray]:
    """Build the vertices and outward faces of a box centred at the origin with gridded, shared-vertex faces.

    Each face is a :func:`grid_faces` grid built on the integer lattice ``0..cells[axis]``, so edge
    vertices of adjacent faces are identical integers and merge exactly before scaling.

    Parameters
    ----------
    size : sequence of float
        Edge lengths along x, y, z [m], shape (3,).
    cells : tuple of int
        Cells along x, y, z, each >= 1.

    Returns
    -------
    vertices : (n_vertices, 3) float64
        [m], each lattice point on the surface once.
    faces : (n_faces, 3) int64
        Two triangles per cell of each face, wound outward.

    Examples
    --------
    >>> vertices, faces = box_surface((2.0, 1.0, 1.0), (2, 1, 1))
    >>> vertices.shape, faces.shape
    ((12, 3), (20, 3))
    """
    lattice, faces, offset = [], [], 0
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3  # u x v = +axis
        for side in (0, cells[axis]):
            i, j = np.meshgrid(np.arange(cells[u] + 1), np.arange(cells[v] + 1), indexing="ij")
            points = np.zeros((i.size, 3), dtype=np.int64)
            points[:, axis], points[:, u], points[:, v] = side, i.ravel(), j.ravel()
            grid = grid_faces(cells[u], cells[v])
            faces.append((grid if side else grid[:, ::-1]) + offset)
            lattice.append(points)
            offset += len(points)
    unique, inverse = np.unique(np.concatenate(lattice), axis=0, return_inverse=True)
    vertices = (unique / np.asarray(cells) - 0.5) * np.asarray(size, dtype=np.float64)
    return vertices, inverse.reshape(-1)[np.concatenate(faces)]
