"""Direct SRP of a self-shadowing model by a z-buffer seen from the Sun: the reference for CAD-like meshes.

Every facet is projected on the plane normal to the Sun direction ``u``, in coordinates ``(X, Y)`` along
two unit vectors ``e1``, ``e2`` (``e1 x e2 = u``) and its height ``H`` along ``u`` (toward the Sun), all
relative to the centre of the model's bounding box. The projected bounding box is cut into square pixels
of side ``pixel_m``, each holding one sample point drawn uniformly inside it (jittered-stratified
sampling, from a hash of the pixel's indices and ``seed``: the same bits on every run, whatever the
tiling or the number of threads). A sample is struck by the facet covering it with the greatest height:
the first the Sun's light meets. The side it strikes is the facet's front where ``n . u > 0``, else its
back; where the facet has no such side (the inside of a closed body, the back of a one-sided sheet) the
light is blocked and adds nothing, as in the solver (METHOD.md "Surfaces and sides"). Each sample of a
side with outward normal ``n``, ``cos = n . u``, carries the projected area ``dA = pixel_m^2`` and, by
eq. (4) of METHOD.md "Direct solar pressure" at ``P = 1 Pa``,

    dF = -dA [ (1 - sigma - rho_s) u + (2 rho_s cos + (2/3) rho_d) n ],  rho_s = rho beta,
    rho_d = rho (1 - beta),   dM = (x - r_ref) x dF,

with ``x`` the sample's point on the struck facet's plane (float64). Coincident facets (overlapping in
one plane) tie, and round-off picks one: the answer is exact there only when both strike sides of the
same normal and optics (a coplanar layer of the face's material).

**Memory.** Facets are rasterised by numba in tiles of 512 x 512 pixels (a height, a facet and a sample
point per pixel, about 8 MB per thread), so memory does not grow with the image: a 10 m model at 1 mm
is 10^8 samples in some 400 tiles.

**Error.** Stratified sampling has no bias; only pixels an outline crosses add noise, so the error
falls as ``pixel_m^1.5`` (about ``0.5 pixel_m^2 sqrt(L / pixel_m)`` in area for outlines of total
length ``L``). Each run estimates its own standard error by collapsed strata: pixels are paired along
``X`` and each pair's squared difference of contributions summed, an estimate of the variance that is
never too small on average (it adds the pair's true difference to the sampling noise).
:func:`converged_reference` halves the pixel and compares. Shares no code with the shadow pass and does
not use Embree; imports only :mod:`sunwind.geometry`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.directions import finite_point, unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.spacecraft import Spacecraft

__all__ = [
    "ConvergenceEstimate",
    "ShadowReference",
    "converged_reference",
    "projected_area_loads",
    "shadow_reference",
]

#: Pixels along each side of a tile (even: pixels pair up along X within a tile).
TILE = 512
#: Most groups of tiles whose sums are kept apart (then summed in a fixed order, so the result does not
#: depend on the number of threads), and most bytes those per-group sums may take.
_GROUPS, _GROUP_BYTES = 32, 64 * 2**20
#: Most pixels one call may ask for (about 20 s of rasterising on one core).
MAX_SAMPLES = 2 * 10**9
#: Standard errors in :attr:`ConvergenceEstimate.force_error_N` and the other error bounds.
ERROR_SIGMAS = 3.0


@dataclass(frozen=True, eq=False)
class ShadowReference:
    """Direct solar pressure on a model at one Sun direction, at a radiation pressure of 1 Pa.

    Attributes
    ----------
    sun_vector : (3,) float64
        Unit vector toward the Sun, body frame.
    force_N : (3,) float64
        Force [N] at ``P = 1 Pa``, i.e. the force per unit pressure [m^2].
    torque_Nm : (3,) float64
        Torque [N m] about ``reference_point_m`` at ``P = 1 Pa``.
    reference_point_m : (3,) float64
    projected_area_m2 : float
        Area of the samples that strike a side, seen from the Sun [m^2].
    lit_area_m2 : (n_sides,) float64
        Lit area of each side [m^2]: its samples' ``dA / cos``.
    lit_centroid_m : (n_sides, 3) float64
        Mean point of each side's samples [m]; the side's centroid where it has none.
    force_sigma_N, torque_sigma_Nm, projected_area_sigma_m2 : float
        Standard errors (collapsed strata) of ``|force_N|`` [N], ``|torque_Nm|`` [N m] and the projected
        area [m^2].
    pixel_m : float
        Pixel side [m].
    seed : int
        Seed of the sample points.
    samples : int
        Pixels in the image.

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> ref = shadow_reference(black, (0.0, 0.0, 1.0), pixel_m=0.05)
    >>> round(ref.projected_area_m2, 9), ref.pixel_m
    (1.0, 0.05)
    """

    sun_vector: NDArray[np.float64]
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]
    projected_area_m2: float
    lit_area_m2: NDArray[np.float64]
    lit_centroid_m: NDArray[np.float64]
    force_sigma_N: float
    torque_sigma_Nm: float
    projected_area_sigma_m2: float
    pixel_m: float
    seed: int
    samples: int


@dataclass(frozen=True, eq=False)
class ConvergenceEstimate:
    """The reference at two resolutions, their difference, and the error bound of the finer.

    Attributes
    ----------
    coarse, fine : ShadowReference
        At ``pixel_m`` (seed ``seed``) and ``pixel_m / 2`` (seed ``seed + 1``).
    force_difference_N, torque_difference_Nm, projected_area_difference_m2 : float
        ``|fine - coarse|`` of the force [N], torque [N m] and projected area [m^2]: about the error of
        ``coarse``.
    force_error_N, torque_error_Nm, projected_area_error_m2 : float
        Error bound of ``fine``: the larger of the difference and ``ERROR_SIGMAS`` of its standard error
        (a difference of two noisy runs can be small by chance, a standard error cannot see a bias).
    seconds : float
        Wall time of both runs [s].

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> estimate = converged_reference(black, (0.0, 0.0, 1.0), pixel_m=0.05)
    >>> estimate.fine.pixel_m, bool(estimate.force_error_N < 1e-6)
    (0.025, True)
    """

    coarse: ShadowReference
    fine: ShadowReference
    force_difference_N: float
    torque_difference_Nm: float
    projected_area_difference_m2: float
    force_error_N: float
    torque_error_Nm: float
    projected_area_error_m2: float
    seconds: float


@dataclass(frozen=True, eq=False)
class _Image:
    """What the kernel reads: projected facets, their pixel boxes and struck sides, the grid, and each
    side's force per sample with what turns sample points into torque arms."""

    projected: NDArray[np.float64]  # (n_facets, 3, 3): corners' (X, Y, H) [m]
    box: NDArray[np.int64]  # (n_facets, 4): first and last pixel along X and Y
    struck: NDArray[np.int64]  # (n_facets,): side the Sun strikes, -1 for none
    shape: NDArray[np.int64]  # (2,): pixels along X (even) and Y
    low: NDArray[np.float64]  # (2,): (X, Y) of the image's corner [m]
    per_sample: NDArray[np.float64]  # (n_sides, 3): force of one sample [N]
    frame: NDArray[np.float64]  # (3, 3): rows e1, e2, u
    offset: NDArray[np.float64]  # (3,): centre - reference point [m]


