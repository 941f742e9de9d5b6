"""Models and simulated telemetry for the fit's twin experiments: the box-wing with three finishes, its
telemetry made by the model itself with other coefficients, plus Gaussian noise."""

from __future__ import annotations

import numpy as np
import pytest
import tomllib
from scipy.integrate import cumulative_trapezoid

from sunwind.forces import srp
from sunwind.forces.fit.forward import with_optics
from sunwind.forces.fit.telemetry import Telemetry
from sunwind.forces.model import Model
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes import box_wing

MATERIALS = """
[materials.paint]
reflectivity = 0.7
specular_fraction = 0.1
[materials.cells]
reflectivity = 0.1
specular_fraction = 0.8
[materials.cfrp]
reflectivity = 0.1
specular_fraction = 0.2
[parts]
"bus" = "paint"
"wing_*" = { front = "cells", back = "cfrp" }
"""
#: The torque reference point of the box-wing [m]: off the centre, so that every side makes a torque.
CENTRE = (0.15, 0.1, -0.2)
MASS_KG = 500.0


def box_wing_model(reflections_ok: bool = True) -> Model:
    """The box-wing of :data:`MATERIALS` about :data:`CENTRE`."""
    spec = parse_materials(tomllib.loads(MATERIALS), "box_wing.toml")
    craft = build_spacecraft(box_wing(facet_size=0.25), spec)
    return Model(craft, reference_point_m=np.array(CENTRE))


def optics_with(model: Model, changes: dict[str, float]) -> np.ndarray:
    """The model's optics (n_materials, 3) with ``{"cells.reflectivity": 0.2, ...}`` applied."""
    table = model.craft.materials
    optics = np.stack([table.rho, table.beta, table.sigma], 1).astype(float)
    columns = ("reflectivity", "specular_fraction", "transmissivity")
    for name, value in changes.items():
        material, _, coefficient = name.rpartition(".")
        optics[table.names.index(material), columns.index(coefficient)] = value
    return optics


def sphere(n: int, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(n, 3))
    return u / np.linalg.norm(u, axis=1, keepdims=True)


def simulate(
    model: Model,
    truth: dict[str, float],
    sun_body: np.ndarray,
    noise: dict[str, float],
    rng: np.random.Generator,
    rotation: np.ndarray | None = None,
    reflections: str = "none",
) -> tuple[Telemetry, dict[str, np.ndarray]]:
    """Telemetry of ``model`` with the ``truth`` coefficients at the rows' Suns, 10 s apart, with
    Gaussian noise of ``noise`` per kind; also the noiseless measurements."""
    n = len(sun_body)
    time = 10.0 * np.arange(n)
    batch = srp(with_optics(model, optics_with(model, truth)), sun_body, reflections=reflections)
    exact = {}
    if "torque" in noise:
        exact["torque"] = batch.torque_Nm
    if "accel" in noise:
        exact["accel"] = batch.force_N / MASS_KG
    if "momentum" in noise:
        torque = batch.torque_Nm if rotation is None else np.einsum("nij,nj->ni", rotation, batch.torque_Nm)
        exact["momentum"] = cumulative_trapezoid(torque, time, axis=0, initial=0.0) + np.array(
            [0.01, -0.02, 0.005]
        )
    measured = {
        kind: values + rng.normal(scale=noise[kind], size=values.shape) for kind, values in exact.items()
    }
    telemetry = Telemetry(time, sun_body, np.full(n, 1361.0), np.ones(n), measured, rotation=rotation)
    return telemetry, exact


@pytest.fixture(scope="module")
def model() -> Model:
    return box_wing_model()


@pytest.fixture
def twin():
    """The module's helpers, for the tests: simulate, sphere, optics_with, MASS_KG."""
    return type(
        "Twin",
        (),
        {
            "simulate": staticmethod(simulate),
            "sphere": staticmethod(sphere),
            "optics_with": staticmethod(optics_with),
            "mass": MASS_KG,
            "materials": MATERIALS,
            "centre": CENTRE,
        },
    )
