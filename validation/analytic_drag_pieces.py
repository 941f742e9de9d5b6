"""The load integrals of convex surface pieces in free-molecular flow: flat pieces, spheres, frustums.

Each piece of a body is reduced to four integrals of the local law of
:mod:`sunwind.validation.analytic_gas_law`, from which :mod:`sunwind.validation.analytic_drag` sums the
force and the torque. The module imports numpy and scipy only, nothing from ``forces``.

Notes
-----
**Body integrals.** With ``f = -g n - tau u`` the load of a piece of surface follows from four
integrals: ``T0 = int tau dA``, ``G = int g n dA``, ``Tr = int tau r dA``, ``Gm = int g (r x n) dA``::

    F / q = -(T0 u + G),        M_0 / q = -(Tr x u + Gm),        M_ref = M_0 - r_ref x F.

*Flat piece* (area ``A``, first moment ``m = int r dA``): ``T0 = tau A``, ``G = g A n``,
``Tr = tau m``, ``Gm = g m x n``.

*Sphere* (radius ``R``): with ``dA = 2 pi R^2 d gamma`` about ``u``, ``T0 = 2 pi R^2 int tau``,
``G = 2 pi R^2 u int g gamma``, ``Tr = 2 pi R^3 u int tau gamma`` (``= (4/3) pi R^3 a_t u``, for both
streams), ``Gm = 0`` (integrals over ``gamma`` in [-1, 1]).
Over ``s`` in ``[-S, S]`` (``E = erf S``, ``e = exp(-S^2)``)::

    int chi ds     = sqrt(pi) (S^2 + 1/2) E + S e
    int s chi ds   = (2/3) sqrt(pi) S^3
    int s^2 chi ds = sqrt(pi) (S^4/2 + 1/8) E + (S^3/2 - S/4) e
    int s psi ds   = (S^4/2 + S^2/2 - 1/8) E + (S^3 + S/2) e / (2 sqrt(pi))

so that ``C_D = ((a_n + a_t)/2) [(2S^2 + 1) e / (sqrt(pi) S^3) + (4S^4 + 4S^2 - 1) E / (2 S^4)]
+ 2 sqrt(pi) K / (3 S)`` on ``A_ref = pi R^2``: the classical result (diffuse and specular spheres
have the same incident part), tending to ``a_n + a_t`` (= 2) plus the re-emission term as
``S -> inf``.

*Lateral surface of a frustum* (cylinder, cone): the generator from ``(r_b, z_b)`` to
``(r_t, z_t)``, slant ``l``, outward normal ``n = cos d e_r + sin d e_z``; azimuth ``phi`` from ``e1``,
the unit projection of ``u`` on the xy-plane (``e2 = e_z x e1``, ``b = |u_xy|``), so ``gamma =
A + B cos phi``, ``A = sin d u_z``, ``B = cos d b``, independent of the position along the generator.
With the generator integrals ``g0 = int rho l dt``, ``gr = int rho^2 l dt``, ``gz = int z rho l dt``,
``gt = cos d gz - sin d gr`` and the azimuth integrals ``Q_tau0 = int tau``, ``Q_tau1 = int tau cos``,
``Q_g0 = int g``, ``Q_g1 = int g cos`` (over ``phi`` in [0, 2 pi]; the ``sin phi`` parts vanish)::

    T0 = g0 Q_tau0,   G = g0 (cos d Q_g1 e1 + sin d Q_g0 e_z),
    Tr = gr Q_tau1 e1 + gz Q_tau0 e_z,   Gm = gt Q_g1 e2.

For the **cylinder** (``A = 0``, ``B = b``, ``p = S b``, ``z = p^2 / 2``, ``I_k = exp(-z) I_k(z)``,
the scaled modified Bessel functions) the azimuth integrals are closed (Sentman's Bessel forms,
rederived with ``int exp(-w cos 2 phi) cos 2m phi = 2 pi (-1)^m I_m(w)`` and, by parts in ``phi``,
``F1 = int cos phi erf(p cos phi) = 2 sqrt(pi) p (I_0 + I_1)``, ``F3 = int cos^3 phi erf(p cos phi)
= sqrt(pi) [(4/3) p (I_0 + I_1) + (2/3) I_1 / p]``)::

    int chi       = 2 pi [I_0 + p^2 (I_0 + I_1)]        int chi cos = pi p sqrt(pi)
    S^2 Q_g0 = pi (a_n - a_t) p^2 + pi a_n + pi K [I_0 + p^2 (I_0 + I_1)]
    S^2 Q_g1 = (a_n - a_t) [sqrt(pi) p (I_0 - I_1) + p^2 F3] + (a_n / 2) F1 + (K / 2) pi^(3/2) p

For the **cone** the azimuth integrals of the full stream have no closed form at incidence
(``A != 0``); they are computed by adaptive quadrature (``scipy.integrate.quad``
over ``phi`` in [0, pi], doubled, ``epsrel = 1e-12``, ``epsabs = 1e-13`` times the integrand's scale,
a break point where ``gamma = 0``). ``closed=False`` (``lateral="quad"`` of
:func:`sunwind.validation.analytic_drag.cylinder_drag`) takes the same route for the cylinder (a
cross-check of the Bessel forms). For the directed stream every frustum is closed: with the windward arc
``|phi| < phi0`` (``cos phi0 = clip(-A/B, -1, 1)``) and ``C_k = int cos^k`` over it, ``Q_tau0 =
2 a_t G0``, ``Q_tau1 = 2 a_t G1``, ``Q_g0 = 2 (a_n - a_t) G2 + kappa G0``, ``Q_g1 = 2 (a_n - a_t) G3 +
kappa G1`` with ``kappa = K sqrt(pi) / S``, ``G0 = A C0 + B C1``, ``G1 = A C1 + B C2``, ``G2 = A^2 C0 +
2AB C1 + B^2 C2``, ``G3 = A^2 C1 + 2AB C2 + B^2 C3``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import quad
from scipy.special import i0e, i1e

from sunwind.validation.analytic_gas_law import SurfaceLaw

__all__ = ["Piece", "flat_piece", "frustum_piece", "sphere_piece"]

_SQRT_PI = math.sqrt(math.pi)
_QUAD_EPSREL = 1e-12
_QUAD_EPSABS = 1e-13  # times pi max|integrand|

Vector = NDArray[np.float64]


class Piece(NamedTuple):
    """The four integrals of one surface piece about the body origin (module Notes), over q.

    Attributes
    ----------
    shear : float
        ``T0 = int tau dA`` [m^2].
    normal : (3,) float64
        ``G = int g n dA`` [m^2].
    shear_moment : (3,) float64
        ``Tr = int tau r dA`` [m^3].
    normal_moment : (3,) float64
        ``Gm = int g (r x n) dA`` [m^3].

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.validation.analytic_gas_law import GasLaw, surface_law
    >>> beam = surface_law(GasLaw("specular"), 7.0, 900.0, stream="directed")
    >>> u = np.array([0.0, 0.0, 1.0])
    >>> piece = flat_piece(1.0, np.zeros(3), u, u, beam)
    >>> piece.shear, piece.normal.tolist()
    (0.0, [0.0, 0.0, 4.0])
    """

    shear: float  # T0 = int tau dA [m^2]
    normal: Vector  # G = int g n dA [m^2]
    shear_moment: Vector  # Tr = int tau r dA [m^3]
    normal_moment: Vector  # Gm = int g (r x n) dA [m^3]


def flat_piece(area: float, first_moment: Vector, normal: Vector, u: Vector, law: SurfaceLaw) -> Piece:
    """Compute the integrals of a flat piece of ``area`` [m^2], ``int r dA`` [m^3] and unit ``normal``.

    Parameters
    ----------
    area : float
        Area of the piece [m^2].
    first_moment : (3,) float64
        ``int r dA`` over the piece [m^3], about the body origin.
    normal : (3,) float64
        Unit outward normal.
    u : (3,) float64
        Unit flow vector, body frame.
    law : SurfaceLaw
        The local law of the surface in the stream.

    Returns
    -------
    Piece
        The integrals ``T0``, ``G``, ``Tr``, ``Gm`` of the piece, over q.

    Examples
    --------
    A unit square facing the specular beam: ``G = 4 n`` (twice the stopped momentum), no shear.

    >>> import numpy as np
    >>> from sunwind.validation.analytic_gas_law import GasLaw, surface_law
    >>> beam = surface_law(GasLaw("specular"), 7.0, 900.0, stream="directed")
    >>> u = np.array([0.0, 0.0, 1.0])
    >>> flat_piece(1.0, np.zeros(3), u, u, beam).normal.tolist()
    [0.0, 0.0, 4.0]
    """
    gamma = float(normal @ u)
    tau, g = float(law.shear_over_t(gamma)), float(law.normal_load(gamma))
    return Piece(tau * area, g * area * normal, tau * first_moment, g * np.cross(first_moment, normal))


def sphere_piece(radius: float, u: Vector, law: SurfaceLaw) -> Piece:
    """Compute the integrals of a sphere centred at the origin (module Notes, "Sphere").

    Parameters
    ----------
    radius : float
        Radius [m].
    u : (3,) float64
        Unit flow vector, body frame.
    law : SurfaceLaw
        The local law of the surface in the stream.

    Returns
    -------
    Piece
        The integrals ``T0``, ``G``, ``Tr``, ``Gm`` of the piece, over q.

    Examples
    --------
    The specular sphere in the beam: ``|G| = 2 pi R^2``, so ``C_D = 2``.

    >>> import numpy as np
    >>> from sunwind.validation.analytic_gas_law import GasLaw, surface_law
    >>> beam = surface_law(GasLaw("specular"), 7.0, 900.0, stream="directed")
    >>> u = np.array([0.0, 0.0, 1.0])
    >>> round(float(sphere_piece(1.0, u, beam).normal[2] / np.pi), 12)
    2.0
    """
    if law.stream == "thermal":
        return _difference(
            sphere_piece(radius, u, _with(law, "full")), sphere_piece(radius, u, _with(law, "directed"))
        )
    a_n, a_t, k, s = law.a_n, law.a_t, law.k, law.speed_ratio
    if law.stream == "directed":  # integrals over gamma in [0, 1]
        int_tau = a_t
        int_g_gamma = 0.5 * (a_n - a_t) + k * _SQRT_PI / (3.0 * s)
    else:
        e, big_e = math.exp(-s * s), math.erf(s)
        chi_0 = _SQRT_PI * (s * s + 0.5) * big_e + s * e
        chi_1 = (2.0 / 3.0) * _SQRT_PI * s**3
        chi_2 = _SQRT_PI * (s**4 / 2 + 0.125) * big_e + (s**3 / 2 - s / 4) * e
        psi_1 = (s**4 / 2 + s * s / 2 - 0.125) * big_e + (s**3 + s / 2) * e / (2 * _SQRT_PI)
        int_tau = a_t * chi_0 / (_SQRT_PI * s * s)
        int_g_gamma = (a_n * psi_1 + 0.5 * k * chi_1 - a_t * chi_2 / _SQRT_PI) / s**4
    int_tau_gamma = 2.0 * a_t / 3.0  # the same for both streams
    area = 2.0 * math.pi * radius**2
    return Piece(area * int_tau, area * int_g_gamma * u, radius * area * int_tau_gamma * u, np.zeros(3))


def frustum_piece(
    r_bottom: float, z_bottom: float, r_top: float, z_top: float, u: Vector, law: SurfaceLaw, closed: bool
) -> Piece:
    """Compute the integrals of the outer lateral surface of a frustum of revolution about z (module Notes).

    ``closed`` selects the Bessel forms (cylinder only, ``r_bottom = r_top``) for the full stream;
    otherwise the full stream's azimuth integrals are adaptive quadratures.

    Parameters
    ----------
    r_bottom, z_bottom : float
        Radius and height of the lower rim [m].
    r_top, z_top : float
        Radius and height of the upper rim [m]; 0 radius for a cone's apex.
    u : (3,) float64
        Unit flow vector, body frame.
    law : SurfaceLaw
        The local law of the surface in the stream.
    closed : bool
        Use the closed (Bessel) forms of a cylinder's azimuth integrals.

    Returns
    -------
    Piece
        The integrals ``T0``, ``G``, ``Tr``, ``Gm`` of the piece, over q.

    Examples
    --------
    A cylinder's side seen along its axis takes nothing from the beam:

    >>> import numpy as np
    >>> from sunwind.validation.analytic_gas_law import GasLaw, surface_law
    >>> beam = surface_law(GasLaw("specular"), 7.0, 900.0, stream="directed")
    >>> u = np.array([0.0, 0.0, 1.0])
    >>> frustum_piece(1.0, -0.5, 1.0, 0.5, u, beam, closed=True).normal.tolist()
    [0.0, 0.0, 0.0]
    """
    d_r, d_z = r_top - r_bottom, z_top - z_bottom
    slant = math.hypot(d_r, d_z)
    cos_d, sin_d = d_z / slant, -d_r / slant
    b = math.hypot(u[0], u[1])
    e1 = np.array([u[0] / b, u[1] / b, 0.0]) if b > 0.0 else np.array([1.0, 0.0, 0.0])
    e2 = np.array([-e1[1], e1[0], 0.0])
    e_z = np.array([0.0, 0.0, 1.0])
    big_a, big_b = sin_d * u[2], cos_d * b
    if law.stream == "directed":
        q_tau0, q_tau1, q_g0, q_g1 = _azimuth_directed(big_a, big_b, law)
    elif law.stream == "thermal":
        full = _with(law, "full")
        q_full = _azimuth_cylinder(b, full) if closed else _azimuth_quad(big_a, big_b, full)
        q_dir = _azimuth_directed(big_a, big_b, _with(law, "directed"))
        q_tau0, q_tau1, q_g0, q_g1 = (x - y for x, y in zip(q_full, q_dir, strict=True))
    else:
        q_tau0, q_tau1, q_g0, q_g1 = _azimuth_cylinder(b, law) if closed else _azimuth_quad(big_a, big_b, law)
    g0 = slant * (r_bottom + r_top) / 2.0
    gr = slant * (r_bottom**2 + r_bottom * r_top + r_top**2) / 3.0
    gz = slant * (z_bottom * r_bottom + (z_bottom * d_r + r_bottom * d_z) / 2.0 + d_z * d_r / 3.0)
    gt = cos_d * gz - sin_d * gr
    return Piece(
        g0 * q_tau0,
        g0 * (cos_d * q_g1 * e1 + sin_d * q_g0 * e_z),
        gr * q_tau1 * e1 + gz * q_tau0 * e_z,
        gt * q_g1 * e2,
    )


def _azimuth_cylinder(b: float, law: SurfaceLaw) -> tuple[float, float, float, float]:
    """``(Q_tau0, Q_tau1, Q_g0, Q_g1)`` of the full stream on a cylinder, ``gamma = b cos(phi)``."""
    a_n, a_t, k, s = law.a_n, law.a_t, law.k, law.speed_ratio
    p = s * b
    z = 0.5 * p * p
    i0, i1 = float(i0e(z)), float(i1e(z))
    chi_0 = 2.0 * math.pi * (i0 + p * p * (i0 + i1))  # int chi
    chi_1 = math.pi * _SQRT_PI * p  # int chi cos
    f1 = 2.0 * _SQRT_PI * p * (i0 + i1)
    f3 = _SQRT_PI * ((4.0 / 3.0) * p * (i0 + i1) + ((2.0 / 3.0) * i1 / p if p > 0.0 else 0.0))
    q_tau0 = a_t * chi_0 / (s * _SQRT_PI)
    q_tau1 = a_t * chi_1 / (s * _SQRT_PI)
    q_g0 = (math.pi * (a_n - a_t) * p * p + math.pi * a_n + 0.5 * k * chi_0) / s**2
    q_g1 = ((a_n - a_t) * (_SQRT_PI * p * (i0 - i1) + p * p * f3) + 0.5 * a_n * f1 + 0.5 * k * chi_1) / s**2
    return q_tau0, q_tau1, q_g0, q_g1


def _azimuth_directed(big_a: float, big_b: float, law: SurfaceLaw) -> tuple[float, float, float, float]:
    """``(Q_tau0, Q_tau1, Q_g0, Q_g1)`` of the directed stream, ``gamma = A + B cos(phi)``, in closed form."""
    if big_b > 0.0:
        phi0 = math.acos(min(1.0, max(-1.0, -big_a / big_b)))
    else:
        phi0 = math.pi if big_a > 0.0 else 0.0
    sin0, cos0 = math.sin(phi0), math.cos(phi0)
    c0, c1, c2 = 2.0 * phi0, 2.0 * sin0, phi0 + sin0 * cos0
    c3 = 2.0 * sin0 - (2.0 / 3.0) * sin0**3
    g0 = big_a * c0 + big_b * c1
    g1 = big_a * c1 + big_b * c2
    g2 = big_a**2 * c0 + 2.0 * big_a * big_b * c1 + big_b**2 * c2
    g3 = big_a**2 * c1 + 2.0 * big_a * big_b * c2 + big_b**2 * c3
    kappa = law.k * _SQRT_PI / law.speed_ratio
    quadratic = 2.0 * (law.a_n - law.a_t)
    return 2.0 * law.a_t * g0, 2.0 * law.a_t * g1, quadratic * g2 + kappa * g0, quadratic * g3 + kappa * g1


def _azimuth_quad(big_a: float, big_b: float, law: SurfaceLaw) -> tuple[float, float, float, float]:
    """``(Q_tau0, Q_tau1, Q_g0, Q_g1)`` by adaptive quadrature over ``phi`` in [0, pi], doubled.

    Tolerances: ``epsrel = 1e-12`` and ``epsabs = 1e-13 pi max|f|`` (``f`` at ``gamma = A, A +- B``), so
    integrals that nearly cancel are resolved to the integrand's rounding level. With the flow along the
    axis (``B < 1e-12``) ``gamma = A`` everywhere and the cosine-weighted integrals, ``O(B)``, are 0.
    """
    results = []
    for function in (law.shear_over_t, law.normal_load):
        if big_b < 1e-12:
            results += [2.0 * math.pi * float(function(big_a)), 0.0]
            continue
        scale = math.pi * float(np.max(np.abs(function(np.array([big_a - big_b, big_a, big_a + big_b])))))
        points = [math.acos(-big_a / big_b)] if abs(big_a) < big_b else None
        for weight in (lambda phi: 1.0, math.cos):
            value, _ = quad(
                lambda phi, f=function, w=weight: w(phi) * float(f(big_a + big_b * math.cos(phi))),
                0.0,
                math.pi,
                points=points,
                epsabs=_QUAD_EPSABS * scale + 1e-300,
                epsrel=_QUAD_EPSREL,
                limit=200,
            )
            results.append(2.0 * value)
    return tuple(results)


def _with(law: SurfaceLaw, stream: str) -> SurfaceLaw:
    return SurfaceLaw(law.speed_ratio, law.a_n, law.a_t, law.k, stream)


def _difference(a: Piece, b: Piece) -> Piece:
    return Piece(*(x - y for x, y in zip(a, b, strict=True)))
