"""The incident stream of a drifting Maxwellian on a surface element, and the momentum of molecules
re-emitted from it (METHOD.md "Free-molecular flow").

``u = v_rel / |v_rel|`` is the unit flow vector (molecules travel along ``-u``); an element of outward
normal ``n`` has ``gamma = n . u`` (> 0 windward, < 0 lee: at finite speed ratio lee faces are struck
too) and ``t = sqrt(1 - gamma^2)``. With ``s = S gamma`` and ``chi(s) = exp(-s^2) + sqrt(pi) s (1 +
erf s)``, the incident momentum and number fluxes over ``q = rho V^2 / 2`` and ``n_k V`` are::

    c_n_inc = [ (s / sqrt(pi)) exp(-s^2) + (1/2 + s^2)(1 + erf s) ] / S^2
    c_t_inc = t chi(s) / (S sqrt(pi))
    N / (n_k V) = chi(s) / (2 sqrt(pi) S)

Hyperthermal limits (``S -> inf``, ``gamma > 0``): ``2 gamma^2``, ``2 gamma t``, ``gamma``; ``1 + erf s``
is computed as ``erfc(-s)``, which keeps its relative accuracy at large negative ``s``.

**Streams.** The *directed* stream is a cold beam of the same density moving at ``-V u``: number flux
``n_k V max(gamma, 0)``, incident coefficients ``2 gamma^2`` and ``2 gamma t`` for ``gamma > 0``, zero
otherwise. The *thermal* stream is the full stream minus the directed one, so ``full = directed +
thermal`` holds by construction; every gas-surface law is linear in the incident distribution, so it
splits the same way.

**Re-emission.** ``N`` molecules per unit area re-emitted as a half-range (Lambertian) Maxwellian at
``T_r`` carry the normal momentum flux ``N m sqrt(pi k T_r / (2 m))``, over ``q`` that is
``(N / (n_k V)) sqrt(pi) sqrt(T_r / T) / S`` (:func:`diffuse_normal`); no mean tangential momentum.
The CLL kernel's reflected normal momentum is :func:`cll_reflected_normal`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray
from scipy.special import erfc, i0e, i1e

from sunwind.geometry.errors import InputError

#: Incident streams: the drifting Maxwellian, its cold directed beam, and their difference.
STREAMS = ("full", "directed", "thermal")

_SQRT_PI = math.sqrt(math.pi)
# Composite Gauss-Legendre rule of the CLL normal integral (see cll_reflected_normal).
_CLL_WINDOW_SQ = 40.0  # the weight exp(-(x - s)^2) is cut where it falls below exp(-40) ~ 4e-18
_CLL_UNIFORM_PANELS = 6
_CLL_GRADED_PANELS = 10
_CLL_NODES = 12
_CLL_CHUNK = 8192
_GL_X, _GL_W = np.polynomial.legendre.leggauss(_CLL_NODES)


class Incident(NamedTuple):
    """What a stream brings to surface elements, each field (n,).

    Parameters
    ----------
    c_n : (n,) float64
        Incident momentum normal to the element over ``q`` (``c_n_inc``) [-].
    c_t : (n,) float64
        Incident momentum along the element's shear direction over ``q`` (``c_t_inc``) [-].
    number_flux : (n,) float64
        Incident molecules per unit area and time over ``n_k V`` [-].

    Examples
    --------
    >>> import numpy as np
    >>> incident(np.array([1.0, 0.0]), 7.0).c_n.round(4)
    array([2.0204, 0.0102])
    """

    c_n: NDArray[np.float64]
    c_t: NDArray[np.float64]
    number_flux: NDArray[np.float64]


def incident(gamma: NDArray[np.float64], speed_ratio: float, stream: str = "full") -> Incident:
    """Incident ``stream`` on elements of ``gamma = n . u`` (module docstring), its arguments unchecked.

    Parameters
    ----------
    gamma : (n,) float64
        ``gamma = n_out . u`` of each element, in [-1, 1].
    speed_ratio : float
        ``S`` of the species [-], > 0.
    stream : {"full", "directed", "thermal"}, optional
        The drifting Maxwellian, its cold directed beam, or their difference.

    Returns
    -------
    Incident
        Normal and tangential momentum over ``q`` and number flux over ``n_k V``, each (n,).

    References
    ----------
    Schaaf and Chambré (1958), the free-molecular incident fluxes of a drifting Maxwellian.

    Examples
    --------
    At ``S = 7``, head-on, edge-on and from behind; the full stream is the directed and the thermal:

    >>> import numpy as np
    >>> gamma = np.array([1.0, 0.0, -1.0])
    >>> full = incident(gamma, 7.0)
    >>> full.c_n.round(4), full.c_t.round(4), full.number_flux.round(4)
    (array([2.0204, 0.0102, 0.    ]), array([0.    , 0.0806, 0.    ]), array([1.    , 0.0403, 0.    ]))
    >>> parts = incident(gamma, 7.0, "directed").c_n + incident(gamma, 7.0, "thermal").c_n
    >>> bool(np.allclose(parts, full.c_n))
    True
    """
    t = np.sqrt(np.maximum(1.0 - gamma * gamma, 0.0))
    if stream == "directed":
        windward = np.maximum(gamma, 0.0)
        return Incident(2.0 * windward * windward, 2.0 * windward * t, windward)
    s = speed_ratio * gamma
    gauss = np.exp(-s * s)
    one_plus_erf = erfc(-s)
    # Both are >= 0 exactly; at large negative s a rounding error could make them a hair below 0.
    chi = np.maximum(gauss + _SQRT_PI * s * one_plus_erf, 0.0)
    pressure = np.maximum(s / _SQRT_PI * gauss + (0.5 + s * s) * one_plus_erf, 0.0)
    c_n = pressure / speed_ratio**2
    c_t = t * chi / (speed_ratio * _SQRT_PI)
    flux = chi / (2.0 * _SQRT_PI * speed_ratio)
    if stream == "thermal":
        c_n_d, c_t_d, flux_d = incident(gamma, speed_ratio, "directed")
        return Incident(c_n - c_n_d, c_t - c_t_d, flux - flux_d)
    return Incident(c_n, c_t, flux)


def incident_number_flux(
    cos_incidence: NDArray[np.float64], speed_ratio: float, stream: str = "full"
) -> NDArray[np.float64]:
    """Incident number flux per unit area over ``n_k V`` [-] (module docstring).

    Parameters
    ----------
    cos_incidence : (n,) float64
        ``gamma = n_out . u`` [-].
    speed_ratio : float
        ``S`` of the species [-], > 0.
    stream : {"full", "directed", "thermal"}

    Returns
    -------
    (n,) float64
        ``chi(S gamma) / (2 sqrt(pi) S)`` (full), ``max(gamma, 0)`` (directed) or their difference.

    Raises
    ------
    InputError
        An unknown ``stream``, or a speed ratio that is not a finite number > 0.

    Examples
    --------
    >>> incident_number_flux([1.0, 0.5], 7.0, "directed")
    array([1. , 0.5])
    """
    check_stream(stream)
    check_speed_ratio(speed_ratio)
    gamma = np.clip(np.asarray(cos_incidence, dtype=np.float64), -1.0, 1.0)
    return incident(gamma, speed_ratio, stream).number_flux


def diffuse_normal(
    flux: NDArray[np.float64] | float, temperature_ratio: NDArray[np.float64], speed_ratio: float
) -> NDArray[np.float64]:
    """Normal momentum over ``q`` of a Lambertian re-emission of ``flux`` at ``T_r / T = temperature_ratio``.

    Parameters
    ----------
    flux : float or ndarray of float64
        Re-emitted molecules per unit area and time over ``n V`` [-].
    temperature_ratio : ndarray of float64
        ``T_r / T``, re-emission over free-stream temperature [-].
    speed_ratio : float
        ``S`` of the species [-], > 0.

    Returns
    -------
    ndarray of float64
        ``flux sqrt(pi) sqrt(T_r / T) / S`` [-], broadcast over the arguments.

    Examples
    --------
    >>> import numpy as np
    >>> diffuse_normal(1.0, np.array([0.3, 1.0]), 7.0).round(4)
    array([0.1387, 0.2532])
    """
    return flux * _SQRT_PI * np.sqrt(temperature_ratio) / speed_ratio


def rice_mean(x: NDArray[np.float64], alpha_n: NDArray[np.float64], tau_w: NDArray[np.float64]) -> NDArray:
    """Mean reflected normal speed of the CLL kernel at incident normal speed ``x`` (over ``sqrt(2kT/m)``).

    The reflected normal speed follows the Rice distribution with ``nu = sqrt(1 - alpha_n) x`` and
    ``sigma^2 = alpha_n tau_w / 2``; its mean is ``sigma sqrt(pi/2) [(1 + a) i0e(a/2) + a i1e(a/2)]`` with
    ``a = nu^2 / (2 sigma^2)``, and ``nu`` when ``sigma = 0``.

    Parameters
    ----------
    x : ndarray of float64
        Incident normal speed over ``sqrt(2 k T / m)`` [-], >= 0.
    alpha_n : ndarray of float64
        CLL's normal energy accommodation [-], in [0, 1].
    tau_w : ndarray of float64
        ``T_w / T``, wall over free-stream temperature [-].

    Returns
    -------
    ndarray of float64
        Mean reflected normal speed over ``sqrt(2 k T / m)`` [-], broadcast over the arguments.

    References
    ----------
    Rice (1944); Cercignani and Lampis (1971); Lord (1991); Olver et al. (eds.), NIST Digital Library of
    Mathematical Functions, ch. 10 (modified Bessel functions).

    Examples
    --------
    Without accommodation the normal speed is kept; with full accommodation it is the wall's, whatever
    ``x``:

    >>> import numpy as np
    >>> rice_mean(np.array([1.0, 2.0]), np.zeros(2), np.full(2, 0.3))
    array([1., 2.])
    >>> rice_mean(np.array([1.0, 2.0]), np.ones(2), np.ones(2)).round(4)
    array([0.8862, 0.8862])
    """
    sigma_sq = 0.5 * alpha_n * tau_w
    nu_sq = (1.0 - alpha_n) * x * x
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a = nu_sq / (2.0 * sigma_sq)
    # sigma -> 0 (alpha_n = 0 or a cold wall) or a > 1e30: the mean is nu (1 + 1/(4a) + ...) = nu.
    narrow = ~(a <= 1e30)
    a = np.where(narrow, 0.0, a)
    mean = np.sqrt(sigma_sq * (0.5 * np.pi)) * ((1.0 + a) * i0e(0.5 * a) + a * i1e(0.5 * a))
    return np.where(narrow, np.sqrt(nu_sq), mean)


def rice_mean_slope(
    x: NDArray[np.float64], alpha_n: NDArray[np.float64], tau_w: NDArray[np.float64]
) -> NDArray:
    """Derivative of :func:`rice_mean` with respect to ``alpha_n``.

    With ``F(a) = (1 + a) i0e(a/2) + a i1e(a/2)``, ``dF/da = (i0e(a/2) + i1e(a/2)) / 2``, so ``dh/d alpha_n
    = sqrt(pi sigma^2 / 2) [F / (2 alpha_n) - F'(a) x^2 / (tau_w alpha_n^2)]``; ``-x / (2 sqrt(1 -
    alpha_n))`` where the mean is ``nu`` (``sigma -> 0``).

    Parameters
    ----------
    x : ndarray of float64
        Incident normal speed over ``sqrt(2 k T / m)`` [-], >= 0.
    alpha_n : ndarray of float64
        CLL's normal energy accommodation [-], in (0, 1].
    tau_w : ndarray of float64
        ``T_w / T`` [-].

    Returns
    -------
    ndarray of float64
        ``d h / d alpha_n``, broadcast over the arguments.

    Examples
    --------
    >>> x, a, t = np.array([0.5, 2.0]), np.full(2, 0.6), np.full(2, 0.3)
    >>> step = (rice_mean(x, a + 1e-6, t) - rice_mean(x, a - 1e-6, t)) / 2e-6
    >>> bool(np.allclose(rice_mean_slope(x, a, t), step, rtol=1e-7))
    True
    """
    sigma_sq = 0.5 * alpha_n * tau_w
    nu_sq = (1.0 - alpha_n) * x * x
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a = nu_sq / (2.0 * sigma_sq)
        narrow = ~(a <= 1e30)
        a = np.where(narrow, 0.0, a)
        half = 0.5 * a
        zeroth, first = i0e(half), i1e(half)
        f = (1.0 + a) * zeroth + a * first
        slope = 0.5 * (zeroth + first)
        da = -(x * x) / (tau_w * alpha_n * alpha_n)
        value = np.sqrt(sigma_sq * (0.5 * np.pi)) * (f / (2.0 * alpha_n) + slope * da)
        narrow_value = -x / (2.0 * np.sqrt(np.maximum(1.0 - alpha_n, 1e-300)))
    return np.where(narrow, narrow_value, value)


def cll_reflected_normal(
    gamma: NDArray[np.float64],
    alpha_n: NDArray[np.float64],
    tau_w: NDArray[np.float64],
    speed_ratio: float,
    stream: str,
    mean: Callable[..., NDArray] | None = None,
) -> NDArray[np.float64]:
    """Normal momentum of the CLL-reflected molecules over ``q``, per element.

    The CLL normal kernel gives, for an incident normal speed ``v_i``, a reflected normal speed with
    the Rice distribution of parameters ``nu = sqrt(1 - alpha_n) v_i``, ``sigma^2 = alpha_n k T_w / m``
    (:func:`rice_mean` ``h``). Directed: ``2 gamma h(S gamma) / S`` for ``gamma > 0``. Full, with
    ``s = S gamma`` and ``x`` the incident normal speed over ``sqrt(2kT/m)``::

        (2 / (S^2 sqrt(pi))) int_0^inf x exp(-(x - s)^2) h(x) dx

    by a fixed composite Gauss-Legendre rule (``_CLL_NODES`` = 12 nodes per panel, 16 panels). The
    integral is cut to ``[max(0, s - sqrt(40)), s + sqrt(min(s, 0)^2 + 40)]``, beyond which the weight
    is below ``exp(-40)`` of its peak; the window is split into 6 equal panels, and 10 more panels are
    graded geometrically (ratio 4) from ``l = sqrt(alpha_n tau_w / (2 (1 - alpha_n)))``, the scale below
    which ``h`` turns from linear to flat (sharp when ``alpha_n`` is small); breakpoints outside the
    window are clipped to it (empty panels). Against adaptive quadrature at 1e-13 over ``s`` in
    [-30, 40], ``alpha_n`` in [0, 1] (down to 1e-12), ``tau_w`` in [1e-3, 1e3] the worst relative error
    is 2e-12, the level of the reference itself; for ``alpha_n = 0`` (``h(x) = x``, closed form
    ``c_n_inc``) it is below 1e-15 for ``s`` in [0, 40]. Elements are processed in chunks of
    ``_CLL_CHUNK`` to bound memory.

    Parameters
    ----------
    gamma : (n,) float64
        ``gamma = n_out . u`` of each element, in [-1, 1].
    alpha_n : (n,) float64
        CLL's normal energy accommodation of each element [-], in [0, 1].
    tau_w : (n,) float64
        ``T_w / T`` of each element [-].
    speed_ratio : float
        ``S`` of the species [-], > 0.
    stream : {"full", "directed", "thermal"}
        Which incident stream is reflected.
    mean : callable, optional
        ``h(x, alpha_n, tau_w)``; default :func:`rice_mean`. :func:`rice_mean_slope` gives the
        derivative with respect to ``alpha_n`` by the same rule (its nodes held).

    Returns
    -------
    (n,) ndarray of float64
        Normal momentum of the reflected molecules over ``q`` [-].

    References
    ----------
    Cercignani and Lampis (1971); Lord (1991); Walker, Mehta and Koller (2014, CLL drag coefficients);
    Olver et al. (eds.), NIST Digital Library of Mathematical Functions, section 3.5.

    Examples
    --------
    With ``alpha_n = 0`` molecules leave with the normal momentum they brought (``c_n_inc``):

    >>> import numpy as np
    >>> gamma = np.array([1.0, 0.5])
    >>> cll_reflected_normal(gamma, np.zeros(2), np.full(2, 0.3), 7.0, "full").round(4)
    array([2.0204, 0.5204])
    >>> incident(gamma, 7.0).c_n.round(4)
    array([2.0204, 0.5204])
    """
    mean = rice_mean if mean is None else mean
    windward = np.maximum(gamma, 0.0)
    directed = 2.0 * windward * mean(speed_ratio * windward, alpha_n, tau_w) / speed_ratio
    if stream == "directed":
        return directed
    full = np.empty_like(gamma)
    for start in range(0, len(gamma), _CLL_CHUNK):
        part = slice(start, start + _CLL_CHUNK)
        full[part] = _cll_full_integral(speed_ratio * gamma[part], alpha_n[part], tau_w[part], mean)
    full *= 2.0 / (speed_ratio**2 * _SQRT_PI)
    return full - directed if stream == "thermal" else full


def _cll_full_integral(
    s: NDArray[np.float64],
    alpha_n: NDArray[np.float64],
    tau_w: NDArray[np.float64],
    mean: Callable[..., NDArray] = rice_mean,
) -> NDArray[np.float64]:
    """``int_0^inf x exp(-(x - s)^2) h(x) dx`` per element by the rule of :func:`cll_reflected_normal`."""
    half_width = math.sqrt(_CLL_WINDOW_SQ)
    lo = np.maximum(s - half_width, 0.0)
    hi = s + np.sqrt(np.minimum(s, 0.0) ** 2 + _CLL_WINDOW_SQ)
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.sqrt(0.5 * alpha_n * tau_w / (1.0 - alpha_n))
    scale = np.where(np.isfinite(scale), scale, hi)
    uniform = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, _CLL_UNIFORM_PANELS + 1)
    graded = scale[:, None] * 4.0 ** np.arange(_CLL_GRADED_PANELS)
    edges = np.sort(np.clip(np.concatenate([uniform, graded], 1), lo[:, None], hi[:, None]), axis=1)
    left, right = edges[:, :-1], edges[:, 1:]
    used = np.any(right > left, axis=0)  # skip panels that are empty for every element
    left, right = left[:, used, None], right[:, used, None]
    x = 0.5 * (left + right) + 0.5 * (right - left) * _GL_X
    weight = 0.5 * (right - left) * _GL_W
    h = mean(x, alpha_n[:, None, None], tau_w[:, None, None])
    return np.sum(weight * x * np.exp(-((x - s[:, None, None]) ** 2)) * h, axis=(1, 2))


def check_stream(stream: str) -> None:
    """Refuse a stream that is not one of :data:`STREAMS`.

    Parameters
    ----------
    stream : str
        The stream's name.

    Raises
    ------
    InputError
        ``stream`` is not one of :data:`STREAMS`.

    Examples
    --------
    >>> check_stream("thermal")
    >>> check_stream("cold")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: stream 'cold' is unknown; choose one of: full, directed, thermal
    """
    if stream not in STREAMS:
        raise InputError(
            f"stream {stream!r} is unknown",
            hint=f"choose one of: {', '.join(STREAMS)}",
            parameters=("stream",),
        )


def check_speed_ratio(speed_ratio: float) -> None:
    """Refuse a speed ratio that is not a finite number > 0.

    Parameters
    ----------
    speed_ratio : float
        ``S`` [-].

    Raises
    ------
    InputError
        ``speed_ratio`` is not finite, or not > 0.

    Examples
    --------
    >>> check_speed_ratio(7.0)
    >>> check_speed_ratio(0.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: speed_ratio 0.0 must be a finite number > 0
    """
    if not (math.isfinite(speed_ratio) and speed_ratio > 0.0):
        raise InputError(
            f"speed_ratio {speed_ratio!r} must be a finite number > 0", parameters=("speed_ratio",)
        )
