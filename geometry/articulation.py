"""Articulated parts: hinges that turn parts of the model rigidly about a line of the body frame.

A hinge is an ``[articulation."GLOB"]`` table of the materials file: the parts its glob matches turn
about ``axis`` through ``origin_m`` by a fixed angle, as close to the Sun as the hinge allows
(``track = "sun"``), or by a schedule of angles in time. This module holds the hinge and its checks, the
angle laws and the turning of vertices; binding hinges to the parts of a model and posing it are
:func:`sunwind.geometry.spacecraft.articulate` and :func:`sunwind.geometry.spacecraft.pose`.
"""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError, MaterialError, combine

#: The angle laws of a hinge: exactly one of these keys.
LAWS = ("angle_deg", "track", "schedule")
#: Keys of an ``[articulation."GLOB"]`` table (``front`` only with ``track``).
HINGE_KEYS = ("axis", "origin_m", *LAWS, "front")
#: What a tracking hinge may follow.
TARGETS = ("sun",)
#: Smallest share of a unit Sun vector across the hinge axis for which tracking turns the hinge; below
#: it the Sun is along the axis, every angle is as good, and the angle is kept at 0.
ALONG_AXIS = 1e-9
#: Smallest share of a unit front normal across the hinge axis: below it turning does not turn the front.
FRONT_ACROSS = 1e-6


@dataclass(frozen=True)
class Hinge:
    """One articulation: the parts matching ``pattern`` turn rigidly about a line of the body frame.

    Attributes
    ----------
    pattern : str
        Part-name glob, matched as ``[parts]`` globs are (:func:`~sunwind.geometry.materials.part_matches`).
    axis : (3,) tuple of float
        Unit hinge axis, body frame; angles turn right-handed about it.
    origin_m : (3,) tuple of float
        A point of the hinge line [m], body frame (metres whatever the mesh unit, as ``centre_of_mass_m``).
    angle_deg : float or None
        Fixed angle [deg] from the mesh as drawn.
    track : str or None
        ``"sun"``: the angle that turns :attr:`front` as close to the Sun as the hinge allows.
    schedule : tuple of (time_s, angle_deg)
        Angles [deg] at times [s] from the start, times increasing; linear between, held outside.
    front : (3,) tuple of float or None
        Unit front normal of the turned parts as drawn (angle 0), for ``track``: given in the file, else
        the area-weighted mean front normal of their sheets, found when the hinge is bound to a model.
    """

    pattern: str
    axis: tuple[float, float, float]
    origin_m: tuple[float, float, float]
    angle_deg: float | None = None
    track: str | None = None
    schedule: tuple[tuple[float, float], ...] = ()
    front: tuple[float, float, float] | None = None

    @property
    def law(self) -> str:
        """``"fixed"``, ``"track"`` or ``"schedule"``."""
        return "fixed" if self.angle_deg is not None else "track" if self.track else "schedule"

    def fixed_at(self, angle_deg: float) -> Hinge:
        """This hinge held at ``angle_deg`` [deg] (a tracking or scheduled hinge stops following)."""
        return replace(self, angle_deg=float(angle_deg), track=None, schedule=())

    @classmethod
    def checked(cls, pattern: str, values: object, source: str | None = None) -> Hinge:
        """A hinge from its ``[articulation."GLOB"]`` table, every key checked.

        Raises
        ------
        MaterialError
            Unknown or missing keys, not exactly one angle law, an axis that is zero or not three finite
            numbers, a schedule that is not ``[time_s, angle_deg]`` pairs at increasing times.
        """
        where = f'[articulation] "{pattern}"'
        if not isinstance(values, Mapping):
            raise MaterialError(
                f"{where} must be a table", path=source, hint=f"write [articulation.{_key(pattern)}]"
            )
        unknown = sorted(set(values) - set(HINGE_KEYS))
        missing = [key for key in ("axis", "origin_m") if key not in values]
        if unknown or missing:
            what = f"has unknown key '{unknown[0]}'" if unknown else f"lacks '{missing[0]}'"
            raise MaterialError(
                f"{where} {what}",
                path=source,
                hint="give axis = [x, y, z], origin_m = [x, y, z] (metres, body frame) and one of "
                'angle_deg = DEG, track = "sun" or schedule = [[time_s, angle_deg], ...]',
            )
        laws = [law for law in LAWS if law in values]
        if len(laws) != 1:
            raise MaterialError(
                f"{where} has {' and '.join(laws) if laws else 'no angle'}",
                path=source,
                hint='give exactly one of angle_deg = DEG, track = "sun" and '
                "schedule = [[time_s, angle_deg], ...]",
            )
        axis = np.array(_triple(where, "axis", values["axis"], source))
        if not np.any(axis):
            raise MaterialError(
                f"{where} axis = {values['axis']!r} is not a direction",
                path=source,
                hint="give the hinge axis as a non-zero vector, e.g. axis = [0, 1, 0]",
            )
        hinge = cls(pattern, _unit(axis), _triple(where, "origin_m", values["origin_m"], source))
        front = values.get("front")
        if front is not None:
            if laws != ["track"]:
                raise MaterialError(f'{where} front is for track = "sun" only', path=source)
            vector = np.array(_triple(where, "front", front, source))
            if not np.any(vector):
                raise MaterialError(f"{where} front = {front!r} is not a direction", path=source)
            hinge = replace(hinge, front=_unit(vector))
        law, value = laws[0], values[laws[0]]
        if law == "angle_deg":
            return replace(hinge, angle_deg=_angle(where, value, source))
        if law == "track":
            if value not in TARGETS:
                raise MaterialError(
                    f"{where} track = {value!r} is not a target", path=source, hint='write track = "sun"'
                )
            return replace(hinge, track=str(value))
        return replace(hinge, schedule=_schedule(where, value, source))


