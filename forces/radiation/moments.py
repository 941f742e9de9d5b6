"""Block moments of the direct SRP force law (eq. 4, :mod:`sunwind.forces.radiation.law`) and the kernel
that sums it over the lit sides of one attitude.

Sides come in the fixed blocks of :attr:`sunwind.geometry.rays.shadows.SideSampler.side_block`. Over a block
whose every side faces the Sun the sum of eq. (4) is a polynomial in ``u_sun``: with ``c = n . u``,
``alpha = 1 - sigma - rho_s``, ``b = 2 rho_s`` and ``g = (2/3) rho_d``,

    sum A [alpha c u + (b c^2 + g c) n] = (a . u) u + T(u, u) + G u,
    a = sum A alpha n,   T = sum A b n (x) n (x) n,   G = sum A g n (x) n,

and likewise for the torque about a point of the block, the lit area, the projected area and the
absorbed projected area. These block moments are made once per model; an attitude then costs one
contraction per such block plus a correction on its sides that are not wholly lit (their full share
taken off, their lit share put back), instead of a pass over all its sides. Blocks that face only in
part are summed side by side.

The same pass sums any per-side weights ``w`` (k of them) times the direct power per unit flux a
side receives, ``A f (n . u)`` with ``f`` its lit share: over a block that faces, ``W u`` with the
block moment ``W = sum A w (x) n`` (:func:`weight_moments`). Inter-reflection takes what the direct
light hands to it this way (:mod:`sunwind.forces.reflection.plan`).
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR

#: Slots of a row of sums of :func:`accumulate_forces` (``P = 1``): force (3), torque (3), lit
#: area, projected area, absorbed projected area (projected area weighted by absorptivity: absorbed
#: power over flux); then the weighted sums of the reflection plan's channels.
FORCE, TORQUE, LIT_AREA, PROJECTED, ABSORBED, TOTALS = 0, 3, 6, 7, 8, 9
#: Least bound on ``n . u`` over a block for its moments to stand for its sides: far above round-off,
#: so every side of such a block certainly faces the Sun and is among the sides summed.
_FACING_MARGIN = 1e-9
#: Slots of one block's moments (module docstring; :func:`block_moments`): block point (3), a (3),
#: G (9), T (27), R (9), H (9), Q (27), area (1), projected (3), absorbed (3), number of sides (1).
_POINT, _A, _G, _T, _R, _H, _Q, _AREA, _PROJECTED, _ABSORBED, _COUNT, MOMENT_SLOTS = (
    0,
    3,
    6,
    15,
    42,
    51,
    60,
    87,
    88,
    91,
    94,
    95,
)


def block_moments(
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    optics: NDArray[np.float64],
    centroids: NDArray[np.float64],
    side_block: NDArray[np.int64],
    n_blocks: int,
) -> NDArray[np.float64]:
    """Compute the moments of each block's sides (module docstring).

    Torques are about each block's area centroid ``o`` (slots 0-2), with ``r = centroid - o``:
    ``R = sum A alpha r (x) n``, ``H = sum A g (r x n) (x) n``, ``Q = sum A b (r x n) (x) n (x) n``.

    Parameters
    ----------
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    areas : (n_sides,) float64
        Area of each side [m^2].
    optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of each side: reflectivity, specular share of it, transmissivity.
    centroids : (n_sides, 3) float64
        Centroid of each side [m].
    side_block : (n_sides,) int64
        Block of each side.
    n_blocks : int
        Number of blocks.

    Returns
    -------
    (n_blocks, MOMENT_SLOTS) ndarray of float64
        Block point, ``a``, ``G``, ``T``, ``R``, ``H``, ``Q``, area, projected and absorbed area vectors and
        the number of sides, flattened.

    References
    ----------
    Shmatov and Mordvinkin (2013), eq. (4), the force law whose block sums these are.

    Examples
    --------
    A black unit plate facing +z: ``a`` is its normal times its area:

    >>> import numpy as np
    >>> normals, areas = np.array([[0.0, 0.0, 1.0]]), np.ones(1)
    >>> optics, centroids = np.zeros((1, 3)), np.zeros((1, 3))  # black: rho = beta = sigma = 0
    >>> side_block = np.zeros(1, dtype=np.int64)
    >>> moments = block_moments(normals, areas, optics, centroids, side_block, 1)
    >>> moments.shape, moments[0, 3:6]
    ((1, 95), array([0., 0., 1.]))
    """
    rho, beta, sigma = optics.T
    rho_s = rho * beta
    alpha, b, g = (1.0 - sigma - rho_s) * areas, 2.0 * rho_s * areas, LAMBERT_FACTOR * (rho - rho_s) * areas

    def per_block(values: NDArray[np.float64]) -> NDArray[np.float64]:
        flat = values.reshape(len(values), -1)
        out = np.zeros((n_blocks, flat.shape[1]))
        np.add.at(out, side_block, flat)
        return out

    block_area = per_block(areas)
    point = per_block(areas[:, None] * centroids) / np.where(block_area > 0, block_area, 1.0)
    r = centroids - point[side_block]
    r_cross_n = np.cross(r, normals)
    nn = normals[:, :, None] * normals[:, None, :]
    nnn = normals[:, :, None, None] * nn[:, None]
    parts = (
        point,
        per_block(alpha[:, None] * normals),
        per_block(g[:, None, None] * nn),
        per_block(b[:, None, None, None] * nnn),
        per_block(alpha[:, None, None] * r[:, :, None] * normals[:, None, :]),
        per_block(g[:, None, None] * r_cross_n[:, :, None] * normals[:, None, :]),
        per_block(b[:, None, None, None] * r_cross_n[:, :, None, None] * nn[:, None]),
        block_area,
        per_block(areas[:, None] * normals),
        per_block(((1.0 - rho - sigma) * areas)[:, None] * normals),
        per_block(np.ones(len(areas))),
    )
    return np.ascontiguousarray(np.concatenate(parts, axis=1))


def weight_moments(
    weights: NDArray[np.float64],
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    side_block: NDArray[np.int64],
    n_blocks: int,
) -> NDArray[np.float64]:
    """Block moments ``W = sum A w (x) n`` of per-side ``weights`` over each block's sides.

    Parameters
    ----------
    weights : (n_sides, k) float64
        The weights ``w`` of each side.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    areas : (n_sides,) float64
        Area of each side [m^2].
    side_block : (n_sides,) int64
        Block of each side.
    n_blocks : int
        Number of blocks.

    Returns
    -------
    (n_blocks, 3 k) ndarray of float64
        ``W`` flattened: ``W[b, 3 j + d]`` for weight ``j`` and axis ``d`` [m^2].

    Examples
    --------
    >>> import numpy as np
    >>> normals, areas = np.array([[0.0, 0.0, 1.0]]), np.ones(1)
    >>> optics, centroids = np.zeros((1, 3)), np.zeros((1, 3))  # black: rho = beta = sigma = 0
    >>> side_block = np.zeros(1, dtype=np.int64)
    >>> weight_moments(np.array([[2.0]]), normals, areas, side_block, 1)
    array([[0., 0., 2.]])
    """
    terms = (areas[:, None, None] * weights[:, :, None] * normals[:, None, :]).reshape(len(areas), -1)
    out = np.zeros((n_blocks, terms.shape[1]))
    np.add.at(out, side_block, terms)
    return out


@numba.njit(cache=True, nogil=True, fastmath=True)
def _add_side(
    s: int,
    lit_area: float,
    point: NDArray[np.float64],
    reference: NDArray[np.float64],
    normals: NDArray[np.float64],
    optics: NDArray[np.float64],
    u: NDArray[np.float64],
    weights: NDArray[np.float64] | None,
    scale: float,
    row: NDArray[np.float64],
) -> None:
    """Add ``scale`` times side ``s``'s eq. (4) force over ``lit_area`` [m^2] with ``P = 1``, acting at
    ``point`` [m], its torque about ``reference`` [m], its areas and its ``weights`` times its
    projected area, to the totals ``row``."""
    r0, r1, r2 = point[0] - reference[0], point[1] - reference[1], point[2] - reference[2]
    u0, u1, u2 = u[0], u[1], u[2]
    n0, n1, n2 = normals[s, 0], normals[s, 1], normals[s, 2]
    cos = n0 * u0 + n1 * u1 + n2 * u2
    rho = optics[s, 0]
    rho_s = rho * optics[s, 1]
    area = scale * lit_area
    a = -area * cos * (1.0 - optics[s, 2] - rho_s)
    b = -area * cos * (2.0 * rho_s * cos + LAMBERT_FACTOR * (rho - rho_s))
    f0, f1, f2 = a * u0 + b * n0, a * u1 + b * n1, a * u2 + b * n2
    row[FORCE] += f0
    row[FORCE + 1] += f1
    row[FORCE + 2] += f2
    row[TORQUE] += r1 * f2 - r2 * f1
    row[TORQUE + 1] += r2 * f0 - r0 * f2
    row[TORQUE + 2] += r0 * f1 - r1 * f0
    row[LIT_AREA] += area
    row[PROJECTED] += area * cos
    row[ABSORBED] += area * cos * (1.0 - rho - optics[s, 2])
    if weights is not None:
        for j in range(weights.shape[1]):
            row[TOTALS + j] += area * cos * weights[s, j]


@numba.njit(cache=True, nogil=True, fastmath=True)
def _add_moments(m: NDArray[np.float64], u: NDArray[np.float64], ref: NDArray[np.float64], row) -> None:
    """Add one block's totals from its moments ``m`` (``P = 1``, torque about ``ref``) to ``row``."""
    au = m[_A] * u[0] + m[_A + 1] * u[1] + m[_A + 2] * u[2]
    force = np.empty(3)
    local = np.empty(3)
    for k in range(3):
        gu = ru = hu = 0.0
        tuu = quu = 0.0
        for i in range(3):
            gu += m[_G + 3 * k + i] * u[i]
            ru += m[_R + 3 * k + i] * u[i]
            hu += m[_H + 3 * k + i] * u[i]
            for j in range(3):
                tuu += m[_T + 9 * k + 3 * i + j] * u[i] * u[j]
                quu += m[_Q + 9 * k + 3 * i + j] * u[i] * u[j]
        force[k] = -(au * u[k] + tuu + gu)
        local[k] = ru  # R u for now; crossed with u below
        row[TORQUE + k] -= quu + hu
    # (R u) x u
    row[TORQUE] -= local[1] * u[2] - local[2] * u[1]
    row[TORQUE + 1] -= local[2] * u[0] - local[0] * u[2]
    row[TORQUE + 2] -= local[0] * u[1] - local[1] * u[0]
    d0, d1, d2 = m[_POINT] - ref[0], m[_POINT + 1] - ref[1], m[_POINT + 2] - ref[2]
    row[FORCE] += force[0]
    row[FORCE + 1] += force[1]
    row[FORCE + 2] += force[2]
    row[TORQUE] += d1 * force[2] - d2 * force[1]
    row[TORQUE + 1] += d2 * force[0] - d0 * force[2]
    row[TORQUE + 2] += d0 * force[1] - d1 * force[0]
    row[LIT_AREA] += m[_AREA]
    row[PROJECTED] += m[_PROJECTED] * u[0] + m[_PROJECTED + 1] * u[1] + m[_PROJECTED + 2] * u[2]
    row[ABSORBED] += m[_ABSORBED] * u[0] + m[_ABSORBED + 1] * u[1] + m[_ABSORBED + 2] * u[2]


