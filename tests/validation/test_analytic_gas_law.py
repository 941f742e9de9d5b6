"""Checks of the local free-molecular law against the incident-stream formulas written again here.

:func:`local_coefficients` is the drifting Maxwellian's incident pressure and shear plus each model's
re-emission, derived apart from :mod:`sunwind.validation.analytic_gas_law` (the same reference sums the
body closed forms in ``test_analytic_drag.py``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import erfc

from sunwind.validation.analytic_gas_law import GasLaw, surface_law

SQRT_PI = math.sqrt(math.pi)
T_INF = 1000.0
SURFACES = {
    "sentman": GasLaw("sentman", energy_accommodation=0.9, wall_temperature_K=300.0),
    "dria": GasLaw("dria", energy_accommodation=0.8, wall_temperature_K=500.0),
    "schaaf-chambre": GasLaw("schaaf-chambre", normal_accommodation=0.7, tangential_accommodation=0.8),
    "specular": GasLaw("specular"),
}


# ------------------------------------------------------------------- the local law, written again


def local_coefficients(surface: GasLaw, speed_ratio: float, gamma: np.ndarray):
    """``(c_n, c_t)`` from the incident drifting Maxwellian and the models' re-emission."""
    s = speed_ratio * gamma
    t = np.sqrt(np.maximum(1 - gamma**2, 0))
    chi = np.exp(-s * s) + SQRT_PI * s * erfc(-s)
    c_n_inc = (s / SQRT_PI * np.exp(-s * s) + (0.5 + s * s) * erfc(-s)) / speed_ratio**2
    c_t_inc = t * chi / (speed_ratio * SQRT_PI)

    def diffuse(temperature_ratio):
        return chi * math.sqrt(temperature_ratio) / (2 * speed_ratio**2)

    tau_w = surface.wall_temperature_K / T_INF
    alpha_e = surface.energy_accommodation
    if surface.model == "sentman":
        return c_n_inc + diffuse(alpha_e * tau_w + (1 - alpha_e) * 2 / 3 * speed_ratio**2), c_t_inc
    if surface.model == "dria":
        return c_n_inc + diffuse(alpha_e * tau_w + (1 - alpha_e) * speed_ratio**2 / 2), c_t_inc
    if surface.model == "schaaf-chambre":
        sigma_n, sigma_t = surface.normal_accommodation, surface.tangential_accommodation
        return (2 - sigma_n) * c_n_inc + sigma_n * diffuse(tau_w), sigma_t * c_t_inc
    return 2 * c_n_inc, 0 * c_t_inc


# -------------------------------------------------------------------------------- the local law


@pytest.mark.parametrize("model", list(SURFACES))
@pytest.mark.parametrize("speed_ratio", [0.5, 3.0, 15.0])
def test_surface_law_is_the_incident_stream_plus_reemission(model, speed_ratio):
    gamma = np.linspace(-1, 1, 201)
    law = surface_law(SURFACES[model], speed_ratio, T_INF)
    c_n, c_t = law.coefficients(gamma)
    c_n_ref, c_t_ref = local_coefficients(SURFACES[model], speed_ratio, gamma)
    # (the law sums terms that partly cancel at large negative s: compared on the scale of max c_n)
    np.testing.assert_allclose(c_n, c_n_ref, rtol=1e-12, atol=1e-15 * c_n.max())
    np.testing.assert_allclose(c_t, c_t_ref, rtol=1e-12, atol=1e-15 * c_n.max())
    # directed = the hyperthermal law, thermal = full - directed
    directed = surface_law(SURFACES[model], speed_ratio, T_INF, "directed").coefficients(gamma)
    thermal = surface_law(SURFACES[model], speed_ratio, T_INF, "thermal").coefficients(gamma)
    for k in range(2):
        np.testing.assert_allclose(directed[k] + thermal[k], (c_n, c_t)[k], rtol=0, atol=1e-14 * c_n.max())
    assert np.all(directed[0][gamma <= 0] == 0) and np.all(directed[1][gamma <= 0] == 0)


def test_cll_has_no_closed_form_here():
    with pytest.raises(ValueError, match="model"):
        surface_law(GasLaw("cll"), 2.0, T_INF)
