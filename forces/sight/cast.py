"""Casting lines of sight from points against the whole mesh: the first facet each line meets and
how far, with the ray origin lifted off the surface the point sits on (METHOD.md "Lines of sight").

Every batch is one call of the model's Embree scene (:meth:`~sunwind.geometry.rays.scene.RayScene.
intersect`). A line starts at ``p + c d`` (``c`` the clearance, ``d`` the unit direction), so a
sensor or retroreflector mounted on a face does not block itself; a facet met within the first
clearance after that origin (a grazing line on the point's own face, where float32 round-off can put
the origin a hair below it) is stepped over by casting again just past it. Surfaces nearer than
about two clearances to the point along the line thus never block it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.sides import SOLID
from sunwind.geometry.spacecraft import Spacecraft

#: Default clearance, as a share of the model's half-size (0.5 mm on a 10 m model): far above the
#: float32 round-off of scene coordinates (6e-8), far below any real feature.
CLEARANCE = 1e-4
#: Casts of a line that keeps meeting facets within a clearance of its origin.
_PASSES = 3
#: Directions probed to find points inside a closed body: the 26 of a cube's faces, edges and
#: corners, turned slightly off the axes so that none runs along a facet of an axis-aligned box.
_PROBES = np.array(
    [(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1) if (i, j, k) != (0, 0, 0)],
    dtype=float,
)


def clearance_of(craft: Spacecraft, clearance_m: float | None) -> float:
    """The clearance [m] lines start off their points: the given one, or ``CLEARANCE`` of the half-size.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    clearance_m : float or None
        A clearance [m], at least the float32 resolution of the model's scene and below 1 % of its
        size; None for the default.

    Returns
    -------
    float
        The clearance [m].

    Raises
    ------
    InputError
        A clearance that is not finite, below the scene's resolution, or above 1 % of its half-size.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> clearance_of(craft, None)
    5e-05
    """
    half = craft.scene.half_size
    if clearance_m is None:
        return CLEARANCE * half
    low, high = 1e-6 * half, 1e-2 * half
    if not (np.isfinite(clearance_m) and low <= clearance_m <= high):
        raise InputError(
            f"clearance_m {clearance_m:g} m must be from {low:.3g} m to {high:.3g} m on this model "
            "(1e-6 to 1e-2 of its half-size)",
            hint="leave it out for the default, 1e-4 of the half-size",
            parameters=("clearance_m",),
        )
    return float(clearance_m)


def cast(
    craft: Spacecraft, start_m: NDArray[np.float64], directions: NDArray[np.float64], clearance_m: float
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Cast lines from points and find the first facet each meets beyond the clearance.

    Parameters
    ----------
    craft : Spacecraft
        The model (its Embree scene is built once and kept).
    start_m : (k, 3) float64
        The points [m], body frame.
    directions : (k, 3) float64
        Unit directions from the points, body frame.
    clearance_m : float
        How far off its point each line starts [m] (module docstring).

    Returns
    -------
    facet : (k,) int64
        The first facet met; -1 where the line leaves the model.
    distance_m : (k,) float64
        Distance from the point to it [m]; NaN where the line is clear.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> start = np.array([[2.0, 0.0, 0.0], [0.5, 0.0, 0.0]])  # off the box, and on its +x face
    >>> facet, distance = cast(craft, start, np.array([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]), 1e-5)
    >>> (facet >= 0).tolist(), distance.round(6).tolist()
    ([True, False], [1.5, nan])
    """
    scene = craft.scene
    k = len(start_m)
    facet = np.full(k, -1, dtype=np.int64)
    distance = np.full(k, np.nan)
    along = np.full(k, clearance_m)  # where each line starts, measured from its point [m]
    todo = np.arange(k)
    for _ in range(_PASSES):
        if not len(todo):
            break
        d = directions[todo]
        origins = scene.to_scene(start_m[todo] + along[todo, None] * d)
        hit, t = scene.intersect(np.ascontiguousarray(origins), np.ascontiguousarray(d, dtype=np.float32))
        t_m = t.astype(np.float64) * scene.half_size
        met = hit >= 0
        near = met & (t_m < clearance_m)
        far = met & ~near
        facet[todo[far]] = hit[far]
        distance[todo[far]] = along[todo[far]] + t_m[far]
        along[todo[near]] += t_m[near] + clearance_m
        todo = todo[near]
    return facet, distance


def cast_from_points(
    craft: Spacecraft, position_m: NDArray[np.float64], directions: NDArray[np.float64], clearance_m: float
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Cast every direction of every point in one batch.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    position_m : (n, 3) float64
        The points [m], body frame.
    directions : (n, m, 3) float64
        Unit directions from each point, body frame.
    clearance_m : float
        How far off its point each line starts [m].

    Returns
    -------
    facet : (n, m) int64
        The first facet met, -1 where clear.
    distance_m : (n, m) float64
        Distance to it [m], NaN where clear.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> toward = np.array([[[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]])
    >>> facet, distance = cast_from_points(craft, np.array([[2.0, 0.0, 0.0]]), toward, 1e-5)
    >>> facet.shape, distance.round(6).tolist()
    ((1, 2), [[1.5, nan]])
    """
    n, m = directions.shape[:2]
    start = np.repeat(position_m, m, axis=0)
    facet, distance = cast(craft, start, directions.reshape(-1, 3), clearance_m)
    return facet.reshape(n, m), distance.reshape(n, m)


def inside_closed(
    craft: Spacecraft, position_m: NDArray[np.float64], clearance_m: float
) -> NDArray[np.bool_]:
    """Find the points inside a closed body: every probe line meets a closed body's facet from behind.

    26 lines are cast from each point; a point is inside when all of them first meet the back of a
    facet of a closed body (a point on a face, or in a concave corner, has open sky some way).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    position_m : (n, 3) float64
        The points [m], body frame.
    clearance_m : float
        How far off its point each line starts [m].

    Returns
    -------
    (n,) bool
        True for a point inside a closed body.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> craft = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> inside_closed(craft, np.array([[0.1, 0.2, 0.0], [0.5, 0.0, 0.0], [2.0, 0.0, 0.0]]), 1e-5).tolist()
    [True, False, False]
    """
    n = len(position_m)
    probes = _PROBES + np.array([0.0123, 0.0217, 0.0311])
    probes /= np.linalg.norm(probes, axis=1, keepdims=True)
    directions = np.broadcast_to(probes, (n, *probes.shape))
    facet, _ = cast_from_points(craft, position_m, directions, clearance_m)
    met = facet >= 0
    safe = np.where(met, facet, 0)
    behind = np.einsum("nmk,nmk->nm", craft.facet_normals[safe], directions) > 0
    closed = craft.facet_kind[safe] == SOLID
    return np.all(met & behind & closed, axis=1)
