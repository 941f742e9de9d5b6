"""What each point sees along an orbit: the Sun, the Earth or a ground station, step by step, and the
intervals it is seen (METHOD.md "Lines of sight").

The trajectory and attitude law are those of ``sunwind orbit`` (:mod:`sunwind.forces.orbit`); at each
step the target's direction is turned into the body frame and one line per point is cast, all steps
and points in one batch. A target is seen from a point when:

- ``sun``: the line toward the Sun's centre is clear, inside the point's cone, and the Earth leaves
  some of the solar disc in view (solar fraction above 0 under the eclipse model: the umbra is not
  seen, the penumbra is, with its fraction given);
- ``earth``: the line toward the Earth's centre (nadir) is clear, and the Earth's disc (angular radius
  ``asin(R / r)``, R = 6378.137 km) overlaps the point's cone: the angle from the boresight to nadir is
  at most the half angle plus that radius;
- a station (geodetic latitude, longitude [deg], altitude [km] on WGS 84): the spacecraft is at least
  ``min_elevation_deg`` above the station's horizon, and the line toward the station is clear and in
  the point's cone. Points with a cone (retroreflectors) get their range offsets
  (:mod:`.ranging`).

Intervals run from the first to the last step of each run of steps seen; their true edges lie within
one step outside them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS
from sunwind.forces.model import Model, as_model
from sunwind.forces.orbit.attitude import AttitudeLaw, quaternion_file_attitude
from sunwind.forces.orbit.eclipse import solar_fraction
from sunwind.forces.orbit.flight import sun_and_moon
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.forces.sight.lines import FRAME, lines_of_sight
from sunwind.forces.sight.points import SightPoints
from sunwind.forces.sight.ranging import RangeOffsets, range_offsets
from sunwind.geometry.errors import InputError


@dataclass(frozen=True)
class Station:
    """A ground station on the WGS 84 ellipsoid.

    Parameters
    ----------
    latitude_deg : float
        Geodetic latitude [deg], -90 to 90.
    longitude_deg : float
        Longitude [deg] east, -360 to 360.
    altitude_km : float
        Height above the ellipsoid [km], -1 to 100.
    min_elevation_deg : float, optional
        Lowest elevation of the spacecraft above the horizon at which it is seen [deg], 0 to 90.

    Examples
    --------
    >>> Station(48.0, 11.0, 0.6).describe()
    'station at 48 deg, 11 deg, 0.6 km (WGS 84), above 0 deg elevation'
    >>> Station(95.0, 11.0, 0.6)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: the station's latitude 95 deg must be from -90 to 90 deg; ...
    """

    latitude_deg: float
    longitude_deg: float
    altitude_km: float
    min_elevation_deg: float = 0.0

    def __post_init__(self) -> None:
        for name, value, low, high, unit in (
            ("latitude", self.latitude_deg, -90.0, 90.0, "deg"),
            ("longitude", self.longitude_deg, -360.0, 360.0, "deg"),
            ("altitude", self.altitude_km, -1.0, 100.0, "km"),
            ("lowest elevation", self.min_elevation_deg, 0.0, 90.0, "deg"),
        ):
            if not (math.isfinite(value) and low <= value <= high):
                raise InputError(
                    f"the station's {name} {value:g} {unit} must be from {low:g} to {high:g} {unit}",
                    hint="give geodetic latitude and longitude in degrees and the altitude in km",
                )

    def describe(self) -> str:
        """The station in words.

        Returns
        -------
        str
            Its place and lowest elevation.

        Examples
        --------
        >>> Station(-35.4, 149.0, 0.8, 10.0).describe()
        'station at -35.4 deg, 149 deg, 0.8 km (WGS 84), above 10 deg elevation'
        """
        return (
            f"station at {self.latitude_deg:g} deg, {self.longitude_deg:g} deg, {self.altitude_km:g} km "
            f"(WGS 84), above {self.min_elevation_deg:g} deg elevation"
        )

    def gcrf(self, trajectory: Trajectory) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The station's GCRF position [m] and local vertical (unit) at the trajectory's steps.

        The ITRS place is turned to GCRF by ERFA's IAU 2006/2000A ``c2t06a`` (UT1 = UTC, no polar
        motion), as :func:`~sunwind.forces.orbit.flight.geodetic` does the other way.

        Parameters
        ----------
        trajectory : Trajectory
            The steps' times.

        Returns
        -------
        position_m : (n, 3) float64
            The station [m], GCRF.
        up : (n, 3) float64
            The normal to the ellipsoid at the station, GCRF.

        Examples
        --------
        >>> from sunwind.forces.orbit import Elements, Epoch, propagate
        >>> path = propagate(Elements.circular(500, 0.0), Epoch.of("2024-03-20T00:00:00Z"), [0.0], "kepler")
        >>> position, up = Station(90.0, 0.0, 0.0).gcrf(path)
        >>> round(float(np.linalg.norm(position)) / 1e3, 3), up.round(2).tolist()  # the pole [km]
        (6356.752, [[0.0, 0.0, 1.0]])
        """
        lat, lon = math.radians(self.latitude_deg), math.radians(self.longitude_deg)
        fixed = erfa.gd2gc(1, lon, lat, self.altitude_km * 1e3)
        up = np.array([math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)])
        epoch, t = trajectory.epoch, trajectory.time_s
        rotation = erfa.c2t06a(*epoch.tt(t), *epoch.ut1(t), 0.0, 0.0)  # GCRF -> ITRS
        return np.einsum("nji,j->ni", rotation, fixed), np.einsum("nji,j->ni", rotation, up)


