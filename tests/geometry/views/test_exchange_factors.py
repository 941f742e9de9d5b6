"""Specular-diffuse exchange factors and the diffuse balance built on them: reduction to the view
factors and eq. (12), closed forms through a mirror and a clear sheet, power and momentum balance,
determinism, the disk cache."""

from dataclasses import replace

import numpy as np
import pytest

import sunwind.geometry.views.hemisphere as hemisphere
from helpers import quad_sheet
from helpers.shapes import parallel_squares
from sunwind.forces.radiation.law import SPEED_OF_LIGHT
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.geometry.views.disk_cache import CacheWarning, write_entry
from sunwind.geometry.views.exchange_factors import (
    CHAIN_RAYS,
    ExchangeFactors,
    compute_exchange_factors,
    exchange_factors,
    onward_share,
)
from sunwind.geometry.views.view_factors import compute_view_factors
from sunwind.meshes.primitives import box

FLOOR = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)  # z = 0, front +z


def square(z: float, part: str, n: int, up: bool = True) -> MeshData:
    """Unit square at height ``z``, front up (+z) or down, 2 n^2 triangles."""
    corners = FLOOR + np.array([0.0, 0.0, z])
    return quad_sheet(corners if up else corners[::-1], part, n)


def model(parts: dict[str, tuple], *meshes: MeshData):
    """``meshes`` with optics per part: ``(rho, beta, sigma)`` for a one-sided sheet or a closed body
    (``"solid"`` as 4th item), two tuples for a two-sided sheet (front, back)."""
    materials, rules = {}, {}
    for part, optics in parts.items():
        sides = optics if isinstance(optics[0], tuple) else (optics,)
        names = []
        for k, (rho, beta, sigma, *_) in enumerate(sides):
            names.append(f"{part}{k}")
            materials[names[-1]] = {"reflectivity": rho, "specular_fraction": beta, "transmissivity": sigma}
        if len(names) == 2:
            rules[part] = {"front": names[0], "back": names[1]}
        else:
            rules[part] = names[0] if optics[-1] == "solid" else {"front": names[0]}
    spec = parse_materials({"materials": materials, "parts": rules})
    return build_spacecraft(MeshData.concatenate(meshes), spec)


def part_mean(craft, values, part: str) -> float:
    """Area-weighted mean of per-side ``values`` over ``part``'s sides."""
    mask = craft.facet_part[craft.side_facet] == craft.part_names.index(part)
    return float(craft.side_areas[mask] @ values[mask] / craft.side_areas[mask].sum())


def to_part(craft, factors, source: str, target: str) -> float:
    """Area-weighted exchange factor from part ``source`` to part ``target``."""
    part = craft.facet_part[craft.side_facet]
    into = np.asarray(factors.matrix[:, part == craft.part_names.index(target)].sum(axis=1)).ravel()
    return part_mean(craft, into, source)


def eq12_totals(craft, view, source, reference):
    """The paper's balance, dense: ``W = S + diag(rho) F^T W``; escaping force [N], torque [N m] and
    absorbed power [W]."""
    rho = craft.side_optics[:, 0]
    f = view.matrix.toarray()
    w = np.linalg.solve(np.eye(craft.n_sides) - rho[:, None] * f.T, source)
    momentum = w @ view.escape_vector
    moment = w @ (np.cross(craft.side_centroids - reference, view.escape_vector) + view.escape_moment)
    absorbed = (f.T @ w) @ (1 - rho) + w @ view.blind_fraction
    return -momentum / SPEED_OF_LIGHT, -moment / SPEED_OF_LIGHT, absorbed


def open_box(optics, n: int = 3):
    """A unit cube without its top, two-sided walls of ``optics`` on both sides."""
    walls = [square(0, "floor", n)]
    for k, corners in enumerate(
        (
            [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]],
            [[1, 1, 0], [0, 1, 0], [0, 1, 1], [1, 1, 1]],
            [[0, 1, 0], [0, 0, 0], [0, 0, 1], [0, 1, 1]],
            [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]],
        )
    ):
        walls.append(quad_sheet(np.array(corners, float), f"wall{k}", n))
    return model({mesh.part_names[0]: (optics, optics) for mesh in walls}, *walls)


