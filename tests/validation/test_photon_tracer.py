"""The Monte Carlo photon tracer against closed forms, its power balance and its determinism.

A tracer estimate passes when it lies within ``Z`` of its own standard errors of the exact value
(plus a floor for round-off and, on the sphere, faceting), and when that standard error is small,
so the check has teeth.
"""

from __future__ import annotations

import numpy as np
import pytest

from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes import primitives
from sunwind.validation.analytic_srp import plate_srp, sphere_srp
from sunwind.validation.analytic_srp_law import Optics
from sunwind.validation.analytic_v_groove import v_groove_srp
from sunwind.validation.cases import BACK_OPTICS, OPTICS, sun_vector
from sunwind.validation.concave import CONCAVE_CASES, TRANSLUCENT
from sunwind.validation.concave_meshes import l_mesh, open_box_mesh, v_groove_mesh
from sunwind.validation.photon_tracer import trace_photons
from sunwind.validation.sampling import Sampling

#: Standard errors a tracer estimate may lie from the exact value.
Z = 4.0


def _optics(optics: Optics) -> dict[str, float]:
    return {"reflectivity": optics.rho, "specular_fraction": optics.beta, "transmissivity": optics.sigma}


def _build(mesh: MeshData, front: Optics, back: Optics | None = None, sheet: bool = True) -> Spacecraft:
    """``mesh`` with one finish: a sheet (two-sided when ``back`` is given) or a closed body."""
    materials = {"front": _optics(front)}
    rule: object = "front"
    if sheet:
        rule = {"front": "front"}
        if back is not None:
            materials["back"] = _optics(back)
            rule = {"front": "front", "back": "back"}
    return build_spacecraft(mesh, parse_materials({"materials": materials, "parts": {"*": rule}}))


def _assert_close(result, exact_force, exact_torque, length_m: float, floor: float = 1e-6) -> None:
    """Tracer within ``Z`` standard errors (plus ``floor`` of the scale) of the exact loads."""
    scale = np.linalg.norm(exact_force)
    force_gap = np.linalg.norm(result.force_N - exact_force)
    torque_gap = np.linalg.norm(result.torque_Nm - exact_torque)
    assert result.force_error_N <= 5e-3 * scale, "the tracer's own error is too large to judge by"
    assert force_gap <= Z * result.force_error_N + floor * scale, (
        force_gap / scale,
        result.force_error_N / scale,
    )
    assert torque_gap <= Z * result.torque_error_Nm + floor * scale * length_m, (
        torque_gap / (scale * length_m),
        result.torque_error_Nm / (scale * length_m),
    )


@pytest.mark.parametrize("finish", OPTICS, ids=str)
@pytest.mark.parametrize("two_sided", [False, True], ids=["one-sided", "two-sided"])
def test_flat_plate_matches_the_closed_form(finish, two_sided):
    """2 x 1 m plate, Sun from the front at three angles, and from behind for the two-sided plate."""
    optics = OPTICS[finish]
    craft = _build(primitives.plate(2.0, 1.0, 4), optics, BACK_OPTICS if two_sided else None)
    alphas = (0.0, 40.0, 75.0, 130.0) if two_sided else (0.0, 40.0, 75.0)
    for seed, alpha in enumerate(alphas):
        u = sun_vector(alpha)
        result = trace_photons(craft, u, Sampling(40_000, seed=seed), reference_point_m=np.zeros(3))
        exact = plate_srp(
            2.0, 1.0, u, optics, one_sided=not two_sided, back_optics=BACK_OPTICS if two_sided else None
        )
        _assert_close(result, exact.force_N, exact.torque_Nm, 1.0)


@pytest.mark.slow
@pytest.mark.parametrize("finish", OPTICS, ids=str)
def test_sphere_matches_the_closed_form(finish):
    """Faceted sphere (the default 118 808 triangles, projected area 5e-5 short): floor 1e-4."""
    optics = OPTICS[finish]
    craft = _build(primitives.sphere(1.0), optics, sheet=False)
    u = sun_vector(50.0)
    result = trace_photons(craft, u, Sampling(200_000), reference_point_m=np.zeros(3))
    exact = sphere_srp(1.0, u, optics)
    _assert_close(result, exact.force_N, exact.torque_Nm, 1.0, floor=1e-4)


