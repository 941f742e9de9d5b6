"""The model's cache: what is built once is kept, listed with its size, cleared, and not shared."""

import pickle
from dataclasses import replace

import numpy as np
import pytest
import trimesh

from helpers import ABSORBER, mesh_from_trimesh
from sunwind.forces.reflection import ReflectionSettings, reflection_plan
from sunwind.forces.srp import srp
from sunwind.geometry.cache import ModelCache
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft


@pytest.fixture
def craft():
    return build_spacecraft(mesh_from_trimesh(trimesh.creation.box((1.0, 2.0, 0.5))), uniform=ABSORBER)


def test_a_value_is_built_once_and_kept_under_its_key():
    cache, calls = ModelCache(), []

    def build():
        calls.append(1)
        return np.ones(10)

    first = cache.get(("thing", 1), build)
    assert cache.get(("thing", 1), build) is first and len(calls) == 1
    assert ("thing", 1) in cache and len(cache) == 1
    (entry,) = cache.entries()
    assert entry.key == ("thing", 1) and entry.kind == "ndarray" and entry.nbytes == 80
    assert cache.nbytes == 80 and "('thing', 1): ndarray" in repr(cache)


def test_clear_drops_every_value_or_those_of_one_name():
    cache = ModelCache()
    cache.get(("a", 1), lambda: 1)
    cache.get(("a", 2), lambda: 2)
    cache.get("b", lambda: 3)
    cache.clear("a")
    assert list(cache) == ["b"]
    cache.clear()
    assert len(cache) == 0


def test_an_attitude_fills_the_model_cache_with_what_it_reuses(craft):
    assert len(craft.cache) == 0
    srp(craft, [0.3, 0.2, 1.0], sampling=ShadowSampling(samples=4), reflections="full")
    names = {key if isinstance(key, str) else key[0] for key in craft.cache}
    assert {"ray scene", "side sampler", "block moments", "view factors", "reflection plan"} <= names
    sampler = next(e for e in craft.cache.entries() if e.key == "side sampler")
    assert sampler.nbytes > 0  # the kept ray origins are counted, the model itself is not
    assert sampler.nbytes < 100 * craft.n_sides * 16 * 3 * 4
    before = srp(craft, [0.3, 0.2, 1.0], sampling=ShadowSampling(samples=4), reflections="full")
    craft.cache.clear()
    after = srp(craft, [0.3, 0.2, 1.0], sampling=ShadowSampling(samples=4), reflections="full")
    assert np.array_equal(before.force_N, after.force_N)  # rebuilt, the same bits


def test_a_model_made_from_another_and_a_pickled_model_start_with_an_empty_cache(craft):
    plan = reflection_plan(craft, ReflectionSettings("none"))
    assert len(craft.cache) == 1
    other = replace(craft, materials=craft.materials.with_gas(wall_temperature_K=500.0))
    assert other.cache is not craft.cache and len(other.cache) == 0
    copy = pickle.loads(pickle.dumps(craft))
    assert len(copy.cache) == 0 and np.array_equal(copy.triangles, craft.triangles)
    assert reflection_plan(craft, ReflectionSettings("none")) is plan
