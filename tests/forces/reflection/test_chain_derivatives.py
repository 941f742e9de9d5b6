"""Derivatives of the beam chains with respect to every material's optics, against central differences
of :func:`follow_chains` itself: the same Illumination, so the same rays, with one coefficient of one
material moved by +-H on a copy of the model."""

from dataclasses import replace

import numpy as np
import pytest
import tomllib

from helpers import quad_sheet
from sunwind.forces.reflection import beams, chain_derivatives
from sunwind.forces.reflection.beams import follow_chains
from sunwind.forces.reflection.chain_derivatives import OPTICS
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import primitives

FLUX = 1000.0
REFERENCE = np.array([0.3, 0.2, 0.1])
SUN = np.array([0.35, 0.2, 0.9]) / np.linalg.norm([0.35, 0.2, 0.9])
#: Step of the central differences. The chains are polynomials of low degree in each coefficient, so the
#: difference's truncation error is nil; its round-off is about 1e-16 |result| / H (1e-8 of the
#: derivatives with adaptive first beams at this step, 1e-7 at 1e-6).
H = 1e-5
#: Agreement asked, relative to the largest derivative of each field.
TOLERANCE = 1e-6
VECTORS = ("force_N", "torque_Nm", "open_sky_force_N", "open_sky_torque_Nm")
POWERS = ("escaped_W", "absorbed_W", "truncated_W", "first_W")
PER_SIDE = ("arrived_W", "diffuse_source_W")

#: Three materials, no share zero (central differences; zero shares, which send derivative-only beams, are
#: tested with ``BOUNDS`` below): glass, a sheet both mirroring and transmitting; paint, also on a
#: closed box, whose transmitted share leaves at once; foil, mostly a mirror.
MATERIALS = """
[materials.glass]
reflectivity = 0.35
specular_fraction = 0.7
transmissivity = 0.4
[materials.paint]
reflectivity = 0.6
specular_fraction = 0.3
transmissivity = 0.1
[materials.foil]
reflectivity = 0.85
specular_fraction = 0.9
transmissivity = 0.02
[parts]
wall0 = { front = "foil", back = "paint" }
wall1 = { front = "glass", back = "glass" }
wall2 = { front = "paint", back = "foil" }
wall3 = { front = "glass", back = "foil" }
wall4 = { front = "foil", back = "glass" }
plate = { front = "foil" }
box = "paint"
"""
WALLS = [
    [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]],
    [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]],
    [[1, 1, 0], [0, 1, 0], [0, 1, 1], [1, 1, 1]],
    [[0, 1, 0], [0, 0, 0], [0, 0, 1], [0, 1, 1]],
    [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]],
]


@pytest.fixture(scope="module")
def craft():
    """An open box of two-sided sheets over a one-sided plate, beside a closed box: beams go round the
    cavity, through its walls onto the plate and from the plate back up."""
    parts = [quad_sheet(np.array(f, dtype=float), f"wall{k}", 3) for k, f in enumerate(WALLS)]
    plate = np.array([[-1, -1, -0.6], [2.5, -1, -0.6], [2.5, 2, -0.6], [-1, 2, -0.6]])
    parts.append(quad_sheet(plate, "plate", 4))
    parts.append(primitives.transform(primitives.box((0.5, 0.5, 0.5), 2), translation=(1.8, 0.5, -0.2)))
    spec = parse_materials(tomllib.loads(MATERIALS))
    return build_spacecraft(MeshData.concatenate(parts), materials=spec)


def moved(craft, material: int, coefficient: int, step: float):
    """A copy of ``craft`` with one coefficient of one material moved by ``step``."""
    name = OPTICS[coefficient]
    values = getattr(craft.materials, name).copy()
    values[material] += step
    return replace(craft, materials=replace(craft.materials, **{name: values}))