def test_closed_body_passes_transmitted_light_untouched():
    """A closed cube with sigma = 0.1: the transmitted share leaves along s, as in the convex law."""
    optics = OPTICS["mixed"]
    craft = _build(primitives.box((1.0, 1.0, 1.0), 4), optics, sheet=False)
    u = np.array([0.4, -0.3, 0.6]) / np.linalg.norm([0.4, -0.3, 0.6])
    result = trace_photons(craft, u, Sampling(100_000), reference_point_m=np.zeros(3))
    force, torque = np.zeros(3), np.zeros(3)
    for axis in range(3):  # each face is a unit plate: turn the Sun into its frame, the loads back
        for sign in (1.0, -1.0):
            e = np.eye(3)
            rotation = np.array([e[(axis + 1) % 3], sign * e[(axis + 2) % 3], sign * e[axis]])
            face = plate_srp(1.0, 1.0, rotation @ u, optics)
            force += rotation.T @ face.force_N
            torque += rotation.T @ face.torque_Nm + np.cross(sign * e[axis] / 2, rotation.T @ face.force_N)
    _assert_close(result, force, torque, 1.0)


@pytest.mark.parametrize("rho", [1.0, 0.9, 0.5])
@pytest.mark.parametrize("psi", [0.0, 12.0, 27.0, -38.0, 45.0])
def test_v_groove_matches_its_closed_form(rho, psi):
    """Mirror V-groove lit across its axis: the share ``tan psi`` leaves after one bounce, the rest is
    retro-reflected after two (sunwind.validation.analytic_v_groove Notes)."""
    craft = _build(v_groove_mesh(), Optics(rho, 1.0, 0.0), Optics(rho, 1.0, 0.0))
    u = np.array([np.sin(np.radians(psi)), 0.0, np.cos(np.radians(psi))])
    ref = craft.default_reference[0]
    result = trace_photons(craft, u, Sampling(50_000, seed=7))
    exact = v_groove_srp(1.0, 3.0, psi, rho, ref_point_m=ref)
    _assert_close(result, exact.force_N, exact.torque_Nm, 1.0)
    t = np.tan(np.radians(abs(psi)))
    one_bounce = result.bounces[1] / result.bounces[1:].sum()
    assert one_bounce == pytest.approx(t, abs=3e-3)


def _balance_models() -> dict[str, tuple[Spacecraft, np.ndarray]]:
    mixed = OPTICS["mixed"]
    return {
        "open box, diffuse": (
            _build(open_box_mesh(), Optics(0.9, 0.0, 0.0), Optics(0.9, 0.0, 0.0)),
            np.array([0.2, 0.1, 1.0]),
        ),
        "L, translucent": (_build(l_mesh(), TRANSLUCENT, TRANSLUCENT), np.array([1.0, -0.5, 0.7])),
        "closed cube, sigma 0.1": (
            _build(primitives.box((1.0, 2.0, 1.0), 3), mixed, sheet=False),
            np.ones(3),
        ),
        "one-sided plate from behind": (
            _build(primitives.plate(1.0, 1.0, 2), mixed),
            np.array([0.3, 0.0, -1.0]),
        ),
    }


@pytest.mark.parametrize("name", list(_balance_models()))
def test_power_balance(name):
    """incident = absorbed + escaped + cut, bundle by bundle, so to round-off."""
    craft, u = _balance_models()[name]
    for max_bounces in (100, 2):
        result = trace_photons(craft, u, Sampling(20_000, max_bounces=max_bounces))
        total = result.absorbed_W + result.escaped_W + result.cut_W
        assert result.incident_W > 0
        assert total == pytest.approx(result.incident_W, rel=1e-9, abs=0)
        assert result.bounces.sum() == result.photons
    if name == "one-sided plate from behind":  # the back of a one-sided sheet absorbs all it meets
        assert result.absorbed_W == pytest.approx(result.incident_W, rel=1e-12)
        assert np.allclose(np.cross(result.force_N, u), 0.0, atol=1e-12 * np.linalg.norm(result.force_N))