def parse_articulation(table: object, source: str | None = None) -> tuple[Hinge, ...]:
    """The hinges of a materials file's ``[articulation]`` table, every problem reported at once."""
    if not isinstance(table, Mapping):
        raise MaterialError(
            "[articulation] must hold one table per hinge",
            path=source,
            hint='write [articulation."wing_*"] followed by axis, origin_m and an angle law',
        )
    hinges, problems = [], []
    for pattern, values in table.items():
        try:
            hinges.append(Hinge.checked(pattern, values, source))
        except MaterialError as error:
            problems.append(error)
    if problems:
        raise combine(problems)
    return tuple(hinges)


def fixed(hinges: Sequence[Hinge], angles: Mapping[str, float], path: str | None = None) -> tuple[Hinge, ...]:
    """``hinges``, each that ``angles`` names (by its glob, as written) held at that angle [deg].

    Raises
    ------
    InputError
        A name that is no hinge's glob (declare it in the materials file), or an angle not finite.
    """
    known = {hinge.pattern for hinge in hinges}
    for name, angle in angles.items():
        if name not in known:
            declared = ", ".join(f'"{p}"' for p in known) or "none"
            raise InputError(
                f'articulate "{name}" names no hinge',
                path=path,
                hint=f"declare it in the materials file as [articulation.{_key(name)}] with axis, "
                f"origin_m and angle_deg (the hinges: {declared})",
                parameters=("articulate",),
            )
        checked_angle(angle, f'articulate "{name}"', "articulate")
    return tuple(
        hinge.fixed_at(angles[hinge.pattern]) if hinge.pattern in angles else hinge for hinge in hinges
    )


def checked_angle(angle: object, name: str, parameter: str) -> float:
    """``angle`` [deg] as a float, refused unless a finite number (``name`` says whose, naming the
    Python ``parameter``)."""
    if isinstance(angle, bool) or not isinstance(angle, int | float) or not math.isfinite(angle):
        raise InputError(f"{name} angle {angle!r} must be a finite number [deg]", parameters=(parameter,))
    return float(angle)


