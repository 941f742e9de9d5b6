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

Shapes of revolution are rings of vertices about the z axis (:mod:`sunwind.meshes.triangulation`):
zipped into triangles for the cylinder, the cone and flat discs; the sphere is the convex hull of
its rings and the dish the Delaunay triangulation of its rings' (x, y), so both curve one way
everywhere. The sphere, cylinder and cone are exactly convex: no facet sees another.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from scipy.spatial import ConvexHull, Delaunay

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData
from sunwind.meshes.arguments import (
    HULL_TRIANGLE_BYTES,
    MAX_LENGTH_M,
    check_count,
    check_lengths,
    check_positive,
    check_triangles,
    per_axis,
)
from sunwind.meshes.assembly import assemble, label, transform
from sunwind.meshes.triangulation import (
    box_surface,
    equal_pieces,
    grid_faces,
    oriented,
    revolved_parts,
    ring_counts,
    ring_vertices,
)

__all__ = [
    "CONE_SEGMENTS",
    "CYLINDER_SEGMENTS",
    "DISH_SEGMENTS",
    "PLATE_DIVISIONS",
    "PRIMITIVES",
    "SPHERE_SUBDIVISIONS",
    "box",
    "box_wing",
    "build",
    "cone",
    "cylinder",
    "dish",
    "plate",
    "sensor_cube",
    "sphere",
]

