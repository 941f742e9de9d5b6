"""Cosine-weighted emission rays from every side, by counter-hash random numbers, in threaded batches.

Each side emits ``g**2`` rays: origins at one uniform point in each of ``g**2`` equal-area strata of its
triangle (a ``g x g`` jittered grid through the area-preserving square-to-triangle map of Heitz 2019),
pushed ``scene.offset_m`` along the side normal; directions cosine-weighted, one in each cell of a
``g x g`` jittered grid through the concentric disk map of Shirley & Chiu 1997, turned by a random
angle about the normal. A seeded permutation pairs points with directions. Random numbers are a hash of
``(seed, side, index)``, so every side's rays are the same bits whatever the thread count or batch size.
View factors (:mod:`.view_factors`) and exchange factors (:mod:`.exchange_factors`) both cast them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TypeVar

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.parallel import map_ranges, thread_count
from sunwind.geometry.progress import advance
from sunwind.geometry.spacecraft import Spacecraft

#: Rays per batch of sides, made, cast and tallied in turn by one thread: ~60 bytes each, ~16 MB.
_BATCH_RAYS = 1 << 18
#: Peak bytes per ray of a batch (origins, directions, levers, hits, tallies; measured 62 to 69).
_RAY_BYTES = 70


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)


T = TypeVar("T")


def map_side_batches(function: Callable[[int, int], T], n: int, rays_per_side: int) -> list[T]:
    """Call ``function(lo, hi)`` on batches of ``range(n)`` of about ``_BATCH_RAYS`` rays; results in order.

    Each batch is made, cast and tallied in turn by one thread, and each batch done advances the
    running progress step (:mod:`sunwind.geometry.progress`). Batch boundaries follow the thread count:
    ``function`` must treat every item on its own.

    Parameters
    ----------
    function : callable
        ``function(lo, hi)`` does items ``lo`` to ``hi - 1``.
    n : int
        Number of items (sides).
    rays_per_side : int
        Rays per item.

    Returns
    -------
    list
        The batches' results, in item order.

    Examples
    --------
    >>> batches = map_side_batches(lambda lo, hi: (lo, hi), 10, 2**17)  # two sides a batch
    >>> [side for lo, hi in batches for side in range(lo, hi)] == list(range(10))
    True
    """
    per_batch = max(1, _BATCH_RAYS // rays_per_side)

    def work(lo: int, hi: int) -> list[T]:
        out = []
        for s in range(lo, hi, per_batch):
            out.append(function(s, min(s + per_batch, hi)))
            advance(min(s + per_batch, hi) - s, n)
        return out

    return [t for chunk in map_ranges(work, n, per_batch) for t in chunk]


def batch_bytes(n: int, rays_per_side: int) -> int:
    """Estimate the peak bytes of the batches :func:`map_side_batches` holds at once.

    Parameters
    ----------
    n : int
        Number of items (sides).
    rays_per_side : int
        Rays per item.

    Returns
    -------
    int
        Peak bytes, one batch per thread at work.

    Examples
    --------
    >>> batch_bytes(10, 256)  # a batch holds up to 1024 sides of 256 rays: the 10 fit in one
    18350080
    """
    per_batch = max(1, _BATCH_RAYS // rays_per_side)
    at_once = min(thread_count(), -(-n // per_batch))
    return _RAY_BYTES * per_batch * rays_per_side * max(1, at_once)


def emission_rays(
    craft: Spacecraft, sides: NDArray[np.int64], grid: int, seed: int
) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float64]]:
    """Make the ``grid**2`` cosine-weighted emission rays of each of some sides.

    Ray ``r`` of ``sides[k]`` is at row ``k grid**2 + r`` (see the module docstring and
    :func:`_emission_rays`); the rays of a side are the same bits whatever else is asked.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    sides : (n,) ndarray of int64
        The emitting sides.
    grid : int
        Strata per axis: ``grid**2`` rays per side.
    seed : int
        Seed of the random numbers, in [0, 2**64).

    Returns
    -------
    origins : (n * grid**2, 3) ndarray of float32
        Scene coordinates, pushed off the surface.
    directions : (n * grid**2, 3) ndarray of float32
        Unit, body frame, cosine-weighted about the side normal.
    levers : (n * grid**2, 3) ndarray of float64
        Surface point minus side centroid [m].

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> origins, directions, levers = emission_rays(craft, np.array([0, 1]), 2, seed=7)
    >>> origins.shape, bool((directions[:4] @ craft.side_normals[0] > 0).all())
    ((8, 3), True)
    """
    scene = craft.scene
    return _emission_rays(
        craft.triangles,
        craft.side_facet,
        craft.side_normals,
        np.asarray(sides, dtype=np.int64),
        grid,
        np.uint64(seed),
        scene.centre,
        scene.half_size,
        scene.offset_m,
    )


@numba.njit(cache=True, nogil=True)
def _mix(z: np.uint64) -> np.uint64:
    """SplitMix64 finaliser: a bijective hash of 64-bit integers."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@numba.njit(cache=True, nogil=True)
def side_key(seed: np.uint64, side: int) -> np.uint64:
    """Make the key of the random numbers of a side's rays under a seed.

    Parameters
    ----------
    seed : numpy.uint64
        The seed.
    side : int
        The side.

    Returns
    -------
    numpy.uint64
        A hash of both.

    Examples
    --------
    >>> import numpy as np
    >>> side_key(np.uint64(7), 3) == side_key(np.uint64(7), 3), side_key(np.uint64(7), 3) == side_key(
    ...     np.uint64(7), 4)
    (True, False)
    """
    return _mix(seed ^ _mix(np.uint64(side) + _GOLDEN))