def shadow_reference(
    craft: Spacecraft,
    sun_vector: Sequence[float] | NDArray,
    pixel_m: float,
    reference_point_m: Sequence[float] | NDArray | None = None,
    seed: int = 0,
) -> ShadowReference:
    """Direct SRP of ``craft`` with self-shadowing at ``P = 1 Pa``, by a z-buffer of pixel ``pixel_m``.

    Parameters
    ----------
    craft : Spacecraft
    sun_vector : (3,) float
        Direction toward the Sun, body frame (normalised here).
    pixel_m : float
        Pixel side [m] in the plane normal to the Sun.
    reference_point_m : (3,) float, optional
        Torque reference [m]; default the model's (``craft.default_reference``).
    seed : int
        Seed of the sample points (>= 0).

    Returns
    -------
    ShadowReference

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box((1.0, 2.0, 3.0)), uniform=Material("black", 0.0, 0.0))
    >>> ref = shadow_reference(black, (0.0, 0.0, 1.0), pixel_m=0.01)
    >>> ref.force_N.round(9) + 0.0, round(ref.projected_area_m2, 9)  # F = -A_proj u: the 1 m x 2 m top
    (array([ 0.,  0., -2.]), 2.0)
    """
    u = unit_vector(sun_vector, "sun_vector")
    if not (isinstance(pixel_m, (int, float)) and math.isfinite(pixel_m) and pixel_m > 0):
        raise InputError(f"pixel_m {pixel_m!r} must be a finite number > 0", parameters=("pixel_m",))
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError(f"seed {seed!r} must be a whole number >= 0", parameters=("seed",))
    reference = (
        np.array(craft.default_reference[0])
        if reference_point_m is None
        else finite_point(reference_point_m, "reference_point_m")
    )
    e1 = np.cross(u, np.eye(3)[np.argmin(np.abs(u))])
    e1 /= np.linalg.norm(e1)
    frame = np.stack([e1, np.cross(u, e1), u])
    centre = craft.bounds.mean(axis=0)
    projected = np.ascontiguousarray((craft.triangles - centre) @ frame.T)
    flat = projected[:, :, :2]
    low = flat.min(axis=(0, 1))
    shape = np.floor((flat.max(axis=(0, 1)) - low) / pixel_m).astype(np.int64) + 1
    shape[0] += shape[0] % 2  # an even width: every pixel has a partner
    if shape.prod() > MAX_SAMPLES:
        raise InputError(
            f"pixel_m {pixel_m:g} asks for {shape.prod():.3g} samples, more than {MAX_SAMPLES:.0e}",
            hint="give a larger pixel_m",
            parameters=("pixel_m",),
        )
    facing = craft.facet_normals @ u
    struck = np.where(facing > 0, craft.facet_sides[:, 0], craft.facet_sides[:, 1])
    struck[facing == 0] = -1
    first = np.floor((flat.min(axis=1) - low) / pixel_m).astype(np.int64)
    last = np.minimum(np.floor((flat.max(axis=1) - low) / pixel_m).astype(np.int64), shape - 1)
    dA = pixel_m**2
    cosine = craft.side_normals @ u
    per_sample = dA * projected_area_loads(craft, u)
    image = _Image(
        projected, np.column_stack([first, last]), struck, shape, low, per_sample, frame, centre - reference
    )
    counts, sums, spread = _rasterise(image, pixel_m, seed)
    points = centre * counts[:, None] + sums @ frame  # sum of each side's sample points [m]
    force = (counts[:, None] * per_sample).sum(axis=0)
    torque = np.cross(points - counts[:, None] * reference, per_sample).sum(axis=0)
    lit = counts > 0
    centroid = np.array(craft.side_centroids)
    centroid[lit] = points[lit] / counts[lit, None]
    return ShadowReference(
        sun_vector=u,
        force_N=force,
        torque_Nm=torque,
        reference_point_m=reference,
        projected_area_m2=float(counts.sum() * dA),
        lit_area_m2=np.where(lit, counts * dA / np.where(lit, cosine, 1.0), 0.0),
        lit_centroid_m=centroid,
        force_sigma_N=float(np.sqrt(spread[:3].sum())),
        torque_sigma_Nm=float(np.sqrt(spread[3:6].sum())),
        projected_area_sigma_m2=float(dA * np.sqrt(spread[6])),
        pixel_m=float(pixel_m),
        seed=int(seed),
        samples=int(shape.prod()),
    )


