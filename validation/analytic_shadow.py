"""Closed-form direct solar-radiation pressure on two parallel square plates, one shadowing the other.

The reference for the solver's partial shadows: the lit part of the lower plate is a polygon known
exactly, so the shadow's area and first moment, and with them the force and the torque, are exact.
The law of a lit piece is that of :mod:`sunwind.validation.analytic_srp_law`. Everything is in the
body frame and SI; the module imports numpy only and nothing from ``forces``.

Notes
-----
**Two plates, one shadowing the other.** The shadow of plate B (in the plane ``z = h``) on the
plane ``z = 0`` is B translated by ``-(h / u_z) u``; it is clipped to plate A
(Sutherland-Hodgman), and its area and first moment come from the shoelace formula. Plate A's
lit part is A minus the shadow: area ``a^2 - S``, first moment ``-S c_S`` (A is centred at the
origin), and the flat-piece integrals of :mod:`sunwind.validation.analytic_srp_law` apply.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.validation.analytic_srp_law import (
    SOLAR_FLUX_1AU_W_M2,
    ForceTorque,
    Optics,
    flat_patch,
    total_load,
    unit_sun,
)

__all__ = ["PlatePair", "ShadowedPlatesSrp", "shadowed_plates_srp"]

Vector = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class PlatePair:
    """Two parallel one-sided square plates, front normals +z: A at the origin, B above it.

    Plate A: side ``a``, centred at the origin in the plane z = 0, corners
    ``(-a/2, -a/2, 0), (a/2, -a/2, 0), (a/2, a/2, 0), (-a/2, a/2, 0)`` (counter-clockwise seen
    from +z). Plate B: side ``b``, corners ``c_B + Rz(gamma) @ p_k`` with
    ``p_k = (-b/2, -b/2, 0), (b/2, -b/2, 0), (b/2, b/2, 0), (-b/2, b/2, 0)`` in that order and
    ``Rz(gamma) = [[cos g, -sin g, 0], [sin g, cos g, 0], [0, 0, 1]]`` (a positive ``gamma``
    turns B counter-clockwise seen from +z). Their backs (normal -z) do not interact with light.

    Attributes
    ----------
    side_a_m, side_b_m : float
        Side lengths a and b [m].
    centre_b_m : (3,) array_like
        Centre ``c_B = (x0, y0, h)`` of plate B [m], with ``h > 0``.
    gamma_deg : float
        Rotation of B about z [deg].

    Examples
    --------
    >>> pair = PlatePair(side_a_m=1.0, side_b_m=1.0, centre_b_m=(0.5, 0.0, 1.0), gamma_deg=0.0)
    >>> pair.side_b_m
    1.0
    """

    side_a_m: float
    side_b_m: float
    centre_b_m: ArrayLike
    gamma_deg: float


@dataclass(frozen=True)
class ShadowedPlatesSrp:
    """Loads on two parallel square plates where the upper one shadows the lower one.

    Attributes
    ----------
    plate_a : ForceTorque
        Load on the lit part of the lower plate A [N, N m].
    plate_b : ForceTorque
        Load on the upper plate B [N, N m].
    total : ForceTorque
        Sum of the two [N, N m].
    shadow_area_m2 : float
        Area of B's shadow on A [m^2].
    shadow_polygon_m : (k, 2) float64
        Vertices (x, y) of B's shadow clipped to A, counter-clockwise seen from +z, in the plane
        z = 0 [m]; ``k = 0`` when no shadow falls on A.

    Examples
    --------
    >>> pair = PlatePair(1.0, 1.0, (0.5, 0.0, 1.0), 0.0)
    >>> result = shadowed_plates_srp(pair, [0.0, 0.0, 1.0], (0.0, 0.0, 0.0))
    >>> result.shadow_area_m2, result.shadow_polygon_m.shape
    (0.5, (4, 2))
    """

    plate_a: ForceTorque
    plate_b: ForceTorque
    total: ForceTorque
    shadow_area_m2: float
    shadow_polygon_m: Vector


def shadowed_plates_srp(
    plates: PlatePair,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    optics_b: Optics | tuple[float, float, float] | None = None,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ShadowedPlatesSrp:
    """Solar-radiation-pressure loads on two parallel one-sided square plates, B shadowing A.

    Parameters
    ----------
    plates : PlatePair
        Sides of A and B [m], centre of B [m] and its rotation about z [deg].
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame, with ``u_z > 0``.
    optics : Optics or (rho, beta, sigma)
        Optical coefficients of A's front, and of B's unless ``optics_b`` is given.
    optics_b : Optics or (rho, beta, sigma), optional
        Optical coefficients of B's front.
    flux_W_m2 : float, optional
        Solar flux [W/m^2], default 1361.
    ref_point_m : (3,) array_like, optional
        Point all torques are taken about [m], default the origin.

    Returns
    -------
    ShadowedPlatesSrp
        Loads on A's lit part, on B, their sum, and the shadow polygon and its area.

    Notes
    -----
    Direct pressure only: light that A reflects upward is counted as escaping even where it
    meets B's back, which does not interact. A solver that traces inter-reflection and lets B's
    back stop that light moves part of A's escaping momentum onto B, so compare with
    inter-reflection off or with ``rho = 0``. Light B reflects goes upward, away from A.

    Raises
    ------
    ValueError
        If the Sun vector is not a unit (3,) vector with ``u_z > 0``, or the plates or optics are
        out of range.

    Examples
    --------
    Black plates, Sun overhead, B shifted half a side: half of A is in shadow, so the total push is
    1.5 times that on one plate, ``P = flux / c`` per m^2:

    >>> pair = PlatePair(1.0, 1.0, (0.5, 0.0, 1.0), 0.0)
    >>> result = shadowed_plates_srp(pair, [0.0, 0.0, 1.0], (0.0, 0.0, 0.0))
    >>> result.shadow_area_m2, round(float(result.total.force_N[2] * 1e6), 4)
    (0.5, -6.8097)
    """
    side_a_m, side_b_m = plates.side_a_m, plates.side_b_m
    u = unit_sun(sun_vector)
    if u[2] <= 0.0:
        raise ValueError(f"shadowed_plates_srp needs the Sun above the plates (u_z > 0), got u_z = {u[2]}")
    centre_b = np.asarray(plates.centre_b_m, dtype=float)
    if centre_b.shape != (3,) or centre_b[2] <= 0.0:
        raise ValueError(f"centre_b_m must be (x0, y0, h) with h > 0 [m], got {plates.centre_b_m}")
    shadow = _clip_convex(_shadow_of_b(side_b_m, centre_b, plates.gamma_deg, u), _square(side_a_m))
    shadow_area, shadow_moment = _polygon_area_moment(shadow)
    up = np.array([0.0, 0.0, 1.0])
    lit_a = flat_patch(side_a_m**2 - shadow_area, -np.array([*shadow_moment, 0.0]), up, u)
    plate_b = flat_patch(side_b_m**2, side_b_m**2 * centre_b, up, u)
    load_a = total_load([(lit_a, optics)], u, flux_W_m2, ref_point_m)
    b_optics = optics if optics_b is None else optics_b
    load_b = total_load([(plate_b, b_optics)], u, flux_W_m2, ref_point_m)
    total = ForceTorque(load_a.force_N + load_b.force_N, load_a.torque_Nm + load_b.torque_Nm)
    return ShadowedPlatesSrp(load_a, load_b, total, shadow_area, shadow)


def _square(side: float) -> Vector:
    """Corners (4, 2) of a square of the given side [m] centred at the origin, counter-clockwise."""
    return 0.5 * side * np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def _shadow_of_b(side_b: float, centre_b: Vector, gamma_deg: float, u: Vector) -> Vector:
    """Shadow (4, 2) of plate B on the plane z = 0: B's corners moved by ``-(h / u_z) u``."""
    gamma = np.radians(gamma_deg)
    rotation = np.array([[np.cos(gamma), -np.sin(gamma)], [np.sin(gamma), np.cos(gamma)]])
    corners = centre_b[:2] + _square(side_b) @ rotation.T
    return corners - (centre_b[2] / u[2]) * u[:2]


