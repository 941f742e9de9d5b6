"""The solver's inter-reflection against the Monte Carlo photon tracer and the V-groove closed form.

Every case of :data:`validation.concave.CONCAVE_CASES` (V-groove, L, open box, the sample's dish),
each finish, each Sun direction: the solver with ``reflections="full"`` must land within
:data:`~validation.concave.TOLERANCE` (1 %) of the tracer in force (over ``|F_mc|``), torque (over
:func:`~validation.concave.torque_scale`) and power (over the incident power). The tracer runs
:data:`~validation.concave.MC_PHOTONS` (600 000) bundles per comparison, enough that its own
standard error stays below a quarter of the tolerance, which is asserted too.

Two comparisons per case: against the physics, and against the tracer following the solver's own
diffuse model (METHOD.md eq. 12 re-emits all the reflected and transmitted light a side receives
diffusely, ``radiosity_model=True``). The second isolates the implementation; the first also
measures the model, which on finishes that mix specular and diffuse reflection, or on translucent
sheets, is off by up to ~1.6 % in force and ~3 % in power on these cases. The whole file takes
about a minute on 2 cores, three quarters of it in the tracer.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from forces.evaluate import srp
from validation.analytic_srp import Optics
from validation.concave import (
    CONCAVE_CASES,
    FINISHES,
    MC_PHOTONS,
    TOLERANCE,
    compare,
    finished_spacecraft,
    sun_from_az_el,
    torque_scale,
    trace_case,
    v_groove_srp,
)

#: The tracer's standard error may be at most this share of the tolerance.
SIGMA_SHARE = 0.25

COMPARISONS = [
    pytest.param(case, finish, sun, id=f"{case.name}/{finish}/az{sun[0]:g}/el{sun[1]:g}")
    for case in CONCAVE_CASES
    for finish in case.finishes
    for sun in case.suns_deg
]
#: Finishes on which the radiosity model and the physics part: specular and diffuse shares together, or
#: light through a sheet.
MIXED_FINISHES = ("mixed", "translucent wall", "sample")
MODEL_COMPARISONS = [p for p in COMPARISONS if p.values[1] in MIXED_FINISHES]
PURE_COMPARISONS = [p for p in COMPARISONS if p.values[1] not in MIXED_FINISHES]
#: Against the physics on mixed finishes the model itself is off: the radiosity balance re-emits
#: diffusely the specular (and transmitted) share of the diffuse light a side receives. Measured: up
#: to 1.6 % in force and torque and 3.2 % of the incident power (the open box lit straight in); the
#: tolerances below bound that model error, and the comparisons with the tracer following the same
#: model hold the solver itself to 1 %.
MODEL_FORCE_TOLERANCE = 0.025
MODEL_POWER_TOLERANCE = 0.04
CASE = {case.name: case for case in CONCAVE_CASES}


@pytest.mark.parametrize(("case", "finish", "sun"), PURE_COMPARISONS)
def test_full_reflection_matches_the_photon_tracer(case, finish, sun):
    row = compare(case, finish, sun, photons=MC_PHOTONS)
    assert row.force_mc_sigma < SIGMA_SHARE * TOLERANCE, row
    assert row.torque_mc_sigma < SIGMA_SHARE * TOLERANCE, row
    assert row.force_difference <= TOLERANCE, row
    assert row.torque_difference <= TOLERANCE, row
    assert row.power_difference <= TOLERANCE, row
    assert row.k_is > 0, row


@pytest.mark.parametrize(("case", "finish", "sun"), MODEL_COMPARISONS)
def test_on_mixed_finishes_the_model_error_against_the_physics_stays_bounded(case, finish, sun):
    row = compare(case, finish, sun, photons=MC_PHOTONS)
    assert row.force_mc_sigma < SIGMA_SHARE * TOLERANCE, row
    assert row.force_difference <= MODEL_FORCE_TOLERANCE, row
    assert row.torque_difference <= MODEL_FORCE_TOLERANCE, row
    assert row.power_difference <= MODEL_POWER_TOLERANCE, row


@pytest.mark.parametrize(("case", "finish", "sun"), MODEL_COMPARISONS)
def test_full_reflection_matches_the_tracer_following_the_radiosity_model(case, finish, sun):
    """Finishes whose diffuse light the model re-emits differently from the physics (mixed ones, the
    translucent wall, the sample's materials): the solver must implement its model."""
    row = compare(case, finish, sun, photons=MC_PHOTONS, radiosity_model=True)
    assert row.force_mc_sigma < SIGMA_SHARE * TOLERANCE, row
    assert row.torque_mc_sigma < SIGMA_SHARE * TOLERANCE, row
    assert row.force_difference <= TOLERANCE, row
    assert row.torque_difference <= TOLERANCE, row
    assert row.power_difference <= TOLERANCE, row


@pytest.mark.parametrize("rho", [1.0, 0.9])
@pytest.mark.parametrize("psi", [0.0, 20.0, -35.0])
def test_v_groove_solver_matches_the_closed_form(rho, psi):
    """Mirror groove lit across its axis (validation.concave Notes); exact, so no tracer noise."""
    case = CASE["v-groove"]
    mirror = Optics(rho, 1.0, 0.0)
    craft = finished_spacecraft(case.mesh(), {"*": (mirror, mirror)}, f"v-groove/mirror {rho}")
    u = np.array([math.sin(math.radians(psi)), 0.0, math.cos(math.radians(psi))])
    ref = craft.default_reference[0]
    exact = v_groove_srp(1.0, 3.0, psi, rho, ref_point_m=ref)
    result = srp(craft, u, reference_point_m=ref, reflections="full")
    scale = torque_scale(exact.force_N, exact.torque_Nm, case.size_m)
    assert np.linalg.norm(result.force_N - exact.force_N) <= TOLERANCE * np.linalg.norm(exact.force_N)
    assert np.linalg.norm(result.torque_Nm - exact.torque_Nm) <= TOLERANCE * scale


@pytest.mark.parametrize("case", CONCAVE_CASES, ids=lambda c: c.name)
def test_direct_part_matches_single_interaction_tracing(case):
    """``reflections="none"`` is the direct law: every photon leaves after its first interaction, which
    is the tracer capped at one interaction. Also: the full result splits into direct + reflected."""
    for sun in case.suns_deg:
        u = sun_from_az_el(*sun)
        mc = trace_case(case, "mixed", sun, photons=200_000, max_bounces=1)
        craft = case.spacecraft("mixed")
        none = srp(craft, u, reference_point_m=mc.reference_point_m, reflections="none")
        full = srp(craft, u, reference_point_m=mc.reference_point_m, reflections="full")
        f_mc = np.linalg.norm(mc.force_N)
        scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)
        assert mc.force_error_N < SIGMA_SHARE * TOLERANCE * f_mc, sun
        assert np.linalg.norm(none.force_N - mc.force_N) <= TOLERANCE * f_mc, sun
        assert np.linalg.norm(none.torque_Nm - mc.torque_Nm) <= TOLERANCE * scale, sun
        assert np.allclose(full.direct_force_N, none.force_N, rtol=1e-9, atol=0)
        assert np.allclose(full.direct_torque_Nm, none.torque_Nm, rtol=1e-9, atol=0)
        assert np.allclose(full.direct_force_N + full.reflected_force_N, full.force_N, rtol=1e-12, atol=0)
        assert np.allclose(
            full.direct_torque_Nm + full.reflected_torque_Nm, full.torque_Nm, rtol=1e-12, atol=0
        )
        assert none.power.incident_W == pytest.approx(mc.incident_W, rel=TOLERANCE)


