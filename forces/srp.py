"""One attitude, end to end: shadow rays, the force law on every lit side, totals about a reference point."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.direct import TOTALS, accumulate_forces, model_block_moments
from sunwind.forces.radiation.law import radiation_pressure, solar_flux
from sunwind.forces.reflection.plan import ReflectionSettings, reflected_part, reflection_plan
from sunwind.forces.results import SrpResult
from sunwind.geometry.directions import finite_point, unit_vector
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE
from sunwind.geometry.spacecraft import Spacecraft


def reference_point(
    craft: Spacecraft, point_m: Sequence[float] | NDArray | None
) -> tuple[NDArray[np.float64], str]:
    """The torque reference point [m] and its name: the user's, else the model default."""
    if point_m is None:
        return craft.default_reference
    return finite_point(point_m, "--ref-point"), "user"


def srp(
    craft: Spacecraft,
    sun_vector: Sequence[float] | NDArray,
    *,
    flux_W_m2: float | None = None,
    distance_au: float | None = None,
    reference_point_m: Sequence[float] | NDArray | None = None,
    samples: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    reflections: str | ReflectionSettings = "auto",
) -> SrpResult:
    """Solar-radiation force and torque with self-shadowing and inter-reflection, at one attitude.

    Parameters
    ----------
    craft : Spacecraft
    sun_vector : (3,) array_like
        Direction from the spacecraft toward the Sun, body frame (normalised here).
    flux_W_m2 : float, optional
        Solar flux; or ``distance_au`` from the Sun (flux 1361 W/m^2 at 1 au); default 1 au.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m] (the centre of mass); default the volume centroid of a closed
        model, else the area centroid.
    samples : int, optional
        Shadow-ray points per side, rounded up to a square; default adaptive.
    tolerance : float
        Adaptive sampling's convergence threshold on a side's lit share.
    reflections : str or ReflectionSettings
        ``"none"``, ``"specular"``, ``"full"`` or ``"auto"`` (full when ``K_IS >= 0.1``), or settings
        with chain cutoff, depth and view-factor sampling
        (:class:`sunwind.forces.reflection.plan.ReflectionSettings`).

    Returns
    -------
    SrpResult
    """
    settings = reflections if isinstance(reflections, ReflectionSettings) else ReflectionSettings(reflections)
    u_sun = unit_vector(sun_vector, "sun_vector")
    flux = solar_flux(flux_W_m2, distance_au)
    pressure = radiation_pressure(flux)
    ref, ref_name = reference_point(craft, reference_point_m)
    plan = reflection_plan(craft, settings)
    sampler = craft.sampler
    low, high = sampler.block_normal_bounds
    args = (craft.side_centroids, craft.side_normals, craft.side_areas, craft.side_optics, u_sun, ref)
    blocks = (
        sampler.side_block,
        low,
        high,
        model_block_moments(craft),
        plan.side_weights,
        plan.block_weights,
    )
    partials = np.zeros((sampler.n_blocks, TOTALS + plan.channels))

    def force_sum(sides: NDArray[np.int64], share: NDArray, centroid: NDArray) -> None:
        accumulate_forces(sides, share, centroid, *args, *blocks, partials)

    light = sampler.illuminate(u_sun, samples, tolerance, reduce=force_sum)
    # block sums added in block order: the same bits whatever the threads did; eq. (4) with P = 1
    totals = partials.sum(axis=0)
    totals[:6] *= pressure
    reflected = reflected_part(craft, light, flux, ref, settings, plan, flux * totals[7:])
    return SrpResult(
        sun_vector=u_sun,
        flux_W_m2=flux,
        pressure_Pa=pressure,
        force_N=totals[0:3] + reflected.force_N,
        torque_Nm=totals[3:6] + reflected.torque_Nm,
        direct_force_N=totals[0:3],
        direct_torque_Nm=totals[3:6],
        reflected=reflected,
        settings=settings,
        reference_point_m=ref,
        reference_point=ref_name,
        lit_area_m2=float(totals[6]),
        projected_area_m2=float(totals[7]),
        rays=light.rays,
        sampling=light.sampling,
        craft=craft,
        illumination=light,
    )
