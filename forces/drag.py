"""Free-molecular force and torque at one attitude (METHOD.md "Free-molecular flow", "Shadowing").

Per species ``k`` and side ``i`` the gas-surface law (:mod:`forces.gsi`) gives pressure and shear for
the incident drifting Maxwellian, split exactly into a *directed* stream (a cold beam along the flow)
and the *thermal* rest. Both reach a side where its view toward the molecules' directions of arrival
is open (:func:`_flow_visibility`):

* a side facing the flow takes them on the share the hyperthermal shadow along ``u = v_rel/|v_rel|``
  leaves lit, or (default) the share lit along directions spread by the thermal speed over the flow
  speed: the penumbra that lets the walls of a cavity intercept molecules the floor would get;
* a lee or edge-on side takes its thermal flux from upstream along its plane.

On a convex body nothing is blocked: the result is the per-side sum of the gas-surface law, lee
faces included, at every speed ratio. With ``full``, re-emitted molecules landing on other sides are
re-emitted again (:mod:`forces.molecular_exchange`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from geometry.directions import unit_vector
from geometry.errors import InputError
from geometry.illumination import DEFAULT_TOLERANCE
from geometry.spacecraft import Spacecraft

from .atmosphere import BOLTZMANN, Atmosphere
from .drag_result import DragResult, GasReflected
from .evaluate import reference_point
from .gsi import diffuse_emission, incident_number_flux, panel_coefficients
from .molecular_exchange import gas_interference_criterion, mean_momentum, molecular_exchange
from .reflections import AUTO_THRESHOLD, ReflectionSettings, model_view_factors

#: Inter-reflection modes of molecules (specular chains are followed for light only).
DRAG_MODES = ("none", "full", "auto")
#: Speed ratio below which the panel method's flow shadowing is a rough approximation on concave
#: shapes (the directed/thermal split; convex shapes stay exact).
LOW_SPEED_RATIO = 3.0


class LowSpeedRatioWarning(UserWarning):
    """The flow's speed ratio is below :data:`LOW_SPEED_RATIO`."""


