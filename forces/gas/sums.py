"""The gas-surface laws summed over species for elements of a few distinct laws, fast, and what they
re-emit diffusely: both read from the laws' :class:`~sunwind.forces.gas.laws.Reemission`.

Each law reduces to ``c_n = a c_n_inc + b N / (n_k V)`` and ``c_t = c c_t_inc`` (plus CLL's exact
reflected normal momentum), with ``a`` (``pressure_scale``) and ``c`` (``shear_scale``) per law and ``b``
(the diffuse re-emission's normal momentum per incident molecule) per law and species; the numba
kernel :func:`sunwind.forces.gas.sum_kernels.species_sums` sums that over species in one pass.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.gas.incident import check_speed_ratio, cll_reflected_normal, diffuse_normal
from sunwind.forces.gas.laws import GasSurfaces, reemission
from sunwind.forces.gas.sum_kernels import species_sums
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges


def summed_coefficients(
    surfaces: GasSurfaces,
    law: NDArray[np.int64],
    cos_incidence: NDArray[np.float64],
    speed_ratios: ArrayLike,
    weights: ArrayLike,
    temperature_K: float,
    flux_weights: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Sum the coefficients of both streams over species with weights, for elements of few distinct laws.

    The weighted sum over species ``k`` of :func:`~sunwind.forces.gas.laws.panel_coefficients`
    (``"directed"`` and ``"full"`` minus ``"directed"``), on parallel threads (rows do not depend on the
    thread count).

    Parameters
    ----------
    surfaces : GasSurfaces
        The distinct laws, (n_laws,).
    law : (n,) int64
        Row of ``surfaces`` of each element.
    cos_incidence : (n,) float64
        ``gamma = n_out . u`` [-].
    speed_ratios : (n_species,) array_like
        ``S_k`` of each species [-], > 0.
    weights : (n_species,) array_like
        ``w_k``, e.g. the species' dynamic pressure ``q_k`` [Pa].
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    flux_weights : (n_laws, n_species, m) float64, optional
        Weights of each species' full-stream number flux over ``n_k V``
        (:func:`~sunwind.forces.gas.incident.incident_number_flux`).

    Returns
    -------
    (n, 4 + m) float64
        ``sum_k w_k (c_n, c_t)`` of the directed stream, the same of the thermal stream, and
        ``sum_k flux_weights[law, k] N_k / (n_k V)`` of the full stream.

    Raises
    ------
    InputError
        A speed ratio that is not a finite number > 0, or ``law`` and ``cos_incidence`` not (n,) arrays of
        valid rows and finite values.

    Examples
    --------
    Head-on at ``S = 7``, a fully accommodating Sentman plate and a mirror:

    >>> import numpy as np
    >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
    >>> surfaces = GasSurfaces.of({"code": [MODEL_CODES["sentman"], MODEL_CODES["specular"]],
    ...     "energy_accommodation": 1.0, "normal_accommodation": 1.0, "tangential_accommodation": 1.0,
    ...     "wall_temperature_K": 300.0})
    >>> summed_coefficients(surfaces, np.array([0, 1]), np.array([1.0, 1.0]), [7.0], [1.0], 1000.0).round(4)
    array([[2.1387, 0.    , 0.0204, 0.    ],
           [4.    , 0.    , 0.0408, 0.    ]])
    """
    ratios = np.atleast_1d(np.asarray(speed_ratios, dtype=np.float64))
    weight = np.broadcast_to(np.asarray(weights, dtype=np.float64), ratios.shape)
    for ratio in ratios:
        check_speed_ratio(float(ratio))
    laws = [reemission(surfaces, float(ratio), temperature_K) for ratio in ratios]
    row = np.ascontiguousarray(law, dtype=np.int64)
    gamma = np.clip(np.ascontiguousarray(cos_incidence, dtype=np.float64), -1.0, 1.0)
    if (
        row.shape != gamma.shape
        or np.any((row < 0) | (row >= len(surfaces)))
        or not np.all(np.isfinite(gamma))
    ):
        raise InputError(
            "law rows and cos_incidence must be (n,) arrays of valid rows and finite values",
            parameters=("law", "cos_incidence"),
        )
    diffuse = np.column_stack(
        [one.diffuse_share * diffuse_normal(1.0, one.temperature_ratio, one.speed_ratio) for one in laws]
    )
    flux = np.zeros((len(surfaces), len(ratios), 0)) if flux_weights is None else flux_weights
    out = np.empty((len(gamma), 4 + flux.shape[2]))
    scales = (laws[0].pressure_scale, diffuse, laws[0].shear_scale)
    args = (row, gamma, ratios, np.ascontiguousarray(weight), *scales)
    map_ranges(lambda lo, hi: species_sums(*args, np.ascontiguousarray(flux), out, lo, hi), len(gamma), 2048)
    if laws[0].cll_alpha_n is not None:  # CLL's reflected normal momentum, by the reference's quadrature
        cll = np.flatnonzero(np.isfinite(laws[0].cll_alpha_n[row]))
        for one, w in zip(laws, weight, strict=True):
            normal = (gamma[cll], one.cll_alpha_n[row[cll]], one.cll_tau_w[row[cll]], one.speed_ratio)
            directed = cll_reflected_normal(*normal, "directed")
            out[cll, 0] += w * directed
            out[cll, 2] += w * (cll_reflected_normal(*normal, "full") - directed)
    return out


def diffuse_emission(
    surfaces: GasSurfaces, speed_ratio: float, temperature_K: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Share of the incident molecules re-emitted diffusely (Lambertian), and their temperature.

    As the molecular exchange carries them (:attr:`~sunwind.forces.gas.laws.Reemission.emission_share`): 1
    (sentman, dria), ``sigma_n`` (schaaf-chambre), 0 (cll and specular, whose molecules the chains follow).
    For sentman, dria and schaaf-chambre the diffuse term of the laws' ``c_n`` is exactly
    ``share N m sqrt(pi k T_r / (2 m)) / q`` with ``N`` the incident number flux, for every stream.

    Parameters
    ----------
    surfaces : GasSurfaces
        Gas-surface parameters of ``n`` elements.
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.

    Returns
    -------
    share : (n,) ndarray of float64
        Share of the incident molecules re-emitted diffusely [-].
    temperature_K : (n,) ndarray of float64
        Their temperature ``T_r`` [K] (0 where none are).

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
    >>> surfaces = GasSurfaces.of({"code": [MODEL_CODES["sentman"], MODEL_CODES["specular"]],
    ...     "energy_accommodation": 1.0, "normal_accommodation": 1.0, "tangential_accommodation": 1.0,
    ...     "wall_temperature_K": 300.0})
    >>> diffuse_emission(surfaces, 7.0, 1000.0)
    (array([1., 0.]), array([300.,   0.]))
    """
    law = reemission(surfaces, speed_ratio, temperature_K)
    return law.emission_share, law.emission_temperature_K
