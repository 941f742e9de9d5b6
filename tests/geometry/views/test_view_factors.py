"""View factors and escape vectors: closed forms, conservation, reciprocity, determinism and the disk cache.

Sampling tolerances are about four standard deviations of the sampling noise, measured over seeds.
"""

from dataclasses import replace

import numpy as np
import pytest
import trimesh

import sunwind.geometry.views.hemisphere as hemisphere
import sunwind.geometry.views.view_factors as vf_module
from helpers import ABSORBER, mesh_from_trimesh, quad_sheet
from helpers.shapes import parallel_squares
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.triangles import normals
from sunwind.geometry.views.disk_cache import CacheWarning, geometry_key, write_entry
from sunwind.geometry.views.near_field import edge_pair_view_factors
from sunwind.geometry.views.view_factors import (
    VIEW_SEED,
    compute_view_factors,
    default_rays_per_side,
    resolve_rays_per_side,
    view_factors,
)
from sunwind.meshes.primitives import box, dish

UNIT_FLOOR = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)  # z = 0, front +z
UNIT_WALL = np.array([[0, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1]], float)  # x = 0, front +x
UNIT_CEILING = np.array([[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]], float)  # z = 1, front -z


def hottel_perpendicular(w: float, h: float) -> float:
    """View factor from a w x 1 rectangle to an h x 1 rectangle at 90 degrees sharing the edge of length 1
    (Hottel; Incropera, Fundamentals of Heat and Mass Transfer, Table 13.2)."""
    s = w * w + h * h
    log = np.log(
        (1 + w * w)
        * (1 + h * h)
        / (1 + s)
        * (w * w * (1 + s) / ((1 + w * w) * s)) ** (w * w)
        * (h * h * (1 + s) / ((1 + h * h) * s)) ** (h * h)
    )
    arctans = w * np.arctan(1 / w) + h * np.arctan(1 / h) - np.sqrt(s) * np.arctan(1 / np.sqrt(s))
    return float((arctans + log / 4) / (np.pi * w))


def sheets(*meshes: MeshData, two_sided: bool = False, reflectivity: float = 0.0):
    """A model of sheets of one diffuse material, one- or two-sided, one part per mesh."""
    side = {"front": "paint", "back": "paint"} if two_sided else {"front": "paint"}
    spec = parse_materials(
        {
            "materials": {"paint": {"reflectivity": reflectivity, "specular_fraction": 0}},
            "parts": {mesh.part_names[0]: side for mesh in meshes},
        }
    )
    return build_spacecraft(MeshData.concatenate(meshes), spec)


def corner(n: int, reflectivity: float = 0.0):
    """A one-sided unit floor and unit wall at 90 degrees sharing an edge, each 2 n^2 triangles."""
    walls = quad_sheet(UNIT_FLOOR, "floor", n), quad_sheet(UNIT_WALL, "wall", n)
    return sheets(*walls, reflectivity=reflectivity)


def plate_factor(craft, view, source: str, target: str) -> float:
    """Area-weighted view factor from part ``source`` to part ``target``."""
    part = craft.facet_part[craft.side_facet]
    a = part == craft.part_names.index(source)
    b = part == craft.part_names.index(target)
    areas = craft.side_areas[a]
    return float(areas @ view.matrix[a][:, b].toarray().sum(axis=1) / areas.sum())


# ------------------------------------------------------------------------------------------- sampling


@pytest.mark.parametrize(
    "mesh", [mesh_from_trimesh(trimesh.creation.icosphere(2)), box((1.0, 2.0, 0.5), 3)], ids=["sphere", "box"]
)
def test_a_convex_body_sees_only_sky_exactly(mesh):
    craft = build_spacecraft(mesh, uniform=ABSORBER)  # the box's faces have coplanar neighbours
    view = compute_view_factors(craft, 64)
    assert view.matrix.nnz == 0
    assert np.array_equal(view.escape_fraction, np.ones(craft.n_sides))
    assert np.array_equal(view.escape_vector, (2 / 3) * craft.side_normals)
    assert np.array_equal(view.escape_moment, np.zeros((craft.n_sides, 3)))
    assert np.array_equal(view.blind_fraction, np.zeros(craft.n_sides))
    assert view.origin == "computed" and view.rays_per_side == 64


