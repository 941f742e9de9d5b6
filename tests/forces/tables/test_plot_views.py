"""sunwind plot: map files named by their table, 3-D views seen from the Sun / upstream or from
``--view-azel`` and filling their frame, map titles that name the reference point, atmosphere and date."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import trimesh
from mpl_toolkits.mplot3d import proj3d

from helpers import ABSORBER, mesh_from_trimesh
from helpers.tables import grid_table, list_table
from sunwind.forces.cli.app import main
from sunwind.forces.gas.atmosphere import explicit
from sunwind.forces.gas.msis import nrlmsis
from sunwind.forces.tables import plots, pressure_views
from sunwind.forces.tables.plots import map_title, plot_table
from sunwind.forces.tables.pressure_views import pressure_figure
from sunwind.geometry.directions import azel_to_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import build_spacecraft

OPTICS = ("--reflectivity", "0.4", "--specular-fraction", "0.5", "--samples", "1", "--reflections", "none")
AIR = ("--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2", "--speed", "7600")


@pytest.fixture(scope="module")
def craft():
    """A 2 x 1 x 0.5 m box, 12 triangles."""
    return build_spacecraft(
        mesh_from_trimesh(trimesh.creation.box(extents=(2.0, 1.0, 0.5))), uniform=ABSORBER
    )


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    """An SRP and drag table of a 12-triangle box on the 90 deg grid, next to its mesh."""
    where = tmp_path_factory.mktemp("plot_views")
    main(["mesh", "box", "-o", str(where / "box.obj")])
    sweep = ["sweep", str(where / "box.obj"), *OPTICS, *AIR, "--srp", "--drag", "--step", "90"]
    main([*sweep, "-o", str(where / "t.nc")])
    return where / "t.nc"


def test_two_tables_plotted_into_one_directory_keep_their_maps_apart(tmp_path):
    first = plot_table(grid_table(30.0, kinds=("srp",)), tmp_path, "a")
    second = plot_table(list_table(5, kinds=("srp",)), tmp_path, "b")
    assert [p.name for p in first] == ["a.srp_force_N.png", "a.srp_torque_Nm.png"]
    assert [p.name for p in second] == ["b.srp_force_N.png", "b.srp_torque_Nm.png"]
    assert sorted(tmp_path.iterdir()) == sorted(first + second)


def test_the_camera_is_at_the_direction_unless_told(craft):
    """Default: the camera at the Sun / upstream, so the loaded side faces the viewer, no arrow (it would
    be seen end-on); ``view_azel`` moves the camera and the arrow shows where the load comes from."""
    sun = azel_to_vector(30.0, 20.0)
    pressure = np.maximum(craft.facet_normals @ sun, 0.0)
    ax = pressure_figure(craft, pressure, sun).axes[0]
    assert (ax.azim, ax.elev) == pytest.approx((30.0, 20.0), abs=1e-9)
    assert not ax.texts and "seen from az 30, el 20 deg" in ax.get_title()
    ax = pressure_figure(craft, pressure, sun, "flow u", view_azel=(-120.0, -45.0)).axes[0]
    assert (ax.azim, ax.elev) == (-120.0, -45.0)
    assert [text.get_text().strip() for text in ax.texts] == ["flow u"]


@pytest.mark.parametrize("view_azel", [None, (-120.0, -45.0), (10.0, 90.0)], ids=["default", "below", "pole"])
def test_the_model_fills_the_frame(craft, view_azel):
    """The model's picture (and the arrow's, off its line) spans 97 % of the frame's width or height,
    in its middle, whatever the camera."""
    sun = azel_to_vector(-60.0, 10.0)
    ax = pressure_figure(craft, np.ones(craft.n_facets), sun, view_azel=view_azel).axes[0]
    x, y, _ = proj3d.proj_transform(*craft.triangles.reshape(-1, 3).T, ax.get_proj())
    frame = np.array([ax.viewLim.intervalx, ax.viewLim.intervaly])
    if view_azel is None:  # the model only: no arrow
        assert max(np.ptp(x), np.ptp(y)) == pytest.approx(0.97 * np.ptp(frame[0]), rel=1e-9)
        np.testing.assert_allclose([x.min() + x.max(), y.min() + y.max()], frame.sum(axis=1), atol=1e-9)
    assert frame[0, 0] < x.min() < x.max() < frame[0, 1] and frame[1, 0] < y.min() < y.max() < frame[1, 1]
    assert max(np.ptp(x), np.ptp(y)) > 0.6 * np.ptp(frame[0])


def test_a_bad_camera_is_refused(craft):
    for bad, reason in (((0.0, 100.0), "elevation 100 deg"), ((math.nan, 0.0), "must be finite")):
        with pytest.raises(InputError, match=f"view_azel .*{reason}"):
            pressure_figure(craft, np.ones(craft.n_facets), [1, 0, 0], view_azel=bad)


def test_plot_flags_place_the_views_and_their_camera(table, run_cli, monkeypatch, tmp_path):
    """--at-azel: the Sun / flow direction of the views (their file names); --view-azel: the camera,
    default at that direction; the maps named by the table; a bad --view-azel is one error line, before
    any file is written."""
    cameras, names = [], []

    def recorded(*args, **kwargs):
        ax = pressure_figure(*args, **kwargs).axes[0]
        cameras.append((ax.azim, ax.elev))
        return ax.figure

    monkeypatch.setattr(pressure_views, "pressure_figure", recorded)
    monkeypatch.setattr(plots, "plot_table", lambda table, directory, name: names.append(name) or [])
    code, out, err = run_cli("plot", table, "--at-azel", "90", "0", "-o", tmp_path / "a")
    assert code == 0, err
    assert names == ["t"]  # the maps' files are t.VARIABLE.png (test_two_tables_...)
    views = [f"t.{kind}.pressure_az+90_el+0.png" for kind in ("srp", "drag")]
    assert [line.rsplit("/", 1)[1] for line in out.splitlines()[1:]] == views
    np.testing.assert_allclose(cameras, [(90.0, 0.0)] * 2, atol=1e-9)  # the camera at the Sun, upstream
    cameras.clear()
    code, out, err = run_cli("plot", table, "--view-azel", "-150", "35", "-o", tmp_path / "b")
    assert code == 0, err
    assert cameras == [(-150.0, 35.0)] * 2
    for bad in (("0", "100"), ("nan", "10")):
        code, out, err = run_cli("plot", table, "--view-azel", *bad, "-o", tmp_path / "c")
        assert code == 1 and err.count("\n") == 1 and err.startswith("sunwind: error: --view-azel ")
        assert not (tmp_path / "c").exists()
    code, out, err = run_cli("plot", table, "--at-azel", "0", "100", "-o", tmp_path / "c")
    assert code == 1 and err.startswith("sunwind: error: --at-azel elevation 100") and err.count("\n") == 1


def test_a_drag_torque_map_names_its_reference_point_atmosphere_and_date():
    table = grid_table(30.0, kinds=("drag",))
    table.attrs["atmosphere"] = json.dumps(nrlmsis(400.0, time="2025-06-01T12:00:00Z").to_json())
    assert map_title(table, "drag_torque_Nm") == (
        "drag torque [N m], body frame of the mesh; reference point (0.1, -0.2, 0.3) m: user\n"
        "q = 2.812e-05 Pa at 7500 m/s; NRLMSIS 2.1 at 400 km, lat 0, lon 0, 2025-06-01T12:00:00Z, "
        "F10.7 150 (81-day 150), Ap 4"
    )
    table.attrs["atmosphere"] = json.dumps(explicit(1e-12, 900.0, "O:0.8,N2:0.2").to_json())
    assert map_title(table, "drag_force_N").splitlines() == [
        "drag force [N], body frame of the mesh",
        "q = 2.812e-05 Pa at 7500 m/s; explicit atmosphere (no date): 1e-12 kg/m^3, 900 K, "
        "mole fractions O 0.8, N2 0.2",
    ]


def test_srp_and_earth_maps_name_the_flux_altitude_sun_and_date():
    table = grid_table(30.0, kinds=("srp",))
    assert map_title(table, "srp_force_N") == "srp force [N], body frame of the mesh\nflux 1000 W/m^2"
    table["earth_torque_Nm"] = table["srp_torque_Nm"].assign_attrs(long_name="Earth torque")
    table.attrs |= {"earth_altitude_km": 500.0, "earth_sun_vector": [0.0, 1.0, 0.0]}
    assert (
        map_title(table, "earth_torque_Nm").splitlines()[1]
        == "altitude 500 km, Sun fixed at (0.000, 1.000, 0.000)"
    )
    table.attrs["atmosphere"] = json.dumps(nrlmsis(400.0).to_json())
    assert map_title(table, "earth_torque_Nm").endswith("; date 2024-01-01T00:00:00Z")
