"""The test-particle Monte Carlo tracer against closed forms, equilibrium, and its own bookkeeping.

A tracer estimate passes when it lies within ``Z`` of its own standard errors of the exact value
**and** within a stated relative tolerance of the load's scale at the stated molecule count (so a
large standard error cannot make a check pass).

Closed forms (derived here; ``q = n m V^2 / 2``, ``c_m = sqrt(2 k T / m)``, ``S = V / c_m``). A flat
side of area ``A``, outward normal ``n``, in a stream of direction ``u`` (gas bulk velocity
``U = -V u``), with ``s = S (u . n)``: incident number flux, normal momentum flux (Schaaf & Chambre)

    N_i = n c_m [exp(-s^2) + sqrt(pi) s erfc(-s)] / (2 sqrt(pi))
    p_i = n m c_m^2 [s exp(-s^2) / (2 sqrt(pi)) + (s^2 + 1/2) erfc(-s) / 2]

and the incident tangential momentum flux ``m N_i U_t`` with ``U_t = -V (u - (u . n) n)``. Full
accommodation at ``T_w`` (``sigma_n = sigma_t = 1``) adds the re-emitted pressure
``p_r = m N_i c_w sqrt(pi) / 2`` (``c_w = sqrt(2 k T_w / m)``), so

    F_diffuse = A [-(p_i + p_r) n + m N_i U_t],      F_specular = -2 A p_i n.

A two-sided plate is the sum over its two sides; edge-on (``u . n = 0``) it has
``C_D = 2 / (S sqrt(pi))`` whatever ``T_w`` (METHOD.md). A sphere of radius ``R``, fully diffuse at
``T_w`` (reference area ``pi R^2``; Bird 1994, eq. 7.68), with the last term absent for a specular
sphere::

    C_D = exp(-S^2) (2 S^2 + 1) / (sqrt(pi) S^3) + (4 S^4 + 4 S^2 - 1) erf(S) / (2 S^4)
          + (2 sqrt(pi) / (3 S)) sqrt(T_w / T).

These equal :mod:`sunwind.validation.analytic_drag`, derived separately, to round-off (checked below when
that module is present). In a gas at rest with ``T_w = T`` (or with specular walls at any ``T_w``),
detailed balance makes the force and torque on any body, concave or not, vanish.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import erfc

from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes import primitives
from sunwind.meshes.assembly import transform
from sunwind.validation.concave_meshes import open_box_mesh
from sunwind.validation.gas_checks import (
    PLATE_MOLECULES,
    SPHERE_MOLECULES,
    TPMC_TOL,
    Z,
    tpmc_edge_on_checks,
    tpmc_plate_checks,
    tpmc_sphere_checks,
)
from sunwind.validation.sampling import Sampling
from sunwind.validation.tpmc import trace_molecules
from sunwind.validation.tpmc_kernels import WallInteraction
from sunwind.validation.tpmc_source import BOLTZMANN_J_K, SpeciesStream

#: Atomic oxygen [kg], thermosphere-like free stream and a cool wall.
MASS = 16 * 1.66053906660e-27
T_INF, T_WALL, DENSITY = 1000.0, 300.0, 1e15
C_M = math.sqrt(2 * BOLTZMANN_J_K * T_INF / MASS)
#: Torque reference point off the plate centre, so the torque check has teeth [m].
REFERENCE = np.array([0.3, -0.2, 0.1])
#: Plate checks: the relative tolerance on ``|F|`` (of ``q A`` when F = 0).
PLATE_TOL = TPMC_TOL

GAS = {"temperature_K": T_INF, "number_density_m3": DENSITY, "mass_kg": MASS}
NEUTRAL = Material("gas", 0.0, 0.0)


# ------------------------------------------------------------------------------------ closed forms
def side_force(normal, u, speed_ratio: float, area: float, diffuse: bool, wall_K: float = T_WALL):
    """Force [N] on one flat side (outward ``normal``) in the stream ``u``; module docstring."""
    normal, u = np.asarray(normal, dtype=float), np.asarray(u, dtype=float)
    gamma = float(u @ normal)
    s = speed_ratio * gamma
    n_i = DENSITY * C_M * (math.exp(-s * s) + math.sqrt(math.pi) * s * erfc(-s)) / (2 * math.sqrt(math.pi))
    p_i = (
        DENSITY
        * MASS
        * C_M**2
        * (s * math.exp(-s * s) / (2 * math.sqrt(math.pi)) + (s * s + 0.5) * erfc(-s) / 2)
    )
    if not diffuse:
        return -2 * p_i * area * normal
    c_w = math.sqrt(2 * BOLTZMANN_J_K * wall_K / MASS)
    p_r = MASS * n_i * c_w * math.sqrt(math.pi) / 2
    shear = MASS * n_i * (-speed_ratio * C_M) * (u - gamma * normal)
    return area * (-(p_i + p_r) * normal + shear)


def incident_shear(normal, u, speed_ratio: float, area: float):
    """Tangential momentum the stream brings to one side per second [N]."""
    normal, u = np.asarray(normal, dtype=float), np.asarray(u, dtype=float)
    gamma = float(u @ normal)
    s = speed_ratio * gamma
    n_i = DENSITY * C_M * (math.exp(-s * s) + math.sqrt(math.pi) * s * erfc(-s)) / (2 * math.sqrt(math.pi))
    return area * MASS * n_i * (-speed_ratio * C_M) * (u - gamma * normal)


def sphere_drag_coefficient(speed_ratio: float, diffuse: bool, wall_K: float = T_WALL) -> float:
    """Drag coefficient of a sphere, reference area ``pi R^2``; module docstring."""
    s = speed_ratio
    cd = math.exp(-s * s) * (2 * s * s + 1) / (math.sqrt(math.pi) * s**3) + (
        4 * s**4 + 4 * s * s - 1
    ) * math.erf(s) / (2 * s**4)
    if diffuse:
        cd += 2 * math.sqrt(math.pi) / (3 * s) * math.sqrt(wall_K / T_INF)
    return cd


def flow(alpha_deg: float, azimuth_deg: float = 17.0) -> np.ndarray:
    """Flow direction at angle of attack ``alpha`` to the plate plane z = 0, off the xz-plane."""
    a, p = math.radians(alpha_deg), math.radians(azimuth_deg)
    return np.array([math.cos(a) * math.cos(p), math.cos(a) * math.sin(p), math.sin(a)])


def dynamic_pressure(speed_ratio: float) -> float:
    """``q = n m V^2 / 2`` [Pa]."""
    return 0.5 * DENSITY * MASS * (speed_ratio * C_M) ** 2


def assert_close(result, force, torque, scale_N: float, lever_m: float, tol: float) -> None:
    """Within ``Z`` standard errors and within ``tol * scale_N`` (torque: ``tol * scale_N * lever_m``)."""
    force_gap = float(np.linalg.norm(result.force_N - force))
    torque_gap = float(np.linalg.norm(result.torque_Nm - torque))
    assert force_gap <= Z * result.force_error_N, (force_gap / result.force_error_N, force_gap / scale_N)
    assert force_gap <= tol * scale_N, (force_gap / scale_N, result.force_error_N / scale_N)
    assert torque_gap <= Z * result.torque_error_Nm + 1e-12 * scale_N * lever_m, torque_gap / max(
        result.torque_error_Nm, 1e-300
    )
    assert torque_gap <= tol * scale_N * lever_m, torque_gap / (scale_N * lever_m)


# ------------------------------------------------------------------------------------ fixtures
@pytest.fixture(scope="module")
def plate() -> Spacecraft:
    """2 x 1 m two-sided sheet in z = 0, centred at the origin (32 triangles, 64 sides)."""
    return build_spacecraft(primitives.plate(2.0, 1.0, 4), uniform=NEUTRAL, two_sided=["plate"])


@pytest.fixture(scope="module")
def open_box() -> Spacecraft:
    """Unit cube open at the top (z = +0.5), five two-sided sheets: a concave body."""
    return build_spacecraft(open_box_mesh(1.0, 4), uniform=NEUTRAL, two_sided=["*"])


def plate_loads(u, speed_ratio: float, diffuse_front: bool, diffuse_back: bool):
    """Exact force [N] and torque about ``REFERENCE`` [N m] on the 2 x 1 m plate."""
    force = side_force((0, 0, 1), u, speed_ratio, 2.0, diffuse_front) + side_force(
        (0, 0, -1), u, speed_ratio, 2.0, diffuse_back
    )
    return force, np.cross(-REFERENCE, force)  # uniform load: centre of pressure at the centroid


@pytest.mark.parametrize("speed_ratio", [1.0, 2.0, 8.0])
def test_closed_forms_agree_with_analytic_drag(speed_ratio):
    """The references above equal :mod:`sunwind.validation.analytic_drag` (derived apart) to round-off."""
    analytic = pytest.importorskip("sunwind.validation.analytic_drag")
    gas_law = pytest.importorskip("sunwind.validation.analytic_gas_law")
    q = dynamic_pressure(speed_ratio)
    u_sphere = np.array([0.3, -0.5, 0.8]) / math.sqrt(0.98)
    for diffuse in (True, False):
        surface = (
            gas_law.GasLaw("schaaf-chambre", wall_temperature_K=T_WALL)
            if diffuse
            else gas_law.GasLaw("specular")
        )
        for alpha in (0.0, 20.0, 50.0, 90.0):
            u = flow(alpha)
            force, torque = plate_loads(u, speed_ratio, diffuse, diffuse)
            load = analytic.plate_drag(
                2.0,
                1.0,
                gas_law.AnalyticStream(u, speed_ratio, T_INF, dynamic_pressure_Pa=q),
                surface,
                one_sided=False,
                ref_point_m=REFERENCE,
            )
            np.testing.assert_allclose(load.force_N, force, rtol=0, atol=1e-12 * q)
            np.testing.assert_allclose(load.torque_Nm, torque, rtol=0, atol=1e-12 * q)
        sphere = analytic.sphere_drag(1.0, gas_law.AnalyticStream(u_sphere, speed_ratio, T_INF), surface)
        assert sphere.drag_coefficient == pytest.approx(
            sphere_drag_coefficient(speed_ratio, diffuse), rel=1e-12
        )


# ------------------------------------------------------------------------------------ closed forms
@pytest.mark.slow
def test_flat_plate_matches_schaaf_chambre():
    """Two-sided plate, diffuse and specular, S = 2 and 8, angles of attack 0 (edge-on), 20, 50 and
    90 deg; within Z standard errors and 1 % at 400 000 molecules, none dropped or absorbed
    (validation.gas_checks, the closed forms of validation.analytic_drag, equal to those above)."""
    checks = list(tpmc_plate_checks(PLATE_MOLECULES))
    assert len(checks) == 16 and all(c.passed for c in checks), [c for c in checks if not c.passed]


def test_edge_on_plate_drag_coefficient():
    """Diffuse plate along the flow: ``C_D = 2 / (S sqrt(pi))`` on the one-side area, any T_w, S = 1, 2, 8."""
    checks = list(tpmc_edge_on_checks(PLATE_MOLECULES))
    assert len(checks) == 6 and all(c.passed for c in checks), [c for c in checks if not c.passed]


def test_plate_sides_take_their_own_kernel_and_wall_temperature(plate):
    """Per-side arrays: front diffuse at 300 K, back specular, at S = 3 and 35 deg (flow on both sides)."""
    front = plate.side_sign > 0
    u = flow(35.0)
    walls = WallInteraction(
        diffuse_fraction=np.where(front, 1.0, 0.0), wall_temperature_K=np.where(front, 300.0, 5000.0)
    )
    result = trace_molecules(
        plate,
        u,
        SpeciesStream(3.0 * C_M, **GAS),
        walls,
        Sampling(PLATE_MOLECULES),
        reference_point_m=REFERENCE,
    )
    force, torque = plate_loads(u, 3.0, True, False)
    assert_close(result, force, torque, float(np.linalg.norm(force)), 1.0, PLATE_TOL)


@pytest.mark.slow
def test_sphere_matches_the_closed_form():
    """Unit sphere (41 716 facets, projected area 1.5e-4 short), flow off every axis, diffuse and
    specular at S = 2 and 8; 1 % at 1e6 molecules."""
    checks = list(tpmc_sphere_checks(SPHERE_MOLECULES))
    assert len(checks) == 4 and all(c.passed for c in checks), [c for c in checks if not c.passed]


# ------------------------------------------------------------------------------------ CLL kernel
@pytest.mark.parametrize(
    ("alpha_n", "sigma_t", "diffuse"), [(1.0, 1.0, True), (0.0, 0.0, False)], ids=["diffuse", "specular"]
)
def test_cll_limits_are_diffuse_and_specular(plate, alpha_n, sigma_t, diffuse):
    """CLL with full accommodation is diffuse at T_w, with none specular: plate at S = 2, 35 deg."""
    u = flow(35.0)
    walls = WallInteraction(
        kernel="cll",
        diffuse_fraction=None,
        normal_accommodation=alpha_n,
        tangential_accommodation=sigma_t,
        wall_temperature_K=T_WALL,
    )
    result = trace_molecules(
        plate,
        u,
        SpeciesStream(2.0 * C_M, **GAS),
        walls,
        Sampling(PLATE_MOLECULES),
        reference_point_m=REFERENCE,
    )
    force, torque = plate_loads(u, 2.0, diffuse, diffuse)
    assert_close(result, force, torque, float(np.linalg.norm(force)), 1.0, PLATE_TOL)


def test_cll_shear_is_sigma_t_of_the_incident_shear(plate):
    """CLL keeps ``1 - sigma_t`` of each molecule's tangential momentum: shear = sigma_t x incident."""
    u, sigma_t = flow(35.0), 0.4
    walls = WallInteraction(
        kernel="cll",
        diffuse_fraction=None,
        normal_accommodation=0.6,
        tangential_accommodation=sigma_t,
        wall_temperature_K=T_WALL,
    )
    result = trace_molecules(plate, u, SpeciesStream(2.0 * C_M, **GAS), walls, Sampling(PLATE_MOLECULES))
    shear = sigma_t * (incident_shear((0, 0, 1), u, 2.0, 2.0) + incident_shear((0, 0, -1), u, 2.0, 2.0))
    gap = np.linalg.norm(result.force_N[:2] - shear[:2])
    assert gap <= Z * np.linalg.norm(result.force_se_N[:2]) and gap <= PLATE_TOL * np.linalg.norm(shear)


