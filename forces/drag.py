"""Free-molecular force and torque at one attitude or a batch: the panel law with flow shadowing, and
the exchange of re-emitted molecules (METHOD.md "Free-molecular flow", "Shadowing and sampling").

Per species and side the gas-surface law (:mod:`sunwind.forces.gas.laws`) acts on the share of the
side's incident molecules that arrives unobstructed (:mod:`sunwind.forces.gas.shadow`); on a convex
body nothing is blocked and the result is the per-side sum of the law, lee faces included, at every
speed ratio. With ``full``, re-emitted molecules landing on other sides are re-emitted again
(:mod:`sunwind.forces.gas.exchange`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.exchange import gas_interference_criterion, molecular_exchange
from sunwind.forces.gas.flow import flow_speed
from sunwind.forces.gas.panel import gas_groups, panel_forces, summed_laws
from sunwind.forces.gas.shadow import flow_shadow
from sunwind.forces.model import Model, as_model
from sunwind.forces.reflection import AUTO_THRESHOLD, ReflectionSettings, model_view_factors
from sunwind.forces.results import DragBatch, DragResult, GasReflected
from sunwind.geometry.directions import unit_vector, unit_vectors
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import using_threads
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, check_sampling
from sunwind.geometry.spacecraft import Spacecraft

#: Inter-reflection modes of molecules (specular chains are followed for light only).
DRAG_MODES = ("none", "full", "auto")
#: Speed ratio below which the panel method's flow shadowing is a rough approximation on concave
#: shapes (the directed/thermal split; convex shapes stay exact).
LOW_SPEED_RATIO = 3.0


class LowSpeedRatioWarning(UserWarning):
    """The flow's speed ratio is below :data:`LOW_SPEED_RATIO` on a model one side of which can shadow
    another (on a convex model nothing is blocked and the result is exact)."""


def drag(
    model: Model | Spacecraft,
    velocity_m_s: Sequence[float] | NDArray,
    atmosphere: Atmosphere,
    *,
    reference_point_m: Sequence[float] | NDArray | None = None,
    samples: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    reflections: str | ReflectionSettings = "auto",
    thermal_spread: bool = True,
) -> DragResult | DragBatch:
    """Free-molecular force and torque with flow shadowing and molecular inter-reflection.

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
        Shadow-ray sampling along the flow, as for sunlight.
    reflections : str or ReflectionSettings
        ``"none"``, ``"full"`` or ``"auto"`` (full when the molecular ``K_IS >= 0.1``).
    thermal_spread : bool
        Give shadows the penumbra of the molecules' thermal spread (four more shadow passes); False
        for the hyperthermal shadow along ``v_rel`` alone (faster; exact as ``S -> infinity`` and on
        convex bodies).

    Returns
    -------
    DragResult, or DragBatch for a batch of velocities

    Warns
    -----
    LowSpeedRatioWarning
        Below speed ratio :data:`LOW_SPEED_RATIO`, on a model that can shadow itself (not convex).
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
    results = []
    with using_threads(model.threads):
        for v in velocities.reshape(-1, 3):  # a loop, not a comprehension: warnings point at the caller
            results.append(
                _one(model, v, atmosphere, reference, (samples, tolerance, thermal_spread), settings)
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
    sampling: tuple[int | None, float, bool],
    settings: ReflectionSettings,
) -> DragResult:
    """One attitude, its arguments checked; ``sampling`` is ``(samples, tolerance, thermal_spread)``."""
    craft = model.craft
    speed = math.hypot(*velocity.tolist())
    u = unit_vector(velocity, "velocity_m_s")
    ref, ref_name = reference
    speed_ratio = atmosphere.mean_speed_ratio(speed)
    if speed_ratio < LOW_SPEED_RATIO and not clearance(craft).open_sky.all():
        warnings.warn(
            f"speed ratio {speed_ratio:.2f} < {LOW_SPEED_RATIO:g}: this model can shadow itself (it is "
            "not convex), and its flow shadowing is approximate at low speed ratio",
            LowSpeedRatioWarning,
            stacklevel=3,
        )
    mode, view, k_is = settings.mode, None, None
    if mode in ("full", "auto"):
        view = model_view_factors(craft, settings)
        k_is = gas_interference_criterion(craft, view)
        if mode == "auto":
            mode = "full" if k_is >= AUTO_THRESHOLD else "none"
    groups = gas_groups(craft)
    gamma = np.einsum("ij,j->i", groups.normals, u)  # per group; einsum: BLAS threads cost more here
    samples, tolerance, spread = sampling
    flow, visible = flow_shadow(craft, u, gamma[groups.side], speed_ratio, spread, samples, tolerance)
    sums = summed_laws(groups, gamma, atmosphere, speed, mode == "full")
    panel = panel_forces(craft, groups, gamma, sums, visible, flow.lit_centroid, u, ref)
    if mode == "full":
        exchange = molecular_exchange(craft, settings).totals(panel.emitted[0], panel.emitted[1], ref)
        reflected = GasReflected(mode, exchange.force_N, exchange.torque_Nm, view, k_is)
    else:
        reflected = GasReflected(mode, np.zeros(3), np.zeros(3), view, k_is)
    facing = flow.facing
    wetted = craft.side_areas[facing] * flow.lit_fraction[facing]
    projected = np.einsum("i,i->", wetted, gamma[groups.side[facing]])
    area, length = model.reference_sizes
    return DragResult(
        force_N=panel.force_N + reflected.force_N,
        torque_Nm=panel.torque_Nm + reflected.torque_Nm,
        direct_force_N=panel.force_N,
        direct_torque_Nm=panel.torque_Nm,
        reflected=reflected,
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        lit_area_m2=float(wetted.sum()),
        projected_area_m2=float(projected),
        rays=flow.rays,
        sampling=flow.sampling,
        craft=craft,
        velocity_m_s=velocity,
        atmosphere=atmosphere,
        reference_area_m2=area,
        reference_length_m=length,
        side_force_N=panel.side_force_N,
        side_torque_Nm=panel.side_torque_Nm,
    )
