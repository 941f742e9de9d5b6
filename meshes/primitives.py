"""Parametric meshes of the validation shapes: plate, sphere, cylinder, cone, box, box-wing, dish.

Every builder returns a :class:`sunwind.geometry.mesh_data.MeshData` in metres whose ``metadata`` holds
``"shape"`` and every parameter as resolved (STYLE.md §8), so :func:`build` can rebuild it.
Closed shapes are watertight: every edge is shared by exactly two faces, the winding is outward
(counter-clockwise seen from outside, positive signed volume) and vertices are shared. Open sheets
(plate, dish) have their front along the right-hand normal; the user declares them one- or
two-sided. No builder assigns materials (``face_material`` is -1).

Curved shapes are inscribed: every vertex lies on the smooth surface, so the faceted area, volume
and projected area fall short of the exact ones by O(h^2) for facet size h. Each default
resolution is chosen from that error law to stay below 1e-4 relative; its docstring states the
law and the resulting error. Doubling the resolution parameter halves the facet size and cuts
the error about four times.

Shapes of revolution are built from rings of vertices about the z axis, each with vertices in
proportion to its radius (a pole is one vertex; rings one facet apart then hold 1, ~6, ~12, ...
vertices, so triangles are nearly equilateral, without the slivers of a fan). :func:`revolve`
zips neighbouring rings into triangles in order of angle (cylinder, cone, flat discs); the
sphere is the convex hull of its rings and the dish the Delaunay triangulation of its rings'
(x, y), so both curve one way everywhere. The sphere, cylinder and cone are exactly convex: no
facet sees another.
"""

from __future__ import annotations

import inspect
import math
import numbers
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import ConvexHull, Delaunay

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData

# Default resolutions; the error each gives is derived in the builders' docstrings.
SPHERE_SUBDIVISIONS = 216
CYLINDER_SEGMENTS = 320
CONE_SEGMENTS = 360
DISH_SEGMENTS = 480
PLATE_DIVISIONS = 32


# ----------------------------------------------------------------------------------- assembly


