"""Closed-form direct solar-radiation-pressure force and torque on smooth convex bodies.

These are the independent references for the ray-traced mesh solver: a flat plate, a sphere, a
cylinder (with or without end caps) and a right circular cone (with or without its base), each the
sum of the lit-surface integrals of its pieces under the law of
:mod:`sunwind.validation.analytic_srp_law`. Everything is in the body frame and SI; the Sun vector
``u`` points from the spacecraft toward the Sun (METHOD.md "Frames, units and signs"). The module imports
numpy only and nothing from ``forces``.

Notes
-----
For the convex bodies here there is no self-shadowing, so the lit part of every piece is exactly
the set where ``n . u > 0``, and every reflected photon escapes: these are the complete SRP loads,
inter-reflection included (``K_IS = 0``).

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
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.validation.analytic_srp_law import (
    SOLAR_FLUX_1AU_W_M2,
    ForceTorque,
    LitIntegrals,
    Optics,
    flat_patch,
    total_load,
    unit_sun,
)

__all__ = ["cone_srp", "cylinder_srp", "plate_srp", "sphere_srp"]

Vector = NDArray[np.float64]


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

    Raises
    ------
    ValueError
        If the Sun vector is not a unit (3,) vector, or ``back_optics`` is given with ``one_sided=True``.

    Examples
    --------
    Sun overhead, 1 m^2: a black plate takes ``P = flux / c``, a white specular one twice that [uN]:

    >>> black = (0.0, 0.0, 0.0)  # rho, beta, sigma
    >>> (plate_srp(1.0, 1.0, [0.0, 0.0, 1.0], black).force_N * 1e6).round(4).tolist()
    [0.0, 0.0, -4.5398]
    >>> (plate_srp(1.0, 1.0, [0.0, 0.0, 1.0], (1.0, 1.0, 0.0)).force_N * 1e6).round(4).tolist()
    [0.0, 0.0, -9.0796]

    References
    ----------
    .. [1] O. Montenbruck and E. Gill, *Satellite Orbits: Models, Methods and Applications*,
       Springer, 2000, section 3.4.
    """
    u = unit_sun(sun_vector)
    if one_sided and back_optics is not None:
        raise ValueError("back_optics is given for a one-sided plate; pass one_sided=False")
    area = size_x_m * size_y_m
    sides = [(flat_patch(area, np.zeros(3), np.array([0.0, 0.0, 1.0]), u), optics)]
    if not one_sided:
        back = optics if back_optics is None else back_optics
        sides.append((flat_patch(area, np.zeros(3), np.array([0.0, 0.0, -1.0]), u), back))
    return total_load(sides, u, flux_W_m2, ref_point_m)


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

    Raises
    ------
    ValueError
        If the Sun vector is not a unit (3,) vector.

    Examples
    --------
    >>> black = (0.0, 0.0, 0.0)  # rho, beta, sigma
    >>> (sphere_srp(1.0, [0.0, 0.0, 1.0], black).force_N * 1e6).round(4).tolist()  # -P pi R^2 u
    [0.0, 0.0, -14.2622]
    """
    u = unit_sun(sun_vector)
    return total_load([(_sphere(radius_m, u), optics)], u, flux_W_m2, ref_point_m)


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

    Raises
    ------
    ValueError
        If the Sun vector is not a unit (3,) vector.

    Examples
    --------
    Lit side-on, a black cylinder takes ``P`` on its silhouette ``2 R L`` [uN]:

    >>> black = (0.0, 0.0, 0.0)  # rho, beta, sigma
    >>> load = cylinder_srp(0.5, 1.0, [1.0, 0.0, 0.0], black)
    >>> ((load.force_N * 1e6).round(4) + 0.0).tolist()  # + 0.0 turns -0.0 into 0.0
    [-4.5398, 0.0, 0.0]
    """
    u = unit_sun(sun_vector)
    half = 0.5 * length_m
    pieces = [_frustum_lateral(radius_m, -half, radius_m, half, u)]
    if caps:
        disc = np.pi * radius_m**2
        for side in (1.0, -1.0):
            moment = np.array([0.0, 0.0, side * half * disc])
            pieces.append(flat_patch(disc, moment, np.array([0.0, 0.0, side]), u))
    return total_load([(piece, optics) for piece in pieces], u, flux_W_m2, ref_point_m)


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

    Raises
    ------
    ValueError
        If the Sun vector is not a unit (3,) vector or ``half_angle_deg`` lies outside (0, 90).

    Examples
    --------
    Lit from below, only the base is lit: ``F = P pi R^2`` along +z [uN]:

    >>> black = (0.0, 0.0, 0.0)  # rho, beta, sigma
    >>> (cone_srp(1.0, [0.0, 0.0, -1.0], black).force_N * 1e6).round(4).tolist()
    [0.0, 0.0, 14.2622]
    """
    if not 0.0 < half_angle_deg < 90.0:
        raise ValueError(f"cone half_angle_deg must lie in (0, 90), got {half_angle_deg}")
    u = unit_sun(sun_vector)
    height = radius_m / np.tan(np.radians(half_angle_deg))
    pieces = [_frustum_lateral(radius_m, 0.0, 0.0, height, u)]
    if base:
        pieces.append(flat_patch(np.pi * radius_m**2, np.zeros(3), np.array([0.0, 0.0, -1.0]), u))
    return total_load([(piece, optics) for piece in pieces], u, flux_W_m2, ref_point_m)


def _sphere(radius: float, u: Vector) -> LitIntegrals:
    """Lit integrals of a sphere of radius [m] centred at the origin (module Notes)."""
    normal_1 = (2.0 * np.pi / 3.0) * radius**2 * u
    return LitIntegrals(
        projected=np.pi * radius**2,
        normal_1=normal_1,
        normal_2=(np.pi / 2.0) * radius**2 * u,
        position_1=radius * normal_1,
        moment_1=np.zeros(3),
        moment_2=np.zeros(3),
    )


def _frustum_lateral(r_bottom: float, z_bottom: float, r_top: float, z_top: float, u: Vector) -> LitIntegrals:
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
    LitIntegrals
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
    return LitIntegrals(
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