def test_a_closed_cavity_lets_nothing_escape():
    # a box of one-sided sheets facing in: every ray from an inner side meets another inner side
    cube = box((1.0, 1.0, 1.0), 2)
    craft = sheets(replace(cube, faces=cube.faces[:, ::-1]))
    view = compute_view_factors(craft, 1024)
    assert np.array_equal(view.escape_fraction, np.zeros(craft.n_sides))
    assert np.array_equal(view.blind_fraction, np.zeros(craft.n_sides))
    assert view.row_sum_error().max() < 1e-12


# noise (RMS over 40 seeds) of F and of F12 - F21: 0.9e-3 and 1.5e-3 for n = 1 at 16384 rays; 2.7e-4 and
# 4.2e-4 for n = 8 at 1024 rays
@pytest.mark.parametrize(
    "n, rays, tolerance, reciprocity", [(1, 16384, 4e-3, 6e-3), (8, 1024, 1.1e-3, 1.7e-3)]
)
def test_perpendicular_squares_match_hottel_and_are_reciprocal(n, rays, tolerance, reciprocity):
    craft = corner(n)
    view = compute_view_factors(craft, rays)
    exact = hottel_perpendicular(1.0, 1.0)
    assert exact == pytest.approx(0.20004, abs=1e-5)
    floor_to_wall = plate_factor(craft, view, "floor", "wall")
    wall_to_floor = plate_factor(craft, view, "wall", "floor")
    assert abs(floor_to_wall - exact) < tolerance
    assert abs(floor_to_wall - wall_to_floor) < reciprocity  # equal areas: A1 F12 = A2 F21
    assert view.row_sum_error().max() < 1e-12


def test_light_reaching_the_back_of_a_one_sided_sheet_is_blind():
    turned = quad_sheet(UNIT_WALL[::-1], "wall", 4)  # the wall's only side faces away from the floor
    craft = sheets(quad_sheet(UNIT_FLOOR, "floor", 4), turned)
    view = compute_view_factors(craft, 1024)
    floor = craft.facet_part[craft.side_facet] == craft.part_names.index("floor")
    areas = craft.side_areas[floor]
    blind = areas @ view.blind_fraction[floor] / areas.sum()
    assert blind == pytest.approx(hottel_perpendicular(1.0, 1.0), abs=3e-3)  # noise ~7e-4, as for F
    assert view.matrix.nnz == 0 and view.row_sum_error().max() < 1e-12


def test_the_near_field_rule_cuts_the_error_of_a_coarse_mesh():
    craft = corner(1)  # 2 triangles per plate
    exact = hottel_perpendicular(1.0, 1.0)

    def rms_error(near_field: bool) -> float:
        views = [compute_view_factors(craft, 256, seed, near_field=near_field) for seed in range(64)]
        errors = [plate_factor(craft, view, "floor", "wall") - exact for view in views]
        return float(np.sqrt(np.mean(np.square(errors))))

    # measured 8.8e-3 with, 1.14e-2 without: the pair sharing the edge carries half of F here (now
    # integrated); the three pairs sharing only a corner stay sampled
    assert rms_error(True) < 0.9 * rms_error(False)


def test_the_near_field_quadrature_sums_to_hottel_over_the_four_triangle_pairs():
    # the coarse corner's triangles all share the origin; the rule is graded toward edge AB and its ends,
    # so each floor triangle is given as (A, B, C) with A at the origin and, where it has one, AB the
    # edge it shares with the wall (x = 0, z = 0)
    a, b, c, d = UNIT_FLOOR
    floors = [np.array([a, b, c]), np.array([a, d, c])]
    walls = [UNIT_WALL[[0, 1, 2]], UNIT_WALL[[0, 2, 3]]]
    emitters = np.array([f for f in floors for _ in walls])
    receivers = np.array([w for _ in floors for w in walls])
    up = np.tile([0.0, 0.0, 1.0], (4, 1))
    factors = edge_pair_view_factors(emitters, up, receivers)
    assert factors.sum() * 0.5 == pytest.approx(hottel_perpendicular(1.0, 1.0), abs=2e-6)
    # reciprocity of the rule on the pair sharing the edge: the same A F integrated over either triangle
    backward = edge_pair_view_factors(walls[0][None], np.array([[1.0, 0.0, 0.0]]), floors[1][None])[0]
    assert factors[2] == pytest.approx(backward, rel=2e-6)


