"""Articulated parts along an orbit: a Sun-tracking wing is posed at every step, its angle rounded to
the hinge step, and each step's load is that of the posed model."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.shapes import hinged_box_wing
from sunwind.forces import explicit, load, srp, sweep
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.tables.jobs import DragSetup, SrpSetup
from sunwind.geometry.directions import azel_to_vector
from sunwind.geometry.errors import InputError

EPOCH = Epoch.of("2024-06-21T00:00:00Z")


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    mesh, materials = hinged_box_wing(tmp_path_factory.mktemp("hinged"))
    return load(mesh, materials, reference_point_m=[0.0, 0.0, 0.0])


@pytest.mark.parametrize("step_deg", [0.0, 5.0])
def test_a_tracking_wing_follows_the_sun_and_each_step_is_srp_of_its_pose(model, step_deg):
    """GEO, nadir: the wing's hinge (body y) is the orbit normal, so the tracked wing faces the Sun
    square on (up to the rounding step) all day; each step equals ``srp`` of the model posed at the
    angle the run reports."""
    times = np.arange(0.0, 86400.0, 7200.0)
    path = propagate(Elements(42164.17e3, 0.0, 0.0, 0.0, 0.0, 0.0), EPOCH, times, "kepler")
    loads = OrbitLoads(SrpSetup(reflections="none"), hinge_step_deg=step_deg)
    result = fly(model, path, AttitudeLaw.parse("nadir"), loads, eclipse="none")
    angles = result.hinge_angles_deg["wing_*"]
    sun = result.series["sun_body"]
    if step_deg:
        assert np.allclose(angles / step_deg, np.round(angles / step_deg), atol=1e-9)
    exact = np.array([model.angles_at(u)["wing_*"] for u in sun])
    off = np.abs((angles - exact + 180.0) % 360.0 - 180.0)
    assert off.max() <= step_deg / 2 + 1e-9
    front = np.stack([np.cos(np.radians(angles)), np.zeros_like(angles), -np.sin(np.radians(angles))], 1)
    in_plane = sun - sun[:, 1:2] * np.array([0.0, 1.0, 0.0])
    cosine = np.einsum("ij,ij->i", front, in_plane / np.linalg.norm(in_plane, axis=1, keepdims=True))
    assert np.all(cosine >= np.cos(np.radians(step_deg / 2)) - 1e-9)
    for i in (0, 5):
        posed = model.posed({"wing_*": angles[i]})
        alone = srp(posed, sun[i], flux_W_m2=float(result.series["srp_flux_W_m2"][i]), reflections="none")
        assert np.allclose(result.series["srp_force_body_N"][i], alone.force_N, rtol=1e-12, atol=0)


@pytest.mark.filterwarnings("ignore:the Sun is along a tracking hinge's axis")
def test_an_srp_table_turns_a_tracking_wing_to_each_entrys_sun_and_a_drag_table_refuses_it(model):
    """Each entry is ``srp`` of the model posed at that Sun's tracking angle; drag has no Sun."""
    table = sweep(model, srp=SrpSetup(reflections="none"), step_deg=45.0)
    assert table.attrs["srp_tracking_hinges"] == "wing_*"
    for az, el in ((45.0, 0.0), (-135.0, 45.0), (90.0, -45.0)):
        u = azel_to_vector(az, el)
        alone = srp(model.posed(model.angles_at(u)), u, reflections="none")
        entry = table["srp_force_N"].sel(sun_azimuth=az, sun_elevation=el).values
        assert np.allclose(entry, alone.force_N, rtol=1e-12, atol=0)
    fixed = srp(model, azel_to_vector(-135.0, 45.0), reflections="none")  # the wings as drawn
    assert not np.allclose(fixed.force_N, table["srp_force_N"].sel(sun_azimuth=-135.0, sun_elevation=45.0))
    air = explicit(3e-12, 900.0, "O:1")
    with pytest.raises(InputError, match="tracks the Sun: a drag table has no Sun"):
        sweep(model, drag=DragSetup(speed_m_s=7600.0, atmosphere=air), step_deg=45.0)
