"""Attitude laws against their definitions, and quaternion files against the laws they stand for."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, propagate
from sunwind.forces.orbit.attitude import hermite_quaternions, quaternion_file_attitude
from sunwind.geometry.errors import InputError

EPOCH = Epoch.of("2024-06-01T00:00:00Z")


@pytest.fixture(scope="module")
def path():
    times = np.arange(0.0, 6000.0, 100.0)
    return propagate(Elements(7200e3, 0.05, 63.4, 40.0, 270.0, 10.0), EPOCH, times, "kepler")


@pytest.fixture(scope="module")
def sun(path):
    return np.tile([1.2e11, -8.0e10, 3.5e10], (len(path.time_s), 1))


def _angle(a, b) -> np.ndarray:
    """Angle [rad] between vectors, accurate near 0 and pi."""
    a, b = np.broadcast_arrays(a, b)
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.einsum("...i,...i", a, b))


def test_nadir_keeps_body_z_on_the_earth_centre_and_y_on_the_negative_orbit_normal(path, sun):
    rotation = AttitudeLaw.parse("nadir").body_to_eci(path, sun)
    assert (
        np.abs(
            rotation @ [0, 0, 1.0] + path.position_m / np.linalg.norm(path.position_m, axis=1)[:, None]
        ).max()
        < 1e-14
    )
    normal = np.cross(path.position_m, path.velocity_m_s)
    assert _angle(rotation @ [0, 1.0, 0], -normal).max() < 1e-12
    assert np.allclose(np.linalg.det(rotation), 1.0)


def test_lvlh_angles_turn_the_nadir_frame_in_the_stated_order(path, sun):
    """lvlh:P,Y,R = R_lvlh Ry(P) Rz(Y) Rx(R): pitch alone turns body +x about LVLH y by P."""
    nadir = AttitudeLaw.parse("nadir").body_to_eci(path, sun)
    pitched = AttitudeLaw.parse("lvlh:30,0,0").body_to_eci(path, sun)
    expected = nadir @ np.array([np.cos(np.radians(30)), 0, -np.sin(np.radians(30))])
    assert np.abs(pitched @ [1.0, 0, 0] - expected).max() < 1e-14
    combined = AttitudeLaw.parse("lvlh:10,20,30").body_to_eci(path, sun)
    offset = Rotation.from_euler("YZX", [10, 20, 30], degrees=True).as_matrix()
    assert np.abs(combined - nadir @ offset).max() < 1e-14


def test_sun_law_points_its_axis_at_the_sun_and_the_second_as_near_the_orbit_normal(path, sun):
    rotation = AttitudeLaw.parse("sun:+x,-y").body_to_eci(path, sun)
    to_sun = sun - path.position_m
    assert _angle(rotation @ [1.0, 0, 0], to_sun).max() < 1e-12
    normal = np.cross(path.position_m, path.velocity_m_s)
    best = np.pi / 2 - _angle(to_sun, normal)  # the closest a vector normal to the Sun line gets
    assert np.allclose(_angle(rotation @ [0, -1.0, 0], normal), np.abs(best), atol=1e-12)


def test_thrust_sun_holds_the_thrust_axis_and_turns_the_array_normal_closest_to_the_sun(path, sun):
    thrust = np.array([0.3, -0.2, 0.9])
    rotation = AttitudeLaw.parse("thrust-sun:0.3,-0.2,0.9").body_to_eci(path, sun)
    assert _angle(rotation @ [1.0, 0, 0], np.tile(thrust, (len(sun), 1))).max() < 1e-12
    to_sun = sun - path.position_m
    off = np.abs(np.pi / 2 - _angle(to_sun, np.tile(thrust, (len(sun), 1))))
    assert np.allclose(_angle(rotation @ [0, 0, 1.0], to_sun), off, atol=1e-12)


def _write_quaternions(tmp_path, times, q, name="attitude.csv"):
    path = tmp_path / name
    rows = ["time_s,qw,qx,qy,qz"] + [
        ",".join(str(float(v)) for v in (t, *row)) for t, row in zip(times, q, strict=True)
    ]
    path.write_text("\n".join(rows) + "\n")
    return path


def test_a_file_of_one_constant_quaternion_reproduces_inertial(path, sun, tmp_path):
    q = np.array([0.8, 0.1, -0.5, 0.3])
    q /= np.linalg.norm(q)
    file = _write_quaternions(tmp_path, [0.0, 3000.0, 6000.0], np.tile(q, (3, 1)))
    inertial = AttitudeLaw.parse("inertial:" + ",".join(str(float(v)) for v in q)).body_to_eci(path, sun)
    for method in ("slerp", "hermite"):
        law = AttitudeLaw.parse(f"csv:{file}", method)
        assert np.abs(quaternion_file_attitude(law, EPOCH, path.time_s) - inertial).max() < 1e-14
    # scalar first, body to inertial: the quaternion (cos 45, 0, 0, sin 45) turns body +x onto +y
    turned = AttitudeLaw.parse("inertial:0.7071067811865476,0,0,0.7071067811865476").body_to_eci(path, sun)
    assert np.allclose(turned[0] @ [1.0, 0, 0], [0, 1.0, 0], atol=1e-15)


def _spin(t: np.ndarray, rate: float, acceleration: float) -> np.ndarray:
    """Quaternions (scalar first) of a rotation about a fixed axis by rate t + acceleration t^2 / 2."""
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    angle = rate * t + 0.5 * acceleration * t**2
    return np.column_stack([np.cos(angle / 2), np.sin(angle / 2)[:, None] * axis])


def _error(q: np.ndarray, truth: np.ndarray) -> float:
    return float(np.max(2 * np.arccos(np.clip(np.abs(np.einsum("ij,ij->i", q, truth)), 0, 1))))


def _interpolated(step: float, rate: float, acceleration: float) -> tuple[float, float, float]:
    """Largest angle [rad] off the true spin of SLERP and of the Hermite spline through samples
    ``step`` [s] apart, and between the two."""
    samples = np.arange(0.0, 201.0, step)
    t = np.linspace(10.0, 190.0, 1441)
    q, truth = _spin(samples, rate, acceleration), _spin(t, rate, acceleration)
    by_slerp = np.roll(Slerp(samples, Rotation.from_quat(np.roll(q, -1, 1)))(t).as_quat(), 1, 1)
    by_hermite = hermite_quaternions(samples, q, t)
    return _error(by_slerp, truth), _error(by_hermite, truth), _error(by_slerp, by_hermite)


def test_hermite_and_slerp_agree_on_a_slow_rotation_and_differ_as_they_should_on_a_fast_one():
    """A spin that speeds up, sampled every few seconds. Slow (1e-4 rad/s): both within 1e-7 rad of
    it and of each other. Fast (0.05 rad/s, + 2e-4 rad/s^2): SLERP turns at a constant rate between
    samples, off by acceleration h^2 / 8 (second order in the step h); the Hermite spline follows the
    acceleration and converges at third order, so it is closer and gains faster as h shrinks."""
    slerp, hermite, between = _interpolated(2.0, 1e-4, 1e-9)
    assert max(slerp, hermite, between) < 1e-7
    coarse = _interpolated(2.0, 0.05, 2e-4)
    fine = _interpolated(1.0, 0.05, 2e-4)
    assert coarse[0] == pytest.approx(2e-4 * 2.0**2 / 8, rel=0.01)
    assert coarse[0] / fine[0] == pytest.approx(4.0, rel=0.01)
    assert coarse[1] < coarse[0] / 4 and coarse[1] / fine[1] > 7.0
    assert coarse[2] > 1e-5  # they differ, by about SLERP's error


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("spin", "is not one of"),
        ("lvlh:1,2", "needs 3 numbers"),
        ("inertial:0,0,0,0", "is not of unit length"),
        ("inertial:2,0,0,0", r"\|q\| = 2\)"),
        ("sun:+x,+x", "two different body axes"),
        ("sun:+q,+x", "is not a body axis"),
        ("nadir:3", "takes no values"),
    ],
)
def test_bad_laws_are_refused_with_the_reason(text, message):
    with pytest.raises(InputError, match=message):
        AttitudeLaw.parse(text)


def test_a_quaternion_file_that_is_not_unit_or_does_not_cover_the_run_is_refused(tmp_path):
    bad = _write_quaternions(tmp_path, [0.0, 10.0], [[1, 0, 0, 0], [2, 0, 0, 0]], "bad.csv")
    with pytest.raises(InputError, match="not a unit quaternion"):
        quaternion_file_attitude(AttitudeLaw.parse(f"csv:{bad}"), EPOCH, np.array([0.0]))
    short = _write_quaternions(tmp_path, [0.0, 10.0], [[1, 0, 0, 0], [1, 0, 0, 0]], "short.csv")
    with pytest.raises(InputError, match="outside the attitude file"):
        quaternion_file_attitude(AttitudeLaw.parse(f"csv:{short}"), EPOCH, np.array([0.0, 20.0]))


def test_a_quaternion_file_law_is_read_not_computed_and_says_so(tmp_path):
    law = AttitudeLaw.parse(f"csv:{tmp_path / 'q.csv'}")
    path = propagate(Elements.circular(500.0, 51.6), Epoch.of("2024-03-20T00:00:00Z"), [0.0], "kepler")
    with pytest.raises(InputError, match="read from its file"):
        law.body_to_eci(path, np.array([[1.5e11, 0.0, 0.0]]))