def check_against_differences(craft, light, coefficients=None, **ends):
    """Compare every derivative field with central differences over ``coefficients`` ((material,
    coefficient) pairs, all by default); returns the result with derivatives."""
    chains = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True, **ends)
    found = chains.derivatives
    n = len(craft.materials)
    if coefficients is None:
        coefficients = [(m, k) for m in range(n) for k in range(3)]
    for m, k in coefficients:
        up, down = (
            follow_chains(moved(craft, m, k, s), light, FLUX, REFERENCE, level=light.level, **ends)
            for s in (H, -H)
        )
        assert up.rays == down.rays == chains.rays  # the same rays: the same decisions
        for name in (*VECTORS, *POWERS, *PER_SIDE):
            difference = (np.asarray(getattr(up, name)) - np.asarray(getattr(down, name))) / (2 * H)
            every = getattr(found, name)
            derivative = every[:, 3 * m + k] if name in PER_SIDE else every[m, k]
            scale = np.abs(every).max()
            assert np.abs(difference - derivative).max() <= TOLERANCE * scale + 1e-9, (name, m, k)
    return chains


def test_the_copy_of_a_model_with_other_materials_has_their_optics(craft):
    copy = moved(craft, 0, 2, 0.25)
    assert craft.side_optics is not copy.side_optics
    foil = craft.side_material == 0
    np.testing.assert_array_equal(copy.side_optics[foil, 2], craft.side_optics[foil, 2] + 0.25)
    np.testing.assert_array_equal(copy.side_optics[~foil], craft.side_optics[~foil])


@pytest.mark.parametrize("samples", [1, 4])
def test_derivatives_with_fixed_sampling_equal_central_differences(craft, samples):
    light = side_sampler(craft).illuminate(SUN, samples)
    # the escape test leaves some first beams out: their power's derivatives count too
    assert beams._emitters(craft, light, FLUX, cull=True).escaping_W > 0
    chains = check_against_differences(craft, light)
    found = chains.derivatives
    assert found.force_N.shape == found.torque_Nm.shape == (3, 3, 3)
    assert found.open_sky_force_N.shape == found.open_sky_torque_Nm.shape == (3, 3, 3)
    assert found.arrived_W.shape == found.diffuse_source_W.shape == (craft.n_sides, 9)
    assert found.escaped_W.shape == found.absorbed_W.shape == (3, 3)
    assert np.all(found.force_N != 0)  # every coefficient of every material counts here


def test_a_sheet_that_mirrors_and_transmits_sends_both_first_beams(craft):
    """Glass sides lit from above send a mirror and a transmitted first beam each, and their
    derivatives in glass's beta (mirror beam only) and sigma (transmitted only) are right."""
    light = side_sampler(craft).illuminate(SUN, 1)
    emitters = beams._emitters(craft, light, FLUX, cull=False)
    glass = craft.materials.names.index("glass")
    on_glass = craft.side_material[emitters.side] == glass
    through = np.einsum("nd,nd->n", emitters.beams.lift, craft.side_normals[emitters.side]) < 0
    assert np.any(on_glass & through) and np.any(on_glass & ~through)
    check_against_differences(craft, light, [(glass, 1), (glass, 2)])


def test_derivatives_with_the_cutoff_and_depth_ending_chains_equal_central_differences(craft):
    light = side_sampler(craft).illuminate(SUN, 4)
    chains = check_against_differences(craft, light, cutoff=0.013, depth=3)
    assert chains.truncated_W > 0.01 * chains.first_W
    assert np.abs(chains.derivatives.truncated_W).max() > 0


def test_derivatives_with_adaptive_first_beams_equal_central_differences(craft):
    light = side_sampler(craft).illuminate(SUN)
    assert light.level is None
    chains = check_against_differences(craft, light, [(0, 0), (1, 1), (2, 2), (1, 2)])
    assert chains.rays > 4 * len(beams._emitters(craft, light, FLUX, cull=False).side)  # refined


@pytest.mark.parametrize("samples", [1, 4, None])
def test_the_derivatives_of_the_power_balance_balance(craft, samples):
    """Every watt of the first beams escapes, is absorbed, truncated or handed to diffuse reflection,
    and so does every derivative."""
    light = side_sampler(craft).illuminate(SUN, samples)
    chains = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True)
    found = chains.derivatives
    spent = (
        found.escaped_W + found.absorbed_W + found.truncated_W + found.diffuse_source_W.sum(0).reshape(3, 3)
    )
    np.testing.assert_allclose(spent, found.first_W, rtol=0, atol=1e-10 * np.abs(found.first_W).max())


