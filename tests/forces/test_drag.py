"""The free-molecular solver: per-side law on convex bodies, shadowing, re-emission, coefficients."""

import math
import warnings

import numpy as np
import pytest

from sunwind import meshes
from sunwind.forces.drag import drag
from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.forces.gas.laws import GasSurfaces, panel_coefficients
from sunwind.forces.model import Model
from sunwind.forces.results import aerodynamic_axes
from sunwind.forces.srp import srp
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

TEMPERATURE_K = 1000.0
AIR = Atmosphere({"O": 4e14, "N2": 1e14}, TEMPERATURE_K, "test")


def speed_for(ratio: float, species: str = "O") -> float:
    """Speed [m/s] at which ``species`` has speed ratio ``ratio`` at :data:`TEMPERATURE_K`."""
    return ratio * math.sqrt(2 * BOLTZMANN * TEMPERATURE_K / SPECIES_MASS_KG[species])


def craft_of(mesh, model="sentman", two_sided=(), **gas):
    surface = GasSurface(model=model, **gas)
    return build_spacecraft(mesh, uniform=Material("m", 0.3, 0.5, gas=surface), two_sided=two_sided)


def per_side_law(craft, velocity, air, reference):
    """Force and torque summed side by side from sunwind.forces.gas.laws: every side sees the free stream."""
    speed = np.linalg.norm(velocity)
    u = velocity / speed
    n = craft.side_normals
    gamma = n @ u
    along = u - gamma[:, None] * n
    length = np.linalg.norm(along, axis=1)
    tangent = np.where(length[:, None] > 1e-12, -along / np.maximum(length, 1e-300)[:, None], 0.0)
    law = GasSurfaces.of(craft.side_gas)
    force = np.zeros((craft.n_sides, 3))
    for species, density in air.number_density_m3.items():
        mass = SPECIES_MASS_KG[species]
        ratio = speed / math.sqrt(2 * BOLTZMANN * air.temperature_K / mass)
        c_n, c_t = panel_coefficients(law, gamma, ratio, air.temperature_K, "full")
        q = 0.5 * density * mass * speed**2
        force += (q * craft.side_areas)[:, None] * (-c_n[:, None] * n + c_t[:, None] * tangent)
    torque = np.cross(craft.side_centroids - reference, force)
    return force.sum(axis=0), torque.sum(axis=0)


CONVEX = {
    "sphere": lambda: primitives.sphere(1.0, subdivisions=16),
    "box": lambda: primitives.box((1.0, 2.0, 0.5), divisions=2),
    "capped cylinder": lambda: primitives.cylinder(0.5, 1.5, segments=48),
}


