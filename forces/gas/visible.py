"""What of the incident stream reaches each side, and the force, torque and first re-emission it gives
there (METHOD.md "The open-sky integral").

A side takes the drifting Maxwellian integrated over the directions from which it sees open sky. The
integral is split at the core cone about the flow (:mod:`.core_cone`):

- **core**: the exact shadow along ``u`` (the caller's: the default shadow pass, or fixed points) gives
  its lit share ``f_u`` and lit centroid; rays from jittered points of the side along directions drawn
  from the kernel within the cone, each beside a ray along ``u`` from the same point, give what the core
  adds beyond ``f_u`` (a difference that vanishes as ``S -> inf``, so the hyperthermal limit is the
  shadow pass alone; :mod:`.core_rays`);
- **rest**: the kernel summed over the side's sampled sky rays (:mod:`sunwind.geometry.views.sky`),
  outside the cone.

An unobstructed side gets the closed form exactly; so does every side of a convex body, which casts
nothing beyond the shadow pass. Rays that provably meet nothing are not cast
(:mod:`sunwind.geometry.rays.hull`); the others go to Embree in one batch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.angular import DirectionTables, SpeciesLaws, cll_normal_table, direction_tables
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.core_cone import CoreCone, core_cone
from sunwind.forces.gas.core_rays import MIN_SIDES_PER_CHUNK, core_corrections
from sunwind.forces.gas.laws import GasSurfaces
from sunwind.forces.gas.panel import GasGroups, species_laws
from sunwind.forces.gas.visible_kernels import (
    CoreParts,
    FlowLaw,
    GroupLoads,
    LawTables,
    SideGeometry,
    SkyParts,
    core_loads,
    side_loads,
    sky_sums,
)
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.sky import SKY_SEED, OpenSky, open_sky


@dataclass(frozen=True, eq=False)
class Arrival:
    """What the incident stream of one attitude does on every side; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (n_sides, 3) float64
        Force on each side, and its torque about the reference point.
    emitted : (2, n_sides) float64
        The first diffuse re-emission of each side: momentum per second [N] and sqrt(mass)-weighted
        molecules per second [sqrt(kg)/s] (:mod:`sunwind.forces.gas.exchange`).
    lit_load : (n_sides, 3) float64
        What one unit of a side's area that the shadow along ``u`` leaves lit takes of the stream [Pa]:
        the core ``K`` of an unobstructed side (what an error in ``f_u`` costs; exact where the side's
        core is followed by rays, an upper bound where it sees the whole core and ``f_u`` only places it).
    rays : int
        Rays cast: the shadow pass's and the core's.
    core_half_angle : float
        ``psi_c`` [rad].
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    emitted: NDArray[np.float64]
    lit_load: NDArray[np.float64]
    rays: int
    core_half_angle: float


def model_sky(craft: Spacecraft, rays_per_side: int | None = None, cache_dir=None) -> OpenSky:
    """The :class:`~sunwind.geometry.views.sky.OpenSky` of ``craft``: from its cache, else the disk cache,
    else sampled (and kept in both)."""
    return craft.cache.get(
        ("open sky", rays_per_side, str(cache_dir)),
        lambda: open_sky(craft, rays_per_side, SKY_SEED, cache_dir),
    )


@dataclass(frozen=True, eq=False)
class StreamTables:
    """What one free stream gives every attitude alike: its species and each law's answer, the
    kernels per direction and the core cone (which depend on ``gamma``, not on the flow direction)."""

    laws: SpeciesLaws
    directions: DirectionTables
    cone: CoreCone


def stream_tables(
    craft: Spacecraft, surfaces: GasSurfaces, atmosphere: Atmosphere, speed_m_s: float
) -> StreamTables:
    """The :class:`StreamTables` of the free stream ``atmosphere`` at ``speed_m_s`` on ``craft``'s laws
    ``surfaces``; the last stream's are kept in the model's cache, so a sweep's attitudes share them.

    They are made for the speed rounded to 13 significant digits, so that attitudes whose ``v_rel``
    differ in length by round-off share them, and every attitude gets the same bits whichever came
    first (a relative change below 5e-14)."""
    speed = float(f"{speed_m_s:.13g}")
    key = (speed, atmosphere.temperature_K, tuple(atmosphere.number_density_m3.items()))
    kept: dict = craft.cache.get("stream tables", dict)
    if key not in kept:
        laws = species_laws(surfaces, atmosphere, speed)
        tables = cll_tables(craft, laws)
        kept.clear()
        kept[key] = StreamTables(laws, direction_tables(laws, tables), core_cone(laws, tables))
    return kept[key]


