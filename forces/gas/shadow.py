"""Which share of each side's incident molecules arrives unobstructed: the flow's shadow on the model
(METHOD.md "Free-molecular flow").

Molecules arrive from directions within about ``1/S`` of the flow (thermal speed over flow speed). A
side facing the flow takes them on the share the hyperthermal shadow along ``u = v_rel/|v_rel|``
leaves lit, or (default) the share lit along directions spread by the thermal speed: the penumbra that
lets the walls of a cavity intercept molecules the floor would get. A lee or edge-on side takes them
from upstream along its plane. Rays that provably meet nothing (:mod:`sunwind.geometry.rays.hull`) are
not cast; the others of an attitude go to Embree in one batch where they can.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.shadow_kernels import (
    gather_rays,
    incidences,
    lee_rays,
    lit_shares,
    may_be_blocked,
    spread_visibility,
)
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.shadows import Illumination, level_for_samples, side_sampler
from sunwind.geometry.spacecraft import Spacecraft

#: Fewest sides in a chunk of the parallel per-side kernels.
MIN_SIDES_PER_CHUNK = 8192


def _spread_directions(u: NDArray[np.float64], speed_ratio: float) -> NDArray[np.float64]:
    """The four unit directions ``u +- e_k / S`` of the thermal spread, (4, 3) (:func:`flow_shadow`)."""
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    directions = u + np.array([e1, -e1, e2, -e2]) / speed_ratio
    return directions / np.linalg.norm(directions, axis=1)[:, None]


class _RayBatch:
    """Rays of several kinds queued to be cast in one call, then handed back kind by kind."""

    def __init__(self) -> None:
        self.origins: list[NDArray[np.float32]] = []
        self.directions: list[NDArray[np.float32]] = []

    def add(self, origins: NDArray[np.float32], directions: NDArray[np.float32]) -> int:
        """Queue rays (n, 3) in scene coordinates; returns their place in :meth:`cast`'s answer."""
        self.origins.append(origins)
        self.directions.append(directions)
        return len(self.origins) - 1

    def cast(self, craft: Spacecraft) -> list[NDArray[np.bool_]]:
        """Whether each queued ray meets the model, one array per :meth:`add`."""
        if not self.origins:
            return []
        blocked = craft.scene.occluded(np.concatenate(self.origins), np.concatenate(self.directions))
        return np.split(blocked, np.cumsum([len(o) for o in self.origins])[:-1])


class _Shadow(NamedTuple):
    """Shadow rays from sides facing some directions, queued in a :class:`_RayBatch`."""

    incidence: NDArray[np.float64]  # max(n . d, 0) of each side and direction, (n, m)
    pair: NDArray[np.int64]  # i m + j of each ray cast (side row i, direction j)
    batch: int  # place of the rays in the batch
    points: int  # rays per side and direction, cast or not

    def lit(self, blocked: list[NDArray[np.bool_]]) -> NDArray[np.float64]:
        """Lit share of each side along each direction, (n, m), from the batch's answer."""
        return lit_shares(self.pair, blocked[self.batch], self.points, *self.incidence.shape)


def flow_shadow(
    craft: Spacecraft,
    u: NDArray[np.float64],
    gamma: NDArray[np.float64],
    speed_ratio: float,
    spread: bool,
    samples: int | None,
    tolerance: float,
) -> tuple[Illumination, NDArray[np.float64]]:
    """The shadow of the flow along ``u``, and the share of each side's incident molecular flux that
    arrives unobstructed, (n_sides,).

    Molecules arrive from directions within about ``1/S`` of ``u`` (thermal speed over flow speed).
    A side facing the flow: its lit share along ``u`` when ``spread`` is off (the hyperthermal
    shadow); with ``spread``, the lit shares along the four directions ``u +- e_k / S`` (``e_1``,
    ``e_2`` normal to ``u``: the molecules' thermal velocity at one thermal speed, a rule exact for
    the second moments of the thermal spread), each weighted by its incidence on the side, so the
    shadow has the penumbra the thermal spread gives it. A lee or edge-on side: the direction
    upstream along its plane raised by ``atan(1/S)`` toward its normal, one ray from its centroid.
    Every direction counted lies in the side's own open hemisphere, so on a convex body nothing is
    blocked at any speed ratio. ``gamma`` is ``n . u`` of each side.

    Rays that provably meet nothing (:mod:`sunwind.geometry.rays.hull`) are not cast. With a fixed sample
    count
    whose ray origins the sampler keeps, the spread's rays are cast in one batch with the lee probes,
    and with one point per side the shadow rays along ``u`` too; otherwise the shadow along ``u`` and
    along each spread direction is a pass of :meth:`sunwind.geometry.rays.shadows.SideSampler.illuminate`.
    """
    sampler, batch = side_sampler(craft), _RayBatch()
    level = None if samples is None else level_for_samples(samples)
    facing, kept = (None, None) if level is None else sampler.facing_rays(u, level)
    # with one point per side the flow's shadow is lit shares of 0 or 1: its rays join the batch
    own_flow = level == 1 and kept is not None
    directions = _spread_directions(u, speed_ratio) if spread else np.empty((0, 3))
    passes = None  # with no kept origins, a shadow pass along u and each spread direction
    if not own_flow:
        along = np.concatenate([u[None], directions]) if kept is None else u[None]
        passes = _shadow_passes(sampler, along, samples, tolerance)
    flow = None if own_flow else passes[0]
    facing = facing if flow is None else flow.facing
    if own_flow:
        directions = np.concatenate([u[None], directions])
    shadow = None
    if kept is not None and len(directions):
        shadow = _shadow_rays(craft, facing, kept, directions, batch)
    lee = np.ones(craft.n_sides, dtype=bool)
    lee[facing] = False
    lee = np.flatnonzero(lee)
    probed, probes = _lee_rays(craft, u, lee, gamma[lee], speed_ratio, batch)
    blocked = batch.cast(craft)
    incidence, lit = (None, None) if shadow is None else (shadow.incidence, shadow.lit(blocked))
    if own_flow:
        rays = int(np.count_nonzero(shadow.pair % len(directions) == 0))
        sampling = f"{level**2} points per side"
        runs = (facing,), (lit[:, 0].astype(np.float64),)
        flow = Illumination(u, craft.side_normals, *runs, craft.side_centroids, rays, sampling, level)
        incidence, lit = incidence[:, 1:], lit[:, 1:]
    visible = np.array(flow.lit_fraction, dtype=np.float64)
    visible[lee] = 1.0
    visible[lee[probed]] = np.where(blocked[probes], 0.0, 1.0)
    if spread:
        if lit is None:  # a shadow pass along each direction
            incidence = np.empty((len(facing), len(directions)))
            incidences(facing, craft.side_normals, directions, incidence, 0, len(facing))
            lit = np.column_stack([light.lit_fraction[facing] for light in passes[1:]])
        spread_visibility(facing, incidence, lit, visible)
    return flow, visible


