"""The torque reference point in the simulator formats (issue 33), on tables of real sweeps of a coarse
box-wing: a SPAD file says it holds forces only and that the point does not enter; a Basilisk lookup
moves the torques to the body origin B, names the point in a comment and, for a point off the origin,
warns at write time what to set in Basilisk; Tudat files keep the moments about the point, name the
setting Tudat needs, and warn when the point is a default centroid."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr

from sunwind.forces.export import ReferencePointWarning
from sunwind.forces.export.basilisk import write_basilisk
from sunwind.forces.export.spad import write_spad
from sunwind.forces.export.tudat import write_tudat
from sunwind.forces.gas import explicit
from sunwind.forces.tables import DragSetup, SrpSetup, sweep
from sunwind.geometry.materials import Material
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing
from tests.forces.export.test_basilisk import load_lookup
from tests.forces.export.test_spad import strict_read
from tests.forces.export.test_tudat import read_coefficients

#: The reference point off the origin [m], and how the files write it.
POINT, SHOWN = (0.1, -0.2, 0.3), "[0.1, -0.2, 0.3]"
OPTICS = ("--reflectivity", "0.4", "--specular-fraction", "0.5", "--two-sided", "wing*")


@pytest.fixture(scope="module")
def tables() -> dict:
    """Grid tables (30 deg, SRP and drag) of a 96-triangle box-wing about ``POINT``, about the origin,
    and about the default point (the area centroid, the origin to rounding)."""
    craft = build_spacecraft(
        box_wing(facet_size=0.5), uniform=Material("paint", 0.4, 0.5, 0.1), two_sided=["wing*"]
    )
    air = explicit(3e-12, 900.0, "O:0.8,N2:0.2")

    def swept(point) -> xr.Dataset:
        common = {"sampling": ShadowSampling(samples=1), "reflections": "none", "reference_point_m": point}
        srp, drag = SrpSetup(**common), DragSetup(speed_m_s=7600.0, atmosphere=air, **common)
        return sweep(craft, srp=srp, drag=drag, step_deg=30.0)

    return {"point": swept(POINT), "origin": swept((0.0, 0.0, 0.0)), "default": swept(None)}


def cross(r: tuple[float, float, float], f: np.ndarray) -> np.ndarray:
    """``r x f`` for rows ``f`` (n, 3), written out component by component."""
    x, y, z = r
    return np.stack([y * f[:, 2] - z * f[:, 1], z * f[:, 0] - x * f[:, 2], x * f[:, 1] - y * f[:, 0]], 1)


def silently(write, *args):
    """``write(*args)``, failing on any warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return write(*args)


@pytest.mark.parametrize("kind", ["srp", "drag"])
def test_spad_says_it_holds_forces_only_and_the_point_does_not_enter(tables, tmp_path, kind):
    spad = strict_read(silently(write_spad, tables["point"], tmp_path / "point.spo", kind))  # GMAT's rules
    header = spad["header"]
    assert header["Holds"] == "forces only (area vectors); GMAT computes no torque from a SPAD file"
    point = f"{SHOWN} m (user), of the table's torques; it does not enter the areas"
    assert header["Reference Point"] == point
    assert header["Frame"] == "body frame of the mesh" and header["Analysis Type"] == "Area"
    origin = strict_read(silently(write_spad, tables["origin"], tmp_path / "origin.spo", kind))
    np.testing.assert_array_equal(spad["area"], origin["area"])  # the point does not enter
    assert origin["header"]["Reference Point"].startswith("[0, 0, 0] m (user),")


