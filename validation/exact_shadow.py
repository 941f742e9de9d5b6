"""Exact lit polygons of a small mesh in sunlight, by clipping: the reference for shadow edges.

For a side with outward normal ``n`` facing the Sun (``n . u > 0``), a point ``x`` of it is dark when a
ray ``x + t u`` (``t > 0``) meets another facet. A facet point ``q`` shades the side's plane at
``x = q - t u`` with ``t = (q - p0) . n / (u . n)``, so the shadow a facet casts is its part in front of
the plane, ``(q - p0) . n > 0``, projected along ``u``: a convex polygon. The lit region is the side's
triangle minus the union of those shadows, kept as disjoint convex pieces (a convex polygon minus a
convex polygon is cut along the subtrahend's edges). Area and centroid are exact to round-off; the
work grows with the number of facets squared, so it is for models of tens to hundreds of facets.
Shares no code with the ray-cast shadows it checks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: Pieces or shadows thinner than this share of the side's size are dropped (round-off slivers).
_SLIVER = 1e-12


@dataclass(frozen=True)
class LitSide:
    """The exactly lit part of one side: its area and centroid.

    Attributes
    ----------
    area_m2 : float
        Lit area [m^2].
    centroid_m : (3,) float64
        Centroid of the lit part [m]; the side's own centroid when it is dark.

    Examples
    --------
    >>> import numpy as np
    >>> floor = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    >>> roof = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]]
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> lit = lit_side(np.array([floor]), 0, up, up)
    >>> lit.area_m2, lit.centroid_m.round(6).tolist()
    (0.5, [0.333333, 0.333333, 0.0])
    """

    area_m2: float
    centroid_m: NDArray[np.float64]


def lit_side(triangles: NDArray[np.float64], index: int, normal: NDArray, sun: NDArray) -> LitSide:
    """Clip the lit part of the side of facet ``index``; every other facet may shade it.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of every facet of the model [m].
    index : int
        The facet whose side is wanted.
    normal : (3,) float64
        Outward unit normal of that side.
    sun : (3,) float64
        Unit Sun direction (toward the Sun), body frame.

    Returns
    -------
    LitSide
        Lit area [m^2] and centroid [m]; zero area when the side faces away from the Sun.

    Examples
    --------
    A triangle under a copy of itself 1 m above, Sun overhead: the lower one is dark, the upper one lit.

    >>> import numpy as np
    >>> floor = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    >>> roof = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]]
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> pair = np.array([floor, roof])
    >>> lit_side(pair, 0, up, up).area_m2, lit_side(pair, 1, up, up).area_m2
    (0.0, 0.5)
    """
    corners = triangles[index]
    origin = corners.mean(axis=0)
    facing = float(normal @ sun)
    if facing <= 0:
        return LitSide(0.0, origin)
    axis_u = corners[1] - corners[0]
    axis_u /= np.linalg.norm(axis_u)
    axis_v = np.cross(normal, axis_u)
    size = float(np.ptp(corners, axis=0).max())

    def plane(points: NDArray[np.float64]) -> NDArray[np.float64]:
        along = (points - origin) @ normal / facing  # the distance each point travels along -sun
        flat = points - along[:, None] * sun - origin
        return np.column_stack([flat @ axis_u, flat @ axis_v])

    pieces = [_counter_clockwise(plane(corners))]
    others = np.delete(np.arange(len(triangles)), index)
    for polygon in _front_parts(triangles[others], origin, normal, size):
        shadow = _counter_clockwise(plane(polygon))
        if abs(_area(shadow)) <= _SLIVER * size**2:
            continue
        pieces = [part for piece in pieces for part in _difference(piece, shadow, size)]
    areas = np.array([_area(piece) for piece in pieces])
    if areas.sum() <= 0:
        return LitSide(0.0, origin)
    centre = sum(a * _centroid(p) for a, p in zip(areas, pieces, strict=True)) / areas.sum()
    return LitSide(float(areas.sum()), origin + centre[0] * axis_u + centre[1] * axis_v)


def exact_sides(craft, sun: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact lit area and lit centroid of every side of a model under the Sun direction ``sun``.

    Parameters
    ----------
    craft : Spacecraft
        The model (:class:`~sunwind.geometry.spacecraft.Spacecraft`), tens to hundreds of facets.
    sun : (3,) float64
        Unit Sun direction (toward the Sun), body frame.

    Returns
    -------
    area : (n_sides,) float64
        Lit area of each side [m^2].
    centroid : (n_sides, 3) float64
        Lit centroid of each side [m] (the side's centroid where it is dark).

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> area, centroid = exact_sides(black, np.array([0.0, 0.0, 1.0]))
    >>> round(float(area.sum()), 12), int((area > 0).sum())  # the top face's two triangles
    (1.0, 2)
    """
    triangles = craft.vertices[craft.faces]
    lit = [lit_side(triangles, f, n, sun) for f, n in zip(craft.side_facet, craft.side_normals, strict=True)]
    return np.array([s.area_m2 for s in lit]), np.array([s.centroid_m for s in lit])