# ------------------------------------------------------------------------------------------ angle laws
def tracking_angle(
    axis: Sequence[float] | NDArray, front: Sequence[float] | NDArray, sun_body: Sequence[float] | NDArray
) -> float:
    """The angle [deg] about ``axis`` that turns ``front`` (its direction at angle 0) closest to ``sun_body``.

    With ``a`` the unit axis and ``v_perp = v - (a . v) a``, ``n(theta) . s`` is largest at
    ``theta = atan2(a . (n_perp x s_perp), n_perp . s_perp)``. A Sun along the axis (``|s_perp|`` below
    :data:`ALONG_AXIS` of ``|s|``) leaves every angle as good: the angle is kept at 0, with a warning
    (shown once).
    """
    a = np.asarray(axis, dtype=np.float64) / np.linalg.norm(axis)
    n, s = np.asarray(front, dtype=np.float64), np.asarray(sun_body, dtype=np.float64)
    n_perp, s_perp = n - (a @ n) * a, s - (a @ s) * a
    if np.linalg.norm(s_perp) <= ALONG_AXIS * np.linalg.norm(s):
        warnings.warn(
            "the Sun is along a tracking hinge's axis: every angle faces it alike; the angle is kept at "
            "0 deg",
            stacklevel=2,
        )
        return 0.0
    return math.degrees(math.atan2(float(a @ np.cross(n_perp, s_perp)), float(n_perp @ s_perp)))


def schedule_angle(hinge: Hinge, time_s: float) -> float:
    """The angle [deg] of a scheduled hinge at ``time_s`` [s]: linear between its points, held outside."""
    if isinstance(time_s, bool) or not isinstance(time_s, int | float) or not math.isfinite(time_s):
        raise InputError(f"time_s {time_s!r} must be a finite number [s]", parameters=("time_s",))
    times, angles = np.array(hinge.schedule, dtype=np.float64).T
    return float(np.interp(time_s, times, angles))


# ------------------------------------------------------------------------------------------- turning
def rotation(axis: Sequence[float], angle_deg: float) -> NDArray[np.float64]:
    """Right-handed rotation matrix (3, 3) by ``angle_deg`` [deg] about the unit ``axis`` (Rodrigues)."""
    a = np.asarray(axis, dtype=np.float64)
    theta = math.radians(angle_deg)
    skew = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return math.cos(theta) * np.eye(3) + math.sin(theta) * skew + (1.0 - math.cos(theta)) * np.outer(a, a)


def turned(
    vertices: NDArray[np.float64], vertex_hinge: NDArray, hinges: Sequence[Hinge], angles_deg: Sequence[float]
) -> NDArray[np.float64]:
    """``vertices`` [m] with those of hinge ``k`` (``vertex_hinge == k``) turned by ``angles_deg[k]`` about
    its line; a whole number of turns (0, 360, ...) moves nothing, to the bit."""
    out = np.array(vertices, dtype=np.float64)
    for k, (hinge, angle) in enumerate(zip(hinges, angles_deg, strict=True)):
        turn = math.remainder(angle, 360.0)
        if turn == 0.0:
            continue
        rows = vertex_hinge == k
        origin = np.asarray(hinge.origin_m)
        out[rows] = (out[rows] - origin) @ rotation(hinge.axis, turn).T + origin
    return out


