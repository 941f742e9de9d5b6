"""Numba kernels of inter-reflection (:mod:`sunwind.forces.reflection.beams`): emitting first beams, landing
beams and their sums.

Each kernel runs serially over its beams in their given order, so its sums have the same bits
whatever the threads did elsewhere. Powers are in W, momenta in W (divide by c for N), lengths in m.
"""

from __future__ import annotations

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import BLIND, ESCAPED

#: Slots of the running sums ``totals`` of :func:`land`: from ``MOMENTUM`` the momentum (3) and its
#: moment about the reference point (3), from ``OPEN_SKY`` the same of landed diffuse light leaving as
#: from an open plate, then the escaped, absorbed and truncated power.
MOMENTUM, OPEN_SKY, ESCAPED_W, ABSORBED_W, TRUNCATED_W = 0, 6, 12, 13, 14
N_TOTALS = 15


@numba.njit(cache=True, nogil=True)
def _share(side_optics: NDArray[np.float64], side_sheet: NDArray[np.bool_], s: int, through: bool) -> float:
    """Share of the light meeting side ``s`` that leaves it as a beam: specular reflection
    ``rho beta``, or (``through``) the transmission ``sigma`` of a sheet; a closed body sends none."""
    if through:
        return side_optics[s, 2] if side_sheet[s] else 0.0
    return side_optics[s, 0] * side_optics[s, 1]


@numba.njit(cache=True, nogil=True)
def _cos(s: int, side_normals: NDArray[np.float64], toward_source: NDArray[np.float64]) -> float:
    """Cosine of incidence on side ``s``."""
    return (
        side_normals[s, 0] * toward_source[0]
        + side_normals[s, 1] * toward_source[1]
        + side_normals[s, 2] * toward_source[2]
    )


@numba.njit(cache=True, nogil=True)
def _incident(
    s: int,
    lit_fraction: NDArray[np.float64],
    side_areas: NDArray[np.float64],
    side_normals: NDArray[np.float64],
    toward_source: NDArray[np.float64],
    flux_W_m2: float,
) -> tuple[float, float]:
    """Cosine of incidence on side ``s`` and the direct power [W] on its lit part."""
    cos = _cos(s, side_normals, toward_source)
    return cos, flux_W_m2 * side_areas[s] * lit_fraction[s] * cos


@numba.njit(cache=True, nogil=True)
def _swept_box_escapes(
    p: int,
    above: bool,
    direction: tuple[float, float, float],
    patch_low: NDArray[np.float64],
    patch_high: NDArray[np.float64],
    patch_normal: NDArray[np.float64],
    patch_offset: NDArray[np.float64],
    node_low: NDArray[np.float64],
    node_high: NDArray[np.float64],
    first_child: NDArray[np.int64],
    margin_m: float,
    reach_m: float,
    stack: NDArray[np.int64],
) -> bool:
    """Whether box ``p`` of ``patch_low``..``patch_high``, swept along ``direction``, misses the box
    (grown by ``margin_m``) of every leaf of the tree ``node_low``..``node_high`` (children
    ``first_child`` and the next, -1 for a leaf: :class:`sunwind.geometry.rays.box_tree.BoxTree`) that
    reaches more than
    ``reach_m`` off the patch's plane on the beam's side (``above``: along the plane's normal). Nodes
    that do not reach off the plane, or that the swept box misses, are not gone into. The swept box
    meets a box where a ray from its centre meets that box grown by its half-size."""
    inverse = (
        1.0 / direction[0] if direction[0] != 0.0 else 0.0,
        1.0 / direction[1] if direction[1] != 0.0 else 0.0,
        1.0 / direction[2] if direction[2] != 0.0 else 0.0,
    )
    stack[0] = 0
    top = 1
    while top > 0:
        top -= 1
        k = stack[top]
        centre = spread = 0.0
        for a in range(3):
            centre += patch_normal[p, a] * 0.5 * (node_high[k, a] + node_low[k, a])
            spread += abs(patch_normal[p, a]) * 0.5 * (node_high[k, a] - node_low[k, a])
        height = centre - patch_offset[p]
        if (height + spread <= reach_m) if above else (height - spread >= -reach_m):
            continue
        near, far = 0.0, np.inf
        for a in range(3):
            middle = 0.5 * (patch_high[p, a] + patch_low[p, a])
            half = 0.5 * (patch_high[p, a] - patch_low[p, a]) + margin_m
            lo, hi = node_low[k, a] - half - middle, node_high[k, a] + half - middle
            if direction[a] == 0.0:  # parallel to the slab: always in it or never
                if lo > 0.0 or hi < 0.0:
                    far = -1.0
                continue
            t1, t2 = lo * inverse[a], hi * inverse[a]
            near, far = max(near, min(t1, t2)), min(far, max(t1, t2))
        if near > far:
            continue
        if first_child[k] < 0:
            return False
        stack[top] = first_child[k]
        stack[top + 1] = first_child[k] + 1
        top += 2
    return True