@pytest.mark.parametrize("samples", [1, 4, None])
def test_taking_derivatives_changes_no_bit_of_the_result(craft, samples):
    light = side_sampler(craft).illuminate(SUN, samples)
    plain = follow_chains(craft, light, FLUX, REFERENCE, level=light.level)
    both = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True)
    assert plain.derivatives is None and both.derivatives is not None
    for name in (*VECTORS, *POWERS, *PER_SIDE, "truncated_W", "rays", "depth"):
        np.testing.assert_array_equal(getattr(plain, name), getattr(both, name))


def test_with_too_many_materials_for_a_bit_mask_every_column_gives_the_same_derivatives(craft, monkeypatch):
    light = side_sampler(craft).illuminate(SUN, 4)
    masked = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True).derivatives
    monkeypatch.setattr(chain_derivatives, "MASKED_MATERIALS", 2)
    every = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True).derivatives
    for name in (*VECTORS, *POWERS, *PER_SIDE):
        expected = getattr(masked, name)
        np.testing.assert_allclose(
            getattr(every, name), expected, rtol=0, atol=1e-13 * np.abs(expected).max()
        )


def test_a_closed_body_that_transmits_nothing_has_the_derivative_of_transmitting_a_little():
    """A closed body's transmitted share leaves at once, no ray needed: at ``sigma = 0`` its derivative is
    the one-sided difference as sigma grows (the chains are linear in it there)."""
    plate = quad_sheet(np.array([[-1, -1, -0.6], [2.5, -1, -0.6], [2.5, 2, -0.6], [-1, 2, -0.6]]), "plate", 4)
    box = primitives.transform(primitives.box((0.5, 0.5, 0.5), 2), translation=(1.8, 0.5, -0.2))
    materials = MATERIALS.replace("transmissivity = 0.1", "transmissivity = 0.0").split("[parts]")[0]
    spec = parse_materials(tomllib.loads(materials + '[parts]\nplate = { front = "foil" }\nbox = "paint"\n'))
    craft = build_spacecraft(MeshData.concatenate([plate, box]), materials=spec)
    paint = craft.materials.names.index("paint")
    assert craft.materials.sigma[paint] == 0.0
    light = side_sampler(craft).illuminate(SUN, 4)
    chains = follow_chains(craft, light, FLUX, REFERENCE, level=4, derivatives=True)
    on_box = craft.side_material == paint
    assert chains.arrived_W[on_box].sum() > 0.01 * chains.first_W  # the plate's beams meet the box
    up = follow_chains(moved(craft, paint, 2, H), light, FLUX, REFERENCE, level=4)
    for name in ("force_N", "torque_Nm", "escaped_W", "absorbed_W"):
        difference = (np.asarray(getattr(up, name)) - np.asarray(getattr(chains, name))) / H
        derivative = getattr(chains.derivatives, name)[paint, 2]
        assert np.abs(difference - derivative).max() <= TOLERANCE * np.abs(derivative).max(), name
    assert np.abs(chains.derivatives.escaped_W[paint, 2]) > 0


#: The model of the tests above with shares at their bounds: paint is Lambertian (``beta = 0``), foil opaque
#: (``sigma = 0``), tint mirrors nothing (``rho = 0 < beta``), and matte (``beta = 0``) lines the
#: underside of the box's floor, which only the plate's beams reach.
BOUNDS = {
    "paint": {"specular_fraction": 0.0},
    "foil": {"transmissivity": 0.0},
    "tint": {"reflectivity": 0.0, "specular_fraction": 0.6, "transmissivity": 0.5},
    "matte": {"reflectivity": 0.7, "specular_fraction": 0.0, "transmissivity": 0.2},
}
#: Forward differences' step: their error (h^2 times the third derivative) is far below TOLERANCE.
FORWARD = 1e-5
#: Chains followed to a fixed depth with no cutoff, as at h > 0 (see test_the_cutoff_...).
NO_CUTOFF = {"cutoff": 0.0, "depth": 12}


