"""The free stream of the TPMC tracer: one species' drifting Maxwellian and its exact inflow samplers.

:mod:`sunwind.validation.tpmc` launches its molecules through the faces of a box round the model with
these samplers. Like the tracer, the module imports nothing from ``forces``.

Notes
-----
**Free stream** (METHOD.md "Free-molecular flow"). ``u = v_rel / |v_rel|`` is the flow direction in
the body frame; the gas moves relative to the body with bulk velocity ``U = -V u`` and temperature
``T``; molecules of mass ``m`` [kg], number density ``n`` [m^-3]. With ``c_m = sqrt(2 k T / m)`` the
most probable thermal speed, the velocity distribution is the drifting Maxwellian
``f(v) = n / (pi^(3/2) c_m^3) exp(-|v - U|^2 / c_m^2)`` and the speed ratio is ``S = V / c_m``.

**Source.** Molecules enter an axis-aligned box, the model's bounding box grown on every side by a
small share of the model half-size (:mod:`sunwind.validation.tpmc`), through its six faces. There
are no collisions, so the molecules inside the box are exactly those that crossed its boundary
inward, and a molecule that never meets the body simply passes. Through a face of area ``A`` with
inward unit normal ``e`` and normal speed ratio ``s = (U . e) / c_m`` the inward number flux is the
exact half-range integral

    Gamma(s) = n c_m / (2 sqrt(pi)) [exp(-s^2) + sqrt(pi) s erfc(-s)]     [m^-2 s^-1],

and the total inflow rate is ``N_dot = sum_faces A Gamma(s)`` [1/s]. Each molecule of a batch of
``N`` carries the weight ``N_dot / N`` [1/s]; its face is drawn with probability ``A Gamma / N_dot``
(multinomially), its entry point uniformly on the face. Its velocity has the flux-weighted
half-range Maxwellian distribution of that face: tangential components ``U_t + c_m / sqrt(2) N(0, 1)``,
and normal component ``c_m x`` with ``x > 0`` drawn exactly from ``p(x) ~ x exp(-(x - s)^2)`` by
rejection (:func:`flux_normal_speeds`):

- ``s >= 0``: with ``y = x - s``, ``p ~ (y + s) exp(-y^2)`` on ``y > -s``; propose from
  ``(|y| + s) exp(-y^2)`` on the whole line, the mixture of ``|y| exp(-y^2)`` (weight 1,
  ``|y| = sqrt(-ln U)``, random sign) and ``s exp(-y^2)`` (weight ``s sqrt(pi)``, ``y ~ N(0, 1/2)``);
  accept when ``y > -s`` with probability ``(y + s) / (|y| + s)``. Efficiency ``>= 1/2``.
- ``-1 < s < 0``: with ``a = -s`` and ``y = x + a``, ``p ~ (y - a) exp(-y^2)`` on ``y > a``; propose
  the tail ``y = sqrt(a^2 - ln U)`` of ``y exp(-y^2)`` and accept with probability ``(y - a) / y``.
- ``s <= -1``: ``p ~ x exp(-2 a x) exp(-x^2)``; propose ``x ~ Gamma(2, 1 / (2 a))`` and accept with
  probability ``exp(-x^2)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["BOLTZMANN_J_K", "SpeciesStream", "flux_normal_speeds", "inflow_flux"]

#: Boltzmann constant [J/K] (exact, SI 2019).
BOLTZMANN_J_K = 1.380649e-23


@dataclass(frozen=True)
class SpeciesStream:
    """The free stream of one gas species relative to the body (module Notes, "Free stream").

    Attributes
    ----------
    speed_m_s : float
        ``V = |v_rel|`` [m/s], >= 0 (0 is a gas at rest).
    temperature_K : float
        Free-stream (translational) temperature ``T`` [K], > 0.
    number_density_m3 : float
        Number density ``n`` of the species [m^-3], >= 0.
    mass_kg : float
        Molecular mass ``m`` of the species [kg], > 0.

    Examples
    --------
    >>> oxygen = SpeciesStream(7500.0, 1000.0, 1e15, 16 * 1.66054e-27)
    >>> oxygen.speed_m_s
    7500.0
    """

    speed_m_s: float
    temperature_K: float
    number_density_m3: float
    mass_kg: float


def inflow_flux(s: float) -> float:
    """Inward number flux of a drifting Maxwellian through a plane, over ``n c_m`` [-].

    ``Gamma / (n c_m) = [exp(-s^2) + sqrt(pi) s erfc(-s)] / (2 sqrt(pi))`` with ``s`` the drift
    velocity's component along the plane's inward normal over ``c_m = sqrt(2 k T / m)``.

    Parameters
    ----------
    s : float
        Drift component along the inward normal over ``c_m`` [-]; negative when the gas drifts away.

    Returns
    -------
    float
        ``Gamma / (n c_m)`` [-]: ``1 / (2 sqrt(pi))`` for a gas at rest, tending to ``s`` for large ``s``.

    Examples
    --------
    >>> round(inflow_flux(0.0) * 2 * math.sqrt(math.pi), 12), round(inflow_flux(5.0), 6)
    (1.0, 5.0)
    """
    return (math.exp(-s * s) + math.sqrt(math.pi) * s * math.erfc(-s)) / (2.0 * math.sqrt(math.pi))


def flux_normal_speeds(s: float, count: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """Draw ``count`` exact samples ``x > 0`` of ``p(x) ~ x exp(-(x - s)^2)``, by rejection (module Notes).

    The normal velocity component, over ``c_m``, of molecules of a drifting Maxwellian crossing a
    plane in the direction of its normal, when the drift component along it over ``c_m`` is ``s``.

    Parameters
    ----------
    s : float
        Drift component along the plane's normal over ``c_m`` [-].
    count : int
        Number of samples.
    rng : numpy.random.Generator
        Source of the random numbers.

    Returns
    -------
    (count,) float64
        Normal speeds over ``c_m`` [-], all > 0.

    Examples
    --------
    >>> x = flux_normal_speeds(0.0, 5, np.random.default_rng(0))
    >>> x.shape, bool((x > 0).all())
    ((5,), True)
    """
    out: list[NDArray[np.float64]] = []
    need = count
    while need > 0:
        k = 2 * need + 16
        if s >= 0.0:
            pick_rayleigh = rng.random(k) * (1.0 + s * math.sqrt(math.pi)) < 1.0
            rayleigh = np.sqrt(-np.log1p(-rng.random(k))) * np.where(rng.random(k) < 0.5, -1.0, 1.0)
            y = np.where(pick_rayleigh, rayleigh, rng.standard_normal(k) / math.sqrt(2.0))
            accept = (y > -s) & (rng.random(k) * (np.abs(y) + s) < y + s)
            x = y[accept] + s
        elif s > -1.0:
            a = -s
            y = np.sqrt(a * a - np.log1p(-rng.random(k)))
            x = (y - a)[rng.random(k) * y < y - a]
        else:
            a = -s
            x = rng.gamma(2.0, 1.0 / (2.0 * a), k)
            x = x[rng.random(k) < np.exp(-x * x)]
        x = x[:need]
        out.append(x)
        need -= len(x)
    return np.concatenate(out) if out else np.zeros(0)
