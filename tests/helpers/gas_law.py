"""The local free-molecular law written again, apart from the solver and the closed forms: the drifting
Maxwellian's incident pressure and shear plus each model's re-emission, and the surfaces the gas tests use."""

from __future__ import annotations

import math

import numpy as np
from scipy.special import erfc

from sunwind.validation.analytic_gas_law import GasLaw
from sunwind.validation.gas_checks import SURFACES as VALIDATION_SURFACES

SQRT_PI = math.sqrt(math.pi)
T_INF = 1000.0
SURFACES = {**VALIDATION_SURFACES, "dria": GasLaw("dria", energy_accommodation=0.8, wall_temperature_K=500.0)}


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