@numba.njit(cache=True, nogil=True)
def _beam_direction(
    s: int, through: bool, cos: float, side_normals: NDArray[np.float64], toward_source: NDArray[np.float64]
) -> tuple[float, float, float]:
    """Direction of the beam side ``s`` sends: sunlight mirrored on it, or (``through``) passed on."""
    bend = 0.0 if through else 2.0 * cos
    return (
        bend * side_normals[s, 0] - toward_source[0],
        bend * side_normals[s, 1] - toward_source[1],
        bend * side_normals[s, 2] - toward_source[2],
    )


@numba.njit(cache=True, nogil=True)
def escaping_patches(
    facing: NDArray[np.int64],
    lit_fraction: NDArray[np.float64],
    side_normals: NDArray[np.float64],
    side_optics: NDArray[np.float64],
    side_sheet: NDArray[np.bool_],
    toward_source: NDArray[np.float64],
    side_patch: NDArray[np.int64],
    patch_low: NDArray[np.float64],
    patch_high: NDArray[np.float64],
    patch_normal: NDArray[np.float64],
    patch_offset: NDArray[np.float64],
    node_low: NDArray[np.float64],
    node_high: NDArray[np.float64],
    first_child: NDArray[np.int64],
    tree_depth: int,
    margin_m: float,
    reach_m: float,
) -> NDArray[np.bool_]:
    """Which patches of coplanar sides send first beams known to escape: mirror (column 0), transmitted (1).

    Sides of patch ``side_patch[s]`` (-1 for none) lie in the plane ``patch_normal . x = patch_offset`` and
    inside the box ``patch_low`` .. ``patch_high``, grown by more than a ray's origin offset. A first beam
    of the patch leaves that box along one direction (all its sides share their normal), away from the
    plane, so it can meet only facets reaching off the plane on its side. Where the box swept along the
    beam misses all of those in the tree ``node_low`` .. ``node_high`` (see :func:`_swept_box_escapes`;
    ``tree_depth`` its depth), every first beam of the patch escapes.

    Parameters
    ----------
    facing : (m,) int64
        Sides facing the source.
    lit_fraction : (n_sides,) float64
        Lit share of each side.
    side_normals : (n_sides, 3) float64
        Outward unit normal of each side.
    side_optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of each side.
    side_sheet : (n_sides,) bool
        Whether each side belongs to a sheet.
    toward_source : (3,) float64
        Unit vector toward the light source.
    side_patch : (n_sides,) int64
        Patch of each side, -1 for none.
    patch_low, patch_high : (n_patches, 3) float64
        Corners of each patch's grown box [m].
    patch_normal : (n_patches, 3) float64
        Unit normal of each patch's plane.
    patch_offset : (n_patches,) float64
        ``n . x`` of each patch's plane [m].
    node_low, node_high : (n_nodes, 3) float64
        Corners of the boxes of the facet tree's nodes [m].
    first_child : (n_nodes,) int64
        First child of each node, -1 for a leaf.
    tree_depth : int
        Depth of the tree.
    margin_m : float
        Growth of the nodes' boxes for the sweep [m].
    reach_m : float
        A node reaches off a plane where its box does by more than this [m].

    Returns
    -------
    (n_patches, 2) ndarray of bool
        Whether the patch's mirror and transmitted first beams all escape.

    Examples
    --------
    A mirrored cube lit along ``(0, 0.6, 0.8)``: the mirror beams of its two lit faces escape:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection.beams import chain_model
    >>> from sunwind.forces.reflection.escape import escape_test
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> mirror = sw.Material("mirror", reflectivity=1.0, specular_fraction=1.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=mirror, threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.6, 0.8]), 4, None)
    >>> test, sheet = escape_test(craft), chain_model(craft).side_sheet
    >>> escapes = escaping_patches(light.facing, light.lit_fraction, craft.side_normals, craft.side_optics,
    ...     sheet, light.direction, test.side_patch, test.patch_low, test.patch_high, test.patch_normal,
    ...     test.patch_offset, test.tree.low, test.tree.high, test.tree.first_child, test.tree.depth,
    ...     test.margin_m, test.reach_m)
    >>> int(escapes[:, 0].sum()), bool(escapes[:, 1].any())
    (2, False)
    """
    n_patches = patch_low.shape[0]
    escapes = np.zeros((n_patches, 2), dtype=np.bool_)
    first = np.full((n_patches, 2), -1, dtype=np.int64)
    for k in range(facing.shape[0]):
        s, p = facing[k], side_patch[facing[k]]
        if p < 0 or lit_fraction[s] <= 0.0:
            continue
        for kind in range(2):
            if first[p, kind] < 0 and _share(side_optics, side_sheet, s, kind == 1) > 0.0:
                first[p, kind] = s
    stack = np.empty(tree_depth + 2, dtype=np.int64)
    for p in range(n_patches):
        for kind in range(2):
            s = first[p, kind]
            if s >= 0:
                cos = _cos(s, side_normals, toward_source)
                escapes[p, kind] = _swept_box_escapes(
                    p,
                    kind == 0,
                    _beam_direction(s, kind == 1, cos, side_normals, toward_source),
                    patch_low,
                    patch_high,
                    patch_normal,
                    patch_offset,
                    node_low,
                    node_high,
                    first_child,
                    margin_m,
                    reach_m,
                    stack,
                )
    return escapes


