"""TableInterpolator: exact at nodes, continuous across az = +-180 and the poles, converging with the step.

``grid_table`` and ``list_table`` build synthetic sweep tables that follow the sweep contract; the exporter
and plot tests use them too.
"""

from __future__ import annotations

import numpy as np
import pytest

from helpers.tables import ATTRS, field, grid_table, list_table
from sunwind.forces.tables.interpolation import TableInterpolator, azel_directions, check_step, grid_axes
from sunwind.geometry.errors import InputError


def random_directions(n: int, seed: int = 11) -> np.ndarray:
    d = np.random.default_rng(seed).normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


@pytest.mark.parametrize("method", ["bilinear", "bicubic"])
@pytest.mark.parametrize("step", [15.0, 40.0])  # 40 deg: an odd number of azimuth steps
def test_exact_on_grid_nodes(method, step):
    table = grid_table(step, el_step_deg=10.0)
    interp = TableInterpolator(table, method)
    nodes = table["sun_vector"].values
    force, torque = interp.srp(nodes)
    np.testing.assert_allclose(force, table["srp_force_N"].values, rtol=0, atol=1e-18)
    np.testing.assert_allclose(torque, table["srp_torque_Nm"].values, rtol=0, atol=1e-18)
    drag_force, _ = interp.drag(table["flow_vector"].values)
    np.testing.assert_allclose(drag_force, table["drag_force_N"].values, rtol=0, atol=1e-15)


@pytest.mark.parametrize("method", ["bilinear", "bicubic"])
def test_continuous_across_azimuth_180_and_the_poles(method):
    interp = TableInterpolator(grid_table(15.0), method)
    el = np.linspace(-89.0, 89.0, 37)
    eps = 1e-7
    west = interp.drag(azel_directions(180.0 - eps, el)).force_N
    east = interp.drag(azel_directions(-180.0 + eps, el)).force_N
    np.testing.assert_allclose(west, east, rtol=0, atol=1e-9)
    az = np.linspace(-180.0, 180.0, 73)
    for pole in (90.0, -90.0):
        at_pole = interp.drag(np.array([0.0, 0.0, np.sign(pole)])).force_N
        near = interp.drag(azel_directions(az, pole - np.sign(pole) * 1e-6)).force_N
        np.testing.assert_allclose(near, np.broadcast_to(at_pole, near.shape), rtol=0, atol=1e-9)
        np.testing.assert_allclose(at_pole, field(np.array([0.0, 0.0, np.sign(pole)]), 1e-3)[0], atol=1e-15)


# Max error over 4000 random directions of the field above (max |F| ~ 2), bound = coefficient * step^order,
# the coefficient about 1.3 x the largest seen at 20, 10 and 5 deg (bilinear ~1.6e-4, bicubic ~1.7e-6).
BOUNDS = {"bilinear": (2, 2.2e-4), "bicubic": (3, 2.3e-6)}


@pytest.mark.parametrize("method", ["bilinear", "bicubic"])
def test_error_falls_with_the_step(method):
    order, coefficient = BOUNDS[method]
    d = random_directions(4000)
    exact = field(d, 1e-6)[0]
    errors = []
    for step in (20.0, 10.0, 5.0):
        force = TableInterpolator(grid_table(step, kinds=("srp",)), method).srp(d).force_N
        errors.append(np.abs(force - exact).max() / 1e-6)
        assert errors[-1] <= coefficient * step**order, (step, errors[-1])
    observed = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert (observed > order - 0.3).all(), observed


def test_reads_a_netcdf_file_and_rescales_the_flux(tmp_path):
    table = grid_table(30.0)
    path = tmp_path / "sweep.nc"
    table.to_netcdf(path)
    d = random_directions(50)
    from_file = TableInterpolator(path).srp(d)
    in_memory = TableInterpolator(table).srp(d)
    np.testing.assert_allclose(from_file.force_N, in_memory.force_N, rtol=1e-14)
    doubled = TableInterpolator(table).srp(d, flux_W_m2=2 * ATTRS["flux_W_m2"])
    np.testing.assert_allclose(doubled.torque_Nm, 2 * in_memory.torque_Nm, rtol=1e-14)
    assert TableInterpolator(table).values(["srp_lit_area_m2"], d[:4].reshape(2, 2, 3)).shape == (2, 2, 1)


def test_bad_input():
    with pytest.raises(InputError, match="no flow_azimuth/flow_elevation grid"):
        TableInterpolator(list_table()).drag([1.0, 0.0, 0.0])
    with pytest.raises(InputError, match="the table has no drag_force_N, drag_torque_Nm") as error:
        TableInterpolator(grid_table(30.0, kinds=("srp",))).drag([1.0, 0.0, 0.0])
    assert error.value.hint == "run the sweep with drag included"
    with pytest.raises(InputError, match="unknown interpolation method 'spline'"):
        TableInterpolator(grid_table(30.0), "spline")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="finite and non-zero"):
        TableInterpolator(grid_table(30.0)).srp([0.0, 0.0, 0.0])
    skewed = grid_table(30.0).assign_coords(sun_azimuth=np.linspace(-170.0, 190.0, 13))
    with pytest.raises(InputError, match="sun_azimuth must run from -180 to 180 deg"):
        grid_axes(skewed, "sun")


def test_check_step_names_the_step_and_suggests_divisors():
    assert check_step(7.5, 360.0, "azimuth") == 48
    with pytest.raises(InputError) as error:
        check_step(7.5, 360.0, "azimuth", whole_degrees=True)
    assert str(error.value) == (
        "azimuth step 7.5 deg is not a whole number of degrees; use a whole number of degrees that divides "
        "180 deg, e.g. 5, 6, 9, 10"  # the advice the sweep grid gives: 8 divides 360 but no grid takes it
    )
    with pytest.raises(InputError, match=r"elevation step 7 deg does not divide 180 deg; .* 5, 6, 7.5, 9"):
        check_step(7.0, 180.0, "elevation")