@dataclass(frozen=True, eq=False)
class SightPasses:
    """What each point sees of a target along an orbit, step by step.

    Parameters
    ----------
    points : SightPoints
        The points.
    target : str
        The target in words.
    epoch : str
        The run's start, UTC ISO 8601.
    time_s : (T,) float64
        Seconds after the epoch.
    direction_body : (T, 3) float64
        Unit direction from the spacecraft toward the target, body frame.
    visible : (n, T) bool
        The point sees the target (module docstring).
    clear : (n, T) bool
        The line toward the target leaves the model.
    blocking_part : (n, T) int64
        Index into ``part_names`` of the part met; -1 clear.
    part_names : tuple of str
        The model's parts.
    extra : dict of str to (T,) ndarray
        ``solar_fraction`` (sun), ``earth_angular_radius_deg`` (earth), ``elevation_deg`` and
        ``range_m`` (station).
    ranges : RangeOffsets or None
        Range offsets of the points with a cone toward a station; None for other targets.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, propagate
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> path = propagate(Elements.circular(500, 97.4), Epoch.of("2024-03-20T00:00:00Z"),
    ...                  np.arange(0.0, 5700.0, 60.0), "kepler")
    >>> points = SightPoints.of(["zenith", "nadir"], [[0, 0, -0.5], [0, 0, 0.5]], [[0, 0, -1], [0, 0, 1]],
    ...                         [80.0, 80.0])
    >>> passes = visibility_along(model, points, path, AttitudeLaw.parse("nadir"), "earth")
    >>> passes.visible.all(axis=1).tolist()  # nadir pointing: body +z toward the Earth
    [False, True]
    """

    points: SightPoints
    target: str
    epoch: str
    time_s: NDArray[np.float64]
    direction_body: NDArray[np.float64]
    visible: NDArray[np.bool_]
    clear: NDArray[np.bool_]
    blocking_part: NDArray[np.int64]
    part_names: tuple[str, ...]
    extra: dict
    ranges: RangeOffsets | None = None

    def intervals(self, i: int) -> list[tuple[float, float, float]]:
        """The runs of steps at which point ``i`` sees the target.

        Parameters
        ----------
        i : int
            The point.

        Returns
        -------
        list of (float, float, float)
            ``(start_s, end_s, duration_s)`` from the first to the last step of each run; the true
            edges lie within one step outside.

        Examples
        --------
        >>> passes = SightPasses(SightPoints.of(["p"], [[0, 0, 0]]), "sun", "", np.arange(6) * 10.0,
        ...                      np.zeros((6, 3)), np.array([[1, 1, 0, 0, 1, 1]], bool),
        ...                      np.ones((1, 6), bool), np.full((1, 6), -1), (), {})
        >>> passes.intervals(0)
        [(0.0, 10.0, 10.0), (40.0, 50.0, 10.0)]
        """
        seen = np.concatenate([[False], self.visible[i], [False]]).astype(np.int8)
        starts = np.flatnonzero(np.diff(seen) == 1)
        ends = np.flatnonzero(np.diff(seen) == -1) - 1
        t = self.time_s
        return [(float(t[a]), float(t[b]), float(t[b] - t[a])) for a, b in zip(starts, ends, strict=True)]

    def to_json(self) -> dict:
        """The passes as a JSON-ready dict: per point, the series and intervals (keys carry units).

        Returns
        -------
        dict
            ``frame``, ``target``, ``epoch``, ``time_s``, ``direction_body``, the target's extra series,
            ``points`` (``name``, ``visible``, ``blocked_by`` per step, ``visible_fraction``,
            ``intervals`` of ``start_s``, ``end_s``, ``duration_s``) and, toward a station,
            ``range_offsets``.

        Examples
        --------
        >>> passes = SightPasses(SightPoints.of(["p"], [[0, 0, 0]]), "sun", "", np.arange(3) * 10.0,
        ...                      np.zeros((3, 3)), np.array([[0, 1, 1]], bool),
        ...                      np.ones((1, 3), bool), np.full((1, 3), -1), (), {})
        >>> passes.to_json()["points"][0]["intervals"]
        [{'start_s': 10.0, 'end_s': 20.0, 'duration_s': 10.0}]
        """
        rows = []
        for i, name in enumerate(self.points.names):
            parts = [self.part_names[k] if k >= 0 else None for k in self.blocking_part[i]]
            rows.append(
                {
                    "name": name,
                    "visible": self.visible[i].tolist(),
                    "blocked_by": parts,
                    "visible_fraction": round(float(self.visible[i].mean()), 6),
                    "intervals": [
                        {"start_s": a, "end_s": b, "duration_s": d} for a, b, d in self.intervals(i)
                    ],
                }
            )
        out = {
            "frame": FRAME,
            "target": self.target,
            "epoch": self.epoch,
            "interval_edges": "first and last step seen; the true edges lie within one step outside",
            "time_s": self.time_s.tolist(),
            "direction_body": self.direction_body.round(9).tolist(),
            **{key: np.round(value, 6).tolist() for key, value in self.extra.items()},
            "points": rows,
        }
        if self.ranges is not None:
            out["range_offsets"] = self.ranges.to_json()
        return out

    def to_dataset(self) -> object:
        """The series as an xarray Dataset (time and point), for netCDF.

        Returns
        -------
        xarray.Dataset
            ``visible`` and ``clear`` (0/1) and ``blocking_part`` on (point, time_s), the direction and
            the target's extra series on time, and ``range_offset_m`` toward a station.

        Examples
        --------
        >>> passes = SightPasses(SightPoints.of(["p"], [[0, 0, 0]]), "sun", "", np.arange(3) * 10.0,
        ...                      np.zeros((3, 3)), np.array([[0, 1, 1]], bool),
        ...                      np.ones((1, 3), bool), np.full((1, 3), -1), (), {})
        >>> passes.to_dataset()["visible"].dims
        ('point', 'time_s')
        """
        import xarray as xr

        cells = ("point", "time_s")
        data = {
            "visible": (cells, self.visible.astype(np.int8), {"units": "1", "long_name": "target seen"}),
            "clear": (cells, self.clear.astype(np.int8), {"units": "1", "long_name": "line clear"}),
            "blocking_part": (
                cells,
                self.blocking_part.astype(np.int16),
                {"units": "1", "codes": "-1 clear"},
            ),
            "direction_body": (("time_s", "axis"), self.direction_body, {"units": "1", "frame": "body"}),
        }
        units = {"solar_fraction": "1", "earth_angular_radius_deg": "degree", "elevation_deg": "degree"}
        for key, value in self.extra.items():
            data[key] = ("time_s", value, {"units": units.get(key, "m")})
        if self.ranges is not None:
            data["range_offset_m"] = (
                cells,
                self.ranges.offset_m,
                {"units": "m", "long_name": "-u . (p - c)"},
            )
        coords = {"point": list(self.points.names), "time_s": self.time_s, "axis": ["x", "y", "z"]}
        coords["part"] = list(self.part_names)
        attrs = {"frame": FRAME, "target": self.target, "epoch": self.epoch}
        return xr.Dataset(data, coords=coords, attrs=attrs)


