"""Each orbit step's inputs as a record of named columns: cut into chunks, put back together, sent to
Dask workers, fingerprinted; what the orbit computes as one record of settings (OrbitLoads), its flux at
1 au under its own name; the modules' examples run."""

from __future__ import annotations

import doctest
import importlib
import pickle
from dataclasses import replace

import numpy as np
import pytest

from sunwind.forces import Model
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, StepInputs, fly, propagate
from sunwind.forces.orbit.flight import step_inputs
from sunwind.forces.tables.checkpoint import inputs_digest
from sunwind.forces.tables.engine import SweepRun
from sunwind.forces.tables.jobs import GasOptions, SrpSetup
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing

EPOCH = Epoch.of("2024-06-01T00:00:00Z")


@pytest.fixture(scope="module")
def model():
    craft = build_spacecraft(
        box_wing(facet_size=0.5), uniform=Material("paint", 0.5, 0.4, 0.0), two_sided=["wing*"]
    )
    return Model(craft)


@pytest.fixture(scope="module")
def path():
    return propagate(Elements.circular(450.0, 51.6, 20.0), EPOCH, np.arange(7) * 600.0, "kepler")


def test_steps_are_named_columns_cut_by_a_slice_and_put_back_together(path):
    steps = step_inputs(path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup(), GasOptions()))
    assert len(steps) == 7 and steps.sun_body.shape == (7, 3) and steps.body_to_eci.shape == (7, 3, 3)
    assert np.allclose(np.linalg.norm(steps.sun_body, axis=1), 1.0)
    assert np.array_equal(steps.flux_W_m2, steps.sunlight_W_m2 * steps.solar_fraction)
    chunk = steps[2:5]
    assert len(chunk) == 3 and chunk.epoch == steps.epoch
    assert np.array_equal(chunk.velocity_body_m_s, steps.velocity_body_m_s[2:5])
    whole = StepInputs.concatenate([steps[:2], chunk, steps[5:]])
    for name in StepInputs.columns():
        assert np.array_equal(getattr(whole, name), getattr(steps, name), equal_nan=True), name
    with pytest.raises(TypeError, match="slice"):
        steps[3]
    with pytest.raises(InputError, match="rows"):
        replace(steps, height_km=steps.height_km[:3])


def test_steps_without_drag_have_no_geodetic_place(path):
    steps = step_inputs(path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup()))
    assert np.isnan(steps.altitude_km).all() and np.isfinite(steps.height_km).all()


def test_steps_pickle_for_dask_and_their_fingerprint_follows_every_column_and_the_epoch(path):
    steps = step_inputs(path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup()))
    back = pickle.loads(pickle.dumps(steps))
    assert inputs_digest(back) == inputs_digest(steps)
    assert inputs_digest(steps[1:]) != inputs_digest(steps)
    assert inputs_digest(replace(steps, flux_W_m2=steps.flux_W_m2 * 2)) != inputs_digest(steps)
    later = replace(steps, epoch=Epoch.of("2024-06-02T00:00:00Z"))
    assert inputs_digest(later) != inputs_digest(steps)


def test_a_run_in_chunks_of_one_step_gives_the_bits_of_one_chunk(model, path):
    loads = OrbitLoads(SrpSetup(reflections="none"))
    whole = fly(model, path, AttitudeLaw.parse("nadir"), loads)
    chunked = fly(model, path, AttitudeLaw.parse("nadir"), loads, run=SweepRun(chunk=1))
    for name in whole.names:
        assert np.array_equal(whole.series[name], chunked.series[name]), name


def test_the_flux_at_1_au_is_the_orbits_own_and_a_setups_flux_is_refused(model, path):
    law = AttitudeLaw.parse("nadir")
    base = fly(model, path, law, OrbitLoads(SrpSetup(reflections="none")))
    doubled = fly(model, path, law, OrbitLoads(SrpSetup(reflections="none"), flux_1au_W_m2=2722.0))
    assert doubled.flux_1au_W_m2 == 2722.0 and base.flux_1au_W_m2 == 1361.0
    assert np.allclose(doubled.series["srp_force_body_N"], 2 * base.series["srp_force_body_N"], rtol=1e-12)
    assert base.attributes["settings"]["flux_1au_W_m2"] == 1361.0
    with pytest.raises(InputError, match="flux_1au_W_m2") as error:
        OrbitLoads(SrpSetup(flux_W_m2=1000.0))
    assert error.value.parameters == ("flux_1au_W_m2",)


def test_precomputes_run_once_per_run(model, path, monkeypatch):
    made = []
    monkeypatch.setattr(OrbitLoads, "precompute", lambda self, model: made.append(self.kind))
    fly(
        model,
        path,
        AttitudeLaw.parse("nadir"),
        OrbitLoads(SrpSetup(reflections="none")),
        run=SweepRun(chunk=2),
    )
    assert made == ["orbit"]


def test_the_dataset_runs_vectors_along_component_with_udunits(model, path):
    result = fly(model, path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup(reflections="none")))
    table = result.to_dataset()
    assert "xyz" not in table.dims and table["force_body_N"].dims == ("time", "component")
    assert table["velocity_eci_m_s"].attrs["units"] == "m s-1"
    assert table["density_kg_m3"].attrs["units"] == "kg m-3"
    assert table["angular_impulse_body_Nms"].attrs["units"] == "N m s"


@pytest.mark.parametrize(
    "name",
    [
        "sunwind.forces.orbit",
        "sunwind.forces.orbit.inputs",
        "sunwind.forces.orbit.steps",
        "sunwind.forces.orbit.flight",
        "sunwind.forces.orbit.results",
        "sunwind.forces.tables.jobs",
        "sunwind.forces.tables.checkpoint",
        "sunwind.forces.tables.engine",
    ],
)
def test_the_examples_run(name):
    failed, tried = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert tried and not failed