def converged_reference(
    craft: Spacecraft,
    sun_vector: Sequence[float] | NDArray,
    pixel_m: float,
    reference_point_m: Sequence[float] | NDArray | None = None,
    seed: int = 0,
) -> ConvergenceEstimate:
    """:func:`shadow_reference` at ``pixel_m`` and at ``pixel_m / 2`` (seed ``seed + 1``, so the two sample
    sets are independent), their difference, and the error bound of the finer run.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    sun_vector : (3,) array_like
        Direction toward the Sun, body frame.
    pixel_m : float
        Pixel of the coarser run [m]; the finer one uses half.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default as :func:`shadow_reference`.
    seed : int, optional
        Seed of the coarser run; the finer one uses ``seed + 1``.

    Returns
    -------
    ConvergenceEstimate
        Both references, their differences and the error bound of the finer one.

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> grey = build_spacecraft(box(), uniform=Material("grey", 0.5, 0.5))
    >>> estimate = converged_reference(grey, (1.0, 2.0, 3.0), pixel_m=0.005)
    >>> bool(estimate.force_error_N < 1e-3 * np.linalg.norm(estimate.fine.force_N))
    True
    """
    start = time.perf_counter()
    coarse = shadow_reference(craft, sun_vector, pixel_m, reference_point_m, seed)
    fine = shadow_reference(craft, sun_vector, pixel_m / 2, reference_point_m, seed + 1)
    force = float(np.linalg.norm(fine.force_N - coarse.force_N))
    torque = float(np.linalg.norm(fine.torque_Nm - coarse.torque_Nm))
    area = abs(fine.projected_area_m2 - coarse.projected_area_m2)
    return ConvergenceEstimate(
        coarse=coarse,
        fine=fine,
        force_difference_N=force,
        torque_difference_Nm=torque,
        projected_area_difference_m2=area,
        force_error_N=max(force, ERROR_SIGMAS * fine.force_sigma_N),
        torque_error_Nm=max(torque, ERROR_SIGMAS * fine.torque_sigma_Nm),
        projected_area_error_m2=max(area, ERROR_SIGMAS * fine.projected_area_sigma_m2),
        seconds=time.perf_counter() - start,
    )


