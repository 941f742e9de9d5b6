"""Solar-radiation pressure at one attitude or a batch: shadow rays, the force law on every lit side,
inter-reflection, totals about a reference point (METHOD.md "Direct solar pressure", "Inter-reflection").
With ``reflections="plates"`` every side facing the Sun is wholly lit and alone (the flat-plate model):
no ray is cast."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.batches import SrpBatch
from sunwind.forces.model import Model, as_model
from sunwind.forces.radiation.direct import DirectTotals, direct_pass, lit_area_loads
from sunwind.forces.radiation.law import radiation_pressure, solar_flux, surface_forces
from sunwind.forces.reflection import ReflectionSettings, reflected_part, reflection_plan
from sunwind.forces.reflection.sensitivity import optics_sensitivities
from sunwind.forces.results import SrpResult
from sunwind.geometry.directions import unit_vectors
from sunwind.geometry.parallel import map_items, using_threads
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft


def srp(
    model: Model | Spacecraft,
    sun_vector: Sequence[float] | NDArray,
    *,
    flux_W_m2: float | None = None,
    distance_au: float | None = None,
    reference_point_m: Sequence[float] | NDArray | None = None,
    sampling: ShadowSampling | None = None,
    reflections: str | ReflectionSettings = "auto",
    sensitivities: bool = False,
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
        Solar flux [W/m^2]; give this or ``distance_au``; default the flux at 1 au.
    distance_au : float, optional
        Distance from the Sun [au], the flux scaled from 1361 W/m^2 at 1 au by its inverse square.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m] (the centre of mass); default the model's, else the volume
        centroid of a closed model, else the area centroid.
    sampling : ShadowSampling, optional
        How the shadow pass samples each side (:class:`~sunwind.geometry.rays.sampling.ShadowSampling`):
        by default shadow edges located and cut along the outline to its ``tolerance``, the pass
        checking itself (the result's ``error_estimate`` is the error it estimates it left, relative
        to the force and torque); or a fixed count of ``samples`` per side (no estimate).
    reflections : str or ReflectionSettings
        One of :data:`~sunwind.forces.reflection.settings.MODES`, read for light: ``"none"``,
        ``"specular"``, ``"full"``, ``"auto"`` (full when ``K_IS >= 0.1``) or ``"plates"`` (every side
        facing the Sun wholly lit, no ray cast); or settings with chain cutoff, depth and view-factor
        sampling (:class:`~sunwind.forces.reflection.ReflectionSettings`).
    sensitivities : bool
        Also give ``result.sensitivities``: the derivatives of force and torque with respect to every
        material's reflectivity, specular fraction and transmissivity
        (:class:`~sunwind.forces.sensitivity.Sensitivities`; METHOD.md "Sensitivities"), in the same
        pass: eq. (4)'s partials, the beam chains' forward derivatives and the diffuse balance's adjoint.

    Returns
    -------
    SrpResult or SrpBatch
        The result of one Sun vector, or a batch of results for a batch of Sun vectors.

    Raises
    ------
    InputError
        A Sun vector that is not three finite numbers (or rows of them), a flux, reference point,
        sampling or reflections out of range.

    References
    ----------
    Shmatov and Mordvinkin (2013): the force law, eq. (4); the interference criterion ``K_IS``, eq. (7);
    the diffuse balance, eq. (12).

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box_wing(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1)
    >>> result = sw.srp(model, [0.0, 0.0, 1.0], reflections="none")
    >>> bool(result.force_N[2] < 0)  # pushed away from the Sun
    True
    >>> sw.srp(model, [[0, 0, 1], [1, 0, 0]], reflections="plates").force_N.shape
    (2, 3)
    """
    model = as_model(model)
    settings = ReflectionSettings.of(reflections)
    suns = unit_vectors(sun_vector, "sun_vector")
    flux = solar_flux(flux_W_m2, distance_au)
    reference = model.reference(reference_point_m)
    shadows = ShadowSampling.of(sampling)
    with using_threads(model.threads):
        results = map_items(
            lambda u: _one(model.craft, u, flux, reference, shadows, settings, sensitivities),
            suns.reshape(-1, 3),
        )
    return results[0] if suns.ndim == 1 else SrpBatch(tuple(results))


def _one(
    craft: Spacecraft,
    u_sun: NDArray[np.float64],
    flux: float,
    reference: tuple[NDArray[np.float64], str],
    sampling: ShadowSampling,
    settings: ReflectionSettings,
    sensitivities: bool,
) -> SrpResult:
    """One attitude, its arguments checked."""
    pressure = radiation_pressure(flux)
    ref, ref_name = reference
    plan = reflection_plan(craft, settings)
    if plan.mode == "plates":
        direct = _plate_pass(craft, u_sun, ref)
    else:
        direct = direct_pass(craft, u_sun, ref, sampling.samples, sampling.tolerance, plan.weights)
    light = direct.illumination
    reflected = reflected_part(craft, direct, flux, ref, settings, plan, sensitivities)
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
        sensitivities=optics_sensitivities(craft, light, flux, ref, plan, reflected.chains)
        if sensitivities
        else None,
    )


def _plate_pass(
    craft: Spacecraft, u_sun: NDArray[np.float64], reference_m: NDArray[np.float64]
) -> DirectTotals:
    """The direct pass of ``plates``: eq. (4) on every side facing ``u_sun``, wholly lit, with ``P = 1``;
    no ray is cast."""
    cos = craft.side_normals @ u_sun
    facing = np.flatnonzero(cos > 0.0)
    light = Illumination(
        direction=u_sun,
        side_normals=craft.side_normals,
        facing_runs=(facing,),
        share_runs=(np.ones(len(facing)),),
        lit_centroid=craft.side_centroids,
        rays=0,
        sampling="plates: every side facing the Sun wholly lit",
    )
    rho, beta, sigma = craft.side_optics[facing].T
    areas, cos = craft.side_areas[facing], cos[facing]
    forces = surface_forces(craft.side_normals[facing], areas, cos, rho, beta, sigma, u_sun, 1.0)
    projected = areas * cos
    return DirectTotals(
        illumination=light,
        force=forces.sum(axis=0),
        torque=np.cross(craft.side_centroids[facing] - reference_m, forces).sum(axis=0),
        lit_area_m2=float(areas.sum()),
        projected_area_m2=float(projected.sum()),
        absorbed_area_m2=float(projected @ (1.0 - rho - sigma)),
        channels_m2=np.zeros(0),
    )
