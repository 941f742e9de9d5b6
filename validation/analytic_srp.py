"""Closed-form direct solar-radiation-pressure force and torque on smooth convex bodies.

These are the independent references for the ray-traced mesh solver: a flat plate, a sphere, a
cylinder (with or without end caps), a right circular cone (with or without its base) and two
parallel square plates, one partly shadowing the other. Everything is in the body frame and SI;
the Sun vector ``u`` points from the spacecraft toward the Sun (METHOD.md "Frames"). The module
imports numpy only and nothing from ``forces``.

Notes
-----
**Surface law.** A lit element (outward normal ``n``, area ``dA``, ``c = n . u > 0``) takes
(METHOD.md, the paper's eq. (4) with its ``s = -u`` and inner normal ``n_paper = -n``)::

    dF = -P dA c [ a u + (2 rho_s c + (2/3) rho_d) n ],    a = 1 - sigma - rho_s,

with ``P = flux / c_light``, ``rho_s = rho beta`` and ``rho_d = rho (1 - beta)``; unlit elements
take nothing. The paper's eq. (2) has the opposite sign (it is the momentum carried off by the
mirror-reflected light) and eq. (5) drops a ``cos(theta)`` on ``sigma``; eq. (4), used here, is
right. The paper's coefficients are normalised by ``Q/(2c)``, so its ``C`` is ``2 F / (P A)``.
This module returns dimensional forces only.

**Reduction to six lit integrals.** Because ``u`` and the material are constant over a piece of
surface, the force and the torque about the body origin are fixed by six integrals over the lit
part ``S+ = {n . u > 0}`` of that piece::

    K  = int c dA          J1 = int c n dA         J2 = int c^2 n dA
    R1 = int c r dA        T1 = int c r x n dA     T2 = int c^2 r x n dA

    F   = -P [ a K u + 2 rho_s J2 + (2/3) rho_d J1 ]
    M_0 = -P [ a R1 x u + 2 rho_s T2 + (2/3) rho_d T1 ],     M_ref = M_0 - r_ref x F.

``K`` is the projected (shadow) area of the piece. For the convex bodies here there is no
self-shadowing, so ``S+`` is exactly the set where ``n . u > 0``, and every reflected photon
escapes: these are the complete SRP loads, inter-reflection included (``K_IS = 0``).

**Flat piece** (area ``A``, first moment ``m = int r dA``, normal ``n``): with ``c = n . u > 0``,
``K = c A``, ``J1 = c A n``, ``J2 = c^2 A n``, ``R1 = c m``, ``T1 = c m x n``, ``T2 = c^2 m x n``.

**Sphere** (radius ``R``, centre at the origin, ``n = r / R``). On the lit hemisphere around
``u`` the integrals of ``c^k n`` are along ``u`` by symmetry, with
``int_{hemisphere} c^k dOmega = 2 pi / (k + 1)``; ``r x n = 0``. Hence ``K = pi R^2``,
``J1 = (2 pi / 3) R^2 u``, ``J2 = (pi / 2) R^2 u``, ``R1 = R J1``, ``T1 = T2 = 0``, and
``F = -P pi R^2 (1 - sigma + (4/9) rho_d) u`` with no torque about the centre; the specular
share drops out.

**Lateral surface of a frustum** (cylinder and cone). Take the generator from
``(r_b, z_b)`` to ``(r_t, z_t)``, ``z_t > z_b``, slant length ``l``. Its outward normal is
``n = cos(d) e_r + sin(d) e_z`` with ``cos(d) = (z_t - z_b) / l``, ``sin(d) = (r_b - r_t) / l``
(``d = 0`` for a cylinder, ``d`` = half-angle for a cone). Measure the azimuth ``phi`` from
``e1``, the unit projection of ``u`` on the xy-plane (``e2 = e_z x e1``, ``s = |u_xy|``). Then
``c = A + B cos(phi)`` with ``A = sin(d) u_z`` and ``B = cos(d) s >= 0``, independent of the
position along the generator, so the lit set is the arc ``|phi| < phi0``:

- ``B > 0``: ``cos(phi0) = clip(-A / B, -1, 1)``. ``-A/B <= -1`` means fully lit
  (``phi0 = pi``), ``-A/B >= 1`` fully dark (``phi0 = 0``). The normals lean ``90 deg - d``
  off the axis, so with the Sun at ``alpha`` from +z a cone's side is fully lit for
  ``alpha <= d`` and dark for ``alpha >= 180 deg - d`` (70 and 110 deg for the paper's cone);
  between, ``cos(phi0) = -tan(d) / tan(alpha)``. The clip makes the regimes join continuously.
- ``B = 0`` (Sun on the axis): ``c = A`` everywhere; fully lit if ``A > 0``, else dark.

With ``C_k = int_{-phi0}^{phi0} cos^k dphi``, i.e. ``C0 = 2 phi0``, ``C1 = 2 sin(phi0)``,
``C2 = phi0 + sin(phi0) cos(phi0)``, ``C3 = 2 sin(phi0) - (2/3) sin^3(phi0)``, the arc integrals
of ``c`` and ``c^2`` (terms odd in ``phi`` vanish) are::

    G0 = int c        = A C0 + B C1        G1 = int c cos    = A C1 + B C2
    G2 = int c^2      = A^2 C0 + 2AB C1 + B^2 C2
    G3 = int c^2 cos  = A^2 C1 + 2AB C2 + B^2 C3

With ``rho(t) = r_b + (r_t - r_b) t``, ``z(t) = z_b + (z_t - z_b) t`` and
``dA = rho l dt dphi``, the generator integrals are ``g0 = int rho l dt = l (r_b + r_t) / 2``,
``gr = int rho^2 l dt = l (r_b^2 + r_b r_t + r_t^2) / 3``,
``gz = int z rho l dt = l [z_b r_b + (z_b (r_t - r_b) + r_b (z_t - z_b)) / 2
+ (z_t - z_b)(r_t - r_b) / 3]``. Writing ``r = rho e_r + z e_z`` gives
``r x n = (z cos(d) - rho sin(d)) e_phi``, so with ``gt = cos(d) gz - sin(d) gr``::

    K  = g0 G0
    J1 = g0 (cos(d) G1 e1 + sin(d) G0 e_z)      J2 = g0 (cos(d) G3 e1 + sin(d) G2 e_z)
    R1 = gr G1 e1 + gz G0 e_z                   T1 = gt G1 e2       T2 = gt G3 e2

For the cylinder (``d = 0``, centred) ``gz = gt = 0``: the lateral surface alone has the torque
``M_0 = (pi/2) P a R^2 L s u_z e2`` about its centre, which the lit cap cancels exactly.

**Two plates, one shadowing the other.** The shadow of plate B (in the plane ``z = h``) on the
plane ``z = 0`` is B translated by ``-(h / u_z) u``; it is clipped to plate A
(Sutherland-Hodgman), and its area and first moment come from the shoelace formula. Plate A's
lit part is A minus the shadow: area ``a^2 - S``, first moment ``-S c_S`` (A is centred at the
origin), and the flat-piece integrals above apply.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "SOLAR_FLUX_1AU_W_M2",
    "SPEED_OF_LIGHT_M_S",
    "ForceTorque",
    "Optics",
    "ShadowedPlatesSrp",
    "cone_srp",
    "cylinder_srp",
    "plate_srp",
    "shadowed_plates_srp",
    "sphere_srp",
    "sun_vector_from_alpha",
]

SPEED_OF_LIGHT_M_S = 299_792_458.0
SOLAR_FLUX_1AU_W_M2 = 1361.0
_UNIT_TOLERANCE = 1e-9

Vector = NDArray[np.float64]


class Optics(NamedTuple):
    """Optical coefficients of one surface (METHOD.md "Surfaces"); a plain 3-tuple also works.

    Attributes
    ----------
    rho : float
        Reflectivity [-], in [0, 1].
    beta : float
        Specular share of the reflected light [-], in [0, 1].
    sigma : float
        Transmissivity [-], in [0, 1], with ``rho + sigma <= 1``.
    """

    rho: float
    beta: float
    sigma: float


class ForceTorque(NamedTuple):
    """Force and torque on a body or a part of it; body frame, SI.

    Attributes
    ----------
    force_N : (3,) float64
        Force [N].
    torque_Nm : (3,) float64
        Torque [N m] about the reference point the function was given.
    """

    force_N: Vector
    torque_Nm: Vector


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
    """

    plate_a: ForceTorque
    plate_b: ForceTorque
    total: ForceTorque
    shadow_area_m2: float
    shadow_polygon_m: Vector