def _body_to_eci(trajectory: Trajectory, attitude: AttitudeLaw, sun_m: NDArray) -> NDArray[np.float64]:
    if attitude.kind == "csv":
        return quaternion_file_attitude(attitude, trajectory.epoch, trajectory.time_s)
    return attitude.body_to_eci(trajectory, sun_m)


def _target(trajectory: Trajectory, target: object, sun_m: NDArray, eclipse: str) -> tuple:
    """The target's GCRF direction, whether it is up at each step, and its extra series."""
    r = trajectory.position_m
    if target == "sun":
        fraction = solar_fraction(r, sun_m, eclipse)
        toward = sun_m - r
        return toward, fraction > 0, {"solar_fraction": fraction}
    if target == "earth":
        radius = np.linalg.norm(r, axis=1)
        angular = np.degrees(np.arcsin(np.minimum(EARTH_RADIUS / radius, 1.0)))
        return -r, np.ones(len(r), bool), {"earth_angular_radius_deg": angular}
    if isinstance(target, Station):
        place, up = target.gcrf(trajectory)
        toward = place - r
        distance = np.linalg.norm(toward, axis=1)
        elevation = np.degrees(np.arcsin(np.clip(np.einsum("nk,nk->n", up, -toward) / distance, -1, 1)))
        return (
            toward,
            elevation >= target.min_elevation_deg,
            {"elevation_deg": elevation, "range_m": distance},
        )
    raise InputError(
        f"target {target!r} is not 'sun', 'earth' or a Station",
        hint="e.g. target='sun' or target=Station(48.1, 11.3, 0.6)",
        parameters=("target",),
    )