def test_parallel_squares_match_the_closed_form():
    # 32 triangles per square, 1024 rays: noise 7.6e-4 (RMS over 40 seeds)
    craft = sheets(quad_sheet(UNIT_FLOOR, "floor", 4), quad_sheet(UNIT_CEILING, "ceiling", 4))
    view = compute_view_factors(craft, 1024)
    exact = parallel_squares(1.0)
    assert exact == pytest.approx(0.1998, abs=1e-4)
    assert abs(plate_factor(craft, view, "floor", "ceiling") - exact) < 3e-3
    assert abs(plate_factor(craft, view, "ceiling", "floor") - exact) < 3e-3


def open_box():
    """A two-sided unit box without its top: 10 triangles, 20 sides."""
    cube = box((1.0, 1.0, 1.0), 1)
    keep = normals(cube.vertices[cube.faces])[:, 2] < 0.5
    topless = replace(
        cube, faces=cube.faces[keep], face_part=cube.face_part[keep], face_material=cube.face_material[keep]
    )
    return sheets(topless, two_sided=True)


@pytest.mark.parametrize(
    "build, tolerance",
    # the pairwise reciprocity error is noise, ~1/sqrt(rays): over 20 seeds 0.014 +- 0.002 (open box),
    # 0.055 +- 0.006 (dish)
    [(open_box, 0.04), (lambda: sheets(dish(1.2, 0.35, segments=6), two_sided=True), 0.12)],
    ids=["open box", "dish"],
)
def test_rows_sum_to_one_and_exchange_is_reciprocal(build, tolerance):
    craft = build()
    view = compute_view_factors(craft, 16384)
    assert view.row_sum_error().max() < 1e-12
    assert view.matrix.nnz > 0
    assert view.reciprocity_error(craft.side_areas) < tolerance
    assert np.all(view.escape_fraction >= 0) and np.all(view.matrix.data > 0)