# ------------------------------------------------------------------------------------ concave, balance
@pytest.mark.parametrize(
    "kernel",
    [
        {"diffuse_fraction": 1.0, "wall_temperature_K": T_INF},
        {"diffuse_fraction": 0.0, "wall_temperature_K": 300.0},
        {"diffuse_fraction": "ramp", "wall_temperature_K": T_INF},
        {
            "kernel": "cll",
            "diffuse_fraction": None,
            "normal_accommodation": 0.3,
            "tangential_accommodation": 0.7,
            "wall_temperature_K": T_INF,
        },
    ],
    ids=["diffuse", "specular", "mixed-per-side", "cll"],
)
def test_concave_body_in_gas_at_rest_feels_nothing(open_box, kernel):
    """Detailed balance: V = 0 and walls at T (any kernel; specular at any T_w) give F = 0, M = 0.

    Checks the momentum bookkeeping through many bounces (a molecule meets the open box ~1.7 times):
    within Z standard errors and 1 % of ``n k T`` times the box's 5 m^2 (one side).
    """
    if isinstance(kernel.get("diffuse_fraction"), str):
        kernel = {**kernel, "diffuse_fraction": np.linspace(0.0, 1.0, open_box.n_sides)}
    result = trace_molecules(
        open_box,
        (0.2, 0.1, 1.0),
        SpeciesStream(0.0, **GAS),
        WallInteraction(**kernel),
        Sampling(PLATE_MOLECULES, max_bounces=1000),
    )
    scale = DENSITY * BOLTZMANN_J_K * T_INF * 5.0
    assert_close(result, np.zeros(3), np.zeros(3), scale, 0.5, PLATE_TOL)
    assert result.hits > 1.5 * result.struck