def _mesh(
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
    metadata : dict
        ``{"shape": ..., <parameters>}``.
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
    """The mesh rotated about the origin, then translated: ``x' = R x + t``.

    Parameters
    ----------
    mesh : MeshData
    rotation : (3, 3) float, optional
        Proper rotation matrix (det +1, so windings stay outward); identity when omitted.
    translation : (3,) float
        Offset [m].
    """
    vertices = mesh.vertices
    if rotation is not None:
        rotation = np.asarray(rotation, dtype=np.float64)
        if not np.allclose(rotation @ rotation.T, np.eye(3)) or np.linalg.det(rotation) < 0:
            raise InputError("rotation must be a proper rotation matrix (orthonormal, det +1)")
        vertices = vertices @ rotation.T
    return replace(mesh, vertices=vertices + np.asarray(translation, dtype=np.float64))


def label(mesh: MeshData, part: str, material: str | None = None) -> MeshData:
    """The mesh with all its faces in one part and, when given, one material key.

    Parameters
    ----------
    mesh : MeshData
    part : str
        New part name for every face.
    material : str, optional
        Material key of every face; without it faces keep no material (-1).
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
    """Right-handed rotation by ``angle_deg`` [deg] about the body ``"x"``, ``"y"`` or ``"z"`` axis.

    Returns
    -------
    (3, 3) float64
    """
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    matrix = np.eye(3)
    matrix[i, i] = matrix[j, j] = c
    matrix[j, i], matrix[i, j] = s, -s
    return matrix


# ------------------------------------------------------------------------- shared construction


def grid_faces(nu: int, nv: int) -> NDArray[np.int64]:
    """Triangles of an ``nu`` x ``nv`` cell grid, counter-clockwise in the (u, v) plane.

    Vertices are numbered ``i * (nv + 1) + j`` for ``i`` along u in ``0..nu`` and ``j`` along v in
    ``0..nv``; each cell is split along its (i, j)-(i+1, j+1) diagonal.

    Returns
    -------
    (2 nu nv, 3) int64
        Face normal along ``u x v``.
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
    """Vertices per ring in proportion to its radius: ``max(3, round(segments r / max(r)))``, 1 at r = 0.

    Rings spaced one rim facet width apart then get 1, ~6, ~12, ... vertices: nearly equilateral
    triangles, no fan of slivers.

    Parameters
    ----------
    r : (n_rings,) float
        Ring radii [m], >= 0.
    segments : int
        Vertices on the widest ring.

    Returns
    -------
    (n_rings,) int64
    """
    r = np.asarray(r, dtype=np.float64)
    return np.where(r > 0, np.maximum(3, np.rint(segments * r / r.max())), 1).astype(np.int64)


def ring_vertices(
    r: ArrayLike, z: ArrayLike, counts: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Vertices of coaxial rings about the z axis, ring ``k`` at angles ``2 pi i / counts[k]`` from +x.

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
    count give a surface that is not exactly convex (see :func:`sphere`).

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
    strip : (n_faces,) int64
        Profile segment ``k`` (between points ``k`` and ``k + 1``) each face belongs to.
    """
    vertices, starts = ring_vertices(r, z, counts)
    faces, strip = _zip_rings(starts, np.asarray(counts, dtype=np.int64))
    return vertices, faces, strip


def _revolved_parts(
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
    generator_legs : sequence of int
        Legs whose rings all get ``segments`` vertices on the same generators, so the facets are
        planar strips of the inscribed pyramid (a cone's side); other rings get
        :func:`ring_counts`.
    """
    points = np.asarray(corners, dtype=np.float64)
    pieces_arr = np.asarray(pieces, dtype=np.int64)
    leg = np.repeat(np.arange(len(pieces_arr)), pieces_arr)
    t = (np.arange(len(leg)) - np.repeat(np.cumsum(pieces_arr) - pieces_arr, pieces_arr)) / pieces_arr[leg]
    profile = np.vstack([points[leg] + t[:, None] * (points[leg + 1] - points[leg]), points[-1]])
    counts = ring_counts(profile[:, 0], segments)
    on_generator = np.isin(np.append(leg, leg[-1]), generator_legs) & (profile[:, 0] > 0)
    counts[on_generator] = segments
    vertices, faces, strip = revolve(profile[:, 0], profile[:, 1], counts)
    return _mesh(vertices, faces, leg[strip], leg_parts, metadata)


def _oriented(faces: NDArray[np.int64], normals: ArrayLike, vertices: NDArray) -> NDArray[np.int64]:
    """``faces`` with each row reversed where its right-hand normal opposes ``normals``, (n, 3) or (3,)."""
    corners = vertices[faces]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    flip = (cross * np.asarray(normals)).sum(axis=1) < 0
    return np.where(flip[:, None], faces[:, ::-1], faces).astype(np.int64)


def _pieces(length: float, step: float) -> int:
    """Fewest equal pieces of ``length`` no longer than ``step`` (at least one)."""
    return max(1, math.ceil(length / step - 1e-9))


# ------------------------------------------------------------------------------ input checks


def _positive(**values: float) -> None:
    """Raise :class:`InputError` unless every value is a finite number > 0."""
    for name, value in values.items():
        real = isinstance(value, numbers.Real) and not isinstance(value, bool)
        if not (real and math.isfinite(value) and value > 0):
            raise InputError(f"{name} = {value!r} must be a finite number > 0")


def _count(minimum: int, **values: Any) -> None:
    """Raise :class:`InputError` unless every value is an integer >= ``minimum``."""
    for name, value in values.items():
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
            raise InputError(f"{name} = {value!r} must be an integer >= {minimum}")


def _per_axis(name: str, value: int | Sequence[int], n: int) -> tuple[int, ...]:
    """An int or a length-``n`` sequence of ints (each >= 1) as an ``n``-tuple."""
    values = (value,) * n if isinstance(value, (int, np.integer)) else tuple(value)
    if len(values) != n:
        raise InputError(f"{name} = {value!r} must be an integer or {n} integers")
    _count(1, **{f"{name}[{i}]": v for i, v in enumerate(values)})
    return tuple(int(v) for v in values)


# --------------------------------------------------------------------------------- primitives


def plate(
    size_x: float = 1.0, size_y: float = 1.0, divisions: int | Sequence[int] = PLATE_DIVISIONS
) -> MeshData:
    """Flat rectangular sheet centred at the origin in the plane z = 0, front normal +z.

    Its area ``size_x * size_y`` and its projected area ``size_x * size_y * |d_z|`` along a unit
    direction ``d`` are exact at any resolution. It is an open sheet: declare it one- or two-sided
    in the materials file.

    Parameters
    ----------
    size_x, size_y : float
        Side lengths along x and y [m].
    divisions : int or (int, int)
        Cells along x and y (the same for both when one integer); default 32, 2048 triangles.

    Returns
    -------
    MeshData
        Part ``"plate"``; ``2 * nx * ny`` triangles, counter-clockwise seen from +z.
    """
    _positive(size_x=size_x, size_y=size_y)
    nx, ny = _per_axis("divisions", divisions, 2)
    x, y = np.meshgrid(
        np.linspace(-size_x / 2, size_x / 2, nx + 1),
        np.linspace(-size_y / 2, size_y / 2, ny + 1),
        indexing="ij",
    )
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    faces = grid_faces(nx, ny)
    metadata = {"shape": "plate", "size_x": float(size_x), "size_y": float(size_y), "divisions": (nx, ny)}
    return _mesh(vertices, faces, np.zeros(len(faces)), ["plate"], metadata)


def sphere(radius: float = 1.0, subdivisions: int = SPHERE_SUBDIVISIONS) -> MeshData:
    """Closed sphere centred at the origin, inscribed (every vertex at distance ``radius``), convex.

    Vertices lie on ``subdivisions + 1`` circles of latitude of equal angular spacing, poles
    included, each with vertices in proportion to its radius (``2 * subdivisions`` on the
    equator); their convex hull is the mesh. Triangles are nearly equilateral with edge
    ``h ~ pi R / subdivisions``; there are about ``2.55 * subdivisions**2`` of them. Being a convex
    hull, no facet sees another (no self-shadowing or inter-reflection on the faceted sphere).

    Error law: an inscribed triangulation lies inside the sphere by ``~h^2 / (8 R)`` on average, so
    area, volume and projected area fall short by ``c (pi / subdivisions)^2`` relative, with
    ``c ~ 0.22`` (area), ``0.40`` (volume), ``0.15-0.24`` (projected area, by direction).
    Volume is the binding one: it falls short by at least ``6 pi / (sqrt(3) N) = 10.9 / N`` for
    ``N`` equilateral inscribed triangles, so 1e-4 needs more than 109 000 triangles whatever the
    layout. The default ``subdivisions = 216`` (118 808 triangles) gives area -5.2e-5, volume
    -9.8e-5 and projected area -3.5e-5 to -5.7e-5 relative; each doubling cuts them four times.

    Parameters
    ----------
    radius : float
        [m].
    subdivisions : int
        Latitude bands from pole to pole (>= 2); facet size ``~ pi * radius / subdivisions``.

    Returns
    -------
    MeshData
        Part ``"sphere"``.
    """
    _positive(radius=radius)
    _count(2, subdivisions=subdivisions)
    theta = np.linspace(np.pi, 0.0, subdivisions + 1)
    r = radius * np.sin(theta)
    r[[0, -1]] = 0.0
    vertices, _ = ring_vertices(r, radius * np.cos(theta), ring_counts(r, 2 * subdivisions))
    hull = ConvexHull(vertices)
    faces = _oriented(hull.simplices, hull.equations[:, :3], vertices)
    metadata = {"shape": "sphere", "radius": float(radius), "subdivisions": int(subdivisions)}
    return _mesh(vertices, faces, np.zeros(len(faces)), ["sphere"], metadata)


def cylinder(
    radius: float = 1.0,
    length: float = 2.0,
    segments: int = CYLINDER_SEGMENTS,
    rings: int | None = None,
    caps: bool = True,
) -> MeshData:
    """Right circular cylinder on the z axis, centred at the origin, inscribed.

    The lateral surface is ``segments`` flat strips cut into ``rings`` bands; each cap is a disc of
    concentric rings (1, ~6, ~12, ... vertices out to ``segments`` on the rim) spaced one rim
    facet width ``a = 2 pi R / segments`` apart, so cap triangles are nearly equilateral.

    Error law (``n = segments``): lateral area ``1 - n sin(pi/n) / pi ~ pi^2 / (6 n^2)``; cap area,
    volume and projected area along the axis ``1 - n sin(2 pi/n) / (2 pi) ~ 2 pi^2 / (3 n^2)``;
    projected width across the axis between ``2 R cos(pi/n)`` and ``2 R``, a shortfall of at most
    ``pi^2 / (2 n^2)``. The default ``n = 320`` gives lateral -1.6e-5, caps and volume -6.4e-5,
    width at most -4.8e-5 relative, in 97 920 triangles for the default proportions.

    Parameters
    ----------
    radius, length : float
        [m].
    segments : int
        Facets round the circumference (>= 3).
    rings : int, optional
        Bands along the axis; default ``ceil(length / a)``, lateral cells about square.
    caps : bool
        Close the ends; without caps it is an open tube (declare it a sheet).

    Returns
    -------
    MeshData
        Parts ``"lateral"`` and, with caps, ``"cap_bottom"`` (z = -length/2, normal -z) and
        ``"cap_top"`` (z = +length/2, normal +z). ``metadata["rings"]`` is the resolved value.
    """
    _positive(radius=radius, length=length)
    _count(3, segments=segments)
    facet = 2 * np.pi * radius / segments
    if rings is None:
        rings = _pieces(length, facet)
    _count(1, rings=rings)
    metadata = {
        "shape": "cylinder",
        "radius": float(radius),
        "length": float(length),
        "segments": int(segments),
        "rings": int(rings),
        "caps": bool(caps),
    }
    half, cap = length / 2, _pieces(radius, facet)
    if caps:
        corners = [(0.0, -half), (radius, -half), (radius, half), (0.0, half)]
        return _revolved_parts(
            corners, [cap, rings, cap], ["cap_bottom", "lateral", "cap_top"], segments, metadata
        )
    return _revolved_parts([(radius, -half), (radius, half)], [rings], ["lateral"], segments, metadata)


def cone(
    radius: float = 1.0,
    half_angle_deg: float = 70.0,
    segments: int = CONE_SEGMENTS,
    rings: int | None = None,
    base: bool = True,
) -> MeshData:
    """Right circular cone, base disc in z = 0 centred at the origin, apex at (0, 0, h), inscribed.

    ``half_angle_deg`` is the angle between the axis and a generator, so the height is
    ``h = radius / tan(half_angle)`` and the slant ``s = radius / sin(half_angle)``. The side is
    the inscribed ``segments``-sided pyramid, cut into ``rings`` bands along the generators, so it
    is exactly convex (facets between generators are planar; triangles narrow toward the apex).
    The base is a disc of concentric rings one rim facet width ``a = 2 pi R / segments`` apart,
    with vertices in proportion to their radius (nearly equilateral triangles).

    Error law (``n = segments``): base area, volume and projected area along the axis fall short
    by ``1 - n sin(2 pi/n) / (2 pi) ~ 2 pi^2 / (3 n^2)``; the side area by
    ``~(pi^2 / n^2) (1/6 + sin^2(half_angle) / 2)``; the projected area in any direction by no more
    than the base's share. The default ``n = 360`` gives base, volume and projected area -5.1e-5 at
    worst and side area -4.6e-5, in 64 440 triangles at 70 deg.

    Parameters
    ----------
    radius : float
        Base radius [m].
    half_angle_deg : float
        Half-angle at the apex, in (0, 90) [deg].
    segments : int
        Facets round the base rim (>= 3).
    rings : int, optional
        Bands along the side; default ``ceil(s / a)``, side cells about square at the rim.
    base : bool
        Close the base; without it the side is an open sheet.

    Returns
    -------
    MeshData
        Parts ``"base"`` (normal -z) when ``base`` and ``"lateral"``. ``metadata["rings"]`` is the
        resolved value.
    """
    _positive(radius=radius, half_angle_deg=half_angle_deg)
    _count(3, segments=segments)
    if not half_angle_deg < 90:
        raise InputError(f"half_angle_deg = {half_angle_deg!r} must be in (0, 90)")
    height = radius / math.tan(math.radians(half_angle_deg))
    facet = 2 * np.pi * radius / segments
    if rings is None:
        rings = _pieces(math.hypot(radius, height), facet)
    _count(1, rings=rings)
    metadata = {
        "shape": "cone",
        "radius": float(radius),
        "half_angle_deg": float(half_angle_deg),
        "segments": int(segments),
        "rings": int(rings),
        "base": bool(base),
    }
    if base:
        corners = [(0.0, 0.0), (radius, 0.0), (0.0, height)]
        pieces, parts = [_pieces(radius, facet), rings], ["base", "lateral"]
        return _revolved_parts(corners, pieces, parts, segments, metadata, generator_legs=[1])
    corners = [(radius, 0.0), (0.0, height)]
    return _revolved_parts(corners, [rings], ["lateral"], segments, metadata, generator_legs=[0])


def dish(diameter: float = 1.2, focal_ratio: float = 0.35, segments: int = DISH_SEGMENTS) -> MeshData:
    """Paraboloidal reflector sheet ``z = r^2 / (4 f)``, vertex at the origin, concave side +z.

    ``f = focal_ratio * diameter``; the rim is at ``r = diameter / 2``, ``z = diameter /
    (16 focal_ratio)``. The front (right-hand normal) is the concave side, facing +z toward the
    focus. It is an open sheet: declare it one- or two-sided. Vertices lie on rings one rim facet
    width apart along the arc, with vertices in proportion to their radius; the triangles are the
    Delaunay triangulation of their (x, y), which on a paraboloid is the lower convex hull, so the
    faceted dish curves one way everywhere (no ridges).

    Error law (``n = segments``): area and the projected area along the axis fall short by about
    ``2 pi^2 / (3 n^2)`` (the rim polygon); the default ``n = 480`` gives -3.5e-5 (area) and
    -2.9e-5 (projected) in about 41 000 triangles at the default proportions.

    Parameters
    ----------
    diameter : float
        Rim diameter [m].
    focal_ratio : float
        ``f / D`` [-].
    segments : int
        Facets round the rim (>= 3).

    Returns
    -------
    MeshData
        Part ``"dish"``.
    """
    _positive(diameter=diameter, focal_ratio=focal_ratio)
    _count(3, segments=segments)
    focal = focal_ratio * diameter
    # Rings equally spaced in arc length along the parabola, from the vertex out.
    fine = np.linspace(0.0, diameter / 2, 4097)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(fine), np.diff(fine**2) / (4 * focal)))])
    pieces = _pieces(arc[-1], np.pi * diameter / segments)
    r = np.interp(np.linspace(0.0, arc[-1], pieces + 1), arc, fine)
    vertices, _ = ring_vertices(r, r**2 / (4 * focal), ring_counts(r, segments))
    faces = _oriented(Delaunay(vertices[:, :2]).simplices, np.array([0.0, 0.0, 1.0]), vertices)
    metadata = {
        "shape": "dish",
        "diameter": float(diameter),
        "focal_ratio": float(focal_ratio),
        "segments": int(segments),
    }
    return _mesh(vertices, faces, np.zeros(len(faces)), ["dish"], metadata)


