"""The core of the incident stream: the cone of directions about the flow from which a fast stream's
molecules come, its integral over an unobstructed side, and how its directions are sampled (METHOD.md
"The open-sky integral").

At speed ratio ``S`` the molecules arrive from within about ``1/S`` of ``u``: a kernel far narrower than
the spacing of a side's sampled sky rays (:mod:`sunwind.geometry.views.sky`) when ``S`` is large. The
integral over a side's open sky is therefore split at the cone ``psi < psi_c`` about ``u``:

- the **core** (inside the cone) is followed per attitude by rays: the exact shadow along ``u`` and
  directions sampled from the kernel within the cone (:mod:`.visible`);
- the **rest** (outside) is summed over the side's sampled sky rays.

``psi_c = min(CORE_MAX_RAD, CORE_SPREAD / S_min)``, ``S_min`` the lowest speed ratio among species
carrying at least :data:`SIGNIFICANT` of the dynamic pressure. Above ``S = CORE_SPREAD / CORE_MAX_RAD``
the cone holds all but ``~exp(-CORE_SPREAD^2)`` of every such species' stream (the rest vanishes as
``S -> inf`` and the core becomes the hyperthermal shadow); below it the cone is ``CORE_MAX_RAD`` wide and
the broad remainder of the stream, which the sky rays resolve well, is theirs.

:func:`core_cone` tabulates, on ``gamma = n . u``, what the core brings an unobstructed side of each
law: the law's normal and tangential force per unit area and the first re-emission's two exchange
sources. Over a ring of directions at angle ``psi`` from ``u`` (azimuth ``phi``), ``mu = n . w = A + B
cos(phi)`` with ``A = gamma cos(psi)``, ``B = sqrt(1 - gamma^2) sin(psi)``; the ring's integrals of
``mu+``, ``mu+ mu`` and ``mu+ cos(phi)`` over the part in front of the side are closed forms, and the
radial integral is Gauss-Legendre split where the ring first meets the side's plane (``psi = |asin
gamma|``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.angular import (
    EMITTED_MOMENTUM,
    EMITTED_ROOT_MASS,
    MOMENTUM,
    PUSH,
    SpeciesLaws,
    channel_values,
    mu_grid,
)

#: Width of the core in thermal spreads: ``psi_c = CORE_SPREAD / S`` where that is below CORE_MAX_RAD.
CORE_SPREAD = 3.0
#: Widest core [rad] (17 deg).
CORE_MAX_RAD = 0.3
#: Share of the dynamic pressure below which a species does not set the core's width.
SIGNIFICANT = 1e-3
#: Points of the core's tables on ``gamma`` in [-1, 1].
GAMMA_POINTS = 513
#: Gauss-Legendre nodes per radial piece, azimuthal nodes of CLL's ring integral, and points of the
#: sampling distribution's inverse.
_RADIAL_NODES, _RING_NODES, _QUANTILES = 24, 16, 257
_RX, _RW = np.polynomial.legendre.leggauss(_RADIAL_NODES)
_PX, _PW = np.polynomial.legendre.leggauss(_RING_NODES)

#: Columns of :attr:`CoreCone.gamma_table`: normal force [Pa] (along the outward normal), tangential
#: force [Pa] (along ``t_hat``), emitted momentum rate [N/m^2], emitted sqrt(mass) rate, per unit area.
NORMAL, TANGENTIAL, CORE_MOMENTUM, CORE_ROOT_MASS = range(4)


@dataclass(frozen=True, eq=False)
class CoreCone:
    """The core cone of one attitude (module docstring).

    Attributes
    ----------
    half_angle : float
        ``psi_c`` [rad].
    gamma_table : (n_laws, 4, GAMMA_POINTS) float64
        What the core brings an unobstructed side of each law at ``gamma`` (columns :data:`NORMAL`,
        :data:`TANGENTIAL`, :data:`CORE_MOMENTUM`, :data:`CORE_ROOT_MASS`), on ``linspace(-1, 1)``.
    psi_quantiles : (_QUANTILES,) float64
        ``psi`` [rad] at evenly spaced probabilities of the sampling distribution within the cone
        (density ``k_P / Z`` per unit solid angle, ``k_P`` the species' summed momentum kernel).
    normaliser : float
        ``Z = integral over the cone of k_P dOmega`` [Pa].

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.gas.angular import SpeciesLaws
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(speed_ratio=np.array([7.0]), dynamic_pressure_Pa=np.array([3e-5]),
    ...     pressure_scale=one, shear_scale=one, push=np.array([[0.1]]), emission=np.zeros((1, 1, 2)),
    ...     cll_alpha_n=np.array([np.nan]), cll_tau_w=np.zeros(1))
    >>> cone = core_cone(laws, {})
    >>> cone.gamma_table.shape, cone.psi_quantiles.shape
    ((1, 4, 513), (257,))
    """

    half_angle: float
    gamma_table: NDArray[np.float64]
    psi_quantiles: NDArray[np.float64]
    normaliser: float


def core_half_angle(laws: SpeciesLaws) -> float:
    """Half-angle ``psi_c`` of the core cone [rad] (module docstring).

    ``psi_c = min(CORE_MAX_RAD, CORE_SPREAD / S_min)``, ``S_min`` the lowest speed ratio among the
    species carrying at least :data:`SIGNIFICANT` of the dynamic pressure.

    Parameters
    ----------
    laws : SpeciesLaws
        The attitude's free stream by species.

    Returns
    -------
    float
        ``psi_c`` [rad], in (0, CORE_MAX_RAD].

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.gas.angular import SpeciesLaws
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(speed_ratio=np.array([7.0]), dynamic_pressure_Pa=np.array([3e-5]),
    ...     pressure_scale=one, shear_scale=one, push=np.array([[0.1]]), emission=np.zeros((1, 1, 2)),
    ...     cll_alpha_n=np.array([np.nan]), cll_tau_w=np.zeros(1))
    >>> core_half_angle(laws)
    0.3
    """
    q = laws.dynamic_pressure_Pa
    significant = laws.speed_ratio[q >= SIGNIFICANT * q.sum()]
    return min(CORE_MAX_RAD, CORE_SPREAD / float(significant.min()))


def core_cone(
    laws: SpeciesLaws, cll_tables: dict[int, NDArray[np.float64]], half_angle: float | None = None
) -> CoreCone:
    """Core cone of one attitude: its width, per-law tables on ``gamma`` and sampling distribution.

    Parameters
    ----------
    laws : SpeciesLaws
        The attitude's free stream by species and each law's answer to it.
    cll_tables : dict of int to ndarray
        As for :func:`~sunwind.forces.gas.angular.channel_values`: each CLL law's
        :func:`~sunwind.forces.gas.angular.cll_normal_table`; empty when no law is CLL.
    half_angle : float, optional
        ``psi_c`` [rad] to use instead of :func:`core_half_angle` (for tests: at pi the core is the
        whole stream).

    Returns
    -------
    CoreCone
        The cone, its tables on ``gamma = n . u`` and its sampling distribution.

    References
    ----------
    Olver et al. (eds.), NIST Digital Library of Mathematical Functions, section 3.5 (Gauss-Legendre
    quadrature of the radial integral).

    Examples
    --------
    Head-on, the core carries nearly all the normal force of the whole stream at ``S = 7``:

    >>> import numpy as np
    >>> from sunwind.forces.gas.angular import SpeciesLaws
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(speed_ratio=np.array([7.0]), dynamic_pressure_Pa=np.array([3e-5]),
    ...     pressure_scale=one, shear_scale=one, push=np.array([[0.1]]), emission=np.zeros((1, 1, 2)),
    ...     cll_alpha_n=np.array([np.nan]), cll_tau_w=np.zeros(1))
    >>> core = core_cone(laws, {}).gamma_table[0, NORMAL, -1]
    >>> whole = core_cone(laws, {}, half_angle=np.pi).gamma_table[0, NORMAL, -1]
    >>> round(float(core / 3e-5), 3), round(float(whole / 3e-5), 3)
    (-2.097, -2.12)
    """
    half = core_half_angle(laws) if half_angle is None else half_angle
    gamma = np.linspace(-1.0, 1.0, GAMMA_POINTS)
    kink = np.clip(np.abs(np.arcsin(gamma)), 0.0, half)
    # two radial pieces per gamma, [0, kink] and [kink, half] (one empty where the kink is at an end)
    psi = np.concatenate([_nodes(np.zeros_like(kink), kink), _nodes(kink, np.full_like(kink, half))], axis=1)
    weight = np.concatenate(
        [_weights(np.zeros_like(kink), kink), _weights(kink, np.full_like(kink, half))], 1
    )
    channels, cll = channel_values(laws, np.cos(psi).ravel(), cll_tables)
    shape = psi.shape
    g, nu = gamma[:, None], np.sqrt(1.0 - gamma * gamma)[:, None]
    a, b = g * np.cos(psi), nu * np.sin(psi)
    i0, i1, ic, phi0 = _ring_integrals(a, b)
    w = weight * np.sin(psi)
    table = np.empty((len(laws.pressure_scale), 4, GAMMA_POINTS))
    for law in range(len(laws.pressure_scale)):
        k_p, push = channels[law, MOMENTUM].reshape(shape), channels[law, PUSH].reshape(shape)
        normal = -laws.pressure_scale[law] * k_p * i1 - push * i0
        if cll is not None and np.any(cll[law]):
            normal -= _cll_ring(cll[law].reshape(*shape, -1), a, b, phi0)
        tangential = -laws.shear_scale[law] * k_p * (g * np.sin(psi) * ic - nu * np.cos(psi) * i0)
        table[law, NORMAL] = np.sum(w * normal, axis=1)
        table[law, TANGENTIAL] = np.sum(w * tangential, axis=1)
        table[law, CORE_MOMENTUM] = np.sum(w * channels[law, EMITTED_MOMENTUM].reshape(shape) * i0, axis=1)
        table[law, CORE_ROOT_MASS] = np.sum(w * channels[law, EMITTED_ROOT_MASS].reshape(shape) * i0, axis=1)
    return CoreCone(half, table, *_sampling(laws, half))


def _nodes(lo: NDArray[np.float64], hi: NDArray[np.float64]) -> NDArray[np.float64]:
    return 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * _RX


def _weights(lo: NDArray[np.float64], hi: NDArray[np.float64]) -> NDArray[np.float64]:
    return 0.5 * (hi - lo)[:, None] * _RW


def _ring_integrals(a: NDArray, b: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Over ``phi`` in [0, 2 pi) with ``mu = a + b cos(phi)`` (``b >= 0``): the integrals of ``mu+``,
    ``mu+ mu`` and ``mu+ cos(phi)``, and the half-width ``phi0`` of the arc where ``mu > 0``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(b > 0.0, -a / b, np.where(a > 0.0, -np.inf, np.inf))
    phi0 = np.arccos(np.clip(ratio, -1.0, 1.0))
    sin0, half = np.sin(phi0), 0.5 * phi0 + 0.25 * np.sin(2.0 * phi0)
    i0 = 2.0 * (a * phi0 + b * sin0)
    i1 = 2.0 * (a * a * phi0 + 2.0 * a * b * sin0 + b * b * half)
    ic = 2.0 * (a * sin0 + b * half)
    return i0, i1, ic, phi0


def _cll_ring(kernel: NDArray, a: NDArray, b: NDArray, phi0: NDArray) -> NDArray:
    """``int mu+ R(psi, mu) dphi`` over the ring, ``kernel`` (..., MU_POINTS) CLL's ``R`` on
    :func:`~sunwind.forces.gas.angular.mu_grid` at each ring, by Gauss-Legendre on [0, phi0], doubled."""
    phi = 0.5 * phi0[..., None] * (1.0 + _PX)
    mu = np.clip(a[..., None] + b[..., None] * np.cos(phi), 0.0, 1.0)
    position = np.sqrt(mu) * (len(mu_grid()) - 1)  # the table is on mu = t^2, t evenly spaced
    below = np.minimum(position.astype(np.int64), len(mu_grid()) - 2)
    frac = position - below
    r = (1.0 - frac) * np.take_along_axis(kernel, below, -1) + frac * np.take_along_axis(
        kernel, below + 1, -1
    )
    return phi0 * np.sum(_PW * mu * r, axis=-1)


def _sampling(laws: SpeciesLaws, half: float) -> tuple[NDArray[np.float64], float]:
    """Inverse of the cumulative distribution ``~ k_P(psi) sin(psi)`` on [0, half] at evenly spaced
    probabilities (:attr:`CoreCone.psi_quantiles`), and ``Z`` (:attr:`CoreCone.normaliser`)."""
    psi = np.linspace(0.0, half, 16 * _QUANTILES)
    channels, _ = channel_values(laws, np.cos(psi), {})
    density = channels[0, MOMENTUM] * np.sin(psi)
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(psi))])
    if cumulative[-1] <= 0.0:  # no stream within the cone (cannot happen for S > 0): spread evenly
        return np.linspace(0.0, half, _QUANTILES), 0.0
    quantiles = np.interp(np.linspace(0.0, 1.0, _QUANTILES), cumulative / cumulative[-1], psi)
    return quantiles, 2.0 * math.pi * float(cumulative[-1])
