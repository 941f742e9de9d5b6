"""The direct solar-radiation-pressure law of a lit piece of surface, reduced to six integrals.

The closed forms of :mod:`sunwind.validation.analytic_srp` (convex bodies),
:mod:`sunwind.validation.analytic_shadow` (a plate shadowing another) and
:mod:`sunwind.validation.analytic_v_groove` build on it. Everything is in the body frame and SI; the Sun
vector ``u`` points from the spacecraft toward the Sun (METHOD.md "Frames, units and signs"). The module
imports numpy only and nothing from ``forces``.

Notes
-----
**Surface law.** A lit element (outward normal ``n``, area ``dA``, ``c = n . u > 0``) takes
(METHOD.md "Direct solar pressure": the paper's eq. (4) with its ``s = -u`` and inner normal ``n_paper =
-n``)::

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

``K`` is the projected (shadow) area of the piece.

**Flat piece** (area ``A``, first moment ``m = int r dA``, normal ``n``): with ``c = n . u > 0``,
``K = c A``, ``J1 = c A n``, ``J2 = c^2 A n``, ``R1 = c m``, ``T1 = c m x n``, ``T2 = c^2 m x n``.
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
    "LitIntegrals",
    "Optics",
    "flat_patch",
    "sun_vector_from_alpha",
    "total_load",
    "unit_sun",
]

SPEED_OF_LIGHT_M_S = 299_792_458.0
SOLAR_FLUX_1AU_W_M2 = 1361.0
_UNIT_TOLERANCE = 1e-9

Vector = NDArray[np.float64]


class Optics(NamedTuple):
    """Optical coefficients of one surface (METHOD.md "Surfaces and sides"); a plain 3-tuple also works.

    Attributes
    ----------
    rho : float
        Reflectivity [-], in [0, 1].
    beta : float
        Specular share of the reflected light [-], in [0, 1].
    sigma : float
        Transmissivity [-], in [0, 1], with ``rho + sigma <= 1``.

    Examples
    --------
    >>> Optics(rho=0.6, beta=0.9, sigma=0.0).rho
    0.6
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

    Examples
    --------
    >>> load = ForceTorque(np.zeros(3), np.array([0.0, 0.0, 1e-6]))
    >>> load.torque_Nm.tolist()
    [0.0, 0.0, 1e-06]
    """

    force_N: Vector
    torque_Nm: Vector


@dataclass(frozen=True)
class LitIntegrals:
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

    Examples
    --------
    A 2 m^2 patch facing +z, the Sun 60 deg off its normal, projects half its area:

    >>> patch = flat_patch(2.0, np.zeros(3), np.array([0.0, 0.0, 1.0]), sun_vector_from_alpha(60.0))
    >>> round(patch.projected, 12), patch.normal_2.round(12).tolist()
    (1.0, [0.0, 0.0, 0.5])
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

    Examples
    --------
    >>> sun_vector_from_alpha(90.0).round(12).tolist()
    [1.0, 0.0, 0.0]
    """
    alpha = np.radians(alpha_deg)
    return np.array([np.sin(alpha), 0.0, np.cos(alpha)])


def unit_sun(sun_vector: ArrayLike) -> Vector:
    """Check that the Sun vector is a unit (3,) vector and return it as float64.

    Parameters
    ----------
    sun_vector : (3,) array_like
        Unit vector from the spacecraft toward the Sun, body frame.

    Returns
    -------
    (3,) float64
        The same vector.

    Raises
    ------
    ValueError
        If the vector is not of shape (3,) or its norm differs from 1 by more than 1e-9.

    Examples
    --------
    >>> unit_sun([0, 0, 1]).tolist()
    [0.0, 0.0, 1.0]
    >>> unit_sun([0, 0, 2])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: ...
    """
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


def total_load(
    pieces: list[tuple[LitIntegrals, Optics | tuple[float, float, float]]],
    u: Vector,
    flux_W_m2: float,
    ref_point_m: ArrayLike,
) -> ForceTorque:
    """Sum the loads of surface pieces and move the torque to the reference point.

    Parameters
    ----------
    pieces : list of (LitIntegrals, optics)
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

    Examples
    --------
    A black 2 m^2 plate, the Sun 60 deg off its normal: ``F = -P A cos(alpha) u``:

    >>> u = sun_vector_from_alpha(60.0)
    >>> patch = flat_patch(2.0, np.zeros(3), np.array([0.0, 0.0, 1.0]), u)
    >>> load = total_load([(patch, Optics(0.0, 0.0, 0.0))], u, 1361.0, (0.0, 0.0, 0.0))
    >>> (load.force_N * 1e6).round(4).tolist()
    [-3.9316, 0.0, -2.2699]

    References
    ----------
    .. [1] O. Montenbruck and E. Gill, *Satellite Orbits: Models, Methods and Applications*,
       Springer, 2000, section 3.4 (solar radiation pressure on a flat surface).
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


def _piece_load(lit: LitIntegrals, optics: Optics, u: Vector, pressure: float) -> tuple[Vector, Vector]:
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


def flat_patch(area: float, first_moment: Vector, normal: Vector, u: Vector) -> LitIntegrals:
    """Lit integrals of a flat piece from its area [m^2], ``int r dA`` (3,) [m^3] and unit normal.

    The piece is wholly lit when ``n . u > 0`` and contributes nothing otherwise.

    Parameters
    ----------
    area : float
        Area of the piece [m^2].
    first_moment : (3,) float64
        ``int r dA`` over the piece [m^3], about the body origin.
    normal : (3,) float64
        Unit front normal.
    u : (3,) float64
        Unit Sun vector, body frame.

    Returns
    -------
    LitIntegrals
        The six integrals, with ``c = n . u`` constant over the piece; all zero when it is dark.

    Examples
    --------
    >>> dark = flat_patch(1.0, np.zeros(3), np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]))
    >>> dark.projected
    0.0
    """
    c = max(float(normal @ u), 0.0)
    arm = np.cross(first_moment, normal)
    return LitIntegrals(
        projected=c * area,
        normal_1=c * area * normal,
        normal_2=c * c * area * normal,
        position_1=c * first_moment,
        moment_1=c * arm,
        moment_2=c * c * arm,
    )
