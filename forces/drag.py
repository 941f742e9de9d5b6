"""Free-molecular force and torque at one attitude (METHOD.md "Free-molecular flow", "Shadowing").

Per species ``k`` and side ``i`` the gas-surface law (:mod:`sunwind.forces.gas.laws`) gives pressure and
shear for
the incident drifting Maxwellian, split exactly into a *directed* stream (a cold beam along the flow)
and the *thermal* rest. Both reach a side where its view toward the molecules' directions of arrival
is open (:func:`_flow_shadow`):

* a side facing the flow takes them on the share the hyperthermal shadow along ``u = v_rel/|v_rel|``
  leaves lit, or (default) the share lit along directions spread by the thermal speed over the flow
  speed: the penumbra that lets the walls of a cavity intercept molecules the floor would get;
* a lee or edge-on side takes its thermal flux from upstream along its plane.

On a convex body nothing is blocked: the result is the per-side sum of the gas-surface law, lee
faces included, at every speed ratio. With ``full``, re-emitted molecules landing on other sides are
re-emitted again (:mod:`sunwind.forces.gas.exchange`).

Speed (METHOD.md "Speed"). Sides of one law and one normal share every coefficient: the laws are
evaluated once per such group, summed over species in one pass
(:func:`sunwind.forces.gas.laws.summed_coefficients`).
Rays that provably meet nothing are not cast (:mod:`sunwind.geometry.rays.hull`); the others of an attitude
go to
Embree in one batch. Per-side kernels run on the threads of :mod:`sunwind.geometry.parallel` and write
per-side results, which are summed afterwards: results do not depend on the number of threads.
"""

from __future__ import annotations

import math
import warnings
import weakref
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.drag_result import DragResult, GasReflected
from sunwind.forces.gas.atmosphere import BOLTZMANN, Atmosphere
from sunwind.forces.gas.exchange import gas_interference_criterion, mean_momentum, molecular_exchange
from sunwind.forces.gas.kernels import (
    gather_rays,
    group_stresses,
    incidences,
    lee_rays,
    lit_shares,
    may_be_blocked,
    side_forces,
    spread_visibility,
)
from sunwind.forces.gas.laws import diffuse_emission, summed_coefficients
from sunwind.forces.reflection.plan import AUTO_THRESHOLD, ReflectionSettings, model_view_factors
from sunwind.forces.srp import reference_point
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, Illumination, level_for_samples
from sunwind.geometry.spacecraft import Spacecraft

#: Inter-reflection modes of molecules (specular chains are followed for light only).
DRAG_MODES = ("none", "full", "auto")
#: Speed ratio below which the panel method's flow shadowing is a rough approximation on concave
#: shapes (the directed/thermal split; convex shapes stay exact).
LOW_SPEED_RATIO = 3.0
#: Gas-law columns of :attr:`Spacecraft.side_gas`, in the order of
# :func:`sunwind.forces.gas.laws.panel_coefficients`.
_LAW_FIELDS = (
    "code",
    "energy_accommodation",
    "normal_accommodation",
    "tangential_accommodation",
    "wall_temperature_K",
)
#: Fewest sides in a chunk of the parallel per-side kernels.
_MIN_SIDES_PER_CHUNK = 8192


class LowSpeedRatioWarning(UserWarning):
    """The flow's speed ratio is below :data:`LOW_SPEED_RATIO`."""


@dataclass(frozen=True)
class _GasGroups:
    """The sides of one model grouped by gas-surface law and normal (equal bits): sides of a group
    share ``gamma`` and every coefficient, so the gas-surface laws are evaluated once per group."""

    laws: tuple[NDArray, ...]  # code, alpha_E, sigma_n, sigma_t, T_w of each distinct law, (n_laws,)
    law: NDArray[np.int64]  # law of each group, (n_groups,)
    normals: NDArray[np.float64]  # (n_groups, 3)
    side: NDArray[np.int64]  # group of each side, (n_sides,)


_groups: weakref.WeakKeyDictionary[Spacecraft, _GasGroups] = weakref.WeakKeyDictionary()


def _gas_groups(craft: Spacecraft) -> _GasGroups:
    """The :class:`_GasGroups` of ``craft``, made once and kept with the model."""
    if craft not in _groups:
        gas = craft.side_gas
        columns = np.column_stack([gas[name].astype(np.float64) for name in _LAW_FIELDS])
        table, side_law = np.unique(columns, axis=0, return_inverse=True)
        keys = np.column_stack([side_law.reshape(-1), craft.side_normals])
        _, first, side_group = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        laws = (table[:, 0].astype(np.int8), *(np.ascontiguousarray(table[:, j]) for j in range(1, 5)))
        _groups[craft] = _GasGroups(
            laws=laws,
            law=side_law.reshape(-1)[first].astype(np.int64),
            normals=np.ascontiguousarray(craft.side_normals[first]),
            side=side_group.reshape(-1).astype(np.int64),
        )
    return _groups[craft]


