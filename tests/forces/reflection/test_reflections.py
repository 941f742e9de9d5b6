"""Inter-reflection: specular chains, the diffuse balance, their bookkeeping and their limits."""

import numpy as np
import pytest
import tomllib

from helpers import MIXED, quad_sheet
from helpers.shapes import MIRROR, SHEER, WHITE, P, groove, open_box
from sunwind.forces.radiation.law import SPEED_OF_LIGHT
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.reflection.diffuse import diffuse_exchange
from sunwind.forces.srp import srp
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives


def full(mode: str = "full", **options) -> ReflectionSettings:
    return ReflectionSettings(mode, **options)


@pytest.mark.slow
@pytest.mark.parametrize(
    "mesh", [primitives.sphere(1.0, 3), primitives.box((1.0, 2.0, 0.5), 3), primitives.cylinder(0.5, 2.0)]
)
@pytest.mark.parametrize("mode", ["specular", "full"])
def test_reflections_change_nothing_on_convex_bodies(mesh, mode):
    craft = build_spacecraft(mesh, uniform=MIXED)
    for sun in ([0.3, -0.5, 0.8], [1.0, 0.0, 0.0]):
        direct = srp(craft, sun, reflections="none")
        result = srp(craft, sun, reflections=full(mode))
        scale = np.linalg.norm(direct.force_N)
        assert np.abs(result.reflected_force_N).max() <= 1e-12 * scale
        assert np.abs(result.reflected_torque_Nm).max() <= 1e-12 * scale
        assert abs(result.power.imbalance) < 1e-12
    assert srp(craft, [1.0, 0.0, 0.0], reflections="full").k_is == 0.0
    assert srp(craft, [0, 0, 1]).reflections == "none"  # auto


def test_mirror_groove_lit_along_its_bisector_retro_reflects_everything():
    """Every photon meets both mirrors and goes back: F = -2 P (aperture) u_sun, to round-off."""
    craft = groove(MIRROR)
    result = srp(craft, [0.0, 0.0, 1.0], reflections=full())
    aperture = 2.0 * 4.0
    np.testing.assert_allclose(result.force_N, [0, 0, -2 * P * aperture], rtol=1e-9, atol=1e-9 * P)
    assert result.power.absorbed_W == pytest.approx(0.0, abs=1e-9 * result.power.incident_W)
    assert result.power.escaped_W == pytest.approx(result.power.incident_W, rel=1e-12)


def test_the_chain_depth_and_cutoff_drop_power_and_say_so():
    craft = groove(MIRROR)
    result = srp(craft, [0.0, 0.0, 1.0], reflections=full("specular", depth=1))
    # the first beams land on the other mirror; what they would reflect again is dropped
    assert result.power.truncated_W == pytest.approx(result.power.incident_W, rel=1e-12)
    assert abs(result.power.imbalance) < 1e-12
    with pytest.raises(InputError, match="cutoff"):
        ReflectionSettings("full", cutoff=1.5)
    with pytest.raises(InputError, match="mode"):
        ReflectionSettings("most")


@pytest.mark.parametrize("material", [MIXED, SHEER, WHITE, MIRROR], ids=lambda m: m.name)
@pytest.mark.parametrize("sun", [[0.2, 0.1, 1.0], [0.9, -0.4, 0.5]])
def test_power_balances_to_round_off_in_a_cavity(material, sun):
    result = srp(open_box(material), sun, reflections=full())
    assert result.reflections == "full"
    assert abs(result.power.imbalance) < 1e-9
    assert result.power.incident_W > 0


def test_a_white_cavity_absorbs_nothing_and_returns_all_light():
    result = srp(open_box(WHITE), [0.1, 0.2, 1.0], reflections=full())
    power = result.power
    assert power.absorbed_W == pytest.approx(0.0, abs=1e-9 * power.incident_W)
    assert power.escaped_W == pytest.approx(power.incident_W, rel=1e-9)


def test_light_a_sheet_transmits_lands_on_what_is_behind_it():
    """A clear sheet (sigma = 1) over a black plate: the plate absorbs the beam, F = -P A u_sun."""
    sheet = quad_sheet(np.array([[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1.0]]), "cover", 4)
    plate = quad_sheet(np.array([[-1, -1, 0], [2, -1, 0], [2, 2, 0], [-1, 2, 0.0]]), "plate", 3)
    spec = parse_materials(
        tomllib.loads(
            """
        [materials.clear]
        reflectivity = 0.0
        specular_fraction = 0.0
        transmissivity = 1.0
        [materials.black]
        reflectivity = 0.0
        specular_fraction = 0.0
        [parts]
        cover = { front = "clear", back = "clear" }
        plate = { front = "black" }
        """
        )
    )
    craft = build_spacecraft(MeshData.concatenate([sheet, plate]), materials=spec)
    direct = srp(craft, [0, 0, 1], reflections="none")
    result = srp(craft, [0, 0, 1], reflections=full("specular"))
    assert direct.force_N[2] == pytest.approx(-P * (9.0 - 1.0), rel=1e-12)  # the sheet's full shadow
    assert result.force_N[2] == pytest.approx(-P * 9.0, rel=1e-12)


