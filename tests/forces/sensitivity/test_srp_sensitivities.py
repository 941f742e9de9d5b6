"""SRP sensitivities against central differences of the whole model, every optic of every material.

The model: a box bus (closed body, translucent) with two sheet wings, cells in front and Kapton behind,
every coefficient inside its bounds so a central difference is possible. Tolerance 1e-6 of the largest
derivative of the field (force; torque, or 0.01 of the force's times the model's size where the torque is
nearly zero by symmetry); the differences use h = 1e-5, whose own
error (h^2 times the third derivative) is far below that.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import sunwind as sw
from sunwind.forces.sensitivity import OPTICS, Sensitivities
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.spacecraft import build_spacecraft

MATERIALS = {
    "bus": {"reflectivity": 0.4, "specular_fraction": 0.3, "transmissivity": 0.05},
    "cells": {"reflectivity": 0.2, "specular_fraction": 0.5, "transmissivity": 0.1},
    "kapton": {"reflectivity": 0.6, "specular_fraction": 0.1, "transmissivity": 0.02},
}
PARTS = {"bus": "bus", "wing_*": {"front": "cells", "back": "kapton"}}
# Sun on the wings' fronts and the bus, then on their backs past the bus
SUNS = (np.array([0.5, 0.7, 0.3]), np.array([-0.6, -0.2, 0.5]))
STEP = 1e-5
TOLERANCE = 1e-6


@pytest.fixture(scope="module")
def craft():
    spec = parse_materials({"materials": MATERIALS, "parts": PARTS})
    return build_spacecraft(sw.meshes.box_wing(facet_size=0.25), spec)


def perturbed(craft, material: str, coefficient: str, step: float):
    """``craft`` with one coefficient of one material moved by ``step`` (fresh caches)."""
    table = craft.materials
    column = {"reflectivity": "rho", "specular_fraction": "beta", "transmissivity": "sigma"}[coefficient]
    values = getattr(table, column).copy()
    values[table.names.index(material)] += step
    return dataclasses.replace(craft, materials=dataclasses.replace(table, **{column: values}))


def check_against_differences(craft, run) -> float:
    """Worst relative difference between ``run(craft).sensitivities`` and central differences."""
    found: Sensitivities = run(craft, True).sensitivities
    worst = 0.0
    for material in craft.materials.names:
        for coefficient in OPTICS:
            up, down = (run(perturbed(craft, material, coefficient, s), False) for s in (STEP, -STEP))
            derivative = found.of(f"{material}.{coefficient}")
            # a torque is judged on max(|dM|, 0.01 |dF| L), as every torque error in sunwind
            floor = 0.01 * np.abs(derivative.force_N).max() * craft.diagonal_m
            for field in ("force_N", "torque_Nm"):
                difference = (getattr(up, field) - getattr(down, field)) / (2 * STEP)
                mine = getattr(derivative, field)
                scale = max(
                    np.abs(difference).max(), np.abs(mine).max(), floor if field == "torque_Nm" else 0.0
                )
                if scale > 0:
                    worst = max(worst, float(np.abs(mine - difference).max() / scale))
    return worst


@pytest.mark.parametrize("reflections", ["none", "plates", "specular", "full"])
@pytest.mark.parametrize("sun", SUNS, ids=["front", "back"])
def test_sensitivities_match_central_differences(craft, reflections, sun):
    """Direct light, the beam chains (adaptive first beams) and the diffuse balance with its exchange
    factors, every optic of every material."""
    settings = sw.ReflectionSettings(reflections, cache_dir=False, rays_per_side=64)

    def run(model, sensitivities):
        return sw.srp(model, sun, reflections=settings, sensitivities=sensitivities)

    assert check_against_differences(craft, run) < TOLERANCE


def test_full_reflections_with_fixed_sampling_match_central_differences(craft):
    settings = sw.ReflectionSettings("full", cache_dir=False, rays_per_side=64)
    sampling = sw.ShadowSampling(samples=3)

    def run(model, sensitivities):
        return sw.srp(model, SUNS[1], reflections=settings, sampling=sampling, sensitivities=sensitivities)

    assert check_against_differences(craft, run) < TOLERANCE


def test_a_matte_model_at_its_bounds_matches_forward_differences():
    """beta = sigma = 0: a mirror share or a transmission would open paths the exchange does not yet
    follow; the derivative is their first order, checked by second-order forward differences."""
    spec = parse_materials(
        {
            "materials": {"paint": {"reflectivity": 0.7, "specular_fraction": 0.0}},
            "parts": {"bus": "paint", "wing_*": {"front": "paint", "back": "paint"}},
        }
    )
    craft = build_spacecraft(sw.meshes.box_wing(facet_size=0.25), spec)
    settings = sw.ReflectionSettings("full", cache_dir=False, rays_per_side=64)
    sun = SUNS[1]
    found = sw.srp(craft, sun, reflections=settings, sensitivities=True).sensitivities
    for coefficient in ("specular_fraction", "transmissivity"):
        f0, f1, f2 = (
            sw.srp(perturbed(craft, "paint", coefficient, s), sun, reflections=settings).force_N
            for s in (0.0, STEP, 2 * STEP)
        )
        difference = (-3 * f0 + 4 * f1 - f2) / (2 * STEP)
        mine = found.of(f"paint.{coefficient}").force_N
        assert np.abs(mine - difference).max() < TOLERANCE * np.abs(difference).max()


def test_fixed_sampling_sensitivities_match_central_differences(craft):
    sampling = sw.ShadowSampling(samples=4)

    def run(model, sensitivities):
        return sw.srp(model, SUNS[0], reflections="none", sampling=sampling, sensitivities=sensitivities)

    assert check_against_differences(craft, run) < TOLERANCE


def test_sensitivities_are_linear_in_the_flux_and_leave_the_result_alone(craft):
    plain = sw.srp(craft, SUNS[0], reflections="none")
    one = sw.srp(craft, SUNS[0], reflections="none", sensitivities=True)
    two = sw.srp(craft, SUNS[0], reflections="none", sensitivities=True, flux_W_m2=2 * 1361.0)
    assert np.array_equal(plain.force_N, one.force_N) and plain.sensitivities is None
    assert np.allclose(two.sensitivities.force_N, 2 * one.sensitivities.force_N, rtol=1e-12, atol=0)
    assert not one.sensitivities.force_N[:, 3:].any()  # emissivity and accommodations: not in SRP


def test_a_black_face_on_plate_has_the_closed_form_sensitivities():
    """A unit face at normal incidence, where the shares push -P u (absorbed), -2P n (specular),
    -(5/3) P n (diffuse) and nothing (transmitted): dF/d rho = P (1 - 2 beta - (5/3)(1 - beta)) n,
    dF/d beta = -(1/3) P rho n, dF/d sigma = +P n."""
    grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.25)
    cube = sw.load(sw.meshes.box((1.0, 1.0, 1.0)), uniform=grey, threads=1)
    found = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none", sensitivities=True).sensitivities
    pressure = 1361.0 / 299792458.0
    assert np.allclose(found.of("grey.reflectivity").force_N, [-0.75 * pressure, 0, 0], rtol=1e-12)
    assert np.allclose(found.of("grey.specular_fraction").force_N, [-pressure * 0.3 / 3, 0, 0], rtol=1e-12)
    assert np.allclose(found.of("grey.transmissivity").force_N, [pressure, 0, 0], rtol=1e-12)


def test_sensitivities_in_json_and_dataset(craft):
    result = sw.srp(craft, SUNS[0], reflections="none", sensitivities=True)
    document = result.to_json()["sensitivities"]
    assert set(document) == {"bus", "cells", "kapton"}
    assert (
        document["cells"]["reflectivity"]["force_N"]
        == result.sensitivities.of("cells.reflectivity").force_N.tolist()
    )
    dataset = result.sensitivities.to_dataset()
    assert dataset["force_N"].dims == ("material", "coefficient", "component")
    assert dataset["force_N"].sel(material="bus", coefficient="transmissivity").values.tolist() == (
        result.sensitivities.of("bus.transmissivity").force_N.tolist()
    )


def test_specular_chains_at_their_bounds_match_forward_differences():
    """beta = 0 and sigma = 0 on an open box of sheets over a mirror plate, beside a closed box, with
    mirror beams landing: the beam a small mirror share or transmission would start (a derivative-only
    beam, first or after a landing) is in the derivative, checked by second-order forward differences.
    No cutoff (a fixed depth): at h > 0 the cutoff would end a continuation by its power ~ h; the walls
    do not touch, so that no edge joins a side with a zero share to another material's (the model at
    h > 0 would compare their adaptive first beams)."""
    from helpers import quad_sheet
    from sunwind.geometry.mesh_data import MeshData
    from sunwind.meshes import primitives

    walls = np.array(
        [
            [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]],
            [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]],
            [[1, 1, 0], [0, 1, 0], [0, 1, 1], [1, 1, 1]],
            [[0, 1, 0], [0, 0, 0], [0, 0, 1], [0, 1, 1]],
            [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]],
        ],
        dtype=float,
    )
    parts = [quad_sheet(w.mean(0) + 0.96 * (w - w.mean(0)), f"wall{k}", 3) for k, w in enumerate(walls)]
    plate = np.array([[-1, -1, -0.6], [2.5, -1, -0.6], [2.5, 2, -0.6], [-1, 2, -0.6]])
    parts.append(quad_sheet(plate, "plate", 4))
    parts.append(primitives.transform(primitives.box((0.5, 0.5, 0.5), 2), translation=(1.8, 0.5, -0.2)))
    spec = parse_materials(
        {
            "materials": {
                "paint": {"reflectivity": 0.6, "specular_fraction": 0.0, "transmissivity": 0.1},
                "foil": {"reflectivity": 0.85, "specular_fraction": 0.9, "transmissivity": 0.0},
                "glass": {"reflectivity": 0.3, "specular_fraction": 0.7, "transmissivity": 0.4},
            },
            "parts": {
                "wall0": {"front": "foil", "back": "paint"},
                "wall1": {"front": "glass", "back": "glass"},
                "wall2": {"front": "paint", "back": "foil"},
                "wall3": {"front": "glass", "back": "foil"},
                "wall4": {"front": "foil", "back": "paint"},
                "plate": {"front": "foil"},
                "box": "paint",
            },
        }
    )
    craft = build_spacecraft(MeshData.concatenate(parts), spec)
    settings = sw.ReflectionSettings("specular", cutoff=0.0, depth=12, cache_dir=False)
    sun = np.array([0.35, 0.2, 0.9])
    found = sw.srp(craft, sun, reflections=settings, sensitivities=True).sensitivities
    for material, coefficient in (("paint", "specular_fraction"), ("foil", "transmissivity")):
        f0, f1, f2 = (
            sw.srp(perturbed(craft, material, coefficient, s), sun, reflections=settings)
            for s in (0.0, STEP, 2 * STEP)
        )
        mine = found.of(f"{material}.{coefficient}")
        floor = 0.01 * np.abs(mine.force_N).max() * craft.diagonal_m
        for field in ("force_N", "torque_Nm"):
            values = [getattr(f, field) for f in (f0, f1, f2)]
            difference = (-3 * values[0] + 4 * values[1] - values[2]) / (2 * STEP)
            scale = max(np.abs(difference).max(), floor if field == "torque_Nm" else 0.0)
            assert np.abs(getattr(mine, field) - difference).max() < TOLERANCE * scale, (material, field)


def test_the_diffuse_balances_sensitivities_are_sized_before_they_are_made(craft, monkeypatch):
    """Their columns grow with sides times materials: over SUNWIND_MAX_MEMORY they are refused, naming
    the fix, before any array is made."""
    craft = dataclasses.replace(craft)  # an empty cache: the sensitivities not yet made
    settings = sw.ReflectionSettings("full", cache_dir=False, rays_per_side=64)
    sw.srp(craft, SUNS[0], reflections=settings)  # the plan and its exchange, within any limit
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "64K")
    refused = r"not enough memory.*diffuse balance's sensitivities"
    with pytest.raises(sw.SunwindError, match=refused) as raised:
        sw.srp(craft, SUNS[0], reflections=settings, sensitivities=True)
    assert "specular" in str(raised.value)
