"""The TPMC re-emission kernels: Maxwell energy accommodation per molecule and Lord's CLL moments."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sunwind.validation.tpmc_kernels import cll_reemission, maxwell_reemission
from sunwind.validation.tpmc_source import BOLTZMANN_J_K

#: Standard errors a sample mean may lie from the exact value (as in test_tpmc.py).
Z = 5.0
#: Atomic oxygen [kg] and a cool wall [K].
MASS = 16 * 1.66053906660e-27
T_WALL = 300.0


def test_maxwell_energy_accommodation_per_molecule():
    """Diffuse re-emission leaves with ``alpha_E 2 k T_w + (1 - alpha_E) E_in`` per molecule, outward."""
    rng = np.random.default_rng(3)
    k = 400_000
    normal = np.tile([0.0, 0.0, 1.0], (k, 1))
    v_in = np.tile([3000.0, 1000.0, -6000.0], (k, 1))
    wall_c2 = np.full(k, 2 * BOLTZMANN_J_K * T_WALL / MASS)
    e_in = 0.5 * MASS * float(v_in[0] @ v_in[0])
    for alpha in (1.0, 0.6, 0.0):
        out = maxwell_reemission(v_in, normal, np.ones(k), wall_c2, np.full(k, alpha), rng)
        energy = 0.5 * MASS * np.einsum("ij,ij->i", out, out)
        expected = alpha * 2 * BOLTZMANN_J_K * T_WALL + (1 - alpha) * e_in
        assert np.all(out[:, 2] > 0)
        assert energy.mean() == pytest.approx(expected, abs=Z * energy.std() / math.sqrt(k))
    specular = maxwell_reemission(v_in, normal, np.zeros(k), wall_c2, np.ones(k), rng)
    np.testing.assert_array_equal(specular, np.tile([3000.0, 1000.0, 6000.0], (k, 1)))


def test_cll_moments():
    """Lord's CLL: ``E[u_n^2] = alpha_n + (1 - alpha_n) u_i^2`` and ``E[v_t] = (1 - sigma_t) v_t,in``."""
    rng = np.random.default_rng(4)
    k, alpha_n, sigma_t = 400_000, 0.35, 0.7
    normal = np.tile([0.0, 0.0, 1.0], (k, 1))
    c_w2 = 2 * BOLTZMANN_J_K * T_WALL / MASS
    v_in = np.tile([3000.0, 1000.0, -6000.0], (k, 1))
    out = cll_reemission(v_in, normal, np.full(k, c_w2), np.full(k, alpha_n), np.full(k, sigma_t), rng)
    assert np.all(out[:, 2] >= 0)
    un2 = out[:, 2] ** 2 / c_w2
    assert un2.mean() == pytest.approx(alpha_n + (1 - alpha_n) * 6000.0**2 / c_w2, abs=Z * un2.std() / k**0.5)
    for axis, v_t in ((0, 3000.0), (1, 1000.0)):
        component = out[:, axis]
        assert component.mean() == pytest.approx((1 - sigma_t) * v_t, abs=Z * component.std() / k**0.5)
