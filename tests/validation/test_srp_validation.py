"""The meshed solver against the closed forms, every case of validation/cases.py."""

import numpy as np
import pytest

from sunwind.validation.cases import REFINEMENT_CASES, SHADOW_CASE, SRP_CASES
from sunwind.validation.light_checks import refinement_study, run_shadow_case, run_srp_case

#: Plates (exact at any resolution) in the quick run; the curved bodies (seconds each) in the full one.
CONVEX = [pytest.param(c, marks=() if c.name.startswith("plate") else pytest.mark.slow) for c in SRP_CASES]


@pytest.mark.parametrize("case", CONVEX, ids=lambda c: c.name)
def test_convex_body_matches_its_closed_form_at_every_sun_angle(case):
    rows = run_srp_case(case)
    assert len(rows) == len(case.alphas_deg)
    worst_force = max(r.force_error for r in rows)
    worst_torque = max(r.torque_error for r in rows)
    assert worst_force <= case.rel_tol, (case.reason, rows)
    assert worst_torque <= case.rel_tol, (case.reason, rows)


@pytest.mark.slow
@pytest.mark.parametrize("case", REFINEMENT_CASES, ids=lambda c: c.name)
def test_error_falls_with_mesh_refinement_at_second_order(case):
    errors = refinement_study(case)
    assert errors[0] > errors[1] > errors[2]
    order = np.log2(errors[0] / errors[2]) / 2  # mean order over two halvings of the facet size
    assert 1.3 < order < 2.7, errors


def test_partial_shadow_force_and_torque_match_the_exact_answer():
    rows = run_shadow_case(SHADOW_CASE)
    for row in rows:
        assert row.force_error <= SHADOW_CASE.rel_tol and row.torque_error <= SHADOW_CASE.rel_tol, row
    assert min(r.reference for r in rows) > 0  # a real torque to test against


def test_partial_shadow_is_a_real_shadow():
    """The shadow removes a sizeable area from A for every direction checked."""
    for sun in SHADOW_CASE.sun_vectors:
        u = np.asarray(sun) / np.linalg.norm(sun)
        assert SHADOW_CASE.reference(u).shadow_area_m2 > 0.1