@pytest.mark.parametrize("ratio", [2.0, 5.0, 8.0, 15.0])
@pytest.mark.parametrize("body", list(CONVEX))
@pytest.mark.parametrize("reflections", ["none", "full"])
def test_convex_body_is_the_per_side_law_at_every_speed_ratio(body, ratio, reflections):
    """No shadowing artefact: lee faces keep their thermal flux, windward faces are all lit, and
    re-emitted molecules all escape, so the solver is the per-side sum of the law (to round-off)."""
    craft = craft_of(CONVEX[body](), "schaaf-chambre", normal_accommodation=0.8, tangential_accommodation=0.9)
    velocity = speed_for(ratio) * np.array([0.6, -0.48, 0.64])
    ref = np.array([0.1, 0.2, -0.1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # exact at every speed ratio: nothing to warn of
        result = drag(
            craft,
            velocity,
            AIR,
            reference_point_m=ref,
            reflections=reflections,
            sampling=ShadowSampling(samples=4),
        )
    force, torque = per_side_law(craft, velocity, AIR, ref)
    scale = np.linalg.norm(force)
    assert np.linalg.norm(result.force_N - force) <= 1e-12 * scale
    assert np.linalg.norm(result.torque_Nm - torque) <= 1e-9 * scale
    assert np.linalg.norm(result.reflected_force_N) <= 1e-12 * scale
    assert result.reflections == reflections


def test_lee_faces_carry_force_at_finite_speed_ratio():
    """A sphere's rear hemisphere is struck too: culling it would change the drag."""
    craft = craft_of(primitives.sphere(1.0, subdivisions=16))
    velocity = speed_for(2.0) * np.array([1.0, 0.0, 0.0])
    result = drag(craft, velocity, AIR, reflections="none")
    lee = craft.side_normals @ np.array([1.0, 0.0, 0.0]) < 0
    lee_force = result.side_force_N[lee].sum(axis=0)
    assert np.linalg.norm(lee_force) > 0.01 * np.linalg.norm(result.force_N)


def test_sphere_drag_does_not_depend_on_flow_direction_and_has_no_torque_about_its_centre():
    """Directions around the axis of the latitude-longitude mesh, where its faceting is the same."""
    craft = craft_of(primitives.sphere(1.0, subdivisions=40))
    results = [
        drag(craft, speed_for(6.0) * np.asarray(d) / np.linalg.norm(d), AIR, reflections="none")
        for d in ([1, 0, 0], [0, -1, 0], [1, 1, 0.2])
    ]
    cd = [r.force_coefficients[0] for r in results]
    assert max(cd) - min(cd) < 5e-3 * cd[0]  # facet orientation only
    for r in results:
        assert np.linalg.norm(r.torque_Nm) < 1e-3 * np.linalg.norm(r.force_N) * 1.0
        assert abs(r.force_coefficients[1]) < 2e-3 and abs(r.force_coefficients[2]) < 2e-3


def test_shadowed_plate_keeps_only_its_thermal_flux():
    """A plate hidden behind a larger one in a hyperthermal beam gets only the thermal part."""
    front = meshes.transform(primitives.plate(2.0, 2.0, 8), translation=(0.0, 0.0, 1.0))
    back = meshes.label(primitives.plate(1.0, 1.0, 8), "back")
    craft = craft_of(MeshData.concatenate([meshes.label(front, "front"), back]), two_sided=["*"])
    velocity = speed_for(15.0) * np.array([0.0, 0.0, 1.0])
    shielded = drag(craft, velocity, AIR, reflections="none")
    alone = craft_of(back, two_sided=["*"])
    lone = drag(alone, velocity, AIR, reflections="none")
    back_sides = craft.facet_part[craft.side_facet] == craft.part_names.index("back")
    shielded_back = shielded.side_force_N[back_sides].sum(axis=0)
    # the hidden plate keeps a few per cent: the thermal remainder of the windward face and the lee face
    assert 0 < np.linalg.norm(shielded_back) < 0.1 * np.linalg.norm(lone.force_N)


def test_lit_area_is_the_unshadowed_windward_area_and_projects_to_the_shadow():
    """A 1 x 2 x 3 box in a flow along (1, 1, 1): the +x, +y, +z faces (6 + 3 + 2 m^2) face it and
    cast a shadow of 11 / sqrt(3) m^2; a plate behind a larger one adds nothing."""
    box = craft_of(primitives.box((1.0, 2.0, 3.0)))
    oblique = drag(box, speed_for(8.0) * np.ones(3) / math.sqrt(3.0), AIR, reflections="none")
    assert oblique.lit_area_m2 == pytest.approx(11.0, rel=1e-12)
    assert oblique.projected_area_m2 == pytest.approx(11.0 / math.sqrt(3.0), rel=1e-12)
    front = meshes.transform(primitives.plate(2.0, 2.0, 8), translation=(0.0, 0.0, 1.0))
    back = meshes.label(primitives.plate(1.0, 1.0, 8), "back")
    craft = craft_of(MeshData.concatenate([meshes.label(front, "front"), back]), two_sided=["*"])
    shielded = drag(craft, speed_for(8.0) * np.array([0.0, 0.0, 1.0]), AIR, reflections="none")
    assert shielded.lit_area_m2 == pytest.approx(4.0, rel=1e-12)
    assert shielded.projected_area_m2 == pytest.approx(4.0, rel=1e-12)
    assert shielded.to_json()["lit_area_m2"] == shielded.lit_area_m2


def test_coefficients_use_the_stated_axes_and_normalisation():
    craft = craft_of(primitives.sphere(1.0, subdivisions=16))
    velocity = speed_for(8.0) * np.array([0.0, 1.0, 0.0])
    model = Model(craft, reference_area_m2=2.0, reference_length_m=3.0)
    result = drag(model, velocity, AIR, reflections="none")
    q = 0.5 * AIR.density_kg_m3 * np.linalg.norm(velocity) ** 2
    axes = aerodynamic_axes(result.flow_direction)
    assert np.allclose(axes @ axes.T, np.eye(3))
    assert np.allclose(np.cross(axes[0], axes[1]), axes[2])  # drag x side = lift
    assert result.force_coefficients[0] == pytest.approx(-result.force_N @ [0, 1, 0] / (q * 2.0), rel=1e-12)
    assert np.allclose(result.CM, result.torque_Nm / (q * 2.0 * 3.0))
    payload = result.to_json()
    for key in ("force_N", "torque_Nm", "density_kg_m3", "temperature_K", "speed_m_s", "dynamic_pressure_Pa"):
        assert key in payload
    assert payload["CD"] == pytest.approx(result.force_coefficients[0])
    assert payload["reference_area_m2"] == 2.0 and payload["reference_length_m"] == 3.0


def test_default_reference_area_is_the_mean_projected_area():
    craft = craft_of(primitives.sphere(1.0, subdivisions=40))
    result = drag(craft, speed_for(8.0) * np.array([1.0, 0, 0]), AIR, reflections="none")
    assert result.reference_area_m2 == pytest.approx(math.pi, rel=2e-3)


def test_zero_velocity_and_unknown_modes_are_refused_as_for_light():
    craft = craft_of(primitives.sphere(1.0, subdivisions=8))
    with pytest.raises(InputError, match="zero length"):
        drag(craft, [0.0, 0.0, 0.0], AIR)
    message = "reflections 'mirror' is not a mode; use one of none, specular, full, auto, plates"
    with pytest.raises(InputError, match=message):
        drag(craft, [7000.0, 0, 0], AIR, reflections="mirror")
    with pytest.raises(InputError, match=message):
        srp(craft, [1.0, 0, 0], reflections="mirror")


def test_plates_give_each_side_the_whole_stream_and_cast_no_ray():
    box = craft_of(primitives.box((1.0, 2.0, 3.0)))
    v = speed_for(6.0) * np.array([0.3, -0.5, 0.8])
    plates, exact = drag(box, v, AIR, reflections="plates"), drag(box, v, AIR, reflections="none")
    assert plates.reflections == "plates" and plates.rays == 0 and plates.error_estimate is None
    assert np.allclose(plates.force_N, exact.force_N, rtol=1e-9)  # convex: every side sees open sky
    assert np.allclose(plates.torque_Nm, exact.torque_Nm, rtol=1e-9, atol=1e-12 * np.abs(exact.force_N).max())
    assert plates.to_json()["open_sky"]["rays_per_side"] == 0


def test_specular_follows_unaccommodated_molecules_without_diffuse_exchange():
    mirroring = craft_of(primitives.box((1.0, 1.0, 1.0)), "schaaf-chambre", normal_accommodation=0.2)
    v = speed_for(6.0) * np.array([0.3, -0.5, 0.8])
    convex = drag(mirroring, v, AIR, reflections="specular")  # no side sends to another
    assert convex.reflections == "specular"
    assert np.array_equal(convex.force_N, drag(mirroring, v, AIR, reflections="none").force_N)


@pytest.mark.parametrize(
    "velocity, message",
    [
        ([1e-300, 0, 0], "speed of 1e-300 m/s, below 1 m/s: too slow to be a flow"),
        ([0.6, 0.0, 0.0], "below 1 m/s"),
        ([[7000.0, 0, 0], [0, 0.5, 0]], "speed of 0.5 m/s, below 1 m/s"),
        ([1e300, 0, 0], "above 1e\\+06 m/s"),
        ([math.nan, 0, 0], "three finite numbers"),
    ],
)
def test_speeds_that_are_no_flow_are_refused_with_the_threshold(velocity, message):
    craft = craft_of(primitives.sphere(1.0, subdivisions=4))
    with pytest.raises(InputError, match=message):
        drag(craft, velocity, AIR)


def test_a_table_setup_checks_its_speed_like_a_velocity():
    from sunwind.forces.tables import DragSetup

    with pytest.raises(InputError, match="below 1 m/s"):
        DragSetup(speed_m_s=1e-300, atmosphere=AIR)
    with pytest.raises(InputError, match="not a number"):
        DragSetup(speed_m_s="7000", atmosphere=AIR)


def test_re_emission_exchange_adds_drag_on_a_cavity_facing_the_flow():
    """Molecules the walls of an open box re-emit can leave only through its opening, upstream, so
    more of their momentum leaves against the flow than the open-plate law lets the walls send
    sideways: the exchange adds drag, and keeps the force on the axis of a symmetric box."""
    from sunwind.validation.concave_meshes import open_box_mesh

    craft = craft_of(open_box_mesh(1.0, 6), two_sided=["*"])
    velocity = speed_for(8.0) * np.array([0.0, 0.0, 1.0])
    none = drag(craft, velocity, AIR, reflections="none")
    full = drag(craft, velocity, AIR, reflections="full")
    assert full.reflected.k_is > 0.1
    assert full.force_N[2] < (1 + 0.005) * none.force_N[2] < 0
    # the sampling of the core rays and of the view factors only
    assert np.linalg.norm(full.force_N[:2]) < 5e-4 * abs(full.force_N[2])
