"""Free-molecular force and torque at one attitude or a batch: the incident stream integrated over each
side's open sky, and the molecules re-emitted from side to side (METHOD.md "Free-molecular flow").

Per side, the gas-surface law (:mod:`sunwind.forces.gas.laws`) acts on the drifting Maxwellian that
reaches it (:mod:`sunwind.forces.gas.visible`): its closed form where the side sees open sky all round
(on a convex body, every side, at every speed ratio), else the integral over the directions from which
it does, at any speed ratio. With ``full``, molecules a side sends on unaccommodated (mirrored, CLL's
lobe) are followed surface to surface (:mod:`sunwind.forces.gas.chains`), and those re-emitted
diffusely are exchanged between sides (:mod:`sunwind.forces.gas.exchange`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.batches import DragBatch
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.chains import ChainLaws, molecular_chains
from sunwind.forces.gas.exchange import gas_interference_criterion, molecular_exchange
from sunwind.forces.gas.flow import flow_speed
from sunwind.forces.gas.panel import closed_loads, gas_groups, species_streams, summed_laws
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.gas.visible import arrival, model_sky, stream_tables
from sunwind.forces.model import Model, as_model
from sunwind.forces.reflection import AUTO_THRESHOLD, ReflectionSettings, model_view_factors
from sunwind.forces.results import DragResult, GasReflected
from sunwind.geometry.directions import unit_vector, unit_vectors
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_items, using_threads
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, check_sampling, side_sampler
from sunwind.geometry.spacecraft import Spacecraft

#: Inter-reflection modes of molecules: none, or chains and exchange (``full``), or ``full`` when the
#: molecular ``K_IS`` >= the threshold (``auto``).
DRAG_MODES = ("none", "full", "auto")


def drag(
    model: Model | Spacecraft,
    velocity_m_s: Sequence[float] | NDArray,
    atmosphere: Atmosphere,
    *,
    reference_point_m: Sequence[float] | NDArray | None = None,
    samples: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    reflections: str | ReflectionSettings = "auto",
    gas_sampling: GasSampling | None = None,
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
    samples, tolerance
        Shadow-ray sampling along the flow, as for sunlight: the core of the open-sky integral. The
        default pass's estimate of the error it left is the result's ``error_estimate``.
    reflections : str or ReflectionSettings
        ``"none"``, ``"full"`` or ``"auto"`` (full when the molecular ``K_IS >= 0.1``).
    gas_sampling : GasSampling, optional
        Sampling of the open-sky integral and the chains (:class:`~sunwind.forces.gas.sampling.
        GasSampling`): rays per side of each side's sky, sampled once per model; core rays and chain
        molecules per attitude. Default ``GasSampling()``.

    Returns
    -------
    DragResult, or DragBatch for a batch of velocities

    """
    model = as_model(model)
    settings = ReflectionSettings.of(reflections)
    if settings.mode not in DRAG_MODES:
        raise InputError(
            f"reflections {settings.mode} is for light only",
            hint=f"for molecules use one of {', '.join(DRAG_MODES)}",
            parameters=("reflections",),
        )
    velocities = checked_velocities(velocity_m_s)
    if not isinstance(atmosphere, Atmosphere):
        raise InputError("atmosphere must be an Atmosphere (nrlmsis or explicit)", parameters=("atmosphere",))
    reference = model.reference(reference_point_m)
    check_sampling(samples, tolerance)
    gas = GasSampling() if gas_sampling is None else gas_sampling
    if not isinstance(gas, GasSampling):
        raise InputError("gas_sampling must be a GasSampling", parameters=("gas_sampling",))
    with using_threads(model.threads):
        results = map_items(
            lambda v: _one(model, v, atmosphere, reference, (samples, tolerance), gas, settings),
            velocities.reshape(-1, 3),
        )
    return results[0] if velocities.ndim == 1 else DragBatch(tuple(results))


def checked_velocities(velocity_m_s: Sequence[float] | NDArray) -> NDArray[np.float64]:
    """``v_rel`` as (3,) or (n, 3) float64, each three finite numbers of a flow speed
    (:func:`~sunwind.forces.gas.flow.flow_speed`)."""
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
    sampling: tuple[int | None, float],
    gas: GasSampling,
    settings: ReflectionSettings,
) -> DragResult:
    """One attitude, its arguments checked; ``sampling`` is ``(samples, tolerance)``."""
    craft = model.craft
    speed = math.hypot(*velocity.tolist())
    u = unit_vector(velocity, "velocity_m_s")
    ref, ref_name = reference
    mode, view, k_is = settings.mode, None, None
    if mode in ("full", "auto"):
        view = model_view_factors(craft, settings)
        k_is = gas_interference_criterion(craft, view)
        if mode == "auto":
            mode = "full" if k_is >= AUTO_THRESHOLD else "none"
    groups = gas_groups(craft)
    gamma = np.einsum("ij,j->i", groups.normals, u)  # per group; einsum: BLAS threads cost more here
    stream = stream_tables(craft, groups.surfaces, atmosphere, speed)
    laws = stream.laws
    closed = closed_loads(groups, gamma, summed_laws(groups, gamma, laws, atmosphere.temperature_K), u)
    sky = model_sky(craft, gas.sky_rays, settings.cache_dir)
    flow = side_sampler(craft).illuminate(u, *sampling)
    panel = arrival(craft, groups, (closed, stream), flow, ref, sky, gas.core_rays)
    if mode == "full":
        masses, densities = species_streams(atmosphere)
        chains = molecular_chains(
            craft, groups, laws, (masses, densities, speed), u, ref, gas.chain_molecules
        )
        mirrored = ChainLaws.of(groups.surfaces).mirrored[groups.law[groups.side]]
        exchange = molecular_exchange(craft, settings, mirrored).totals(
            panel.emitted[0], panel.emitted[1], ref, chains.deposit
        )
        force, torque = exchange.force_N + chains.force_N, exchange.torque_Nm + chains.torque_Nm
        reflected = GasReflected(mode, force, torque, view, k_is, chains)
    else:
        reflected = GasReflected(mode, np.zeros(3), np.zeros(3), view, k_is, None)
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
    )