def escape_reference(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Escape vector and moment of a triangle of the unit floor beside the unit wall x = 0, by quadrature.

    Points: 12 x 12 Gauss-Legendre over the triangle (Duffy map). Directions: midpoint rule in
    ``(sin^2 theta, phi)``, where the cosine-weighted measure is uniform; a direction is blocked when it
    crosses x = 0 within the wall. Error 2.3e-4 (vector), 4e-5 (moment), against 30 x 30 points and
    400 x 800 directions.
    """
    x, w = np.polynomial.legendre.leggauss(12)
    x, w = (x + 1) / 2, w / 2
    s, t = np.meshgrid(x, x, indexing="ij")
    weights = (np.outer(w, w) * 2 * s).ravel()  # sums to 1: the area average
    b1, b2 = (s * (1 - t)).ravel(), (s * t).ravel()
    points = corners[0] + b1[:, None] * (corners[1] - corners[0]) + b2[:, None] * (corners[2] - corners[0])
    q, phi = np.meshgrid((np.arange(100) + 0.5) / 100, (np.arange(200) + 0.5) * np.pi / 100, indexing="ij")
    d = np.stack([np.sqrt(q) * np.cos(phi), np.sqrt(q) * np.sin(phi), np.sqrt(1 - q)], -1).reshape(-1, 3)
    vector, moment = np.zeros(3), np.zeros(3)
    for p, weight in zip(points, weights, strict=True):
        with np.errstate(divide="ignore", invalid="ignore"):
            distance = -p[0] / d[:, 0]
            y, z = p[1] + distance * d[:, 1], distance * d[:, 2]
        sky = d[~((d[:, 0] < 0) & (y >= 0) & (y <= 1) & (z <= 1))]
        vector += weight * sky.sum(axis=0) / len(d)
        moment += weight * np.cross(p - corners.mean(axis=0), sky).sum(axis=0) / len(d)
    return vector, moment


def test_escape_vector_and_moment_of_a_side_of_an_l_match_quadrature():
    # 16384 rays: noise up to 1.3e-3 on the vector, 5.6e-4 on the moment (standard deviation over 20 seeds)
    craft = corner(1)
    view = compute_view_factors(craft, 16384)
    for side in range(2):  # the two floor triangles; one shares the edge with the wall
        vector, moment = escape_reference(craft.triangles[craft.side_facet[side]])
        assert np.abs(view.escape_vector[side] - vector).max() < 5e-3
        assert np.abs(view.escape_moment[side] - moment).max() < 2.5e-3
        assert np.linalg.norm(vector - (2 / 3) * craft.side_normals[side]) > 0.05  # the wall matters


def test_results_are_the_same_bits_whatever_the_threads_and_batches(monkeypatch, limit_threads):
    craft = sheets(dish(1.2, 0.35, segments=12), two_sided=True)
    runs = []  # 8 or 3 sides per batch: many batches, and chunks of work for each thread
    for threads, batch in (("1", 256 * 8), ("2", 256 * 8), ("2", 256 * 3)):
        limit_threads(int(threads))
        monkeypatch.setattr(hemisphere, "_BATCH_RAYS", batch)
        runs.append(compute_view_factors(craft, 256))
    first = runs[0]
    for other in runs[1:]:
        for name in ("data", "indices", "indptr"):
            assert np.array_equal(getattr(first.matrix, name), getattr(other.matrix, name))
        for name in ("escape_fraction", "escape_vector", "escape_moment", "blind_fraction"):
            assert np.array_equal(getattr(first, name), getattr(other, name))
    assert first.matrix.nnz > 0


@pytest.mark.parametrize(
    "n_sides, rays", [(1, 16384), (1000, 16384), (5000, 3249), (138654, 256), (10**7, 256)]
)
def test_default_rays_per_side(n_sides, rays):
    assert default_rays_per_side(n_sides) == rays


def test_rays_per_side_round_up_to_squares_and_must_be_positive():
    assert [resolve_rays_per_side(r, 10) for r in (1, 2, 9, 10, None)] == [1, 4, 9, 16, 16384]
    for bad in (0, -4, 2.5, True):
        with pytest.raises(ValueError, match="rays_per_side"):
            resolve_rays_per_side(bad, 10)
    with pytest.raises(ValueError, match="seed"):
        compute_view_factors(corner(1), 16, seed=-1)


# ---------------------------------------------------------------------------------------------- cache


def entries(directory) -> list:
    return sorted(directory.glob("*.npz"))


def assert_same(a, b) -> None:
    assert (a.matrix != b.matrix).nnz == 0
    for name in ("escape_fraction", "escape_vector", "escape_moment", "blind_fraction"):
        assert np.array_equal(getattr(a, name), getattr(b, name))
    assert (a.rays_per_side, a.seed) == (b.rays_per_side, b.seed)


def test_a_second_call_reads_the_cache(tmp_path):
    craft = corner(2)
    first = view_factors(craft, 64, cache_dir=tmp_path)
    [path] = entries(tmp_path)
    assert first.origin == f"computed (stored in cache {path})"
    second = view_factors(craft, 64, cache_dir=tmp_path)
    assert second.origin == f"cache {path}"
    assert second.seconds == first.seconds
    assert_same(first, second)
    assert_same(first, compute_view_factors(craft, 64))


def test_the_key_follows_geometry_and_settings_not_materials(tmp_path):
    craft = corner(2)
    view_factors(craft, 64, cache_dir=tmp_path)
    view_factors(craft, 100, cache_dir=tmp_path)  # rounded up to 121 rays: another entry
    view_factors(craft, 64, seed=VIEW_SEED + 1, cache_dir=tmp_path)
    assert len(entries(tmp_path)) == 3
    assert view_factors(corner(2, reflectivity=0.7), 64, cache_dir=tmp_path).origin.startswith("cache ")
    moved = sheets(quad_sheet(UNIT_FLOOR + 0.5, "floor", 2), quad_sheet(UNIT_WALL, "wall", 2))
    settings = vf_module._settings(64, VIEW_SEED)
    assert geometry_key(moved, settings) != geometry_key(craft, settings)


@pytest.mark.parametrize(
    "damage",
    [lambda b: b[: len(b) // 2], lambda b: b"not a zip file at all", lambda b: b[:100] + bytes(50) + b[150:]],
    ids=["truncated", "garbage", "overwritten"],
)
def test_a_corrupt_entry_is_reported_and_rebuilt(tmp_path, damage):
    craft = corner(2)
    fresh = view_factors(craft, 64, cache_dir=tmp_path)
    [path] = entries(tmp_path)
    path.write_bytes(damage(path.read_bytes()))
    with pytest.warns(CacheWarning, match="was corrupt"):
        rebuilt = view_factors(craft, 64, cache_dir=tmp_path)
    assert rebuilt.origin.startswith(f"computed (cache entry {path} was corrupt (")
    assert "rebuilt" in rebuilt.origin
    assert_same(fresh, rebuilt)
    assert view_factors(craft, 64, cache_dir=tmp_path).origin == f"cache {path}"  # and stored again


def test_a_stale_or_tampered_entry_is_reported_and_rebuilt(tmp_path):
    craft = corner(2)
    fresh = view_factors(craft, 64, cache_dir=tmp_path)
    [path] = entries(tmp_path)
    stored = dict(np.load(path))
    arrays = {name: value for name, value in stored.items() if name not in ("key", "checksum")}
    write_entry(path, "0" * 64, arrays)  # a sound entry, made for other inputs
    with pytest.warns(CacheWarning, match="was stale"):
        rebuilt = view_factors(craft, 64, cache_dir=tmp_path)
    assert rebuilt.origin.startswith(f"computed (cache entry {path} was stale")
    assert_same(fresh, rebuilt)
    stored["escape_fraction"][0] -= 0.5  # altered data under the right key and the old checksum
    np.savez(path, **stored)
    with pytest.warns(CacheWarning, match="checksum mismatch"):
        assert (
            "was corrupt (checksum mismatch): rebuilt" in view_factors(craft, 64, cache_dir=tmp_path).origin
        )


def _forge(path, key, change) -> None:
    """Rewrite the entry at ``path`` with ``change(arrays)`` applied, under its own key and a valid
    checksum: what the checksum cannot catch."""
    stored = dict(np.load(path))
    arrays = {name: value.copy() for name, value in stored.items() if name not in ("key", "checksum")}
    change(arrays)
    write_entry(path, key, arrays)


@pytest.mark.parametrize(
    "change, problem",
    [
        (lambda a: a["data"].fill(np.nan), "values not finite"),
        (lambda a: a["escape_vector"].fill(np.inf), "values not finite"),
        (lambda a: a["escape_fraction"].fill(-0.5), "negative"),
        (lambda a: a["blind_fraction"].fill(1.5), "a share above 1"),
        (lambda a: a["escape_fraction"].fill(0.25), "rows do not balance"),
        (lambda a: a["indices"].fill(10**6), "matrix structure out of range"),
        (lambda a: a.update(seconds=np.array(np.nan)), "values not finite"),
    ],
    ids=[
        "nan factors",
        "inf escape vector",
        "negative share",
        "share above 1",
        "unbalanced",
        "indices",
        "seconds",
    ],
)
def test_a_forged_entry_with_a_valid_checksum_is_checked_and_rebuilt(tmp_path, change, problem):
    craft = corner(2)
    fresh = view_factors(craft, 64, cache_dir=tmp_path)
    [path] = entries(tmp_path)
    _forge(path, geometry_key(craft, vf_module._settings(64, VIEW_SEED)), change)
    with pytest.warns(CacheWarning, match=f"{path.name} was corrupt \\({problem}"):
        rebuilt = view_factors(craft, 64, cache_dir=tmp_path)
    assert rebuilt.origin.startswith("computed (cache entry") and "rebuilt" in rebuilt.origin
    assert_same(fresh, rebuilt)
    assert view_factors(craft, 64, cache_dir=tmp_path).origin == f"cache {path}"  # stored again


def test_no_cache_writes_nothing_and_the_environment_names_the_default(tmp_path, monkeypatch):
    craft = corner(1)
    monkeypatch.setenv("SUNWIND_CACHE_DIR", str(tmp_path / "env"))
    assert view_factors(craft, 16, cache_dir=False).origin == "computed"
    assert not (tmp_path / "env").exists()
    view = view_factors(craft, 16)
    assert len(entries(tmp_path / "env")) == 1
    assert view.origin.startswith(f"computed (stored in cache {tmp_path / 'env'}")


def test_an_unwritable_cache_is_reported_not_raised(tmp_path):
    craft = corner(1)
    blocker = tmp_path / "file"
    blocker.write_text("a file where the cache directory should be")
    view = view_factors(craft, 16, cache_dir=blocker)
    assert view.origin.startswith(f"computed (cache {blocker} not writable (")
    assert_same(view, compute_view_factors(craft, 16))
    assert sorted(tmp_path.iterdir()) == [blocker]
