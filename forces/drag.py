"""Free-molecular force and torque at one attitude or a batch: the incident stream integrated over each
side's open sky, and the molecules re-emitted from side to side (METHOD.md "Free-molecular flow").

Per side, the gas-surface law (:mod:`sunwind.forces.gas.laws`) acts on the drifting Maxwellian that
reaches it (:mod:`sunwind.forces.gas.visible`): its closed form where the side sees open sky all round
(on a convex body, every side, at every speed ratio), else the integral over the directions from which
it does, at any speed ratio. With ``specular``, molecules a side sends on unaccommodated (mirrored,
CLL's lobe) are followed surface to surface (:mod:`sunwind.forces.gas.chains`); with ``full`` those
re-emitted diffusely are exchanged between sides too (:mod:`sunwind.forces.gas.exchange`). With
``plates`` every side takes the closed form of an unobstructed side and casts no ray.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.batches import DragBatch
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.chain_tangents import ChainTangent, Derivatives, check_covered, exchange_slopes
from sunwind.forces.gas.chains import ChainLaws, SpeciesStream, molecular_chains
from sunwind.forces.gas.exchange import molecular_exchange, open_plate_recoil
from sunwind.forces.gas.flow import flow_speed
from sunwind.forces.gas.panel import GasGroups, closed_loads, gas_groups, species_streams, summed_laws
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.gas.tangents import closed_tangent, stream_tangents
from sunwind.forces.gas.visible import arrival, model_sky, stream_tables
from sunwind.forces.model import Model, as_model
from sunwind.forces.reflection import (
    Reflected,
    ReflectionSettings,
    interference,
    model_view_factors,
    resolved_mode,
)
from sunwind.forces.results import DragResult
from sunwind.forces.sensitivity import Sensitivities
from sunwind.geometry.directions import unit_vector, unit_vectors
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_items, using_threads
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.sky import OpenSky


def drag(
    model: Model | Spacecraft,
    velocity_m_s: Sequence[float] | NDArray,
    atmosphere: Atmosphere,
    *,
    reference_point_m: Sequence[float] | NDArray | None = None,
    sampling: ShadowSampling | None = None,
    reflections: str | ReflectionSettings = "auto",
    gas_sampling: GasSampling | None = None,
    sensitivities: bool = False,
) -> DragResult | DragBatch:
    """Free-molecular force and torque with the open-sky integral and molecular inter-reflection.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model (:func:`sunwind.forces.load`); its thread count, reference point and
        coefficient reference sizes apply.
    velocity_m_s : (3,) or (n, 3) array_like
        ``v_rel``, the spacecraft's velocity relative to the atmosphere, body frame [m/s]; a batch
        gives a batch of results.
    atmosphere : Atmosphere
        Number density of every species and the temperature (:mod:`sunwind.forces.gas.atmosphere`).
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default as :func:`sunwind.forces.srp.srp`.
    sampling : ShadowSampling, optional
        Shadow-ray sampling along the flow, as for sunlight: the core of the open-sky integral
        (:class:`~sunwind.geometry.rays.sampling.ShadowSampling`; default its defaults). The default
        pass's estimate of the error it left is the result's ``error_estimate``.
    reflections : str or ReflectionSettings
        One of :data:`~sunwind.forces.reflection.settings.MODES`, read for molecules: ``"none"``,
        ``"specular"`` (unaccommodated molecules followed, no diffuse exchange), ``"full"``, ``"auto"``
        (full when the molecular ``K_IS >= 0.1``) or ``"plates"`` (every side in the whole stream, no
        shadowing, no ray cast); or settings with the view factors' sampling.
    gas_sampling : GasSampling, optional
        Sampling of the open-sky integral and the chains (:class:`~sunwind.forces.gas.sampling.
        GasSampling`): rays per side of each side's sky, sampled once per model; core rays and chain
        molecules per attitude. Default ``GasSampling()``.
    sensitivities : bool
        Also the derivatives of force and torque with respect to each material's accommodation
        coefficients (:class:`~sunwind.forces.sensitivity.Sensitivities` in the result's
        ``sensitivities``; zero where a material's law does not read a coefficient): those of the
        function computed, its rays and samples held, forward mode on the same rays
        (:mod:`sunwind.forces.gas.tangents`).

    Returns
    -------
    DragResult or DragBatch
        The result of one velocity, or a batch of results for a batch of velocities.

    Raises
    ------
    InputError
        A velocity that is not three finite numbers of a flow speed, an atmosphere, sampling or
        reflections of the wrong kind or out of range; sensitivities of a combination not covered
        (:func:`~sunwind.forces.gas.chain_tangents.check_covered`).

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box_wing(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> fast = sw.GasSampling(sky_rays=16, core_rays=1024)
    >>> result = sw.drag(model, [7600.0, 0.0, 0.0], air, reflections="none", gas_sampling=fast)
    >>> bool(result.force_N[0] < 0)  # drag acts against v_rel
    True
    >>> with_sensitivities = sw.drag(model, [7600.0, 0.0, 0.0], air, reflections="none",
    ...     gas_sampling=fast, sensitivities=True)
    >>> bool(with_sensitivities.sensitivities.of("white.energy_accommodation").force_N[0] > 0)
    True
    """
    model = as_model(model)
    settings = ReflectionSettings.of(reflections)
    velocities = checked_velocities(velocity_m_s)
    if not isinstance(atmosphere, Atmosphere):
        raise InputError("atmosphere must be an Atmosphere (nrlmsis or explicit)", parameters=("atmosphere",))
    reference = model.reference(reference_point_m)
    shadows = ShadowSampling.of(sampling)
    gas = GasSampling.of(gas_sampling)
    with using_threads(model.threads):
        results = map_items(
            lambda v: _one(model, v, atmosphere, reference, shadows, gas, settings, sensitivities),
            velocities.reshape(-1, 3),
        )
    return results[0] if velocities.ndim == 1 else DragBatch(tuple(results))


def checked_velocities(velocity_m_s: Sequence[float] | NDArray) -> NDArray[np.float64]:
    """Check the relative velocities and return them as (3,) or (n, 3) float64.

    Each must be three finite numbers of a flow speed (:func:`~sunwind.forces.gas.flow.flow_speed`).

    Parameters
    ----------
    velocity_m_s : (3,) or (n, 3) array_like
        ``v_rel``, the spacecraft's velocity relative to the atmosphere, body frame [m/s].

    Returns
    -------
    (3,) or (n, 3) ndarray of float64
        The velocities, as given.

    Raises
    ------
    InputError
        Not of shape (3,) or (n, 3), not finite, zero, or a speed out of range.

    Examples
    --------
    >>> checked_velocities([7600, 0, 0])
    array([7600.,    0.,    0.])
    """
    velocity = np.asarray(velocity_m_s, dtype=np.float64)
    unit_vectors(velocity, "velocity_m_s")  # shape, finite, not zero
    for v in velocity.reshape(-1, 3):
        flow_speed(math.hypot(*v.tolist()), "velocity_m_s")
    return velocity


def _one(
    model: Model,
    velocity: NDArray[np.float64],
    atmosphere: Atmosphere,
    reference: tuple[NDArray[np.float64], str],
    sampling: ShadowSampling,
    gas: GasSampling,
    settings: ReflectionSettings,
    sensitivities: bool = False,
) -> DragResult:
    """One attitude, its arguments checked."""
    craft = model.craft
    speed = math.hypot(*velocity.tolist())
    u = unit_vector(velocity, "velocity_m_s")
    ref, ref_name = reference
    view, k_is = None, None
    if settings.uses_view_factors:
        view = model_view_factors(craft, settings)
        k_is = interference(craft, settings, molecules=True)
    mode = resolved_mode(settings.mode, k_is)
    groups = gas_groups(craft)
    gamma = np.einsum("ij,j->i", groups.normals, u)  # per group; einsum: BLAS threads cost more here
    stream = stream_tables(craft, groups.surfaces, atmosphere, speed)
    laws = stream.laws
    closed = closed_loads(groups, gamma, summed_laws(groups, gamma, laws, atmosphere.temperature_K), u)
    tangents, derivative = (), None
    if sensitivities:
        check_covered(groups.surfaces, mode)
        tangents = stream_tangents(craft, groups.surfaces, atmosphere, speed, stream)
        tangents = [(t, closed_tangent(groups, gamma, t, u)) for t in tangents]
        derivative = Derivatives.zeros(craft, ref)
    if mode == "plates":
        for t, closed_t in tangents:
            side_force = closed_t[groups.side, :3] * craft.side_areas[:, None]
            side_torque = np.cross(craft.side_centroids - ref, side_force)
            derivative.add_sides(t.coefficient[groups.law[groups.side]], side_force, side_torque)
        result = _plate_result(model, velocity, atmosphere, reference, groups, closed, settings)
        return result if derivative is None else replace(result, sensitivities=_record(craft, derivative))
    sky = model_sky(craft, gas.sky_rays, settings.cache_dir)
    flow = side_sampler(craft).illuminate(u, sampling.samples, sampling.tolerance)
    panel_tangents = [t.panel(closed_t) for t, closed_t in tangents]
    panel = arrival(craft, groups, (closed, stream), flow, ref, sky, gas.core_rays, panel_tangents)
    for (t, _), (side_force, side_torque, _) in zip(tangents, panel.tangents, strict=True):
        derivative.add_sides(t.coefficient[groups.law[groups.side]], side_force, side_torque)
    if mode in ("specular", "full"):
        masses, densities = species_streams(atmosphere)
        chain_tangent = None if derivative is None else ChainTangent.of(craft, groups)
        chains = molecular_chains(
            craft,
            groups,
            laws,
            SpeciesStream(masses, densities, speed),
            u,
            ref,
            gas.chain_molecules,
            chain_tangent,
        )
        if mode == "full":
            mirrored = ChainLaws.of(groups.surfaces).mirrored[groups.law[groups.side]]
            molecular = molecular_exchange(craft, settings, mirrored)
            exchange = molecular.totals(panel.emitted[0], panel.emitted[1], ref, chains.deposit)
            if derivative is not None:
                slopes = exchange_slopes(craft, molecular, mirrored, settings.view_key)
                molecular = (molecular, slopes, panel.emitted + chains.deposit)
        else:  # what the chains land leaves as from an open plate, as the first re-emission does
            molecular = None
            exchange = open_plate_recoil(craft, chains.deposit[0], ref)
        if derivative is not None:
            sources = {
                t.direction: (emitted, t.coefficient[groups.law[groups.side]])
                for (t, _), (_, _, emitted) in zip(tangents, panel.tangents, strict=True)
            }
            derivative.add_reflections(chain_tangent, sources, molecular)
        force, torque = exchange.force_N + chains.force_N, exchange.torque_Nm + chains.torque_Nm
        reflected = Reflected(
            mode=mode, force_N=force, torque_Nm=torque, power=None, chains=chains, view=view, k_is=k_is
        )
    else:
        zero = np.zeros(3)
        reflected = Reflected(
            mode=mode, force_N=zero, torque_Nm=zero, power=None, chains=None, view=view, k_is=k_is
        )
    side_force, side_torque = panel.force_N, panel.torque_Nm
    panel_force, panel_torque = side_force.sum(axis=0), side_torque.sum(axis=0)
    facing = flow.facing
    wetted = craft.side_areas[facing] * flow.lit_fraction[facing]
    projected = np.einsum("i,i->", wetted, gamma[groups.side[facing]])
    area, length = model.reference_sizes
    check = flow.check
    shadow_error = None if check is None else check.loads_error(craft, panel.lit_load, ref)
    return DragResult(
        force_N=panel_force + reflected.force_N,
        torque_Nm=panel_torque + reflected.torque_Nm,
        direct_force_N=panel_force,
        direct_torque_Nm=panel_torque,
        reflected=reflected,
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        lit_area_m2=float(wetted.sum()),
        projected_area_m2=float(projected),
        rays=panel.rays,
        sampling=flow.sampling,
        craft=craft,
        velocity_m_s=velocity,
        atmosphere=atmosphere,
        reference_area_m2=area,
        reference_length_m=length,
        side_force_N=side_force,
        side_torque_Nm=side_torque,
        open_sky=sky,
        core_half_angle_rad=panel.core_half_angle,
        shadow_error=shadow_error,
        sensitivities=None if derivative is None else _record(craft, derivative),
    )


def _record(craft: Spacecraft, derivative: Derivatives) -> Sensitivities:
    """The :class:`~sunwind.forces.sensitivity.Sensitivities` of the accommodations' derivatives."""
    record = Sensitivities.zeros(craft.materials.names, derivative.reference_m)
    record.force_N[:, 4:7], record.torque_Nm[:, 4:7] = derivative.force_N, derivative.torque_Nm
    return record


def _plate_result(
    model: Model,
    velocity: NDArray[np.float64],
    atmosphere: Atmosphere,
    reference: tuple[NDArray[np.float64], str],
    groups: GasGroups,
    closed: NDArray[np.float64],
    settings: ReflectionSettings,
) -> DragResult:
    """The result of ``plates``: every side takes the whole stream as an unobstructed side does, its
    group's ``closed`` loads (the flat-plate model); no ray is cast and no molecule goes from side to
    side."""
    craft = model.craft
    ref, ref_name = reference
    side_force = closed[groups.side, :3] * craft.side_areas[:, None]
    side_torque = np.cross(craft.side_centroids - ref, side_force)
    gamma = craft.side_normals @ unit_vector(velocity, "velocity_m_s")
    facing = gamma > 0.0
    force, torque = side_force.sum(axis=0), side_torque.sum(axis=0)
    area, length = model.reference_sizes
    n = craft.n_sides
    sky = OpenSky(
        blocked_fraction=np.zeros(n),
        keeps_open=np.ones(n, bool),
        start=np.zeros(n + 1, np.int64),
        direction=np.zeros((0, 3), np.float32),
        lever=np.zeros((0, 3), np.float32),
        rays_per_side=0,
        seed=0,
        seconds=0.0,
        origin="plates: every side sees the whole sky",
    )
    return DragResult(
        force_N=force,
        torque_Nm=torque,
        direct_force_N=force,
        direct_torque_Nm=torque,
        reflected=Reflected(
            mode="plates",
            force_N=np.zeros(3),
            torque_Nm=np.zeros(3),
            power=None,
            chains=None,
            view=None,
            k_is=None,
        ),
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        lit_area_m2=float(craft.side_areas[facing].sum()),
        projected_area_m2=float(craft.side_areas[facing] @ gamma[facing]),
        rays=0,
        sampling="plates: no shadowing",
        craft=craft,
        velocity_m_s=velocity,
        atmosphere=atmosphere,
        reference_area_m2=area,
        reference_length_m=length,
        side_force_N=side_force,
        side_torque_Nm=side_torque,
        open_sky=sky,
        core_half_angle_rad=0.0,
        shadow_error=None,
    )
