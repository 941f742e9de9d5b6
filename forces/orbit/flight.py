"""Orbit mode: SRP and drag along a trajectory and an attitude history (METHOD.md "Orbit mode").

:func:`fly` puts each step's inputs together — the Sun from the ephemeris (or fixed), the eclipse, the
attitude, ``v_rel`` against the air turning with the Earth and the geodetic place of the atmosphere —
and runs the steps as a sweep runs its attitudes (:mod:`sunwind.forces.orbit.steps`): one model, its
caches and scene kept from step to step, checkpointed chunks, Dask, progress.
"""

from __future__ import annotations

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS, EARTH_ROTATION
from sunwind.forces.model import Model, as_model
from sunwind.forces.orbit.attitude import AttitudeLaw, quaternion_file_attitude
from sunwind.forces.orbit.eclipse import solar_fraction
from sunwind.forces.orbit.results import OrbitResult
from sunwind.forces.orbit.steps import (
    FLUX,
    FRACTION,
    HEIGHT,
    NADIR,
    PLACE,
    POLE,
    ROW_WIDTH,
    SUN,
    SUNLIGHT,
    TIME,
    VELOCITY,
    Loads,
    OrbitSetup,
    SpaceWeather,
    StepInputs,
)
from sunwind.forces.orbit.sun import AU_M, fixed_sun, moon_position, sun_position
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.forces.tables.engine import SweepRun, run_jobs
from sunwind.forces.tables.jobs import Job
from sunwind.geometry.errors import InputError


def fly(
    model: Model,
    trajectory: Trajectory,
    attitude: AttitudeLaw,
    loads: Loads,
    *,
    sun_eci: NDArray[np.float64] | None = None,
    eclipse: str = "conical",
    moon: bool = False,
    run: SweepRun | None = None,
) -> OrbitResult:
    """Forces and torques at every step of ``trajectory`` with the spacecraft held by ``attitude``.

    Parameters
    ----------
    model : Model
        The loaded model; its reference point applies.
    trajectory : Trajectory
        Times, GCRF positions and velocities (:mod:`sunwind.forces.orbit.trajectory`).
    attitude : AttitudeLaw
        Body-to-GCRF rotation at each step (:mod:`sunwind.forces.orbit.attitude`).
    loads : Loads
        SRP and drag settings and the air (:class:`~sunwind.forces.orbit.steps.Loads`);
        the solar flux is scaled by ``(1 au / d)^2`` and the visible share of the Sun at each step.
    sun_eci : (3,) array_like, optional
        A fixed Sun direction (GCRF, at 1 au) instead of the ephemeris.
    eclipse : str
        ``conical`` (penumbra), ``cylindrical`` or ``none``.
    moon : bool
        The Moon eclipses the Sun too (ERFA's ``moon98``); needs the ephemeris Sun.
    run : SweepRun, optional
        Chunks, checkpoint, resume, Dask, threads and progress, as for sweeps.
    """
    model, run = as_model(model), run or SweepRun()
    srp = loads.srp
    if srp is None and loads.drag is None and loads.earth is None:
        raise InputError(
            "give srp, drag or earth (or more): what the orbit computes", parameters=("srp", "drag", "earth")
        )
    time_s, r, v = trajectory.time_s, trajectory.position_m, trajectory.velocity_m_s
    sun_m = sun_position(trajectory.epoch, time_s) if sun_eci is None else fixed_sun(sun_eci, len(time_s))
    if attitude.kind == "csv":
        body_to_eci = quaternion_file_attitude(attitude, trajectory.epoch, time_s)
    else:
        body_to_eci = attitude.body_to_eci(trajectory, sun_m)
    to_sun = sun_m - r
    distance = np.linalg.norm(to_sun, axis=1)
    check_sun(sun_eci, moon)
    moon_m = moon_position(trajectory.epoch, time_s) if moon else None
    fraction = solar_fraction(r, sun_m, eclipse, moon_m)
    rows = np.zeros((len(time_s), ROW_WIDTH))
    rows[:, TIME] = time_s
    rows[:, SUN] = np.einsum("nji,nj->ni", body_to_eci, to_sun / distance[:, None])
    flux_1au = SOLAR_FLUX_1AU if srp is None else srp.flux_W_m2
    rows[:, SUNLIGHT] = flux_1au * (AU_M / distance) ** 2
    rows[:, FRACTION] = fraction
    rows[:, FLUX] = rows[:, SUNLIGHT] * fraction
    radius = np.linalg.norm(r, axis=1)
    rows[:, NADIR] = np.einsum("nji,nj->ni", body_to_eci, -r / radius[:, None])
    rows[:, HEIGHT] = (radius - EARTH_RADIUS) / 1e3
    rows[:, POLE] = body_to_eci[:, 2, :]  # GCRF z in the body frame
    air_velocity = EARTH_ROTATION * np.stack([-r[:, 1], r[:, 0], np.zeros(len(r))], axis=1)
    rows[:, VELOCITY] = np.einsum("nji,nj->ni", body_to_eci, v - air_velocity)
    if loads.drag is not None:
        rows[:, PLACE] = geodetic(trajectory)
        if isinstance(loads.air, SpaceWeather):
            loads.air.check(rows[:, PLACE][:, 0])
    if loads.earth is not None:
        check_height(rows[:, HEIGHT])
    setup = OrbitSetup.of(loads, trajectory.epoch, len(model.craft.part_names))
    records = run_jobs(model, [Job(setup, rows)], run)["orbit"]
    steps = StepInputs(rows, body_to_eci, fraction)
    return OrbitResult.of(model, trajectory, attitude, setup, steps, records)


def check_height(height_km: NDArray[np.float64]) -> None:
    """Refuse the Earth's radiation on an orbit that goes below the surface of the sphere."""
    low = float(height_km.min())
    if not low > 0:
        raise InputError(
            f"the orbit reaches {low:.1f} km above the Earth's sphere: no place for its radiation",
            hint="check the orbit (a trajectory in metres, GCRF)",
            parameters=("earth",),
        )


def check_sun(sun_eci: NDArray[np.float64] | None, moon: bool) -> None:
    """Refuse a fixed Sun direction that is not one, or one asked for together with the Moon."""
    if sun_eci is not None:
        direction = np.asarray(sun_eci, dtype=float)
        if direction.shape != (3,) or not np.all(np.isfinite(direction)) or not direction.any():
            raise InputError(
                f"sun_eci {sun_eci} must be a finite, non-zero direction", parameters=("sun_eci",)
            )
        if moon:
            raise InputError(
                "the Moon's eclipses need the Sun where it is: drop sun_eci or moon",
                parameters=("sun_eci", "moon"),
            )


def geodetic(trajectory: Trajectory) -> NDArray[np.float64]:
    """Altitude [km] above the WGS 84 ellipsoid, geodetic latitude and longitude [deg] at each step
    (GCRF to ITRS by ERFA's IAU 2006/2000A ``c2t06a``, UT1 = UTC, no polar motion)."""
    epoch, time_s = trajectory.epoch, trajectory.time_s
    rotation = erfa.c2t06a(*epoch.tt(time_s), *epoch.ut1(time_s), 0.0, 0.0)
    fixed = np.einsum("nij,nj->ni", rotation, trajectory.position_m)
    longitude, latitude, height = erfa.gc2gd(1, fixed)
    return np.stack([height / 1e3, np.degrees(latitude), np.degrees(longitude)], axis=1)