def _spread_directions(u: NDArray[np.float64], speed_ratio: float) -> NDArray[np.float64]:
    """The four unit directions ``u +- e_k / S`` of the thermal spread, (4, 3) (:func:`_flow_shadow`)."""
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


def _flow_shadow(
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
    sampler, batch = craft.sampler, _RayBatch()
    level = None if samples is None else level_for_samples(samples)
    facing, kept = (None, None) if level is None else sampler.facing_rays(u, level)
    # with one point per side the flow's shadow is lit shares of 0 or 1: its rays join the batch
    own_flow = level == 1 and kept is not None
    flow = None if own_flow else sampler.illuminate(u, samples, tolerance)
    facing = facing if flow is None else flow.facing
    directions = _spread_directions(u, speed_ratio) if spread else np.empty((0, 3))
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
            passes = [sampler.illuminate(d, samples, tolerance).lit_fraction[facing] for d in directions]
            lit = np.column_stack(passes)
        spread_visibility(facing, incidence, lit, visible)
    return flow, visible


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
    (:func:`_flow_shadow`); returns their rows of ``lee`` and their place in ``batch``."""
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

    map_ranges(work, n, _MIN_SIDES_PER_CHUNK)
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

    map_ranges(work, len(facing), _MIN_SIDES_PER_CHUNK)
    pair, ray_origins, ray_directions = gather_rays(cast, incidence, origins, rays)
    return _Shadow(incidence, pair, batch.add(ray_origins, ray_directions), origins.shape[1])


def _settings(reflections: str | ReflectionSettings) -> ReflectionSettings:
    settings = reflections if isinstance(reflections, ReflectionSettings) else ReflectionSettings(reflections)
    if settings.mode not in DRAG_MODES:
        raise InputError(
            f"--reflections {settings.mode} is for light only",
            hint=f"for molecules use one of {', '.join(DRAG_MODES)}",
        )
    return settings


def drag(
    craft: Spacecraft,
    velocity_m_s: Sequence[float] | NDArray,
    atmosphere: Atmosphere,
    *,
    reference_point_m: Sequence[float] | NDArray | None = None,
    samples: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    reflections: str | ReflectionSettings = "auto",
    reference_area_m2: float | None = None,
    reference_length_m: float | None = None,
    thermal_spread: bool = True,
) -> DragResult:
    """Free-molecular force and torque with flow shadowing and molecular inter-reflection.

    Parameters
    ----------
    craft : Spacecraft
    velocity_m_s : (3,) array_like
        ``v_rel``, the spacecraft's velocity relative to the atmosphere, body frame [m/s].
    atmosphere : Atmosphere
        Number density of every species and the temperature (:mod:`sunwind.forces.gas.atmosphere`).
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default as :func:`sunwind.forces.srp.srp`.
    samples, tolerance
        Shadow-ray sampling along the flow, as for sunlight.
    reflections : str or ReflectionSettings
        ``"none"``, ``"full"`` or ``"auto"`` (full when the molecular ``K_IS >= 0.1``).
    reference_area_m2, reference_length_m : float, optional
        For the coefficients; default a quarter of the total area (the mean projected area of a
        convex body: ``pi R^2`` for a sphere) and the largest extent of the bounding box.
    thermal_spread : bool
        Give shadows the penumbra of the molecules' thermal spread (four more shadow passes); False
        for the hyperthermal shadow along ``v_rel`` alone (faster; exact as ``S -> infinity`` and on
        convex bodies).

    Returns
    -------
    DragResult
    """
    settings = _settings(reflections)
    velocity = np.asarray(velocity_m_s, dtype=np.float64)
    if velocity.shape != (3,) or not np.all(np.isfinite(velocity)) or not np.any(velocity):
        raise InputError(
            f"flow velocity {velocity.tolist()} must be three finite numbers, not all zero",
            hint="give --velocity X Y Z [m/s] (spacecraft relative to the atmosphere) or --flow-azel",
        )
    speed = float(np.linalg.norm(velocity))
    u = unit_vector(velocity, "velocity")
    ref, ref_name = reference_point(craft, reference_point_m)
    area_ref, length_ref = reference_sizes(craft, reference_area_m2, reference_length_m)
    speed_ratio = atmosphere.mean_speed_ratio(speed)
    if speed_ratio < LOW_SPEED_RATIO:
        warnings.warn(
            f"speed ratio {speed_ratio:.2f} < {LOW_SPEED_RATIO:g}: flow shadowing of concave parts is "
            "approximate at low speed ratio (convex shapes stay exact)",
            LowSpeedRatioWarning,
            stacklevel=2,
        )

    mode, view, k_is = settings.mode, None, None
    if mode in ("full", "auto"):
        view = model_view_factors(craft, settings)
        k_is = gas_interference_criterion(craft, view)
        if mode == "auto":
            mode = "full" if k_is >= AUTO_THRESHOLD else "none"
    groups = _gas_groups(craft)
    gamma = np.einsum("ij,j->i", groups.normals, u)  # per group; einsum: BLAS threads cost more here
    flow, visible = _flow_shadow(
        craft, u, gamma[groups.side], speed_ratio, thermal_spread, samples, tolerance
    )
    sums = _summed_laws(groups, gamma, atmosphere, speed, mode == "full")
    stresses = group_stresses(gamma, sums, groups.normals, u)
    side_force, side_torque = np.empty((3, craft.n_sides)), np.empty((3, craft.n_sides))  # sum fast by rows
    emitted = np.empty((sums.shape[1] - 4, craft.n_sides))
    args = (
        groups.side,
        stresses,
        sums[:, 4:],
        craft.side_areas,
        visible,
        craft.side_centroids,
        flow.lit_centroid,
    )
    map_ranges(
        lambda lo, hi: side_forces(*args, ref, side_force, side_torque, emitted, lo, hi),
        craft.n_sides,
        _MIN_SIDES_PER_CHUNK,
    )
    panel_force, panel_torque = side_force.sum(axis=1), side_torque.sum(axis=1)
    if mode == "full":
        exchange = molecular_exchange(craft, view).totals(emitted[0], emitted[1], ref)
        reflected = GasReflected(mode, exchange.force_N, exchange.torque_Nm, view, k_is)
    else:
        reflected = GasReflected(mode, np.zeros(3), np.zeros(3), view, k_is)
    return DragResult(
        velocity_m_s=velocity,
        atmosphere=atmosphere,
        force_N=panel_force + reflected.force_N,
        torque_Nm=panel_torque + reflected.torque_Nm,
        direct_force_N=panel_force,
        direct_torque_Nm=panel_torque,
        reflected=reflected,
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        reference_area_m2=area_ref,
        reference_length_m=length_ref,
        projected_area_m2=float(
            np.einsum(
                "i,i->",
                craft.side_areas[flow.facing],
                flow.lit_fraction[flow.facing] * gamma[groups.side[flow.facing]],
            )
        ),
        side_force_N=side_force.T,
        rays=flow.rays,
        sampling=flow.sampling,
        craft=craft,
    )


def _summed_laws(
    groups: _GasGroups, gamma: NDArray[np.float64], atmosphere: Atmosphere, speed: float, re_emission: bool
) -> NDArray[np.float64]:
    """The gas-surface laws of each group (``gamma = n . u`` of each) summed over the species, each
    weighted by its dynamic pressure ``q_k`` [Pa]: :func:`sunwind.forces.gas.laws.summed_coefficients`,
    (n_groups, 4),
    and with ``re_emission`` two more columns: per unit area of the group and per unit share arriving
    unobstructed, the first re-emission's momentum per second [N/m^2] and its molecules per second
    weighted by the square root of their mass [sqrt(kg)/(s m^2)] (:mod:`sunwind.forces.gas.exchange`)."""
    temperature = atmosphere.temperature_K
    # species of equal mass (O and anomalous O) move alike: one stream of their summed density
    names = list(atmosphere.number_density_m3)
    mass, species = np.unique([atmosphere.mass_kg[name] for name in names], return_inverse=True)
    density = np.bincount(species, weights=list(atmosphere.number_density_m3.values()))
    ratio = speed / np.sqrt(2 * BOLTZMANN * temperature / mass)
    emission = None
    if re_emission:
        emission = np.empty((len(groups.laws[0]), len(mass), 2))
        for k in range(len(mass)):
            share, re_temperature = diffuse_emission(*groups.laws, ratio[k], temperature)
            rate = share * density[k] * speed  # molecules per second and unit area, per unit incident flux
            emission[:, k, 0] = rate * mean_momentum(re_temperature, mass[k])
            emission[:, k, 1] = rate * np.sqrt(mass[k])
    q = 0.5 * density * mass * speed**2
    return summed_coefficients(groups.laws, groups.law, gamma, ratio, q, temperature, emission)


def reference_sizes(craft: Spacecraft, area_m2: float | None, length_m: float | None) -> tuple[float, float]:
    """Coefficient reference area [m^2] and length [m]: the user's, else the defaults of :func:`drag`."""
    area = craft.total_area / 4 if area_m2 is None else float(area_m2)
    length = float(np.ptp(craft.bounds, axis=0).max()) if length_m is None else float(length_m)
    for name, value in (("--ref-area", area), ("--ref-length", length)):
        if not np.isfinite(value) or value <= 0:
            raise InputError(f"{name} {value} must be a positive number")
    return area, length
