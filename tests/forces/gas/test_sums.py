"""The fast species sums of the gas-surface laws against the reference panel_coefficients."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from sunwind.forces.gas import (
    MODEL_CODES,
    GasSurfaces,
    incident_number_flux,
    panel_coefficients,
    summed_coefficients,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import using_threads

T_INF = 1000.0  # free-stream temperature [K]

#: (model, alpha_E, sigma_n or alpha_n, sigma_t, T_w): every model, accommodation at its limits too
LAWS = [
    ("sentman", 1.0, 0.0, 0.0, 300.0),
    ("sentman", 0.9, 0.0, 0.0, 300.0),
    ("sentman", 0.0, 0.0, 0.0, 0.0),
    ("dria", 0.8, 0.0, 0.0, 500.0),
    ("schaaf-chambre", 0.0, 0.8, 0.9, 300.0),
    ("schaaf-chambre", 0.0, 1.0, 0.0, 1000.0),
    ("cll", 0.0, 0.7, 0.8, 300.0),
    ("cll", 0.0, 0.05, 0.3, 200.0),
    ("cll", 0.0, 1.0, 1.0, 1000.0),
    ("cll", 0.0, 0.0, 0.5, 300.0),
    ("specular", 0.0, 0.0, 0.0, 300.0),
]
#: cosines of incidence: lee, edge-on (both zeros and the smallest values) and windward
GAMMA = np.concatenate([np.linspace(-1.0, 1.0, 401), [0.0, -0.0, 1e-17, -1e-17, 1e-9, -1e-9]])
SPEED_RATIOS = [0.5, 1.0, 2.0, 3.9, 7.75, 12.3, 20.0]


def law_table(laws=LAWS):
    """The per-law columns of ``laws``."""
    model, *rest = zip(*laws, strict=True)
    return GasSurfaces(np.array([MODEL_CODES[m] for m in model]), *(np.array(c, float) for c in rest))


def reference(law, gamma, speed_ratio, stream):
    """panel_coefficients of one law on every ``gamma``, (n, 2)."""
    one = law_table([law])
    columns = one.take(np.zeros(len(gamma), dtype=np.int64))
    return np.column_stack(panel_coefficients(columns, gamma, speed_ratio, T_INF, stream))


def assert_close(fast, ref, scale, speed_ratio, gamma):
    """To 1e-12 of ``|ref|``, or of ``scale`` deep in the lee (``S gamma < -3``), where the incident
    stream is a difference of nearly equal terms and any two erfc implementations part at the level
    of their own round-off times ``(S gamma)^4``; the values there are below ``exp(-9)`` of ``scale``."""
    deep_lee = speed_ratio * gamma < -3.0
    bound = np.where(deep_lee[:, None], scale, np.abs(ref)) * 1e-12
    assert np.all(np.abs(fast - ref) <= bound + 1e-300), np.max(np.abs(fast - ref) / (bound + 1e-300))


@pytest.mark.parametrize("speed_ratio", SPEED_RATIOS)
@pytest.mark.parametrize("law", LAWS, ids=[f"{law[0]}-{i}" for i, law in enumerate(LAWS)])
def test_one_species_is_the_reference_for_both_streams(law, speed_ratio):
    sums = summed_coefficients(
        law_table([law]),
        np.zeros(len(GAMMA), np.int64),
        GAMMA,
        [speed_ratio],
        [1.0],
        T_INF,
        np.ones((1, 1, 1)),
    )
    directed, full = (
        reference(law, GAMMA, speed_ratio, "directed"),
        reference(law, GAMMA, speed_ratio, "full"),
    )
    scale = np.abs(full).max(axis=0)
    assert_close(sums[:, 0:2], directed, scale, speed_ratio, GAMMA)
    assert_close(sums[:, 0:2] + sums[:, 2:4], full, scale, speed_ratio, GAMMA)
    # the thermal stream is full minus directed: round-off at the scale of the full stream
    thermal_error = np.abs(sums[:, 2:4] - (full - directed))
    assert np.all(
        thermal_error
        <= 1e-12 * np.maximum(np.abs(full), np.where(speed_ratio * GAMMA[:, None] < -3, scale, 0))
    )
    flux = incident_number_flux(GAMMA, speed_ratio, "full")
    assert_close(sums[:, 4:5], flux[:, None], flux.max(), speed_ratio, GAMMA)


def test_species_and_laws_are_weighted_sums_of_single_ones():
    rng = np.random.default_rng(5)
    law = rng.integers(0, len(LAWS), 300)
    gamma = rng.uniform(-1, 1, 300)
    ratios, weights = np.array([1.9, 3.9, 7.7, 12.3]), np.array([2.0, 0.5, 3.0, 1e-3])
    flux_weights = rng.uniform(0, 2, (len(LAWS), len(ratios), 2))
    sums = summed_coefficients(law_table(), law, gamma, ratios, weights, T_INF, flux_weights)
    expected = np.zeros((300, 6))
    for k, (ratio, weight) in enumerate(zip(ratios, weights, strict=True)):
        for row, one in enumerate(LAWS):
            at = law == row
            directed = reference(one, gamma[at], ratio, "directed")
            full = reference(one, gamma[at], ratio, "full")
            expected[at, 0:2] += weight * directed
            expected[at, 2:4] += weight * (full - directed)
            expected[at, 4:6] += flux_weights[row, k] * incident_number_flux(gamma[at], ratio)[:, None]
    np.testing.assert_allclose(sums, expected, rtol=1e-12, atol=1e-15 * np.abs(expected).max())


def test_rows_do_not_depend_on_the_thread_count():
    gamma = np.linspace(-1, 1, 50_001)
    law = np.arange(len(gamma)) % len(LAWS)
    args = (law_table(), law, gamma, [2.0, 8.0], [1.0, 2.0], T_INF)
    many = summed_coefficients(*args)
    with using_threads(1):
        assert np.array_equal(summed_coefficients(*args), many)


def test_bad_input():
    laws, row = law_table(), np.zeros(3, np.int64)
    with pytest.raises(InputError):
        summed_coefficients(laws, row, np.zeros(3), [0.0], [1.0], T_INF)
    with pytest.raises(InputError):
        summed_coefficients(laws, row + len(LAWS), np.zeros(3), [1.0], [1.0], T_INF)
    with pytest.raises(InputError):
        summed_coefficients(laws, row, np.array([0.0, np.nan, 0.0]), [1.0], [1.0], T_INF)
    bad = replace(laws, energy_accommodation=laws.energy_accommodation + 2.0)
    with pytest.raises(InputError):
        summed_coefficients(bad, row, np.zeros(3), [1.0], [1.0], T_INF)
