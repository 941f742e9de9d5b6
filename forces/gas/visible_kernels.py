"""Numba kernels of what reaches each side of the incident stream (:mod:`sunwind.forces.gas.visible`).

:func:`core_samples` makes the core cone's rays, :func:`core_shares` reads their answers,
:func:`sky_sums` sums the kernel over each side's kept sky rays, and :func:`side_loads` puts the pieces
together into each side's force, torque and first re-emission. Kernels taking ``lo, hi`` write rows
``lo:hi`` (or the sides they name) of their outputs only, so threads given disjoint ranges produce the
same bits as one.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.views.hemisphere import side_key, square_to_triangle, uniform


class LawTables(NamedTuple):
    """Each law's kernels per direction and what the sides need to apply them (read by name in numba).

    Attributes
    ----------
    channels : (n_laws, n_x, 4) float64
        :attr:`~sunwind.forces.gas.angular.DirectionTables.channels`, on ``x = sin(psi / 2)``.
    cll : (n_laws, n_x, n_mu) float64 or None
        CLL's reflected normal push, on ``mu = t^2``; None where no law is CLL.
    pressure_scale, shear_scale : (n_laws,) float64
        Each law's ``a`` and ``c`` (:class:`~sunwind.forces.gas.angular.SpeciesLaws`).
    normals : (n_sides, 3) float64
        Outward unit normal of each side.

    Examples
    --------
    One law whose momentum kernel is 1 in every direction, on one side of normal +x:

    >>> import math
    >>> import numpy as np
    >>> tables = LawTables(channels=np.tile([1.0, 0.0, 0.0, 0.0], (1, 2, 1)), cll=None,
    ...     pressure_scale=np.ones(1), shear_scale=np.ones(1), normals=np.array([[1.0, 0.0, 0.0]]))
    >>> tables.channels.shape
    (1, 2, 4)
    """

    channels: NDArray[np.float64]
    cll: NDArray[np.float64] | None
    pressure_scale: NDArray[np.float64]
    shear_scale: NDArray[np.float64]
    normals: NDArray[np.float64]


class FlowLaw(NamedTuple):
    """The law of each side and the flow it meets.

    Attributes
    ----------
    side_law : (n_sides,) int64
        Law of each side, into the :class:`LawTables`.
    u : (3,) float64
        Unit flow direction.
    cos_core : float
        Cosine of the core cone's half-angle ``psi_c``.

    Examples
    --------
    >>> import math
    >>> import numpy as np
    >>> flow_law = FlowLaw(side_law=np.array([0]), u=np.array([1.0, 0.0, 0.0]), cos_core=math.cos(0.3))
    >>> round(flow_law.cos_core, 4)
    0.9553
    """

    side_law: NDArray[np.int64]
    u: NDArray[np.float64]
    cos_core: float


class GroupLoads(NamedTuple):
    """What the whole stream does on an unobstructed side of each group.

    Attributes
    ----------
    law : (n_groups,) int64
        Law of each group.
    normals : (n_groups, 3) float64
        Its outward unit normal.
    closed : (n_groups, 5) float64
        Force per unit area [Pa] (3) and the two re-emission channels.

    Examples
    --------
    >>> import numpy as np
    >>> zero = np.zeros((1, 3))
    >>> groups = GroupLoads(law=np.array([0]), normals=np.array([[1.0, 0.0, 0.0]]),
    ...     closed=np.array([[-2.0, 0.0, 0.0, 1.0, 1.0]]))
    >>> geometry = SideGeometry(areas=np.array([0.5]), centroids=np.array([[1.0, 0.0, 0.0]]))
    >>> core_parts = CoreParts(at_lit=np.ones(1), at_centroid=np.zeros(1),
    ...     lit_centroid=np.array([[1.0, 0.0, 0.0]]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> sky = SkyParts(keeps_open=np.array([False]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> groups.closed.shape
    (1, 5)
    """

    law: NDArray[np.int64]
    normals: NDArray[np.float64]
    closed: NDArray[np.float64]


class SideGeometry(NamedTuple):
    """Areas and centroids of the sides.

    Attributes
    ----------
    areas : (n_sides,) float64
        Area of each side [m^2].
    centroids : (n_sides, 3) float64
        Centroid of each side [m].

    Examples
    --------
    >>> import numpy as np
    >>> SideGeometry(areas=np.array([0.5]), centroids=np.zeros((1, 3))).areas
    array([0.5])
    """

    areas: NDArray[np.float64]
    centroids: NDArray[np.float64]


class CoreParts(NamedTuple):
    """What the core brings each side (:class:`~sunwind.forces.gas.core_rays.CoreCorrections`).

    Attributes
    ----------
    at_lit, at_centroid : (n_sides,) float64
        Shares of the unobstructed core ``K`` acting at the lit centroid and at the centroid.
    lit_centroid : (n_sides, 3) float64
        Lit centroids of the exact shadow along ``u`` [m].
    force, moment, emitted : (n_sides, 3), (n_sides, 3), (n_sides, 2) float64
        :func:`core_sums`'s corrections per unit area: force [Pa], moment [Pa m], re-emission.

    Examples
    --------
    >>> import numpy as np
    >>> zero = np.zeros((1, 3))
    >>> groups = GroupLoads(law=np.array([0]), normals=np.array([[1.0, 0.0, 0.0]]),
    ...     closed=np.array([[-2.0, 0.0, 0.0, 1.0, 1.0]]))
    >>> geometry = SideGeometry(areas=np.array([0.5]), centroids=np.array([[1.0, 0.0, 0.0]]))
    >>> core_parts = CoreParts(at_lit=np.ones(1), at_centroid=np.zeros(1),
    ...     lit_centroid=np.array([[1.0, 0.0, 0.0]]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> sky = SkyParts(keeps_open=np.array([False]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> core_parts.at_lit + core_parts.at_centroid
    array([1.])
    """

    at_lit: NDArray[np.float64]
    at_centroid: NDArray[np.float64]
    lit_centroid: NDArray[np.float64]
    force: NDArray[np.float64]
    moment: NDArray[np.float64]
    emitted: NDArray[np.float64]


class SkyParts(NamedTuple):
    """What each side's sampled sky rays give (:func:`sky_sums`).

    Attributes
    ----------
    keeps_open : (n_sides,) bool
        Whether the side's kept rays are its open ones (else its blocked ones).
    force, moment, emitted : (n_sides, 3), (n_sides, 3), (n_sides, 2) float64
        Their sums per unit area: force [Pa], moment about the centroid [Pa m], re-emission.

    Examples
    --------
    >>> import numpy as np
    >>> zero = np.zeros((1, 3))
    >>> groups = GroupLoads(law=np.array([0]), normals=np.array([[1.0, 0.0, 0.0]]),
    ...     closed=np.array([[-2.0, 0.0, 0.0, 1.0, 1.0]]))
    >>> geometry = SideGeometry(areas=np.array([0.5]), centroids=np.array([[1.0, 0.0, 0.0]]))
    >>> core_parts = CoreParts(at_lit=np.ones(1), at_centroid=np.zeros(1),
    ...     lit_centroid=np.array([[1.0, 0.0, 0.0]]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> sky = SkyParts(keeps_open=np.array([False]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> sky.keeps_open
    array([False])
    """

    keeps_open: NDArray[np.bool_]
    force: NDArray[np.float64]
    moment: NDArray[np.float64]
    emitted: NDArray[np.float64]


@numba.njit(cache=True, nogil=True)
def core_samples(
    sides: NDArray[np.int64],
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    level: int,
    frame: tuple[NDArray[np.float64], float, float],
    axes: NDArray[np.float64],
    quantiles: NDArray[np.float64],
    strata: tuple[int, int],
    seed: np.uint64,
    origins: NDArray[np.float32],
    levers: NDArray[np.float64],
    directions: NDArray[np.float32],
    weights: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """Make the core rays of ``sides[lo:hi]``: ``J`` directions within the cone from each of ``P`` points.

    From each of ``P = level**2`` points of a side, ``J = strata[0] strata[1]`` directions within the core
    cone.

    Row ``k P + p`` of the outputs belongs to point ``p`` of ``sides[k]``: ``origins`` (rows, 1, 3) in
    scene coordinates (``frame`` = centre, half-size, origin offset [m]) pushed off the surface, ``levers``
    (rows, 3) the point minus the side centroid [m], ``directions`` (rows, J, 3) and ``weights`` (rows, J)
    ``max(n . w, 0)``. Points are jittered in a ``level x level`` grid mapped onto the triangle
    (area-preserving), a fresh draw on every side, so that no part of a side (a thin shadow along an
    edge) is missed by every side alike. Directions are ``cos(psi) u + sin(psi) (cos(phi) e1 + sin(phi)
    e2)`` (``axes`` = ``u, e1, e2``), ``psi`` from the inverse distribution ``quantiles`` at a stratified
    probability, ``phi`` stratified over the turn from a random start. Random numbers are counter hashes
    of ``(seed, side)``.

    Parameters
    ----------
    sides : (n,) int64
        Sides that cast core rays.
    triangles : (n_facets, 3, 3) float64
        Corners of each facet [m].
    side_facet : (n_sides,) int64
        Facet of each side.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    level : int
        Points per side along each edge of the grid (``P = level**2`` points).
    frame : (centre, half_size, offset)
        The scene's centre (3,) [m], half-size [m] and the distance [m] rays start off the surface.
    axes : (3, 3) float64
        Rows ``u``, ``e1``, ``e2``: the flow direction and two unit vectors normal to it and each other.
    quantiles : (n_q,) float64
        ``psi`` [rad] at evenly spaced probabilities of the cone's sampling distribution
        (:attr:`~sunwind.forces.gas.core_cone.CoreCone.psi_quantiles`).
    strata : (int, int)
        Radial and azimuthal strata of the directions from each point.
    seed : uint64
        Seed of the random numbers.
    origins : (n P, 1, 3) float32
        Ray origins in scene coordinates; written.
    levers : (n P, 3) float64
        Each point minus its side's centroid [m]; written.
    directions : (n P, J, 3) float32
        Ray directions; written.
    weights : (n P, J) float64
        ``max(n . w, 0)`` of each direction; written.
    lo, hi : int
        The entries ``sides[lo:hi]`` to sample.

    Examples
    --------
    One triangle facing +z, a cone of 0.1 rad about ``u = +z``, one point and two directions:

    >>> import math
    >>> import numpy as np
    >>> triangle = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> axes = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    >>> origins, levers = np.empty((1, 1, 3), np.float32), np.empty((1, 3))
    >>> directions, weights = np.empty((1, 2, 3), np.float32), np.empty((1, 2))
    >>> core_samples(np.array([0]), triangle, np.array([0]), np.array([[0.0, 0.0, 1.0]]), 1,
    ...     (np.zeros(3), 1.0, 0.0), axes, np.linspace(0.0, 0.1, 5), (1, 2), np.uint64(1),
    ...     origins, levers, directions, weights, 0, 1)
    >>> bool(np.all(weights >= math.cos(0.1)))
    True
    """
    centre, half_size, offset = frame
    n_points, radial, around = level * level, strata[0], strata[1]
    per_point = radial * around + 3
    last = quantiles.shape[0] - 1
    third = 1.0 / 3.0
    for k in range(lo, hi):
        s = sides[k]
        key = side_key(seed, s)
        corners = triangles[side_facet[s]]
        for p in range(n_points):
            row = k * n_points + p
            first = p * per_point
            b1, b2 = square_to_triangle(
                (p // level + uniform(key, first)) / level, (p % level + uniform(key, first + 1)) / level
            )
            b0 = 1.0 - b1 - b2
            for d in range(3):
                point = b0 * corners[0, d] + b1 * corners[1, d] + b2 * corners[2, d]
                levers[row, d] = (
                    (b0 - third) * corners[0, d] + (b1 - third) * corners[1, d] + (b2 - third) * corners[2, d]
                )
                origins[row, 0, d] = np.float32((point + offset * normals[s, d] - centre[d]) / half_size)
            turn = uniform(key, first + 2)
            for i in range(radial):
                for j in range(around):
                    index = i * around + j
                    probability = (i + uniform(key, first + 3 + index)) / radial
                    position = probability * last
                    below = min(int(position), last - 1)
                    psi = quantiles[below] + (position - below) * (quantiles[below + 1] - quantiles[below])
                    phi = 2.0 * math.pi * (turn + j / around)
                    c, sn = math.cos(psi), math.sin(psi)
                    cp, sp = math.cos(phi), math.sin(phi)
                    mu = 0.0
                    for d in range(3):
                        w = c * axes[0, d] + sn * (cp * axes[1, d] + sp * axes[2, d])
                        directions[row, index, d] = np.float32(w)
                        mu += normals[s, d] * w
                    weights[row, index] = max(mu, 0.0)


@numba.njit(cache=True, nogil=True)
def core_sums(
    n_points: int,
    facing: NDArray[np.bool_],
    control_blocked: NDArray[np.bool_],
    blocked: NDArray[np.bool_],
    samples: tuple[NDArray[np.float32], NDArray[np.float64], NDArray[np.float64]],
    sides: NDArray[np.int64],
    flow_law: FlowLaw,
    tables: LawTables,
    normaliser: float,
    force: NDArray[np.float64],
    moment: NDArray[np.float64],
    emitted: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """Sum what the core adds to sides ``sides[lo:hi]`` beyond ``f_u`` times its unobstructed integral.

    From rows ``k n_points + p`` of the core rays: per unit area, the force [Pa], its moment about the
    side centroid [Pa m] and the two re-emission channels, into rows ``sides[k]``.

    With ``samples`` = directions ``w`` (rows, J, 3), weights ``mu = max(n . w, 0)`` and levers [m], ``B``
    whether a core ray met the model, ``B_u`` whether the ray along ``u`` from the same point did
    (``control_blocked``; 0 where the side does not face ``u``, whose core is then taken unobstructed
    first), the force per unit area is the unbiased estimate

        Z / (P J) sum (B_u - B) mu g(w) / k_P(psi)

    of the core integral of ``g`` (the law's force per unit solid angle and ``mu``, as in
    :func:`sky_sums`) over what the ``u``-shadow leaves out or counts wrongly: directions ``w`` drawn
    with density ``k_P / Z`` in the cone (``normaliser`` = ``Z`` [Pa]). It keeps the direction of what
    is blocked (a shadow on one side of the cone turns the shear), and vanishes exactly where no ray
    meets the model and none along ``u`` would. ``flow_law`` = the law of each side, ``u``, and the
    cone's cosine; ``tables`` as :func:`sky_sums`.

    Parameters
    ----------
    n_points : int
        Points per side ``P``.
    facing : (n,) bool
        Whether each of ``sides`` faces ``u``.
    control_blocked : (n P,) bool
        Whether the ray along ``u`` from each point met the model.
    blocked : (n P, J) bool
        Whether each core ray met the model.
    samples : (directions, weights, levers)
        The core rays' directions (n P, J, 3) float32, ``mu`` weights (n P, J) and levers (n P, 3) [m]
        (:func:`core_samples`).
    sides : (n,) int64
        Sides that cast core rays.
    flow_law : FlowLaw
        The law of each side, ``u`` and the cone's cosine.
    tables : LawTables
        Each law's kernels per direction, ``a``, ``c`` and the side normals.
    normaliser : float
        ``Z``, the cone's integral of ``k_P`` [Pa].
    force, moment : (n_sides, 3) float64
        Force [Pa] and its moment about the centroid [Pa m] per unit area; rows ``sides[lo:hi]`` written.
    emitted : (n_sides, 2) float64
        The two re-emission channels per unit area; rows ``sides[lo:hi]`` written.
    lo, hi : int
        The entries ``sides[lo:hi]`` to sum.

    Examples
    --------
    A side facing the flow whose one core ray is blocked while the ray along ``u`` is clear loses that
    ray's push:

    >>> import math
    >>> import numpy as np
    >>> tables = LawTables(channels=np.tile([1.0, 0.0, 0.0, 0.0], (1, 2, 1)), cll=None,
    ...     pressure_scale=np.ones(1), shear_scale=np.ones(1), normals=np.array([[1.0, 0.0, 0.0]]))
    >>> flow_law = FlowLaw(side_law=np.array([0]), u=np.array([1.0, 0.0, 0.0]), cos_core=math.cos(0.3))
    >>> samples = (np.array([[[1.0, 0.0, 0.0]]], np.float32), np.ones((1, 1)), np.zeros((1, 3)))
    >>> force, moment, emitted = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros((1, 2))
    >>> core_sums(1, np.array([True]), np.array([False]), np.array([[True]]), samples, np.array([0]),
    ...     flow_law, tables, 2.0, force, moment, emitted, 0, 1)
    >>> force
    array([[2., 0., 0.]])
    """
    directions, mu_weights, levers = samples
    side_law, u = flow_law.side_law, flow_law.u
    channels, cll, normals = tables.channels, tables.cll, tables.normals
    pressure, shear = tables.pressure_scale, tables.shear_scale
    per_point = mu_weights.shape[1]
    scale = normaliser / (n_points * per_point)
    for k in range(lo, hi):
        s = sides[k]
        law = side_law[s]
        scales = (pressure[law], shear[law])
        n = (normals[s, 0], normals[s, 1], normals[s, 2])
        f0 = f1 = f2 = m0 = m1 = m2 = e0 = e1 = 0.0
        for p in range(n_points):
            row = k * n_points + p
            control = 1.0 if facing[k] and control_blocked[row] else 0.0
            for j in range(per_point):
                gain = control - (1.0 if blocked[row, j] else 0.0)
                mu = mu_weights[row, j]
                if gain == 0.0 or mu <= 0.0:
                    continue
                w0, w1, w2 = (
                    np.float64(directions[row, j, 0]),
                    np.float64(directions[row, j, 1]),
                    np.float64(directions[row, j, 2]),
                )
                cos_psi = w0 * u[0] + w1 * u[1] + w2 * u[2]
                g0, g1, g2, c0, c1, k_p = _direction_load(
                    channels, cll, law, scales, n, (w0, w1, w2), cos_psi
                )
                if k_p <= 0.0:
                    continue
                factor = gain * mu / k_p
                g0, g1, g2 = factor * g0, factor * g1, factor * g2
                l0, l1, l2 = levers[row, 0], levers[row, 1], levers[row, 2]
                f0 += g0
                f1 += g1
                f2 += g2
                m0 += l1 * g2 - l2 * g1
                m1 += l2 * g0 - l0 * g2
                m2 += l0 * g1 - l1 * g0
                e0 += factor * c0
                e1 += factor * c1
        force[s, 0], force[s, 1], force[s, 2] = scale * f0, scale * f1, scale * f2
        moment[s, 0], moment[s, 1], moment[s, 2] = scale * m0, scale * m1, scale * m2
        emitted[s, 0], emitted[s, 1] = scale * e0, scale * e1


@numba.njit(cache=True, nogil=True)
def _direction_load(
    channels: NDArray[np.float64],
    cll: NDArray[np.float64] | None,
    law: int,
    scales: tuple[float, float],
    n: tuple[float, float, float],
    w: tuple[float, float, float],
    cos_psi: float,
) -> tuple[float, float, float, float, float, float]:
    """Of the stream arriving at a side of unit normal ``n`` from direction ``w`` (``cos(psi) = w . u``),
    per unit solid angle and ``mu = n . w``: the force of the side's law ``-a mu k_P n - c k_P (w - mu n)
    - (b + R) n`` [Pa] (``scales`` = ``a, c``), the two re-emission channels and ``k_P`` itself.

    ``channels`` (n_laws, n_x, 4) on ``x = sin(psi / 2)``; ``cll`` (n_laws, n_x, n_mu) on ``mu = t^2``
    with ``t`` evenly spaced (CLL's ``R``; laws past its first axis have none), or None where no law is
    CLL: numba then compiles the function without the lookup, which, even never taken, would slow the
    sky sums by half.
    """
    n_x = channels.shape[1]
    position = math.sqrt(max(0.5 * (1.0 - cos_psi), 0.0)) * (n_x - 1)
    i = min(int(position), n_x - 2)
    t = position - i
    k_p = channels[law, i, 0] + t * (channels[law, i + 1, 0] - channels[law, i, 0])
    push = channels[law, i, 1] + t * (channels[law, i + 1, 1] - channels[law, i, 1])
    mu = max(n[0] * w[0] + n[1] * w[1] + n[2] * w[2], 0.0)
    if cll is not None:
        if law < cll.shape[0]:
            n_mu = cll.shape[2]
            at = math.sqrt(mu) * (n_mu - 1)
            j = min(int(at), n_mu - 2)
            v = at - j
            low = cll[law, i, j] + t * (cll[law, i + 1, j] - cll[law, i, j])
            high = cll[law, i, j + 1] + t * (cll[law, i + 1, j + 1] - cll[law, i, j + 1])
            push += low + v * (high - low)
    a, c = scales
    along_n = (c - a) * mu * k_p - push
    along_w = -c * k_p
    e0 = channels[law, i, 2] + t * (channels[law, i + 1, 2] - channels[law, i, 2])
    e1 = channels[law, i, 3] + t * (channels[law, i + 1, 3] - channels[law, i, 3])
    return (
        along_n * n[0] + along_w * w[0],
        along_n * n[1] + along_w * w[1],
        along_n * n[2] + along_w * w[2],
        e0,
        e1,
        k_p,
    )


@numba.njit(cache=True, nogil=True, fastmath=True)
def sky_sums(
    sides: NDArray[np.int64],
    start: NDArray[np.int64],
    rays: tuple[NDArray[np.float32], NDArray[np.float32]],
    flow_law: FlowLaw,
    tables: LawTables,
    weight: float,
    force: NDArray[np.float64],
    moment: NDArray[np.float64],
    emitted: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """Sum over the kept sky rays of ``sides[lo:hi]`` of :func:`_direction_load` outside the core.

    ``rays`` = the kept rays' directions ``w`` and levers [m]; ``flow_law`` = the law of each side,
    ``u`` and ``cos(psi_c)`` (:class:`FlowLaw`); ``tables`` = ``channels``, ``cll``, the laws' ``a`` and
    ``c``, and the side normals (:class:`LawTables`). A ray with ``w . u < cos(psi_c)`` adds, times
    ``weight`` (``pi / N``), its law's force [Pa], that force's moment about the side centroid ``lever x
    force`` [Pa m] and the two re-emission channels. Results go to rows ``sides[k]`` of ``force``,
    ``moment`` (n_sides, 3) and ``emitted`` (n_sides, 2).

    Parameters
    ----------
    sides : (n,) int64
        Sides with kept sky rays.
    start : (n_sides + 1,) int64
        Side ``s``'s kept rays are rows ``start[s]:start[s + 1]`` of ``rays``.
    rays : (directions, levers)
        Directions ``w`` (n_rays, 3) float32 and levers from the side centroid (n_rays, 3) float32 [m].
    flow_law : FlowLaw
        The law of each side, ``u`` and ``cos(psi_c)``.
    tables : LawTables
        Each law's kernels per direction, ``a``, ``c`` and the side normals.
    weight : float
        Weight of each ray, ``pi / N`` for ``N`` rays per side.
    force, moment : (n_sides, 3) float64
        Sums of force [Pa] and moment [Pa m] per unit area; rows ``sides[lo:hi]`` written.
    emitted : (n_sides, 2) float64
        Sums of the two re-emission channels; rows ``sides[lo:hi]`` written.
    lo, hi : int
        The entries ``sides[lo:hi]`` to sum.

    Examples
    --------
    One ray along the normal of a side edge-on to the flow, outside the core:

    >>> import math
    >>> import numpy as np
    >>> tables = LawTables(channels=np.tile([1.0, 0.0, 0.0, 0.0], (1, 2, 1)), cll=None,
    ...     pressure_scale=np.ones(1), shear_scale=np.ones(1), normals=np.array([[1.0, 0.0, 0.0]]))
    >>> flow_law = FlowLaw(side_law=np.array([0]), u=np.array([0.0, 1.0, 0.0]), cos_core=math.cos(0.3))
    >>> rays = (np.array([[1.0, 0.0, 0.0]], np.float32), np.zeros((1, 3), np.float32))
    >>> force, moment, emitted = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros((1, 2))
    >>> sky_sums(np.array([0]), np.array([0, 1]), rays, flow_law, tables, math.pi, force, moment, emitted,
    ...     0, 1)
    >>> force.round(4)
    array([[-3.1416,  0.    ,  0.    ]])
    """
    direction, lever = rays
    side_law, u, cos_core = flow_law.side_law, flow_law.u, flow_law.cos_core
    channels, cll, normals = tables.channels, tables.cll, tables.normals
    pressure, shear = tables.pressure_scale, tables.shear_scale
    u0, u1, u2 = u[0], u[1], u[2]
    for k in range(lo, hi):
        s = sides[k]
        law = side_law[s]
        scales = (pressure[law], shear[law])
        n = (normals[s, 0], normals[s, 1], normals[s, 2])
        f0 = f1 = f2 = m0 = m1 = m2 = e0 = e1 = 0.0
        for r in range(start[s], start[s + 1]):
            w0, w1, w2 = np.float64(direction[r, 0]), np.float64(direction[r, 1]), np.float64(direction[r, 2])
            cos_psi = w0 * u0 + w1 * u1 + w2 * u2
            if cos_psi >= cos_core:
                continue
            g0, g1, g2, c0, c1, _ = _direction_load(channels, cll, law, scales, n, (w0, w1, w2), cos_psi)
            l0, l1, l2 = np.float64(lever[r, 0]), np.float64(lever[r, 1]), np.float64(lever[r, 2])
            f0 += g0
            f1 += g1
            f2 += g2
            m0 += l1 * g2 - l2 * g1
            m1 += l2 * g0 - l0 * g2
            m2 += l0 * g1 - l1 * g0
            e0 += c0
            e1 += c1
        force[s, 0], force[s, 1], force[s, 2] = weight * f0, weight * f1, weight * f2
        moment[s, 0], moment[s, 1], moment[s, 2] = weight * m0, weight * m1, weight * m2
        emitted[s, 0], emitted[s, 1] = weight * e0, weight * e1


@numba.njit(cache=True, nogil=True)
def side_loads(
    side_group: NDArray[np.int64],
    groups: GroupLoads,
    core: NDArray[np.float64],
    u: NDArray[np.float64],
    sides: SideGeometry,
    core_parts: CoreParts,
    sky: SkyParts,
    reference: NDArray[np.float64],
    force: NDArray[np.float64],
    torque: NDArray[np.float64],
    emitted: NDArray[np.float64],
    lo: int,
    hi: int,
) -> None:
    """Force [N], torque [N m] ((3, n_sides) each) and first re-emission (2, n_sides) of sides ``lo:hi``.

    ``groups`` = each group's law, normal and closed-form loads on an unobstructed side
    (:class:`GroupLoads`); ``core`` (n_laws, 4, n_gamma) the core
    cone's share of them, normal and tangential force and re-emission, on ``gamma`` in [-1, 1];
    ``sides`` = the side areas [m^2] and centroids [m] (:class:`SideGeometry`). ``core_parts``
    (:class:`CoreParts`) = the share of the unobstructed core ``K`` acting at the lit centroid of the
    exact shadow along ``u`` (``f_u``), the share acting at the centroid, those lit centroids [m], and
    :func:`core_sums`'s corrections (force, moment, re-emission per unit area); ``sky``
    (:class:`SkyParts`) = whether the side's kept sky rays are the open ones, and their
    :func:`sky_sums`. Per unit area::

        visible = f_u K + c K + corrections + (closed - K - sky sums  |  sky sums of the open rays),

    so an unobstructed side gets ``closed`` exactly.

    Parameters
    ----------
    side_group : (n_sides,) int64
        Group of each side.
    groups : GroupLoads
        Each group's law, normal and closed-form loads.
    core : (n_laws, 4, n_gamma) float64
        The core cone's table (:attr:`~sunwind.forces.gas.core_cone.CoreCone.gamma_table`).
    u : (3,) float64
        Unit flow vector.
    sides : SideGeometry
        Side areas [m^2] and centroids [m].
    core_parts : CoreParts
        What the core brings each side.
    sky : SkyParts
        What each side's sampled sky rays give.
    reference : (3,) float64
        Torque reference point [m].
    force, torque : (3, n_sides) float64
        Force [N] and torque [N m] of each side; columns ``lo:hi`` written.
    emitted : (2, n_sides) float64
        First re-emission of each side; columns ``lo:hi`` written.
    lo, hi : int
        The sides to compute.

    Examples
    --------
    A side that sees the whole sky takes its group's closed form times its area:

    >>> import numpy as np
    >>> zero = np.zeros((1, 3))
    >>> groups = GroupLoads(law=np.array([0]), normals=np.array([[1.0, 0.0, 0.0]]),
    ...     closed=np.array([[-2.0, 0.0, 0.0, 1.0, 1.0]]))
    >>> geometry = SideGeometry(areas=np.array([0.5]), centroids=np.array([[1.0, 0.0, 0.0]]))
    >>> core_parts = CoreParts(at_lit=np.ones(1), at_centroid=np.zeros(1),
    ...     lit_centroid=np.array([[1.0, 0.0, 0.0]]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> sky = SkyParts(keeps_open=np.array([False]), force=zero, moment=zero, emitted=np.zeros((1, 2)))
    >>> core = np.zeros((1, 4, 3))
    >>> force, torque, emitted = np.empty((3, 1)), np.empty((3, 1)), np.empty((2, 1))
    >>> side_loads(np.array([0]), groups, core, np.array([1.0, 0.0, 0.0]), geometry, core_parts, sky,
    ...     np.zeros(3), force, torque, emitted, 0, 1)
    >>> force.T, emitted.T
    (array([[-1.,  0.,  0.]]), array([[0.5, 0.5]]))
    """
    group_law, group_normals, closed = groups.law, groups.normals, groups.closed
    areas, centroids = sides.areas, sides.centroids
    at_lit, at_centroid, lit_centroid = core_parts.at_lit, core_parts.at_centroid, core_parts.lit_centroid
    core_force, core_moment, core_emitted = core_parts.force, core_parts.moment, core_parts.emitted
    keeps_open, sky_force, sky_moment, sky_emitted = sky.keeps_open, sky.force, sky.moment, sky.emitted
    for s in range(lo, hi):
        group = side_group[s]
        law = group_law[group]
        k0, k1, k2, i, t = _core_load(core, law, group_normals[group], u)
        core_e0 = core[law, 2, i] + t * (core[law, 2, i + 1] - core[law, 2, i])
        core_e1 = core[law, 3, i] + t * (core[law, 3, i + 1] - core[law, 3, i])
        sign = 1.0 if keeps_open[s] else -1.0
        # what acts at the centroid: the core's share there and its corrections, the sky rays' sums
        middle = at_centroid[s]
        p0 = middle * k0 + core_force[s, 0] + sign * sky_force[s, 0]
        p1 = middle * k1 + core_force[s, 1] + sign * sky_force[s, 1]
        p2 = middle * k2 + core_force[s, 2] + sign * sky_force[s, 2]
        seen = at_lit[s] + middle
        e0 = seen * core_e0 + core_emitted[s, 0] + sign * sky_emitted[s, 0]
        e1 = seen * core_e1 + core_emitted[s, 1] + sign * sky_emitted[s, 1]
        if not keeps_open[s]:  # the rest of the stream, its blocked rays taken off above
            p0 += closed[group, 0] - k0
            p1 += closed[group, 1] - k1
            p2 += closed[group, 2] - k2
            e0 += closed[group, 3] - core_e0
            e1 += closed[group, 4] - core_e1
        q0, q1, q2 = at_lit[s] * k0, at_lit[s] * k1, at_lit[s] * k2  # at the lit centroid
        c0, c1, c2 = (
            centroids[s, 0] - reference[0],
            centroids[s, 1] - reference[1],
            centroids[s, 2] - reference[2],
        )
        l0 = lit_centroid[s, 0] - reference[0]
        l1 = lit_centroid[s, 1] - reference[1]
        l2 = lit_centroid[s, 2] - reference[2]
        area = areas[s]
        force[0, s], force[1, s], force[2, s] = area * (p0 + q0), area * (p1 + q1), area * (p2 + q2)
        m0 = core_moment[s, 0] + sign * sky_moment[s, 0]
        m1 = core_moment[s, 1] + sign * sky_moment[s, 1]
        m2 = core_moment[s, 2] + sign * sky_moment[s, 2]
        torque[0, s] = area * ((c1 * p2 - c2 * p1) + (l1 * q2 - l2 * q1) + m0)
        torque[1, s] = area * ((c2 * p0 - c0 * p2) + (l2 * q0 - l0 * q2) + m1)
        torque[2, s] = area * ((c0 * p1 - c1 * p0) + (l0 * q1 - l1 * q0) + m2)
        emitted[0, s], emitted[1, s] = area * e0, area * e1


@numba.njit(cache=True, nogil=True)
def _core_load(
    core: NDArray[np.float64], law: int, normal: NDArray[np.float64], u: NDArray[np.float64]
) -> tuple[float, float, float, int, float]:
    """``K``: the force per unit area [Pa] the core brings an unobstructed side of ``law`` and unit
    ``normal``, from ``core`` (n_laws, 4, n_gamma) on ``gamma = normal . u`` in [-1, 1]: its normal part
    along the normal, its tangential part along ``t_hat``, against the flow's share in the side's plane;
    and where ``gamma`` falls in the table (row ``i``, share ``t`` of the way to the next)."""
    n0, n1, n2 = normal[0], normal[1], normal[2]
    n_gamma = core.shape[2]
    gamma = n0 * u[0] + n1 * u[1] + n2 * u[2]
    position = (min(max(gamma, -1.0), 1.0) + 1.0) * 0.5 * (n_gamma - 1)
    i = min(int(position), n_gamma - 2)
    t = position - i
    c_n = core[law, 0, i] + t * (core[law, 0, i + 1] - core[law, 0, i])
    c_t = core[law, 1, i] + t * (core[law, 1, i + 1] - core[law, 1, i])
    a0, a1, a2 = u[0] - gamma * n0, u[1] - gamma * n1, u[2] - gamma * n2
    length = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    t0 = t1 = t2 = 0.0
    if length > 1e-12:
        t0, t1, t2 = -a0 / length, -a1 / length, -a2 / length
    return c_n * n0 + c_t * t0, c_n * n1 + c_t * t1, c_n * n2 + c_t * t2, i, t


@numba.njit(cache=True, nogil=True)
def core_loads(
    side_group: NDArray[np.int64],
    group_law: NDArray[np.int64],
    group_normals: NDArray[np.float64],
    core: NDArray[np.float64],
    u: NDArray[np.float64],
    out: NDArray[np.float64],
) -> None:
    """Write ``K`` of every side (:func:`_core_load`) into ``out`` (n_sides, 3) [Pa].

    ``K`` is the force the core brings one unit of the side's area that the shadow along ``u`` leaves lit.

    Parameters
    ----------
    side_group : (n_sides,) int64
        Group of each side.
    group_law : (n_groups,) int64
        Law of each group.
    group_normals : (n_groups, 3) float64
        Outward unit normal of each group.
    core : (n_laws, 4, n_gamma) float64
        The core cone's table (:attr:`~sunwind.forces.gas.core_cone.CoreCone.gamma_table`).
    u : (3,) float64
        Unit flow vector.
    out : (n_sides, 3) float64
        ``K`` of each side [Pa]; written.

    Examples
    --------
    >>> import numpy as np
    >>> core = np.zeros((1, 4, 3))
    >>> core[0, 0] = -2.0  # a normal force of -2 Pa at every gamma
    >>> out = np.empty((1, 3))
    >>> core_loads(np.array([0]), np.array([0]), np.array([[1.0, 0.0, 0.0]]), core, np.array([1.0, 0.0, 0.0]),
    ...     out)
    >>> out
    array([[-2.,  0.,  0.]])
    """
    for s in range(side_group.shape[0]):
        group = side_group[s]
        k0, k1, k2, _, _ = _core_load(core, group_law[group], group_normals[group], u)
        out[s, 0], out[s, 1], out[s, 2] = k0, k1, k2
