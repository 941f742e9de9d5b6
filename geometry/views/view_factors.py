"""View factors between sides and the escape vectors of their diffuse emission, by Embree ray sampling.

METHOD.md "Inter-reflection" and "Speed": ``F_ij`` and ``e_esc`` depend on geometry alone, so they are
computed once per model (the paper's array ``PRB``), kept on disk, and reused for every attitude, for
light and gas alike.

Each side emits ``rays_per_side = g**2`` stratified cosine-weighted rays (:mod:`.hemisphere`), the
same bits whatever the thread count or batch size.

A ray that meets side ``j`` counts toward ``F_ij``; one that meets a side the model does not have
(``BLIND``) toward ``blind_fraction``. Escape uses the exact unobstructed hemisphere as control
variate, so a side that sees only sky gets ``f_esc = 1``, ``e_esc = (2/3) n_out`` and ``m = 0`` exactly,
and every row sums to one to round-off::

    f_esc = 1 - blocked / N,   e_esc = (2/3) n_out - (1/N) sum_blocked w,
    m = -(1/N) sum_blocked (o - c) x w        (o on the side's surface, c its centroid)

Near field (:mod:`.near_field`): between edge-adjacent sides that meet at a concave edge ``F_ij`` is
integrated instead, and the rest of the row rescaled so it still sums to one (adding the difference to
the escape share instead would open a closed cavity whenever the sampled near value happened to exceed
the exact one). ``escape_vector`` and ``escape_moment`` keep their sampled (unbiased) values.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import count, require
from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft
from sunwind.geometry.triangles import STRATIFIED_SEED
from sunwind.geometry.views.disk_cache import (
    cache_directory,
    check_balance,
    factor_arrays,
    factor_fields,
    geometry_key,
    kept_on_disk,
)
from sunwind.geometry.views.hemisphere import batch_bytes, emission_rays, map_side_batches
from sunwind.geometry.views.near_field import (
    CONCAVE_TOLERANCE,
    NEAR_LEVELS_EDGE,
    NEAR_LEVELS_ENDS,
    NEAR_ORDER,
    NEAR_RATIO,
    with_near_field,
)

#: Seed of the emission rays.
VIEW_SEED = STRATIFIED_SEED
#: Bounds of the default rays per side: ``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // n_sides))`` rounded
#: down to a square ``g**2`` (the ``g x g`` grids stratify points and directions alike). 2**24 rays
#: take ~3 s of CPU (made, cast by Embree and tallied); 256 rays (g = 16) keep the noise of one ``F_ij``
#: below ``0.5 / sqrt(256) = 3 %`` absolute, and far less on sums over many sides.
MIN_RAYS, MAX_RAYS, TOTAL_RAYS = 256, 16_384, 2**24
#: Most rays per side that may be asked for: four times the default's most (its noise halved); the
#: rays of 256 sides then take ~3 s, and more per side would take hours on a mesh of thousands of facets.
MAX_RAYS_PER_SIDE = 65_536
#: Version of the method; part of the cache key, so changing the method never reads old entries.
METHOD_VERSION = 1


@dataclass(frozen=True, eq=False)
class ViewFactors:
    """Share of each side's Lambertian emission reaching each other side, the sky or a blind side.

    Attributes
    ----------
    matrix : (n_sides, n_sides) scipy.sparse.csr_matrix, float64
        ``F_ij``: share of side i's emission that first strikes side j.
    escape_fraction : (n_sides,) float64
        ``f_esc,i``: share that leaves to open sky.
    escape_vector : (n_sides, 3) float64
        ``e_esc,i = (1/pi) * integral over open sky of cos(theta) w dOmega``, averaged over the side's
        area, body frame; ``(2/3) n_out`` for a side that sees only sky. Diffuse light of power ``W``
        leaving side i pushes it by ``-(W / c) e_esc,i`` [N].
    escape_moment : (n_sides, 3) float64 [m]
        ``m_i``: the same average of ``(r - c_i) x w`` (``r`` the emission point, ``c_i`` the side
        centroid); the torque of that escaping light about ``r_ref`` is
        ``-(W / c) [(c_i - r_ref) x e_esc,i + m_i]`` [N m]. Zero for a side that sees only sky.
    blind_fraction : (n_sides,) float64
        Share that strikes a side the model does not have (absorbed there).
    rays_per_side : int
        Rays each side cast.
    seed : int
        Seed of the rays.
    seconds : float
        Time the computation took [s] (the original time when loaded from cache).
    origin : str
        "computed ..." or "cache <path>".

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> view = compute_view_factors(craft, rays_per_side=64)
    >>> view.matrix.shape, view.escape_fraction[[0, 16]].round(3)  # the bus's -x face sees sky only
    ((144, 144), array([1.   , 0.891]))
    >>> view.escape_vector[0].round(4) + 0.0
    array([-0.6667,  0.    ,  0.    ])
    """

    matrix: scipy.sparse.csr_matrix
    escape_fraction: NDArray[np.float64]
    escape_vector: NDArray[np.float64]
    escape_moment: NDArray[np.float64]
    blind_fraction: NDArray[np.float64]
    rays_per_side: int
    seed: int
    seconds: float
    origin: str

    def row_sum_error(self) -> NDArray[np.float64]:
        """Measure how far each side's shares are from summing to one.

        Returns
        -------
        (n_sides,) ndarray of float64
            ``|sum_j F_ij + f_esc,i + f_blind,i - 1|``.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> float(view.row_sum_error().max()) < 1e-12
        True
        """
        rows = np.asarray(self.matrix.sum(axis=1)).ravel()
        return np.abs(rows + self.escape_fraction + self.blind_fraction - 1)

    def reciprocity_error(self, areas: NDArray[np.float64]) -> float:
        """Measure the departure from reciprocity: ``sum |A_i F_ij - A_j F_ji| / sum A_i F_ij`` over pairs.

        Sampling noise sets its size: about ``1 / sqrt(hits)`` of a typical pair, so it is large for fine
        meshes whose pairs get few hits each.

        Parameters
        ----------
        areas : (n_sides,) ndarray of float64
            Side areas [m^2].

        Returns
        -------
        float
            The relative error; 0 where no side sees another.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> round(view.reciprocity_error(craft.side_areas), 3)  # 64 rays a side: noisy
        1.141
        """
        exchange = scipy.sparse.diags(np.asarray(areas, dtype=np.float64)) @ self.matrix
        total = exchange.sum()
        return float(abs(exchange - exchange.T).sum() / total) if total > 0 else 0.0

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays [bytes].

        Returns
        -------
        int
            Bytes of the sparse matrix and the per-side arrays.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> view = compute_view_factors(craft, rays_per_side=64)
        >>> view.nbytes
        11344
        """
        m = self.matrix
        arrays = (self.escape_fraction, self.escape_vector, self.escape_moment, self.blind_fraction)
        return m.data.nbytes + m.indices.nbytes + m.indptr.nbytes + sum(a.nbytes for a in arrays)


