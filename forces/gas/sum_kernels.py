"""Numba kernels of the gas-surface laws summed over species, and the force per unit area they give each
group of sides (:mod:`sunwind.forces.gas.sums`, :mod:`sunwind.forces.gas.panel`).

:func:`species_sums` is the fast twin of :func:`sunwind.forces.gas.laws.panel_coefficients` for every
law but the reflected normal momentum of CLL, in the form each law reduces to (its
:class:`~sunwind.forces.gas.laws.Reemission`)::

    c_n = a c_n_inc + b N / (n_k V),    c_t = c c_t_inc,

with ``a``, ``c`` per law and ``b`` per law and species. :func:`group_stresses` turns the summed
coefficients into the force per unit area of each group. Kernels taking ``lo, hi`` write rows ``lo:hi``
of their outputs only, so threads given disjoint ranges produce the same bits as one.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import NDArray

_SQRT_PI = math.sqrt(math.pi)
_INV_SQRT_PI = 1.0 / _SQRT_PI
#: Above this ``s``, ``erfc(-s) = 2 - erfc(s)`` rounds to 2: ``erfc(6) = 2.2e-17`` is below half the
#: spacing of doubles at 2.
_ERFC_IS_TWO = 6.0


@numba.njit(cache=True, nogil=True)
def species_sums(
    law: NDArray[np.int64],
    gamma: NDArray[np.float64],
    speed_ratio: NDArray[np.float64],
    weight: NDArray[np.float64],
    pressure_scale: NDArray[np.float64],
    diffuse: NDArray[np.float64],
    shear_scale: NDArray[np.float64],
    flux_weight: NDArray[np.float64],
    out: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """Species sums of the directed and thermal coefficients of elements ``lo:hi``, into ``out``.

    Parameters
    ----------
    law : (n,) int64
        Law of each element, a row of the per-law arrays.
    gamma : (n,) float64
        ``n . u`` [-], in [-1, 1].
    speed_ratio, weight : (n_species,) float64
        ``S_k`` [-] and the weight ``w_k`` of each species' coefficients.
    pressure_scale : (n_laws,) float64
        ``a`` of each law [-].
    diffuse : (n_laws, n_species) float64
        ``b``: normal momentum of the diffuse re-emission per incident molecule, over ``q / (n_k V)``.
    shear_scale : (n_laws,) float64
        ``c`` of each law [-].
    flux_weight : (n_laws, n_species, m) float64
        Weights of the full stream's number flux ``N / (n_k V)``.
    out : (n, 4 + m) float64
        ``sum_k w_k (c_n, c_t)`` of the directed stream, the same of the thermal stream, and
        ``sum_k flux_weight[law, k] N_k / (n_k V)`` of the full stream.
    lo, hi : int
        The elements to compute, ``lo:hi``; other rows of ``out`` are left as they are.

    Examples
    --------
    One species at ``S = 7``, law ``a = c = 1``, ``b = 0``, head-on and edge-on (the directed stream
    misses the edge):

    >>> import numpy as np
    >>> out = np.empty((2, 4))
    >>> species_sums(np.array([0, 0]), np.array([1.0, 0.0]), np.array([7.0]), np.array([1.0]),
    ...     np.array([1.0]), np.array([[0.0]]), np.array([1.0]), np.zeros((1, 1, 0)), out, 0, 2)
    >>> out.round(4)
    array([[2.    , 0.    , 0.0204, 0.    ],
           [0.    , 0.    , 0.0102, 0.0806]])
    """
    n_species, m = speed_ratio.shape[0], flux_weight.shape[2]
    # the divisions of the incident stream (module Notes of sunwind.forces.gas.laws), as factors
    pressure_factor = 1.0 / (speed_ratio * speed_ratio)
    flux_factor = 1.0 / (2.0 * _SQRT_PI * speed_ratio)
    shear_factor = 1.0 / (speed_ratio * _SQRT_PI)
    for i in range(lo, hi):
        g, row = gamma[i], law[i]
        t = math.sqrt(max(1.0 - g * g, 0.0))
        w = max(g, 0.0)
        a, c = pressure_scale[row], shear_scale[row]
        directed_n_sum = directed_t_sum = thermal_n_sum = thermal_t_sum = 0.0
        for j in range(m):
            out[i, 4 + j] = 0.0
        for k in range(n_species):
            b, q = diffuse[row, k], weight[k]
            directed_n = a * (2.0 * w * w) + b * w
            directed_t = c * (2.0 * w * t)
            s = speed_ratio[k] * g
            gauss = math.exp(-s * s)
            one_plus_erf = 2.0 if s > _ERFC_IS_TWO else math.erfc(-s)
            chi = max(gauss + _SQRT_PI * s * one_plus_erf, 0.0)
            pressure = max(s * _INV_SQRT_PI * gauss + (0.5 + s * s) * one_plus_erf, 0.0)
            flux = chi * flux_factor[k]
            full_n = a * (pressure * pressure_factor[k]) + b * flux
            full_t = c * (t * chi * shear_factor[k])
            directed_n_sum += q * directed_n
            directed_t_sum += q * directed_t
            thermal_n_sum += q * (full_n - directed_n)
            thermal_t_sum += q * (full_t - directed_t)
            for j in range(m):
                out[i, 4 + j] += flux_weight[row, k, j] * flux
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = (
            directed_n_sum,
            directed_t_sum,
            thermal_n_sum,
            thermal_t_sum,
        )


@numba.njit(cache=True, nogil=True)
def group_stresses(
    gamma: NDArray[np.float64],
    sums: NDArray[np.float64],
    normals: NDArray[np.float64],
    u: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Force per unit area [Pa] of the directed and the thermal stream on each group.

    Group ``g`` of normal ``normals[g]`` and ``gamma[g] = n . u`` takes ``-c_n n + c_t t_hat`` with its
    :func:`species_sums` row ``sums[g]`` (weights ``q_k`` [Pa]); ``t_hat = -(u - gamma n) / |...|``, none
    where that length is below 1e-12.

    Parameters
    ----------
    gamma : (n_groups,) float64
        ``n . u`` of each group [-].
    sums : (n_groups, 4 + m) float64
        :func:`species_sums` of each group, weighted by ``q_k`` [Pa]; the first four columns are read.
    normals : (n_groups, 3) float64
        Outward unit normal of each group.
    u : (3,) float64
        Unit flow vector ``v_rel / |v_rel|``.

    Returns
    -------
    (n_groups, 6) ndarray of float64
        Force per unit area of the directed stream (3 columns) and of the thermal stream (3) [Pa].

    Examples
    --------
    >>> import numpy as np
    >>> group_stresses(np.array([1.0]), np.array([[2.0, 0.0, 0.02, 0.0]]), np.array([[1.0, 0.0, 0.0]]),
    ...     np.array([1.0, 0.0, 0.0])).round(3)
    array([[-2.  ,  0.  ,  0.  , -0.02,  0.  ,  0.  ]])
    """
    out = np.empty((gamma.shape[0], 6))
    for g in range(gamma.shape[0]):
        n0, n1, n2 = normals[g, 0], normals[g, 1], normals[g, 2]
        a0, a1, a2 = u[0] - gamma[g] * n0, u[1] - gamma[g] * n1, u[2] - gamma[g] * n2
        length = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        t0 = t1 = t2 = 0.0
        if length > 1e-12:
            t0, t1, t2 = -a0 / length, -a1 / length, -a2 / length
        pn, pt, hn, ht = sums[g, 0], sums[g, 1], sums[g, 2], sums[g, 3]
        out[g, 0], out[g, 1], out[g, 2] = -pn * n0 + pt * t0, -pn * n1 + pt * t1, -pn * n2 + pt * t2
        out[g, 3], out[g, 4], out[g, 5] = -hn * n0 + ht * t0, -hn * n1 + ht * t1, -hn * n2 + ht * t2
    return out
