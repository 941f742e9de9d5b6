"""Closed-form free-molecular force and torque on convex bodies: flat plate, sphere, cylinder, cone.

These are independent references for the free-molecular solver: the surface law is derived here
again (Sentman 1961; Schaaf & Chambre 1958) and the module imports numpy and scipy only, nothing
from ``forces``. Everything is in the body frame and SI, one gas species, and the bodies are
convex, so every element sees only the free stream (no shadowing, no molecular inter-reflection).

Notes
-----
**Flow and frames** (METHOD.md "Frames"). ``u = v_rel / |v_rel|`` is the unit flow vector (the
spacecraft's velocity relative to the atmosphere, body frame); molecules travel along ``-u``. The
bodies are placed as in :mod:`sunwind.meshes.primitives`: the plate centred at the origin in ``z = 0``
with front normal +z; the sphere centred at the origin; the cylinder on the z axis from
``z = -L/2`` to ``L/2``; the cone with its base disc in ``z = 0`` (normal -z) and apex at
``(0, 0, R / tan(half_angle))``. :func:`flow_vector_from_alpha` puts ``u`` at ``alpha`` from +z in
the xz-plane.

**Local law.** An element with outward normal ``n`` and ``gamma = n . u`` takes, per unit area
and over the dynamic pressure ``q = rho V^2 / 2``, ``f = -c_n n + c_t t_hat`` with
``t_hat = -(u - gamma n) / t``, ``t = sqrt(1 - gamma^2)``. With ``S`` the speed ratio, ``s = S gamma``,
``chi(s) = exp(-s^2) + sqrt(pi) s (1 + erf s)`` and ``psi(s) = (s / sqrt(pi)) exp(-s^2) +
(1/2 + s^2)(1 + erf s)``, the incident drifting Maxwellian gives ``c_n_inc = psi / S^2`` and
``c_t_inc = t chi / (S sqrt(pi))``; a Lambertian re-emission of the incident molecules at ``T_r``
adds ``chi sqrt(T_r / T) / (2 S^2)`` to ``c_n``. Every model here is then::

    c_n = a_n psi / S^2 + K chi / (2 S^2),       c_t = a_t t chi / (S sqrt(pi))

with ``(a_n, a_t, K)``: ``(1, 1, sqrt(T_r/T))`` for ``"sentman"`` (``T_r/T = alpha_E tau_w +
(1 - alpha_E)(2/3) S^2``) and ``"dria"`` (``... + (1 - alpha_E) S^2 / 2``), ``(2 - sigma_n, sigma_t,
sigma_n sqrt(tau_w))`` for ``"schaaf-chambre"``, ``(2, 0, 0)`` for ``"specular"``
(``tau_w = T_w / T``). Writing ``t_hat`` out, the force per area is ``f = -g(gamma) n - tau(gamma) u``
with ``tau = c_t / t = a_t chi / (S sqrt(pi))`` and ``g = c_n - gamma tau``, i.e.::

    S^2 g = (a_n - a_t)(s exp(-s^2) / sqrt(pi) + s^2 (1 + erf s)) + (a_n / 2)(1 + erf s)
            + (K / 2) chi(s).

``chi(s) - chi(-s) = 2 sqrt(pi) s``, so the odd part of ``chi`` is linear in ``gamma``.

**Streams.** ``"directed"`` is the cold beam of the same density along ``-u`` reflected by the
same kernel and ``T_r``: for ``gamma > 0`` ``g = 2 (a_n - a_t) gamma^2 + (K sqrt(pi) / S) gamma``,
``tau = 2 a_t gamma``, and zero on lee faces (it is the hyperthermal law). ``"thermal"`` is
``full - directed``.

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
a break point where ``gamma = 0``). ``lateral="quad"`` uses the same route for the cylinder (a
cross-check of the Bessel forms). For the directed stream every frustum is closed: with the windward arc
``|phi| < phi0`` (``cos phi0 = clip(-A/B, -1, 1)``) and ``C_k = int cos^k`` over it, ``Q_tau0 =
2 a_t G0``, ``Q_tau1 = 2 a_t G1``, ``Q_g0 = 2 (a_n - a_t) G2 + kappa G0``, ``Q_g1 = 2 (a_n - a_t) G3 +
kappa G1`` with ``kappa = K sqrt(pi) / S``, ``G0 = A C0 + B C1``, ``G1 = A C1 + B C2``, ``G2 = A^2 C0 +
2AB C1 + B^2 C2``, ``G3 = A^2 C1 + 2AB C2 + B^2 C3``.

**Cylinder torque and lift** (METHOD.md "Traps"). Take ``u = sin(alpha) e1 + cos(alpha) e_z``.
About its centre, the lateral surface's pressures have no moment (``r x n = z e_z x n`` integrates
to zero over ``z``), but its shear acts at ``R n``: ``M_0 / q = -R^2 L (int tau cos) e1 x u
= a_t pi R^2 L sin(alpha) cos(alpha) e2``, exact at every ``S`` because ``tau(gamma) - tau(-gamma) =
2 a_t gamma``. The caps' shear acts at ``+-L/2 e_z`` and gives ``-a_t pi R^2 L sin(alpha) cos(alpha)
e2``: the closed cylinder has no torque about its centre. Its lift is ``-q G . e_L`` with
``e_L = cos(alpha) e1 - sin(alpha) e_z``, and ``G . e_L = R L cos(alpha) int g cos - pi R^2 sin(alpha)
(g(cos alpha) - g(-cos alpha))`` depends only on the odd part of ``g`` (the even part cancels on a
body symmetric about its centre). If that odd part is linear, ``c gamma``, then ``G . e_L =
c pi R sin(alpha) cos(alpha) (L/2 - R)`` and ``C_L = -c sin(alpha) cos(alpha) (L / (2R) - 1)``
(``A_ref = pi R^2``): zero exactly when ``L = 2R``. That is the case of the directed (hyperthermal)
stream of any model with ``a_n = a_t`` (fully diffuse: sentman, dria at any ``alpha_E`` and ``T_w``;
schaaf-chambre with ``sigma_n = sigma_t = 1``), where ``g = kappa gamma`` on windward faces — the
Lambertian law of light, ``c = kappa``. At finite ``S`` the full stream adds the odd part
``erf(S gamma) / (2 S^2)`` of the incident pressure, which is not linear, so an
``L = D`` diffuse cylinder has a lift of order ``1/S^2`` (``S^2 C_L -> -(4 cos(alpha) - pi
sin(alpha)) / pi``); a specular one (``a_n != a_t``) has a lift of order 1.

**Coefficients.** ``C = F . e / (q A_ref)`` with the drag direction ``e_D = -u``, the lift direction
``e_L`` perpendicular to ``u`` in the plane of ``u`` and the body axis ``a = +z`` (plate normal,
cylinder and cone axis), pointing away from ``a``: ``e_L = -(a - (a.u) u) / |a - (a.u) u|``
(``e_L . a < 0``; a plate whose front faces the flow has positive lift), and the side direction
``e_S = e_L x e_D``, so ``(e_D, e_S, e_L)`` is right-handed. When ``u`` is along the axis the body
+x axis stands in for ``a`` (lift is then zero by symmetry). Default ``A_ref``: the plate's area
(one face), ``pi R^2`` for the sphere, the cylinder (its cross-section) and the cone (its base).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import quad
from scipy.special import erfc, i0e, i1e

__all__ = [
    "DRAG_MODELS",
    "FmfLoad",
    "GasLaw",
    "SurfaceLaw",
    "cone_drag",
    "cylinder_drag",
    "flow_vector_from_alpha",
    "plate_drag",
    "sphere_drag",
    "surface_law",
]

#: Models with closed forms here (CLL has none; see sunwind.forces.gas.laws for it).
DRAG_MODELS = ("sentman", "dria", "schaaf-chambre", "specular")
STREAMS = ("full", "directed", "thermal")
_SQRT_PI = math.sqrt(math.pi)
_UNIT_TOLERANCE = 1e-9
_QUAD_EPSREL = 1e-12
_QUAD_EPSABS = 1e-13  # times pi max|integrand|

Vector = NDArray[np.float64]


@dataclass(frozen=True)
class GasLaw:
    """Gas-surface interaction parameters of a body's surface (one material everywhere).

    Attributes
    ----------
    model : str
        One of ``DRAG_MODELS``.
    energy_accommodation : float
        ``alpha_E`` [-] (sentman, dria).
    normal_accommodation, tangential_accommodation : float
        ``sigma_n``, ``sigma_t`` [-] (schaaf-chambre).
    wall_temperature_K : float
        ``T_w`` [K].
    """

    model: str
    energy_accommodation: float = 1.0
    normal_accommodation: float = 1.0
    tangential_accommodation: float = 1.0
    wall_temperature_K: float = 300.0


@dataclass(frozen=True)
class SurfaceLaw:
    """The local law ``f = -c_n n + c_t t_hat = -g n - tau u`` (over q) of one model and species.

    Attributes
    ----------
    speed_ratio : float
        ``S`` [-].
    a_n, a_t : float
        Weights of the incident pressure and shear (module Notes).
    k : float
        ``K = share * sqrt(T_r / T)`` of the Lambertian re-emission [-].
    stream : str
        ``"full"``, ``"directed"`` or ``"thermal"``.
    """

    speed_ratio: float
    a_n: float
    a_t: float
    k: float
    stream: str = "full"

    def shear_over_t(self, gamma: ArrayLike) -> NDArray[np.float64]:
        """``tau = c_t / t`` [-] at incidence cosines ``gamma``."""
        gamma = np.asarray(gamma, dtype=np.float64)
        if self.stream == "directed":
            return 2.0 * self.a_t * np.maximum(gamma, 0.0)
        full = self.a_t * _chi(self.speed_ratio * gamma) / (self.speed_ratio * _SQRT_PI)
        if self.stream == "thermal":
            return full - 2.0 * self.a_t * np.maximum(gamma, 0.0)
        return full

    def normal_load(self, gamma: ArrayLike) -> NDArray[np.float64]:
        """``g = c_n - gamma tau`` [-], the coefficient of ``-n`` in ``f = -g n - tau u``."""
        gamma = np.asarray(gamma, dtype=np.float64)
        windward = np.maximum(gamma, 0.0)
        directed = 2.0 * (self.a_n - self.a_t) * windward**2 + self.k * _SQRT_PI / self.speed_ratio * windward
        if self.stream == "directed":
            return directed
        s = self.speed_ratio * gamma
        gauss, one_plus_erf = np.exp(-s * s), erfc(-s)
        full = (
            (self.a_n - self.a_t) * (s * gauss / _SQRT_PI + s * s * one_plus_erf)
            + 0.5 * self.a_n * one_plus_erf
            + 0.5 * self.k * _chi(s)
        ) / self.speed_ratio**2
        return full - directed if self.stream == "thermal" else full

    def coefficients(self, gamma: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(c_n, c_t)`` [-] at incidence cosines ``gamma``."""
        gamma = np.asarray(gamma, dtype=np.float64)
        tau = self.shear_over_t(gamma)
        return self.normal_load(gamma) + gamma * tau, np.sqrt(np.maximum(1.0 - gamma**2, 0.0)) * tau