def _box_surface(size: Sequence[float], cells: tuple[int, int, int]) -> tuple[NDArray, NDArray]:
    """Vertices and outward faces of a box centred at the origin with gridded, shared-vertex faces.

    Each face is a :func:`grid_faces` grid built on the integer lattice ``0..cells[axis]``, so edge
    vertices of adjacent faces are identical integers and merge exactly before scaling.
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


def box(size: Sequence[float] = (1.0, 1.0, 1.0), divisions: int | Sequence[int] = 1) -> MeshData:
    """Closed rectangular box centred at the origin, edges along the axes.

    Area, volume and projected area ``sum_i |d_i| A_i`` are exact at any resolution; ``divisions``
    only sets the facet size (for shadow resolution).

    Parameters
    ----------
    size : (3,) float
        Edge lengths along x, y, z [m].
    divisions : int or (int, int, int)
        Cells along each edge direction; default 1 (12 triangles).

    Returns
    -------
    MeshData
        Part ``"box"``.
    """
    size = tuple(float(s) for s in size)
    if len(size) != 3:
        raise InputError(f"size = {size!r} must be three edge lengths")
    _positive(**{f"size[{i}]": s for i, s in enumerate(size)})
    cells = _per_axis("divisions", divisions, 3)
    vertices, faces = _box_surface(size, cells)
    metadata = {"shape": "box", "size": size, "divisions": cells}
    return _mesh(vertices, faces, np.zeros(len(faces)), ["box"], metadata)


def box_wing(
    bus_size: Sequence[float] = (1.0, 1.0, 1.0),
    wing_span: float = 3.0,
    wing_width: float = 1.0,
    wing_gap: float = 0.5,
    facet_size: float = 0.1,
) -> MeshData:
    """Box bus with two flat solar wings along +y and -y: the classic box-wing model.

    The bus is a closed box centred at the origin. Each wing is a zero-thickness rectangle in the
    plane x = 0 (which contains the y axis), ``wing_span`` long along y and ``wing_width`` wide
    along z, centred on z = 0, its root edge ``wing_gap`` beyond the bus face, sharing no vertex
    with the bus. The wings' front normal is +x (solar cells face +x), their back -x; both wings
    are in ``two_sided_parts``.

    Parameters
    ----------
    bus_size : (3,) float
        Bus edge lengths along x, y, z [m].
    wing_span, wing_width : float
        Wing length along y and width along z [m].
    wing_gap : float
        Distance from the bus side face to the wing root [m], > 0.
    facet_size : float
        Largest facet edge along the grid lines [m]; each face gets ``ceil(length / facet_size)``
        cells per side.

    Returns
    -------
    MeshData
        Parts ``"bus"``, ``"wing_left"`` (-y), ``"wing_right"`` (+y).
    """
    _positive(wing_span=wing_span, wing_width=wing_width, wing_gap=wing_gap, facet_size=facet_size)
    bus_size = tuple(float(s) for s in bus_size)
    cells = tuple(_pieces(s, facet_size) for s in bus_size)
    bus = label(box(bus_size, cells), "bus")
    sheet = plate(wing_span, wing_width, (_pieces(wing_span, facet_size), _pieces(wing_width, facet_size)))
    # Plate (x, y, z) -> body (y, z, x): span along y, width along z, front normal +x.
    to_body = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    centre = bus_size[1] / 2 + wing_gap + wing_span / 2
    wings = [
        label(transform(sheet, to_body, (0.0, sign * centre, 0.0)), name)
        for sign, name in ((-1.0, "wing_left"), (1.0, "wing_right"))
    ]
    metadata = {
        "shape": "box_wing",
        "bus_size": bus_size,
        "wing_span": float(wing_span),
        "wing_width": float(wing_width),
        "wing_gap": float(wing_gap),
        "facet_size": float(facet_size),
    }
    mesh = MeshData.concatenate([bus, *wings], source="<box_wing>")
    return replace(mesh, two_sided_parts=frozenset({"wing_left", "wing_right"}), metadata=metadata)


# ----------------------------------------------------------------------------------- registry

#: Builders by name, for :func:`build` and the validation case table.
PRIMITIVES: dict[str, Callable[..., MeshData]] = {
    "plate": plate,
    "sphere": sphere,
    "cylinder": cylinder,
    "cone": cone,
    "dish": dish,
    "box": box,
    "box_wing": box_wing,
}


def build(kind: str, **params: Any) -> MeshData:
    """Build a primitive by name: ``build("cylinder", radius=0.5)``.

    A mesh is rebuilt from its metadata by ``meta = dict(mesh.metadata); build(meta.pop("shape"),
    **meta)``.

    Raises
    ------
    InputError
        Unknown ``kind`` or parameter (the message lists the valid ones), or a bad value.
    """
    if kind not in PRIMITIVES:
        raise InputError(f"unknown primitive '{kind}'", hint=f"choose one of: {', '.join(PRIMITIVES)}")
    builder = PRIMITIVES[kind]
    valid = list(inspect.signature(builder).parameters)
    unknown = [name for name in params if name not in valid]
    if unknown:
        raise InputError(
            f"primitive '{kind}' has no parameter '{unknown[0]}'",
            hint=f"its parameters are: {', '.join(valid)}",
        )
    return builder(**params)
