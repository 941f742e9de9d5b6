"""The incident stream per direction of arrival: what a drifting Maxwellian brings a surface element from
each direction, and its tables for one attitude (METHOD.md "Free-molecular flow", "The open-sky
integral").

A molecule arriving from direction ``w`` (a unit vector from the surface toward where the molecule
comes from) moves along ``-w`` with speed ``c``. With ``cos(psi) = w . u`` (``u = v_rel / |v_rel|``),
``s = S cos(psi)`` and ``J_k(s) = int_0^inf x^k exp(-(x - s)^2) dx``, a species of number density
``n``, mass ``m`` and most probable thermal speed ``c_m = sqrt(2 k T / m)`` brings an element of outward
normal ``n_out``, per unit solid angle and per unit ``mu = n_out . w > 0``::

    number   dN / (n V)  = exp(-S^2 sin^2 psi) J_3(s) / (pi^(3/2) S)              (k_N)
    momentum dP / q      = -w 2 exp(-S^2 sin^2 psi) J_4(s) / (pi^(3/2) S^2)       (k_P, along -w)

with ``V = S c_m`` and ``q = n m V^2 / 2``; integrated over an open hemisphere they are the closed forms of
:mod:`sunwind.forces.gas.incident`. ``J_0 = (sqrt(pi)/2) erfc(-s)``, ``J_1 = exp(-s^2)/2 + s J_0`` and
``J_(k+1) = s J_k + (k/2) J_(k-1)``. Every product ``exp(-S^2 sin^2 psi) J_k`` is evaluated in a form
that neither overflows nor cancels badly: for ``s < 0`` with ``erfcx`` and the common factor
``exp(-S^2)``.

The kernels depend on the direction only through ``psi``; one attitude's kernels, summed over species
and weighted for each gas-surface law, are tabulated on ``x = sin(psi / 2)`` (:func:`direction_tables`)
and looked up per ray by linear interpolation.

The CLL kernel's reflected normal momentum depends on the incident normal speed, so per direction on
``psi`` and ``mu`` both: ``dR / q = 2 exp(-S^2 sin^2 psi) G(s, mu) / (pi^(3/2) S^2)`` with
``G(s, mu) = int_0^inf x^3 exp(-(x - s)^2) h(x mu) dx`` and ``h`` the mean reflected normal speed of
:func:`sunwind.forces.gas.incident.cll_reflected_normal`; ``G`` depends on the law (``alpha_n``,
``T_w / T``) but not on the species, and is tabulated once per law and free-stream temperature
(:func:`cll_normal_table`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.special import erfc, erfcx

from sunwind.forces.gas.incident import rice_mean

#: Points of the tables on ``x = sin(psi / 2)`` in [0, 1]: spacing 2.4e-4, so a kernel of angular width
#: ``1/S`` spans 2000 / S of them.
X_POINTS = 4097
#: Points of the CLL tables on ``mu = t^2``, ``t`` evenly spaced in [0, 1] (grazing arrivals, whose mean
#: reflected normal speed turns sharply at small ``mu``, get the finest spacing), and spacing of
#: ``G``'s table on ``s``.
MU_POINTS = 33
_S_STEP = 0.05
#: ``G(s, mu)`` is tabulated from ``s = -_S_LOW``; below, ``exp(-S^2)`` (S >= -s) is under 1e-15.
_S_LOW = 6.0
#: Gauss-Legendre rule of ``G``'s integral over x: panels of width 1 over the window where the weight
#: ``exp(-(x - s)^2)`` exceeds exp(-49), 8 nodes each.
_G_HALF_WIDTH, _G_NODES = 7, 8
_GL_X, _GL_W = np.polynomial.legendre.leggauss(_G_NODES)
_PI_32 = math.pi**1.5

#: Channels of :attr:`DirectionTables.channels`, per law: incident momentum ``k_P`` [Pa], the diffuse
#: re-emission's normal push ``b`` [Pa], and the first re-emission's momentum rate [N/m^2] and
#: sqrt(mass)-weighted molecule rate [sqrt(kg)/(s m^2)] (the molecular exchange's sources); each per
#: unit solid angle and unit ``mu``.
MOMENTUM, PUSH, EMITTED_MOMENTUM, EMITTED_ROOT_MASS = range(4)
N_CHANNELS = 4


def scaled_moments(cos_psi: NDArray[np.float64], speed_ratio: float) -> tuple[NDArray, NDArray]:
    """Compute ``exp(-S^2 sin^2 psi) J_k(S cos psi)`` for ``k = 3, 4``, elementwise.

    Evaluated without overflow or cancellation: for ``s = S cos psi < 0`` through ``erfcx`` and the
    common factor ``exp(-S^2)`` (module docstring).

    Parameters
    ----------
    cos_psi : (n,) array_like of float64
        Cosine of the angle between the arrival direction ``w`` and the flow direction ``u``; clipped
        to [-1, 1].
    speed_ratio : float
        Molecular speed ratio ``S = V / c_m`` [-], positive.

    Returns
    -------
    j3 : (n,) ndarray of float64
        ``exp(-S^2 sin^2 psi) J_3(s)`` [-], never negative.
    j4 : (n,) ndarray of float64
        ``exp(-S^2 sin^2 psi) J_4(s)`` [-], never negative.

    References
    ----------
    Olver et al. (eds.), NIST Digital Library of Mathematical Functions, ch. 7 (repeated integrals of
    the error function).

    Examples
    --------
    >>> j3, j4 = scaled_moments([1.0, 0.0], 2.0)
    >>> j3.round(4), j4.round(4)
    (array([1.94972e+01, 9.20000e-03]), array([5.09579e+01, 1.22000e-02]))
    """
    cos_psi = np.clip(np.asarray(cos_psi, dtype=np.float64), -1.0, 1.0)
    s = speed_ratio * cos_psi
    gauss = math.exp(-speed_ratio * speed_ratio)  # exp(-S^2 sin^2 psi) exp(-s^2)
    ahead = s >= 0.0
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        spread = np.exp(-(speed_ratio * speed_ratio) * (1.0 - cos_psi * cos_psi))
        j0 = np.where(ahead, spread * erfc(-s), gauss * erfcx(np.maximum(-s, 0.0))) * (math.sqrt(math.pi) / 2)
    j1 = 0.5 * gauss + s * j0
    j2 = s * j1 + 0.5 * j0
    j3 = s * j2 + j1
    j4 = s * j3 + 1.5 * j2
    return np.maximum(j3, 0.0), np.maximum(j4, 0.0)


def direction_flux(cos_psi: NDArray[np.float64], speed_ratio: float) -> tuple[NDArray, NDArray]:
    """Number kernel ``k_N / (n V)`` and momentum kernel ``k_P / q`` per unit solid angle and ``mu``.

    Parameters
    ----------
    cos_psi : (n,) array_like of float64
        Cosine of the angle between the arrival direction ``w`` and the flow direction ``u``.
    speed_ratio : float
        Molecular speed ratio ``S`` [-], positive.

    Returns
    -------
    number : (n,) ndarray of float64
        ``exp(-S^2 sin^2 psi) J_3 / (pi^(3/2) S)`` [1/sr].
    momentum : (n,) ndarray of float64
        ``2 exp(-S^2 sin^2 psi) J_4 / (pi^(3/2) S^2)`` [1/sr], the magnitude of the momentum brought
        along ``-w``.

    Examples
    --------
    Head-on arrivals carry almost everything at ``S = 5``; from the side or behind, next to nothing:

    >>> number, momentum = direction_flux([1.0, 0.0, -1.0], 5.0)
    >>> number.round(4), momentum.round(4)
    (array([8.4352, 0.    , 0.    ]), array([17.8445,  0.    ,  0.    ]))
    """
    j3, j4 = scaled_moments(cos_psi, speed_ratio)
    return j3 / (_PI_32 * speed_ratio), 2.0 * j4 / (_PI_32 * speed_ratio**2)


def x_grid() -> NDArray[np.float64]:
    """Abscissae ``x = sin(psi / 2)`` of the direction tables, evenly spaced in [0, 1].

    Returns
    -------
    (X_POINTS,) ndarray of float64
        From 0 (arrival along ``u``) to 1 (arrival from behind).

    Examples
    --------
    >>> x = x_grid()
    >>> x.shape, float(x[0]), float(x[-1])
    ((4097,), 0.0, 1.0)
    """
    return np.linspace(0.0, 1.0, X_POINTS)


def cos_of_x(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Cosine ``cos(psi) = 1 - 2 x^2`` at the table abscissae ``x = sin(psi / 2)``.

    Parameters
    ----------
    x : ndarray of float64
        Values of ``sin(psi / 2)`` in [0, 1], any shape.

    Returns
    -------
    ndarray of float64
        ``cos(psi)``, the shape of ``x``.

    Examples
    --------
    >>> import numpy as np
    >>> cos_of_x(np.array([0.0, 0.5, 1.0]))
    array([ 1. ,  0.5, -1. ])
    """
    return 1.0 - 2.0 * x * x


