"""The incident stream integrated over each side's open sky, and the molecular chains, against
independent answers: closed forms, quadrature, the hyperthermal shadow, the mirror V-groove and a gas
at rest."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sunwind.forces.drag import drag
from sunwind.forces.gas.angular import cll_direction_kernel, cll_normal_table, direction_flux, mu_grid
from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.forces.gas.core_cone import NORMAL, TANGENTIAL, core_cone
from sunwind.forces.gas.incident import cll_reflected_normal, incident
from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces, panel_coefficients
from sunwind.forces.gas.panel import species_laws
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.views.sky import compute_open_sky
from sunwind.geometry.views.view_factors import compute_view_factors
from sunwind.meshes import primitives
from sunwind.validation.analytic_v_groove import v_groove_srp
from sunwind.validation.concave_meshes import l_mesh, open_box_mesh, v_groove_mesh

SPEED_OF_LIGHT = 299_792_458.0


def oxygen(temperature_K: float = 1000.0, density_m3: float = 1e15) -> Atmosphere:
    return Atmosphere({"O": density_m3}, temperature_K, "test: atomic oxygen")


def speed_for(ratio: float, temperature_K: float = 1000.0) -> float:
    """Speed [m/s] at which atomic oxygen at ``temperature_K`` has speed ratio ``ratio``."""
    return ratio * math.sqrt(2 * BOLTZMANN * temperature_K / SPECIES_MASS_KG["O"])


def sheets(mesh, surface: GasSurface):
    return build_spacecraft(mesh, uniform=Material("wall", 0.0, 0.0, gas=surface), two_sided=["*"])


def hemisphere(gamma: float, nodes: int = 160):
    """Directions ``w`` over the hemisphere about ``n = +z``, their ``mu`` and quadrature weights (Gauss-
    Legendre in ``mu``, split at ``mu = 0.9`` where a fast stream's peak sits, and evenly in azimuth), and
    the flow ``u`` at ``n . u = gamma`` in the xz-plane."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    pieces = [(0.0, 0.9), (0.9, 1.0)]
    mu = np.concatenate([0.5 * (b - a) * x + 0.5 * (a + b) for a, b in pieces])
    weight_mu = np.concatenate([0.5 * (b - a) * w for a, b in pieces])
    phi = (np.arange(4 * nodes) + 0.5) * (2 * math.pi / (4 * nodes))
    m, p = np.meshgrid(mu, phi, indexing="ij")
    s = np.sqrt(1 - m * m)
    directions = np.stack([s * np.cos(p), s * np.sin(p), m], axis=-1).reshape(-1, 3)
    weights = (weight_mu[:, None] * np.full(len(phi), 2 * math.pi / len(phi))).ravel()
    u = np.array([math.sqrt(1 - gamma * gamma), 0.0, gamma])
    return directions, directions[:, 2], weights, u


@pytest.mark.parametrize("ratio", [0.5, 1.5, 3.0, 8.0])
@pytest.mark.parametrize("gamma", [-0.6, 0.0, 0.4, 1.0])
def test_the_stream_per_direction_integrates_to_the_closed_forms(ratio, gamma):
    """Number, normal and tangential momentum over an open hemisphere: the incident closed forms."""
    w, mu, weights, u = hemisphere(gamma)
    number, momentum = direction_flux(w @ u, ratio)
    c_n, c_t, flux = incident(np.array([gamma]), ratio)
    momentum_vector = -(weights * mu * momentum) @ w  # molecules move along -w
    assert (weights * mu * number).sum() == pytest.approx(flux[0], rel=1e-9, abs=1e-14)
    assert -momentum_vector[2] == pytest.approx(c_n[0], rel=1e-9, abs=1e-14)
    assert -momentum_vector[0] == pytest.approx(c_t[0], rel=1e-9, abs=1e-14)  # t_hat = -x here
    assert abs(momentum_vector[1]) < 1e-12


@pytest.mark.slow
@pytest.mark.parametrize(("alpha_n", "ratio"), [(0.2, 1.5), (0.8, 1.5), (0.2, 8.0), (1.0, 3.0)])
def test_cll_normal_momentum_per_direction_integrates_to_the_exact_cll_normal(alpha_n, ratio):
    table = cll_normal_table(alpha_n, 0.3, ratio + 1.0)
    for gamma in (0.0, 0.5, 1.0):
        w, mu, weights, u = hemisphere(gamma, 80)
        kernel = cll_direction_kernel(w @ u, ratio, table)
        per_mu = np.array([np.interp(m, mu_grid(), row) for m, row in zip(mu, kernel, strict=True)])
        got = (weights * mu * per_mu).sum()
        exact = cll_reflected_normal(np.array([gamma]), np.array([alpha_n]), np.array([0.3]), ratio, "full")
        assert got == pytest.approx(exact[0], rel=2e-3)


LAWS = (
    GasSurface("sentman", 0.9),
    GasSurface("schaaf-chambre", normal_accommodation=0.6, tangential_accommodation=0.8),
    GasSurface("cll", normal_accommodation=0.3, tangential_accommodation=0.5),
    GasSurface("specular"),
)


def surfaces() -> GasSurfaces:
    return GasSurfaces.of(
        {
            "code": [MODEL_CODES[g.model] for g in LAWS],
            "energy_accommodation": [g.energy_accommodation for g in LAWS],
            "normal_accommodation": [g.normal_accommodation for g in LAWS],
            "tangential_accommodation": [g.tangential_accommodation for g in LAWS],
            "wall_temperature_K": [g.wall_temperature_K for g in LAWS],
        }
    )


def closed_force(law: GasSurfaces, gamma: np.ndarray, atmosphere: Atmosphere, speed: float) -> tuple:
    """Normal and tangential force per unit area [Pa] of ``law`` on an unobstructed side at ``gamma``."""
    normal, tangential = np.zeros(len(gamma)), np.zeros(len(gamma))
    for species, density in atmosphere.number_density_m3.items():
        mass = SPECIES_MASS_KG[species]
        ratio = speed / math.sqrt(2 * BOLTZMANN * atmosphere.temperature_K / mass)
        c_n, c_t = panel_coefficients(law, gamma, ratio, atmosphere.temperature_K)
        q = 0.5 * density * mass * speed**2
        normal, tangential = normal - q * c_n, tangential + q * c_t
    return normal, tangential


@pytest.mark.parametrize(("ratio", "half_angle"), [(0.7, math.pi), (1.5, math.pi), (20.0, None)])
def test_a_core_cone_over_the_whole_sphere_is_the_closed_form_of_every_law(ratio, half_angle):
    """The core's table (ring closed forms, radial Gauss-Legendre) with the cone opened to pi; and the
    default cone of a fast stream (3 / S wide) holding all of it but ~exp(-9)."""
    from sunwind.forces.gas.visible import cll_tables

    air = Atmosphere({"O": 1e15, "He": 3e14}, 900.0, "test")
    speed = speed_for(ratio, 900.0)
    laws = species_laws(surfaces(), air, speed)
    craft = sheets(primitives.plate(1.0, 1.0, 1), LAWS[0])
    cone = core_cone(laws, cll_tables(craft, laws), half_angle=half_angle)
    gamma = np.linspace(-1.0, 1.0, cone.gamma_table.shape[2])
    for k in range(len(LAWS)):
        normal, tangential = closed_force(surfaces().take(np.full(len(gamma), k)), gamma, air, speed)
        scale = np.abs(normal).max()
        # The default cone leaves out exp(-9) of He's stream at S = 10 (7 % of the dynamic pressure);
        # CLL's (psi, mu) table is interpolated.
        tolerance = 2e-3 if LAWS[k].model == "cll" else 3e-5
        assert np.abs(cone.gamma_table[k, NORMAL] - normal).max() < tolerance * scale
        assert np.abs(cone.gamma_table[k, TANGENTIAL] - tangential).max() < tolerance * scale


def test_hull_sides_keep_no_sky_rays_and_an_l_sees_its_view_factor():
    """A convex body casts nothing; the sky's blocked share of the L's sides is the share of their
    emission the view factors (sampled independently) find meeting the model."""
    box = build_spacecraft(primitives.box((1.0, 2.0, 0.5), divisions=2), uniform=Material("m", 0.0, 0.0))
    sky = compute_open_sky(box)
    assert len(sky.direction) == 0 and not np.any(sky.blocked_fraction)
    craft = sheets(l_mesh(), GasSurface("sentman"))
    sky = compute_open_sky(craft, 1024)
    view = compute_view_factors(craft, 1024)
    areas = craft.side_areas
    sky_share = areas @ sky.blocked_fraction / areas.sum()
    view_share = areas @ (1 - view.escape_fraction) / areas.sum()
    assert sky_share == pytest.approx(view_share, abs=2e-3)
    kept = np.diff(sky.start)
    assert np.all(kept <= sky.rays_per_side // 2)
    assert np.allclose(np.linalg.norm(sky.direction, axis=1), 1.0, atol=1e-6)


def test_the_hyperthermal_limit_is_the_shadow_pass():
    """At S = 10^4 the incident stream is the hyperthermal beam: each side takes its closed-form law on its
    lit share along the flow, acting at its lit centroid, shadow edges located exactly."""
    craft = sheets(open_box_mesh(1.0, 4), GasSurface("sentman", wall_temperature_K=300.0))
    air, speed = oxygen(1.0), speed_for(1e4, 1.0)
    u = np.array([0.3, 0.2, 0.9]) / math.sqrt(0.94)
    result = drag(craft, speed * u, air, reflections="none", reference_point_m=np.zeros(3))
    flow = side_sampler(craft).illuminate(u)
    gamma = craft.side_normals @ u
    normal, tangential = closed_force(GasSurfaces.of(craft.side_gas), gamma, air, speed)
    along = u - gamma[:, None] * craft.side_normals
    t_hat = -along / np.maximum(np.linalg.norm(along, axis=1), 1e-300)[:, None]
    per_area = normal[:, None] * craft.side_normals + tangential[:, None] * t_hat
    force = (craft.side_areas * flow.lit_fraction)[:, None] * per_area
    torque = np.cross(flow.lit_centroid, force).sum(axis=0)
    scale = np.linalg.norm(force.sum(axis=0))
    assert np.linalg.norm(result.force_N - force.sum(axis=0)) < 2e-4 * scale
    assert np.linalg.norm(result.torque_Nm - torque) < 2e-4 * scale * 1.0


@pytest.mark.parametrize("angle_deg", [0.0, 20.0, -35.0])
def test_a_mirror_v_groove_in_a_hyperthermal_stream_is_the_mirror_law(angle_deg):
    """Specular walls at S = 10^4: molecules bounce once or twice as light does in a mirror groove
    (the closed form of :mod:`sunwind.validation.analytic_v_groove` with P = rho V^2)."""
    craft = sheets(v_groove_mesh(1.0, 3.0, (4, 8)), GasSurface("specular"))
    air, speed = oxygen(1.0), speed_for(1e4, 1.0)
    psi = math.radians(angle_deg)
    u = np.array([math.sin(psi), 0.0, math.cos(psi)])
    result = drag(craft, speed * u, air, reflections="full", reference_point_m=np.zeros(3))
    momentum_flux = air.density_kg_m3 * speed**2
    exact = v_groove_srp(1.0, 3.0, angle_deg, 1.0, flux_W_m2=momentum_flux * SPEED_OF_LIGHT)
    scale = np.linalg.norm(exact.force_N)
    assert np.linalg.norm(result.force_N - exact.force_N) < 2e-3 * scale
    assert np.linalg.norm(result.torque_Nm - exact.torque_Nm) < 2e-3 * scale * 1.0
    assert result.reflected.chains.truncated < 1e-6


@pytest.mark.filterwarnings("ignore:velocity_m_s gives a speed of:sunwind.geometry.errors.UnitWarning")
def test_a_cavity_in_gas_at_rest_feels_nothing():
    """Diffuse walls at the gas's temperature: at small S the force is linear in S (the box's drag), and
    extrapolated to a gas at rest it vanishes (detailed balance) to the sampling of its sky, against the
    pressure on one wall; it does so only with the exchange of re-emitted molecules."""
    craft = sheets(open_box_mesh(1.0, 4), GasSurface("sentman", wall_temperature_K=1000.0))
    air, u = oxygen(1000.0), np.array([0.3, 0.2, 0.9]) / math.sqrt(0.94)
    pressure = air.number_density_m3["O"] * BOLTZMANN * air.temperature_K

    def force(ratio: float, reflections: str = "full") -> np.ndarray:
        return drag(craft, speed_for(ratio) * u, air, reflections=reflections).force_N / pressure

    at_rest = 2 * force(0.005) - force(0.01)  # Richardson: linear in S
    assert np.linalg.norm(at_rest) < 3e-3 < 0.1 * np.linalg.norm(force(0.01))
    assert np.linalg.norm(2 * force(0.005, "none") - force(0.01, "none")) > 0.1


def test_a_convex_mirror_sends_every_molecule_away():
    craft = build_spacecraft(
        primitives.sphere(1.0, subdivisions=8), uniform=Material("m", 0.0, 0.0, gas=GasSurface("specular"))
    )
    result = drag(craft, speed_for(3.0) * np.array([1.0, 0.0, 0.0]), oxygen(), reflections="full")
    assert np.array_equal(result.reflected_force_N, np.zeros(3))
    assert result.reflected.chains.packets == 0


def test_gas_sampling_is_checked():
    with pytest.raises(InputError, match="sky_rays 0 must be a whole number"):
        GasSampling(sky_rays=0)
    with pytest.raises(InputError, match="chain_molecules"):
        GasSampling(chain_molecules=2.5)


def test_core_rays_are_sized_before_they_are_drawn(monkeypatch):
    craft = sheets(open_box_mesh(1.0, 8), GasSurface("sentman"))
    v = speed_for(3.0) * np.array([0.3, 0.4, -0.8]) / math.sqrt(0.89)
    drag(craft, v, oxygen(), reflections="none")  # the sky, sampled before the limit is set
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "2M")
    with pytest.raises(
        InputError, match=r"core rays; limit 2 MiB \(SUNWIND_MAX_MEMORY=2M\); lower core_rays"
    ):
        drag(craft, v, oxygen(), reflections="none", gas_sampling=GasSampling(core_rays=2**26))


def test_chain_molecules_are_sized_before_they_are_drawn(monkeypatch):
    """Refused against the memory limit before they are drawn; at the same limit the default runs."""
    half = GasSurface("schaaf-chambre", normal_accommodation=0.5, tangential_accommodation=0.5)
    craft = sheets(open_box_mesh(1.0, 12), half)
    v = speed_for(3.0) * np.array([0.3, 0.4, -0.8]) / math.sqrt(0.89)
    full = ReflectionSettings("full", rays_per_side=64, cache_dir=False)
    drag(craft, v, oxygen(), reflections=full)  # the sky and view factors, made before the limit is set
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "100M")
    with pytest.raises(InputError, match="chain molecules; limit 100 MiB"):
        drag(craft, v, oxygen(), reflections=full, gas_sampling=GasSampling(chain_molecules=2**26))
    assert drag(craft, v, oxygen(), reflections=full).reflected.chains.packets > 0