def cll_tables(craft: Spacecraft, laws: SpeciesLaws) -> dict[int, NDArray[np.float64]]:
    """:func:`~sunwind.forces.gas.angular.cll_normal_table` of every CLL law, reaching the species'
    largest ``S`` (rounded up to a whole number so that attitudes share it); kept in the model's cache."""
    s_high = float(math.ceil(laws.speed_ratio.max()))
    out = {}
    for law in np.flatnonzero(np.isfinite(laws.cll_alpha_n)):
        alpha, tau = float(laws.cll_alpha_n[law]), float(laws.cll_tau_w[law])
        out[int(law)] = craft.cache.get(
            ("CLL normal table", alpha, tau, s_high), lambda a=alpha, t=tau: cll_normal_table(a, t, s_high)
        )
    return out


def arrival(
    craft: Spacecraft,
    groups: GasGroups,
    stream: tuple[NDArray[np.float64], StreamTables],
    flow: Illumination,
    reference_m: NDArray[np.float64],
    sky: OpenSky,
    core_rays: int,
) -> Arrival:
    """What the incident stream of one attitude does on every side (module docstring).

    Parameters
    ----------
    craft : Spacecraft
    groups : GasGroups
        The model's sides grouped by law and normal.
    stream : (closed, tables)
        What the whole stream does on an unobstructed side of each group, (n_groups, 5): force per unit
        area [Pa] (3) and first re-emission (2); and the free stream's :class:`StreamTables`.
    flow : Illumination
        The exact shadow along ``u = flow.direction`` (the unit flow vector ``v_rel / |v_rel|``).
    reference_m : (3,) float64
        Torque reference point [m].
    sky : OpenSky
        The model's sampled open sky.
    core_rays : int
        Most rays of the core per attitude (:func:`core_sampling`).
    """
    closed, tables = stream
    u = flow.direction
    laws, directions, cone = tables.laws, tables.directions, tables.cone
    n = craft.n_sides
    side_law = groups.law[groups.side]
    law_tables = LawTables(
        channels=directions.channels,
        cll=directions.cll,
        pressure_scale=laws.pressure_scale,
        shear_scale=laws.shear_scale,
        normals=craft.side_normals,
    )
    flow_law = FlowLaw(side_law=side_law, u=u, cos_core=math.cos(cone.half_angle))
    core = core_corrections(craft, flow, cone, flow_law, law_tables, core_rays)
    sky_force, sky_moment, sky_emitted = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros((n, 2))
    with_rays = np.flatnonzero(np.diff(sky.start) > 0)
    map_ranges(
        lambda lo, hi: sky_sums(
            with_rays,
            sky.start,
            (sky.direction, sky.lever),
            flow_law,
            law_tables,
            math.pi / sky.rays_per_side,
            sky_force,
            sky_moment,
            sky_emitted,
            lo,
            hi,
        ),
        len(with_rays),
        256,
    )
    force, torque, emitted = np.empty((3, n)), np.empty((3, n)), np.empty((2, n))
    core_parts = CoreParts(
        at_lit=core.at_lit,
        at_centroid=core.at_centroid,
        lit_centroid=flow.lit_centroid,
        force=core.force,
        moment=core.moment,
        emitted=core.emitted,
    )
    sky_parts = SkyParts(keeps_open=sky.keeps_open, force=sky_force, moment=sky_moment, emitted=sky_emitted)
    map_ranges(
        lambda lo, hi: side_loads(
            groups.side,
            GroupLoads(law=groups.law, normals=groups.normals, closed=closed),
            cone.gamma_table,
            u,
            SideGeometry(areas=craft.side_areas, centroids=craft.side_centroids),
            core_parts,
            sky_parts,
            reference_m,
            force,
            torque,
            emitted,
            lo,
            hi,
        ),
        n,
        MIN_SIDES_PER_CHUNK,
    )
    lit_load = np.empty((n, 3))
    core_loads(groups.side, groups.law, groups.normals, cone.gamma_table, u, lit_load)
    return Arrival(force.T, torque.T, emitted, lit_load, flow.rays + core.rays, cone.half_angle)