@dataclass(frozen=True)
class _LitIntegrals:
    """The six lit-surface integrals of one surface piece, about the body origin (module Notes).

    Attributes
    ----------
    projected : float
        ``K = int c dA`` [m^2].
    normal_1, normal_2 : (3,) float64
        ``J1 = int c n dA``, ``J2 = int c^2 n dA`` [m^2].
    position_1 : (3,) float64
        ``R1 = int c r dA`` [m^3].
    moment_1, moment_2 : (3,) float64
        ``T1 = int c (r x n) dA``, ``T2 = int c^2 (r x n) dA`` [m^3].
    """

    projected: float
    normal_1: Vector
    normal_2: Vector
    position_1: Vector
    moment_1: Vector
    moment_2: Vector


def sun_vector_from_alpha(alpha_deg: float) -> Vector:
    """Sun vector at angle ``alpha`` from the body axis +z, in the xz-plane.

    Parameters
    ----------
    alpha_deg : float
        Angle between the body axis +z and the Sun vector [deg]; 0 puts the Sun on +z.

    Returns
    -------
    (3,) float64
        ``u = (sin(alpha), 0, cos(alpha))``, unit, spacecraft -> Sun, body frame.
    """
    alpha = np.radians(alpha_deg)
    return np.array([np.sin(alpha), 0.0, np.cos(alpha)])