def projected_area_loads(craft: Spacecraft, sun_vector: NDArray[np.float64]) -> NDArray[np.float64]:
    """Eq. (4) of METHOD.md at ``P = 1 Pa`` per unit of each side's area projected along the unit
    ``sun_vector`` [N/m^2], (n_sides, 3): the force of one sample of unit pixel area.

    Parameters
    ----------
    craft : Spacecraft
        The model, with the optics of each side.
    sun_vector : (3,) float64
        Unit direction toward the Sun, body frame.

    Returns
    -------
    (n_sides, 3) float64
        Force per unit projected area of each side [N/m^2] at 1 Pa.

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> white = build_spacecraft(box(), uniform=Material("white", 1.0, 1.0))  # a mirror: 2 cos n
    >>> top = white.side_normals[:, 2] > 0.5
    >>> projected_area_loads(white, np.array([0.0, 0.0, 1.0]))[top][0] + 0.0
    array([ 0.,  0., -2.])
    """
    rho, beta, sigma = craft.side_optics.T
    normal = craft.side_normals
    cosine = normal @ sun_vector
    return -(
        (1 - sigma - rho * beta)[:, None] * sun_vector
        + (2 * rho * beta * cosine + (2 / 3) * rho * (1 - beta))[:, None] * normal
    )