@dataclass(frozen=True)
class FmfLoad:
    """Free-molecular force and torque on a body, with its coefficients; body frame, SI.

    Attributes
    ----------
    force_N : (3,) float64
        Force [N].
    torque_Nm : (3,) float64
        Torque [N m] about ``reference_point_m``.
    reference_point_m : (3,) float64
        Torque reference point [m].
    dynamic_pressure_Pa : float
        ``q = rho V^2 / 2`` [Pa].
    reference_area_m2 : float
        ``A_ref`` [m^2] of the coefficients.
    drag_direction, lift_direction, side_direction : (3,) float64
        Unit vectors ``e_D = -u``, ``e_L``, ``e_S`` (module Notes, "Coefficients").
    """

    force_N: Vector
    torque_Nm: Vector
    reference_point_m: Vector
    dynamic_pressure_Pa: float
    reference_area_m2: float
    drag_direction: Vector
    lift_direction: Vector
    side_direction: Vector

    def _coefficient(self, direction: Vector) -> float:
        return float(self.force_N @ direction) / (self.dynamic_pressure_Pa * self.reference_area_m2)

    @property
    def drag_coefficient(self) -> float:
        """``C_D = F . (-u) / (q A_ref)`` [-]."""
        return self._coefficient(self.drag_direction)

    @property
    def lift_coefficient(self) -> float:
        """``C_L = F . e_L / (q A_ref)`` [-]."""
        return self._coefficient(self.lift_direction)

    @property
    def side_coefficient(self) -> float:
        """``C_S = F . e_S / (q A_ref)`` [-]."""
        return self._coefficient(self.side_direction)


