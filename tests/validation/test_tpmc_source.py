"""The TPMC source samplers: the flux-weighted normal speeds exactly, and the inflow flux's limits."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats
from scipy.special import erfc

from sunwind.validation.tpmc_source import flux_normal_speeds, inflow_flux


@pytest.mark.parametrize("s", [-4.0, -1.5, -1.0, -0.4, 0.0, 0.7, 3.0])
def test_flux_normal_sampler_has_the_exact_distribution(s):
    """Kolmogorov-Smirnov against the exact CDF of ``p(x) ~ x exp(-(x - s)^2)``, x > 0."""
    norm = (math.exp(-s * s) + math.sqrt(math.pi) * s * erfc(-s)) / 2

    def cdf(x):
        x = np.asarray(x)
        return (
            (math.exp(-s * s) - np.exp(-((x - s) ** 2))) / 2
            + s * math.sqrt(math.pi) / 2 * (erfc(-s) - erfc(x - s))
        ) / norm

    x = flux_normal_speeds(s, 100_000, np.random.default_rng(7))
    assert len(x) == 100_000 and np.all(x > 0)
    assert stats.kstest(x, cdf).pvalue > 1e-3


def test_inflow_flux_limits():
    """One-sided flux: ``1/(2 sqrt(pi))`` at rest; net ``Gamma(s) - Gamma(-s) = s``; ``~ s`` for s >> 1."""
    assert inflow_flux(0.0) == pytest.approx(1 / (2 * math.sqrt(math.pi)), rel=1e-15)
    for s in (0.3, 1.0, 2.5, 8.0):
        assert inflow_flux(s) - inflow_flux(-s) == pytest.approx(s, rel=1e-12)
    assert inflow_flux(8.0) == pytest.approx(8.0, rel=1e-10)
    assert 0 < inflow_flux(-8.0) < 1e-29
