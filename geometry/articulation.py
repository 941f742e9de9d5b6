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

    Examples
    --------
    >>> hinge = Hinge.checked("wing*", {"axis": [0, 2, 0], "origin_m": [0, 0, 0], "angle_deg": 30})
    >>> hinge.axis, hinge.law
    ((0.0, 1.0, 0.0), 'fixed')
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
        """Name of the angle law this hinge follows.

        Returns
        -------
        str
            ``"fixed"``, ``"track"`` or ``"schedule"``.

        Examples
        --------
        >>> Hinge("wing*", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), track="sun").law
        'track'
        """
        return "fixed" if self.angle_deg is not None else "track" if self.track else "schedule"

    def fixed_at(self, angle_deg: float) -> Hinge:
        """Hold this hinge at a fixed angle; a tracking or scheduled hinge stops following its law.

        Parameters
        ----------
        angle_deg : float
            The angle to hold [deg].

        Returns
        -------
        Hinge
            A copy with ``angle_deg`` set and ``track`` and ``schedule`` cleared.

        Examples
        --------
        >>> hinge = Hinge("wing*", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), track="sun")
        >>> held = hinge.fixed_at(45)
        >>> held.law, held.angle_deg
        ('fixed', 45.0)
        """
        return replace(self, angle_deg=float(angle_deg), track=None, schedule=())

    @classmethod
    def checked(cls, pattern: str, values: object, source: str | None = None) -> Hinge:
        """Build a hinge from its ``[articulation."GLOB"]`` table, checking every key.

        Parameters
        ----------
        pattern : str
            The part-name glob the table is keyed by.
        values : object
            The parsed table: ``axis``, ``origin_m`` and exactly one of ``angle_deg``, ``track`` and
            ``schedule``; ``front`` beside ``track`` only.
        source : str or None, optional
            Path of the materials file, for error messages.

        Returns
        -------
        Hinge
            The hinge, its axis (and front, if given) made unit.

        Raises
        ------
        MaterialError
            Unknown or missing keys, not exactly one angle law, an axis that is zero or not three finite
            numbers, a schedule that is not ``[time_s, angle_deg]`` pairs at increasing times.

        Examples
        --------
        >>> hinge = Hinge.checked("panel", {"axis": [1, 0, 0], "origin_m": [0, 0, 1],
        ...     "schedule": [[0, 0], [60, 90]]})
        >>> hinge.law, hinge.schedule
        ('schedule', ((0.0, 0.0), (60.0, 90.0)))
        >>> Hinge.checked("panel", {"axis": [0, 0, 0], "origin_m": [0, 0, 0], "angle_deg": 5})
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.MaterialError: [articulation] "panel" axis = [0, 0, 0] is not a direction...
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
    """Read the hinges of a materials file's ``[articulation]`` table, reporting every problem at once.

    Parameters
    ----------
    table : object
        The parsed ``[articulation]`` table: one sub-table per hinge, keyed by its part glob.
    source : str or None, optional
        Path of the materials file, for error messages.

    Returns
    -------
    tuple of Hinge
        The hinges, in table order.

    Raises
    ------
    MaterialError
        When the table is not a mapping or any hinge is bad (all problems combined into one error).

    Examples
    --------
    >>> hinges = parse_articulation({"wing_*": {"axis": [0, 1, 0], "origin_m": [0, 0, 0], "track": "sun"}})
    >>> [(h.pattern, h.law) for h in hinges]
    [('wing_*', 'track')]
    """
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
    """Hold the hinges that ``angles`` names at the given angles.

    Parameters
    ----------
    hinges : sequence of Hinge
        The model's hinges.
    angles : mapping of str to float
        Angle [deg] for each hinge to hold, keyed by its glob as written in the materials file.
    path : str or None, optional
        Path of the materials file, for error messages.

    Returns
    -------
    tuple of Hinge
        ``hinges`` in order, each that ``angles`` names held at its angle (:meth:`Hinge.fixed_at`).

    Raises
    ------
    InputError
        A name that is no hinge's glob (declare it in the materials file), or an angle not finite.

    Examples
    --------
    >>> hinge = Hinge("wing*", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), track="sun")
    >>> fixed([hinge], {"wing*": 10.0})[0].angle_deg
    10.0
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
    """Check that an angle is a finite number and return it as a float.

    Parameters
    ----------
    angle : object
        The angle [deg] as given.
    name : str
        Whose angle it is, for the error message.
    parameter : str
        The Python parameter that gave it, named by the error.

    Returns
    -------
    float
        ``angle`` [deg].

    Raises
    ------
    InputError
        When ``angle`` is a bool, not a number, or not finite.

    Examples
    --------
    >>> checked_angle(15, "hinge", "angle_deg")
    15.0
    >>> checked_angle(float("nan"), "hinge", "angle_deg")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: hinge angle nan must be a finite number [deg]...
    """
    if isinstance(angle, bool) or not isinstance(angle, int | float) or not math.isfinite(angle):
        raise InputError(f"{name} angle {angle!r} must be a finite number [deg]", parameters=(parameter,))
    return float(angle)


