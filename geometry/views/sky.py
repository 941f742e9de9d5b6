"""Each side's open sky, sampled once per model: which of its cosine-weighted hemisphere rays leave the
model (METHOD.md "The open-sky integral").

A rarefied gas at finite speed ratio reaches a side from every direction of its open hemisphere from
which the side sees open sky (the paper's solid angle ``Omega_inf``, eq. 7). That set depends on the
geometry alone, so it is sampled once: every side casts ``rays_per_side = g**2`` rays of the emission
law of :mod:`.hemisphere` (stratified points on the side, stratified cosine-weighted directions) with
:data:`SKY_SEED`, and each ray either escapes or meets the model. For any kernel ``k`` of the
direction ``w`` (``mu = n . w``) the cosine weighting gives, over the side's area,

    integral over open sky of k mu dOmega ~= (pi / N) sum_escaping k(w_r)
                                          = integral over the hemisphere - (pi / N) sum_blocked k(w_r),

unbiased either way. Of every side only the smaller set is kept, its rays' directions and levers
(origin on the surface minus the side centroid, for the torque): a side that sees only sky keeps
nothing and its integral is the hemisphere's closed form exactly; a side that sees none keeps nothing
either and gets exactly zero. A side whose plane supports the model's convex hull
(:mod:`sunwind.geometry.rays.hull`) casts nothing.

The kept rays are stored with the model (and on disk, like the view factors): ~24 bytes each, about
half of one view-factor pass at most.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.memory import count, require
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.spacecraft import ESCAPED, Spacecraft
from sunwind.geometry.views.disk_cache import CacheEntryError, cache_directory, geometry_key, kept_on_disk
from sunwind.geometry.views.hemisphere import batch_bytes, emission_rays, map_side_batches
from sunwind.geometry.views.view_factors import resolve_rays_per_side

#: Seed of the sky rays (other than the view factors', so the two samplings are independent).
SKY_SEED = 0x5EED_0F_5C1
#: Bounds of the default rays per side: ``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // sides))`` rounded
#: down to a square (sides that cast: those not on the model's hull).
MIN_RAYS, MAX_RAYS, TOTAL_RAYS = 36, 4096, 2**22
#: Bytes kept per ray (direction and lever, float32).
RAY_BYTES = 24
#: Version of the method; part of the cache key.
METHOD_VERSION = 1


@dataclass(frozen=True, eq=False)
class OpenSky:
    """Which of each side's sampled hemisphere rays leave the model, and the rays of the smaller set.

    Attributes
    ----------
    blocked_fraction : (n_sides,) float64
        Share of the side's rays that meet the model.
    keeps_open : (n_sides,) bool
        The kept rays of the side are those that escape (else those that meet the model).
    start : (n_sides + 1,) int64
        Rays of side ``i`` are ``start[i]:start[i + 1]`` of ``direction`` and ``lever``.
    direction : (n_kept, 3) float32
        Unit direction of each kept ray, body frame (into the side's open hemisphere).
    lever : (n_kept, 3) float32
        Its origin on the side's surface minus the side's centroid [m].
    rays_per_side : int
        Rays each side cast (``N``; sides on the model's hull cast none).
    seed : int
    seconds : float
        Time the sampling took [s] (the original time when read from the disk cache).
    origin : str
        "computed ..." or "cache <path>".

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> sky = compute_open_sky(craft, rays_per_side=16)
    >>> sky.rays_per_side, sky.blocked_fraction[:3], int(sky.start[-1])  # the bus's -x face sees only sky
    (16, array([0., 0., 0.]), 41)
    """

    blocked_fraction: NDArray[np.float64]
    keeps_open: NDArray[np.bool_]
    start: NDArray[np.int64]
    direction: NDArray[np.float32]
    lever: NDArray[np.float32]
    rays_per_side: int
    seed: int
    seconds: float
    origin: str

    @property
    def nbytes(self) -> int:
        """Memory held by the arrays [bytes].

        Returns
        -------
        int
            Bytes of the per-side arrays and the kept rays.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> sky = compute_open_sky(craft, rays_per_side=16)
        >>> sky.nbytes
        3440
        """
        arrays = (self.blocked_fraction, self.keeps_open, self.start, self.direction, self.lever)
        return sum(a.nbytes for a in arrays)

    def to_json(self) -> dict:
        """Describe the sampling, JSON-ready: rays per side, where it came from and its time [s].

        Returns
        -------
        dict
            ``rays_per_side``, ``origin`` and ``seconds``.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> sky = compute_open_sky(craft, rays_per_side=16)
        >>> sorted(sky.to_json().items())[:2]
        [('origin', 'computed'), ('rays_per_side', 16)]
        """
        return {"rays_per_side": self.rays_per_side, "origin": self.origin, "seconds": self.seconds}

    @property
    def partly_open(self) -> NDArray[np.int64]:
        """Sides some but not all of whose rays meet the model.

        Returns
        -------
        (k,) ndarray of int64
            The sides, ascending.

        Examples
        --------
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> sky = compute_open_sky(craft, rays_per_side=16)
        >>> len(sky.partly_open), sky.partly_open[:3]
        (31, array([16, 17, 18]))
        """
        return np.flatnonzero((self.blocked_fraction > 0) & (self.blocked_fraction < 1))


def default_sky_rays(n_casting: int) -> int:
    """Choose the default sky rays per side when ``n_casting`` sides cast.

    Parameters
    ----------
    n_casting : int
        Sides not on the model's hull.

    Returns
    -------
    int
        ``max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // n_casting))`` rounded down to a square.

    Examples
    --------
    >>> default_sky_rays(100), default_sky_rays(10**6)
    (4096, 36)
    """
    return math.isqrt(max(MIN_RAYS, min(MAX_RAYS, TOTAL_RAYS // max(n_casting, 1)))) ** 2


def compute_open_sky(craft: Spacecraft, rays_per_side: int | None = None, seed: int = SKY_SEED) -> OpenSky:
    """Sample the open sky of every side not on the model's hull (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    rays_per_side : int, optional
        Rays per side, rounded up to a square; default :func:`default_sky_rays`.
    seed : int
        Seed of the rays.

    Returns
    -------
    OpenSky
        The sampled sky, ``origin`` "computed".

    Raises
    ------
    InputError
        A bad ``rays_per_side``, or too many rays for the memory.

    Examples
    --------
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> sky = compute_open_sky(craft, rays_per_side=10)
    >>> sky.rays_per_side, sky.origin
    (16, 'computed')
    """
    start_time = time.perf_counter()
    casting = np.flatnonzero(~clearance(craft).open_sky)
    rays = (
        default_sky_rays(len(casting))
        if rays_per_side is None
        else resolve_rays_per_side(rays_per_side, craft.n_sides)
    )
    grid = math.isqrt(rays)
    kept_bound = len(casting) * (rays // 2)
    require(
        batch_bytes(len(casting), rays) + RAY_BYTES * kept_bound,
        f"{count(rays)} sky rays per side x {len(casting)} sides",
        "lower sky_rays",
        ("sky_rays",),
    )
    scene = craft.scene

    def batch(lo: int, hi: int) -> tuple[NDArray, ...]:
        origins, directions, lever = emission_rays(craft, casting[lo:hi], grid, seed)
        struck = craft.struck_sides(scene.first_hit(origins, directions), directions)
        return _kept(struck != ESCAPED, directions, lever, rays)

    parts = map_side_batches(batch, len(casting), rays) if len(casting) else []
    if parts:
        blocked, keeps_open, counts, direction, lever = (np.concatenate(f) for f in zip(*parts, strict=True))
    else:
        blocked = counts = np.zeros(0, dtype=np.int64)
        keeps_open, direction, lever = np.zeros(0, dtype=bool), *np.zeros((2, 0, 3), dtype=np.float32)
    n = craft.n_sides
    fraction, opened, per_side = np.zeros(n), np.zeros(n, dtype=bool), np.zeros(n, dtype=np.int64)
    fraction[casting], opened[casting], per_side[casting] = blocked / rays, keeps_open, counts
    return OpenSky(
        blocked_fraction=fraction,
        keeps_open=opened,
        start=np.concatenate([[0], np.cumsum(per_side)]),
        direction=direction,
        lever=lever,
        rays_per_side=rays,
        seed=int(seed),
        seconds=time.perf_counter() - start_time,
        origin="computed",
    )


@numba.njit(cache=True, nogil=True)
def _kept(
    blocked: NDArray[np.bool_], directions: NDArray[np.float32], lever: NDArray[np.float64], n: int
) -> tuple[NDArray, ...]:
    """Per side of ``n`` consecutive rays: blocked rays, whether the escaping set is the one kept (the
    smaller; ties keep the blocked), how many are kept, and their directions and levers."""
    sides = blocked.shape[0] // n
    hits = np.zeros(sides, dtype=np.int64)
    for k in range(sides):
        for r in range(k * n, (k + 1) * n):
            hits[k] += blocked[r]
    keeps_open = np.empty(sides, dtype=np.bool_)
    kept = np.empty(sides, dtype=np.int64)
    for k in range(sides):
        keeps_open[k] = n - hits[k] < hits[k]
        kept[k] = n - hits[k] if keeps_open[k] else hits[k]
    out_direction = np.empty((kept.sum(), 3), dtype=np.float32)
    out_lever = np.empty((kept.sum(), 3), dtype=np.float32)
    at = 0
    for k in range(sides):
        for r in range(k * n, (k + 1) * n):
            if blocked[r] != keeps_open[k]:
                for d in range(3):
                    out_direction[at, d] = directions[r, d]
                    out_lever[at, d] = np.float32(lever[r, d])
                at += 1
    return hits, keeps_open, kept, out_direction, out_lever


# ----------------------------------------------------------------------------------------- disk cache


def _settings(rays_per_side: int, seed: int) -> dict[str, object]:
    return {"what": "open_sky", "method": METHOD_VERSION, "rays_per_side": rays_per_side, "seed": int(seed)}


def _encode(sky: OpenSky) -> dict[str, NDArray]:
    names = ("blocked_fraction", "keeps_open", "start", "direction", "lever")
    return {name: getattr(sky, name) for name in names} | {
        "rays_per_side": np.array(sky.rays_per_side),
        "seconds": np.array(sky.seconds),
    }


def _decode(arrays, n_sides: int, seed: int, origin: str) -> OpenSky:
    """The :class:`OpenSky` stored in ``arrays``, checked: shapes, a monotone ``start``, unit directions,
    finite levers, shares in [0, 1]."""
    try:
        start, direction, lever = arrays["start"], arrays["direction"], arrays["lever"]
        fraction, keeps_open = arrays["blocked_fraction"], arrays["keeps_open"]
        rays = int(arrays["rays_per_side"])
        fits = (
            start.shape == (n_sides + 1,)
            and fraction.shape == keeps_open.shape == (n_sides,)
            and direction.shape == lever.shape == (start[-1], 3)
            and direction.dtype == lever.dtype == np.float32
            and keeps_open.dtype == np.bool_
        )
        if not fits or start[0] != 0 or np.any(np.diff(start) < 0) or np.any(np.diff(start) > rays // 2):
            raise CacheEntryError("was corrupt (arrays of the wrong shape)")
        norms = np.linalg.norm(direction.astype(np.float64), axis=1)
        if not (
            np.all(np.isfinite(lever))
            and np.all(np.abs(norms - 1) < 1e-5)
            and np.all((fraction >= 0) & (fraction <= 1))
        ):
            raise CacheEntryError("was corrupt (values out of range)")
        return OpenSky(
            fraction, keeps_open, start, direction, lever, rays, seed, float(arrays["seconds"]), origin
        )
    except (KeyError, IndexError, ValueError, TypeError) as error:
        raise CacheEntryError(f"was corrupt ({type(error).__name__}: {error})") from error


def open_sky(
    craft: Spacecraft,
    rays_per_side: int | None = None,
    seed: int = SKY_SEED,
    cache_dir: str | os.PathLike | bool | None = None,
) -> OpenSky:
    """Sample the open sky as :func:`compute_open_sky`, kept on disk and read back when it matches.

    As :func:`sunwind.geometry.views.view_factors.view_factors`: ``origin`` of the result says whether
    it was read or computed, and cache trouble is never an error.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    rays_per_side : int, optional
        As for :func:`compute_open_sky`.
    seed : int
        As for :func:`compute_open_sky`.
    cache_dir : path, bool or None
        Directory of the cache; None (or True) the default (:func:`~.disk_cache.default_cache_dir`);
        False: no disk cache.

    Returns
    -------
    OpenSky
        The sampled sky, from the cache or computed.

    Raises
    ------
    InputError
        A bad ``rays_per_side``, or too many rays for the memory.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> folder = tempfile.TemporaryDirectory()
    >>> open_sky(craft, 16, cache_dir=folder.name).origin
    'computed (stored in cache .../open_sky-....npz)'
    >>> open_sky(craft, 16, cache_dir=folder.name).origin
    'cache .../open_sky-....npz'
    >>> folder.cleanup()
    """
    directory = cache_directory(cache_dir)
    if directory is None:
        return compute_open_sky(craft, rays_per_side, seed)
    if rays_per_side is None:
        rays_per_side = default_sky_rays(int(np.count_nonzero(~clearance(craft).open_sky)))
    return kept_on_disk(
        directory,
        "open_sky",
        geometry_key(craft, _settings(rays_per_side, seed)),
        lambda: compute_open_sky(craft, rays_per_side, seed),
        _encode,
        lambda arrays, origin: _decode(arrays, craft.n_sides, seed, origin),
    )