class _Piece(NamedTuple):
    """The four integrals of one surface piece about the body origin (module Notes), over q."""

    shear: float  # T0 = int tau dA [m^2]
    normal: Vector  # G = int g n dA [m^2]
    shear_moment: Vector  # Tr = int tau r dA [m^3]
    normal_moment: Vector  # Gm = int g (r x n) dA [m^3]


def flow_vector_from_alpha(alpha_deg: float) -> Vector:
    """Flow vector at ``alpha`` from the body axis +z, in the xz-plane.

    Parameters
    ----------
    alpha_deg : float
        Angle between +z and ``u`` [deg]; 0 puts the flow on +z (molecules arrive from +z).

    Returns
    -------
    (3,) float64
        ``u = (sin(alpha), 0, cos(alpha))``.
    """
    alpha = math.radians(alpha_deg)
    return np.array([math.sin(alpha), 0.0, math.cos(alpha)])


def surface_law(
    surface: GasLaw, speed_ratio: float, temperature_K: float, stream: str = "full"
) -> SurfaceLaw:
    """The local law of ``surface`` for a species of speed ratio ``S`` in gas at ``T`` [K].

    Raises
    ------
    ValueError
        Unknown model or stream, or a parameter out of range.
    """
    if surface.model not in DRAG_MODELS:
        raise ValueError(f"model must be one of {DRAG_MODELS}, got {surface.model!r}")
    if stream not in STREAMS:
        raise ValueError(f"stream must be one of {STREAMS}, got {stream!r}")
    if not (
        math.isfinite(speed_ratio) and speed_ratio > 0 and math.isfinite(temperature_K) and temperature_K > 0
    ):
        raise ValueError(
            f"speed ratio and temperature must be finite and > 0, got {speed_ratio}, {temperature_K}"
        )
    for name in ("energy_accommodation", "normal_accommodation", "tangential_accommodation"):
        if not 0.0 <= getattr(surface, name) <= 1.0:
            raise ValueError(f"{name} must lie in [0, 1], got {getattr(surface, name)}")
    if not surface.wall_temperature_K >= 0.0:
        raise ValueError(f"wall temperature must be >= 0 K, got {surface.wall_temperature_K}")
    tau_w = surface.wall_temperature_K / temperature_K
    alpha_e = surface.energy_accommodation
    if surface.model == "sentman":
        a_n, a_t, k = 1.0, 1.0, math.sqrt(alpha_e * tau_w + (1 - alpha_e) * (2 / 3) * speed_ratio**2)
    elif surface.model == "dria":
        a_n, a_t, k = 1.0, 1.0, math.sqrt(alpha_e * tau_w + (1 - alpha_e) * 0.5 * speed_ratio**2)
    elif surface.model == "schaaf-chambre":
        sigma_n = surface.normal_accommodation
        a_n, a_t, k = 2.0 - sigma_n, surface.tangential_accommodation, sigma_n * math.sqrt(tau_w)
    else:
        a_n, a_t, k = 2.0, 0.0, 0.0
    return SurfaceLaw(float(speed_ratio), a_n, a_t, k, stream)


