"""Figures: the right PNG files, non-empty; bad input refused (no image comparison)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from helpers import ABSORBER, mesh_from_trimesh
from helpers.tables import grid_table, list_table
from sunwind.forces.tables.plots import plot_table
from sunwind.forces.tables.pressure_views import plot_facet_pressure, view_box
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import build_spacecraft

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def is_png(path) -> bool:
    return path.stat().st_size > 10_000 and path.read_bytes()[:8] == PNG_SIGNATURE


@pytest.mark.parametrize(
    ("table", "names"),
    [
        (grid_table(15.0), ["srp_force_N", "srp_torque_Nm", "drag_force_N", "drag_torque_Nm"]),
        (list_table(30, kinds=("drag",)), ["drag_force_N", "drag_torque_Nm"]),
    ],
    ids=["grid", "list"],
)
def test_plot_table_writes_one_png_per_force_and_torque(tmp_path, table, names):
    paths = plot_table(table, tmp_path / "figures", "t")
    assert [path.name for path in paths] == [f"t.{name}.png" for name in names]
    assert all(is_png(path) for path in paths)
    assert sorted((tmp_path / "figures").iterdir()) == sorted(paths)


def test_plot_facet_pressure_on_20000_triangles(tmp_path):
    craft = build_spacecraft(mesh_from_trimesh(trimesh.creation.icosphere(subdivisions=5)), uniform=ABSORBER)
    assert craft.n_facets == 20480
    sun = np.array([0.6, 0.0, 0.8])
    pressure = 4.54e-6 * np.maximum(craft.facet_normals @ sun, 0.0) ** 2
    path = plot_facet_pressure(craft, pressure, sun, tmp_path / "pressure.png")
    assert is_png(path)


def test_bad_input(tmp_path):
    craft = build_spacecraft(mesh_from_trimesh(trimesh.creation.box()), uniform=ABSORBER)
    with pytest.raises(
        InputError, match=r"pressure_Pa has shape \(3,\), expected one finite value per facet"
    ):
        plot_facet_pressure(craft, [1.0, 2.0, 3.0], [1, 0, 0], tmp_path / "p.png")
    with pytest.raises(InputError, match=r"direction .* has zero length"):
        plot_facet_pressure(craft, np.zeros(craft.n_facets), [0, 0, 0], tmp_path / "p.png")
    with pytest.raises(InputError, match=r"no srp_\* or drag_\* force or torque to plot"):
        plot_table(grid_table(30.0)[["sun_vector"]], tmp_path, "t")
    assert not list(tmp_path.iterdir())


def test_the_3d_view_is_the_model_box_at_equal_aspect():
    """The view's limits are the model's box about its centre, each side at least 10 % of the largest (a
    flat sheet still has a depth); the picture is zoomed to fill the frame (test_plot_views.py)."""
    plate = trimesh.creation.box(extents=(2.0, 1.0, 0.1))
    low, high = view_box(plate.triangles + np.array([5.0, 0.0, -1.0]))
    np.testing.assert_allclose(high - low, [2.0, 1.0, 0.2])  # z: at least 10 % of 2 m
    np.testing.assert_allclose((low + high) / 2, [5.0, 0.0, -1.0], atol=1e-12)