def test_basilisk_moves_the_torques_to_b_and_warns_what_to_set(tables, tmp_path):
    table = tables["point"]
    with pytest.warns(ReferencePointWarning) as said:
        path = write_basilisk(table, tmp_path / "srp.xml")
    assert len(said) == 1
    assert str(said[0].message) == (
        "Basilisk lookup srp.xml: torque_B is about the body-frame origin B, which the format fixes: the "
        f"torques about the reference point {SHOWN} m (user) were moved there (M_ref + r_ref x F); in "
        "Basilisk make B the mesh origin and set the hub's r_BcB_B to the centre of mass relative to B "
        f"({SHOWN} if that is the reference point): the lookup gives the torque about B, Basilisk's "
        "dynamics take the centre of mass from r_BcB_B"
    )
    assert (
        f"<!-- reference point of the table's torques: {SHOWN} m (user); torque_B = M_ref + r_ref x F is "
        "about B, the point the format fixes (B: the mesh origin; the hub's r_BcB_B: the centre of mass "
        "from B) -->"
    ) in path.read_text()
    lookup = load_lookup(path)
    # each entry against the table's node in its direction (flux 1361 W/m^2: the 1 au values as swept)
    sun = table["sun_vector"].values.reshape(-1, 3)
    node = np.argmax(lookup["sHat_B"] @ sun.T, axis=1)
    force, torque = (table[name].values.reshape(-1, 3)[node] for name in ("srp_force_N", "srp_torque_Nm"))
    scale = np.abs(lookup["torque_B"]).max()
    np.testing.assert_allclose(lookup["force_B"], force, rtol=1e-15)
    np.testing.assert_allclose(lookup["torque_B"], torque + cross(POINT, force), rtol=0, atol=1e-13 * scale)
    # and against the sweep taken about the origin itself
    about_b = load_lookup(silently(write_basilisk, tables["origin"], tmp_path / "origin.xml"))
    np.testing.assert_allclose(lookup["torque_B"], about_b["torque_B"], rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize(
    ("name", "shown"),
    [("origin", "[0, 0, 0] m (user)"), ("default", "[0, 0, 0] m (area centroid (default))")],
)
def test_basilisk_with_the_point_at_the_origin_says_it_and_warns_nothing(tables, tmp_path, name, shown):
    """The default point, the box-wing's area centroid, is the origin to rounding (1e-17 m)."""
    path = silently(write_basilisk, tables[name], tmp_path / "srp.xml")
    assert f"<!-- reference point of the table's torques: {shown}; " in path.read_text()


def test_tudat_files_keep_the_moments_about_the_point_and_name_the_setting(tables, tmp_path):
    files = silently(write_tudat, tables["point"], tmp_path / "aero")  # the user's point: no warning
    assert files.moment_reference_point_m == POINT
    setting = (
        f"# moment reference point: {SHOWN} m (user); pass moment_reference_point={SHOWN} to Tudat's "
        "tabulated_from_files: Tudat then moves the moments to the body's centre of mass r_com, adding "
        "(r_ref - r_com) x C_F / L_ref (left NaN, it takes them as about the centre of mass)\n"
    )
    for path in [*files.force.values(), *files.moment.values()]:
        assert setting in path.read_text()
    # Tudat's correction with r_com at the origin turns them into the moments about the origin
    origin = silently(write_tudat, tables["origin"], tmp_path / "origin")
    c_f, c_m, c_m_origin = (
        np.stack([read_coefficients(paths[i])[2] for i in range(3)], axis=-1)
        for paths in (files.force, files.moment, origin.moment)
    )
    moved = c_m + cross(POINT, c_f.reshape(-1, 3)).reshape(c_f.shape) / files.reference_length_m
    np.testing.assert_allclose(moved, c_m_origin, rtol=0, atol=1e-12 * np.abs(c_m_origin).max())


def test_tudat_files_about_a_default_point_warn_what_to_pass(tables, tmp_path):
    with pytest.warns(ReferencePointWarning) as said:
        write_tudat(tables["default"], tmp_path / "aero")
    assert len(said) == 1 and said[0].message.parameters == ("reference_point_m",)
    assert str(said[0].message) == (
        "Tudat files aero_C*.txt: the moment coefficients are about the area centroid (default) [0, 0, 0] "
        "m, not the centre of mass: pass moment_reference_point=[0, 0, 0] to Tudat's tabulated_from_files, "
        "which then moves them to the body's centre of mass (left NaN, Tudat takes them as about it), or "
        "sweep again with the centre of mass as reference_point_m"
    )


def test_sweep_to_basilisk_with_a_ref_point_shows_one_warning_line(run_cli, tmp_path):
    """``sunwind sweep ... --format basilisk -o x --ref-point 0.1 0 0``: the warning is one line of its own
    (``sunwind: warning: ...``); at the origin there is none."""
    mesh = tmp_path / "box_wing.obj"
    assert run_cli("mesh", "box_wing", "--facet-size", "0.5", "-o", mesh)[0] == 0
    srp = ("sweep", mesh, *OPTICS, "--srp", "--samples", "1", "--reflections", "none", "--step", "45")
    code, out, err = run_cli(*srp, "--format", "basilisk", "-o", tmp_path / "x", "--ref-point", 0.1, 0, 0)
    assert code == 0, err
    assert f"wrote {tmp_path / 'x.xml'}" in out
    (line,) = [line for line in err.splitlines() if "r_BcB_B" in line or "Basilisk" in line]
    assert line.startswith("sunwind: warning: Basilisk lookup x.xml: torque_B is about the body-frame")
    assert "reference point [0.1, 0, 0] m (user) were moved there" in line and line.endswith("from r_BcB_B")
    code, _, err = run_cli(*srp, "-o", tmp_path / "y.xml", "--ref-point", 0, 0, 0)
    assert code == 0 and "warning" not in err, err