@numba.njit(cache=True, nogil=True)
def uniform(key: np.uint64, index: int) -> float:
    """Draw a random number in [0, 1) as a hash of a key and an index.

    Parameters
    ----------
    key : numpy.uint64
        The key (:func:`side_key`).
    index : int
        Which number of the key's.

    Returns
    -------
    float
        The number, 53 random bits.

    Examples
    --------
    >>> import numpy as np
    >>> key = side_key(np.uint64(7), 3)
    >>> round(uniform(key, 0), 6), uniform(key, 0) == uniform(key, 0)
    (0.189562, True)
    """
    return float(_mix(key + np.uint64(index + 1) * _GOLDEN) >> np.uint64(11)) * 2.0**-53


@numba.njit(cache=True, nogil=True)
def _disk(a: float, b: float) -> tuple[float, float]:
    """Concentric map (Shirley & Chiu 1997) of the unit square onto the unit disk, area-preserving."""
    a, b = 2 * a - 1, 2 * b - 1
    if a == 0 and b == 0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        r, phi = a, (math.pi / 4) * (b / a)
    else:
        r, phi = b, math.pi / 2 - (math.pi / 4) * (a / b)
    return r * math.cos(phi), r * math.sin(phi)


@numba.njit(cache=True, nogil=True)
def square_to_triangle(a: float, b: float) -> tuple[float, float]:
    """Map the unit square onto a triangle's barycentrics, area-preserving and with low distortion.

    The map of Heitz (2019).

    Parameters
    ----------
    a, b : float
        A point of the unit square.

    Returns
    -------
    tuple of float
        Barycentrics ``(b1, b2)``, with ``b1 + b2 <= 1``.

    Examples
    --------
    >>> square_to_triangle(0.5, 0.25), square_to_triangle(0.25, 0.5)
    ((0.375, 0.125), (0.125, 0.375))
    """
    if b > a:
        a *= 0.5
        return a, b - a
    b *= 0.5
    return a - b, b


@numba.njit(cache=True, nogil=True)
def _frame(n: NDArray[np.float64], angle: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two unit tangents completing the unit normal ``n`` to a right-handed frame, turned by ``angle``
    about it (branchless frame of Duff et al. 2017)."""
    sign = math.copysign(1.0, n[2])
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    t1 = np.array([1 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]])
    t2 = np.array([b, sign + n[1] * n[1] * a, -n[1]])
    c, s = math.cos(angle), math.sin(angle)
    return c * t1 + s * t2, c * t2 - s * t1


@numba.njit(cache=True, nogil=True)
def _emission_rays(
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    sides: NDArray[np.int64],
    grid: int,
    seed: np.uint64,
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float64]]:
    """The ``grid**2`` emission rays of each of ``sides`` (see the module docstring).

    Returns
    -------
    origins : (count * grid**2, 3) float32
        Scene coordinates, pushed ``offset_m`` off the surface.
    directions : (count * grid**2, 3) float32
        Unit, body frame, cosine-weighted about the side normal.
    lever : (count * grid**2, 3) float64
        Surface point minus side centroid [m].
    """
    n = grid * grid
    count = sides.shape[0]
    origins = np.empty((count * n, 3), dtype=np.float32)
    directions = np.empty((count * n, 3), dtype=np.float32)
    lever = np.empty((count * n, 3))
    order = np.empty(n, dtype=np.int64)
    third = 1.0 / 3.0
    for k in range(count):
        s = sides[k]
        key = side_key(seed, s)
        # random numbers: direction jitter [0, 2n), point jitter [2n, 4n), pairing [4n, 5n), turn 5n
        # (above 5n: picks of the exchange factors' chains)
        for i in range(n):
            order[i] = i
        for i in range(n - 1, 0, -1):
            j = int(uniform(key, 4 * n + i) * (i + 1))
            order[i], order[j] = order[j], order[i]
        normal = normals[s]
        t1, t2 = _frame(normal, 2 * math.pi * uniform(key, 5 * n))
        corners = triangles[side_facet[s]]
        for i in range(n):
            x, y = _disk(
                (i // grid + uniform(key, 2 * i)) / grid, (i % grid + uniform(key, 2 * i + 1)) / grid
            )
            z = math.sqrt(max(0.0, 1.0 - x * x - y * y))
            c = order[i]
            b1, b2 = square_to_triangle(
                (c // grid + uniform(key, 2 * n + 2 * c)) / grid,
                (c % grid + uniform(key, 2 * n + 2 * c + 1)) / grid,
            )
            b0 = 1.0 - b1 - b2
            r = k * n + i
            for d in range(3):
                point = b0 * corners[0, d] + b1 * corners[1, d] + b2 * corners[2, d]
                lever[r, d] = (
                    (b0 - third) * corners[0, d] + (b1 - third) * corners[1, d] + (b2 - third) * corners[2, d]
                )
                origins[r, d] = (point + offset_m * normal[d] - centre[d]) / half_size
                directions[r, d] = x * t1[d] + y * t2[d] + z * normal[d]
    return origins, directions, lever