def detached(
    vertices: NDArray[np.float64], faces: NDArray[np.int64], facet_group: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Vertices and faces with a copy of each vertex for every further group (``facet_group``: a hinge's
    index, -1 for unturned facets) whose facets use it, so that no vertex is shared across groups."""
    span = int(facet_group.max(initial=-1)) + 2
    keys = faces.reshape(-1) * span + np.repeat(np.asarray(facet_group, dtype=np.int64) + 1, 3)
    pairs, inverse = np.unique(keys, return_inverse=True)
    vertex = pairs // span
    first = np.r_[True, vertex[1:] != vertex[:-1]]
    index = np.where(first, vertex, len(vertices) + np.cumsum(~first) - 1)
    if first.all():
        return vertices, faces
    return np.concatenate([vertices, vertices[vertex[~first]]]), index[inverse.reshape(-1)].reshape(-1, 3)


def front_normal(triangles: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Area-weighted mean front normal (counter-clockwise winding) of ``triangles`` (n, 3, 3), unit; None
    when they have none (no triangles, or fronts that cancel as a closed body's do)."""
    doubled = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    total, area = doubled.sum(axis=0), np.linalg.norm(doubled, axis=1).sum()
    if area == 0.0 or np.linalg.norm(total) <= FRONT_ACROSS * area:
        return None
    return total / np.linalg.norm(total)


# ------------------------------------------------------------------------------------------- binding
def part_groups(
    hits: NDArray[np.bool_], part_names: Sequence[str], hinges: Sequence[Hinge], mesh: str, path: str | None
) -> NDArray[np.int64]:
    """The hinge that turns each part (-1: none), from ``hits[k, p]``: hinge ``k``'s glob matches part ``p``.

    Raises
    ------
    MaterialError
        A glob that matches no part of ``mesh``, or a part that two globs match.
    """
    problems = []
    listed = ", ".join(part_names[:20]) + (f", ... ({len(part_names)} parts)" if len(part_names) > 20 else "")
    for k in np.flatnonzero(~hits.any(axis=1)):
        problems.append(
            MaterialError(
                f'[articulation] "{hinges[k].pattern}" matches no part of {mesh}',
                path=path,
                hint=f"the parts are: {listed}",
            )
        )
    for p in np.flatnonzero(hits.sum(axis=0) > 1):
        first, second = (hinges[k].pattern for k in np.flatnonzero(hits[:, p])[:2])
        problems.append(
            MaterialError(
                f'part \'{part_names[p]}\' is turned by two hinges, [articulation] "{first}" and "{second}"',
                path=path,
                hint="make the hinges' globs match different parts",
            )
        )
    if problems:
        raise combine(problems)
    return np.where(hits.any(axis=0), hits.argmax(axis=0), -1)


def check_bodies(
    faces: NDArray[np.int64],
    solid: NDArray[np.bool_],
    facet_group: NDArray[np.int64],
    facet_names: Sequence[str],
    hinges: Sequence[Hinge],
    path: str | None,
) -> None:
    """Refuse a closed body (``solid`` facets, closed across parts) whose facets two groups turn apart:
    turning one of them would open it. ``facet_names`` names each facet's part.

    Raises
    ------
    MaterialError
        Naming the hinge, the part it turns and a part of the same body it does not.
    """
    index = np.flatnonzero(solid)
    edges = np.sort(faces[index][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    keys = edges[:, 0] * (int(faces.max(initial=0)) + 1) + edges[:, 1]
    order = np.argsort(keys, kind="stable")
    keys, owner = keys[order], np.repeat(index, 3)[order]
    starts = np.flatnonzero(np.r_[True, keys[1:] != keys[:-1]]) if len(keys) else np.zeros(0, np.int64)
    group = facet_group[owner]
    low, high = np.minimum.reduceat(group, starts), np.maximum.reduceat(group, starts)
    split = np.flatnonzero(low != high)
    if not len(split):
        return
    run = slice(starts[split[0]], starts[split[0] + 1] if split[0] + 1 < len(starts) else len(keys))
    turned_by, other = high[split[0]], low[split[0]]
    facet = owner[run][group[run] == turned_by][0]
    beside = owner[run][group[run] == other][0]
    by = f'[articulation] "{hinges[other].pattern}" turns' if other >= 0 else "it does not turn"
    raise MaterialError(
        f"[articulation] \"{hinges[turned_by].pattern}\" turns part '{facet_names[facet]}', which closes a "
        f"body with part '{facet_names[beside]}' that {by}",
        path=path,
        hint="turn the whole body with one hinge, or close each part on its own (parts that only touch "
        "are fine: their shared vertices are split)",
    )


def with_fronts(
    hinges: Sequence[Hinge],
    triangles: NDArray[np.float64],
    facet_group: NDArray[np.int64],
    sheet: NDArray[np.bool_],
    path: str | None,
) -> tuple[Hinge, ...]:
    """``hinges`` with the front of each tracking hinge that gives none: the area-weighted mean front
    normal of the sheets (``sheet`` facets of ``triangles``, the mesh as drawn) it turns.

    Raises
    ------
    MaterialError
        A tracking hinge whose parts have no front (closed bodies only: their normals cancel), or whose
        front lies along its axis.
    """
    out = list(hinges)
    for k, hinge in enumerate(hinges):
        if hinge.track is None:
            continue
        where = f'[articulation] "{hinge.pattern}" tracks the Sun, but'
        found = front_normal(triangles[(facet_group == k) & sheet]) if hinge.front is None else hinge.front
        if found is None:
            raise MaterialError(
                f"{where} the parts it turns have no front",
                path=path,
                hint="give front = [x, y, z], their front normal as drawn (a closed body's normals cancel; "
                "the front of a sheet is its counter-clockwise side)",
            )
        front, axis = np.asarray(found), np.asarray(hinge.axis)
        if np.linalg.norm(front - (axis @ front) * axis) < FRONT_ACROSS:
            raise MaterialError(
                f"{where} its front {np.round(front, 6).tolist()} lies along its axis",
                path=path,
                hint="a tracking hinge's axis must lie across the front of the parts it turns",
            )
        out[k] = replace(hinge, front=_unit(front))
    return tuple(out)


# -------------------------------------------------------------------------------------------- helpers
def _key(pattern: str) -> str:
    """``pattern`` as a quoted TOML key."""
    return json.dumps(pattern, ensure_ascii=False)


def _triple(where: str, key: str, value: object, source: str | None) -> tuple[float, float, float]:
    """``value`` as three finite floats, else an error naming ``key``."""
    numbers = isinstance(value, list) and all(
        isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in value
    )
    if not numbers or len(value) != 3:  # type: ignore[arg-type]
        raise MaterialError(
            f"{where} {key} = {value!r} is not 3 finite numbers",
            path=source,
            hint=f"give {key} = [x, y, z] in the body frame" + (" (metres)" if key.endswith("_m") else ""),
        )
    return (float(value[0]), float(value[1]), float(value[2]))  # type: ignore[index]


def _unit(vector: NDArray[np.float64]) -> tuple[float, float, float]:
    """``vector`` (not zero) normalised, as a tuple; scaled first, so that no component overflows."""
    scaled = vector / np.abs(vector).max()
    unit = scaled / np.linalg.norm(scaled)
    return (float(unit[0]), float(unit[1]), float(unit[2]))


def _angle(where: str, value: object, source: str | None) -> float:
    """``angle_deg``: a finite number [deg]."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise MaterialError(f"{where} angle_deg = {value!r} is not a finite number", path=source)
    return float(value)


def _schedule(where: str, value: object, source: str | None) -> tuple[tuple[float, float], ...]:
    """``schedule``: [time_s, angle_deg] pairs of finite numbers at increasing times."""
    hint = "give schedule = [[time_s, angle_deg], ...] in time order, each time once"
    pairs = isinstance(value, list) and len(value) > 0
    for pair in value if pairs else ():  # type: ignore[union-attr]
        pairs = pairs and isinstance(pair, list) and len(pair) == 2
        pairs = pairs and all(
            isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in pair
        )
    if not pairs:
        raise MaterialError(
            f"{where} schedule = {value!r} is not [time_s, angle_deg] pairs", path=source, hint=hint
        )
    points = tuple((float(t), float(a)) for t, a in value)  # type: ignore[union-attr]
    for (t0, _), (t1, _) in pairwise(points):
        if t1 <= t0:
            raise MaterialError(
                f"{where} schedule times do not increase (t = {t1:g} s after t = {t0:g} s)",
                path=source,
                hint=hint,
            )
    return points
