"""Tudat coefficient files: Tudat's file layout, its angle-of-attack/sideslip convention, body-frame
coefficients C_F = F / (q S), C_M = M / (q S L)."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from helpers.tables import ATTRS, REFERENCE_POINT_M, field, grid_table, list_table
from sunwind.forces.export.tudat import flow_vector, write_tudat
from sunwind.geometry.errors import InputError


def read_coefficients(path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """alpha, beta [rad] and the (n_alpha, n_beta) block, by Tudat's readCoefficientsFile rules."""
    lines = [line.strip() for line in path.read_text(encoding="ascii").splitlines()]
    rows = [re.split(r"[\t ;,]+", line) for line in lines if line and not line.startswith("#")]
    assert rows[0] == ["2"]
    alpha, beta = (np.array(row, dtype=float) for row in rows[1:3])
    block = np.array(rows[3:], dtype=float)
    assert block.shape == (len(alpha), len(beta))
    return alpha, beta, block


def test_alpha_beta_follow_tudat_aerodynamic_to_body_rotation():
    """x of the airspeed-based frame in body axes: R_BA = Ry(-alpha) Rz(beta) (Tudat, Mooij)."""
    rng = np.random.default_rng(4)
    alpha, beta = rng.uniform(-np.pi, np.pi, 20), rng.uniform(-np.pi / 2, np.pi / 2, 20)
    for a, b, u in zip(alpha, beta, flow_vector(alpha, beta), strict=True):
        rotation = Rotation.from_rotvec([0.0, -a, 0.0]) * Rotation.from_rotvec([0.0, 0.0, b])
        np.testing.assert_allclose(u, rotation.apply([1.0, 0.0, 0.0]), atol=1e-15)
        np.testing.assert_allclose([np.arctan2(u[2], u[0]), np.arcsin(u[1])], [a, b], atol=1e-12)


def test_files_hold_body_frame_coefficients(tmp_path):
    table = grid_table(10.0, kinds=("drag",))
    files = write_tudat(table, tmp_path / "craft")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"craft_C{kind}{axis}.txt" for kind in "FM" for axis in "xyz"
    )
    assert files.reference_area_m2 == ATTRS["reference_area_m2"]
    assert files.moment_reference_point_m == REFERENCE_POINT_M
    qs = ATTRS["dynamic_pressure_Pa"] * ATTRS["reference_area_m2"]
    scale = {"force": 1.0 / qs, "moment": 1.0 / (qs * ATTRS["reference_length_m"])}
    for kind, paths in (("force", files.force), ("moment", files.moment)):
        for index, path in paths.items():
            alpha, beta, block = read_coefficients(path)
            np.testing.assert_allclose(np.degrees(alpha), np.arange(-180, 181, 10), atol=1e-12)
            np.testing.assert_allclose(np.degrees(beta), np.arange(-90, 91, 10), atol=1e-12)
            u = flow_vector(alpha[:, None], beta[None, :])
            exact = field(u, 1e-3)[0 if kind == "force" else 1][..., index] * scale[kind]
            tolerance = 2e-3 * np.abs(exact).max()  # bicubic from the 10-deg az/el grid
            np.testing.assert_allclose(block, exact, rtol=0, atol=tolerance)
            # alpha = beta = 0 is u = +x, a node of the az/el grid: exact there
            np.testing.assert_allclose(block[18, 9], exact[18, 9], rtol=1e-12)
    assert "body_fixed_frame_coefficients" in files.force[0].read_text()


def test_bad_input(tmp_path):
    with pytest.raises(InputError, match="need a grid of flow directions, not an attitude list"):
        write_tudat(list_table(), tmp_path / "craft")
    with pytest.raises(InputError) as error:
        write_tudat(grid_table(15.0, kinds=("srp",)), tmp_path / "craft")
    assert str(error.value) == (
        "cannot write Tudat coefficient files: the table has no drag_force_N, drag_torque_Nm; "
        "run the sweep with drag included"
    )
    with pytest.raises(InputError, match="angle-of-attack step 7 deg does not divide 360 deg; use"):
        write_tudat(grid_table(15.0), tmp_path / "craft", alpha_step_deg=7.0)
    table = grid_table(30.0)
    del table.attrs["reference_length_m"]
    with pytest.raises(InputError, match="reference_length_m attribute is missing or not positive"):
        write_tudat(table, tmp_path / "craft")
    assert not list(tmp_path.iterdir())