def default_rays_per_side(n_sides: int) -> int:
    """Choose the default rays per side for a model of ``n_sides`` sides.

    Parameters
    ----------
    n_sides : int
        Sides of the model.

    Returns
    -------
    int
        ``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // n_sides))`` rounded down to a square.

    Examples
    --------
    >>> default_rays_per_side(144), default_rays_per_side(10**6)
    (16384, 256)
    """
    return math.isqrt(max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // max(n_sides, 1)))) ** 2


def resolve_rays_per_side(rays_per_side: int | None, n_sides: int) -> int:
    """Find the rays per side to cast: the default for None, else the number given rounded up to a square.

    Parameters
    ----------
    rays_per_side : int or None
        Rays per side asked for, a whole number from 1 to :data:`MAX_RAYS_PER_SIDE`; None for the default.
    n_sides : int
        Sides of the model, for the default.

    Returns
    -------
    int
        A square number of rays.

    Raises
    ------
    InputError
        ``rays_per_side`` not a whole number in range.

    Examples
    --------
    >>> resolve_rays_per_side(None, 144), resolve_rays_per_side(10, 144)
    (16384, 16)
    """
    if rays_per_side is None:
        return default_rays_per_side(n_sides)
    check_rays_per_side(rays_per_side)
    return (math.isqrt(int(rays_per_side) - 1) + 1) ** 2


def check_rays_per_side(rays_per_side: int, name: str = "rays_per_side") -> None:
    """Refuse anything but a whole number of rays per side from 1 to :data:`MAX_RAYS_PER_SIDE`.

    Parameters
    ----------
    rays_per_side : int
        The number given.
    name : str, optional
        The parameter that gave it, for the message.

    Raises
    ------
    InputError
        When it is not such a number.

    Examples
    --------
    >>> check_rays_per_side(4096)
    >>> check_rays_per_side(0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: rays_per_side 0 must be a whole number from 1 to 65536 ...
    """
    integer = isinstance(rays_per_side, (int, np.integer)) and not isinstance(rays_per_side, bool)
    if not integer or not 1 <= rays_per_side <= MAX_RAYS_PER_SIDE:
        raise InputError(
            f"{name} {rays_per_side!r} must be a whole number from 1 to {MAX_RAYS_PER_SIDE} (four times "
            "the default's most; more would take hours on a mesh of thousands of facets)",
            hint=f"e.g. 4096, or leave it out for the default ({MIN_RAYS} to {MAX_RAYS} by mesh size)",
            parameters=(name,),
        )


# ---------------------------------------------------------------------------------------- computation


def compute_view_factors(
    craft: Spacecraft, rays_per_side: int | None = None, seed: int = VIEW_SEED, *, near_field: bool = True
) -> ViewFactors:
    """Sample the view factors, escape fractions, escape vectors and moments of every side.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    rays_per_side : int, optional
        Rays per side, rounded up to a square; default :func:`default_rays_per_side`.
    seed : int
        Seed of the rays (non-negative, below 2**64).
    near_field : bool
        Integrate ``F_ij`` of concave edge-adjacent pairs (see the module notes); False keeps the
        sampled values (for comparison).

    Returns
    -------
    ViewFactors
        The factors, ``origin`` "computed".

    Raises
    ------
    InputError
        A bad ``rays_per_side`` or ``seed``, or too many rays for the memory.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> view = compute_view_factors(craft, rays_per_side=60)
    >>> view.rays_per_side, view.origin, view.matrix.nnz
    (64, 'computed', 129)
    """
    start = time.perf_counter()
    rays = resolve_rays_per_side(rays_per_side, craft.n_sides)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64:
        raise InputError(f"seed = {seed!r} must be an integer from 0 to 2**64 - 1")
    n = craft.n_sides
    what = f"{count(rays)} view-factor rays per side x {n} sides"
    require(batch_bytes(n, rays), what, "lower rays_per_side", ("rays_per_side",))
    nnz, cols, hits, blind, blocked, sum_w, sum_m = _sample(craft, math.isqrt(rays), seed)
    matrix = scipy.sparse.csr_matrix((hits / rays, cols, np.r_[0, np.cumsum(nnz)]), shape=(n, n))
    escape = (rays - blocked) / rays
    blind_fraction = blind / rays
    if near_field:
        matrix, scale = with_near_field(craft, matrix)
        escape, blind_fraction = escape * scale, blind_fraction * scale
    return ViewFactors(
        matrix=matrix,
        escape_fraction=escape,
        escape_vector=(2 / 3) * craft.side_normals - sum_w / rays,
        escape_moment=-sum_m / rays,
        blind_fraction=blind_fraction,
        rays_per_side=rays,
        seed=int(seed),
        seconds=time.perf_counter() - start,
        origin="computed",
    )


def _sample(craft: Spacecraft, grid: int, seed: int) -> tuple[NDArray, ...]:
    """Cast ``grid**2`` rays from every side in threaded batches; the per-side tallies of
    :func:`_tally`, concatenated in side order."""
    scene = craft.scene

    def batch(lo: int, hi: int) -> tuple[NDArray, ...]:
        origins, directions, lever = emission_rays(craft, np.arange(lo, hi), grid, seed)
        struck = craft.struck_sides(scene.first_hit(origins, directions), directions)
        return _tally(struck, directions, lever, grid**2)

    tallies = map_side_batches(batch, craft.n_sides, grid**2)
    return tuple(np.concatenate(field) for field in zip(*tallies, strict=True))


@numba.njit(cache=True, nogil=True)
def _tally(
    struck: NDArray[np.int64], directions: NDArray[np.float32], lever: NDArray[np.float64], n: int
) -> tuple[NDArray, ...]:
    """Per-side sums of ``n`` consecutive rays per side, in ray order.

    Returns
    -------
    nnz : (count,) int64
        Distinct sides struck by each side's rays.
    cols, hits : (sum(nnz),) int64
        Those sides, ascending per emitting side, and their ray counts.
    blind, blocked : (count,) int64
        Rays that struck a blind side; rays that struck anything.
    sum_w, sum_m : (count, 3) float64
        Sums of ``w`` and of ``lever x w`` over the blocked rays.
    """
    count = struck.shape[0] // n
    nnz = np.zeros(count, dtype=np.int64)
    cols = np.empty(struck.shape[0], dtype=np.int64)
    hits = np.empty(struck.shape[0], dtype=np.int64)
    blind = np.zeros(count, dtype=np.int64)
    blocked = np.zeros(count, dtype=np.int64)
    sum_w = np.zeros((count, 3))
    sum_m = np.zeros((count, 3))
    targets = np.empty(n, dtype=np.int64)
    at = 0
    for k in range(count):
        m = 0
        for r in range(k * n, (k + 1) * n):
            target = struck[r]
            if target == ESCAPED:
                continue
            blocked[k] += 1
            w0, w1, w2 = float(directions[r, 0]), float(directions[r, 1]), float(directions[r, 2])
            l0, l1, l2 = lever[r, 0], lever[r, 1], lever[r, 2]
            sum_w[k, 0] += w0
            sum_w[k, 1] += w1
            sum_w[k, 2] += w2
            sum_m[k, 0] += l1 * w2 - l2 * w1
            sum_m[k, 1] += l2 * w0 - l0 * w2
            sum_m[k, 2] += l0 * w1 - l1 * w0
            if target == BLIND:
                blind[k] += 1
            else:
                targets[m] = target
                m += 1
        sides = np.sort(targets[:m])
        for i in range(m):
            if i == 0 or sides[i] != sides[i - 1]:
                cols[at] = sides[i]
                hits[at] = 0
                nnz[k] += 1
                at += 1
            hits[at - 1] += 1
    return nnz, cols[:at].copy(), hits[:at].copy(), blind, blocked, sum_w, sum_m


# ----------------------------------------------------------------------------------------- near field


# ----------------------------------------------------------------------------------------- disk cache


def _settings(rays_per_side: int, seed: int) -> dict[str, object]:
    """Everything besides the geometry that the result depends on: the cache key's settings."""
    return {
        "what": "view_factors",
        "method": METHOD_VERSION,
        "rays_per_side": rays_per_side,
        "seed": int(seed),
        "near_field": [NEAR_ORDER, NEAR_RATIO, NEAR_LEVELS_EDGE, NEAR_LEVELS_ENDS, CONCAVE_TOLERANCE],
    }


#: Per-side arrays of the view factors (width 1 or 3), and their numbers, as stored on disk.
_COLUMNS = {"escape_fraction": 1, "escape_vector": 3, "escape_moment": 3, "blind_fraction": 1}
_NUMBERS = ("seconds",)


def view_factors(
    craft: Spacecraft,
    rays_per_side: int | None = None,
    seed: int = VIEW_SEED,
    cache_dir: str | os.PathLike | bool | None = None,
) -> ViewFactors:
    """Compute the view factors as :func:`compute_view_factors`, kept on disk and read back when they match.

    ``origin`` of the result says what happened: "cache <path>", "computed (stored in cache <path>)",
    or "computed (...)" naming a corrupt or stale entry that was rebuilt, or a cache that could not be
    written. Cache trouble is never an error and never gives a wrong result: an entry whose values are
    not finite, out of [0, 1] or whose rows do not sum to 1 is rebuilt, with a ``CacheWarning``.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    rays_per_side : int, optional
        As for :func:`compute_view_factors`.
    seed : int
        As for :func:`compute_view_factors`.
    cache_dir : path, bool or None
        Directory of the cache; None (or True): ``$SUNWIND_CACHE_DIR``, else ``~/.cache/sunwind``
        (``$XDG_CACHE_HOME`` if set); False: no disk cache.

    Returns
    -------
    ViewFactors
        The factors, from the cache or computed.

    Raises
    ------
    InputError
        A bad ``rays_per_side`` or ``seed``, or too many rays for the memory.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> folder = tempfile.TemporaryDirectory()
    >>> view_factors(craft, 64, cache_dir=folder.name).origin
    'computed (stored in cache .../view_factors-....npz)'
    >>> view_factors(craft, 64, cache_dir=folder.name).origin
    'cache .../view_factors-....npz'
    >>> folder.cleanup()
    """
    directory = cache_directory(cache_dir)
    if directory is None:
        return compute_view_factors(craft, rays_per_side, seed)
    rays = resolve_rays_per_side(rays_per_side, craft.n_sides)

    def decode(arrays, origin: str) -> ViewFactors:
        fields = factor_fields(arrays, craft.n_sides, _COLUMNS, _NUMBERS)
        view = ViewFactors(**fields, rays_per_side=rays, seed=int(seed), origin=origin)
        check_balance(view.row_sum_error())  # F_ij, f_esc, f_blind each a share of one emission
        return view

    return kept_on_disk(
        directory,
        "view_factors",
        geometry_key(craft, _settings(rays, seed)),
        lambda: compute_view_factors(craft, rays, seed),
        lambda factors: factor_arrays(factors, _COLUMNS, _NUMBERS),
        decode,
    )