def test_bounce_cap_is_reported():
    """A diffuse open box keeps light bouncing: a cap of 2 cuts some of it and says how much."""
    craft = _build(open_box_mesh(), Optics(0.9, 0.0, 0.0), Optics(0.9, 0.0, 0.0))
    capped = trace_photons(craft, [0.0, 0.0, 1.0], Sampling(20_000, max_bounces=2))
    free = trace_photons(craft, [0.0, 0.0, 1.0], Sampling(20_000))
    assert capped.cut_W > 0.2 * capped.incident_W
    assert free.cut_W < 1e-3 * free.incident_W
    assert len(capped.bounces) == 3 and capped.bounces[2] > 0
    assert free.mean_bounces > 3


def test_same_seed_same_bits_and_other_seeds_differ():
    case = next(c for c in CONCAVE_CASES if c.name == "open box")
    craft = case.spacecraft("mixed")
    u = [0.3, 0.2, 0.9]
    a, b = (trace_photons(craft, u, Sampling(30_000, seed=11)) for _ in range(2))
    c = trace_photons(craft, u, Sampling(30_000, seed=12))
    for name in ("force_N", "torque_Nm", "force_se_N", "torque_se_Nm", "bounces"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert a.absorbed_W == b.absorbed_W and a.escaped_W == b.escaped_W
    assert not np.array_equal(a.force_N, c.force_N)
    assert np.linalg.norm(a.force_N - c.force_N) < 5 * np.hypot(a.force_error_N, c.force_error_N)


def test_result_reports_its_inputs():
    craft = _build(primitives.plate(1.0, 1.0, 2), Optics(0.5, 0.5, 0.0))
    result = trace_photons(craft, [0.0, 0.0, 2.0], Sampling(1_001, batches=4), flux_W_m2=1000.0)
    assert result.photons == 1_004 and result.batches == 4
    assert np.allclose(result.sun_vector, [0.0, 0.0, 1.0])
    assert np.allclose(result.reference_point_m, craft.default_reference[0])
    assert result.incident_W == pytest.approx(1000.0)
    assert result.seconds > 0 and result.photons_per_second > 0
    with pytest.raises(ValueError):
        trace_photons(craft, [0.0, 0.0, 1.0], Sampling(10, batches=1))


@pytest.mark.parametrize("finish", ["specular", "diffuse"])
def test_radiosity_model_changes_nothing_on_a_pure_finish(finish):
    """Only the specular share or a sheet's transmission of diffusely reflected light differ."""
    craft = next(c for c in CONCAVE_CASES if c.name == "open box").spacecraft(finish)
    u = [0.3, 0.2, 0.9]
    physics = trace_photons(craft, u, Sampling(20_000, seed=3))
    model = trace_photons(craft, u, Sampling(20_000, seed=3), radiosity_model=True)
    assert np.array_equal(physics.force_N, model.force_N)
    assert np.array_equal(physics.torque_Nm, model.torque_Nm)


@pytest.mark.parametrize(("name", "finish"), [("open box", "mixed"), ("L", "translucent wall")])
def test_radiosity_model_differs_from_the_physics_on_a_mixed_finish(name, finish):
    """Re-emitting all reflected (and transmitted) diffuse light as Lambertian moves the force by
    about 1 % on these cases: far beyond the tracer's noise, so the two runs are told apart."""
    case = next(c for c in CONCAVE_CASES if c.name == name)
    craft = case.spacecraft(finish)
    u = sun_vector(20.0) if name == "open box" else np.array([0.4, -0.7, 0.45])
    physics = trace_photons(craft, u, Sampling(300_000))
    model = trace_photons(craft, u, Sampling(300_000), radiosity_model=True)
    gap = np.linalg.norm(physics.force_N - model.force_N)
    assert gap > 5 * np.hypot(physics.force_error_N, model.force_error_N)
    assert model.absorbed_W + model.escaped_W + model.cut_W == pytest.approx(model.incident_W, rel=1e-9)