def exact_absorber_srp(craft, sun: NDArray[np.float64]) -> tuple[NDArray, NDArray, float]:
    """Direct SRP of a wholly absorbing model at a radiation pressure of 1 Pa, from its exact lit polygons.

    Parameters
    ----------
    craft : Spacecraft
        The model (:class:`~sunwind.geometry.spacecraft.Spacecraft`); its optics are ignored (every
        side absorbs).
    sun : (3,) float64
        Unit Sun direction (toward the Sun), body frame.

    Returns
    -------
    force : (3,) float64
        Force [N] at 1 Pa, ``-P A_lit,projected u``.
    torque : (3,) float64
        Torque about the origin [N m].
    area : float
        Lit area [m^2].

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> force, torque, area = exact_absorber_srp(black, np.array([0.0, 0.0, 1.0]))
    >>> (force.round(12) + 0.0).tolist(), round(area, 12)
    ([0.0, 0.0, -1.0], 1.0)
    """
    area, centre = exact_sides(craft, sun)
    force = -(area * np.clip(craft.side_normals @ sun, 0, None))[:, None] * sun
    return force.sum(axis=0), np.cross(centre, force).sum(axis=0), float(area.sum())


def _front_parts(triangles: NDArray, origin: NDArray, normal: NDArray, size: float) -> list[NDArray]:
    """Each triangle clipped to the open half-space in front of the plane through ``origin``."""
    out = []
    for corners in triangles:
        height = (corners - origin) @ normal
        if np.all(height <= _SLIVER * size):
            continue
        kept = _clip(corners, height - _SLIVER * size)
        if len(kept) >= 3:
            out.append(kept)
    return out


def _clip(points: NDArray[np.float64], value: NDArray[np.float64]) -> NDArray[np.float64]:
    """The polygon ``points`` where the linear function with vertex values ``value`` is >= 0."""
    out = []
    for k in range(len(points)):
        a, b, fa, fb = points[k - 1], points[k], value[k - 1], value[k]
        if (fa >= 0) != (fb >= 0):
            out.append(a + (b - a) * (fa / (fa - fb)))
        if fb >= 0:
            out.append(b)
    return np.array(out) if out else np.empty((0, points.shape[1]))


def _difference(piece: NDArray, shadow: NDArray, size: float) -> list[NDArray]:
    """Convex ``piece`` minus convex counter-clockwise ``shadow``, as disjoint convex pieces."""
    out, inside = [], piece
    for k in range(len(shadow)):
        a, b = shadow[k - 1], shadow[k]
        edge = b - a
        left = edge[0] * (inside[:, 1] - a[1]) - edge[1] * (inside[:, 0] - a[0])  # > 0: inside the shadow
        outside = _clip(inside, -left)
        if len(outside) >= 3 and _area(outside) > _SLIVER * size**2:
            out.append(outside)
        inside = _clip(inside, left)
        if len(inside) < 3 or _area(inside) <= _SLIVER * size**2:
            return out
    return out


def _area(polygon: NDArray[np.float64]) -> float:
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _centroid(polygon: NDArray[np.float64]) -> NDArray[np.float64]:
    x, y = polygon[:, 0], polygon[:, 1]
    cross = x * np.roll(y, -1) - np.roll(x, -1) * y
    return np.array([np.dot(x + np.roll(x, -1), cross), np.dot(y + np.roll(y, -1), cross)]) / (
        3 * cross.sum()
    )


def _counter_clockwise(polygon: NDArray[np.float64]) -> NDArray[np.float64]:
    return polygon if _area(polygon) >= 0 else polygon[::-1]
