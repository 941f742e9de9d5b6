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
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.angular import DirectionTables, SpeciesLaws, cll_normal_table, direction_tables
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.core_cone import CoreCone, core_cone
from sunwind.forces.gas.core_rays import MIN_SIDES_PER_CHUNK, CoreCorrections, core_corrections
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
    tangents : tuple of (force, torque, emitted)
        Per :class:`PanelTangent` given to :func:`arrival`, the derivatives of ``force_N``,
        ``torque_Nm`` and ``emitted``.

    Examples
    --------
    >>> import numpy as np
    >>> zero = np.zeros((1, 3))
    >>> one_side = Arrival(zero, zero, np.zeros((2, 1)), zero, rays=0, core_half_angle=0.3)
    >>> one_side.force_N.shape
    (1, 3)
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    emitted: NDArray[np.float64]
    lit_load: NDArray[np.float64]
    rays: int
    core_half_angle: float
    tangents: tuple = ()


class PanelTangent(NamedTuple):
    """Derivatives of one free stream's laws with respect to one parameter, as :func:`arrival` reads
    them (:mod:`sunwind.forces.gas.tangents` makes them).

    Attributes
    ----------
    closed : (n_groups, 5) float64
        Derivative of the closed-form loads of each group (:func:`~sunwind.forces.gas.panel.closed_loads`).
    channels : (n_laws, X_POINTS, N_CHANNELS) float64
        Direction tables: ``k_P`` itself in the momentum channel, the derivatives in the others.
    cll : (n_laws, X_POINTS, MU_POINTS) float64 or None
        Derivative of CLL's reflected normal momentum; None where no law is CLL.
    pressure_scale, shear_scale : (n_laws,) float64
        Derivatives of ``a`` and ``c``.
    gamma_table : (n_laws, 4, GAMMA_POINTS) float64
        Derivative of the core cone's table.

    Examples
    --------
    >>> zero = np.zeros(1)
    >>> PanelTangent(np.zeros((1, 5)), np.zeros((1, 4097, 4)), None, zero, zero, np.zeros((1, 4, 513))).cll
    """

    closed: NDArray[np.float64]
    channels: NDArray[np.float64]
    cll: NDArray[np.float64] | None
    pressure_scale: NDArray[np.float64]
    shear_scale: NDArray[np.float64]
    gamma_table: NDArray[np.float64]


def model_sky(craft: Spacecraft, rays_per_side: int | None = None, cache_dir=None) -> OpenSky:
    """Sampled open sky of ``craft``: from its cache, else the disk cache, else sampled and kept in both.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    rays_per_side : int, optional
        Sky rays per side; None for the default of :func:`sunwind.geometry.views.sky.open_sky`.
    cache_dir : path, None or False, optional
        Disk cache directory as for :class:`~sunwind.forces.reflection.settings.ReflectionSettings`:
        None for the default directory, False for no disk cache.

    Returns
    -------
    OpenSky
        Each side's open-sky rays and which sides see the whole sky.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> sky = model_sky(craft, 16, cache_dir=False)
    >>> sky.rays_per_side, model_sky(craft, 16, cache_dir=False) is sky
    (16, True)
    """
    return craft.cache.get(
        ("open sky", rays_per_side, str(cache_dir)),
        lambda: open_sky(craft, rays_per_side, SKY_SEED, cache_dir),
    )


@dataclass(frozen=True, eq=False)
class StreamTables:
    """Tables of one free stream that every attitude shares.

    They hold the stream's species and each law's answer, the kernels per direction, and the core cone;
    all depend on ``gamma = n . u``, not on the flow direction itself.

    Parameters
    ----------
    laws : SpeciesLaws
        The free stream by species and how each gas-surface law answers it.
    directions : DirectionTables
        The kernels of each law per direction of arrival.
    cone : CoreCone
        The core cone about the flow.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> tables = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> tables.laws.speed_ratio.round(3), tables.cone.half_angle
    (array([7.357]), 0.3)
    """

    laws: SpeciesLaws
    directions: DirectionTables
    cone: CoreCone


