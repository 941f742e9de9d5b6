"""Closed-form solar-radiation pressure on a 90 deg V-groove of mirrors lit across its axis.

The exact reference for inter-reflection: light that enters the groove leaves after one or two
mirror bounces, both known in closed form. The geometry is
:func:`sunwind.validation.concave_meshes.v_groove_mesh`; :mod:`sunwind.validation.concave` checks the
solver and the photon tracer against it. The module imports numpy only and nothing from ``forces``.

Notes
-----
**V-groove of mirrors, lit across its axis.** Two plates of slant width ``w`` and length ``L`` meet
at 90 deg along the y axis (the apex, at the origin) and open toward +z; their inner normals are
``n_l = (1, 0, 1)/sqrt(2)`` (wall at x < 0) and ``n_r = (-1, 0, 1)/sqrt(2)``. The Sun is at
``psi`` from +z in the xz-plane, ``u = (sin psi, 0, cos psi)``, ``|psi| <= 45 deg``; photons travel
along ``s = -u`` and stay in their plane y = const, so the length ``L`` enters only as a factor.
Take ``psi >= 0`` (the other sign is the mirror image x -> -x) and write ``h = w / sqrt(2)``,
``c = cos psi``, ``sn = sin psi``, ``t = tan psi``.

*What enters.* The walls' outer sides face away from the Sun (``(+-1, 0, -1)/sqrt(2) . u <= 0``),
and the groove seen from the Sun spans exactly its aperture, the segment ``z = h``,
``-h <= x <= h``: all the light, power ``P_in = Phi A c`` with ``A = 2 h L = sqrt(2) w L``, enters
there, uniformly in the crossing abscissa ``x0``.

*First wall.* The ray ``(x0 - t' sn, h - t' c)`` meets the right wall (``z = x``) at
``t' = (h - x0)/(c - sn)`` and the left wall (``z = -x``) at ``t' = (h + x0)/(c + sn)``; the right
one is first exactly when ``x0 > h t``.

*Right wall first.* The mirror ``n_r`` maps ``(dx, dz)`` to ``(dz, dx)``, so the ray leaves along
``(-c, -sn)``, downward (``sn >= 0``), and must meet the left wall below the rim: two bounces.

*Left wall first.* It strikes at height ``z1 = (h sn - x0 c)/(c + sn)`` and leaves along
``(-dz, -dx) = (c, sn)``, upward; it meets the right wall at height ``z1 (c + sn)/(c - sn)``, which is
on the wall (``<= h``) when ``x0 >= h (2 t - 1)``: two bounces; else it leaves through the aperture
after one.

So one-bounce light enters on ``-h <= x0 < h (2 t - 1)``, a share ``t = tan psi`` of the aperture,
and leaves along ``e1 = s - 2 (s . n_A) n_A = (cos psi, 0, sin psi)``, the mirror image of ``s`` in
the wall ``A`` that faces the Sun more (the left one for ``psi > 0``). The rest, ``1 - t``, meets both
walls; two reflections in perpendicular mirrors reverse the ray, ``d -> -d``: it leaves along
``-s = u`` (a corner reflector). With reflectivity ``rho`` (specular, ``sigma = 0``) one-bounce light
leaves with ``rho P_in t`` and two-bounce light with ``rho^2 P_in (1 - t)``; momentum in minus momentum
out gives, with ``P = Phi / c_light``,

    F = P A cos(psi) [ (1 + rho^2 (1 - tan psi)) s - rho tan(psi) e1 ].

Limits: ``psi = 0``: everything is retro-reflected, ``F = -(1 + rho^2) P A u`` (``2 P A`` along
``-u`` for perfect mirrors). ``psi = 45 deg``: the left wall is at normal incidence and the right one
grazed; ``e1 = u`` and ``F = -(1 + rho) P A cos(psi) u``, a plain mirror of area ``w L``. ``rho = 0``:
``F = P A cos(psi) s``, an absorber.

*Torque about the apex.* A ray of power ``dW`` gives the impulse rate ``(dW / c_light)(d_in - d_out)``
at each bounce point, and ``r x d`` is the same at every point of a straight line, so its torque is
``(dW / c_light)(m_in - k m_out)`` with ``m = r x d`` of its incoming and outgoing lines and ``k`` the
share of its power that leaves. In the xz-plane ``m_y = z d_x - x d_z``; the incoming line through
``(x0, h)`` has ``m_in = x0 c - h sn``. A mirror through the apex maps a line to its mirror image,
which flips the sign of ``m``: one bounce gives ``m_out = -m_in`` (``k = rho``); two perpendicular
mirrors make a half-turn about the apex, which keeps it: ``m_out = m_in`` (``k = rho^2``). Over the
entry abscissae, ``int_{-h}^{h (2t - 1)} m_in dx0 = -2 h^2 sn`` (one bounce) and
``int_{h (2t - 1)}^{h} m_in dx0 = 0`` (two bounces). With ``dW = Phi c L dx0``,

    M_apex = -(1 + rho) P h^2 L sin(2 psi) e_y = -(1 + rho) P (w^2 / 2) L sin(2 psi) e_y,

and about a point ``r_ref``, ``M = M_apex - r_ref x F``. At ``psi = 45 deg`` with ``rho = 1`` this is
the force ``2 P A cos(psi)`` along ``s`` acting at the centre of the left wall, as it must be.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from sunwind.validation.analytic_srp_law import SOLAR_FLUX_1AU_W_M2, SPEED_OF_LIGHT_M_S, ForceTorque

__all__ = ["v_groove_srp"]


def v_groove_srp(
    width_m: float,
    length_m: float,
    angle_deg: float,
    rho: float = 1.0,
    *,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Exact SRP force and torque on a 90 deg V-groove of specular plates lit across its axis.

    Geometry as :func:`sunwind.validation.concave_meshes.v_groove_mesh` (apex on the y axis at the
    origin, open to +z); the Sun at ``angle_deg`` from +z toward +x, ``u = (sin psi, 0, cos psi)``.
    Derivation in the module Notes.

    Parameters
    ----------
    width_m, length_m : float
        Slant width ``w`` of each plate and groove length ``L`` [m].
    angle_deg : float
        ``psi`` [deg], in [-45, 45]: the light enters through the aperture only.
    rho : float
        Reflectivity of the inner sides [-], all specular (``beta = 1``, ``sigma = 0``).
    flux_W_m2 : float
        Solar flux [W/m^2].
    ref_point_m : (3,) array_like
        Torque reference point [m].

    Returns
    -------
    ForceTorque
        Force [N] and torque [N m] about ``ref_point_m``, body frame.

    Raises
    ------
    ValueError
        If ``angle_deg`` lies outside [-45, 45] (light would strike the outer sides).

    Examples
    --------
    Sun along the groove's bisector, mirrors: each ray strikes both plates and leaves upward [uN]:

    >>> load = v_groove_srp(1.0, 1.0, 0.0)
    >>> ((load.force_N * 1e6).round(4) + 0.0).tolist()  # + 0.0 turns -0.0 into 0.0
    [0.0, 0.0, -12.8405]
    """
    if abs(angle_deg) > 45.0:
        raise ValueError(f"angle_deg = {angle_deg} outside [-45, 45]: light would strike the outer sides")
    psi = math.radians(angle_deg)
    u = np.array([math.sin(psi), 0.0, math.cos(psi)])
    s = -u
    n_a = np.array([math.copysign(1.0, psi), 0.0, 1.0]) / math.sqrt(2)  # inner normal of the wall facing u
    e1 = s - 2.0 * (s @ n_a) * n_a
    t = math.tan(abs(psi))
    pressure = flux_W_m2 / SPEED_OF_LIGHT_M_S
    aperture = math.sqrt(2) * width_m * length_m
    force = pressure * aperture * math.cos(psi) * ((1.0 + rho**2 * (1.0 - t)) * s - rho * t * e1)
    torque_apex = np.array(
        [0.0, -(1.0 + rho) * pressure * width_m**2 / 2 * length_m * math.sin(2 * psi), 0.0]
    )
    return ForceTorque(force, torque_apex - np.cross(np.asarray(ref_point_m, dtype=np.float64), force))