@pytest.fixture(scope="module")
def bounded():
    """:func:`craft` with the materials of ``BOUNDS``, tint on a wall the Sun lights inside, matte under
    the floor; its walls do not touch."""
    table = tomllib.loads(MATERIALS)
    for name, values in BOUNDS.items():
        table["materials"].setdefault(name, {"reflectivity": 0.5, "specular_fraction": 0.5}).update(values)
    table["parts"]["wall1"] = {"front": "tint", "back": "tint"}
    table["parts"]["wall0"] = {"front": "matte", "back": "paint"}
    # walls 2 cm apart: no edge joins two materials' sides (see test_adaptive_...)
    walls = [np.mean(f, axis=0) + 0.96 * (f - np.mean(f, axis=0)) for f in np.array(WALLS, dtype=float)]
    parts = [quad_sheet(corners, f"wall{k}", 3) for k, corners in enumerate(walls)]
    plate = np.array([[-1, -1, -0.6], [2.5, -1, -0.6], [2.5, 2, -0.6], [-1, 2, -0.6]])
    parts.append(quad_sheet(plate, "plate", 4))
    parts.append(primitives.transform(primitives.box((0.5, 0.5, 0.5), 2), translation=(1.8, 0.5, -0.2)))
    return build_spacecraft(MeshData.concatenate(parts), materials=parse_materials(table))


def check_against_forward_differences(craft, light, coefficients, **ends):
    """Compare every derivative field over ``coefficients`` ((material name, coefficient) pairs) with
    second-order forward differences ``(-3 f(0) + 4 f(h) - f(2h)) / 2h`` of :func:`follow_chains` on the
    same ``light``; returns the result with derivatives."""
    chains = follow_chains(craft, light, FLUX, REFERENCE, level=light.level, derivatives=True, **ends)
    found = chains.derivatives
    for name, k in coefficients:
        m = craft.materials.names.index(name)
        f0, f1, f2 = (
            chains
            if s == 0
            else follow_chains(moved(craft, m, k, s), light, FLUX, REFERENCE, level=light.level, **ends)
            for s in (0.0, FORWARD, 2 * FORWARD)
        )
        for field in (*VECTORS, *POWERS, *PER_SIDE):
            values = [np.asarray(getattr(f, field)) for f in (f0, f1, f2)]
            difference = (-3 * values[0] + 4 * values[1] - values[2]) / (2 * FORWARD)
            every = getattr(found, field)
            derivative = every[:, 3 * m + k] if field in PER_SIDE else every[m, k]
            scale = max(np.abs(every).max(), np.abs(difference).max())
            assert np.abs(difference - derivative).max() <= TOLERANCE * scale + 1e-9, (field, name, k)
    return chains


@pytest.mark.parametrize("samples", [1, 4, None])
def test_zero_shares_have_the_derivatives_of_the_beams_they_would_start(bounded, samples):
    """d/d beta of a Lambertian paint, d/d rho of a material with ``rho = 0``, d/d sigma of an opaque
    sheet, d/d beta of a Lambertian side only beams reach: derivative-only beams, first beams and
    continuations, with fixed and adaptive first beams."""
    light = side_sampler(bounded).illuminate(SUN, samples)
    if samples is not None:  # the escape test leaves derivative-only beams out too
        assert beams._emitters(bounded, light, FLUX, True, cull=True).derivatives.culled.any()
    at_bounds = [("paint", 1), ("tint", 0), ("foil", 2), ("matte", 1)]
    chains = check_against_forward_differences(bounded, light, at_bounds, **NO_CUTOFF)
    found, names = chains.derivatives, bounded.materials.names
    assert found.rays > 0
    for name, k in at_bounds:
        assert np.abs(found.force_N[names.index(name), k]).max() > 1e-3 * np.abs(found.force_N).max(), name
    matte = names.index("matte")
    assert np.all(found.first_W[matte] == 0)  # matte sends no first beam: its beta counts by continuations
    emitters = beams._emitters(bounded, light, FLUX, cull=False)  # no derivative-only ones
    mirror = np.einsum("nd,nd->n", emitters.beams.lift, bounded.side_normals[emitters.side]) > 0
    zero = [names.index("paint"), names.index("tint")]  # mirror shares rho beta = 0
    assert len(emitters.side) and not np.isin(bounded.side_material[emitters.side[mirror]], zero).any()


