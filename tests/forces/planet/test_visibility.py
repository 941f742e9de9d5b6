"""The precomputed directional visibility (issue 35): the grid, the cap integral as weighted sums against
rays and against a shadow pass per cell, its error estimate, its memory bound and its disk cache."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from helpers.shapes import hinged_box_wing, plate_over_plate
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.visibility import direction_grid, level_for, visibility
from sunwind.forces.reflection import ReflectionSettings
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.views.disk_cache import CacheWarning
from sunwind.meshes import primitives
from sunwind.validation import planet_fluxes as ref

EARTH = planet("earth")
FLUX = 1361.0
LIGHT = PlanetLight.of(EARTH, FLUX)
NADIR = np.array([0.0, 0.0, -1.0])
SUN = np.array(
    [math.sin(0.7) * math.cos(0.4), math.sin(0.7) * math.sin(0.4), math.cos(0.7)]
)  # 40 deg off zenith
WHITE = Material("white", reflectivity=0.6, specular_fraction=0.5, transmissivity=0.05, emissivity=0.8)


def test_grids_nest_and_spread_values_conservatively():
    """Level k's first nodes are level k-1's; spread weights sum to the values; a value at a node stays on
    it; the sum against node values is the integral of their piecewise-linear interpolant (a linear
    function of the projected point, reproduced exactly)."""
    coarse, fine = direction_grid(2), direction_grid(3)
    assert np.array_equal(fine.nodes[: len(coarse.nodes)], coarse.nodes)
    rng = np.random.default_rng(35)
    points = rng.normal(size=(500, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    values = rng.random(500)
    weights = fine.weights(points, values)
    assert weights.sum() == pytest.approx(values.sum(), rel=1e-12)
    assert np.all(weights >= 0)
    on_node = fine.weights(fine.nodes[[7]], np.array([2.0]))
    assert on_node[7] == pytest.approx(2.0, abs=1e-12) and abs(on_node.sum() - 2.0) < 1e-12
    a, c = np.array([0.3, -0.2, 0.5]), 0.7
    face, _ = fine.locate(points)
    corners = fine.nodes[fine.faces[face]]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    projected = (
        points
        * (np.einsum("ij,ij->i", normal, corners[:, 0]) / np.einsum("ij,ij->i", normal, points))[:, None]
    )
    assert weights @ (fine.nodes @ a + c) == pytest.approx(values @ (projected @ a + c), rel=1e-12)
    assert [level_for(d) for d in (20.0, 10.0, 5.0, 2.5, 1.2)] == [2, 3, 4, 5, 6]


@pytest.mark.parametrize(
    "cell_deg, tolerance", [(10.0, 1.5e-3), pytest.param(5.0, 4e-4, marks=pytest.mark.slow)]
)
def test_shadowed_plate_converges_to_the_ray_brute_force(cell_deg, tolerance):
    """A 1 m plate facing the planet with a 0.4 m plate 0.3 m below it: the irradiance of the big plate
    from the visibility against the ray brute force (at a resolution good to 1e-4), falling with the
    grid's spacing (second order)."""
    craft, big, small = plate_over_plate()
    body = ref.SphericalPlanet(EARTH.radius_m, 500e3, FLUX, EARTH.albedo)
    sun = SUN
    part = craft.facet_part[craft.side_facet]
    facing = (part == craft.part_names.index("big")) & (craft.side_normals[:, 2] < 0)
    blockers = np.array([small[[0, 1, 2]], small[[0, 2, 3]]])
    expected = ref.shadowed_plate_irradiance(
        blockers, big, [0, 0, -1.0], NADIR, sun, body, "infrared", (64, 32)
    )
    result = planet_radiation(
        craft, Place(NADIR, 500.0, sun), LIGHT, reflections="none", cap=CapSampling(cell_deg)
    )
    got = result.infrared.incident_side_W[facing].sum()
    assert abs(got / expected.irradiance_W_m2 - 1) <= tolerance
    cells = planet_radiation(
        craft, Place(NADIR, 500.0, sun), LIGHT, reflections="none", cap=CapSampling(method="cells")
    )
    assert result.rays < cells.rays / 20  # the Sun's pass only


def _places() -> list[Place]:
    """A Sun high, one at the terminator and one just out of eclipse, 500 km up."""
    nadir = np.array([0.3, -0.4, -1.0]) / np.linalg.norm([0.3, -0.4, -1.0])
    across = np.cross(nadir, [1.0, 0.0, 0.0])
    across /= np.linalg.norm(across)
    out = []
    for angle, fraction in ((150.0, 1.0), (92.0, 1.0), (68.1, 0.6)):
        a = math.radians(angle)
        out.append(Place(nadir, 500.0, math.cos(a) * nadir + math.sin(a) * across, solar_fraction=fraction))
    return out


