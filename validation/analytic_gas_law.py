"""The local free-molecular law of one gas species on a surface element, and the free stream it sees.

The law is derived here again (Sentman 1961; Schaaf & Chambre 1958), for the closed forms of
:mod:`sunwind.validation.analytic_drag`, apart from the solver's; the module imports numpy and scipy
only, nothing from ``forces``. Everything is in the body frame and SI.

Notes
-----
**Flow and frames** (METHOD.md "Frames, units and signs"). ``u = v_rel / |v_rel|`` is the unit flow vector
(the spacecraft's velocity relative to the atmosphere, body frame); molecules travel along ``-u``.
:func:`flow_vector_from_alpha` puts ``u`` at ``alpha`` from +z in the xz-plane.

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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import erfc

__all__ = [
    "DRAG_MODELS",
    "STREAMS",
    "AnalyticStream",
    "GasLaw",
    "SurfaceLaw",
    "flow_vector_from_alpha",
    "surface_law",
]

#: Models with closed forms here (CLL has none; see sunwind.forces.gas.laws for it).
DRAG_MODELS = ("sentman", "dria", "schaaf-chambre", "specular")
#: The molecules a law or a load counts (module Notes, "Streams").
STREAMS = ("full", "directed", "thermal")
_SQRT_PI = math.sqrt(math.pi)

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

    Examples
    --------
    >>> diffuse = GasLaw("sentman", energy_accommodation=0.9, wall_temperature_K=300.0)
    >>> diffuse.model, diffuse.normal_accommodation
    ('sentman', 1.0)
    """

    model: str
    energy_accommodation: float = 1.0
    normal_accommodation: float = 1.0
    tangential_accommodation: float = 1.0
    wall_temperature_K: float = 300.0


@dataclass(frozen=True, eq=False)
class AnalyticStream:
    """The free stream of one gas species as the body sees it, and which of its molecules count.

    Attributes
    ----------
    flow_direction : (3,) array_like
        Unit flow vector ``u = v_rel / |v_rel|``, body frame; molecules travel along ``-u``.
    speed_ratio : float
        ``S = V / sqrt(2 k T / m)`` of the species [-].
    temperature_K : float
        Free-stream temperature ``T`` [K].
    dynamic_pressure_Pa : float
        ``q = rho V^2 / 2`` [Pa]; default 1, so a force reads as ``C A_ref`` in N.
    stream : {"full", "directed", "thermal"}
        All molecules, the cold beam along ``-u`` (the hyperthermal law), or the difference
        (module Notes, "Streams").

    Examples
    --------
    >>> flow = AnalyticStream(flow_vector_from_alpha(30.0), speed_ratio=7.0, temperature_K=900.0)
    >>> flow.dynamic_pressure_Pa, flow.stream
    (1.0, 'full')
    """

    flow_direction: ArrayLike
    speed_ratio: float
    temperature_K: float
    dynamic_pressure_Pa: float = 1.0
    stream: str = "full"


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

    Examples
    --------
    A specular face normal to the hyperthermal beam takes ``c_n = 4`` (twice the stopped momentum, over q):

    >>> law = surface_law(GasLaw("specular"), speed_ratio=7.0, temperature_K=900.0, stream="directed")
    >>> c_n, c_t = law.coefficients([1.0, 0.5])
    >>> c_n.tolist(), c_t.tolist()
    ([4.0, 1.0], [0.0, 0.0])
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

    Examples
    --------
    >>> flow_vector_from_alpha(90.0).round(12).tolist()
    [1.0, 0.0, 0.0]
    """
    alpha = math.radians(alpha_deg)
    return np.array([math.sin(alpha), 0.0, math.cos(alpha)])


def surface_law(
    surface: GasLaw, speed_ratio: float, temperature_K: float, stream: str = "full"
) -> SurfaceLaw:
    """The local law of ``surface`` for a species of speed ratio ``S`` in gas at ``T`` [K].

    Parameters
    ----------
    surface : GasLaw
        Model and accommodation of the surface.
    speed_ratio : float
        ``S = V / sqrt(2 k T / m)`` of the species [-], finite and > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], finite and > 0.
    stream : {"full", "directed", "thermal"}, optional
        Which molecules count (module Notes, "Streams").

    Returns
    -------
    SurfaceLaw
        ``(a_n, a_t, K)`` of the model at this ``S`` and ``T_w / T`` (module Notes, "Local law").

    Raises
    ------
    ValueError
        Unknown model or stream, or a parameter out of range.

    Examples
    --------
    >>> law = surface_law(GasLaw("schaaf-chambre", normal_accommodation=0.5), 7.0, 900.0)
    >>> law.a_n, law.a_t, round(law.k, 4)
    (1.5, 1.0, 0.2887)

    References
    ----------
    .. [1] L. H. Sentman, "Free molecule flow theory and its application to the determination of
       aerodynamic forces", Lockheed Missiles and Space Co., LMSC-448514, 1961.
    .. [2] S. A. Schaaf and P. L. Chambre, "Flow of rarefied gases", in *Fundamentals of Gas
       Dynamics*, Princeton University Press, 1958.
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


def _chi(s: NDArray[np.float64]) -> NDArray[np.float64]:
    """``chi(s) = exp(-s^2) + sqrt(pi) s (1 + erf s)``, with ``1 + erf s = erfc(-s)``."""
    return np.exp(-s * s) + _SQRT_PI * s * erfc(-s)
