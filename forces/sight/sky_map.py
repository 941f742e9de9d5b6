"""Maps of what blocks each point's view over azimuth and elevation, and the blocked fraction of its
field of view with an error estimate (METHOD.md "Lines of sight").

The grid is in the body frame: azimuth ``atan2(y, x)`` from +x toward +y in [-180, 180), elevation
``asin(z)`` from the xy plane toward +z in [-90, 90], cells of equal steps in both. One line is cast
through each cell's centre; a cell counts with its solid angle ``dA (sin el_hi - sin el_lo)``. The
field of view is the cells whose centre lies in the point's cone (the whole sky without one), and the
blocked fraction is the solid-angle-weighted share of its cells whose line is blocked. Its error
estimate is the larger of two: the change on a grid twice as coarse, ``|F_h - F_2h|``, and four times
the edge-cell spread ``sqrt((sum_N w^2 + F^2 sum_W w^2) / 24) / W``. An edge cell (one whose state
differs from a neighbour's; two per crossing of an edge) is classed whole by its centre while a share
of it, uniform in [0, 1], lies on the other side, an error of standard deviation ``w / sqrt(12)``: the
edge cells of the blocked part of the view (``sum_N``) move the numerator, those of the cone's edge
(``sum_W``) the denominator ``W``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from importlib.metadata import version

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.model import Model, as_model
from sunwind.forces.sight.cast import cast_from_points, clearance_of, inside_closed
from sunwind.forces.sight.lines import FRAME
from sunwind.forces.sight.points import SightPoints
from sunwind.geometry import memory
from sunwind.geometry.errors import FlaggedWarning, InputError

#: Steps a map may take [deg] (the error estimate's grid is twice as coarse).
STEP_RANGE_DEG = (0.1, 15.0)
#: Cells a field of view should span; fewer and its fraction is coarse (a warning says so).
FEW_CELLS = 30
#: Bytes per cast line (origins, directions, results, the map).
_LINE_BYTES = 120


@dataclass(frozen=True, eq=False)
class SightMap:
    """Per point, the blocked cells of an azimuth-elevation grid and the blocked fraction of its view.

    Parameters
    ----------
    points : SightPoints
        The points.
    azimuth_deg : (n_az,) float64
        Cell centres [deg], ``atan2(y, x)`` in the body frame.
    elevation_deg : (n_el,) float64
        Cell centres [deg], ``asin(z)`` in the body frame.
    blocking_part : (n, n_el, n_az) int16
        Index into ``part_names`` of the part each cell's line meets; -1 clear (every cell of a point
        inside a closed body is blocked, with part -2).
    in_view : (n, n_el, n_az) bool
        The cell's centre lies in the point's cone.
    solid_angle_sr : (n_el,) float64
        Solid angle of a cell of each elevation row [sr].
    blocked_fraction : (n,) float64
        Solid-angle-weighted blocked share of each field of view.
    error_estimate : (n,) float64
        The larger of ``|F_h - F_2h|`` (the change on a grid twice as coarse) and four edge-cell
        standard deviations (module docstring).
    part_names : tuple of str
        The model's parts.
    clearance_m : float
        How far off its point each line starts [m].

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> points = SightPoints.of(["on_top"], [[0.0, 0.0, 0.5]])  # on the top face: half the sky is the box
    >>> view = blocked_map(model, points, step_deg=5.0)
    >>> view.blocking_part.shape, round(float(view.blocked_fraction[0]), 3)
    ((1, 36, 72), 0.5)
    """

    points: SightPoints
    azimuth_deg: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    blocking_part: NDArray[np.int16]
    in_view: NDArray[np.bool_]
    solid_angle_sr: NDArray[np.float64]
    blocked_fraction: NDArray[np.float64]
    error_estimate: NDArray[np.float64]
    part_names: tuple[str, ...]
    clearance_m: float

    @property
    def step_deg(self) -> float:
        """The grid's step [deg] in azimuth and elevation."""
        return float(180.0 / len(self.elevation_deg))

    @property
    def fraction_by_part(self) -> NDArray[np.float64]:
        """(n, n_parts) float64: the share of each field of view each part blocks."""
        w = self.solid_angle_sr[None, :, None] * self.in_view
        total = w.sum(axis=(1, 2))
        parts = [(w * (self.blocking_part == k)).sum(axis=(1, 2)) for k in range(len(self.part_names))]
        return np.stack(parts, axis=1) / total[:, None]

    def to_json(self) -> dict:
        """Each point's blocked fraction, its error estimate and the share of each part.

        Returns
        -------
        dict
            ``frame``, ``grid`` (conventions, ``step_deg``), ``clearance_m`` and ``points``: per point
            ``name``, ``field_of_view_sr``, ``blocked_fraction``, ``error_estimate``,
            ``blocked_fraction_by_part`` (parts that block some of it).

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
        >>> view = blocked_map(model, SightPoints.of(["on_top"], [[0.0, 0.0, 0.5]]), step_deg=5.0)
        >>> view.to_json()["points"][0]["blocked_fraction_by_part"]
        {'box': 0.5}
        """
        w = self.solid_angle_sr[None, :, None] * self.in_view
        by_part = self.fraction_by_part
        rows = []
        for i, name in enumerate(self.points.names):
            rows.append(
                {
                    "name": name,
                    "field_of_view_sr": round(float(w[i].sum()), 6),
                    "blocked_fraction": round(float(self.blocked_fraction[i]), 6),
                    "error_estimate": round(float(self.error_estimate[i]), 6),
                    "blocked_fraction_by_part": {
                        part: round(float(by_part[i, k]), 6)
                        for k, part in enumerate(self.part_names)
                        if by_part[i, k] > 0
                    },
                }
            )
        grid = {"conventions": GRID, "step_deg": self.step_deg}
        return {"frame": FRAME, "grid": grid, "clearance_m": self.clearance_m, "points": rows}

    def to_dataset(self, source: str = "") -> object:
        """The maps as an xarray Dataset with units and conventions, for netCDF.

        Parameters
        ----------
        source : str, optional
            The mesh the maps were made on, kept in the attributes.

        Returns
        -------
        xarray.Dataset
            ``blocking_part`` and ``in_field_of_view`` on (point, elevation_deg, azimuth_deg),
            ``blocked_fraction`` with its ``error_estimate`` on point, the share of
            each part, the points' positions and cones.

        Examples
        --------
        >>> import sunwind as sw
        >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
        >>> view = blocked_map(model, SightPoints.of(["on_top"], [[0.0, 0.0, 0.5]]), step_deg=5.0)
        >>> table = view.to_dataset()
        >>> table["blocked_fraction"].attrs["units"], table["blocking_part"].dims
        ('1', ('point', 'elevation_deg', 'azimuth_deg'))
        """
        import xarray as xr

        p = self.points
        cell = ("point", "elevation_deg", "azimuth_deg")
        data = {
            "blocking_part": (cell, self.blocking_part, _attrs("1", "index of the part the line meets")),
            "in_field_of_view": (cell, self.in_view.astype(np.int8), _attrs("1", "cell centre in the cone")),
            "solid_angle_sr": ("elevation_deg", self.solid_angle_sr, _attrs("sr", "solid angle of a cell")),
            "blocked_fraction": ("point", self.blocked_fraction, _attrs("1", "blocked share of the view")),
            "error_estimate": ("point", self.error_estimate, _attrs("1", "max(|F_h - F_2h|, 4 edge sigma)")),
            "blocked_fraction_by_part": (("point", "part"), self.fraction_by_part, _attrs("1", "share")),
            "position_m": (("point", "axis"), p.position_m, _attrs("m", "point, body frame")),
            "boresight": (("point", "axis"), p.boresight, _attrs("1", "cone axis, body frame")),
            "half_angle_deg": ("point", p.half_angle_deg, _attrs("degree", "cone half angle")),
        }
        coords = {
            "point": list(p.names),
            "elevation_deg": (
                "elevation_deg",
                self.elevation_deg,
                {"units": "degree", "long_name": "asin(z)"},
            ),
            "azimuth_deg": ("azimuth_deg", self.azimuth_deg, {"units": "degree", "long_name": "atan2(y, x)"}),
            "part": list(self.part_names),
            "axis": ["x", "y", "z"],
        }
        attrs = {
            "conventions": GRID,
            "frame": FRAME,
            "step_deg": self.step_deg,
            "clearance_m": self.clearance_m,
            "blocking_part_codes": "-1 clear, -2 point inside a closed body, else index into part",
            "mesh": source,
            "sunwind_version": version("sunwind"),
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)