@dataclass(frozen=True, eq=False)
class SpeciesLaws:
    """One attitude's free stream by species and how each gas-surface law of a model answers it.

    Attributes
    ----------
    speed_ratio : (k,) float64
        ``S_k`` of each species (species of equal mass merged).
    dynamic_pressure_Pa : (k,) float64
        ``q_k = n_k m_k V^2 / 2``.
    pressure_scale, shear_scale : (n_laws,) float64
        Factor of the incident normal momentum each law puts on the surface (1 plus its specular
        share) and of the incident tangential momentum it takes.
    push : (n_laws, k) float64
        Normal momentum of each law's diffuse re-emission per incident molecule, over ``q_k / (n_k V)``.
    emission : (n_laws, k, 2) float64
        Per unit incident flux over ``n_k V``: the first diffuse re-emission's momentum rate [N/m^2] and
        its sqrt(mass)-weighted molecule rate [sqrt(kg)/(s m^2)].
    cll_alpha_n, cll_tau_w : (n_laws,) float64
        CLL's ``alpha_n`` (NaN for other laws) and ``T_w / T``.

    Examples
    --------
    Made by :func:`sunwind.forces.gas.panel.species_laws`; here one species and one law by hand:

    >>> import numpy as np
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(speed_ratio=np.array([7.0]), dynamic_pressure_Pa=np.array([3e-5]),
    ...     pressure_scale=one, shear_scale=one, push=np.array([[0.1]]), emission=np.zeros((1, 1, 2)),
    ...     cll_alpha_n=np.array([np.nan]), cll_tau_w=np.zeros(1))
    >>> laws.push.shape
    (1, 1)
    """

    speed_ratio: NDArray[np.float64]
    dynamic_pressure_Pa: NDArray[np.float64]
    pressure_scale: NDArray[np.float64]
    shear_scale: NDArray[np.float64]
    push: NDArray[np.float64]
    emission: NDArray[np.float64]
    cll_alpha_n: NDArray[np.float64]
    cll_tau_w: NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class DirectionTables:
    """One attitude's kernels per law on ``x = sin(psi / 2)`` (:func:`x_grid`), summed over species.

    Attributes
    ----------
    channels : (n_laws, X_POINTS, N_CHANNELS) float64
        :data:`MOMENTUM`, :data:`PUSH`, :data:`EMITTED_MOMENTUM`, :data:`EMITTED_ROOT_MASS`; a point's
        channels side by side, so that a lookup reads one cache line.
    cll : (n_laws, X_POINTS, MU_POINTS) float64 or None
        CLL's reflected normal momentum [Pa] per unit solid angle and ``mu`` on ``(x, mu)``; zero for
        other laws; None where no law is CLL.

    Examples
    --------
    >>> import numpy as np
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(np.array([7.0]), np.array([3e-5]), one, one, np.array([[0.1]]),
    ...     np.zeros((1, 1, 2)), np.array([np.nan]), np.zeros(1))
    >>> tables = direction_tables(laws, {})
    >>> tables.channels.shape, tables.cll is None
    ((1, 4097, 4), True)
    """

    channels: NDArray[np.float64]
    cll: NDArray[np.float64] | None