@numba.njit(cache=True, nogil=True, fastmath=True)
def _add_weight_moments(w: NDArray[np.float64], u: NDArray[np.float64], row: NDArray[np.float64]) -> None:
    """Add one block's weighted sums from its weight moments ``w`` (3 k,) to ``row``."""
    for j in range(w.shape[0] // 3):
        row[TOTALS + j] += w[3 * j] * u[0] + w[3 * j + 1] * u[1] + w[3 * j + 2] * u[2]


@numba.njit(cache=True, nogil=True, fastmath=True)
def accumulate_forces(
    sides: NDArray[np.int64],
    lit_share: NDArray[np.float64],
    lit_centroid: NDArray[np.float64],
    side_centroid: NDArray[np.float64],
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    optics: NDArray[np.float64],
    sun_vector: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    side_block: NDArray[np.int64],
    block_low: NDArray[np.float64],
    block_high: NDArray[np.float64],
    moments: NDArray[np.float64],
    side_weights: NDArray[np.float64] | None,
    block_weights: NDArray[np.float64] | None,
    partials: NDArray[np.float64],
) -> None:
    """Sum eq. (4) with ``P = 1`` and the weights times the direct power over the facing sides, per block.

    Torques are about ``reference_m``; the weights are ``side_weights``.

    ``lit_share[k]`` is the lit share of side ``sides[k]`` (float, or bool: lit or not). Per-side
    arrays are indexed by side: ``lit_centroid`` (n, 3) [m] where each side's force acts
    (``side_centroid`` on wholly lit sides), ``normals`` (n, 3), ``areas`` (n,) [m^2], ``optics``
    (n, 3) holding ``(rho, beta, sigma)``. A block holds consecutive side numbers and its facing
    sides come together in ``sides``, in ascending order. A block whose normal bounds
    ``block_low``/``block_high`` (n_blocks, 3) show that all its sides face is added from its
    ``moments`` (:func:`block_moments`), corrected on sides not wholly lit; the others side by side.
    Each side's ``[Fx, Fy, Fz, Mx, My, Mz, lit area, projected area, absorbed projected area]``
    [N/Pa, N m/Pa, m^2, m^2, m^2], then its ``side_weights`` (n, k) times its lit projected area, land
    in row ``side_block[s]`` of ``partials`` (n_blocks, TOTALS + k); ``block_weights`` (n_blocks, 3 k)
    are the weights' :func:`weight_moments`; both None for no weights (a kernel compiled without them).
    Summing the rows in order gives a total that does not depend on how the blocks were split
    between calls. (fastmath lets the compiler fuse multiply-adds; the sums keep their order, so
    results repeat from run to run.)

    Parameters
    ----------
    sides : (m,) int64
        The facing sides, ascending, a block's together.
    lit_share : (m,) float64 or bool
        Lit share of each of ``sides``.
    lit_centroid : (n, 3) float64
        Where each side's force acts [m].
    side_centroid : (n, 3) float64
        Centroid of each side [m].
    normals : (n, 3) float64
        Outward unit normal of each side.
    areas : (n,) float64
        Area of each side [m^2].
    optics : (n, 3) float64
        ``(rho, beta, sigma)`` of each side.
    sun_vector : (3,) float64
        Unit vector toward the Sun.
    reference_m : (3,) float64
        Torque reference point [m].
    side_block : (n,) int64
        Block of each side.
    block_low, block_high : (n_blocks, 3) float64
        Bounds of each block's side normals.
    moments : (n_blocks, MOMENT_SLOTS) float64
        :func:`block_moments` of the blocks.
    side_weights : (n, k) float64 or None
        Per-side weights of the reflection plan's channels; None for none.
    block_weights : (n_blocks, 3 k) float64 or None
        Their :func:`weight_moments`; None for none.
    partials : (n_blocks, TOTALS + k) float64
        Per-block sums; added to.

    References
    ----------
    Shmatov and Mordvinkin (2013), eq. (4).

    Examples
    --------
    A black unit plate facing the Sun, half lit, is pushed away by half the pressure:

    >>> import numpy as np
    >>> normals, areas = np.array([[0.0, 0.0, 1.0]]), np.ones(1)
    >>> optics, centroids = np.zeros((1, 3)), np.zeros((1, 3))  # black: rho = beta = sigma = 0
    >>> side_block = np.zeros(1, dtype=np.int64)
    >>> moments = block_moments(normals, areas, optics, centroids, side_block, 1)
    >>> partials = np.zeros((1, TOTALS))
    >>> accumulate_forces(np.array([0]), np.array([0.5]), centroids, centroids, normals, areas, optics,
    ...     np.array([0.0, 0.0, 1.0]), np.zeros(3), side_block, normals, normals, moments, None, None,
    ...     partials)
    >>> partials[0, FORCE : FORCE + 3], float(partials[0, LIT_AREA])
    (array([ 0. ,  0. , -0.5]), 0.5)
    """
    u, ref = sun_vector, reference_m
    u0, u1, u2 = u[0], u[1], u[2]
    n = sides.shape[0]
    k = 0
    while k < n:
        block = side_block[sides[k]]
        row = partials[block]
        lower = 0.0
        for d, component in enumerate((u0, u1, u2)):
            lower += min(block_low[block, d] * component, block_high[block, d] * component)
        if lower > _FACING_MARGIN:
            # every side of the block faces: the moments, then the sides not wholly lit
            _add_moments(moments[block], u, ref, row)
            if block_weights is not None:
                _add_weight_moments(block_weights[block], u, row)
            end = k + int(moments[block, _COUNT])
            while k < end:
                f = lit_share[k]
                if f != 1.0:
                    s = sides[k]
                    _add_side(s, areas[s], side_centroid[s], ref, normals, optics, u, side_weights, -1.0, row)
                    if f != 0.0:
                        _add_side(
                            s, areas[s] * f, lit_centroid[s], ref, normals, optics, u, side_weights, 1.0, row
                        )
                k += 1
            continue
        while k < n and side_block[sides[k]] == block:
            s = sides[k]
            f = lit_share[k]
            k += 1
            if f != 0.0:
                _add_side(s, areas[s] * f, lit_centroid[s], ref, normals, optics, u, side_weights, 1.0, row)