@pytest.mark.parametrize("case", CONCAVE_CASES, ids=lambda c: c.name)
def test_specular_mode_is_full_for_mirrors_and_none_for_lambertian_finishes(case):
    """``"specular"`` follows mirror beams only: all of ``"full"`` on a specular finish, nothing more
    than ``"none"`` on a purely diffuse one."""
    u = sun_from_az_el(*case.suns_deg[1])
    for finish, same_as in (("specular", "full"), ("diffuse", "none")):
        assert FINISHES[finish].sigma == 0
        craft = case.spacecraft(finish)
        ref = craft.default_reference[0]
        specular = srp(craft, u, reference_point_m=ref, reflections="specular")
        other = srp(craft, u, reference_point_m=ref, reflections=same_as)
        atol = 1e-6 * np.linalg.norm(other.force_N)
        assert np.allclose(specular.force_N, other.force_N, rtol=0, atol=atol), finish
        assert np.allclose(specular.torque_Nm, other.torque_Nm, rtol=0, atol=atol * case.size_m), finish


def test_power_balance_of_the_solver():
    """incident = absorbed + escaped, up to the power the chain cutoff drops, for every mixed case."""
    for case in CONCAVE_CASES:
        craft = case.spacecraft("mixed")
        power = srp(craft, sun_from_az_el(*case.suns_deg[0]), reflections="full").power
        rest = power.incident_W - power.absorbed_W - power.escaped_W
        assert abs(rest) <= 1e-4 * power.incident_W, case.name
