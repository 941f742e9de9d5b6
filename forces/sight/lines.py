"""Lines of sight from named points in given directions: clear or blocked (by which part, how far),
and inside the point's cone or not (METHOD.md "Lines of sight")."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.model import Model, as_model
from sunwind.forces.sight.cast import cast_from_points, clearance_of, inside_closed
from sunwind.forces.sight.points import SightPoints
from sunwind.geometry.errors import FlaggedWarning, InputError

#: The frame and units of every output, said in the text and the JSON.
FRAME = "body frame of the mesh; positions [m]; directions are unit vectors from the point toward the target"


@dataclass(frozen=True, eq=False)
class LinesOfSight:
    """Lines of sight of n points in m directions each, body frame.

    Parameters
    ----------
    points : SightPoints
        The points, with their cones.
    directions : (n, m, 3) float64
        Unit directions from each point toward the target, body frame.
    facet : (n, m) int64
        First facet each line meets; -1 where the line is clear.
    distance_m : (n, m) float64
        Distance from the point to that facet [m]; NaN where clear.
    blocking_part : (n, m) int64
        Index into ``part_names`` of the part met; -1 where clear.
    part_names : tuple of str
        The model's parts.
    inside : (n,) bool
        The point lies inside a closed body: every line from it is blocked.
    clearance_m : float
        How far off its point each line starts [m] (a point on a face does not block itself).

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> points = SightPoints.of(["camera"], [[2.0, 0.0, 0.0]], [[-1, 0, 0]], [20.0])
    >>> lines = lines_of_sight(model, points, [[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    >>> lines.clear.tolist(), lines.in_cone.tolist(), lines.visible.tolist()
    ([[False, True]], [[True, False]], [[False, False]])
    """

    points: SightPoints
    directions: NDArray[np.float64]
    facet: NDArray[np.int64]
    distance_m: NDArray[np.float64]
    blocking_part: NDArray[np.int64]
    part_names: tuple[str, ...]
    inside: NDArray[np.bool_]
    clearance_m: float

    @property
    def clear(self) -> NDArray[np.bool_]:
        """(n, m) bool: the line leaves the model without meeting a facet (and the point is outside)."""
        return (self.facet < 0) & ~self.inside[:, None]

    @property
    def in_cone(self) -> NDArray[np.bool_]:
        """(n, m) bool: the direction lies within the point's cone (always, without a cone)."""
        return self.points.in_cone(self.directions)

    @property
    def visible(self) -> NDArray[np.bool_]:
        """(n, m) bool: clear and in the cone."""
        return self.clear & self.in_cone

    def blocked_by(self, i: int, j: int) -> str | None:
        """The part that blocks point ``i``'s line ``j``; None when it is clear.

        Parameters
        ----------
        i, j : int
            Point and direction.

        Returns
        -------
        str or None
            The part's name, ``"(inside a closed body)"`` for a point inside one, None when clear.

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
        >>> lines = lines_of_sight(model, SightPoints.of(["p"], [[2.0, 0.0, 0.0]]), [-1.0, 0.0, 0.0])
        >>> lines.blocked_by(0, 0)
        'box'
        """
        if self.blocking_part[i, j] >= 0:
            return self.part_names[self.blocking_part[i, j]]
        return "(inside a closed body)" if self.inside[i] else None

    def to_json(self) -> dict:
        """The lines as a JSON-ready dict: per point, its cone and each line (keys carry units).

        Returns
        -------
        dict
            ``frame``, ``clearance_m`` and ``points``: each with ``name``, ``position_m``,
            ``boresight``, ``half_angle_deg`` (None without a cone), ``inside_closed_body`` and
            ``lines`` (``direction``, ``clear``, ``blocked_by``, ``distance_m``, ``in_cone``,
            ``off_boresight_deg``, ``visible``).

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
        >>> lines = lines_of_sight(model, SightPoints.of(["p"], [[2.0, 0.0, 0.0]]), [-1.0, 0.0, 0.0])
        >>> line = lines.to_json()["points"][0]["lines"][0]
        >>> line["blocked_by"], line["distance_m"], line["visible"]
        ('box', 1.5, False)
        """
        p = self.points
        off = p.off_boresight_deg(self.directions)
        clear, in_cone, visible = self.clear, self.in_cone, self.visible
        out = []
        for i, name in enumerate(p.names):
            cone = bool(p.has_cone[i])
            lines = [
                {
                    "direction": self.directions[i, j].tolist(),
                    "clear": bool(clear[i, j]),
                    "blocked_by": self.blocked_by(i, j),
                    "distance_m": _number(self.distance_m[i, j]),
                    "in_cone": bool(in_cone[i, j]),
                    "off_boresight_deg": _number(off[i, j]) if cone else None,
                    "visible": bool(visible[i, j]),
                }
                for j in range(self.directions.shape[1])
            ]
            out.append(
                {
                    "name": name,
                    "position_m": p.position_m[i].tolist(),
                    "boresight": p.boresight[i].tolist() if cone else None,
                    "half_angle_deg": float(p.half_angle_deg[i]) if cone else None,
                    "inside_closed_body": bool(self.inside[i]),
                    "lines": lines,
                }
            )
        return {"frame": FRAME, "clearance_m": self.clearance_m, "points": out}


def _number(value: float) -> float | None:
    """A float for JSON rounded to 1e-6 (a micrometre, a microdegree: below float32's ray precision),
    None for NaN."""
    return None if not np.isfinite(value) else round(float(value), 6)


def directions_for(directions: object, n: int) -> NDArray[np.float64]:
    """Directions as unit vectors, shape (n, m, 3): one direction, m shared ones, or m per point.

    Parameters
    ----------
    directions : array_like of float, shape (3,), (m, 3) or (n, m, 3)
        Directions from the points toward the target, body frame, any non-zero length.
    n : int
        Number of points.

    Returns
    -------
    (n, m, 3) float64
        Unit directions.

    Raises
    ------
    InputError
        Another shape, a non-finite number, or a zero direction.

    Examples
    --------
    >>> directions_for([0.0, 0.0, 2.0], 2).tolist()
    [[[0.0, 0.0, 1.0]], [[0.0, 0.0, 1.0]]]
    >>> directions_for([0.0, 0.0, 0.0], 1)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: directions: direction 0 has zero length; ...
    """
    d = np.asarray(directions, dtype=float)
    if d.ndim == 1:
        d = d[None]
    if d.ndim == 2:
        d = np.broadcast_to(d, (n, *d.shape))
    if d.ndim != 3 or d.shape[0] != n or d.shape[2] != 3 or d.shape[1] == 0:
        raise InputError(
            f"directions of shape {np.shape(directions)} are not (3,), (m, 3) or ({n}, m, 3)",
            parameters=("directions",),
        )
    if not np.all(np.isfinite(d)):
        raise InputError("directions hold a number that is not finite", parameters=("directions",))
    norm = np.linalg.norm(d, axis=2, keepdims=True)
    if np.any(norm == 0):
        zero = int(np.argwhere(norm[..., 0] == 0)[0, -1])
        raise InputError(
            f"directions: direction {zero} has zero length",
            hint="give a direction from the point toward the target, e.g. 1 0 0",
            parameters=("directions",),
        )
    return d / norm


def lines_of_sight(
    model: Model,
    points: SightPoints,
    directions: object,
    *,
    clearance_m: float | None = None,
) -> LinesOfSight:
    """Cast lines of sight from points of a model: clear or blocked (by which part, how far), in cone.

    All lines go to Embree in one batch. A point on a face does not block itself (its lines start
    ``clearance_m`` off it); a point inside a closed body is warned about and all its lines are blocked.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model (its pose as loaded).
    points : SightPoints
        The points [m], body frame, with optional cones (:func:`~sunwind.forces.sight.points.
        read_points`, :meth:`SightPoints.of`).
    directions : array_like of float, shape (3,), (m, 3) or (n, m, 3)
        Directions from the points toward the target, body frame (normalised here).
    clearance_m : float or None, optional
        How far off its point each line starts [m]; default 1e-4 of the model's half-size.

    Returns
    -------
    LinesOfSight
        Per point and direction: clear, the part met and its distance, in cone.

    Raises
    ------
    InputError
        A zero or non-finite direction, a clearance out of range.

    Warns
    -----
    FlaggedWarning
        A point lies inside a closed body.

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> points = SightPoints.of(["on_face"], [[0.5, 0.0, 0.0]])  # on the +x face of the unit box
    >>> lines = lines_of_sight(model, points, [[1.0, 0.0, 0.0], [1.0, 0.0, 0.01], [-1.0, 0.0, 0.0]])
    >>> lines.clear.tolist(), lines.blocked_by(0, 2), round(float(lines.distance_m[0, 2]), 6)
    ([[True, True, False]], 'box', 1.0)
    """
    craft = as_model(model).craft
    d = directions_for(directions, len(points.names))
    clearance = clearance_of(craft, clearance_m)
    facet, distance = cast_from_points(craft, points.position_m, d, clearance)
    inside = inside_closed(craft, points.position_m, clearance)
    for name in [n for n, k in zip(points.names, inside, strict=True) if k]:
        warnings.warn(
            f"point {name!r} lies inside a closed body of {craft.source}: every line from it is "
            "reported blocked; check its position (metres, body frame of the mesh)",
            FlaggedWarning,
            stacklevel=2,
        )
    facet[inside] = -1
    distance[inside] = np.nan
    part = np.where(facet >= 0, craft.facet_part[np.maximum(facet, 0)], -1).astype(np.int64)
    return LinesOfSight(points, d, facet, distance, part, craft.part_names, inside, clearance)
