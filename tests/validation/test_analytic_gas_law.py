"""Checks of the local free-molecular law against the incident-stream formulas written again here.

:func:`local_coefficients` is the drifting Maxwellian's incident pressure and shear plus each model's
re-emission, derived apart from :mod:`sunwind.validation.analytic_gas_law` (the same reference sums the
body closed forms in ``test_analytic_drag.py``).
"""

from __future__ import annotations

import numpy as np
import pytest

from helpers.gas_law import SURFACES, T_INF, local_coefficients
from sunwind.validation.analytic_gas_law import GasLaw, surface_law

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