def test_the_adjoint_totals_equal_a_full_solve():
    craft = open_box(MIXED)
    exchange = diffuse_exchange(craft, full())
    source = np.random.default_rng(1).random(craft.n_sides)
    ref = np.array([0.3, 0.2, 0.1])
    by_adjoint = exchange.totals(source, ref)
    by_solve = exchange.totals_of(exchange.solve(source), ref)
    np.testing.assert_allclose(by_adjoint.force_N, by_solve.force_N, rtol=1e-10)
    np.testing.assert_allclose(by_adjoint.torque_Nm, by_solve.torque_Nm, rtol=1e-10, atol=1e-22)
    assert by_adjoint.escaped_W + by_adjoint.absorbed_W == pytest.approx(source.sum(), rel=1e-10)


def test_k_is_of_an_l_of_one_sided_squares_is_the_hottel_view_factor_ratio():
    """Each square sends F = 0.20004 of its diffuse light to the other: K_IS = F / (1 - F)."""
    a = quad_sheet(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]), "floor", 4)
    b = quad_sheet(np.array([[0, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1.0]]), "wall", 4)
    document = '[materials.m]\nreflectivity = 0.6\nspecular_fraction = 0.3\n[parts]\n"*" = { front = "m" }'
    spec = parse_materials(tomllib.loads(document))
    craft = build_spacecraft(MeshData.concatenate([a, b]), materials=spec)
    hottel = 0.200044
    assert srp(craft, [1, 1, 1], reflections="full").k_is == pytest.approx(hottel / (1 - hottel), rel=0.02)
    assert srp(craft, [1, 1, 1], reflections="none").k_is is None  # not computed unless asked


def test_results_with_reflections_are_the_same_bits_whatever_the_threads(monkeypatch, limit_threads):
    craft = open_box(MIXED)
    runs = []
    for threads in ("1", "2"):
        limit_threads(int(threads))
        result = srp(craft, [0.3, 0.2, 1.0], reflections=full())
        runs.append(np.r_[result.force_N, result.torque_Nm])
    assert np.array_equal(runs[0], runs[1])


@pytest.mark.slow
@pytest.mark.parametrize("samples", [1, None], ids=["one-point", "default"])
def test_the_diffuse_light_the_direct_pass_hands_on_equals_the_side_by_side_sums(samples):
    """The direct pass sums what each lit side hands the diffuse balance from block moments
    (:func:`sunwind.forces.radiation.direct.weight_moments`); side by side, from each side's first diffuse
    reflection through the adjoint totals, the result is the same to 1e-10."""
    craft = open_box(MIXED, 24)
    u = np.array([0.3, 0.2, 1.0]) / np.linalg.norm([0.3, 0.2, 1.0])
    low, high = side_sampler(craft).block_normal_bounds
    assert (np.minimum(low * u, high * u).sum(axis=1) > 0).any()  # blocks summed from their moments
    ref = np.array([0.2, 0.7, 0.4])
    result = srp(
        craft, u, reflections=full(), sampling=ShadowSampling(samples=samples), reference_point_m=ref
    )
    light, chains = result.illumination, result.reflected.chains
    rho, beta, _ = craft.side_optics.T
    power = np.zeros(craft.n_sides)
    facing = light.facing
    power[facing] = result.flux_W_m2 * craft.side_areas[facing] * light.lit_fraction[facing]
    power[facing] *= craft.side_normals[facing] @ u
    first = rho * (1 - beta) * power
    balance = diffuse_exchange(craft, full()).totals(first + chains.diffuse_source_W, ref)
    open_plate = -(2 / 3) * first[:, None] * craft.side_normals / SPEED_OF_LIGHT  # what eq. (4) took
    force = result.direct_force_N + chains.force_N + balance.force_N - open_plate.sum(axis=0)
    torque = result.direct_torque_Nm + chains.torque_Nm + balance.torque_Nm
    torque -= np.cross(craft.side_centroids - ref, open_plate).sum(axis=0)
    np.testing.assert_allclose(result.force_N, force, rtol=1e-10, atol=1e-10 * np.abs(force).max())
    np.testing.assert_allclose(result.torque_Nm, torque, rtol=1e-10, atol=1e-10 * np.abs(torque).max())
    assert result.power.escaped_W == pytest.approx(chains.escaped_W + balance.escaped_W, rel=1e-10)