def test_concave_molecules_bounce_and_the_bounce_limit_counts(open_box):
    """Flow into the open box at S = 4: molecules meet it several times; a limit of 2 drops some."""
    stream = SpeciesStream(4.0 * C_M, **GAS)
    walls = WallInteraction(diffuse_fraction=1.0, wall_temperature_K=T_WALL)
    full = trace_molecules(open_box, (0.2, 0.1, 1.0), stream, walls, Sampling(100_000))
    assert full.dropped == 0 and full.absorbed == 0
    assert full.hits > 2 * full.struck and full.bounces[3:].sum() > 0.2 * full.struck
    assert full.bounces.sum() == full.molecules
    assert full.hits == int((np.arange(len(full.bounces)) * full.bounces).sum())
    cut = trace_molecules(open_box, (0.2, 0.1, 1.0), stream, walls, Sampling(100_000, max_bounces=2))
    assert cut.struck == full.struck  # same seed: same first strikes
    assert 0 < cut.dropped <= cut.bounces[2]
    assert cut.hits == cut.bounces[1] + 2 * cut.bounces[2]


def test_closed_body_interior_is_never_struck_and_default_reference():
    """A closed box: no molecule reaches its inside; the torque is about its volume centroid."""
    craft = build_spacecraft(
        transform(primitives.box((1.0, 2.0, 0.5)), translation=(1.0, 0.0, 0.0)), uniform=NEUTRAL
    )
    result = trace_molecules(
        craft,
        (1.0, 0.3, -0.2),
        SpeciesStream(2.0 * C_M, **GAS),
        WallInteraction(diffuse_fraction=0.5, wall_temperature_K=T_WALL),
        Sampling(40_000),
    )
    assert result.absorbed == 0 and result.dropped == 0
    np.testing.assert_allclose(result.reference_point_m, [1.0, 0.0, 0.0], atol=1e-12)