def _shadow_passes(sampler, directions: NDArray[np.float64], samples: int | None, tolerance: float) -> list:
    """:meth:`~sunwind.geometry.rays.shadows.SideSampler.illuminate` along each of ``directions``, the
    passes shared among the threads (each runs serially inside its thread)."""
    chunks = map_ranges(
        lambda lo, hi: [sampler.illuminate(d, samples, tolerance) for d in directions[lo:hi]],
        len(directions),
        1,
    )
    return [light for chunk in chunks for light in chunk]


def _clearance_arrays(craft: Spacecraft) -> tuple[NDArray, ...]:
    """The arrays of :func:`sunwind.geometry.rays.hull.clearance` in the order the ray kernels take them."""
    clear = clearance(craft)
    return clear.open_sky, clear.own_part_clear, clear.blockers, clear.box_low, clear.box_high


def _lee_rays(
    craft: Spacecraft,
    u: NDArray[np.float64],
    lee: NDArray[np.int64],
    gamma: NDArray[np.float64],
    speed_ratio: float,
    batch: _RayBatch,
) -> tuple[NDArray[np.int64], int]:
    """Queue the probe rays of the ``lee`` sides (``gamma`` = ``n . u`` of each) that may meet the model
    (:func:`flow_shadow`); returns their rows of ``lee`` and their place in ``batch``."""
    scene, n = craft.scene, len(lee)
    origins, probes = np.empty((n, 1, 3), dtype=np.float32), np.empty((n, 1, 3), dtype=np.float32)
    cast = np.empty((n, 1, 1), dtype=bool)
    elevation, frame = math.atan(1.0 / speed_ratio), (scene.centre, scene.half_size, scene.offset_m)
    clear = _clearance_arrays(craft)

    def work(lo: int, hi: int) -> None:
        lee_rays(
            lee, gamma, craft.side_normals, craft.side_centroids, u, elevation, frame, origins, probes, lo, hi
        )
        may_be_blocked(lee, origins, probes, craft.side_normals, clear, cast, lo, hi)

    map_ranges(work, n, MIN_SIDES_PER_CHUNK)
    probed = np.flatnonzero(cast[:, 0, 0])
    return probed, batch.add(origins[probed, 0], probes[probed, 0])


def _shadow_rays(
    craft: Spacecraft,
    facing: NDArray[np.int64],
    origins: NDArray[np.float32],
    directions: NDArray[np.float64],
    batch: _RayBatch,
) -> _Shadow:
    """Queue the shadow rays from the ``facing`` sides' ``origins`` (n, p, 3) along ``directions``
    (m, 3) that may meet the model, direction by direction; a side casts none along a direction it does
    not face."""
    rays = directions.astype(np.float32)
    clear = _clearance_arrays(craft)
    incidence = np.empty((len(facing), len(rays)))
    cast = np.empty((len(facing), len(rays), origins.shape[1]), dtype=bool)

    def work(lo: int, hi: int) -> None:
        incidences(facing, craft.side_normals, directions, incidence, lo, hi)
        may_be_blocked(facing, origins, rays[None], craft.side_normals, clear, cast, lo, hi)

    map_ranges(work, len(facing), MIN_SIDES_PER_CHUNK)
    pair, ray_origins, ray_directions = gather_rays(cast, incidence, origins, rays)
    return _Shadow(incidence, pair, batch.add(ray_origins, ray_directions), origins.shape[1])