# ------------------------------------------------------------------------------------------- bodies


def plate_drag(
    size_x_m: float,
    size_y_m: float,
    flow_direction: ArrayLike,
    surface: GasLaw,
    speed_ratio: float,
    temperature_K: float,
    *,
    one_sided: bool = True,
    dynamic_pressure_Pa: float = 1.0,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
    stream: str = "full",
) -> FmfLoad:
    """Free-molecular load on a flat rectangular plate centred at the origin in z = 0, front normal +z.

    Parameters
    ----------
    size_x_m, size_y_m : float
        Side lengths along x and y [m].
    flow_direction : (3,) array_like
        Unit flow vector ``u = v_rel / |v_rel|``, body frame.
    surface : GasLaw
        Gas-surface interaction of both faces.
    speed_ratio : float
        ``S`` of the species [-].
    temperature_K : float
        Free-stream temperature [K].
    one_sided : bool, optional
        If True (default) only the front face (normal +z) interacts; else both faces, the lee face
        included (struck by the thermal stream).
    dynamic_pressure_Pa : float, optional
        ``q`` [Pa], default 1 (the force is then ``C A_ref``-like in N).
    ref_point_m : (3,) array_like, optional
        Torque reference [m], default the origin.
    reference_area_m2 : float, optional
        ``A_ref`` [m^2], default the plate area (one face).
    stream : {"full", "directed", "thermal"}

    Returns
    -------
    FmfLoad
    """
    u = _unit_flow(flow_direction)
    law = surface_law(surface, speed_ratio, temperature_K, stream)
    area = size_x_m * size_y_m
    normals = [np.array([0.0, 0.0, 1.0])] + ([] if one_sided else [np.array([0.0, 0.0, -1.0])])
    pieces = [_flat(area, np.zeros(3), n, u, law) for n in normals]
    return _load(pieces, u, dynamic_pressure_Pa, ref_point_m, reference_area_m2 or area)


