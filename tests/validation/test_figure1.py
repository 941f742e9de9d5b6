"""The paper's Fig. 1 case: drag and SRP on a 1 m aluminium sphere cross between 500 and 1000 km."""

import numpy as np

from sunwind.validation.figure1 import crossover, figure1, plot


def test_crossover_lies_where_the_paper_puts_it_and_moves_up_with_solar_activity(tmp_path):
    result = figure1(np.arange(300.0, 1101.0, 100.0), subdivisions=24)
    # SRP on a sphere: P pi R^2 (1 + 4/9 rho_d), rho_d = 0.85 * 0.1, faceting -0.3 %
    expected = 1361.0 / 299_792_458.0 * np.pi * (1 + 4 / 9 * 0.085)
    assert abs(result.srp_N / expected - 1) < 5e-3
    low, moderate, high = (result.crossover_km[k] for k in ("low", "moderate", "high"))
    assert 400 < low < moderate < high < 1000
    assert 500 <= moderate <= 1000  # the paper: atmosphere ahead below ~500 km, sunlight above ~1000 km
    plot(result, str(tmp_path / "fig1.png"))
    assert (tmp_path / "fig1.png").stat().st_size > 10_000


def test_crossover_interpolates_log_force():
    altitudes = np.array([100.0, 200.0])
    assert crossover(altitudes, np.array([10.0, 0.1]), 1.0) == 150.0
    assert np.isnan(crossover(altitudes, np.array([0.5, 0.1]), 1.0))