def _tangent_directions(normals: NDArray[np.float64], u: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit direction of the molecules' motion along each side, ``-(u - gamma n)/|...|``; 0 where the
    flow is normal to the side."""
    along = u[None, :] - (normals @ u)[:, None] * normals
    length = np.linalg.norm(along, axis=1)
    safe = np.where(length > 1e-12, length, 1.0)
    return np.where(length[:, None] > 1e-12, -along / safe[:, None], 0.0)


def _flow_visibility(
    craft: Spacecraft,
    u: NDArray[np.float64],
    tangents: NDArray[np.float64],
    along_u: NDArray[np.float64],
    speed_ratio: float,
    spread: bool,
    samples: int | None,
    tolerance: float,
) -> NDArray[np.float64]:
    """Share of each side's incident molecular flux that arrives unobstructed, (n_sides,).

    Molecules arrive from directions within about ``1/S`` of ``u`` (thermal speed over flow speed).
    A side facing the flow: its lit share along ``u`` (``along_u``) when ``spread`` is off (the
    hyperthermal shadow); with ``spread``, the lit shares along the four directions
    ``u +- e_k / S`` (``e_1``, ``e_2`` normal to ``u``: the molecules' thermal velocity at one thermal
    speed, a rule exact for the second moments of the thermal spread), each weighted by its incidence
    on the side, so the shadow has the penumbra the thermal spread gives it. A lee or edge-on side: the
    direction upstream along its plane raised by ``atan(1/S)`` toward its normal, one ray from its
    centroid. Every direction counted lies in the side's own open hemisphere, so on a convex body
    nothing is blocked at any speed ratio.
    """
    normals = craft.side_normals
    gamma = normals @ u
    visible = np.array(along_u, dtype=np.float64)
    if spread:
        e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(u, e1)
        weighted, weights = np.zeros(craft.n_sides), np.zeros(craft.n_sides)
        for offset in (e1, -e1, e2, -e2):
            direction = u + offset / speed_ratio
            direction /= np.linalg.norm(direction)
            incidence = np.maximum(normals @ direction, 0.0)
            lit = craft.sampler.illuminate(direction, samples, tolerance).lit_fraction
            weighted += incidence * lit
            weights += incidence
        windward = (gamma > 0) & (weights > 0)
        visible[windward] = weighted[windward] / weights[windward]
    lee = np.flatnonzero(gamma <= 0)
    if len(lee) == 0:
        return visible
    elevation = math.atan(1.0 / speed_ratio)
    lee_normals = normals[lee]
    probe = math.cos(elevation) * -tangents[lee] + math.sin(elevation) * lee_normals
    probe /= np.linalg.norm(probe, axis=1)[:, None]
    scene = craft.scene
    blocked = scene.occluded(scene.origins(craft.side_centroids[lee], lee_normals), probe.astype(np.float32))
    visible[lee] = np.where(blocked, 0.0, 1.0)
    return visible


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
        Number density of every species and the temperature (:mod:`forces.atmosphere`).
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default as :func:`forces.evaluate.srp`.
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
    area_ref, length_ref = _reference_sizes(craft, reference_area_m2, reference_length_m)
    speed_ratio = atmosphere.mean_speed_ratio(speed)
    if speed_ratio < LOW_SPEED_RATIO:
        warnings.warn(
            f"speed ratio {speed_ratio:.2f} < {LOW_SPEED_RATIO:g}: flow shadowing of concave parts is "
            "approximate at low speed ratio (convex shapes stay exact)",
            LowSpeedRatioWarning,
            stacklevel=2,
        )

    flow = craft.sampler.illuminate(u, samples, tolerance)
    mode, view, k_is = settings.mode, None, None
    if mode in ("full", "auto"):
        view = model_view_factors(craft, settings)
        k_is = gas_interference_criterion(craft, view)
        if mode == "auto":
            mode = "full" if k_is >= AUTO_THRESHOLD else "none"
    normals, gamma = craft.side_normals, craft.side_normals @ u
    tangents = _tangent_directions(normals, u)
    visible = _flow_visibility(
        craft, u, tangents, flow.lit_fraction, speed_ratio, thermal_spread, samples, tolerance
    )
    gas = craft.side_gas
    law = (
        gas["code"],
        gas["energy_accommodation"],
        gas["normal_accommodation"],
        gas["tangential_accommodation"],
        gas["wall_temperature_K"],
    )
    temperature = atmosphere.temperature_K
    directed = np.zeros((craft.n_sides, 2))  # sum_k q_k (c_n, c_t) of the directed stream [Pa]
    thermal = np.zeros((craft.n_sides, 2))
    momentum_emitted = np.zeros(craft.n_sides)
    root_mass_emitted = np.zeros(craft.n_sides)
    for species, number_density in atmosphere.number_density_m3.items():
        mass = atmosphere.mass_kg[species]
        ratio = speed / np.sqrt(2 * BOLTZMANN * temperature / mass)
        q = 0.5 * number_density * mass * speed**2
        beam = np.column_stack(panel_coefficients(*law, gamma, ratio, temperature, "directed"))
        full = np.column_stack(panel_coefficients(*law, gamma, ratio, temperature, "full"))
        directed += q * beam
        thermal += q * (full - beam)
        if mode == "full":
            share, re_temperature = diffuse_emission(*law, ratio, temperature)
            landed = visible * incident_number_flux(gamma, ratio, "full")
            emitted = share * number_density * speed * craft.side_areas * landed  # molecules/s
            momentum_emitted += emitted * mean_momentum(re_temperature, mass)
            root_mass_emitted += emitted * np.sqrt(mass)

    areas = craft.side_areas
    directed_force = (visible * areas)[:, None] * (-directed[:, :1] * normals + directed[:, 1:] * tangents)
    thermal_force = (visible * areas)[:, None] * (-thermal[:, :1] * normals + thermal[:, 1:] * tangents)
    side_force = directed_force + thermal_force
    side_torque = np.cross(flow.lit_centroid - ref, directed_force) + np.cross(
        craft.side_centroids - ref, thermal_force
    )
    panel_force, panel_torque = side_force.sum(axis=0), side_torque.sum(axis=0)
    if mode == "full":
        exchange = molecular_exchange(craft, view).totals(momentum_emitted, root_mass_emitted, ref)
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
        projected_area_m2=float(areas[flow.facing] @ (flow.lit_fraction[flow.facing] * gamma[flow.facing])),
        side_force_N=side_force,
        rays=flow.rays,
        sampling=flow.sampling,
        craft=craft,
    )


def _reference_sizes(craft: Spacecraft, area_m2: float | None, length_m: float | None) -> tuple[float, float]:
    """Coefficient reference area [m^2] and length [m]: the user's, else the defaults of :func:`drag`."""
    area = craft.total_area / 4 if area_m2 is None else float(area_m2)
    length = float(np.ptp(craft.bounds, axis=0).max()) if length_m is None else float(length_m)
    for name, value in (("--ref-area", area), ("--ref-length", length)):
        if not np.isfinite(value) or value <= 0:
            raise InputError(f"{name} {value} must be a positive number")
    return area, length