def sphere_drag(
    radius_m: float,
    flow_direction: ArrayLike,
    surface: GasLaw,
    speed_ratio: float,
    temperature_K: float,
    *,
    dynamic_pressure_Pa: float = 1.0,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
    stream: str = "full",
) -> FmfLoad:
    """Free-molecular load on a sphere centred at the origin (force along ``-u``, no torque there).

    Parameters are those of :func:`plate_drag`; ``radius_m`` [m]; default ``A_ref = pi R^2``.
    """
    u = _unit_flow(flow_direction)
    law = surface_law(surface, speed_ratio, temperature_K, stream)
    return _load(
        [_sphere(radius_m, u, law)],
        u,
        dynamic_pressure_Pa,
        ref_point_m,
        reference_area_m2 or math.pi * radius_m**2,
    )


def cylinder_drag(
    radius_m: float,
    length_m: float,
    flow_direction: ArrayLike,
    surface: GasLaw,
    speed_ratio: float,
    temperature_K: float,
    *,
    caps: bool = True,
    lateral: str = "bessel",
    dynamic_pressure_Pa: float = 1.0,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
    stream: str = "full",
) -> FmfLoad:
    """Free-molecular load on a circular cylinder on the z axis, centred at the origin.

    Parameters
    ----------
    radius_m, length_m : float
        Radius R and length L [m]; the cylinder spans ``z = -L/2 .. L/2``.
    caps : bool, optional
        Include the end discs (normals +-z); without them only the outer lateral surface interacts.
    lateral : {"bessel", "quad"}, optional
        Azimuth integrals of the lateral surface in closed form (default) or by adaptive quadrature.
    flow_direction, surface, speed_ratio, temperature_K, dynamic_pressure_Pa, ref_point_m, stream
        As in :func:`plate_drag`.
    reference_area_m2 : float, optional
        Default ``pi R^2``.

    Returns
    -------
    FmfLoad
    """
    if lateral not in ("bessel", "quad"):
        raise ValueError(f"lateral must be 'bessel' or 'quad', got {lateral!r}")
    u = _unit_flow(flow_direction)
    law = surface_law(surface, speed_ratio, temperature_K, stream)
    half = 0.5 * length_m
    pieces = [_frustum(radius_m, -half, radius_m, half, u, law, closed=lateral == "bessel")]
    if caps:
        disc = math.pi * radius_m**2
        for side in (1.0, -1.0):
            pieces.append(
                _flat(disc, np.array([0.0, 0.0, side * half * disc]), np.array([0.0, 0.0, side]), u, law)
            )
    return _load(pieces, u, dynamic_pressure_Pa, ref_point_m, reference_area_m2 or math.pi * radius_m**2)


def cone_drag(
    radius_m: float,
    flow_direction: ArrayLike,
    surface: GasLaw,
    speed_ratio: float,
    temperature_K: float,
    *,
    half_angle_deg: float = 70.0,
    base: bool = True,
    dynamic_pressure_Pa: float = 1.0,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
    stream: str = "full",
) -> FmfLoad:
    """Free-molecular load on a right circular cone: base disc in z = 0 (normal -z), apex on +z.

    Parameters
    ----------
    radius_m : float
        Base radius R [m]; the apex is at ``(0, 0, R / tan(half_angle))``.
    half_angle_deg : float, optional
        Angle between the axis and a generator [deg], in (0, 90); default 70 as in the paper.
    base : bool, optional
        Include the base disc; without it only the outer lateral surface interacts.
    flow_direction, surface, speed_ratio, temperature_K, dynamic_pressure_Pa, ref_point_m, stream
        As in :func:`plate_drag`; the torque reference defaults to the base centre.
    reference_area_m2 : float, optional
        Default ``pi R^2`` (the base).

    Returns
    -------
    FmfLoad

    Notes
    -----
    The lateral full-stream azimuth integrals are adaptive quadratures (module Notes); the directed
    stream is closed.
    """
    if not 0.0 < half_angle_deg < 90.0:
        raise ValueError(f"cone half_angle_deg must lie in (0, 90), got {half_angle_deg}")
    u = _unit_flow(flow_direction)
    law = surface_law(surface, speed_ratio, temperature_K, stream)
    height = radius_m / math.tan(math.radians(half_angle_deg))
    pieces = [_frustum(radius_m, 0.0, 0.0, height, u, law, closed=False)]
    if base:
        pieces.append(_flat(math.pi * radius_m**2, np.zeros(3), np.array([0.0, 0.0, -1.0]), u, law))
    return _load(pieces, u, dynamic_pressure_Pa, ref_point_m, reference_area_m2 or math.pi * radius_m**2)