def _rasterise(image: _Image, pixel_m: float, seed: int) -> tuple[NDArray, NDArray, NDArray]:
    """Samples per side (n_sides,), the sums of their ``(X, Y, H)`` (n_sides, 3) and the pairs' squared
    differences of force, torque and count (7,), tile by tile on the shared threads; groups of tiles are
    summed apart, then in a fixed order."""
    n_sides = len(image.per_sample)
    tiles = -(-image.shape // TILE)
    n_tiles = int(tiles.prod())
    groups = max(1, min(n_tiles, _GROUPS, _GROUP_BYTES // (32 * max(n_sides, 1))))
    bounds = np.linspace(0, n_tiles, groups + 1).astype(np.int64)
    counts = np.zeros((groups, n_sides), dtype=np.int64)
    sums = np.zeros((groups, n_sides, 3))
    spread = np.zeros((groups, 7))

    def run(lo: int, hi: int) -> None:
        for group in range(lo, hi):  # a few groups of tiles per thread
            _raster_tiles(
                image.projected, image.box, image.struck, image.per_sample, image.frame, image.offset,
                int(bounds[group]), int(bounds[group + 1]), int(tiles[0]), int(image.shape[0]),
                int(image.shape[1]), float(image.low[0]), float(image.low[1]), float(pixel_m), int(seed),
                counts[group], sums[group], spread[group],
            )  # fmt: skip

    map_ranges(run, groups, 1)
    return counts.sum(axis=0).astype(np.float64), sums.sum(axis=0), spread.sum(axis=0)


@numba.njit(cache=True, nogil=True, inline="always")
def _mix(z: np.uint64) -> np.uint64:  # pragma: no cover - compiled
    """SplitMix64's finaliser: a well-mixed 64-bit hash of ``z``."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


@numba.njit(cache=True, nogil=True, inline="always")
def _uniform(seed: int, i: int, j: int, k: int) -> float:  # pragma: no cover - compiled
    """A uniform number in [0, 1) fixed by ``seed``, pixel ``(i, j)`` and coordinate ``k``."""
    golden = np.uint64(0x9E3779B97F4A7C15)
    z = _mix(np.uint64(seed) * golden + np.uint64(k))
    z = _mix(z + np.uint64(i) * golden)
    z = _mix(z + np.uint64(j) * golden)
    return float(z >> np.uint64(11)) * (1.0 / 9007199254740992.0)


@numba.njit(cache=True, nogil=True)
def _raster_tiles(
    projected, box, struck, per_sample, frame, offset, tile_lo, tile_hi, tiles_x, nx, ny, x0, y0, pixel,
    seed, counts, sums, spread,
):  # fmt: skip  # pragma: no cover - compiled
    """Rasterise tiles ``tile_lo`` to ``tile_hi`` (row-major, ``tiles_x`` per row) of the ``nx`` x ``ny``
    image: per pixel the facet of greatest height ``H`` at its sample point. Add each struck side's
    samples to ``counts``, their ``(X, Y, H)`` to ``sums``, and the squared differences of force, torque
    and count between the pixels ``(2k, j)`` and ``(2k + 1, j)`` to ``spread``."""
    height = np.empty((TILE, TILE))
    facet = np.empty((TILE, TILE), dtype=np.int64)
    px = np.empty((TILE, TILE))
    py = np.empty((TILE, TILE))
    pair = np.zeros((2, 7))
    for t in range(tile_lo, tile_hi):
        i0, j0 = (t % tiles_x) * TILE, (t // tiles_x) * TILE
        i1, j1 = min(i0 + TILE, nx), min(j0 + TILE, ny)
        for a in range(i1 - i0):
            for b in range(j1 - j0):
                height[a, b] = -np.inf
                facet[a, b] = -1
                px[a, b] = x0 + (i0 + a + _uniform(seed, i0 + a, j0 + b, 0)) * pixel
                py[a, b] = y0 + (j0 + b + _uniform(seed, i0 + a, j0 + b, 1)) * pixel
        for f in range(len(projected)):
            a_lo, a_hi = max(box[f, 0], i0), min(box[f, 2], i1 - 1)
            b_lo, b_hi = max(box[f, 1], j0), min(box[f, 3], j1 - 1)
            if a_lo > a_hi or b_lo > b_hi:
                continue
            xa, ya, ha = projected[f, 0, 0], projected[f, 0, 1], projected[f, 0, 2]
            xb, yb, hb = projected[f, 1, 0] - xa, projected[f, 1, 1] - ya, projected[f, 1, 2] - ha
            xc, yc, hc = projected[f, 2, 0] - xa, projected[f, 2, 1] - ya, projected[f, 2, 2] - ha
            det = xb * yc - xc * yb
            if det == 0.0:
                continue  # edge-on to the Sun: covers no sample
            for a in range(a_lo - i0, a_hi - i0 + 1):
                for b in range(b_lo - j0, b_hi - j0 + 1):
                    dx, dy = px[a, b] - xa, py[a, b] - ya
                    w1 = (dx * yc - xc * dy) / det
                    w2 = (xb * dy - dx * yb) / det
                    if w1 < 0.0 or w2 < 0.0 or w1 + w2 > 1.0:
                        continue
                    h = ha + w1 * hb + w2 * hc
                    if h > height[a, b]:
                        height[a, b] = h
                        facet[a, b] = f
        for a in range(0, i1 - i0, 2):
            for b in range(j1 - j0):
                for k in range(2):
                    pair[k, :] = 0.0
                    f = facet[a + k, b]
                    if f < 0 or struck[f] < 0:
                        continue  # nothing there, or light blocked by a blind side
                    s = struck[f]
                    x, y, h = px[a + k, b], py[a + k, b], height[a + k, b]
                    counts[s] += 1
                    sums[s, 0] += x
                    sums[s, 1] += y
                    sums[s, 2] += h
                    r0 = offset[0] + x * frame[0, 0] + y * frame[1, 0] + h * frame[2, 0]
                    r1 = offset[1] + x * frame[0, 1] + y * frame[1, 1] + h * frame[2, 1]
                    r2 = offset[2] + x * frame[0, 2] + y * frame[1, 2] + h * frame[2, 2]
                    f0, f1, f2 = per_sample[s, 0], per_sample[s, 1], per_sample[s, 2]
                    pair[k, 0], pair[k, 1], pair[k, 2] = f0, f1, f2
                    pair[k, 3] = r1 * f2 - r2 * f1
                    pair[k, 4] = r2 * f0 - r0 * f2
                    pair[k, 5] = r0 * f1 - r1 * f0
                    pair[k, 6] = 1.0
                for c in range(7):
                    spread[c] += (pair[0, c] - pair[1, c]) ** 2
