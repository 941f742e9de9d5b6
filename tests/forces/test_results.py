"""Every result shares one base and one vocabulary: the same JSON keys and ``to_dataset()`` for SRP,
drag and the planet's radiation, one name (``component``) for the vector dimension, batches that give
every per-attitude field, and nothing computed on attribute access that the call did not ask for."""

import types
from dataclasses import replace

import numpy as np
import pytest

import sunwind as sw
from helpers import MIXED
from sunwind.forces.gas import explicit
from sunwind.forces.vocabulary import COMPONENT, units_of
from sunwind.meshes import primitives


@pytest.fixture(scope="module")
def box_wing():
    return sw.load(primitives.box_wing(facet_size=0.5), uniform=replace(MIXED, emissivity=0.8), threads=1)


@pytest.fixture(scope="module")
def air():
    return explicit(density_kg_m3=1e-12, temperature_K=1000.0, composition={"O": 1.0})


def test_the_public_namespace_is_the_users_vocabulary_and_every_name_resolves():
    assert dir(sw) == sorted([*sw.__all__, "__version__"])
    for name in sw.__all__:
        assert getattr(sw, name) is not None, name
    leaked = [
        name
        for name, value in vars(sw).items()
        if not name.startswith("_") and name not in sw.__all__ and not isinstance(value, types.ModuleType)
    ]
    assert leaked == [], leaked  # the public names, dunders and subpackages once imported, nothing else
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        sw.nothing  # noqa: B018


def test_k_is_is_not_computed_when_the_reflections_asked_for_need_no_view_factors(box_wing):
    """``reflections="none"`` builds no view factors, neither for ``k_is`` nor for the JSON report."""
    box_wing.cache.clear()
    result = sw.srp(box_wing, [0.3, -0.5, 0.8], reflections="none")
    assert result.k_is is None and result.to_json()["k_is"] is None
    assert not any("view" in str(entry) for entry in box_wing.cache.entries())
    full = sw.srp(box_wing, [0.3, -0.5, 0.8], reflections="full")
    assert full.k_is > 0  # the wings see the bus


def test_srp_and_drag_share_their_json_keys_and_dataset_variables(box_wing, air):
    light = sw.srp(box_wing, [0.3, -0.5, 0.8], reflections="none")
    gas = sw.drag(box_wing, [7500.0, 500.0, -300.0], air, reflections="none")
    shared = set(light.to_json()) & set(gas.to_json())
    base = {"frame", "force_N", "torque_Nm", "reference_point_m", "reference_point", "error_estimate"}
    assert base | {"azimuth_deg", "elevation_deg", "direct", "reflected", "k_is"} <= shared
    for result in (light, gas):
        az, el = result.azel_deg
        assert result.to_json()["azimuth_deg"] == az and result.to_json()["elevation_deg"] == el
        table = result.to_dataset()
        assert table["force_N"].dims == (COMPONENT,) and list(table[COMPONENT].values) == ["x", "y", "z"]
        for name in result.VARIABLES:
            value = getattr(result, name)
            expected = np.nan if value is None else value
            np.testing.assert_array_equal(table[name].values, expected)
            assert table[name].attrs["units"] == units_of(name), name
        assert table.attrs["frame"] == "body frame of the mesh"
        assert table.attrs["reference_point"] == result.reference_point


def test_a_batch_gives_every_per_attitude_field_and_its_dataset_runs_along_attitude(box_wing, air):
    velocities = np.array([[7500.0, 0.0, 0.0], [0.0, 7500.0, 100.0], [5000.0, -5000.0, 0.0]])
    batch = sw.drag(box_wing, velocities, air, reflections="none")
    for name in (*batch[0].VARIABLES, "azel_deg", "force_coefficients", "flow_direction"):
        stacked = getattr(batch, name)
        for k, result in enumerate(batch):
            value = getattr(result, name)
            np.testing.assert_array_equal(stacked[k], np.nan if value is None else value)
    assert batch.CD.shape == (3,) and batch.CM.shape == (3, 3)
    table = batch.to_dataset()
    assert dict(table.sizes) == {"attitude": 3, COMPONENT: 3}
    np.testing.assert_array_equal(table["CD"].values, batch.CD)
    np.testing.assert_array_equal(table["azimuth_deg"].values, batch.azel_deg[:, 0])
    with pytest.raises(AttributeError, match="no attribute 'to_csv'"):
        batch.to_csv  # noqa: B018


def test_the_planets_radiation_is_a_result_like_the_others(box_wing):
    place = sw.Place(nadir=np.array([0.0, 0.0, 1.0]), altitude_km=500.0, sun_vector=np.array([1.0, 0.0, 0.0]))
    result = sw.planet_radiation(box_wing, place, reflections="none")
    assert isinstance(result, sw.Result)
    np.testing.assert_array_equal(result.force_N, result.albedo_force_N + result.infrared_force_N)
    document = result.to_json()
    assert document["force_N"] == result.force_N.tolist() and document["frame"] == "body frame of the mesh"
    table = result.to_dataset()
    assert table["infrared_force_N"].dims == (COMPONENT,) and table.attrs["kind"] == "planet radiation"


def test_a_mesh_in_memory_loads_as_a_model_without_a_source_and_refuses_a_file_unit():
    """``sw.load`` takes a mesh of ``sw.meshes``: the same model as the one built from its triangles, with
    no file to go to Dask workers; ``unit`` (a file's length unit) is refused, not ignored."""
    cube = sw.load(primitives.box((1.0, 2.0, 3.0)), uniform=MIXED, threads=1)
    assert cube.source is None and cube.craft.n_facets == 12
    assert cube.craft.total_area == pytest.approx(2 * (2.0 + 3.0 + 6.0), rel=1e-12)
    with pytest.raises(sw.SunwindError, match="unit is the length unit of a mesh file"):
        sw.load(primitives.box(), uniform=MIXED, unit="mm")


def test_the_validation_runner_refuses_an_unknown_family_in_one_line(capsys):
    from sunwind.validation.runner import main, run

    with pytest.raises(sw.SunwindError, match="no validation family is called 'drag'"):
        run(quick=True, families=["drag"])
    with pytest.raises(SystemExit) as stop:
        main(["--family", "drag"])
    assert stop.value.code == 2 and "invalid choice: 'drag'" in capsys.readouterr().err
