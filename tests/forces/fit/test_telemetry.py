"""Reading telemetry: the Sun of the quaternions from the ephemeris, optional columns, and the rows'
geometries (tracking hinges turned to each row's Sun)."""

from __future__ import annotations

import numpy as np
import pytest

import sunwind as sw
from sunwind.forces.fit.forward import Geometry
from sunwind.forces.fit.telemetry import Telemetry, read_telemetry
from sunwind.forces.orbit.attitude import quaternion_matrix
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU

EPOCH = "2024-06-21T00:00:00Z"


def test_quaternions_and_an_epoch_give_the_body_sun_and_the_flux_at_its_distance(tmp_path):
    q = np.array([[1.0, 0, 0, 0], [np.cos(0.3), 0, np.sin(0.3), 0], [np.cos(0.6), np.sin(0.6), 0, 0]])
    path = tmp_path / "q.csv"
    rows = [
        f"{t},{w},{x},{y},{z},1e-6,0,0,0.5" for t, (w, x, y, z) in zip([0, 60, 120], q.tolist(), strict=True)
    ]
    path.write_text("time_s,qw,qx,qy,qz,momentum_x,momentum_y,momentum_z,solar_fraction\n" + "\n".join(rows))
    telemetry = read_telemetry(path, EPOCH)
    sun = sun_position(Epoch.of(EPOCH), np.array([0.0, 60.0, 120.0]))
    distance = np.linalg.norm(sun, axis=1)
    expected = np.einsum("nji,nj->ni", quaternion_matrix(q), sun / distance[:, None])
    assert np.allclose(telemetry.sun_body, expected, atol=1e-12)
    assert np.allclose(telemetry.flux_W_m2, SOLAR_FLUX_1AU * (AU_M / distance) ** 2)
    assert telemetry.flux_W_m2[0] < SOLAR_FLUX_1AU  # the Earth is near aphelion in June
    assert telemetry.kinds == ("momentum",) and telemetry.rotation.shape == (3, 3, 3)
    assert np.all(telemetry.solar_fraction == 0.5)


def test_sun_columns_win_over_the_ephemeris_and_a_flux_column_is_taken(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text(
        "time_s,sun_x,sun_y,sun_z,qw,qx,qy,qz,flux_W_m2,torque_x,torque_y,torque_z\n"
        "0,0,0,2,1,0,0,0,1300,0,0,0\n"
        "1,0,2,0,1,0,0,0,1310,0,0,0\n"
    )
    telemetry = read_telemetry(path)
    assert telemetry.sun_body.tolist() == [[0, 0, 1], [0, 1, 0]]
    assert telemetry.flux_W_m2.tolist() == [1300, 1310] and telemetry.rotation is not None


def test_tracking_hinges_turn_to_each_rows_sun():
    model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_path("sample_spacecraft_tracking.toml"))
    suns = np.array([[1.0, 0, 0], [1.0, 0, 0], [0, 0, 1.0]])
    telemetry = Telemetry(np.arange(3.0), suns, np.full(3, 1361.0), np.ones(3), {"torque": np.zeros((3, 3))})
    geometry = Geometry.of(model, telemetry)
    assert geometry.row_group.tolist() == [0, 0, 1]
    expected = [model.angles_at(u) for u in suns[[0, 2]]]
    for got, want in zip(geometry.angles, expected, strict=True):
        assert got == pytest.approx(want)
    assert expected[0] != expected[1]


def test_drag_columns_need_a_density_and_take_a_default_temperature(tmp_path):
    from sunwind.geometry.errors import InputError

    path = tmp_path / "d.csv"
    path.write_text(
        "time_s,sun_x,sun_y,sun_z,vel_x,vel_y,vel_z,accel_x,accel_y,accel_z\n0,1,0,0,7600,0,0,0,0,0\n"
    )
    with pytest.raises(InputError, match="no column density_kg_m3"):
        read_telemetry(path)
    path.write_text(
        "time_s,sun_x,sun_y,sun_z,vel_x,vel_y,vel_z,density_kg_m3,accel_x,accel_y,accel_z\n"
        "0,1,0,0,7600,0,0,1e-12,0,0,0\n"
    )
    flow = read_telemetry(path).flow
    assert flow["temperature_K"].tolist() == [1000.0] and flow["velocity_m_s"].tolist() == [[7600.0, 0, 0]]