#: The grid's conventions, in words.
GRID = (
    "body frame; azimuth = atan2(y, x) from +x toward +y, elevation = asin(z) from the xy plane toward +z; "
    "cell centres; one line per cell"
)


def _attrs(units: str, long_name: str) -> dict:
    return {"units": units, "long_name": long_name, "frame": "body"}


def grid(step_deg: float) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The cell centres and solid angles of a grid of about ``step_deg``, its rows a multiple of four.

    Parameters
    ----------
    step_deg : float
        The step asked for [deg]; the grid takes ``180 / n_el`` with ``n_el`` a multiple of 4, at most
        the step (so that the equator is a row edge on the grid and on the one twice as coarse).

    Returns
    -------
    azimuth_deg : (2 n_el,) float64
        Cell centres [deg].
    elevation_deg : (n_el,) float64
        Cell centres [deg].
    solid_angle_sr : (n_el,) float64
        Solid angle of one cell of each row [sr]; they sum to 4 pi over the grid.

    Raises
    ------
    InputError
        A step outside ``STEP_RANGE_DEG``.

    Examples
    --------
    >>> az, el, w = grid(15.0)
    >>> el.tolist()[:3], len(az), round(float(w.sum() * len(az) / (4 * np.pi)), 12)
    ([-82.5, -67.5, -52.5], 24, 1.0)
    """
    low, high = STEP_RANGE_DEG
    if not (math.isfinite(step_deg) and low <= step_deg <= high):
        raise InputError(
            f"step_deg {step_deg:g} must be from {low:g} to {high:g} degrees",
            hint="2 degrees (the default) gives fractions to about 1e-3 on a spacecraft",
            parameters=("step_deg",),
        )
    return _cells(4 * math.ceil(45.0 / step_deg - 1e-9))


def _cells(n_el: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Cell centres (azimuth, elevation) [deg] and row solid angles [sr] of ``n_el`` rows."""
    h = 180.0 / n_el
    elevation = -90.0 + h * (np.arange(n_el) + 0.5)
    azimuth = -180.0 + h * (np.arange(2 * n_el) + 0.5)
    edges = np.radians(-90.0 + h * np.arange(n_el + 1))
    return azimuth, elevation, np.radians(h) * np.diff(np.sin(edges))