@numba.njit(cache=True, nogil=True)
def emitters(
    facing: NDArray[np.int64],
    lit_fraction: NDArray[np.float64],
    lit_centroid: NDArray[np.float64],
    side_areas: NDArray[np.float64],
    side_normals: NDArray[np.float64],
    side_optics: NDArray[np.float64],
    side_sheet: NDArray[np.bool_],
    toward_source: NDArray[np.float64],
    flux_W_m2: float,
    side_patch: NDArray[np.int64] | None,
    escapes: NDArray[np.bool_] | None,
) -> tuple[
    NDArray[np.int64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    float,
]:
    """First beams the lit sides send, those known to escape left out.

    The mirror beam of every side with ``rho beta > 0``, then the beam every sheet with ``sigma > 0``
    transmits, each in the order of ``facing``. Beams of the patches ``escapes`` marks
    (:func:`escaping_patches`) are left out and their power summed instead.

    Parameters
    ----------
    facing : (m,) int64
        Sides facing the source.
    lit_fraction : (n_sides,) float64
        Lit share of each side.
    lit_centroid : (n_sides, 3) float64
        Centroid of each side's lit part [m].
    side_areas : (n_sides,) float64
        Area of each side [m^2].
    side_normals : (n_sides, 3) float64
        Outward unit normal of each side.
    side_optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of each side.
    side_sheet : (n_sides,) bool
        Whether each side belongs to a sheet.
    toward_source : (3,) float64
        Unit vector toward the light source.
    flux_W_m2 : float
        Flux of the source [W/m^2].
    side_patch : (n_sides,) int64 or None
        Patch of each side, -1 for none; None to leave no beam out.
    escapes : (n_patches, 2) bool or None
        :func:`escaping_patches`; None to leave no beam out.

    Returns
    -------
    side : (n,) int64
        Side sending each beam.
    origin : (n, 3) ndarray of float64
        The lit centroid it leaves from [m].
    direction : (n, 3) ndarray of float64
        Its unit direction.
    lift : (n, 3) ndarray of float64
        Unit vector off the surface on the beam's side.
    power : (n,) ndarray of float64
        Its power [W].
    escaping : float
        Power of the beams left out [W].

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection.beams import chain_model
    >>> from sunwind.forces.reflection.escape import escape_test
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> mirror = sw.Material("mirror", reflectivity=1.0, specular_fraction=1.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=mirror, threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.6, 0.8]), 4, None)
    >>> test, sheet = escape_test(craft), chain_model(craft).side_sheet
    >>> escapes = escaping_patches(light.facing, light.lit_fraction, craft.side_normals, craft.side_optics,
    ...     sheet, light.direction, test.side_patch, test.patch_low, test.patch_high, test.patch_normal,
    ...     test.patch_offset, test.tree.low, test.tree.high, test.tree.first_child, test.tree.depth,
    ...     test.margin_m, test.reach_m)
    >>> side, origin, direction, lift, power, escaping = emitters(light.facing, light.lit_fraction,
    ...     light.lit_centroid, craft.side_areas, craft.side_normals, craft.side_optics, sheet,
    ...     light.direction, 1000.0, None, None)
    >>> side, power, escaping
    (array([ 6,  7, 10, 11]), array([300., 300., 400., 400.]), 0.0)
    >>> emitters(light.facing, light.lit_fraction, light.lit_centroid, craft.side_areas, craft.side_normals,
    ...     craft.side_optics, sheet, light.direction, 1000.0, test.side_patch, escapes)[5]
    1400.0
    """
    m = facing.shape[0]
    sends = np.zeros((2, m), dtype=np.bool_)
    n, escaping = 0, 0.0
    for kind in range(2):
        for k in range(m):
            s = facing[k]
            share = _share(side_optics, side_sheet, s, kind == 1)
            if lit_fraction[s] <= 0.0 or share <= 0.0:
                continue
            if (
                side_patch is not None
                and escapes is not None
                and side_patch[s] >= 0
                and escapes[side_patch[s], kind]
            ):
                escaping += (
                    share * _incident(s, lit_fraction, side_areas, side_normals, toward_source, flux_W_m2)[1]
                )
                continue
            sends[kind, k] = True
            n += 1
    side = np.empty(n, dtype=np.int64)
    origin = np.empty((n, 3))
    direction = np.empty((n, 3))
    lift = np.empty((n, 3))
    power = np.empty(n)
    count = 0
    for kind in range(2):
        for k in range(m):
            if not sends[kind, k]:
                continue
            s = facing[k]
            cos, incident = _incident(s, lit_fraction, side_areas, side_normals, toward_source, flux_W_m2)
            side[count] = s
            power[count] = incident * _share(side_optics, side_sheet, s, kind == 1)
            d0, d1, d2 = _beam_direction(s, kind == 1, cos, side_normals, toward_source)
            direction[count, 0], direction[count, 1], direction[count, 2] = d0, d1, d2
            sign = -1.0 if kind == 1 else 1.0
            for d in range(3):
                origin[count, d] = lit_centroid[s, d]
                lift[count, d] = sign * side_normals[s, d]
            count += 1
    return side, origin, direction, lift, power, escaping


@numba.njit(cache=True, nogil=True)
def scene_rays(
    origin_m: NDArray[np.float64],
    lift: NDArray[np.float64],
    direction: NDArray[np.float64],
    centre: NDArray[np.float64],
    half_size: float,
    offset_m: float,
) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
    """Ray origins ``origin_m + offset_m lift`` and directions in float32 scene coordinates.

    The scene frame is :class:`sunwind.geometry.rays.scene.SceneFrame`'s: centred on ``centre`` and scaled
    by ``half_size``.

    Parameters
    ----------
    origin_m : (n, 3) float64
        Where each ray starts on the surface [m].
    lift : (n, 3) float64
        Unit vector off the surface on the ray's side.
    direction : (n, 3) float64
        Unit direction of each ray.
    centre : (3,) float64
        Centre of the scene [m].
    half_size : float
        Half-size of the scene [m].
    offset_m : float
        How far off the surface rays start [m].

    Returns
    -------
    origins : (n, 3) ndarray of float32
        Origins in scene coordinates.
    directions : (n, 3) ndarray of float32
        The directions.

    Examples
    --------
    >>> import numpy as np
    >>> up = np.array([[0.0, 0.0, 1.0]])
    >>> scene_rays(np.zeros((1, 3)), up, up, np.zeros(3), 2.0, 0.01)
    (array([[0.   , 0.   , 0.005]], dtype=float32), array([[0., 0., 1.]], dtype=float32))
    """
    n = origin_m.shape[0]
    origins = np.empty((n, 3), dtype=np.float32)
    directions = np.empty((n, 3), dtype=np.float32)
    for i in range(n):
        for d in range(3):
            origins[i, d] = (origin_m[i, d] + offset_m * lift[i, d] - centre[d]) / half_size
            directions[i, d] = direction[i, d]
    return origins, directions


@numba.njit(cache=True, nogil=True)
def strike(
    facets: NDArray[np.int32],
    origin_m: NDArray[np.float64],
    lift: NDArray[np.float64],
    direction: NDArray[np.float64],
    offset_m: float,
    facet_normals: NDArray[np.float64],
    facet_offsets: NDArray[np.float64],
    facet_sides: NDArray[np.int64],
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Side each ray strikes on the facet it first hits, and where.

    Sides as :meth:`sunwind.geometry.spacecraft.Spacecraft.struck_sides` gives them: the front side where
    the ray travels against the facet normal, else the back; ``BLIND`` where the facet has no such side.
    The point is where the ray from ``origin_m + offset_m lift`` crosses the facet's plane ``n . x = c``,
    in float64.

    Parameters
    ----------
    facets : (n,) int32
        Facet each ray first hits, negative where it escapes.
    origin_m : (n, 3) float64
        Where each ray starts on the surface [m].
    lift : (n, 3) float64
        Unit vector off the surface on the ray's side.
    direction : (n, 3) float64
        Unit direction of each ray.
    offset_m : float
        How far off the surface rays start [m].
    facet_normals : (n_facets, 3) float64
        Unit normal of each facet.
    facet_offsets : (n_facets,) float64
        ``n . x`` of each facet's plane [m].
    facet_sides : (n_facets, 2) int64
        Front and back side of each facet, negative where it has none.

    Returns
    -------
    sides : (n,) ndarray of int64
        Side struck, ``ESCAPED`` (-1) where the ray escapes, ``BLIND`` (-2) where the facet has no such side.
    points : (n, 3) ndarray of float64
        Where it strikes [m]; zero where it strikes no side.

    Examples
    --------
    Two rays down from ``z = 2``: one escapes, one meets the front (side 3) of a facet in the plane ``z = 1``:

    >>> import numpy as np
    >>> start, down = np.array([[0.0, 0.0, 2.0]] * 2), np.array([[0.0, 0.0, -1.0]] * 2)
    >>> sides, points = strike(np.array([-1, 0], np.int32), start, -down, down, 0.0,
    ...     np.array([[0.0, 0.0, 1.0]]), np.array([1.0]), np.array([[3, -1]]))
    >>> sides, points[1]
    (array([-1,  3]), array([0., 0., 1.]))
    """
    n = facets.shape[0]
    sides = np.empty(n, dtype=np.int64)
    points = np.zeros((n, 3))
    for i in range(n):
        f = facets[i]
        if f < 0:
            sides[i] = ESCAPED
            continue
        n0, n1, n2 = facet_normals[f, 0], facet_normals[f, 1], facet_normals[f, 2]
        along = n0 * direction[i, 0] + n1 * direction[i, 1] + n2 * direction[i, 2]
        s = facet_sides[f, 1 if along > 0.0 else 0]
        sides[i] = s if s >= 0 else BLIND
        if s < 0:
            continue
        o0 = origin_m[i, 0] + offset_m * lift[i, 0]
        o1 = origin_m[i, 1] + offset_m * lift[i, 1]
        o2 = origin_m[i, 2] + offset_m * lift[i, 2]
        height = facet_offsets[f] - (n0 * o0 + n1 * o1 + n2 * o2)
        t = height / along if along != 0.0 else 0.0  # a ray can strike a facet only across its plane
        points[i, 0] = o0 + t * direction[i, 0]
        points[i, 1] = o1 + t * direction[i, 1]
        points[i, 2] = o2 + t * direction[i, 2]
    return sides, points


@numba.njit(cache=True, nogil=True)
def _push(
    totals: NDArray[np.float64],
    slot: int,
    at: NDArray,
    i: int,
    reference: NDArray,
    x: float,
    y: float,
    z: float,
) -> None:
    """Add the vector ``(x, y, z)`` acting at ``at[i]`` to ``totals[slot:slot + 3]`` and its moment
    about ``reference`` to the next three slots (rows are indexed here: an array view per beam costs
    more than the sums)."""
    r0, r1, r2 = at[i, 0] - reference[0], at[i, 1] - reference[1], at[i, 2] - reference[2]
    totals[slot] += x
    totals[slot + 1] += y
    totals[slot + 2] += z
    totals[slot + 3] += r1 * z - r2 * y
    totals[slot + 4] += r2 * x - r0 * z
    totals[slot + 5] += r0 * y - r1 * x


@numba.njit(cache=True, nogil=True)
def land(
    origin_m: NDArray[np.float64],
    direction: NDArray[np.float64],
    power_W: NDArray[np.float64],
    start_W: NDArray[np.float64],
    sides: NDArray[np.int64],
    points_m: NDArray[np.float64],
    first: bool,
    last: bool,
    cutoff: float,
    side_normals: NDArray[np.float64],
    side_optics: NDArray[np.float64],
    side_sheet: NDArray[np.bool_],
    lambert_factor: float,
    reference_m: NDArray[np.float64],
    totals: NDArray[np.float64],
    arrived_W: NDArray[np.float64],
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]
]:
    """Count one generation of beams and return the next.

    Each beam leaves ``origin_m`` and meets side ``sides`` (or ``ESCAPED``/``BLIND``) at ``points_m``.

    A ``first`` generation's beams the direct law let leave give their momentum back where they
    land; a later one's escaping beams take theirs away. A beam that meets a side splits into
    absorbed, diffuse (to the open-sky sums as if it left along ``lambert_factor n``), mirror and
    transmitted parts; a closed body's transmitted share leaves unchanged. A new beam below ``cutoff``
    of its chain's starting power, or any new beam of the ``last`` generation, is truncated.
    ``totals`` (the ``N_TOTALS`` slots above) and ``arrived_W``, the beam power each side meets, are
    added to in place.

    Returns the new beams' origin (n, 3), lift (n, 3), direction (n, 3), power and starting power.

    Parameters
    ----------
    origin_m : (n, 3) float64
        Where each beam leaves from [m].
    direction : (n, 3) float64
        Unit direction of each beam.
    power_W : (n,) float64
        Power of each beam [W].
    start_W : (n,) float64
        Power its chain started with [W].
    sides : (n,) int64
        Side each beam meets, or ``ESCAPED``/``BLIND``.
    points_m : (n, 3) float64
        Where it meets it [m].
    first : bool
        Whether these are first beams (the direct law let them leave).
    last : bool
        Whether this is the last generation (every new beam truncated).
    cutoff : float
        New beams below this share of their chain's starting power are truncated.
    side_normals : (n_sides, 3) float64
        Outward unit normal of each side.
    side_optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of each side.
    side_sheet : (n_sides,) bool
        Whether each side belongs to a sheet.
    lambert_factor : float
        ``2/3``: the momentum of diffuse light leaving an open plate per unit power.
    reference_m : (3,) float64
        Torque reference point [m].
    totals : (N_TOTALS,) float64
        Running sums; added to.
    arrived_W : (n_sides,) float64
        Beam power arriving at each side [W]; added to.

    Returns
    -------
    origin : (k, 3) ndarray of float64
        Where each new beam starts [m].
    lift : (k, 3) ndarray of float64
        Unit vector off the surface on its side.
    direction : (k, 3) ndarray of float64
        Its unit direction.
    power : (k,) ndarray of float64
        Its power [W].
    start : (k,) ndarray of float64
        Its chain's starting power [W].

    Examples
    --------
    A 10 W first beam going up meets a mirror facing down at ``z = 1``: its momentum is given back there and
    it goes on down:

    >>> import numpy as np
    >>> totals, arrived = np.zeros(N_TOTALS), np.zeros(1)
    >>> origin, lift, direction, power, start = land(np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]]),
    ...     np.array([10.0]), np.array([10.0]), np.array([0]), np.array([[0.0, 0.0, 1.0]]), True, False, 1e-6,
    ...     np.array([[0.0, 0.0, -1.0]]), np.array([[1.0, 1.0, 0.0]]), np.zeros(1, bool), 2 / 3, np.zeros(3),
    ...     totals, arrived)
    >>> direction, power, totals[MOMENTUM : MOMENTUM + 3], arrived
    (array([[ 0.,  0., -1.]]), array([10.]), array([ 0.,  0., 10.]), array([10.]))
    """
    n = power_W.shape[0]
    most = 2 * np.sum(sides >= 0)  # a side sends at most a mirror and a transmitted beam
    new_origin = np.empty((most, 3))
    new_lift = np.empty((most, 3))
    new_direction = np.empty((most, 3))
    new_power = np.empty(most)
    new_start = np.empty(most)
    count = 0
    escaped = absorbed = truncated = 0.0
    for i in range(n):
        s, p = sides[i], power_W[i]
        d0, d1, d2 = direction[i, 0], direction[i, 1], direction[i, 2]
        if s == ESCAPED:
            if not first:
                _push(totals, MOMENTUM, origin_m, i, reference_m, -p * d0, -p * d1, -p * d2)
            escaped += p
            continue
        if first:
            _push(totals, MOMENTUM, origin_m, i, reference_m, p * d0, p * d1, p * d2)
        if s == BLIND:
            absorbed += p
            continue
        rho, beta, sigma = side_optics[s, 0], side_optics[s, 1], side_optics[s, 2]
        n0, n1, n2 = side_normals[s, 0], side_normals[s, 1], side_normals[s, 2]
        absorbed += (1.0 - rho - sigma) * p
        diffuse = rho * (1.0 - beta) * p
        arrived_W[s] += p
        w = -lambert_factor * diffuse
        _push(totals, OPEN_SKY, points_m, i, reference_m, w * n0, w * n1, w * n2)
        if not side_sheet[s] and sigma > 0.0:
            w = -sigma * p
            _push(totals, MOMENTUM, points_m, i, reference_m, w * d0, w * d1, w * d2)
            escaped += sigma * p
        along = d0 * n0 + d1 * n1 + d2 * n2
        for through in (False, True):
            share = _share(side_optics, side_sheet, s, through)
            if share <= 0.0:
                continue
            if last or share * p < cutoff * start_W[i]:
                truncated += share * p
                continue
            new_origin[count, 0], new_origin[count, 1], new_origin[count, 2] = (
                points_m[i, 0],
                points_m[i, 1],
                points_m[i, 2],
            )
            sign = -1.0 if through else 1.0
            new_lift[count, 0], new_lift[count, 1], new_lift[count, 2] = sign * n0, sign * n1, sign * n2
            bend = 0.0 if through else 2.0 * along
            new_direction[count, 0] = d0 - bend * n0
            new_direction[count, 1] = d1 - bend * n1
            new_direction[count, 2] = d2 - bend * n2
            new_power[count] = share * p
            new_start[count] = start_W[i]
            count += 1
    totals[ESCAPED_W] += escaped
    totals[ABSORBED_W] += absorbed
    totals[TRUNCATED_W] += truncated
    return new_origin[:count], new_lift[:count], new_direction[:count], new_power[:count], new_start[:count]
