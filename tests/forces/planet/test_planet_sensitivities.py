"""The planet's radiation sensitivities (d force, d torque per material coefficient): every coefficient of
every material against central differences of the whole ``planet_radiation``, on a box-wing of three
materials that shadows itself, by the visibility and by the cells, with reflections none and plates."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.visibility import level_for, visibility
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensitivity import COEFFICIENTS
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes import primitives

LIGHT = PlanetLight.of(planet("earth"), 1361.0)
REFERENCE = np.array([0.1, -0.2, 0.3])
CELL_DEG = 30.0
#: The coefficients the planet's bands depend on, and the column of MaterialTable each is.
COLUMNS = {"reflectivity": "rho", "specular_fraction": "beta", "transmissivity": "sigma", "emissivity": "eps"}
#: Nadir tilted so that the bus and the wings shade one another across the cap; the Sun 55 deg from the
#: zenith, and 93 deg (the terminator crosses the cap).
PLACES = {
    "day": Place([0.35, 0.25, -1.0], 500.0, [0.6, -0.2, 0.8]),
    "terminator": Place(
        [0.0, 0.3, -1.0], 800.0, [math.sin(math.radians(93.0)), 0.0, math.cos(math.radians(93.0))]
    ),
}
STEP = 1e-3


@pytest.fixture(scope="module")
def craft() -> Spacecraft:
    names = ("reflectivity", "specular_fraction", "transmissivity", "emissivity")
    optics = {"white": (0.5, 0.4, 0.0, 0.8), "cells": (0.2, 0.7, 0.1, 0.85), "kapton": (0.6, 0.2, 0.05, 0.6)}
    spec = parse_materials(
        {
            "materials": {name: dict(zip(names, values, strict=True)) for name, values in optics.items()},
            "parts": {"bus": "white", "wing*": {"front": "cells", "back": "kapton"}},
        }
    )
    return build_spacecraft(primitives.box_wing(facet_size=0.5), spec)


def _radiation(craft: Spacecraft, place: Place, method: str = "visibility", **options):
    cap = CapSampling(CELL_DEG, method)
    return planet_radiation(craft, place, LIGHT, reference_point_m=REFERENCE, cap=cap, **options)


def _perturbed(craft: Spacecraft, material: int, coefficient: str, step: float) -> Spacecraft:
    """A copy of ``craft`` (empty cache) with one coefficient of one material moved by ``step``."""
    table = craft.materials
    column = np.array(getattr(table, COLUMNS[coefficient]), dtype=np.float64)
    column[material] += step
    return dataclasses.replace(craft, materials=dataclasses.replace(table, **{COLUMNS[coefficient]: column}))


@pytest.mark.parametrize("place", sorted(PLACES))
@pytest.mark.parametrize(
    "method, reflections",
    [("visibility", "none"), ("cells", "none"), ("visibility", "plates"), ("cells", "plates")],
)
def test_every_coefficient_against_central_differences(craft, place, method, reflections):
    """d force and d torque per material and coefficient against central differences of the whole
    calculation, each perturbed model built afresh (its visibility rebuilt for its optics): to 1e-6 of
    the derivative's scale (the direct load is linear in each coefficient, so the differences are exact
    to rounding); the gas coefficients are zero. The visibility's passes take 4 fixed points per side
    (its 24 rebuilds in a second; the default passes' couples are checked below)."""
    options = {"method": method, "reflections": reflections}
    if method == "visibility":
        options["sampling"] = ShadowSampling(samples=4)
    result = _radiation(craft, PLACES[place], sensitivities=True, **options)
    if reflections == "none":
        assert result.rays > 0
    found = result.sensitivities
    assert found.materials == craft.materials.names
    assert np.array_equal(found.reference_point_m, REFERENCE)
    assert not np.any(found.force_N[:, 4:]) and not np.any(found.torque_Nm[:, 4:])
    scale = {"force": np.abs(found.force_N).max(), "torque": np.abs(found.torque_Nm).max()}
    assert scale["force"] > 0 and scale["torque"] > 0
    for m in range(len(craft.materials)):
        for coefficient in COLUMNS:
            up = _radiation(_perturbed(craft, m, coefficient, STEP), PLACES[place], **options)
            down = _radiation(_perturbed(craft, m, coefficient, -STEP), PLACES[place], **options)
            k = COEFFICIENTS.index(coefficient)
            for name, got in (("force", found.force_N[m, k]), ("torque", found.torque_Nm[m, k])):
                attribute = f"{name}_N" if name == "force" else f"{name}_Nm"
                expected = (getattr(up, attribute) - getattr(down, attribute)) / (2 * STEP)
                size = max(float(np.abs(expected).max()), 1e-3 * scale[name])
                assert np.abs(got - expected).max() <= 1e-6 * size, (
                    craft.materials.names[m],
                    coefficient,
                    name,
                )


def test_the_visibility_keeps_the_lit_couples_per_material_with_the_optics(craft):
    """A perturbed model's visibility is its own (its optics enter the key); a fresh copy of the model
    reads the visibility, lit couples per material included, from disk and gives the same derivatives;
    the per-material couples weighted by the shares are the visibility's couples of each band."""
    level, sampling, settings = level_for(CELL_DEG), ShadowSampling(), ReflectionSettings("none")
    seen = visibility(craft, level, sampling, settings)
    other = visibility(_perturbed(craft, 0, "reflectivity", STEP), level, sampling, settings)
    assert other is not seen and not np.array_equal(other.shift_torque_Nm, seen.shift_torque_Nm)
    assert np.array_equal(other.lit_torque_Nm, seen.lit_torque_Nm)  # the couples per share: optics apart
    table = craft.materials
    for band, (rho, beta, sigma) in enumerate([(table.rho, table.beta, table.sigma), (1 - table.eps, 0, 0)]):
        shares = np.stack(np.broadcast_arrays(1 - rho - sigma, rho * beta, rho * (1 - beta), sigma), axis=1)
        weighted = np.einsum("ms,jmsc->jc", shares, seen.lit_torque_Nm)
        assert np.allclose(weighted, seen.shift_torque_Nm[band], rtol=1e-12, atol=1e-18)
    first = _radiation(craft, PLACES["day"], sensitivities=True, reflections="none")
    copy = dataclasses.replace(craft)  # an empty cache: the visibility comes from disk
    again = _radiation(copy, PLACES["day"], sensitivities=True, reflections="none")
    assert visibility(copy, level, sampling, settings).origin.startswith("cache")
    assert np.array_equal(again.sensitivities.force_N, first.sensitivities.force_N)
    assert np.array_equal(again.sensitivities.torque_Nm, first.sensitivities.torque_Nm)


def test_the_methods_agree_and_the_plates_need_no_shadow(craft):
    """The visibility's and the cells' derivatives agree to the shadowing's resolution, and the plate
    mode's are those of the whole cap on every side (the same by either method)."""
    place = PLACES["day"]
    grid = _radiation(craft, place, sensitivities=True, reflections="none").sensitivities
    cells = _radiation(craft, place, sensitivities=True, reflections="none", method="cells").sensitivities
    assert np.abs(grid.force_N - cells.force_N).max() <= 0.05 * np.abs(cells.force_N).max()
    plates = [
        _radiation(craft, place, sensitivities=True, reflections="plates", method=method).sensitivities
        for method in ("visibility", "cells")
    ]
    assert np.array_equal(plates[0].force_N, plates[1].force_N)
    assert np.array_equal(plates[0].torque_Nm, plates[1].torque_Nm)


@pytest.mark.parametrize("reflections", ["specular", "full"])
def test_reflections_followed_by_the_visibility_are_refused(craft, reflections):
    """The visibility keeps its nodes' chains without their derivatives: the cells are named."""
    with pytest.raises(InputError, match=f"reflections '{reflections}' need the cap's cells") as raised:
        _radiation(craft, PLACES["day"], sensitivities=True, reflections=reflections)
    assert "cells" in raised.value.hint and "none" in raised.value.hint


@pytest.mark.parametrize("place", sorted(PLACES))
@pytest.mark.parametrize("reflections", ["specular", "full"])
def test_reflected_light_by_the_cells_against_central_differences(craft, place, reflections):
    """The cells' beam chains (their derivatives traced) and, with full, the diffuse balance of the
    albedo in the solar optics and of the infrared in (1 - eps, 0, 0), every coefficient of every
    material against central differences of the whole calculation (step 1e-5: the reflected part is not
    linear in the coefficients; second-order forward differences for the white bus's transmissivity,
    0), to 1e-6 of the derivative's scale."""
    settings = ReflectionSettings(reflections, cache_dir=False, rays_per_side=64)
    options = {"method": "cells", "reflections": settings, "sampling": ShadowSampling(samples=3)}
    found = _radiation(craft, PLACES[place], sensitivities=True, **options).sensitivities
    step = 1e-5
    for m in range(len(craft.materials)):
        for coefficient in COLUMNS:
            at_bound = getattr(craft.materials, COLUMNS[coefficient])[m] == 0.0
            steps, weights = (
                ((0.0, step, 2 * step), (-1.5, 2.0, -0.5)) if at_bound else ((-step, step), (-0.5, 0.5))
            )
            runs = [_radiation(_perturbed(craft, m, coefficient, h), PLACES[place], **options) for h in steps]
            k = COEFFICIENTS.index(coefficient)
            for attribute, got in (("force_N", found.force_N[m, k]), ("torque_Nm", found.torque_Nm[m, k])):
                expected = sum(w * getattr(r, attribute) for w, r in zip(weights, runs, strict=True)) / step
                scale = np.abs(getattr(found, attribute)).max()
                size = max(float(np.abs(expected).max()), 1e-3 * scale)
                assert np.abs(got - expected).max() <= 1e-6 * size, (m, coefficient, attribute)


def test_without_sensitivities_there_are_none(craft):
    assert _radiation(craft, PLACES["day"], reflections="none").sensitivities is None


def test_auto_reflections_that_resolve_to_none_give_sensitivities():
    """A convex box has ``K_IS = 0``: ``auto`` is ``none``, and its derivatives are those of ``none``."""
    grey = parse_materials({
        "materials": {"grey": {"reflectivity": 0.3, "specular_fraction": 0.2, "emissivity": 0.7}},
        "parts": {"*": "grey"},
    })  # fmt: skip
    box = build_spacecraft(primitives.box(), grey)
    auto = _radiation(box, PLACES["day"], sensitivities=True)
    none = _radiation(box, PLACES["day"], sensitivities=True, reflections="none")
    assert auto.reflections == "none"
    assert np.array_equal(auto.sensitivities.force_N, none.sensitivities.force_N)