def _directions(azimuth_deg: NDArray, elevation_deg: NDArray) -> NDArray[np.float64]:
    """Unit vectors of the grid's cells, (n_el, n_az, 3)."""
    az, el = np.meshgrid(np.radians(azimuth_deg), np.radians(elevation_deg))
    return np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)


def _cast_grid(craft, points: SightPoints, n_el: int, clearance: float, inside: NDArray) -> tuple:
    """Cast one line through each cell of every point: blocking part, in view, solid angle, axes."""
    azimuth, elevation, solid = _cells(n_el)
    d = _directions(azimuth, elevation)
    n = len(points.names)
    flat = np.broadcast_to(d.reshape(1, -1, 3), (n, d.shape[0] * d.shape[1], 3))
    facet, _ = cast_from_points(craft, points.position_m, flat, clearance)
    part = np.where(facet >= 0, craft.facet_part[np.maximum(facet, 0)], -1).astype(np.int16)
    part[inside] = -2
    shape = (n, len(elevation), len(azimuth))
    return part.reshape(shape), points.in_cone(flat).reshape(shape), solid, azimuth, elevation


def _fraction(part: NDArray, in_view: NDArray, solid: NDArray) -> NDArray[np.float64]:
    """Solid-angle-weighted share of the view whose line is blocked, per point."""
    w = solid[None, :, None] * in_view
    return (w * (part != -1)).sum(axis=(1, 2)) / w.sum(axis=(1, 2))


