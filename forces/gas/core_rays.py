"""The core cone's rays: what the incident stream's core brings each side beyond the exact shadow along
the flow (METHOD.md "The open-sky integral").

The core (:mod:`.core_cone`) is the narrow cone about ``u`` from which a fast stream's molecules come.
The exact shadow pass along ``u`` gives each side facing the flow its lit share ``f_u``: the whole core
seen along ``u`` alone, exact as ``S -> inf``. What the cone's width changes is sampled: from jittered
points of the side, directions drawn from the kernel within the cone, each beside a ray along ``u``
from the same point (:func:`~sunwind.forces.gas.visible_kernels.core_sums`). Only sides that the cone
may reach obstructed cast (:mod:`sunwind.geometry.rays.hull`: a side on the model's hull, or on its part's
hull with the cone missing every other part's box, sees the whole core); rays that provably meet nothing
are not cast; the rest go to Embree in one batch.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.core_cone import CoreCone
from sunwind.forces.gas.visible_kernels import FlowLaw, LawTables, core_samples, core_sums
from sunwind.geometry.memory import count, require
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.rays.clear_kernels import cone_may_be_blocked, may_be_blocked
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft

#: Sampling of the core by budget: (points per side as a level, (radial, azimuthal) strata of the
#: directions from each point), finest first; each point also casts one ray along ``u``.
CORE_SAMPLINGS = ((4, (2, 4)), (4, (2, 2)), (2, (2, 2)), (1, (2, 2)), (1, (1, 2)))
#: Seed of the core rays' random numbers.
CORE_SEED = 0xC04E
#: Fewest sides per chunk of the parallel per-side kernels.
MIN_SIDES_PER_CHUNK = 4096
#: Peak bytes per core ray: its sample (origin and lever per point; direction, weight and flags), the
#: batch handed to Embree and its answers.
CORE_RAY_BYTES = 80


@dataclass(frozen=True, eq=False)
class CoreCorrections:
    """What the core brings every side, on top of the unobstructed core ``K`` (per unit area).

    Attributes
    ----------
    at_lit, at_centroid : (n_sides,) float64
        Shares of ``K`` acting at the lit centroid of the shadow along ``u`` (``f_u`` of a side that casts
        core rays and faces ``u``) and at the centroid (the rest of ``K`` where the side casts none: it
        sees the whole core; all of ``K`` where it casts but does not face ``u``).
    force, moment, emitted : (n_sides, 3), (n_sides, 3), (n_sides, 2) float64
        :func:`~sunwind.forces.gas.visible_kernels.core_sums` of the sides that cast: force [Pa], its
        moment about the centroid [Pa m], re-emission channels.
    rays : int
        Rays cast.

    Examples
    --------
    >>> import numpy as np
    >>> none = CoreCorrections(at_lit=np.ones(2), at_centroid=np.zeros(2), force=np.zeros((2, 3)),
    ...     moment=np.zeros((2, 3)), emitted=np.zeros((2, 2)), rays=0)
    >>> none.at_lit + none.at_centroid
    array([1., 1.])
    """

    at_lit: NDArray[np.float64]
    at_centroid: NDArray[np.float64]
    force: NDArray[np.float64]
    moment: NDArray[np.float64]
    emitted: NDArray[np.float64]
    rays: int
    tangents: tuple = ()


def core_sampling(n_sides: int, budget: int) -> tuple[int, tuple[int, int]]:
    """Finest of :data:`CORE_SAMPLINGS` whose rays over ``n_sides`` sides fit ``budget``.

    Taken over all the model's sides, so that a side's core rays depend neither on the attitude nor on
    which rays were found clear.

    Parameters
    ----------
    n_sides : int
        Sides of the model.
    budget : int
        Most core rays per attitude.

    Returns
    -------
    level : int
        Points per side along each edge of the side's sampling (``level**2`` points).
    strata : (int, int)
        Radial and azimuthal strata of the directions drawn from each point.

    Examples
    --------
    >>> core_sampling(12, 1000), core_sampling(12, 10)
    ((4, (2, 2)), (1, (1, 2)))
    """
    for level, strata in CORE_SAMPLINGS:
        if n_sides * level**2 * (strata[0] * strata[1] + 1) <= budget:
            return level, strata
    return CORE_SAMPLINGS[-1]


def core_corrections(
    craft: Spacecraft,
    flow: Illumination,
    cone: CoreCone,
    flow_law: FlowLaw,
    tables: LawTables,
    budget: int,
    tangents: Sequence[LawTables] = (),
) -> CoreCorrections:
    """The :class:`CoreCorrections` of one attitude (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    flow : Illumination
        The exact shadow along ``u = flow.direction``.
    cone : CoreCone
        The free stream's core cone.
    flow_law : FlowLaw
        The law of each side, ``u`` and the cone's cosine.
    tables : LawTables
        Each law's kernels per direction, its ``a`` and ``c``, and the side normals.
    budget : int
        Most core rays (:func:`core_sampling`).
    tangents : sequence of LawTables, optional
        Derivatives of ``tables`` with respect to a parameter of the laws: the same rays give the
        derivatives of ``force``, ``moment`` and ``emitted`` (the sums are linear in the laws), in
        :attr:`CoreCorrections.tangents`, one ``(force, moment, emitted)`` per tangent.

    Returns
    -------
    CoreCorrections
        What the core brings every side beyond the unobstructed core ``K``.

    Raises
    ------
    MemoryError
        The core rays would not fit in the memory left.

    Examples
    --------
    Every side of a convex body sees the whole core, so a cube in a stream along +x casts no core ray:

    >>> import math
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> from sunwind.forces.gas.visible import stream_tables
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> stream = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> tables = LawTables(channels=stream.directions.channels, cll=stream.directions.cll,
    ...     pressure_scale=stream.laws.pressure_scale, shear_scale=stream.laws.shear_scale,
    ...     normals=craft.side_normals)
    >>> flow_law = FlowLaw(side_law=groups.law[groups.side], u=u, cos_core=math.cos(stream.cone.half_angle))
    >>> flow = side_sampler(craft).illuminate(u, 4, None)
    >>> corrections = core_corrections(craft, flow, stream.cone, flow_law, tables, 1000)
    >>> corrections.rays, bool(np.all(corrections.at_lit + corrections.at_centroid == 1.0))
    (0, True)
    """
    n, u = craft.n_sides, flow.direction
    gamma = craft.side_normals @ u
    at_lit, at_centroid = flow.lit_fraction.copy(), 1.0 - flow.lit_fraction
    sums = [(np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 2))) for _ in range(1 + len(tangents))]
    sides = _reached(craft, u, gamma, cone.half_angle)
    at_centroid[sides] = np.where(gamma[sides] > 0.0, 0.0, 1.0)
    rays = 0
    if len(sides):
        plan = (cone, core_sampling(n, budget))
        laws = list(zip([tables, *tangents], sums, strict=True))
        rays = _sample_core(craft, sides, gamma[sides] > 0.0, plan, flow_law, laws)
    force, moment, emitted = sums[0]
    return CoreCorrections(
        at_lit=at_lit,
        at_centroid=at_centroid,
        force=force,
        moment=moment,
        emitted=emitted,
        rays=rays,
        tangents=tuple(sums[1:]),
    )


def _sample_core(
    craft: Spacecraft,
    sides: NDArray[np.int64],
    facing: NDArray[np.bool_],
    plan: tuple[CoreCone, tuple[int, tuple[int, int]]],
    flow_law: FlowLaw,
    laws: list[tuple[LawTables, tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]]],
) -> int:
    """Cast the core rays of ``sides`` (those facing ``u``: ``facing``) at ``plan`` = (cone, (level,
    strata)) and write their :func:`~sunwind.forces.gas.visible_kernels.core_sums` of each ``(tables,
    sums)`` of ``laws`` into its ``sums`` (force, moment, emitted); the rays cast."""
    cone, (level, strata) = plan
    u = flow_law.u
    points, per_point = level**2, strata[0] * strata[1]
    rows = len(sides) * points
    require(
        CORE_RAY_BYTES * rows * (per_point + 1),
        f"{count(rows * (per_point + 1))} core rays",
        "lower core_rays",
        ("core_rays",),
    )
    origins = np.empty((rows, 1, 3), dtype=np.float32)
    levers = np.empty((rows, 3))
    directions = np.empty((rows, per_point, 3), dtype=np.float32)
    weights = np.empty((rows, per_point))
    scene, clear = craft.scene, clearance(craft)
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    axes = np.array([u, e1, np.cross(u, e1)])
    frame = (scene.centre, scene.half_size, scene.offset_m)
    row_sides = np.repeat(sides, points)
    cast = np.empty((rows, per_point, 1), dtype=bool)
    control_cast = np.zeros((rows, 1, 1), dtype=bool)
    along_u = u.astype(np.float32)[None, None]

    def work(lo: int, hi: int) -> None:
        core_samples(
            sides, craft.triangles, craft.side_facet, craft.side_normals, level, frame, axes,
            cone.psi_quantiles, strata, np.uint64(CORE_SEED), origins, levers, directions, weights, lo, hi,
        )  # fmt: skip
        first, last = lo * points, hi * points
        may_be_blocked(row_sides, origins, directions, craft.side_normals, clear.arrays, cast, first, last)
        may_be_blocked(
            row_sides, origins, along_u, craft.side_normals, clear.arrays, control_cast, first, last
        )

    map_ranges(work, len(sides), max(1, MIN_SIDES_PER_CHUNK // points))
    control_cast[~np.repeat(facing, points)] = False
    blocked, control_blocked, rays = _cast(scene, origins, directions, cast[:, :, 0] & (weights > 0.0),
                                           control_cast[:, 0, 0], along_u[0])  # fmt: skip
    samples = (directions, weights, levers)
    for tables, sums in laws:
        map_ranges(
            lambda lo, hi, tables=tables, sums=sums: core_sums(
                points,
                facing,
                control_blocked,
                blocked,
                samples,
                sides,
                flow_law,
                tables,
                cone.normaliser,
                *sums,
                lo,
                hi,
            ),
            len(sides),
            MIN_SIDES_PER_CHUNK,
        )
    return rays


def _reached(craft: Spacecraft, u: NDArray[np.float64], gamma: NDArray[np.float64], half: float) -> NDArray:
    """Sides whose open hemisphere the cone of ``half`` [rad] about ``u`` enters and that it may reach
    obstructed (:func:`~sunwind.geometry.rays.clear_kernels.cone_may_be_blocked`)."""
    clear = clearance(craft)
    sides = np.flatnonzero((gamma > -math.sin(half)) & ~clear.open_sky)
    spheres = craft.cache.get("side spheres", lambda: _side_spheres(craft))
    reached = np.empty(len(sides), dtype=bool)
    map_ranges(
        lambda lo, hi: cone_may_be_blocked(sides, spheres, u, half, clear.arrays, reached, lo, hi),
        len(sides),
        MIN_SIDES_PER_CHUNK,
    )
    return sides[reached]


def _side_spheres(craft: Spacecraft) -> NDArray[np.float64]:
    """Each side's centroid and the largest distance of a corner from it, scene coordinates, (n_sides, 4)."""
    scene = craft.scene
    corners = (craft.triangles[craft.side_facet] - scene.centre) / scene.half_size
    centre = corners.mean(axis=1)
    reach = np.linalg.norm(corners - centre[:, None], axis=2).max(axis=1)
    return np.column_stack([centre, reach])


def _cast(scene, origins, directions, cast, control_cast, along_u) -> tuple[NDArray, NDArray, int]:
    """Cast the core rays ``cast`` (rows, J) and the rays along ``u`` ``control_cast`` (rows,) in one
    batch; whether each met the model (False where not cast), and the rays cast."""
    core_rows, core_cols = np.nonzero(cast)
    control = np.flatnonzero(control_cast)
    ray_origins = np.concatenate([origins[core_rows, 0], origins[control, 0]])
    ray_directions = np.concatenate(
        [directions[core_rows, core_cols], np.broadcast_to(along_u, (len(control), 3))]
    )
    hit = scene.occluded(ray_origins, ray_directions) if len(ray_origins) else np.zeros(0, dtype=bool)
    blocked = np.zeros(cast.shape, dtype=bool)
    blocked[core_rows, core_cols] = hit[: len(core_rows)]
    control_blocked = np.zeros(len(control_cast), dtype=bool)
    control_blocked[control] = hit[len(core_rows) :]
    return blocked, control_blocked, len(ray_origins)