def test_same_seed_same_bits_and_bad_input(plate):
    stream = SpeciesStream(2.0 * C_M, **GAS)
    walls = {"diffuse_fraction": 0.7, "wall_temperature_K": T_WALL}
    sampling = {"particles": 20_000, "batches": 4}
    a = trace_molecules(plate, flow(30.0), stream, WallInteraction(**walls), Sampling(**sampling, seed=5))
    b = trace_molecules(plate, flow(30.0), stream, WallInteraction(**walls), Sampling(**sampling, seed=5))
    c = trace_molecules(plate, flow(30.0), stream, WallInteraction(**walls), Sampling(**sampling, seed=6))
    np.testing.assert_array_equal(a.force_N, b.force_N)
    np.testing.assert_array_equal(a.torque_se_Nm, b.torque_se_Nm)
    assert a.hits == b.hits and not np.array_equal(a.force_N, c.force_N)
    assert a.molecules == 20_000 and a.batches == 4
    with pytest.raises(ValueError, match="one value per side"):
        walls_3 = WallInteraction(**{**walls, "diffuse_fraction": np.ones(3)})
        trace_molecules(plate, flow(30.0), stream, walls_3, Sampling(**sampling))
    with pytest.raises(ValueError, match="CLL"):
        cll = WallInteraction(**walls, kernel="cll", normal_accommodation=1.0, tangential_accommodation=1.0)
        trace_molecules(plate, flow(30.0), stream, cll, Sampling(**sampling))
    with pytest.raises(ValueError, match="batches"):
        trace_molecules(
            plate, flow(30.0), stream, WallInteraction(**walls), Sampling(**{**sampling, "batches": 1})
        )