def _edges(state: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Cells whose state differs from a neighbour's (azimuth wraps)."""
    edge = (state != np.roll(state, 1, axis=2)) | (state != np.roll(state, -1, axis=2))
    edge[:, 1:] |= state[:, 1:] != state[:, :-1]
    edge[:, :-1] |= state[:, :-1] != state[:, 1:]
    return edge


def _edge_spread(part: NDArray, in_view: NDArray, solid: NDArray, fraction: NDArray) -> NDArray[np.float64]:
    """Standard deviation of the fraction from the cells on an edge (module docstring), per point: those
    of the blocked part of the view move the numerator, those of the cone's edge the denominator (times
    the fraction)."""
    w2 = solid[None, :, None] ** 2
    blocked = (w2 * _edges((part != -1) & in_view)).sum(axis=(1, 2))
    cone = (w2 * _edges(in_view)).sum(axis=(1, 2))
    view = (solid[None, :, None] * in_view).sum(axis=(1, 2))
    return np.sqrt((blocked + fraction**2 * cone) / 24) / view


def blocked_map(
    model: Model, points: SightPoints, step_deg: float = 2.0, *, clearance_m: float | None = None
) -> SightMap:
    """Map what blocks each point's view over azimuth and elevation, with the blocked fraction of its
    field of view and its error estimate (module docstring).

    Each point's lines of the grid and of the grid twice as coarse go to Embree in one batch.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model.
    points : SightPoints
        The points [m], body frame, with optional cones (the field of view; the whole sky without).
    step_deg : float, optional
        Grid step [deg], 0.1 to 15; the grid takes ``180 / n`` for the smallest ``n`` a multiple of 4
        at most the step (1, 0.5 exactly; 2 gives 180 / 92).
    clearance_m : float or None, optional
        How far off its point each line starts [m]; default 1e-4 of the model's half-size.

    Returns
    -------
    SightMap
        The maps, fractions and their error estimates.

    Raises
    ------
    InputError
        A step out of range, a map larger than the memory limit.

    Warns
    -----
    FlaggedWarning
        A point inside a closed body (fraction 1), or a cone spanning fewer than ``FEW_CELLS`` cells.

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> points = SightPoints.of(["side"], [[0.0, 0.0, 0.5]], [[1.0, 0.0, 0.0]], [90.0])
    >>> view = blocked_map(model, points, step_deg=2.0)  # the half-sky toward +x: the box fills half
    >>> round(float(view.blocked_fraction[0]), 4), bool(view.error_estimate[0] < 0.01)
    (0.5, True)
    """
    craft = as_model(model).craft
    clearance = clearance_of(craft, clearance_m)
    azimuth, elevation, _ = grid(step_deg)
    n_el, n = len(elevation), len(points.names)
    memory.require(
        n * len(azimuth) ** 2 * 0.625 * _LINE_BYTES,
        f"maps of {n} points at {step_deg:g} deg",
        "give a coarser step or fewer points",
        ("step_deg",),
    )
    inside = inside_closed(craft, points.position_m, clearance)
    part, in_view, solid, azimuth, elevation = _cast_grid(craft, points, n_el, clearance, inside)
    coarse, coarse_view, coarse_solid, *_ = _cast_grid(craft, points, n_el // 2, clearance, inside)
    for k, name in enumerate(points.names):
        if inside[k]:
            warnings.warn(
                f"point {name!r} lies inside a closed body of {craft.source}: its view is reported "
                "all blocked; check its position (metres, body frame of the mesh)",
                FlaggedWarning,
                stacklevel=2,
            )
        cells = int(in_view[k].sum())
        if cells < FEW_CELLS:
            warnings.warn(
                f"the cone of point {name!r} spans {cells} cells of the {180 / len(elevation):g} deg grid: "
                "its blocked fraction is coarse; give a finer step_deg",
                FlaggedWarning,
                stacklevel=2,
            )
    if not in_view.any(axis=(1, 2)).all():
        raise InputError(
            "a cone holds no cell centre", hint="give a finer step_deg", parameters=("step_deg",)
        )
    fraction = _fraction(part, in_view, solid)
    with np.errstate(invalid="ignore"):
        change = np.abs(fraction - _fraction(coarse, coarse_view, coarse_solid))
    estimate = np.maximum(np.nan_to_num(change, nan=1.0), 4 * _edge_spread(part, in_view, solid, fraction))
    return SightMap(
        points,
        azimuth,
        elevation,
        part,
        in_view,
        solid,
        fraction,
        np.minimum(estimate, 1.0),
        craft.part_names,
        clearance,
    )
