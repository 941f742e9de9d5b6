"""The windmill torque of two wings turned opposite ways on one hinge line, against its closed form.

Two flat one-sided wings of area ``A`` lie on the hinge axis y, centred at ``y = +d`` and ``y = -d``,
their fronts facing the Sun ``u = +x`` as drawn. Wing ``+`` turns by ``+delta`` about +y, wing ``-``
by ``-delta``: their normals are ``n_+- = (cos delta, 0, -+sin delta)``, both at incidence
``cos(theta) = cos(delta)``. The flat-plate law (METHOD.md "Direct solar pressure") with ``rho_s`` the
specular and ``rho_d`` the diffuse share,

    F = -P A cos(theta) [ (1 - rho_s) u + (2 rho_s cos(theta) + (2/3) rho_d) n ],

acts at each wing's centroid ``r = (0, +-d, 0)`` (the pressure is uniform over a fully lit plate).
With ``y x x = -z`` and ``y x z = x``, ``r x F = +-d (F_z x - F_x z)``. The ``u`` terms and the ``x``
components of the ``n`` terms are the same on both wings, so their ``z`` torques cancel, and nothing
acts about y. The ``z`` components are ``F_z,+- = +-P A cos(delta) sin(delta) (2 rho_s cos(delta) +
(2/3) rho_d)``, so both wings turn the craft the same way about the Sun line x:

    M_x = 4 P A rho_s d cos^2(delta) sin(delta) + (4/3) P A rho_d d cos(delta) sin(delta),
    M_y = M_z = 0,

positive for this sense of turning (a windmill in the light: the torque is about the direction of the
Sun, across the hinge axis). The specular term is largest where ``d/d delta (cos^2 sin) = cos
(cos^2 - 2 sin^2) = 0``: ``tan(delta) = 1/sqrt(2)``, ``delta = 35.26 deg``.

The wings neither shadow each other (they lie apart along y and the light travels along x) nor, when
mirrors, reflect light onto each other (a mirror beam of a wing stays in that wing's x-z plane), so the
closed form is exact for mirrors with the beam chains on. A diffuse share lights the other wing a
little (the direct law leaves that out), so the mixed case uses ``reflections="none"``, the law the
closed form is.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import tomllib
import xarray as xr

from sunwind.forces import srp
from sunwind.forces.model import Model, ModelSource
from sunwind.geometry.io.obj import write_obj
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.assembly import label, rotation_matrix, transform
from sunwind.meshes.primitives import plate

D, SPAN, WIDTH = 2.0, 2.0, 1.0  # m: wing centres at y = +-D, each SPAN along y and WIDTH along z
AREA = SPAN * WIDTH
SUN = np.array([1.0, 0.0, 0.0])
ANGLES = np.arange(0.0, 81.0, 1.0)  # deg
MATERIALS = """
[materials.mirror]
reflectivity = 1.0
specular_fraction = 1.0
[materials.mixed]
reflectivity = 0.9
specular_fraction = 0.5
[parts]
"wing_*" = {{ front = "{material}" }}
[articulation.wing_p]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
angle_deg = 0
[articulation.wing_n]  # the same line, by another point and an axis of another length
axis = [0, 2, 0]
origin_m = [0, -5, 0]
angle_deg = 0
"""


def wings() -> MeshData:
    """The two wings as drawn: fronts +x, in the plane x = 0, centred at y = +-D."""
    sheet = transform(plate(WIDTH, SPAN, (2, 3)), rotation_matrix("y", 90.0))  # plate +z -> +x
    return MeshData.concatenate(
        [
            label(transform(sheet, None, (0, sign * D, 0)), name)
            for name, sign in (("wing_p", 1), ("wing_n", -1))
        ]
    )


def model(material: str) -> Model:
    """The wings of ``material`` ("mirror" or "mixed") on their hinges, torques about the origin."""
    spec = parse_materials(tomllib.loads(MATERIALS.format(material=material)), "wings.toml")
    return Model(build_spacecraft(wings(), spec), reference_point_m=[0.0, 0.0, 0.0])


def closed_form(delta_deg: float | np.ndarray, pressure: float, rho_s: float, rho_d: float) -> np.ndarray:
    """``M_x`` [N m] of the module docstring."""
    c, s = np.cos(np.radians(delta_deg)), np.sin(np.radians(delta_deg))
    return 4 * pressure * AREA * D * (rho_s * c**2 * s + rho_d * c * s / 3)


def torques(windmill: Model, reflections: str) -> tuple[np.ndarray, float]:
    """Torque [N m] (len(ANGLES), 3) at every turning angle, and the pressure [Pa]."""
    out, pressure = [], math.nan
    for delta in ANGLES:
        result = srp(windmill.posed({"wing_p": delta, "wing_n": -delta}), SUN, reflections=reflections)
        out.append(result.torque_Nm)
        pressure = result.pressure_Pa
    return np.array(out), pressure


def test_mirror_wings_turn_the_craft_about_the_sun_line_as_the_closed_form_says():
    windmill = model("mirror")
    torque, pressure = torques(windmill, "specular")
    scale = pressure * AREA * D
    expected = closed_form(ANGLES, pressure, 1.0, 0.0)
    np.testing.assert_allclose(torque[:, 0], expected, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(torque[:, 1:], 0.0, rtol=0, atol=1e-12 * scale)
    assert abs(torque[0, 0]) <= 1e-15 * scale  # as drawn: no torque
    best = int(np.argmax(torque[:, 0]))
    assert ANGLES[best] == 35.0
    # the vertex of the parabola through the three samples around the largest: within 0.05 deg of 35.26
    low, mid, high = torque[best - 1 : best + 2, 0]
    vertex = ANGLES[best] + 0.5 * (low - high) / (low - 2 * mid + high)
    assert abs(vertex - math.degrees(math.atan(1 / math.sqrt(2)))) < 0.05
    assert torque[best, 0] == pytest.approx(4 * scale * (2 / 3) / math.sqrt(3), rel=1e-3)


def test_a_diffuse_share_adds_its_own_term():
    torque, pressure = torques(model("mixed"), "none")
    rho_s, rho_d = 0.9 * 0.5, 0.9 * 0.5
    expected = closed_form(ANGLES, pressure, rho_s, rho_d)
    scale = pressure * AREA * D
    np.testing.assert_allclose(torque[:, 0], expected, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(torque[:, 1:], 0.0, rtol=0, atol=1e-12 * scale)


def test_the_command_line_turns_the_wings_and_reports_the_angles(run_cli, tmp_path):
    write_obj(wings(), tmp_path / "wings.obj")
    (tmp_path / "wings.toml").write_text(MATERIALS.format(material="mirror"))
    flags = ["--articulate", "wing_p=30", "--articulate", "wing_n=-30", "--ref-point", "0", "0", "0"]
    args = ["srp", tmp_path / "wings.obj", "-m", tmp_path / "wings.toml", "--sun", "1", "0", "0", *flags]
    code, out, err = run_cli(*args, "--reflections", "specular", "--json")
    assert code == 0, err
    document = json.loads(out)
    assert document["articulation"] == {"wing_p": 30.0, "wing_n": -30.0}
    expected = closed_form(30.0, document["pressure_Pa"], 1.0, 0.0)
    assert document["torque_Nm"][0] == pytest.approx(expected, rel=1e-12)
    code, out, err = run_cli(*args, "--reflections", "none")
    assert code == 0 and "articulation     wing_p +30.000 deg (fixed); wing_n -30.000 deg (fixed)" in out


def test_a_sweep_at_held_angles_records_them_and_its_source_loads_that_pose(run_cli, tmp_path):
    write_obj(wings(), tmp_path / "wings.obj")
    (tmp_path / "wings.toml").write_text(MATERIALS.format(material="mirror"))
    table = tmp_path / "t.nc"
    flags = ["--articulate", "wing_p=30", "--reflections", "none", "--samples", "1"]
    code, _, err = run_cli(
        "sweep",
        tmp_path / "wings.obj",
        "-m",
        tmp_path / "wings.toml",
        "--srp",
        "--step",
        "90",
        "-o",
        table,
        *flags,
    )
    assert code == 0, err
    with xr.open_dataset(table) as opened:
        attrs = dict(opened.attrs)
    assert json.loads(attrs["articulation_deg"]) == {"wing_p": 30.0, "wing_n": 0.0}
    source = ModelSource.from_attributes(attrs)
    assert source.articulate == (("wing_p", 30.0),)
    turned = model("mirror").posed({"wing_p": 30.0}).craft
    assert np.array_equal(source.spacecraft().triangles, turned.triangles)