def test_without_mirrors_or_sheets_the_factors_are_the_view_factors_and_the_balance_is_eq12():
    craft = open_box((0.7, 0.0, 0.0))
    view = compute_view_factors(craft, 256)
    factors = exchange_factors(craft, view)
    assert factors.origin == "view factors" and factors.matrix is view.matrix
    assert not factors.truncated_fraction.any()
    source = np.random.default_rng(2).random(craft.n_sides)
    reference = np.array([0.2, 0.4, 0.3])
    totals = DiffuseExchange(craft, view).totals(source, reference)
    force, torque, absorbed = eq12_totals(craft, view, source, reference)
    np.testing.assert_allclose(totals.force_N, force, rtol=1e-12, atol=1e-12 * np.abs(force).max())
    np.testing.assert_allclose(totals.torque_Nm, torque, rtol=1e-12, atol=1e-12 * np.abs(torque).max())
    assert totals.absorbed_W == pytest.approx(absorbed, rel=1e-12)


def test_a_vanishing_mirror_share_tends_to_eq12():
    crafts = [open_box((0.7, beta, 0.0)) for beta in (0.0, 1e-9)]
    view = compute_view_factors(crafts[0], 256)
    results = [DiffuseExchange(craft, view).totals(np.ones(craft.n_sides), np.zeros(3)) for craft in crafts]
    assert results[1].force_N == pytest.approx(results[0].force_N, rel=1e-8)
    assert results[1].absorbed_W == pytest.approx(results[0].absorbed_W, rel=1e-8)


@pytest.mark.parametrize("kind", ["mirror", "clear sheet"])
def test_through_a_mirror_or_a_clear_sheet_a_plate_sees_an_image_or_what_is_behind(kind):
    """A white floor under a unit square one unit up: a perfect mirror makes the floor see its own
    image two units away; a clear sheet lets it see a black square two units up. Both exchange
    factors are the view factor of directly opposed unit squares at distance 2."""
    n = 6
    floor = square(0, "floor", n)
    if kind == "mirror":
        craft = model(
            {"floor": (0.8, 0.0, 0.0), "top": (1.0, 1.0, 0.0)}, floor, square(1, "top", n, up=False)
        )
        far = "floor"
    else:
        clear = ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0))
        parts = {"floor": (0.8, 0.0, 0.0), "top": clear, "black": (0.0, 0.0, 0.0)}
        craft = model(parts, floor, square(1, "top", n), square(2, "black", n, up=False))
        far = "black"
    view = compute_view_factors(craft, 4096)
    factors = compute_exchange_factors(craft, view)
    assert factors.rays_per_side == CHAIN_RAYS
    assert to_part(craft, factors, "floor", "top") == pytest.approx(
        to_part(craft, view, "floor", "top"), abs=1e-15
    )
    # sampling noise of the part mean (72 sides x 1024 rays, stratified): ~3e-4
    assert to_part(craft, factors, "floor", far) == pytest.approx(parallel_squares(0.5), abs=1.5e-3)
    assert to_part(craft, factors, "floor", "top") == pytest.approx(parallel_squares(1.0), abs=1.5e-3)
    assert factors.row_sum_error(onward_share(craft.side_optics)).max() < 1e-12


@pytest.mark.parametrize(
    "optics", [(0.8, 0.5, 0.0), (0.2, 0.5, 0.3), (0.5, 0.0, 0.4), (0.9, 1.0, 0.0)], ids=str
)
def test_weight_and_power_balance_to_round_off(optics):
    craft = open_box(optics)
    view = compute_view_factors(craft, 256)
    factors = compute_exchange_factors(craft, view)
    assert factors.row_sum_error(onward_share(craft.side_optics)).max() < 1e-12
    source = np.random.default_rng(5).random(craft.n_sides)
    totals = DiffuseExchange(craft, view).totals(source, np.zeros(3))
    assert totals.escaped_W + totals.absorbed_W == pytest.approx(source.sum(), rel=1e-12)


def test_light_a_closed_body_transmits_leaves_along_its_line():
    """A translucent closed box on a white floor: the box's transmitted share leaves unchanged, so
    it escapes rather than being absorbed, and the weights still balance."""
    floor = quad_sheet(np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0.0]]), "floor", 4)
    cube = replace(box((1.0, 1.0, 1.0), 2), part_names=("cube",))
    cube = replace(cube, vertices=cube.vertices + np.array([0.0, 0.0, 0.5 + 1e-3]))
    escapes = []
    for sigma in (0.0, 0.5):
        craft = model({"floor": (0.8, 0.0, 0.0), "cube": (0.3, 0.0, sigma, "solid")}, floor, cube)
        factors = compute_exchange_factors(craft, compute_view_factors(craft, 256))
        assert factors.row_sum_error(onward_share(craft.side_optics)).max() < 1e-12
        escapes.append(part_mean(craft, factors.escape_fraction, "floor"))
    assert escapes[1] > escapes[0] + 0.01