# Default resolutions; the error each gives is derived in the builders' docstrings.
SPHERE_SUBDIVISIONS = 216
CYLINDER_SEGMENTS = 320
CONE_SEGMENTS = 360
DISH_SEGMENTS = 480
PLATE_DIVISIONS = 32


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = plate(2.0, 1.0, divisions=(2, 1))
    >>> mesh.n_faces, mesh.part_names, mesh.vertices.min(axis=0).tolist()
    (4, ('plate',), [-1.0, -0.5, 0.0])
    """
    check_lengths(size_x=size_x, size_y=size_y)
    nx, ny = per_axis("divisions", divisions, 2)
    check_triangles(2 * nx * ny, "lower divisions", ("divisions",))
    x, y = np.meshgrid(
        np.linspace(-size_x / 2, size_x / 2, nx + 1),
        np.linspace(-size_y / 2, size_y / 2, ny + 1),
        indexing="ij",
    )
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    faces = grid_faces(nx, ny)
    metadata = {"shape": "plate", "size_x": float(size_x), "size_y": float(size_y), "divisions": (nx, ny)}
    return assemble(vertices, faces, np.zeros(len(faces)), ["plate"], metadata)


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = sphere(0.5, subdivisions=4)
    >>> mesh.n_faces, bool(np.allclose(np.linalg.norm(mesh.vertices, axis=1), 0.5))
    (40, True)
    """
    check_lengths(radius=radius)
    check_count(2, subdivisions=subdivisions)
    check_triangles(
        26 * int(subdivisions) ** 2 // 10, "lower subdivisions", ("subdivisions",), HULL_TRIANGLE_BYTES
    )
    theta = np.linspace(np.pi, 0.0, subdivisions + 1)
    r = radius * np.sin(theta)
    r[[0, -1]] = 0.0
    vertices, _ = ring_vertices(r, radius * np.cos(theta), ring_counts(r, 2 * subdivisions))
    hull = ConvexHull(vertices)
    faces = oriented(hull.simplices, hull.equations[:, :3], vertices)
    metadata = {"shape": "sphere", "radius": float(radius), "subdivisions": int(subdivisions)}
    return assemble(vertices, faces, np.zeros(len(faces)), ["sphere"], metadata)


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = cylinder(0.5, 1.0, segments=8)
    >>> mesh.n_faces, mesh.part_names, mesh.metadata["rings"]
    (80, ('cap_bottom', 'lateral', 'cap_top'), 3)
    """
    check_lengths(radius=radius, length=length)
    check_count(3, segments=segments)
    facet = 2 * np.pi * radius / segments
    if rings is None:
        rings = equal_pieces(length, facet)
    check_count(1, rings=rings)
    metadata = {
        "shape": "cylinder",
        "radius": float(radius),
        "length": float(length),
        "segments": int(segments),
        "rings": int(rings),
        "caps": bool(caps),
    }
    half, cap = length / 2, equal_pieces(radius, facet)
    if caps:
        corners = [(0.0, -half), (radius, -half), (radius, half), (0.0, half)]
        return revolved_parts(
            corners, [cap, rings, cap], ["cap_bottom", "lateral", "cap_top"], segments, metadata
        )
    return revolved_parts([(radius, -half), (radius, half)], [rings], ["lateral"], segments, metadata)


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = cone(1.0, half_angle_deg=45.0, segments=8)
    >>> mesh.part_names, round(float(mesh.vertices[:, 2].max()), 6)
    (('base', 'lateral'), 1.0)
    """
    check_lengths(radius=radius)
    check_positive(half_angle_deg=half_angle_deg)
    check_count(3, segments=segments)
    if not half_angle_deg < 90:
        raise InputError(f"half_angle_deg = {half_angle_deg!r} must be in (0, 90)")
    height = radius / math.tan(math.radians(half_angle_deg))
    if height > MAX_LENGTH_M:
        raise InputError(
            f"half_angle_deg {half_angle_deg:g} makes the cone {height:.3g} m tall, above {MAX_LENGTH_M:g} m",
            hint=f"widen the half-angle to at least {math.degrees(math.atan(radius / MAX_LENGTH_M)):.3g} deg",
            parameters=("half_angle_deg",),
        )
    facet = 2 * np.pi * radius / segments
    if rings is None:
        rings = equal_pieces(math.hypot(radius, height), facet)
    check_count(1, rings=rings)
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
        pieces, parts = [equal_pieces(radius, facet), rings], ["base", "lateral"]
        return revolved_parts(corners, pieces, parts, segments, metadata, generator_legs=[1])
    corners = [(radius, 0.0), (0.0, height)]
    return revolved_parts(corners, [rings], ["lateral"], segments, metadata, generator_legs=[0])


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = dish(1.2, 0.35, segments=8)
    >>> mesh.part_names, round(float(mesh.vertices[:, 2].max()), 4)
    (('dish',), 0.2143)
    """
    check_lengths(diameter=diameter)
    check_positive(focal_ratio=focal_ratio)
    check_count(3, segments=segments)
    focal = focal_ratio * diameter
    # Rings equally spaced in arc length along the parabola, from the vertex out.
    fine = np.linspace(0.0, diameter / 2, 4097)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(fine), np.diff(fine**2) / (4 * focal)))])
    pieces = equal_pieces(arc[-1], np.pi * diameter / segments)
    check_triangles(int(segments) * pieces, "lower segments", ("segments",), HULL_TRIANGLE_BYTES)
    r = np.interp(np.linspace(0.0, arc[-1], pieces + 1), arc, fine)
    vertices, _ = ring_vertices(r, r**2 / (4 * focal), ring_counts(r, segments))
    faces = oriented(Delaunay(vertices[:, :2]).simplices, np.array([0.0, 0.0, 1.0]), vertices)
    metadata = {
        "shape": "dish",
        "diameter": float(diameter),
        "focal_ratio": float(focal_ratio),
        "segments": int(segments),
    }
    return assemble(vertices, faces, np.zeros(len(faces)), ["dish"], metadata)


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = box((1.0, 2.0, 3.0), divisions=2)
    >>> mesh.n_faces, np.ptp(mesh.vertices, axis=0).tolist()
    (48, [1.0, 2.0, 3.0])
    """
    size = tuple(float(s) for s in size)
    if len(size) != 3:
        raise InputError(f"size = {size!r} must be three edge lengths")
    check_lengths(size=size)
    cells = per_axis("divisions", divisions, 3)
    nx, ny, nz = cells
    check_triangles(4 * (nx * ny + ny * nz + nz * nx), "lower divisions", ("divisions",))
    vertices, faces = box_surface(size, cells)
    metadata = {"shape": "box", "size": size, "divisions": cells}
    return assemble(vertices, faces, np.zeros(len(faces)), ["box"], metadata)


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

    Raises
    ------
    InputError
        A size that is not a finite length > 0, or a count out of range.

    Examples
    --------
    >>> mesh = box_wing(facet_size=0.5)
    >>> mesh.part_names, sorted(mesh.two_sided_parts)
    (('bus', 'wing_left', 'wing_right'), ['wing_left', 'wing_right'])
    """
    check_lengths(wing_span=wing_span, wing_width=wing_width, wing_gap=wing_gap, facet_size=facet_size)
    bus_size = tuple(float(s) for s in bus_size)
    check_lengths(bus_size=bus_size)
    cells = tuple(equal_pieces(s, facet_size) for s in bus_size)
    span, width = equal_pieces(wing_span, facet_size), equal_pieces(wing_width, facet_size)
    nx, ny, nz = cells
    check_triangles(4 * (nx * ny + ny * nz + nz * nx + span * width), "raise facet_size", ("facet_size",))
    bus = label(box(bus_size, cells), "bus")
    sheet = plate(wing_span, wing_width, (span, width))
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


def sensor_cube(size: float = 0.1, panel: bool = False, panel_length: float = 0.2) -> MeshData:
    """A cube with a heat-flux sensor on every face, and optionally a deployed panel that shades one.

    The closed cube of edge ``size`` is centred at the origin; each face is its own part,
    ``sensor_px``, ``sensor_mx``, ``sensor_py``, ``sensor_my``, ``sensor_pz``, ``sensor_mz`` (the face
    whose outward normal is +x, -x, ...), the case of the heat-flux dissertation (six plates on a small
    satellite's faces). With ``panel``, a closed 2 mm thick panel ``size`` wide is hinged at the top
    edge of the +y face (1 mm from it) and stands out along +y for ``panel_length``, in the plane of
    the top face: it shades ``sensor_py`` from light that comes from above and in front of it.

    Parameters
    ----------
    size : float
        Cube edge [m].
    panel : bool
        Add the deployed panel (part ``"panel"``).
    panel_length : float
        How far the panel stands out [m].

    Returns
    -------
    MeshData
        Six sensor parts (and ``"panel"``), 12 triangles per box.

    Raises
    ------
    InputError
        A size that is not a finite length > 0.

    Examples
    --------
    >>> mesh = sensor_cube()
    >>> mesh.part_names
    ('sensor_px', 'sensor_mx', 'sensor_py', 'sensor_my', 'sensor_pz', 'sensor_mz')
    >>> sensor_cube(panel=True).part_names[-1], float(sensor_cube(panel=True).vertices[:, 1].max())
    ('panel', 0.251)
    """
    check_lengths(size=size, panel_length=panel_length)
    cube = box((size, size, size))
    corners = cube.vertices[cube.faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    axis = np.argmax(np.abs(normals), axis=1)
    negative = normals[np.arange(len(normals)), axis] < 0
    names = ("sensor_px", "sensor_mx", "sensor_py", "sensor_my", "sensor_pz", "sensor_mz")
    cube = replace(cube, face_part=(2 * axis + negative).astype(np.int32), part_names=names)
    metadata = {
        "shape": "sensor_cube",
        "size": float(size),
        "panel": bool(panel),
        "panel_length": float(panel_length),
    }
    if not panel:
        return replace(cube, metadata=metadata, source="<sensor_cube>")
    thickness, gap = 0.002, 0.001  # the hinge's gap keeps the two bodies apart
    centre = (0.0, size / 2 + gap + panel_length / 2, size / 2 - thickness / 2)
    wing = label(transform(box((size, panel_length, thickness)), translation=centre), "panel")
    return replace(MeshData.concatenate([cube, wing], source="<sensor_cube>"), metadata=metadata)


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
    "sensor_cube": sensor_cube,
}


def build(kind: str, **params: Any) -> MeshData:
    """Build a primitive by name, e.g. ``build("cylinder", radius=0.5)``.

    A mesh is rebuilt from its metadata by ``meta = dict(mesh.metadata); build(meta.pop("shape"),
    **meta)``.

    Parameters
    ----------
    kind : str
        A key of :data:`PRIMITIVES`: ``"plate"``, ``"sphere"``, ``"cylinder"``, ...
    **params : Any
        Keyword arguments of that builder.

    Returns
    -------
    MeshData
        The mesh.

    Raises
    ------
    InputError
        Unknown ``kind`` or parameter (the message lists the valid ones), or a bad value.

    Examples
    --------
    >>> mesh = cylinder(0.5, 1.0, segments=6)
    >>> meta = dict(mesh.metadata)
    >>> bool(np.array_equal(build(meta.pop("shape"), **meta).vertices, mesh.vertices))
    True
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