def channel_values(
    laws: SpeciesLaws, cos_psi: NDArray[np.float64], cll_tables: dict[int, NDArray[np.float64]]
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Evaluate the kernels of every law at the directions ``cos_psi``, summed over the species.

    Parameters
    ----------
    laws : SpeciesLaws
        The attitude's free stream by species and each law's answer to it.
    cos_psi : (n,) ndarray of float64
        Cosine of the angle between each arrival direction and the flow direction ``u``.
    cll_tables : dict of int to ndarray
        Each CLL law's index mapped to its :func:`cll_normal_table`, which must reach ``s = S`` of
        every species; empty when no law is CLL.

    Returns
    -------
    channels : (n_laws, N_CHANNELS, n) ndarray of float64
        :data:`MOMENTUM` [Pa], :data:`PUSH` [Pa], :data:`EMITTED_MOMENTUM` [N/m^2] and
        :data:`EMITTED_ROOT_MASS` [sqrt(kg)/(s m^2)], each per unit solid angle and unit ``mu``.
    cll : (n_laws, n, MU_POINTS) ndarray of float64 or None
        CLL's reflected normal momentum [Pa] per unit solid angle and ``mu`` (zero rows for other laws);
        None when ``cll_tables`` is empty.

    Examples
    --------
    >>> import numpy as np
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(np.array([7.0]), np.array([3e-5]), one, one, np.array([[0.1]]),
    ...     np.zeros((1, 1, 2)), np.array([np.nan]), np.zeros(1))
    >>> channels, cll = channel_values(laws, np.array([1.0, -1.0]), {})
    >>> channels.shape, cll
    ((1, 4, 2), None)
    >>> (channels[0, MOMENTUM] / 3e-5).round(3)
    array([33.114,  0.   ])
    """
    n_laws = laws.push.shape[0]
    channels = np.zeros((n_laws, N_CHANNELS, len(cos_psi)))
    cll = None if not cll_tables else np.zeros((n_laws, len(cos_psi), MU_POINTS))
    for k, (ratio, q) in enumerate(zip(laws.speed_ratio, laws.dynamic_pressure_Pa, strict=True)):
        number, momentum = direction_flux(cos_psi, float(ratio))
        channels[:, MOMENTUM] += q * momentum
        channels[:, PUSH] += (q * laws.push[:, k])[:, None] * number
        channels[:, EMITTED_MOMENTUM] += laws.emission[:, k, 0][:, None] * number
        channels[:, EMITTED_ROOT_MASS] += laws.emission[:, k, 1][:, None] * number
        for law, table in cll_tables.items():
            cll[law] += q * cll_direction_kernel(cos_psi, float(ratio), table)
    return channels, cll


def direction_tables(laws: SpeciesLaws, cll_tables: dict[int, NDArray[np.float64]]) -> DirectionTables:
    """Direction tables of one attitude: :func:`channel_values` on :func:`x_grid`.

    Parameters
    ----------
    laws : SpeciesLaws
        The attitude's free stream by species and each law's answer to it.
    cll_tables : dict of int to ndarray
        Each CLL law's index mapped to its :func:`cll_normal_table`; empty when no law is CLL.

    Returns
    -------
    DirectionTables
        The channels laid out point by point, and CLL's table or None.

    Examples
    --------
    >>> import numpy as np
    >>> one = np.ones(1)
    >>> laws = SpeciesLaws(np.array([7.0]), np.array([3e-5]), one, one, np.array([[0.1]]),
    ...     np.zeros((1, 1, 2)), np.array([np.nan]), np.zeros(1))
    >>> direction_tables(laws, {}).channels.shape
    (1, 4097, 4)
    """
    channels, cll = channel_values(laws, cos_of_x(x_grid()), cll_tables)
    return DirectionTables(np.ascontiguousarray(channels.transpose(0, 2, 1)), cll)


# ------------------------------------------------------------------------------------------------- CLL


def mu_grid() -> NDArray[np.float64]:
    """Abscissae ``mu = t^2`` of the CLL tables, ``t`` evenly spaced in [0, 1].

    Returns
    -------
    (MU_POINTS,) ndarray of float64
        Finest near grazing arrival (``mu = 0``).

    Examples
    --------
    >>> mu = mu_grid()
    >>> mu.shape, round(float(mu[1]), 6), float(mu[-1])
    ((33,), 0.000977, 1.0)
    """
    return np.linspace(0.0, 1.0, MU_POINTS) ** 2


def cll_normal_table(
    alpha_n: float, tau_w: float, s_high: float, mean: Callable[..., NDArray] = rice_mean
) -> NDArray[np.float64]:
    """Table of CLL's integral ``G(s, mu) exp(min(s, 0)^2)`` for one law and free-stream temperature.

    ``G(s, mu) = int_0^inf x^3 exp(-(x - s)^2) h(x mu) dx`` with ``h`` the mean reflected normal speed
    (:func:`sunwind.forces.gas.incident.cll_reflected_normal`), integrated by Gauss-Legendre panels of
    width 1 over the window where the weight exceeds ``exp(-49)``.

    Parameters
    ----------
    alpha_n : float
        CLL's normal energy accommodation [-], in [0, 1].
    tau_w : float
        ``T_w / T``, wall over free-stream temperature [-].
    s_high : float
        Largest ``s`` the table must reach (the largest speed ratio ``S`` of the species).
    mean : callable, optional
        ``h(x, alpha_n, tau_w)``, default :func:`~sunwind.forces.gas.incident.rice_mean`;
        :func:`~sunwind.forces.gas.incident.rice_mean_slope` tabulates ``d G / d alpha_n``.

    Returns
    -------
    (n_s, MU_POINTS) ndarray of float64
        Rows on ``s = -6 + 0.05 j`` up to just past ``s_high``, columns on :func:`mu_grid`.

    References
    ----------
    Cercignani and Lampis (1971); Lord (1991); Olver et al. (eds.), NIST Digital Library of Mathematical
    Functions, section 3.5 (Gauss quadrature).

    Examples
    --------
    >>> table = cll_normal_table(0.5, 0.3, 3.0)
    >>> table.shape
    (182, 33)
    """
    s = np.arange(-_S_LOW, s_high + 2 * _S_STEP, _S_STEP)
    mu = mu_grid()
    out = np.empty((len(s), MU_POINTS))
    for row, value in enumerate(s):
        lo = max(0.0, value - _G_HALF_WIDTH)
        edges = np.arange(lo, max(value, 0.0) + _G_HALF_WIDTH + 1e-9, 1.0)
        left = edges[:-1, None]
        x = (left + 0.5 + 0.5 * _GL_X).ravel()
        weight = np.tile(0.5 * _GL_W, len(left))
        # exp(-(x - s)^2) scaled by exp(s^2) for s < 0: exp(-x^2 + 2 s x)
        shift = value if value >= 0.0 else 0.0
        log_weight = -((x - shift) ** 2) + (2.0 * value * x if value < 0.0 else 0.0)
        base = weight * x**3 * np.exp(log_weight)
        h = mean(x[:, None] * mu[None, :], np.full((1, MU_POINTS), alpha_n), np.full((1, MU_POINTS), tau_w))
        out[row] = base @ h
    return out


def cll_direction_kernel(
    cos_psi: NDArray[np.float64], speed_ratio: float, table: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Interpolate CLL's reflected normal momentum over ``q`` per unit solid angle and ``mu`` in ``table``.

    The value is ``2 exp(-S^2 sin^2 psi) G(S cos psi, mu) / (pi^(3/2) S^2)`` (module docstring), linear
    in ``s`` between the rows of ``table``.

    Parameters
    ----------
    cos_psi : (n,) ndarray of float64
        Cosine of the angle between each arrival direction and the flow direction ``u``.
    speed_ratio : float
        Molecular speed ratio ``S`` [-] of the species.
    table : (n_s, MU_POINTS) ndarray of float64
        The law's :func:`cll_normal_table`, which must reach ``s = S``.

    Returns
    -------
    (n, MU_POINTS) ndarray of float64
        The kernel [1/sr] at each direction and each ``mu`` of :func:`mu_grid`.

    Examples
    --------
    >>> import numpy as np
    >>> table = cll_normal_table(0.5, 0.3, 3.0)
    >>> kernel = cll_direction_kernel(np.array([1.0, 0.5]), 3.0, table)
    >>> kernel.shape, bool((kernel >= 0.0).all())
    ((2, 33), True)
    """
    s = speed_ratio * np.asarray(cos_psi, dtype=np.float64)
    position = (np.clip(s, -_S_LOW, None) + _S_LOW) / _S_STEP
    below = np.minimum(np.floor(position).astype(np.int64), table.shape[0] - 2)
    frac = (position - below)[:, None]
    g = (1.0 - frac) * table[below] + frac * table[below + 1]
    with np.errstate(under="ignore"):
        factor = np.where(
            s >= 0.0,
            np.exp(-(speed_ratio**2) * (1.0 - np.square(np.asarray(cos_psi, dtype=np.float64)))),
            math.exp(-(speed_ratio**2)),
        )
    return (2.0 / (_PI_32 * speed_ratio**2)) * factor[:, None] * g
