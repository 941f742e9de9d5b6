"""Solar-radiation pressure at one attitude or a batch: shadow rays, the force law on every lit side,
inter-reflection, totals about a reference point (METHOD.md "Direct solar pressure", "Inter-reflection")."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.batches import SrpBatch
from sunwind.forces.model import Model, as_model
from sunwind.forces.radiation.direct import direct_pass, lit_area_loads
from sunwind.forces.radiation.law import radiation_pressure, solar_flux
from sunwind.forces.reflection import ReflectionSettings, reflected_part, reflection_plan
from sunwind.forces.results import SrpResult
from sunwind.geometry.directions import unit_vectors
from sunwind.geometry.parallel import map_items, using_threads
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, check_sampling
from sunwind.geometry.spacecraft import Spacecraft


def srp(
    model: Model | Spacecraft,
    sun_vector: Sequence[float] | NDArray,
    *,
    flux_W_m2: float | None = None,
    distance_au: float | None = None,
    reference_point_m: Sequence[float] | NDArray | None = None,
    samples: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    reflections: str | ReflectionSettings = "auto",
) -> SrpResult | SrpBatch:
    """Solar-radiation force and torque with self-shadowing and inter-reflection.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model (:func:`sunwind.forces.load`); its thread count and reference point apply.
    sun_vector : (3,) or (n, 3) array_like
        Direction from the spacecraft toward the Sun, body frame (normalised here); a batch gives a
        batch of results.
    flux_W_m2 : float, optional
        Solar flux; or ``distance_au`` from the Sun (flux 1361 W/m^2 at 1 au); default 1 au.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m] (the centre of mass); default the model's, else the volume
        centroid of a closed model, else the area centroid.
    samples : int, optional
        Fixed shadow-ray points per side, rounded up to a square; default: shadow edges located and
        cut along the outline (:mod:`sunwind.geometry.rays.shadow_edges`).
    tolerance : float
        The default pass's tolerance: the share of a refined side's area its lit part is found to, in
        [1e-6, 1). The pass checks itself: the result's ``error_estimate`` is the error it estimates it
        left, relative to the force and torque (None with ``samples``).
    reflections : str or ReflectionSettings
        ``"none"``, ``"specular"``, ``"full"`` or ``"auto"`` (full when ``K_IS >= 0.1``), or settings
        with chain cutoff, depth and view-factor sampling
        (:class:`~sunwind.forces.reflection.ReflectionSettings`).

    Returns
    -------
    SrpResult, or SrpBatch for a batch of Sun vectors
    """
    model = as_model(model)
    settings = ReflectionSettings.of(reflections)
    suns = unit_vectors(sun_vector, "sun_vector")
    flux = solar_flux(flux_W_m2, distance_au)
    reference = model.reference(reference_point_m)
    check_sampling(samples, tolerance)
    with using_threads(model.threads):
        results = map_items(
            lambda u: _one(model.craft, u, flux, reference, samples, tolerance, settings), suns.reshape(-1, 3)
        )
    return results[0] if suns.ndim == 1 else SrpBatch(tuple(results))


def _one(
    craft: Spacecraft,
    u_sun: NDArray[np.float64],
    flux: float,
    reference: tuple[NDArray[np.float64], str],
    samples: int | None,
    tolerance: float,
    settings: ReflectionSettings,
) -> SrpResult:
    """One attitude, its arguments checked."""
    pressure = radiation_pressure(flux)
    ref, ref_name = reference
    plan = reflection_plan(craft, settings)
    direct = direct_pass(craft, u_sun, ref, samples, tolerance, plan.weights)
    light = direct.illumination
    reflected = reflected_part(craft, direct, flux, ref, settings, plan)
    force, torque = pressure * direct.force, pressure * direct.torque
    shadow_error = None
    if light.check is not None:  # the default pass checked itself: what its errors cost in eq. (4)
        loads = lit_area_loads(craft, u_sun, pressure, light.check.needed)
        shadow_error = light.check.loads_error(craft, loads, ref)
    return SrpResult(
        force_N=force + reflected.force_N,
        torque_Nm=torque + reflected.torque_Nm,
        direct_force_N=force,
        direct_torque_Nm=torque,
        reflected=reflected,
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        projected_area_m2=direct.projected_area_m2,
        rays=light.rays,
        sampling=light.sampling,
        craft=craft,
        sun_vector=u_sun,
        flux_W_m2=flux,
        pressure_Pa=pressure,
        lit_area_m2=direct.lit_area_m2,
        illumination=light,
        shadow_error=shadow_error,
    )