@pytest.mark.slow
def test_visibility_matches_a_shadow_pass_per_cell_with_reflections_and_knows_its_error():
    """A box with wings, mirrors and diffuse white, full reflections: the visibility at the default grid
    against the converged cells (a shadow pass per 2.5 deg cell): within 1e-3 of the force and 1e-2 of
    max(|M|, 0.01 |F| L), and the reported error estimate within a factor 5 of the difference, both ways."""
    model = build_spacecraft(primitives.box_wing(facet_size=0.25), uniform=WHITE)
    size = model.diagonal_m
    for place in _places()[1:]:
        fast = planet_radiation(model, place, reflections="full")
        slow = planet_radiation(model, place, reflections="full", cap=CapSampling(2.5, "cells"))
        force = np.linalg.norm(fast.force_N - slow.force_N) / np.linalg.norm(slow.force_N)
        scale = max(np.linalg.norm(slow.torque_Nm), 0.01 * np.linalg.norm(slow.force_N) * size)
        torque = np.linalg.norm(fast.torque_Nm - slow.torque_Nm) / scale
        assert force < 1e-3 and torque < 1e-2
        estimate = fast.shadow_error.force_N / np.linalg.norm(slow.force_N)
        assert force / 5 < estimate < 5 * force + 1e-5  # the reference's own error is about 1e-5
        for band in ("albedo", "infrared", "solar"):  # powers close as for the cells
            load = getattr(fast, band)
            on_sides = load.absorbed_side_W.sum() + load.reflected_side_W.sum() + load.lost_W
            assert on_sides == pytest.approx(load.power.absorbed_W + load.power.truncated_W, rel=1e-9)


def test_a_convex_model_casts_nothing_and_both_methods_are_exact():
    """On a sphere no side can be shadowed: the visibility is empty, nothing is cast, and the visibility
    and the cells give the exact integrals to round-off."""
    craft = build_spacecraft(primitives.sphere(1.0, 3), uniform=WHITE)
    place = _places()[1]
    seen = visibility(craft, 3, ShadowSampling(), ReflectionSettings("full"), beams=True)
    assert seen.rays == 0 and seen.shadow.nnz == 0 and seen.chains is None
    a = planet_radiation(craft, place, reflections="full")
    b = planet_radiation(craft, place, reflections="full", cap=CapSampling(method="cells"))
    np.testing.assert_allclose(a.force_N, b.force_N, rtol=1e-12, atol=1e-20)


def test_the_visibility_is_kept_on_disk_checked_and_rebuilt_when_damaged(tmp_path):
    """Built once and stored with the view factors; a second model with the same geometry reads it (same
    bits); a damaged file is reported and rebuilt, never used."""
    settings = ReflectionSettings("specular", cache_dir=tmp_path)
    place = _places()[0]

    def fresh():
        return build_spacecraft(primitives.box_wing(facet_size=0.5), uniform=WHITE)

    def run(model):
        return planet_radiation(model, place, reflections=settings, cap=CapSampling(20.0))

    first = run(fresh())
    stored = sorted(tmp_path.glob("visibility-*.npz"))
    assert len(stored) == 1
    again = run(fresh())
    assert np.array_equal(first.force_N, again.force_N) and np.array_equal(first.torque_Nm, again.torque_Nm)
    data = bytearray(stored[0].read_bytes())
    data[len(data) // 2] ^= 0xFF
    stored[0].write_bytes(bytes(data))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rebuilt = run(fresh())
    assert any(issubclass(w.category, CacheWarning) for w in caught)
    assert np.array_equal(first.force_N, rebuilt.force_N)


def test_a_build_too_large_for_memory_is_refused_before_it_starts(monkeypatch):
    craft = build_spacecraft(primitives.box_wing(), uniform=WHITE)
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "64K")
    with pytest.raises(InputError, match=r"directional visibility .* sides along 642 directions") as caught:
        planet_radiation(craft, _places()[0], reflections="none")
    assert "cell_deg" in str(caught.value) and "cells" in str(caught.value)


def test_a_method_not_known_is_refused():
    with pytest.raises(InputError, match="method 'rays' is not one of visibility, cells"):
        CapSampling(method="rays")


def test_an_orbit_with_a_moving_hinge_takes_the_cells_and_a_fixed_one_the_visibility(tmp_path):
    """``EarthTerms(cap_method="auto")``: a tracking wing poses the model anew at every step, so no
    visibility is built; with the hinge held, the model's one visibility serves every step."""
    import sunwind as sw
    from sunwind.forces.orbit.earth_terms import EarthTerms
    from sunwind.forces.tables.jobs import SrpSetup

    mesh, materials = hinged_box_wing(tmp_path)
    materials.write_text(
        materials.read_text().replace("specular_fraction = 0.4", "specular_fraction = 0.4\nemissivity = 0.8")
    )
    epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    path = sw.orbit.propagate(sw.orbit.Elements.circular(500, 97.4), epoch, [0.0, 600.0], "kepler")
    loads = sw.orbit.OrbitLoads(earth=EarthTerms(SrpSetup(reflections="none"), cell_deg=30.0))
    for articulate, built in ((None, False), ({"wing_*": 20.0}, True)):
        model = sw.load(mesh, materials, articulate=articulate, threads=1)
        sw.fly(model, path, sw.orbit.AttitudeLaw.parse("nadir"), loads)
        kept = [
            key for key in model.craft.cache if isinstance(key, tuple) and key[0] == "directional visibility"
        ]
        assert bool(kept) == built
