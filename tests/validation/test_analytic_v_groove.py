"""The V-groove closed form in its limits and under the mirror x -> -x."""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.validation.analytic_v_groove import v_groove_srp


def test_v_groove_closed_form_limits():
    """psi = 0 retro-reflects all (|F| = (1 + rho^2) P A); psi = 45 deg is one mirror of area w L."""
    pressure = 1361.0 / 299_792_458.0
    for rho in (1.0, 0.7):
        straight = v_groove_srp(2.0, 5.0, 0.0, rho)
        assert np.allclose(straight.force_N, [0.0, 0.0, -(1 + rho**2) * pressure * np.sqrt(2) * 10.0])
        assert np.allclose(straight.torque_Nm, 0.0)
        oblique = v_groove_srp(2.0, 5.0, 45.0, rho)
        u = np.array([1.0, 0.0, 1.0]) / np.sqrt(2)
        assert np.allclose(oblique.force_N, -(1 + rho) * pressure * 10.0 * u)
        assert oblique.force_N @ [1.0, 0.0, -1.0] == pytest.approx(0.0, abs=1e-20)
    mirrored = v_groove_srp(1.0, 3.0, -20.0, 0.8)
    plain = v_groove_srp(1.0, 3.0, 20.0, 0.8)
    assert np.allclose(mirrored.force_N * [-1, 1, 1], plain.force_N)
    assert np.allclose(mirrored.torque_Nm, -plain.torque_Nm)
    with pytest.raises(ValueError):
        v_groove_srp(1.0, 3.0, 50.0)