# ------------------------------------------------------------------------------------------- pieces


def _chi(s: NDArray[np.float64]) -> NDArray[np.float64]:
    """``chi(s) = exp(-s^2) + sqrt(pi) s (1 + erf s)``, with ``1 + erf s = erfc(-s)``."""
    return np.exp(-s * s) + _SQRT_PI * s * erfc(-s)


def _unit_flow(flow_direction: ArrayLike) -> Vector:
    u = np.asarray(flow_direction, dtype=np.float64)
    if u.shape != (3,) or abs(np.linalg.norm(u) - 1.0) > _UNIT_TOLERANCE:
        raise ValueError(f"flow_direction must be a unit (3,) vector, got {flow_direction}")
    return u


def _flat(area: float, first_moment: Vector, normal: Vector, u: Vector, law: SurfaceLaw) -> _Piece:
    """Integrals of a flat piece of ``area`` [m^2], ``int r dA`` [m^3] and unit ``normal``."""
    gamma = float(normal @ u)
    tau, g = float(law.shear_over_t(gamma)), float(law.normal_load(gamma))
    return _Piece(tau * area, g * area * normal, tau * first_moment, g * np.cross(first_moment, normal))


def _sphere(radius: float, u: Vector, law: SurfaceLaw) -> _Piece:
    """Integrals of a sphere centred at the origin (module Notes, "Sphere")."""
    if law.stream == "thermal":
        return _difference(_sphere(radius, u, _with(law, "full")), _sphere(radius, u, _with(law, "directed")))
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
    return _Piece(area * int_tau, area * int_g_gamma * u, radius * area * int_tau_gamma * u, np.zeros(3))


def _frustum(
    r_bottom: float, z_bottom: float, r_top: float, z_top: float, u: Vector, law: SurfaceLaw, closed: bool
) -> _Piece:
    """Integrals of the outer lateral surface of a frustum of revolution about z (module Notes).

    ``closed`` selects the Bessel forms (cylinder only, ``r_bottom = r_top``) for the full stream;
    otherwise the full stream's azimuth integrals are adaptive quadratures.
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
    return _Piece(
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


def _difference(a: _Piece, b: _Piece) -> _Piece:
    return _Piece(*(x - y for x, y in zip(a, b, strict=True)))


def _load(
    pieces: list[_Piece], u: Vector, q: float, ref_point_m: ArrayLike, reference_area: float
) -> FmfLoad:
    """Sum the pieces into force and torque about ``ref_point_m`` and set up the coefficient axes."""
    ref = np.asarray(ref_point_m, dtype=np.float64)
    if ref.shape != (3,):
        raise ValueError(f"ref_point_m must be a (3,) point [m], got {ref_point_m}")
    force, torque = np.zeros(3), np.zeros(3)
    for piece in pieces:
        force -= q * (piece.shear * u + piece.normal)
        torque -= q * (np.cross(piece.shear_moment, u) + piece.normal_moment)
    drag, lift, side = _wind_axes(u)
    return FmfLoad(
        force, torque - np.cross(ref, force), ref, float(q), float(reference_area), drag, lift, side
    )


def _wind_axes(u: Vector) -> tuple[Vector, Vector, Vector]:
    """``(e_D, e_L, e_S)`` of the module Notes for the body axis +z (+x when ``u`` is along z)."""
    for axis in (np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])):
        across = axis - (axis @ u) * u
        size = np.linalg.norm(across)
        if size > 1e-12:
            break
    lift = -across / size
    drag = -u
    return drag, lift, np.cross(lift, drag)