@pytest.mark.parametrize("samples", [4, None])
def test_the_coefficients_inside_their_bounds_keep_their_derivatives(bounded, samples):
    light = side_sampler(bounded).illuminate(SUN, samples)
    inside = [("glass", k) for k in range(3)] + [("paint", 0), ("foil", 1), ("tint", 2), ("matte", 0)]
    check_against_forward_differences(bounded, light, inside, **NO_CUTOFF)


@pytest.mark.parametrize("samples", [1, 4, None])
def test_derivative_only_beams_change_no_bit_of_the_result_and_balance(bounded, samples):
    light = side_sampler(bounded).illuminate(SUN, samples)
    plain = follow_chains(bounded, light, FLUX, REFERENCE, level=light.level)
    both = follow_chains(bounded, light, FLUX, REFERENCE, level=light.level, derivatives=True)
    assert both.derivatives.rays > 0  # derivative-only rays, counted apart
    for name in (*VECTORS, *POWERS, *PER_SIDE, "truncated_W", "rays", "depth"):
        np.testing.assert_array_equal(getattr(plain, name), getattr(both, name))
    found = both.derivatives
    n = len(bounded.materials)
    spent = (
        found.escaped_W + found.absorbed_W + found.truncated_W + found.diffuse_source_W.sum(0).reshape(n, 3)
    )
    np.testing.assert_allclose(spent, found.first_W, rtol=0, atol=1e-10 * np.abs(found.first_W).max())


#: A Lambertian plate lit from the side, and beside it a mirror ceiling the Sun does not light: only
#: the plate's derivative-only mirror beams meet it, and its mirror share 0.765 sends them on.
LEDGE = """
[materials.paint]
reflectivity = 0.6
specular_fraction = 0.0
transmissivity = 0.2
[materials.foil]
reflectivity = 0.85
specular_fraction = 0.9
[parts]
plate = { front = "paint" }
ceiling = { front = "foil" }
"""


@pytest.mark.parametrize("samples", [4, None])
@pytest.mark.parametrize("cutoff", [0.5, 0.8])
def test_the_cutoff_ends_derivative_only_chains_by_their_scale(cutoff, samples):
    """A chain whose first beam is derivative-only is cut where the model is at any small share (all its
    powers scale with the share): the ceiling's beams go on at a cutoff of 0.5, not of 0.8 (their
    derivatives are 0.765 of the first beams'). The model at h casts the same rays."""
    plate = quad_sheet(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0.0]]), "plate", 2)
    ceiling = quad_sheet(np.array([[-3, -1, 1], [-3, 1, 1], [-1.2, 1, 1], [-1.2, -1, 1.0]]), "ceiling", 2)
    craft = build_spacecraft(
        MeshData.concatenate([plate, ceiling]), materials=parse_materials(tomllib.loads(LEDGE))
    )
    light = side_sampler(craft).illuminate(np.array([0.8, 0.0, 0.6]), samples)
    chains = check_against_forward_differences(craft, light, [("paint", 1)], cutoff=cutoff)
    found, paint = chains.derivatives, craft.materials.names.index("paint")
    assert found.rays > 0 and chains.absorbed_W == chains.arrived_W.sum() == 0  # no plain beam lands
    assert (found.truncated_W[paint, 1] > 0.1 * found.first_W[paint, 1]) == (cutoff > 0.765)
    up = follow_chains(
        moved(craft, paint, 1, FORWARD), light, FLUX, REFERENCE, level=light.level, cutoff=cutoff
    )
    assert up.rays == chains.rays + found.rays