def stream_tables(
    craft: Spacecraft, surfaces: GasSurfaces, atmosphere: Atmosphere, speed_m_s: float
) -> StreamTables:
    """Stream tables of the free stream ``atmosphere`` at ``speed_m_s`` on ``craft``'s gas-surface laws.

    The last stream's tables are kept in the model's cache, so the attitudes of a sweep share them. They
    are made for the speed rounded to 13 significant digits: attitudes whose ``v_rel`` differ in length
    by round-off share them, and every attitude gets the same bits whichever came first (a relative change
    below 5e-14).

    Parameters
    ----------
    craft : Spacecraft
        The model, whose cache keeps the tables.
    surfaces : GasSurfaces
        The model's distinct gas-surface laws (:attr:`GasGroups.surfaces
        <sunwind.forces.gas.panel.GasGroups>`).
    atmosphere : Atmosphere
        Number densities and temperature of the free stream.
    speed_m_s : float
        Flow speed ``|v_rel|`` [m/s].

    Returns
    -------
    StreamTables
        The species and laws, the direction tables and the core cone.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> tables = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> stream_tables(craft, groups.surfaces, air, 7500.0 * (1 + 1e-15)) is tables
    True
    """
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
    """CLL normal-momentum table of every CLL law of ``laws``, kept in the model's cache.

    Each reaches the species' largest speed ratio rounded up to a whole number, so that attitudes share
    it (:func:`~sunwind.forces.gas.angular.cll_normal_table`).

    Parameters
    ----------
    craft : Spacecraft
        The model, whose cache keeps the tables.
    laws : SpeciesLaws
        The free stream by species and each law's answer; CLL laws have a finite ``cll_alpha_n``.

    Returns
    -------
    dict of int to ndarray
        Index of each CLL law to its table, (n_s, MU_POINTS); empty when no law is CLL.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> from sunwind.forces.gas.panel import species_laws
    >>> cll_tables(craft, species_laws(groups.surfaces, air, 7500.0))
    {}
    """
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
    tangents: Sequence[PanelTangent] = (),
) -> Arrival:
    """What the incident stream of one attitude does on every side (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model.
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
        Most rays of the core per attitude
        (:func:`~sunwind.forces.gas.core_rays.core_sampling`).
    tangents : sequence of PanelTangent, optional
        Derivatives of the laws with respect to a parameter; the same rays give the derivatives of
        force, torque and first re-emission of every side (:attr:`Arrival.tangents`).

    Returns
    -------
    Arrival
        Force, torque and first re-emission of every side, and the rays cast.

    Examples
    --------
    A unit cube in a stream along +x:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> from sunwind.forces.gas.panel import closed_loads, summed_laws
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> tables = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> gamma = groups.normals @ u
    >>> closed = closed_loads(groups, gamma, summed_laws(groups, gamma, tables.laws, 1000.0), u)
    >>> flow = side_sampler(craft).illuminate(u, 4, None)
    >>> sky = model_sky(craft, 16, cache_dir=False)
    >>> result = arrival(craft, groups, (closed, tables), flow, np.zeros(3), sky, 1000)
    >>> result.force_N.shape, result.emitted.shape
    ((12, 3), (2, 12))
    """
    closed, tables = stream
    u = flow.direction
    laws, directions, cone = tables.laws, tables.directions, tables.cone
    side_law = groups.law[groups.side]
    law_tables = LawTables(
        channels=directions.channels,
        cll=directions.cll,
        pressure_scale=laws.pressure_scale,
        shear_scale=laws.shear_scale,
        normals=craft.side_normals,
    )
    tangent_tables = [
        LawTables(
            channels=t.channels,
            cll=t.cll,
            pressure_scale=t.pressure_scale,
            shear_scale=t.shear_scale,
            normals=craft.side_normals,
        )
        for t in tangents
    ]
    flow_law = FlowLaw(side_law=side_law, u=u, cos_core=math.cos(cone.half_angle))
    core = core_corrections(craft, flow, cone, flow_law, law_tables, core_rays, tangent_tables)
    plan = (craft, groups, flow, flow_law, sky, reference_m)
    core_sums = (core.force, core.moment, core.emitted)
    force, torque, emitted = _side_totals(plan, law_tables, closed, cone.gamma_table, core, core_sums)
    derivatives = tuple(
        _side_totals(plan, law, t.closed, t.gamma_table, core, sums)
        for t, law, sums in zip(tangents, tangent_tables, core.tangents, strict=True)
    )
    lit_load = np.empty((craft.n_sides, 3))
    core_loads(groups.side, groups.law, groups.normals, cone.gamma_table, u, lit_load)
    rays = flow.rays + core.rays
    return Arrival(force, torque, emitted, lit_load, rays, cone.half_angle, tangents=derivatives)


def _side_totals(
    plan: tuple,
    law_tables: LawTables,
    closed: NDArray[np.float64],
    gamma_table: NDArray[np.float64],
    core: CoreCorrections,
    core_sums: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Force (n, 3), torque (n, 3) and first re-emission (2, n) of every side for one set of laws
    (or their derivatives): the sky sums and the sides' loads; ``plan`` = (craft, groups, flow,
    flow_law, sky, reference)."""
    craft, groups, flow, flow_law, sky, reference_m = plan
    n, u = craft.n_sides, flow.direction
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
    core_force, core_moment, core_emitted = core_sums
    core_parts = CoreParts(
        at_lit=core.at_lit,
        at_centroid=core.at_centroid,
        lit_centroid=flow.lit_centroid,
        force=core_force,
        moment=core_moment,
        emitted=core_emitted,
    )
    sky_parts = SkyParts(keeps_open=sky.keeps_open, force=sky_force, moment=sky_moment, emitted=sky_emitted)
    map_ranges(
        lambda lo, hi: side_loads(
            groups.side,
            GroupLoads(law=groups.law, normals=groups.normals, closed=closed),
            gamma_table,
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
    return force.T, torque.T, emitted
