"""Knocke's Earth albedo and emissivity: hand-computed values at the equator and the poles, the seasonal
symmetries, the global and annual means, and the range [0, 1]."""

import numpy as np
import pytest

from sunwind.forces.planet.knocke import (
    REFERENCE_EPOCH_JD,
    YEAR_DAYS,
    knocke_albedo,
    knocke_emissivity,
)

T0 = 2444960.5  # 1981 December 22, 0h (Knocke's reference epoch), written out here on purpose
HALF_YEAR = 365.25 / 2
POLES_AND_EQUATOR = np.array([np.pi / 2, 0.0, -np.pi / 2])


def test_the_reference_epoch_and_period():
    assert REFERENCE_EPOCH_JD == T0
    assert YEAR_DAYS == 365.25


def test_values_at_the_reference_epoch():
    """cos w(t - t0) = 1, sin = 0; at the north pole P1 = 1, P2 = 1; at the equator P1 = 0, P2 = -1/2;
    at the south pole P1 = -1, P2 = 1."""
    albedo = [
        0.34 + 0.10 * 1 + 0.29 * 1,  # north pole: 0.73
        0.34 + 0.10 * 0 + 0.29 * -0.5,  # equator: 0.195
        0.34 + 0.10 * -1 + 0.29 * 1,  # south pole: 0.53
    ]
    emissivity = [
        0.68 - 0.07 * 1 - 0.18 * 1,  # north pole: 0.43
        0.68 - 0.07 * 0 - 0.18 * -0.5,  # equator: 0.77
        0.68 - 0.07 * -1 - 0.18 * 1,  # south pole: 0.57
    ]
    assert knocke_albedo(POLES_AND_EQUATOR, T0) == pytest.approx(albedo, abs=1e-15)
    assert knocke_emissivity(POLES_AND_EQUATOR, T0) == pytest.approx(emissivity, abs=1e-15)
    assert albedo == pytest.approx([0.73, 0.195, 0.53]) and emissivity == pytest.approx([0.43, 0.77, 0.57])


def test_values_half_a_year_later():
    """cos w(t - t0) = cos(pi) = -1: the seasonal term changes sign, the poles trade places."""
    albedo = [
        0.34 - 0.10 * 1 + 0.29 * 1,  # north pole: 0.53
        0.34 - 0.10 * 0 + 0.29 * -0.5,  # equator: 0.195
        0.34 - 0.10 * -1 + 0.29 * 1,  # south pole: 0.73
    ]
    emissivity = [
        0.68 + 0.07 * 1 - 0.18 * 1,  # north pole: 0.57
        0.68 + 0.07 * 0 - 0.18 * -0.5,  # equator: 0.77
        0.68 + 0.07 * -1 - 0.18 * 1,  # south pole: 0.43
    ]
    t = T0 + HALF_YEAR
    assert knocke_albedo(POLES_AND_EQUATOR, t) == pytest.approx(albedo, abs=1e-14)
    assert knocke_emissivity(POLES_AND_EQUATOR, t) == pytest.approx(emissivity, abs=1e-14)


def test_a_mid_latitude_value_a_quarter_year_later():
    """At 30 deg north: sin = 1/2, P2 = (3/4 - 1)/2 = -1/8; a quarter year on cos = 0, so P1 drops out."""
    t = T0 + 365.25 / 4
    assert knocke_albedo(np.radians([30.0]), t)[0] == pytest.approx(0.34 + 0.29 * -0.125, abs=1e-14)
    assert knocke_emissivity(np.radians([30.0]), t)[0] == pytest.approx(0.68 - 0.18 * -0.125, abs=1e-14)


@pytest.mark.parametrize("model", [knocke_albedo, knocke_emissivity])
def test_symmetries(model):
    phi = np.linspace(-np.pi / 2, np.pi / 2, 37)
    for t in T0 + np.array([0.0, 17.3, 100.0, 250.5, 9000.0]):
        # half a year on, the hemispheres trade places; a year on, it repeats
        assert model(phi, t + HALF_YEAR) == pytest.approx(model(-phi, t), abs=1e-12)
        assert model(phi, t + 365.25) == pytest.approx(model(phi, t), abs=1e-12)
        # the seasonal term is a cosine from the solstice (c2 = k2 = 0): even about t0
        assert model(phi, 2 * T0 - t) == pytest.approx(model(phi, t), abs=1e-12)
    # at the equinoxes (a quarter year either side of t0) the hemispheres are alike
    for t in (T0 + 365.25 / 4, T0 - 365.25 / 4):
        assert model(phi, t) == pytest.approx(model(-phi, t), abs=1e-12)


@pytest.mark.parametrize(("model", "mean"), [(knocke_albedo, 0.34), (knocke_emissivity, 0.68)])
def test_the_global_mean_is_the_constant_term_at_every_instant(model, mean):
    """Area-weighted over the sphere (weight cos phi), P1(sin phi) and P2(sin phi) average to zero, so the
    global mean is a0 (e0) whatever the season: Gauss-Legendre quadrature in latitude."""
    nodes, weights = np.polynomial.legendre.leggauss(48)
    phi = nodes * np.pi / 2
    for t in T0 + np.linspace(0.0, 365.25, 13):
        global_mean = np.sum(weights * np.cos(phi) * model(phi, t)) * (np.pi / 2) / 2
        assert global_mean == pytest.approx(mean, abs=1e-12)


@pytest.mark.parametrize(
    ("model", "mean", "p2"), [(knocke_albedo, 0.34, 0.29), (knocke_emissivity, 0.68, -0.18)]
)
def test_the_annual_mean_drops_the_seasonal_term(model, mean, p2):
    """Averaged over a year the cosine vanishes: a0 + a2 P2(sin phi); uniform samples of a period are
    exact for a sinusoid."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, 19)
    t = T0 + 3.0 + np.arange(64) * 365.25 / 64
    annual = model(phi[:, None], t[None, :]).mean(axis=1)
    x = np.sin(phi)
    assert annual == pytest.approx(mean + p2 * (3 * x**2 - 1) / 2, abs=1e-12)


@pytest.mark.parametrize("model", [knocke_albedo, knocke_emissivity])
def test_values_lie_in_zero_one_and_arrays_keep_their_shape(model):
    phi = np.linspace(-np.pi / 2, np.pi / 2, 181)
    t = T0 + np.linspace(0.0, 2 * 365.25, 97)
    values = model(phi[:, None], t[None, :])
    assert values.shape == (181, 97)
    assert np.all((values >= 0.0) & (values <= 1.0))
    grid = np.radians([[10.0, -20.0], [45.0, 80.0]])
    assert model(grid, T0 + 5.0).shape == (2, 2)
    assert model(grid, T0 + 5.0)[1, 0] == pytest.approx(model(np.radians([45.0]), T0 + 5.0)[0])
    assert np.ndim(model(0.3, T0)) == 0