def _clip_convex(subject: Vector, clip: Vector) -> Vector:
    """Sutherland-Hodgman clip of a polygon by a convex counter-clockwise polygon.

    Parameters
    ----------
    subject : (n, 2) float64
        Polygon to clip, counter-clockwise [m].
    clip : (m, 2) float64
        Convex clipping polygon, counter-clockwise [m].

    Returns
    -------
    (k, 2) float64
        The intersection, counter-clockwise; ``k = 0`` when it is empty.
    """
    polygon = [np.asarray(p, dtype=float) for p in subject]
    for start, end in zip(clip, np.roll(clip, -1, axis=0), strict=True):
        edge = end - start
        if not polygon:
            break
        side = [edge[0] * (p[1] - start[1]) - edge[1] * (p[0] - start[0]) for p in polygon]
        clipped = []
        for k, (point, inside) in enumerate(zip(polygon, side, strict=True)):
            prev_point, prev_inside = polygon[k - 1], side[k - 1]
            if inside * prev_inside < 0.0:
                t = prev_inside / (prev_inside - inside)
                clipped.append(prev_point + t * (point - prev_point))
            if inside >= 0.0:
                clipped.append(point)
        polygon = clipped
    return np.array(polygon, dtype=float).reshape(-1, 2)


def _polygon_area_moment(polygon: Vector) -> tuple[float, Vector]:
    """Shoelace area [m^2] and first moment ``int (x, y) dA`` (2,) [m^3] of a simple polygon.

    A counter-clockwise polygon has positive area; fewer than three vertices give zero.
    """
    if len(polygon) < 3:
        return 0.0, np.zeros(2)
    x, y = polygon[:, 0], polygon[:, 1]
    x_next, y_next = np.roll(x, -1), np.roll(y, -1)
    cross = x * y_next - x_next * y
    area = 0.5 * float(cross.sum())
    moment = np.array([((x + x_next) * cross).sum(), ((y + y_next) * cross).sum()]) / 6.0
    return area, moment
