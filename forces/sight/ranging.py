"""Retroreflector ranging: the range offset of each visible array along the line of sight to a station,
and the range differences between arrays (METHOD.md "Lines of sight").

For a unit direction ``u`` from the spacecraft toward the station (body frame), array ``i`` at ``p_i``
returns a pulse earlier than the reference point ``c`` by its projection on ``u``: its range offset is
``-u . (p_i - c)`` [m] (the station is far: the lines from every array are parallel, to
``|p - c|^2 / (2 R)``, 5e-8 m for 10 m at 1000 km). An array whose line to the station is blocked, or
which sees the station outside its acceptance cone, returns nothing and is left out. The differences
``offset_i - offset_j = -u . (p_i - p_j)`` of the arrays seen together are what a station measures of
the attitude: two arrays at ``+-L`` on an axis ``a`` differ by ``-2 L cos(angle(a, u))``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.sight.lines import FRAME, LinesOfSight


@dataclass(frozen=True, eq=False)
class RangeOffsets:
    """Range offsets of retroreflector arrays for m station directions.

    Parameters
    ----------
    names : tuple of str
        The arrays (the points), n of them.
    directions : (m, 3) float64
        Unit directions from the spacecraft toward the station, body frame.
    offset_m : (n, m) float64
        ``-u . (p_i - c)`` [m] of each array seen (line clear and in its cone); NaN where it is not.
    reference_point_m : (3,) float64
        The point ``c`` the offsets are measured from [m], body frame.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sight import SightPoints, lines_of_sight
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> arrays = SightPoints.of(["a", "b"], [[0.4, 0, 0.5], [-0.4, 0, 0.5]], [[0, 0, 1]] * 2, [60.0] * 2)
    >>> u = [0.6, 0.0, 0.8]
    >>> ranges = range_offsets(lines_of_sight(model, arrays, u), [0.0, 0.0, 0.0])
    >>> ranges.offset_m.round(6).tolist(), ranges.differences(0)
    ([[-0.64], [-0.16]], [('a', 'b', -0.48)])
    """

    names: tuple[str, ...]
    directions: NDArray[np.float64]
    offset_m: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]

    def differences(self, j: int) -> list[tuple[str, str, float]]:
        """The range differences of the arrays seen in direction ``j``: every pair once, in point order.

        Parameters
        ----------
        j : int
            The direction.

        Returns
        -------
        list of (str, str, float)
            ``(a, b, offset_a - offset_b)`` [m], rounded to 1e-6 m.

        Examples
        --------
        >>> ranges = RangeOffsets(("a", "b", "c"), np.array([[0.0, 0.0, 1.0]]),
        ...                       np.array([[-1.0], [np.nan], [0.5]]), np.zeros(3))
        >>> ranges.differences(0)
        [('a', 'c', -1.5)]
        """
        seen = [k for k in range(len(self.names)) if np.isfinite(self.offset_m[k, j])]
        return [
            (self.names[a], self.names[b], round(float(self.offset_m[a, j] - self.offset_m[b, j]), 6))
            for n, a in enumerate(seen)
            for b in seen[n + 1 :]
        ]

    def to_json(self) -> dict:
        """Per direction: the offsets of the arrays seen and their pairwise differences (keys in metres).

        Returns
        -------
        dict
            ``frame``, ``reference_point_m``, ``offset_sign`` and ``directions``: each with
            ``direction``, ``offsets_m`` (array name to offset, the arrays seen), ``not_seen`` and
            ``differences_m`` (``from``, ``to``, ``difference_m``).

        Examples
        --------
        >>> ranges = RangeOffsets(("a", "b"), np.array([[0.0, 0.0, 1.0]]),
        ...                       np.array([[-1.0], [0.5]]), np.zeros(3))
        >>> ranges.to_json()["directions"][0]["differences_m"]
        [{'from': 'a', 'to': 'b', 'difference_m': -1.5}]
        """
        rows = []
        for j, u in enumerate(self.directions):
            seen = np.isfinite(self.offset_m[:, j])
            rows.append(
                {
                    "direction": u.tolist(),
                    "offsets_m": {
                        name: round(float(self.offset_m[k, j]), 6)
                        for k, name in enumerate(self.names)
                        if seen[k]
                    },
                    "not_seen": [name for k, name in enumerate(self.names) if not seen[k]],
                    "differences_m": [
                        {"from": a, "to": b, "difference_m": d} for a, b, d in self.differences(j)
                    ],
                }
            )
        return {
            "frame": FRAME,
            "reference_point_m": self.reference_point_m.tolist(),
            "offset_sign": "offset = -u . (p - c): negative for an array nearer the station than c",
            "directions": rows,
        }


def range_offsets(lines: LinesOfSight, reference_point_m: NDArray[np.float64] | list) -> RangeOffsets:
    """Range offsets of the arrays of ``lines`` toward a station, and which arrays are seen.

    Parameters
    ----------
    lines : LinesOfSight
        Lines of sight from the arrays toward the station, the same m directions for every array
        (:func:`~sunwind.forces.sight.lines.lines_of_sight`); an array is seen where its line is
        visible (clear and in its acceptance cone).
    reference_point_m : (3,) array_like of float
        The point ``c`` the offsets are measured from [m], body frame (the model's reference point).

    Returns
    -------
    RangeOffsets
        ``-u . (p_i - c)`` for the arrays seen, NaN for the others.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sight import SightPoints, lines_of_sight
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> arrays = SightPoints.of(["top", "bottom"], [[0, 0, 0.5], [0, 0, -0.5]], [[0, 0, 1], [0, 0, -1]],
    ...                         [60.0, 60.0])
    >>> range_offsets(lines_of_sight(model, arrays, [0.0, 0.0, 1.0]), [0, 0, 0]).offset_m.tolist()
    [[-0.5], [nan]]
    """
    u = lines.directions[0]
    c = np.asarray(reference_point_m, dtype=float)
    offsets = -np.einsum("mk,nk->nm", u, lines.points.position_m - c)
    return RangeOffsets(lines.points.names, u, np.where(lines.visible, offsets, np.nan), c)
