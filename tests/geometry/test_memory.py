"""The memory limit and the estimates checked against it (geometry.memory and its callers)."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from sunwind.forces.tables.attitudes import GRID_BYTES, direction_grid
from sunwind.forces.tables.engine import check_table_memory
from sunwind.geometry import memory, triangles
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays import shadows
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.views.view_factors import compute_view_factors
from sunwind.meshes import box, build, sample_spacecraft
from tests.helpers import MIXED


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("123", 123),
        ("4G", 4 * 2**30),
        ("500m", 500 * 2**20),
        ("1.5GiB", 3 * 2**29),
        (" 2k ", 2048),
        ("1e9", 10**9),
    ],
)
def test_sizes_parse_with_binary_suffixes(text, expected):
    assert memory.parse_size(text) == expected


@pytest.mark.parametrize("text", ["", "lots", "-1G", "0", "0.5", "4Q", "inf", "nan", "1e999"])
def test_a_malformed_size_is_an_input_error(text):
    with pytest.raises(InputError, match="is not a memory size"):
        memory.parse_size(text)


def test_limit_is_the_setting_else_the_available_memory(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "3M")
    assert memory.memory_limit() == (3 * 2**20, "SUNWIND_MAX_MEMORY=3M")
    monkeypatch.delenv(memory.LIMIT_VARIABLE)
    limit, source = memory.memory_limit()
    assert limit > 2**20 and source.startswith("available memory")


def test_a_container_limit_caps_the_available_memory(monkeypatch, tmp_path):
    """Under a cgroup limit, what is left of it counts, however much the machine has free."""
    limit, usage = tmp_path / "memory.max", tmp_path / "memory.current"
    limit.write_text("1073741824\n")
    usage.write_text("268435456\n")
    monkeypatch.setattr(memory, "CGROUP_FILES", ((str(limit), str(usage)),))
    assert memory.available_memory() == min(memory._system_available(), 3 * 2**28)
    limit.write_text("max\n")  # unlimited: the machine's own figure
    assert memory.available_memory() == pytest.approx(memory._system_available(), rel=0.05)


def test_require_names_estimate_limit_and_fix(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "1G")
    memory.require(2**30, "exactly the limit", "n/a")
    with pytest.raises(InputError) as error:
        memory.require(22.4 * 2**30, "1e+09 points", "lower samples", ("samples",))
    message = str(error.value.renamed({"samples": "--samples"}))
    assert message == (
        "not enough memory: needs ~22.4 GiB for 1e+09 points; limit 1 GiB (SUNWIND_MAX_MEMORY=1G); "
        "lower --samples"
    )
    with pytest.raises(InputError, match="needs more than 1e308 B for ~1e\\+400"):
        memory.require(10**400, memory.count(10**400), "less")


def test_shadow_sampling_is_sized_before_allocating(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "10M")
    craft = build_spacecraft(box(), uniform=MIXED)
    sampler = side_sampler(craft)
    with pytest.raises(InputError, match=r"1e\+09 points per side x 12 sides"):
        sampler.illuminate(np.array([1.0, 0.0, 0.0]), samples=10**9)
    with pytest.raises(InputError, match="points per side"):  # the drag path asks for origins first
        sampler.facing_rays(np.array([1.0, 0.0, 0.0]), 2**15)
    assert sampler.illuminate(np.array([1.0, 0.0, 0.0]), samples=16).rays == 2 * 16


def test_view_rays_are_sized_before_allocating(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "1M")
    craft = build_spacecraft(box(), uniform=MIXED)
    with pytest.raises(InputError, match="view-factor rays per side x 12 sides"):
        compute_view_factors(craft, 65536)  # the most rays accepted, past a limit of 1 MiB


def test_grid_and_table_are_sized_before_allocating(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "10M")
    with pytest.raises(InputError, match=r"6.48e\+10 grid nodes.*raise step_deg"):
        direction_grid(0.001)
    grid = direction_grid(1.0)  # 65 341 nodes: 8.5 MB of grid, but ~55 MB of table for both kinds
    assert grid.nodes == 361 * 181
    with pytest.raises(InputError, match=r"a table of 6\.53e"):
        check_table_memory(grid, ("srp", "drag"))


@pytest.mark.parametrize(
    ("kind", "params", "fix"),
    [
        ("sphere", {"subdivisions": 100_000}, "lower subdivisions"),
        ("plate", {"divisions": 10**20}, "lower divisions"),
        ("box", {"divisions": (1, 1, 10**7)}, "lower divisions"),
        ("cylinder", {"segments": 10**8}, "lower segments or rings"),
        ("cone", {"rings": 10**9}, "lower segments or rings"),
        ("dish", {"segments": 10**9}, "lower segments"),
        ("box_wing", {"facet_size": 1e-6}, "raise facet_size"),
    ],
)
def test_mesh_resolutions_are_sized_before_allocating(kind, params, fix, monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "10M")
    with pytest.raises(InputError, match=fix):
        build(kind, **params)


def test_sample_triangles_are_sized(monkeypatch):
    monkeypatch.setenv(memory.LIMIT_VARIABLE, "10M")
    with pytest.raises(InputError, match="lower triangles"):
        sample_spacecraft(10**7)


def _peak_bytes(make) -> int:
    tracemalloc.start()
    try:
        make()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_estimates_match_measured_peaks():
    """The per-point and per-node constants are the measured peaks, not guesses (within 2x, not under)."""
    triangles.subdivision_barycentric.cache_clear()
    level = 150
    per_point = _peak_bytes(lambda: triangles.subdivision_barycentric(level)) / level**2
    assert per_point <= shadows._BARYCENTRIC_BYTES <= 2 * per_point
    grid = direction_grid(2.0)
    per_node = _peak_bytes(lambda: grid.distinct) / grid.nodes
    assert per_node <= GRID_BYTES <= 2 * per_node
