"""The direct SRP force law of a flat surface (eq. 4) and the solar flux: limits and momentum balance."""

import numpy as np
import pytest

from helpers import MIXED
from sunwind.forces.radiation.law import (
    SOLAR_FLUX_1AU,
    SPEED_OF_LIGHT,
    radiation_pressure,
    solar_flux,
    surface_forces,
)
from sunwind.geometry.errors import InputError

P = SOLAR_FLUX_1AU / SPEED_OF_LIGHT


def plate_force(rho, beta, sigma, cos):
    """Force on a unit plate with normal +z, Sun in the x-z plane at incidence angle acos(cos)."""
    u = np.array([np.sqrt(1 - cos**2), 0.0, cos])
    one = np.ones(1)
    return surface_forces(
        np.array([[0.0, 0, 1]]), one, np.array([cos]), rho * one, beta * one, sigma * one, u, P
    )[0], u


@pytest.mark.parametrize("cos", [1.0, 0.8, 0.3, 0.01])
def test_force_law_limits(cos):
    n = np.array([0.0, 0, 1])
    absorbed, u = plate_force(0.0, 0.0, 0.0, cos)
    assert np.allclose(absorbed, -P * cos * u)  # all momentum along the beam
    mirror, _ = plate_force(1.0, 1.0, 0.0, cos)
    assert np.allclose(mirror, -2 * P * cos**2 * n)  # normal only: no tangential force
    lambert, _ = plate_force(1.0, 0.0, 0.0, cos)
    assert np.allclose(lambert, -P * cos * (u + 2 / 3 * n))
    clear, _ = plate_force(0.0, 0.0, 1.0, cos)
    assert np.allclose(clear, 0.0)  # fully transmitted light passes unchanged
    # momentum balance of the mixed case: incident - transmitted - specular - diffuse momentum out
    rho, beta, sigma = MIXED.reflectivity, MIXED.specular_fraction, MIXED.transmissivity
    mixed, _ = plate_force(rho, beta, sigma, cos)
    s = -u
    mirror_dir = s - 2 * (s @ n) * n
    expected = P * cos * (s - sigma * s - rho * beta * mirror_dir - rho * (1 - beta) * 2 / 3 * n)
    assert np.allclose(mixed, expected, rtol=1e-13, atol=0)


def test_flux_from_distance_and_pressure():
    assert solar_flux() == SOLAR_FLUX_1AU
    assert np.isclose(solar_flux(distance_au=2.0), SOLAR_FLUX_1AU / 4)
    assert solar_flux(flux_W_m2=1000.0) == 1000.0
    assert np.isclose(radiation_pressure(SOLAR_FLUX_1AU), 4.5398e-6, rtol=1e-4)
    for bad in (
        {"flux_W_m2": np.nan},
        {"flux_W_m2": -1.0},
        {"distance_au": 0.0},
        {"distance_au": np.inf},
        {"flux_W_m2": 1.0, "distance_au": 1.0},
    ):
        with pytest.raises(InputError):
            solar_flux(**bad)