# ------------------------------------------------------------------------------------------ angle laws
def tracking_angle(
    axis: Sequence[float] | NDArray, front: Sequence[float] | NDArray, sun_body: Sequence[float] | NDArray
) -> float:
    """Find the angle [deg] about ``axis`` that turns ``front`` closest to the Sun.

    With ``a`` the unit axis and ``v_perp = v - (a . v) a``, ``n(theta) . s`` is largest at
    ``theta = atan2(a . (n_perp x s_perp), n_perp . s_perp)``. A Sun along the axis (``|s_perp|`` below
    :data:`ALONG_AXIS` of ``|s|``) leaves every angle as good: the angle is kept at 0, with a warning
    (shown once).

    Parameters
    ----------
    axis : (3,) array_like of float
        Hinge axis, body frame; need not be unit.
    front : (3,) array_like of float
        Front normal of the turned parts at angle 0, body frame.
    sun_body : (3,) array_like of float
        Direction to the Sun, body frame.

    Returns
    -------
    float
        The best angle [deg], in (-180, 180].

    Examples
    --------
    >>> round(tracking_angle([0, 0, 1], [1, 0, 0], [0, 1, 0]), 6)
    90.0
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
    """Interpolate the angle [deg] of a scheduled hinge at a time: linear between points, held outside.

    Parameters
    ----------
    hinge : Hinge
        A hinge with a ``schedule``.
    time_s : float
        Time from the start [s].

    Returns
    -------
    float
        The angle [deg].

    Raises
    ------
    InputError
        When ``time_s`` is not a finite number.

    Examples
    --------
    >>> hinge = Hinge("p", (1.0, 0.0, 0.0), (0.0, 0.0, 0.0), schedule=((0.0, 0.0), (10.0, 90.0)))
    >>> schedule_angle(hinge, 5.0), schedule_angle(hinge, 20.0)
    (45.0, 90.0)
    """
    if isinstance(time_s, bool) or not isinstance(time_s, int | float) or not math.isfinite(time_s):
        raise InputError(f"time_s {time_s!r} must be a finite number [s]", parameters=("time_s",))
    times, angles = np.array(hinge.schedule, dtype=np.float64).T
    return float(np.interp(time_s, times, angles))


# ------------------------------------------------------------------------------------------- turning
def rotation(axis: Sequence[float], angle_deg: float) -> NDArray[np.float64]:
    """Build the right-handed rotation matrix about a unit axis (Rodrigues' formula).

    Parameters
    ----------
    axis : (3,) sequence of float
        Unit rotation axis.
    angle_deg : float
        Rotation angle [deg].

    Returns
    -------
    (3, 3) ndarray of float64
        The rotation matrix ``R``; ``R @ v`` turns ``v``.

    Examples
    --------
    >>> rotation((0.0, 0.0, 1.0), 90.0).round(6) @ [1.0, 0.0, 0.0]
    array([0., 1., 0.])
    """
    a = np.asarray(axis, dtype=np.float64)
    theta = math.radians(angle_deg)
    skew = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return math.cos(theta) * np.eye(3) + math.sin(theta) * skew + (1.0 - math.cos(theta)) * np.outer(a, a)


def turned(
    vertices: NDArray[np.float64], vertex_hinge: NDArray, hinges: Sequence[Hinge], angles_deg: Sequence[float]
) -> NDArray[np.float64]:
    """Turn the vertices of each hinge's parts about its line.

    A whole number of turns (0, 360, ...) moves nothing, to the bit.

    Parameters
    ----------
    vertices : (n_vertices, 3) ndarray of float64
        Vertex positions [m], body frame.
    vertex_hinge : (n_vertices,) ndarray of int
        Index of the hinge that turns each vertex, -1 for none.
    hinges : sequence of Hinge
        The hinges.
    angles_deg : sequence of float
        Angle [deg] of each hinge, same length as ``hinges``.

    Returns
    -------
    (n_vertices, 3) ndarray of float64
        A new array: vertex ``i`` of hinge ``k`` turned by ``angles_deg[k]``.

    Examples
    --------
    >>> import numpy as np
    >>> hinge = Hinge("p", (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), angle_deg=90.0)
    >>> turned(np.array([[2.0, 0, 0], [5.0, 0, 0]]), np.array([0, -1]), [hinge], [90.0]).round(6)
    array([[1., 1., 0.],
           [5., 0., 0.]])
    """
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
    """Split the vertices that facets of different hinge groups share.

    Each vertex gets a copy for every further group whose facets use it, so that turning one group does
    not drag the other's facets along.

    Parameters
    ----------
    vertices : (n_vertices, 3) ndarray of float64
        Vertex positions.
    faces : (n_faces, 3) ndarray of int64
        Vertex indices of each triangle.
    facet_group : (n_faces,) ndarray of int
        Group of each facet: a hinge's index, -1 for unturned facets.

    Returns
    -------
    vertices : (n_vertices_out, 3) ndarray of float64
        The vertices, the copies appended; ``vertices`` itself when nothing is shared.
    faces : (n_faces, 3) ndarray of int64
        The faces, re-indexed onto the copies.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    >>> f = np.array([[0, 1, 2], [1, 3, 2]])
    >>> v2, f2 = detached(v, f, np.array([-1, 0]))
    >>> len(v2), f2.tolist()
    (6, [[0, 1, 2], [4, 3, 5]])
    """
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
    """Compute the area-weighted mean front normal of a set of triangles.

    The front is the counter-clockwise side.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray of float64
        Corner coordinates of each triangle.

    Returns
    -------
    (3,) ndarray of float64 or None
        The unit mean normal; None with no triangles or with fronts that cancel (as a closed body's do).

    Examples
    --------
    >>> import numpy as np
    >>> front_normal(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]]))
    array([0., 0., 1.])
    >>> front_normal(np.zeros((0, 3, 3))) is None
    True
    """
    doubled = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    total, area = doubled.sum(axis=0), np.linalg.norm(doubled, axis=1).sum()
    if area == 0.0 or np.linalg.norm(total) <= FRONT_ACROSS * area:
        return None
    return total / np.linalg.norm(total)


# ------------------------------------------------------------------------------------------- binding
def part_groups(
    hits: NDArray[np.bool_], part_names: Sequence[str], hinges: Sequence[Hinge], mesh: str, path: str | None
) -> NDArray[np.int64]:
    """Find the hinge that turns each part from a glob-by-part match table.

    Parameters
    ----------
    hits : (n_hinges, n_parts) ndarray of bool
        ``hits[k, p]``: hinge ``k``'s glob matches part ``p``.
    part_names : sequence of str
        Name of each part.
    hinges : sequence of Hinge
        The hinges.
    mesh : str
        Name of the mesh, for messages.
    path : str or None
        Path of the materials file, for messages.

    Returns
    -------
    (n_parts,) ndarray of int64
        Index of the hinge turning each part, -1 for none.

    Raises
    ------
    MaterialError
        A glob that matches no part of ``mesh``, or a part that two globs match.

    Examples
    --------
    >>> import numpy as np
    >>> hinge = Hinge("wing", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), angle_deg=0.0)
    >>> part_groups(np.array([[False, True]]), ["bus", "wing"], [hinge], "sat.obj", None).tolist()
    [-1, 0]
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
    """Refuse a closed body whose facets two hinge groups would turn apart.

    A closed body here is the ``solid`` facets, closed across parts; turning part of it would open it.

    Parameters
    ----------
    faces : (n_faces, 3) ndarray of int64
        Vertex indices of each triangle.
    solid : (n_faces,) ndarray of bool
        Facets that belong to closed bodies.
    facet_group : (n_faces,) ndarray of int64
        Hinge index of each facet, -1 for unturned.
    facet_names : sequence of str
        Part name of each facet.
    hinges : sequence of Hinge
        The hinges.
    path : str or None
        Path of the materials file, for messages.

    Raises
    ------
    MaterialError
        Naming the hinge, the part it turns and a part of the same body it does not.

    Examples
    --------
    >>> import numpy as np
    >>> faces = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> hinge = Hinge("lid", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), angle_deg=0.0)
    >>> solid = np.ones(4, bool)
    >>> check_bodies(faces, solid, np.array([-1, -1, -1, -1]), ["a"] * 4, [hinge], None)
    >>> check_bodies(faces, solid, np.array([-1, -1, -1, 0]), ["a", "a", "a", "lid"], [hinge], None)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.MaterialError: [articulation] "lid" turns part 'lid', which closes a body ...
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
    """Give each tracking hinge without a front the mean front normal of the sheets it turns.

    Parameters
    ----------
    hinges : sequence of Hinge
        The hinges.
    triangles : (n_faces, 3, 3) ndarray of float64
        The mesh's triangles as drawn.
    facet_group : (n_faces,) ndarray of int64
        Hinge index of each facet, -1 for unturned.
    sheet : (n_faces,) ndarray of bool
        Facets that are sheets (open surfaces with a front).
    path : str or None
        Path of the materials file, for messages.

    Returns
    -------
    tuple of Hinge
        ``hinges``, each tracking one with a unit ``front``.

    Raises
    ------
    MaterialError
        A tracking hinge whose parts have no front (closed bodies only: their normals cancel), or whose
        front lies along its axis.

    Examples
    --------
    >>> import numpy as np
    >>> tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    >>> hinge = Hinge("wing", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), track="sun")
    >>> with_fronts([hinge], tri, np.array([0]), np.array([True]), None)[0].front
    (0.0, 0.0, 1.0)
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
