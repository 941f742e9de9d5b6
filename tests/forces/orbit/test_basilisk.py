"""A Basilisk scenario flown on the same orbit and attitude as sunwind's orbit mode: Basilisk's
``RadiationPressure`` effector in lookup mode reads the table ``sunwind sweep --format basilisk``
writes and takes its nearest entry (:mod:`helpers.basilisk_flight`). Where the body-frame Sun is a
table node the two agree to rounding; elsewhere Basilisk is sunwind at the nearest node, off by no more
than the force changes across the half-diagonal of a grid cell.

Basilisk (``pip install bsk``, the optional extra ``sunwind[basilisk]``) is not among the test
dependencies: without it the test is skipped, saying so.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from helpers.basilisk_flight import BASILISK_AU_M, basilisk_srp
from sunwind.forces import Model, srp, sweep
from sunwind.forces.export import write
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.tables.interpolation import azel_directions
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.geometry.directions import azel_to_vector
from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing

pytest.importorskip("Basilisk", reason="Basilisk (pip install bsk) is not installed: no round trip")

STEP_DEG = 15.0
EPOCH = Epoch.of("2024-06-01T00:00:00Z")
ORBIT = Elements.circular(700.0, 35.0, 40.0)


@pytest.fixture(scope="module")
def setting(tmp_path_factory):
    paint = Material("paint", 0.6, 0.5, 0.0)
    craft = build_spacecraft(box_wing(facet_size=0.25), uniform=paint, two_sided=["wing*"])
    model = Model(craft, reference_point_m=np.array([0.05, -0.1, 0.15]))
    table = sweep(model, srp=SrpSetup(reflections="none"), step_deg=STEP_DEG)
    xml = tmp_path_factory.mktemp("basilisk") / "lookup.xml"
    write(table, xml, "basilisk")
    return model, xml


def _fly_both(model, xml, law: str):
    times = np.arange(0.0, 5400.0, 90.0)
    path = propagate(ORBIT, EPOCH, times, "kepler")
    attitude = AttitudeLaw.parse(law)
    result = fly(model, path, attitude, OrbitLoads(SrpSetup(reflections="none")), eclipse="none")
    sun = sun_position(EPOCH, times)
    force, torque = basilisk_srp(xml, path.position_m, sun, result.body_to_eci)
    point = model.reference_point_m
    ours_force = result.series["srp_force_body_N"]
    ours_torque = result.series["srp_torque_body_Nm"] + np.cross(point, ours_force)  # about B's origin
    distance = np.linalg.norm(sun - path.position_m, axis=1)
    units = (BASILISK_AU_M / AU_M) ** 2  # Basilisk's au is 7 m short of the IAU's
    return result, force / units, torque / units, ours_force, ours_torque, distance


def test_at_table_nodes_basilisk_equals_sunwind(setting, tmp_path):
    """A quaternion file that, at every step, turns the body so that the spacecraft-to-Sun direction is
    the node az 30, el 15 (the real Sun, its parallax included)."""
    model, xml = setting
    node = azel_to_vector(30.0, 15.0)
    times = np.arange(0.0, 5400.0, 90.0)
    path = propagate(ORBIT, EPOCH, times, "kepler")
    to_sun = sun_position(EPOCH, times) - path.position_m
    rows = ["time_s,qw,qx,qy,qz"]
    for t, s in zip(times, to_sun / np.linalg.norm(to_sun, axis=1)[:, None], strict=True):
        x, y, z, w = Rotation.align_vectors([s], [node])[0].as_quat()
        rows.append(",".join(repr(float(v)) for v in (t, w, x, y, z)))
    file = tmp_path / "attitude.csv"
    file.write_text("\n".join(rows))
    result, force, torque, ours_force, ours_torque, _ = _fly_both(model, xml, f"csv:{file}")
    assert np.abs(result.series["sun_body"] - node).max() < 1e-12
    scale = np.abs(ours_force).max()
    assert np.abs(force - ours_force).max() < 1e-9 * scale
    assert np.abs(torque - ours_torque).max() < 1e-9 * scale * 1.0  # on the scale of |F| x 1 m


def test_between_nodes_basilisk_is_off_by_no_more_than_the_nearest_entry_error(setting):
    """Nadir pointing with the real Sun: the body-frame Sun sweeps between nodes. Basilisk's force is
    sunwind's at the nearest node (largest dot product), and its difference from sunwind's force is at
    most the largest change of the force over the node's cell, bounded here by |F| x 2 x the half
    diagonal of a cell (the force of flat plates turns by at most its cosine's rate, doubled for the
    specular share)."""
    model, xml = setting
    result, force, _, ours_force, _, distance = _fly_both(model, xml, "nadir")
    sun_body = result.series["sun_body"]
    az, el = np.meshgrid(np.arange(-180.0, 180.1, STEP_DEG), np.arange(-90.0, 90.1, STEP_DEG))
    nodes = azel_directions(az.ravel(), el.ravel())
    nearest = nodes[np.argmax(sun_body @ nodes.T, axis=1)]
    scale = (AU_M / distance) ** 2
    at_node = np.array([srp(model, u, reflections="none").force_N for u in nearest]) * scale[:, None]
    assert np.abs(force - at_node).max() < 1e-9 * np.abs(at_node).max()
    half_diagonal = np.radians(STEP_DEG) / np.sqrt(2)
    bound = 2 * half_diagonal * np.linalg.norm(ours_force, axis=1).max()
    error = np.linalg.norm(force - ours_force, axis=1)
    assert error.max() <= bound
    assert error.max() > 0.01 * bound  # the steps do fall between nodes
