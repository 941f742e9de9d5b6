"""Checks of the closed form of two parallel plates, one shadowing the other, against ray counts and chords.

The shadow's area is checked against a grid of ray tests; its area and first moment, and with them
plate A's torque, against exact chord integration along x = const; special cases (an axis-aligned
overlap, a shadow wholly on A, none at all) against plain plates.
"""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.validation.analytic_shadow import PlatePair, shadowed_plates_srp
from sunwind.validation.analytic_srp import plate_srp
from sunwind.validation.analytic_srp_law import SPEED_OF_LIGHT_M_S, ForceTorque, Optics, sun_vector_from_alpha

FLUX = 1361.0
PRESSURE = FLUX / SPEED_OF_LIGHT_M_S
REF = np.array([0.13, -0.21, 0.34])
EXACT_TOL = 1e-12  # of P A_ref (force) and P A_ref L_ref (torque), for identities that hold to rounding

MATERIALS = {
    "absorbing": Optics(0.0, 0.0, 0.0),
    "specular": Optics(1.0, 1.0, 0.0),
    "diffuse": Optics(1.0, 0.0, 0.0),
    "mixed": Optics(0.6, 0.3, 0.1),
}


def _gauss(breaks: list[float], order: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights over consecutive breakpoints."""
    x, w = np.polynomial.legendre.leggauss(order)
    lo, hi = np.array(breaks[:-1])[:, None], np.array(breaks[1:])[:, None]
    return (0.5 * (hi + lo) + 0.5 * (hi - lo) * x).ravel(), (0.5 * (hi - lo) * w).ravel()


def _assert_close(got: ForceTorque, want: ForceTorque, area: float, length: float, tol: float):
    """|dF| <= tol P A_ref and |dM| <= tol P A_ref L_ref."""
    force_err = np.linalg.norm(got.force_N - want.force_N) / (PRESSURE * area)
    torque_err = np.linalg.norm(got.torque_Nm - want.torque_Nm) / (PRESSURE * area * length)
    assert force_err <= tol, f"force error {force_err:.2e} of P A_ref"
    assert torque_err <= tol, f"torque error {torque_err:.2e} of P A_ref L_ref"


# ---------------------------------------------------------------------- shadowed plates


def _b_lifted_inside(points: np.ndarray, side_b, centre_b, gamma_deg, u) -> np.ndarray:
    """Which points (n, 2) of the plane z = 0 meet plate B on their ray toward the Sun."""
    lifted = points + (centre_b[2] / u[2]) * u[:2]
    gamma = np.radians(gamma_deg)
    rotation = np.array([[np.cos(gamma), -np.sin(gamma)], [np.sin(gamma), np.cos(gamma)]])
    local = (lifted - centre_b[:2]) @ rotation  # each row turned by -gamma into B's frame
    return np.all(np.abs(local) <= side_b / 2, axis=1)


def _grid_shadow(side_a, side_b, centre_b, gamma_deg, u, n: int = 1000):
    """Shadow area and its first moment on A from an n x n midpoint grid of ray tests."""
    cells = (np.arange(n) + 0.5) / n * side_a - side_a / 2
    x, y = np.meshgrid(cells, cells, indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel()])
    shadowed = _b_lifted_inside(points, side_b, np.asarray(centre_b), gamma_deg, u)
    cell = (side_a / n) ** 2
    return shadowed.sum() * cell, points[shadowed].sum(axis=0) * cell


def _sliced_shadow(side_a, side_b, centre_b, gamma_deg, u):
    """Shadow area and first moment on A by exact chords x = const.

    Along the line x = const on A, the ray test ``|R(-gamma) (p + (h/u_z) u_xy - c_B)| <= b/2``
    is two pairs of linear inequalities in y: the shadowed chord is their intersection with
    [-a/2, a/2]. Its ends are linear in x between the x-coordinates where two of the six
    boundary lines meet, so Gauss-Legendre on each such piece integrates the area and the
    moments exactly.
    """
    gamma = np.radians(gamma_deg)
    shift = (centre_b[2] / u[2]) * u[:2] - centre_b[:2]
    rows = np.array([[np.cos(gamma), np.sin(gamma)], [-np.sin(gamma), np.cos(gamma)]])
    lines = [(*row, sign * side_b / 2 - row @ shift) for row in rows for sign in (1, -1)]
    lines += [(0.0, 1.0, sign * side_a / 2) for sign in (1, -1)]  # n_x x + n_y y = d
    breaks = {-side_a / 2, side_a / 2}
    for k, (nx1, ny1, d1) in enumerate(lines):
        for nx2, ny2, d2 in lines[k + 1 :]:
            det = nx1 * ny2 - nx2 * ny1
            if abs(det) > 1e-12 and abs((d1 * ny2 - d2 * ny1) / det) < side_a / 2:
                breaks.add((d1 * ny2 - d2 * ny1) / det)
    x, w = _gauss(sorted(breaks), 4)

    lo, hi = np.full_like(x, -side_a / 2), np.full_like(x, side_a / 2)
    for c_x, c_y in rows:  # |c_x (x + shift_x) + c_y (y + shift_y)| <= b/2
        offset = c_x * (x + shift[0]) + c_y * shift[1]
        if abs(c_y) < 1e-15:
            hi = np.where(np.abs(offset) <= side_b / 2, hi, lo)
            continue
        ends = np.sort([(side_b / 2 - offset) / c_y, (-side_b / 2 - offset) / c_y], axis=0)
        lo, hi = np.maximum(lo, ends[0]), np.minimum(hi, ends[1])
    length = np.maximum(hi - lo, 0.0)
    centre_y = (hi + lo) / 2
    return w @ length, np.array([w @ (x * length), w @ (centre_y * length)])


def _plate_a_from_shadow(side_a, area, moment, u, optics) -> ForceTorque:
    """A's load from a shadow area and moment: uniform pressure on A minus the shadow."""
    full = plate_srp(side_a, side_a, u, optics)
    per_area = full.force_N / side_a**2
    force = per_area * (side_a**2 - area)
    torque = -np.cross(np.array([*moment, 0.0]), per_area) - np.cross(REF, force)
    return ForceTorque(force, torque)


SHADOW_CASE = (1.0, 0.6, np.array([0.35, -0.3, 0.4]))  # side a, side b, c_B: a partial clip
SHADOW_SUNS = [sun_vector_from_alpha(30.0), np.array([0.3, -0.25, 0.9]) / np.sqrt(0.9625)]


@pytest.mark.parametrize("gamma_deg", [0.0, 25.0, 45.0, 170.0])
@pytest.mark.parametrize("u", SHADOW_SUNS, ids=["inplane", "offplane"])
def test_shadow_area_matches_a_grid_count_of_rays(gamma_deg: float, u: np.ndarray) -> None:
    side_a, side_b, centre_b = SHADOW_CASE
    result = shadowed_plates_srp(PlatePair(side_a, side_b, centre_b, gamma_deg), u, MATERIALS["absorbing"])
    assert 0.0 < result.shadow_area_m2 < side_b**2
    area, _ = _grid_shadow(side_a, side_b, centre_b, gamma_deg, u)
    # a grid of cell h miscounts at most a strip h/2 wide along the shadow's edges:
    # perimeter (< 4 b) x h / 2 = 1.2e-3 a^2 at n = 1000
    assert result.shadow_area_m2 == pytest.approx(area, abs=1.2e-3 * side_a**2)


@pytest.mark.parametrize("gamma_deg", [0.0, 25.0, 45.0, 170.0])
@pytest.mark.parametrize("u", SHADOW_SUNS, ids=["inplane", "offplane"])
def test_shadowed_plate_torque_matches_chord_integration(gamma_deg: float, u: np.ndarray) -> None:
    side_a, side_b, centre_b = SHADOW_CASE
    result = shadowed_plates_srp(
        PlatePair(side_a, side_b, centre_b, gamma_deg), u, MATERIALS["mixed"], ref_point_m=REF
    )
    area, moment = _sliced_shadow(side_a, side_b, centre_b, gamma_deg, u)
    assert result.shadow_area_m2 == pytest.approx(area, abs=1e-12)
    want = _plate_a_from_shadow(side_a, area, moment, u, MATERIALS["mixed"])
    _assert_close(result.plate_a, want, side_a**2, side_a, 1e-11)


def test_axis_aligned_partial_shadow_is_exact() -> None:
    """gamma = 0: the shadow is the overlap of two axis-aligned squares, known in closed form."""
    u = np.array([0.3, 0.2, np.sqrt(1.0 - 0.13)])
    side_a, side_b, centre_b = 1.0, 0.6, np.array([0.35, -0.2, 0.4])
    result = shadowed_plates_srp(
        PlatePair(side_a, side_b, centre_b, 0.0), u, MATERIALS["mixed"], ref_point_m=REF
    )
    centre = centre_b[:2] - centre_b[2] / u[2] * u[:2]
    lo = np.maximum(centre - side_b / 2, -side_a / 2)
    hi = np.minimum(centre + side_b / 2, side_a / 2)
    area = np.prod(hi - lo)
    moment = area * (lo + hi) / 2
    assert result.shadow_area_m2 == pytest.approx(area, rel=1e-13)
    want = _plate_a_from_shadow(side_a, area, moment, u, MATERIALS["mixed"])
    _assert_close(result.plate_a, want, side_a**2, side_a, EXACT_TOL)


def test_shadow_wholly_on_a_is_the_translated_square() -> None:
    u = sun_vector_from_alpha(20.0)
    centre_b = np.array([0.1, 0.05, 0.3])
    result = shadowed_plates_srp(
        PlatePair(2.0, 0.5, centre_b, 33.0), u, MATERIALS["diffuse"], ref_point_m=REF
    )
    centre = centre_b[:2] - centre_b[2] / u[2] * u[:2]
    assert result.shadow_area_m2 == pytest.approx(0.25, rel=1e-13)
    assert len(result.shadow_polygon_m) == 4
    np.testing.assert_allclose(result.shadow_polygon_m.mean(axis=0), centre, atol=1e-15)
    want = _plate_a_from_shadow(2.0, 0.25, 0.25 * centre, u, MATERIALS["diffuse"])
    _assert_close(result.plate_a, want, 4.0, 2.0, EXACT_TOL)


def test_plates_out_of_each_others_light_are_two_independent_plates() -> None:
    u = sun_vector_from_alpha(40.0)
    centre_b = np.array([-1.5, 0.2, 0.5])  # its shadow falls further toward -x, off A
    optics_b = MATERIALS["specular"]
    result = shadowed_plates_srp(
        PlatePair(1.0, 0.6, centre_b, 20.0), u, MATERIALS["mixed"], optics_b=optics_b, ref_point_m=REF
    )
    assert result.shadow_area_m2 == 0.0
    assert result.shadow_polygon_m.shape == (0, 2)
    plate_a = plate_srp(1.0, 1.0, u, MATERIALS["mixed"], ref_point_m=REF)
    plate_b = plate_srp(0.6, 0.6, u, optics_b, ref_point_m=REF - centre_b)
    _assert_close(result.plate_a, plate_a, 1.0, 1.0, EXACT_TOL)
    _assert_close(result.plate_b, plate_b, 1.0, 1.0, EXACT_TOL)
    total = ForceTorque(plate_a.force_N + plate_b.force_N, plate_a.torque_Nm + plate_b.torque_Nm)
    _assert_close(result.total, total, 1.0, 1.0, EXACT_TOL)


def test_shadow_polygon_is_counter_clockwise_and_on_a() -> None:
    u = SHADOW_SUNS[1]
    result = shadowed_plates_srp(PlatePair(1.0, 0.8, [0.5, 0.4, 0.3], 30.0), u, MATERIALS["absorbing"])
    polygon = result.shadow_polygon_m
    assert np.all(np.abs(polygon) <= 0.5 + 1e-15)
    edges = np.roll(polygon, -1, axis=0) - polygon
    following = np.roll(edges, -1, axis=0)
    turns = edges[:, 0] * following[:, 1] - edges[:, 1] * following[:, 0]
    assert len(polygon) >= 3
    assert np.all(turns >= -1e-15)


# ---------------------------------------------------------------------- input checks


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (
            lambda: shadowed_plates_srp(PlatePair(1.0, 0.5, [0, 0, 1], 0.0), [1.0, 0.0, 0.0], (0, 0, 0)),
            "u_z > 0",
        ),
    ],
)
def test_bad_input_is_refused_with_the_reason(call, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()
