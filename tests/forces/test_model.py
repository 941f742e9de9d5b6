"""A loaded model: how it was loaded, its references and threads, and what load refuses."""

import numpy as np
import pytest

from helpers import REPO
from sunwind.forces import Model, ModelSource, drag, explicit, load, srp
from sunwind.geometry.errors import InputError, MaterialError
from sunwind.geometry.materials import Material

SAMPLE = "meshes/data/sample_spacecraft"


@pytest.fixture(scope="module")
def sample():
    return load(REPO / f"{SAMPLE}.obj", REPO / f"{SAMPLE}.toml")


def test_load_keeps_the_source_and_the_source_loads_the_same_model(sample):
    assert isinstance(sample, Model) and sample.source.mesh.endswith("sample_spacecraft.obj")
    again = sample.source.load()
    assert np.array_equal(again.triangles, sample.craft.triangles)
    assert sample.cache is sample.craft.cache
    assert set(sample.digests()) == {"mesh_sha256", "materials_sha256"}
    assert ModelSource.from_attributes(sample.source.attributes()) == sample.source


def test_gas_overrides_set_every_material_and_unknown_keys_are_refused(sample):
    model = load(sample.source.mesh, sample.source.materials, gas={"gsi": "cll", "wall_temperature": 500.0})
    codes = set(model.craft.side_gas["code"].tolist())
    assert codes == {3} and set(model.craft.side_gas["wall_temperature_K"].tolist()) == {500.0}
    with pytest.raises(InputError, match="gas has no key 'T_w'"):
        load(sample.source.mesh, gas={"T_w": 300.0})
    with pytest.raises(MaterialError, match="gsi"):
        ModelSource(sample.source.mesh, gas=(("gsi", "lambert"),))


def test_coefficient_references_of_the_model_apply_and_are_checked(sample):
    air = explicit(3e-12, 900.0, "O:1")
    plain = drag(sample, [7600.0, 0, 0], air, samples=1, reflections="none")
    model = Model(sample.craft, reference_area_m2=2.0, reference_length_m=3.0)
    scaled = drag(model, [7600.0, 0, 0], air, samples=1, reflections="none")
    assert scaled.reference_area_m2 == 2.0 and scaled.reference_length_m == 3.0
    np.testing.assert_allclose(scaled.CD * 2.0, plain.CD * plain.reference_area_m2, rtol=1e-12)
    for bad in ({"reference_area_m2": 0.0}, {"reference_length_m": -1.0}, {"reference_area_m2": np.nan}):
        with pytest.raises(InputError, match="must be a positive number"):
            Model(sample.craft, **bad)
    with pytest.raises(InputError, match="reference_point_m"):
        Model(sample.craft, reference_point_m=[0, 0])


def test_a_model_is_what_srp_and_drag_take_and_anything_else_is_refused(sample):
    with pytest.raises(InputError, match="model must be a Model"):
        srp("craft.obj", [1, 0, 0])
    uniform = load(sample.source.mesh, sample.source.materials, uniform=Material("grey", 0.2, 0.1))
    assert uniform.source.uniform.name == "grey"