def plate_srp(
    size_x_m: float,
    size_y_m: float,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    one_sided: bool = True,
    back_optics: Optics | tuple[float, float, float] | None = None,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Solar-radiation-pressure force and torque on a flat rectangular plate.

    The plate is ``size_x_m`` by ``size_y_m``, centred at the origin in the plane z = 0, with
    front normal +z.

    Parameters
    ----------
    size_x_m, size_y_m : float
        Side lengths along x and y [m].
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame.
    optics : Optics or (rho, beta, sigma)
        Optical coefficients of the front side (normal +z).
    one_sided : bool, optional
        If True (default) only the front interacts; light from below (``u_z < 0``) gives zero.
    back_optics : Optics or (rho, beta, sigma), optional
        Optical coefficients of the back side (normal -z) of a two-sided plate; default the
        front's. Only with ``one_sided=False``.
    flux_W_m2 : float, optional
        Solar flux [W/m^2], default 1361.
    ref_point_m : (3,) array_like, optional
        Point the torque is taken about [m], default the origin.

    Returns
    -------
    ForceTorque
        Force [N] and torque [N m] about ``ref_point_m``, body frame.
    """
    u = _unit_sun(sun_vector)
    if one_sided and back_optics is not None:
        raise ValueError("back_optics is given for a one-sided plate; pass one_sided=False")
    area = size_x_m * size_y_m
    sides = [(_flat_patch(area, np.zeros(3), np.array([0.0, 0.0, 1.0]), u), optics)]
    if not one_sided:
        back = optics if back_optics is None else back_optics
        sides.append((_flat_patch(area, np.zeros(3), np.array([0.0, 0.0, -1.0]), u), back))
    return _total_load(sides, u, flux_W_m2, ref_point_m)


def sphere_srp(
    radius_m: float,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Solar-radiation-pressure force and torque on a sphere centred at the origin.

    Parameters
    ----------
    radius_m : float
        Sphere radius [m].
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame.
    optics : Optics or (rho, beta, sigma)
        Optical coefficients of the surface.
    flux_W_m2 : float, optional
        Solar flux [W/m^2], default 1361.
    ref_point_m : (3,) array_like, optional
        Point the torque is taken about [m], default the origin (the torque there is zero).

    Returns
    -------
    ForceTorque
        Force [N], equal to ``-P pi R^2 (1 - sigma + 4 rho (1 - beta) / 9) u``, and torque
        [N m] about ``ref_point_m``, body frame.
    """
    u = _unit_sun(sun_vector)
    return _total_load([(_sphere(radius_m, u), optics)], u, flux_W_m2, ref_point_m)


def cylinder_srp(
    radius_m: float,
    length_m: float,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    caps: bool = True,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Solar-radiation-pressure force and torque on a circular cylinder along z.

    The cylinder is centred at the origin, its axis along z, from z = -L/2 to z = +L/2.

    Parameters
    ----------
    radius_m, length_m : float
        Radius R and length L [m].
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame.
    optics : Optics or (rho, beta, sigma)
        Optical coefficients, the same on every surface.
    caps : bool, optional
        If True (default) include the end discs at z = +L/2 (normal +z) and z = -L/2 (normal
        -z). If False only the outer side of the lateral surface interacts.
    flux_W_m2 : float, optional
        Solar flux [W/m^2], default 1361.
    ref_point_m : (3,) array_like, optional
        Point the torque is taken about [m], default the origin.

    Returns
    -------
    ForceTorque
        Force [N] and torque [N m] about ``ref_point_m``, body frame.
    """
    u = _unit_sun(sun_vector)
    half = 0.5 * length_m
    pieces = [_frustum_lateral(radius_m, -half, radius_m, half, u)]
    if caps:
        disc = np.pi * radius_m**2
        for side in (1.0, -1.0):
            moment = np.array([0.0, 0.0, side * half * disc])
            pieces.append(_flat_patch(disc, moment, np.array([0.0, 0.0, side]), u))
    return _total_load([(piece, optics) for piece in pieces], u, flux_W_m2, ref_point_m)


def cone_srp(
    radius_m: float,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    half_angle_deg: float = 70.0,
    base: bool = True,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Solar-radiation-pressure force and torque on a right circular cone along z.

    The base disc (radius R) lies in the plane z = 0, centred at the origin, normal -z; the apex
    is at (0, 0, h) with ``h = R / tan(half_angle)``.

    Parameters
    ----------
    radius_m : float
        Base radius R [m].
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame.
    optics : Optics or (rho, beta, sigma)
        Optical coefficients, the same on every surface.
    half_angle_deg : float, optional
        Angle between the axis and a generator [deg], in (0, 90); default 70, as in the paper.
    base : bool, optional
        If True (default) include the base disc; if False only the outer side of the lateral
        surface interacts.
    flux_W_m2 : float, optional
        Solar flux [W/m^2], default 1361.
    ref_point_m : (3,) array_like, optional
        Point the torque is taken about [m], default the origin (centre of the base).

    Returns
    -------
    ForceTorque
        Force [N] and torque [N m] about ``ref_point_m``, body frame.

    Notes
    -----
    With the Sun at ``alpha`` from +z the lateral surface is fully lit for
    ``alpha <= half_angle``, fully dark for ``alpha >= 180 deg - half_angle`` and lit on the arc
    ``|phi| < arccos(-tan(half_angle) / tan(alpha))`` of azimuth about the Sun's between; the
    base is lit for ``alpha > 90 deg``.
    """
    if not 0.0 < half_angle_deg < 90.0:
        raise ValueError(f"cone half_angle_deg must lie in (0, 90), got {half_angle_deg}")
    u = _unit_sun(sun_vector)
    height = radius_m / np.tan(np.radians(half_angle_deg))
    pieces = [_frustum_lateral(radius_m, 0.0, 0.0, height, u)]
    if base:
        pieces.append(_flat_patch(np.pi * radius_m**2, np.zeros(3), np.array([0.0, 0.0, -1.0]), u))
    return _total_load([(piece, optics) for piece in pieces], u, flux_W_m2, ref_point_m)


def shadowed_plates_srp(
    side_a_m: float,
    side_b_m: float,
    centre_b_m: ArrayLike,
    gamma_deg: float,
    sun_vector: ArrayLike,
    optics: Optics | tuple[float, float, float],
    *,
    optics_b: Optics | tuple[float, float, float] | None = None,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ShadowedPlatesSrp:
    """Solar-radiation-pressure loads on two parallel one-sided square plates, B shadowing A.

    Plate A: side ``a``, centred at the origin in the plane z = 0, front normal +z, corners
    ``(-a/2, -a/2, 0), (a/2, -a/2, 0), (a/2, a/2, 0), (-a/2, a/2, 0)`` (counter-clockwise seen
    from +z). Plate B: side ``b``, front normal +z, corners ``c_B + Rz(gamma) @ p_k`` with
    ``p_k = (-b/2, -b/2, 0), (b/2, -b/2, 0), (b/2, b/2, 0), (-b/2, b/2, 0)`` in that order and
    ``Rz(gamma) = [[cos g, -sin g, 0], [sin g, cos g, 0], [0, 0, 1]]`` (a positive ``gamma``
    turns B counter-clockwise seen from +z). Both are one-sided: their backs (normal -z) do not
    interact with light.

    Parameters
    ----------
    side_a_m, side_b_m : float
        Side lengths a and b [m].
    centre_b_m : (3,) array_like
        Centre ``c_B = (x0, y0, h)`` of plate B [m], with ``h > 0``.
    gamma_deg : float
        Rotation of B about z [deg].
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
    """
    u = _unit_sun(sun_vector)
    if u[2] <= 0.0:
        raise ValueError(f"shadowed_plates_srp needs the Sun above the plates (u_z > 0), got u_z = {u[2]}")
    centre_b = np.asarray(centre_b_m, dtype=float)
    if centre_b.shape != (3,) or centre_b[2] <= 0.0:
        raise ValueError(f"centre_b_m must be (x0, y0, h) with h > 0 [m], got {centre_b_m}")
    shadow = _clip_convex(_shadow_of_b(side_b_m, centre_b, gamma_deg, u), _square(side_a_m))
    shadow_area, shadow_moment = _polygon_area_moment(shadow)
    up = np.array([0.0, 0.0, 1.0])
    lit_a = _flat_patch(side_a_m**2 - shadow_area, -np.array([*shadow_moment, 0.0]), up, u)
    plate_b = _flat_patch(side_b_m**2, side_b_m**2 * centre_b, up, u)
    load_a = _total_load([(lit_a, optics)], u, flux_W_m2, ref_point_m)
    b_optics = optics if optics_b is None else optics_b
    load_b = _total_load([(plate_b, b_optics)], u, flux_W_m2, ref_point_m)
    total = ForceTorque(load_a.force_N + load_b.force_N, load_a.torque_Nm + load_b.torque_Nm)
    return ShadowedPlatesSrp(load_a, load_b, total, shadow_area, shadow)


def _unit_sun(sun_vector: ArrayLike) -> Vector:
    """Check that the Sun vector is a unit (3,) vector and return it as float64."""
    u = np.asarray(sun_vector, dtype=float)
    if u.shape != (3,) or abs(np.linalg.norm(u) - 1.0) > _UNIT_TOLERANCE:
        raise ValueError(
            f"sun_vector must be a unit (3,) vector, got {sun_vector}; "
            "divide it by its norm, or use sun_vector_from_alpha"
        )
    return u


def _checked_optics(optics: Optics | tuple[float, float, float]) -> Optics:
    """Check 0 <= rho, beta, sigma <= 1 and rho + sigma <= 1; return them as ``Optics``."""
    rho, beta, sigma = (float(value) for value in optics)
    if not (0.0 <= rho <= 1.0 and 0.0 <= beta <= 1.0 and 0.0 <= sigma <= 1.0):
        raise ValueError(f"rho, beta, sigma must each lie in [0, 1], got {tuple(optics)}")
    if rho + sigma > 1.0:
        raise ValueError(f"rho + sigma must not exceed 1, got rho={rho}, sigma={sigma}")
    return Optics(rho, beta, sigma)


def _total_load(
    pieces: list[tuple[_LitIntegrals, Optics | tuple[float, float, float]]],
    u: Vector,
    flux_W_m2: float,
    ref_point_m: ArrayLike,
) -> ForceTorque:
    """Sum the loads of surface pieces and move the torque to the reference point.

    Parameters
    ----------
    pieces : list of (_LitIntegrals, optics)
        Each surface piece with its optical coefficients.
    u : (3,) float64
        Unit Sun vector, body frame.
    flux_W_m2 : float
        Solar flux [W/m^2].
    ref_point_m : (3,) array_like
        Reference point for the torque [m].

    Returns
    -------
    ForceTorque
        Total force [N] and torque [N m] about ``ref_point_m``.
    """
    ref = np.asarray(ref_point_m, dtype=float)
    if ref.shape != (3,):
        raise ValueError(f"ref_point_m must be a (3,) point [m], got {ref_point_m}")
    pressure = flux_W_m2 / SPEED_OF_LIGHT_M_S
    force, torque = np.zeros(3), np.zeros(3)
    for integrals, optics in pieces:
        piece_force, piece_torque = _piece_load(integrals, _checked_optics(optics), u, pressure)
        force += piece_force
        torque += piece_torque
    return ForceTorque(force, torque - np.cross(ref, force))


def _piece_load(lit: _LitIntegrals, optics: Optics, u: Vector, pressure: float) -> tuple[Vector, Vector]:
    """Force [N] and torque about the origin [N m] of one piece from its six lit integrals."""
    rho_s = optics.rho * optics.beta
    rho_d = optics.rho - rho_s
    absorbed = 1.0 - optics.sigma - rho_s
    force = -pressure * (
        absorbed * lit.projected * u + 2.0 * rho_s * lit.normal_2 + (2.0 / 3.0) * rho_d * lit.normal_1
    )
    torque = -pressure * (
        absorbed * np.cross(lit.position_1, u)
        + 2.0 * rho_s * lit.moment_2
        + (2.0 / 3.0) * rho_d * lit.moment_1
    )
    return force, torque


def _flat_patch(area: float, first_moment: Vector, normal: Vector, u: Vector) -> _LitIntegrals:
    """Lit integrals of a flat piece from its area [m^2], ``int r dA`` (3,) [m^3] and unit normal.

    The piece is wholly lit when ``n . u > 0`` and contributes nothing otherwise.
    """
    c = max(float(normal @ u), 0.0)
    arm = np.cross(first_moment, normal)
    return _LitIntegrals(
        projected=c * area,
        normal_1=c * area * normal,
        normal_2=c * c * area * normal,
        position_1=c * first_moment,
        moment_1=c * arm,
        moment_2=c * c * arm,
    )


def _sphere(radius: float, u: Vector) -> _LitIntegrals:
    """Lit integrals of a sphere of radius [m] centred at the origin (module Notes)."""
    normal_1 = (2.0 * np.pi / 3.0) * radius**2 * u
    return _LitIntegrals(
        projected=np.pi * radius**2,
        normal_1=normal_1,
        normal_2=(np.pi / 2.0) * radius**2 * u,
        position_1=radius * normal_1,
        moment_1=np.zeros(3),
        moment_2=np.zeros(3),
    )


def _frustum_lateral(
    r_bottom: float, z_bottom: float, r_top: float, z_top: float, u: Vector
) -> _LitIntegrals:
    """Lit integrals of the outer lateral surface of a frustum of revolution about z.

    Parameters
    ----------
    r_bottom, z_bottom : float
        Radius and height of the lower rim [m].
    r_top, z_top : float
        Radius and height of the upper rim [m], ``z_top > z_bottom``; ``r_top = 0`` is a cone.
    u : (3,) float64
        Unit Sun vector, body frame.

    Returns
    -------
    _LitIntegrals
        The six integrals over the lit arc (module Notes, "Lateral surface of a frustum").
    """
    d_r, d_z = r_top - r_bottom, z_top - z_bottom
    slant = np.hypot(d_r, d_z)
    cos_d, sin_d = d_z / slant, -d_r / slant
    s = np.hypot(u[0], u[1])
    e1 = np.array([u[0] / s, u[1] / s, 0.0]) if s > 0.0 else np.array([1.0, 0.0, 0.0])
    e2 = np.array([-e1[1], e1[0], 0.0])
    e_z = np.array([0.0, 0.0, 1.0])

    a_coef, b_coef = sin_d * u[2], cos_d * s
    c0, c1, c2, c3 = _lit_arc_cosine_integrals(a_coef, b_coef)
    g0 = a_coef * c0 + b_coef * c1
    g1 = a_coef * c1 + b_coef * c2
    g2 = a_coef**2 * c0 + 2.0 * a_coef * b_coef * c1 + b_coef**2 * c2
    g3 = a_coef**2 * c1 + 2.0 * a_coef * b_coef * c2 + b_coef**2 * c3

    area_gen = slant * (r_bottom + r_top) / 2.0
    radial_gen = slant * (r_bottom**2 + r_bottom * r_top + r_top**2) / 3.0
    height_gen = slant * (z_bottom * r_bottom + (z_bottom * d_r + r_bottom * d_z) / 2.0 + d_z * d_r / 3.0)
    arm_gen = cos_d * height_gen - sin_d * radial_gen
    return _LitIntegrals(
        projected=area_gen * g0,
        normal_1=area_gen * (cos_d * g1 * e1 + sin_d * g0 * e_z),
        normal_2=area_gen * (cos_d * g3 * e1 + sin_d * g2 * e_z),
        position_1=radial_gen * g1 * e1 + height_gen * g0 * e_z,
        moment_1=arm_gen * g1 * e2,
        moment_2=arm_gen * g3 * e2,
    )


def _lit_arc_cosine_integrals(a_coef: float, b_coef: float) -> tuple[float, float, float, float]:
    """Integrals of cos^k(phi), k = 0..3, over the arc where ``a + b cos(phi) > 0``, ``b >= 0``.

    Returns
    -------
    tuple of float
        ``(C0, C1, C2, C3)`` over ``|phi| < phi0`` (module Notes); all zero when no arc is lit.
    """
    if b_coef > 0.0:
        cos_0 = float(np.clip(-a_coef / b_coef, -1.0, 1.0))
    else:
        cos_0 = -1.0 if a_coef > 0.0 else 1.0
    phi_0 = float(np.arccos(cos_0))
    sin_0 = float(np.sqrt(1.0 - cos_0**2))
    return (
        2.0 * phi_0,
        2.0 * sin_0,
        phi_0 + sin_0 * cos_0,
        2.0 * sin_0 - (2.0 / 3.0) * sin_0**3,
    )


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