def test_a_closed_specular_cavity_lets_nothing_out():
    cube = box((1.0, 1.0, 1.0), 2)
    inward = replace(cube, faces=cube.faces[:, ::-1], part_names=("cavity",))
    craft = model({"cavity": (0.9, 0.6, 0.0)}, inward)
    view = compute_view_factors(craft, 1024)
    factors = compute_exchange_factors(craft, view)
    assert factors.chains > 0
    assert np.array_equal(factors.escape_fraction, np.zeros(craft.n_sides))
    assert np.array_equal(factors.escape_vector, view.escape_vector)  # no chain leaves
    assert factors.truncated_fraction.max() < 1e-5  # chains end by the cutoff: light dies out
    source = np.random.default_rng(7).random(craft.n_sides)
    totals = DiffuseExchange(craft, view).totals(source, craft.default_reference[0])
    assert totals.escaped_W == 0.0
    assert totals.absorbed_W == pytest.approx(source.sum(), rel=1e-12)
    # momentum balance: no force but the sampling noise of the view factors' escape vectors,
    # (2/3) n minus the mean of 1024 sampled directions (measured 9e-4 of the source's momentum)
    assert np.linalg.norm(totals.force_N) < 3e-3 * source.sum() / SPEED_OF_LIGHT


def test_the_same_bits_whatever_the_threads_and_batches(monkeypatch, limit_threads):
    craft = open_box((0.2, 0.5, 0.3))  # mirrors and sheets: chains pick one at random
    view = compute_view_factors(craft, 256)
    runs = []
    for threads, batch in (("1", 256 * 8), ("2", 256 * 8), ("2", 256 * 3)):
        limit_threads(int(threads))
        monkeypatch.setattr(hemisphere, "_BATCH_RAYS", batch)
        runs.append(compute_exchange_factors(craft, view))
    first = runs[0]
    assert first.chains > 0
    for other in runs[1:]:
        for name in ("data", "indices", "indptr"):
            assert np.array_equal(getattr(first.matrix, name), getattr(other.matrix, name))
        for name in (
            "escape_fraction",
            "escape_vector",
            "escape_moment",
            "blind_fraction",
            "truncated_fraction",
        ):
            assert np.array_equal(getattr(first, name), getattr(other, name))


def test_sides_that_re_emit_nothing_diffusely_are_not_followed():
    craft = open_box((0.9, 1.0, 0.0))
    view = compute_view_factors(craft, 256)
    factors = compute_exchange_factors(craft, view)
    assert factors.chains == 0 and factors.matrix.nnz == view.matrix.nnz
    # their onward share counts as truncated, so the rows still balance
    assert factors.row_sum_error(onward_share(craft.side_optics)).max() < 1e-12


def test_the_disk_cache_keeps_factors_per_optics(tmp_path):
    craft = open_box((0.8, 0.5, 0.0))
    view = compute_view_factors(craft, 256)
    first = exchange_factors(craft, view, tmp_path)
    again = exchange_factors(craft, view, tmp_path)
    assert first.origin.startswith("computed (stored in cache") and again.origin.startswith("cache ")
    assert isinstance(again, ExchangeFactors) and again.chains == first.chains
    for name in ("escape_fraction", "escape_vector", "escape_moment", "blind_fraction", "truncated_fraction"):
        assert np.array_equal(getattr(first, name), getattr(again, name))
    assert (first.matrix != again.matrix).nnz == 0
    other = exchange_factors(open_box((0.8, 0.4, 0.0)), view, tmp_path)
    assert other.origin.startswith("computed") and len(list(tmp_path.glob("exchange_factors-*.npz"))) == 2
    assert exchange_factors(craft, view).origin == "computed"  # no cache by default


def test_a_forged_exchange_entry_that_does_not_balance_is_rebuilt(tmp_path):
    craft = open_box((0.8, 0.5, 0.0))
    view = compute_view_factors(craft, 256)
    first = exchange_factors(craft, view, tmp_path)
    [path] = tmp_path.glob("exchange_factors-*.npz")
    stored = dict(np.load(path))
    arrays = {name: value for name, value in stored.items() if name not in ("key", "checksum")}
    arrays["truncated_fraction"] = np.full_like(arrays["truncated_fraction"], 0.5)  # shares, yet no balance
    write_entry(path, str(stored["key"]), arrays)
    with pytest.warns(CacheWarning, match="rows do not balance"):
        again = exchange_factors(craft, view, tmp_path)
    assert again.origin.startswith("computed (cache entry")
    assert np.array_equal(again.truncated_fraction, first.truncated_fraction)
