"""A loaded model: how it was loaded, its references and threads, its hinges, and what load refuses."""

import json
import math

import numpy as np
import pytest

from helpers import REPO, quad_sheet
from sunwind.forces import Model, ModelSource, drag, explicit, load, srp
from sunwind.geometry.errors import InputError, MaterialError
from sunwind.geometry.io.obj import write_obj
from sunwind.geometry.materials import Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.rays.sampling import ShadowSampling

SAMPLE = "meshes/data/sample_spacecraft"


@pytest.fixture(scope="module")
def sample():
    return load(REPO / f"{SAMPLE}.obj", REPO / f"{SAMPLE}.toml")


def test_load_keeps_the_source_and_the_source_loads_the_same_model(sample):
    assert isinstance(sample, Model) and sample.source.mesh.endswith("sample_spacecraft.obj")
    again = sample.source.spacecraft()
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
    plain = drag(sample, [7600.0, 0, 0], air, sampling=ShadowSampling(samples=1), reflections="none")
    model = Model(sample.craft, reference_area_m2=2.0, reference_length_m=3.0)
    scaled = drag(model, [7600.0, 0, 0], air, sampling=ShadowSampling(samples=1), reflections="none")
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


# ----------------------------------------------------------------------------------- articulated parts
HINGES = """
[materials.mirror]
reflectivity = 1.0
specular_fraction = 1.0
[parts]
"wing_*" = { front = "mirror" }
[articulation.wing_p]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
track = "sun"
[articulation.wing_n]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
schedule = [[0, 0], [100, 50]]
"""


@pytest.fixture(scope="module")
def hinged(tmp_path_factory):
    """Two wings facing +x at y = +-2 on a tracking hinge (wing_p) and a scheduled one (wing_n), from
    files."""
    folder = tmp_path_factory.mktemp("hinged")
    corners = np.array([[0, 1, -0.5], [0, 3, -0.5], [0, 3, 0.5], [0, 1, 0.5]])  # front +x
    wings = [quad_sheet(corners, "wing_p", 2), quad_sheet(corners * [1, -1, -1], "wing_n", 2)]
    write_obj(MeshData.concatenate(wings), folder / "wings.obj")
    (folder / "wings.toml").write_text(HINGES)
    return load(folder / "wings.obj", folder / "wings.toml", reference_point_m=[0, 0, 0])


def test_the_angles_of_every_law_and_what_each_law_needs(hinged):
    assert [h.law for h in hinged.hinges] == ["track", "schedule"]
    assert hinged.craft.articulation == {"wing_p": 0.0, "wing_n": 0.0}  # loaded as drawn
    angles = hinged.angles_at(sun_body=[1.0, 0.0, -1.0], time_s=25.0)
    assert angles == {"wing_p": pytest.approx(45.0, abs=1e-12), "wing_n": 12.5}
    with pytest.raises(InputError, match='hinge "wing_p" tracks the Sun: its angle needs sun_body'):
        hinged.angles_at(time_s=0.0)
    with pytest.raises(InputError, match='hinge "wing_n" follows a schedule: its angle needs time_s'):
        hinged.angles_at(sun_body=[1, 0, 0])


def test_a_posed_model_keeps_its_references_has_its_own_cache_and_is_kept(hinged):
    posed = hinged.posed({"wing_p": 30.0, "wing_n": -30.0})
    assert posed.craft.articulation == {"wing_p": 30.0, "wing_n": -30.0}
    assert posed.craft.cache is not hinged.craft.cache and not len(posed.cache)
    assert posed.reference_point_m.tolist() == [0, 0, 0] and posed.threads == hinged.threads
    srp(posed, [1, 0, 0], reflections="none")
    assert len(posed.cache)
    again = hinged.posed({"wing_p": 30.0 + 1e-11, "wing_n": -30.0})  # within 1e-9 deg: the same pose
    assert again.craft is posed.craft and len(again.cache)
    assert hinged.posed({"wing_p": 31.0}).craft.articulation == {"wing_p": 31.0, "wing_n": 0.0}
    assert hinged.posed({}) is hinged and hinged.posed({"wing_n": 0.0}) is hinged
    for angle in range(20):  # the oldest poses go
        hinged.posed({"wing_p": float(angle)})
    assert hinged.posed({"wing_p": 30.0, "wing_n": -30.0}).craft is not posed.craft
    with pytest.raises(InputError, match='angles name "dish", which is no hinge'):
        hinged.posed({"dish": 1.0})
    plain = load(REPO / f"{SAMPLE}.obj", REPO / f"{SAMPLE}.toml")
    assert plain.posed({}) is plain and plain.hinges == ()


def test_the_source_of_a_posed_model_loads_it_again_bit_for_bit_and_records_its_angles(hinged):
    posed = hinged.posed(hinged.angles_at([0.3, -0.2, 0.9], time_s=70.0))
    source = posed.source
    assert dict(source.articulate) == posed.craft.articulation
    assert ModelSource.from_attributes(source.attributes()) == source
    assert np.array_equal(source.spacecraft().vertices, posed.craft.vertices)
    assert json.loads(posed.digests()["articulation_deg"]) == posed.craft.articulation
    held = load(source.mesh, source.materials, articulate={"wing_p": 12.0})
    assert [h.law for h in held.hinges] == ["fixed", "schedule"] and held.craft.articulation["wing_p"] == 12.0
    with pytest.raises(InputError, match=r'articulate "wing_\*" names no hinge'):
        load(source.mesh, source.materials, articulate={"wing_*": 1.0})
    with pytest.raises(InputError, match='articulate "wing_p" angle inf must be a finite number'):
        load(source.mesh, source.materials, articulate={"wing_p": math.inf})