def visibility_along(
    model: Model,
    points: SightPoints,
    trajectory: Trajectory,
    attitude: AttitudeLaw,
    target: str | Station,
    *,
    sun_eci: NDArray[np.float64] | None = None,
    eclipse: str = "conical",
    clearance_m: float | None = None,
) -> SightPasses:
    """Whether each point sees the Sun, the Earth or a station at each step of an orbit (module
    docstring), with the range offsets of the points with a cone toward a station.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model, its pose as loaded (hinges do not turn along the orbit here); its reference
        point is that of the range offsets.
    points : SightPoints
        The points [m], body frame.
    trajectory : Trajectory
        The orbit's steps (:func:`~sunwind.forces.orbit.propagate`, a TLE, an ephemeris).
    attitude : AttitudeLaw
        The attitude law, body to GCRF.
    target : {"sun", "earth"} or Station
        What to look at.
    sun_eci : (3,) array_like or None, optional
        A fixed Sun direction (GCRF) instead of the ephemeris.
    eclipse : {"conical", "cylindrical", "none"}, optional
        The Earth's shadow model, for the Sun.
    clearance_m : float or None, optional
        How far off its point each line starts [m]; default 1e-4 of the model's half-size.

    Returns
    -------
    SightPasses
        Per point and step: seen, clear, the part met; and the intervals.

    Raises
    ------
    InputError
        An unknown target, eclipse model or attitude file problem.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, propagate
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> path = propagate(Elements.circular(500, 0.0), Epoch.of("2024-03-20T00:00:00Z"),
    ...                  np.arange(0.0, 5700.0, 60.0), "kepler")
    >>> sensor = SightPoints.of(["sun_sensor"], [[0.0, 0.5, 0.0]], [[0.0, 1.0, 0.0]], [90.0])
    >>> passes = visibility_along(model, sensor, path, AttitudeLaw.parse("sun:+y,+x"), "sun")
    >>> [round(d / 60) for _, _, d in passes.intervals(0)]  # minutes: sunlit before and after the eclipse
    [29, 28]
    """
    model = as_model(model)
    sun_m, _ = sun_and_moon(trajectory, sun_eci, False)
    rotation = _body_to_eci(trajectory, attitude, sun_m)
    toward, up, extra = _target(trajectory, target, sun_m, eclipse)
    toward = toward / np.linalg.norm(toward, axis=1, keepdims=True)
    body = np.einsum("nji,nj->ni", rotation, toward)
    lines = lines_of_sight(model, points, body, clearance_m=clearance_m)
    if target == "earth":
        limit = np.nan_to_num(points.half_angle_deg, nan=180.0)[:, None] + extra["earth_angular_radius_deg"]
        off = np.nan_to_num(points.off_boresight_deg(lines.directions), nan=0.0)
        in_view = off <= limit
    else:
        in_view = lines.in_cone
    visible = lines.clear & in_view & up[None, :]
    ranges = None
    if isinstance(target, Station) and points.has_cone.any():
        ranges = range_offsets(lines, model.reference()[0])
        seen = visible & points.has_cone[:, None]  # a retroreflector has an acceptance cone
        offsets = np.where(seen, ranges.offset_m, np.nan)
        ranges = RangeOffsets(ranges.names, ranges.directions, offsets, ranges.reference_point_m)
    return SightPasses(
        points,
        target if isinstance(target, str) else target.describe(),
        trajectory.epoch.iso(),
        trajectory.time_s,
        body,
        visible,
        lines.clear,
        lines.blocking_part,
        lines.part_names,
        extra,
        ranges,
    )
