"""Orbit mode: SRP and drag along a trajectory and an attitude history (METHOD.md "Orbit mode").

:func:`fly` puts each step's inputs together — the Sun from the ephemeris (or fixed), the eclipse, the
attitude, ``v_rel`` against the air turning with the Earth and the geodetic place of the atmosphere —
and runs the steps as a sweep runs its attitudes (:mod:`sunwind.forces.orbit.steps`): one model, its
caches and scene kept from step to step, checkpointed chunks, Dask, progress. The thermal transient
(``EarthTerms(thermal="transient")``) is integrated over the steps' records once they are all in, with
the share of the Sun in view at any time in between (:class:`SunShare`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.flow import EARTH_RADIUS, EARTH_ROTATION
from sunwind.forces.model import Model, as_model
from sunwind.forces.orbit.attitude import AttitudeLaw, quaternion_file_attitude
from sunwind.forces.orbit.eclipse import solar_fraction
from sunwind.forces.orbit.inputs import StepInputs
from sunwind.forces.orbit.results import OrbitResult
from sunwind.forces.orbit.steps import OrbitLoads, SpaceWeather
from sunwind.forces.orbit.sun import AU_M, fixed_sun, moon_position, sun_position
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.forces.tables.engine import SweepRun, run_jobs
from sunwind.forces.tables.jobs import Job
from sunwind.geometry.errors import InputError


def fly(
    model: Model,
    trajectory: Trajectory,
    attitude: AttitudeLaw,
    loads: OrbitLoads,
    *,
    sun_eci: NDArray[np.float64] | None = None,
    eclipse: str = "conical",
    moon: bool = False,
    run: SweepRun | None = None,
) -> OrbitResult:
    """Compute the forces and torques at every step of ``trajectory``, the spacecraft held by ``attitude``.

    Parameters
    ----------
    model : Model
        The loaded model; its reference point applies.
    trajectory : Trajectory
        Times, GCRF positions and velocities (:mod:`sunwind.forces.orbit.trajectory`).
    attitude : AttitudeLaw
        Body-to-GCRF rotation at each step (:mod:`sunwind.forces.orbit.attitude`).
    loads : OrbitLoads
        What to compute (SRP, drag, the Earth's radiation), the air and the solar flux at 1 au, which
        is scaled by ``(1 au / d)^2`` and the visible share of the Sun at each step.
    sun_eci : (3,) array_like, optional
        A fixed Sun direction (GCRF, at 1 au) instead of the ephemeris.
    eclipse : str
        ``conical`` (penumbra), ``cylindrical`` or ``none``.
    moon : bool
        The Moon eclipses the Sun too (ERFA's ``moon98``); needs the ephemeris Sun.
    run : SweepRun, optional
        Chunks, checkpoint, resume, Dask, threads and progress, as for sweeps. With the thermal
        transient, ``run.progress`` goes on past the number of steps ``n``: ``n + k`` once the
        integration after the steps has reached step ``k``; the checkpoint is kept until the integration
        is done (a run stopped in it resumes without computing a step).

    Returns
    -------
    OrbitResult
        The series of every step, their summary and what the run was.

    Raises
    ------
    InputError
        Nothing to compute; a fixed Sun that is not a direction, or given with the Moon; drag above
        NRLMSIS's range; the Earth's radiation below the Earth's surface.

    Examples
    --------
    >>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, propagate
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.forces import load
    >>> from sunwind.meshes import box_wing
    >>> model = load(box_wing(facet_size=0.5), uniform=Material("paint", 0.4, 0.5, 0.1), two_sided=["wing*"])
    >>> path = propagate(Elements.circular(700, 98.2), Epoch.of("2024-03-20T00:00:00Z"), [0, 60], "kepler")
    >>> result = fly(model, path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup(reflections="none")))
    >>> result.terms, result.series["srp_force_body_N"].shape
    (('srp',), (2, 3))
    """
    model, run = as_model(model), run or SweepRun()
    if loads.srp is None and loads.drag is None and loads.earth is None:
        raise InputError(
            "give srp, drag or earth (or more): what the orbit computes", parameters=("srp", "drag", "earth")
        )
    check_sun(sun_eci, moon)
    steps = step_inputs(trajectory, attitude, loads, sun_eci=sun_eci, eclipse=eclipse, moon=moon)
    if loads.drag is not None and isinstance(loads.air, SpaceWeather):
        loads.air.check(steps.altitude_km)
    setup = loads.sized(len(model.craft.part_names), model.craft.materials.names)
    if loads.earth is not None:
        check_height(steps.height_km)
        setup = replace(setup, earth=loads.earth.sized(model, len(steps)))
    finish = None
    if setup.earth is not None and setup.earth.transient:

        def finish(records: dict) -> dict:
            """The transient over the steps' records, the checkpoint kept until it is done."""
            sun_m, moon_m = sun_and_moon(trajectory, sun_eci, moon)
            share = SunShare(trajectory, sun_m, moon_m, eclipse, steps.solar_fraction)
            angles = [setup.angles_at(model, steps, i) for i in range(len(steps))]
            told = None if run.progress is None else (lambda k: run.progress(len(steps) + k))
            integrated = setup.earth.integrate_thermal(
                model, trajectory.time_s, records[setup.kind], share, angles, block=run.chunk, progress=told
            )
            return records | {setup.kind: integrated}

    records = run_jobs(model, [Job(setup, steps)], run, finish=finish)[setup.kind]
    return OrbitResult.of(model, trajectory, attitude, setup, steps, records)


def step_inputs(
    trajectory: Trajectory,
    attitude: AttitudeLaw,
    loads: OrbitLoads,
    *,
    sun_eci: NDArray[np.float64] | None = None,
    eclipse: str = "conical",
    moon: bool = False,
) -> StepInputs:
    """Each step's inputs, put together before the steps run.

    The Sun from the ephemeris (or fixed), the eclipse, the attitude, ``v_rel`` against the air turning
    with the Earth and, with drag, the geodetic place of the atmosphere.

    Parameters
    ----------
    trajectory : Trajectory
        Times, GCRF positions and velocities.
    attitude : AttitudeLaw
        Body-to-GCRF rotation at each step.
    loads : OrbitLoads
        What the steps compute: its flux at 1 au, and whether drag needs the geodetic place.
    sun_eci : (3,) array_like, optional
        A fixed Sun direction (GCRF, at 1 au) instead of the ephemeris.
    eclipse : str
        ``conical`` (penumbra), ``cylindrical`` or ``none``.
    moon : bool
        The Moon eclipses the Sun too.

    Returns
    -------
    StepInputs
        One row per step of the trajectory.

    Examples
    --------
    >>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, propagate
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> path = propagate(Elements.circular(700, 98.2), Epoch.of("2024-03-20T00:00:00Z"), [0, 60], "kepler")
    >>> steps = step_inputs(path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup()))
    >>> len(steps), steps.nadir_body[0].round(6).tolist()
    (2, [0.0, 0.0, 1.0])
    """
    epoch, time_s, r, v = trajectory.epoch, trajectory.time_s, trajectory.position_m, trajectory.velocity_m_s
    sun_m, moon_m = sun_and_moon(trajectory, sun_eci, moon)
    if attitude.kind == "csv":
        body_to_eci = quaternion_file_attitude(attitude, epoch, time_s)
    else:
        body_to_eci = attitude.body_to_eci(trajectory, sun_m)
    to_sun = sun_m - r
    distance = np.linalg.norm(to_sun, axis=1)
    fraction = solar_fraction(r, sun_m, eclipse, moon_m)
    sunlight = loads.flux_1au_W_m2 * (AU_M / distance) ** 2
    radius = np.linalg.norm(r, axis=1)
    air_velocity = EARTH_ROTATION * np.stack([-r[:, 1], r[:, 0], np.zeros(len(r))], axis=1)
    place = geodetic(trajectory) if loads.drag is not None else np.full((len(time_s), 3), np.nan)
    return StepInputs(
        epoch,
        time_s,
        body_to_eci,
        sun_body=np.einsum("nji,nj->ni", body_to_eci, to_sun / distance[:, None]),
        sunlight_W_m2=sunlight,
        solar_fraction=fraction,
        flux_W_m2=sunlight * fraction,
        velocity_body_m_s=np.einsum("nji,nj->ni", body_to_eci, v - air_velocity),
        nadir_body=np.einsum("nji,nj->ni", body_to_eci, -r / radius[:, None]),
        pole_body=body_to_eci[:, 2, :],  # GCRF z in the body frame
        height_km=(radius - EARTH_RADIUS) / 1e3,
        altitude_km=place[:, 0],
        latitude_deg=place[:, 1],
        longitude_deg=place[:, 2],
    )


def sun_and_moon(
    trajectory: Trajectory, sun_eci: NDArray[np.float64] | None, moon: bool
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The Sun's GCRF position at each step (ephemeris, or fixed at 1 au), and the Moon's when it eclipses.

    Parameters
    ----------
    trajectory : Trajectory
        The steps' times.
    sun_eci : (3,) array_like or None
        A fixed Sun direction (GCRF), or None for the ephemeris.
    moon : bool
        Whether the Moon eclipses the Sun too.

    Returns
    -------
    sun_m : ndarray, shape (n, 3)
        The Sun's position relative to the Earth's centre [m].
    moon_m : ndarray, shape (n, 3) or None
        The Moon's; None without ``moon``.

    Examples
    --------
    >>> from sunwind.forces.orbit import Elements, Epoch, propagate
    >>> path = propagate(Elements.circular(500, 0.0), Epoch.of("2024-03-20T00:00:00Z"), [0.0, 60.0], "kepler")
    >>> sun, moon = sun_and_moon(path, [1.0, 0.0, 0.0], False)
    >>> (sun / AU_M).round(6).tolist(), moon
    ([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]], None)
    """
    epoch, time_s = trajectory.epoch, trajectory.time_s
    sun_m = sun_position(epoch, time_s) if sun_eci is None else fixed_sun(sun_eci, len(time_s))
    return sun_m, moon_position(epoch, time_s) if moon else None


@dataclass(frozen=True, eq=False)
class SunShare:
    """The share of the solar disc in view at any time of a run: :func:`~sunwind.forces.orbit.eclipse.
    solar_fraction` at the spacecraft's position interpolated between the steps by a cubic Hermite spline
    on position and velocity, the Sun and Moon linearly (over a minute they leave the chord by 3 m and
    1 m, 2e-11 and 3e-9 rad seen from the Earth); at a step's time, that step's own share.

    Parameters
    ----------
    trajectory : Trajectory
        The steps' times, GCRF positions and velocities.
    sun_m : ndarray, shape (n, 3)
        The Sun's GCRF position at each step [m].
    moon_m : ndarray, shape (n, 3) or None
        The Moon's, when it eclipses too.
    eclipse : str
        The shadow model (``conical``, ``cylindrical``, ``none``).
    fraction : ndarray, shape (n,)
        The steps' own shares (returned at their times, bitwise).

    Examples
    --------
    A 500 km orbit out of the Earth's shadow, stepped every 300 s: the 8 s penumbra falls between two
    steps, and the share there comes from the interpolated positions (at exact positions, 0.402 and
    0.553 at 1072 s and 1073 s: the spline's error, ``(omega h)^4 r / 384``, is 220 m at 300 s steps,
    0.35 m at 60 s, 2 cm at 30 s).

    >>> import numpy as np
    >>> from sunwind.forces.orbit import Elements, Epoch, propagate
    >>> from sunwind.forces.orbit.eclipse import solar_fraction
    >>> path = propagate(Elements.circular(500, 0.0), Epoch.of("2024-03-20T00:00:00Z"),
    ...                  np.arange(0.0, 5701.0, 300.0), "kepler")
    >>> sun, _ = sun_and_moon(path, [-1.0, 0.0, 0.0], False)
    >>> share = SunShare(path, sun, None, "conical", solar_fraction(path.position_m, sun))
    >>> [round(share(t), 3) for t in (600.0, 1060.0, 1072.0, 1073.0, 1080.0)]
    [0.0, 0.0, 0.392, 0.543, 1.0]
    """

    trajectory: Trajectory
    sun_m: NDArray[np.float64]
    moon_m: NDArray[np.float64] | None
    eclipse: str
    fraction: NDArray[np.float64]

    def __call__(self, t_s: float) -> float:
        """The share of the solar disc in view at ``t_s`` [s] (within the run's times)."""
        times = self.trajectory.time_s
        k = int(np.clip(np.searchsorted(times, t_s, side="right") - 1, 0, max(len(times) - 2, 0)))
        if t_s == times[k] or len(times) == 1:
            return float(self.fraction[k])
        if t_s == times[k + 1]:
            return float(self.fraction[k + 1])
        h = times[k + 1] - times[k]
        s = (t_s - times[k]) / h
        r, v = self.trajectory.position_m, self.trajectory.velocity_m_s
        position = (
            (2 * s**3 - 3 * s**2 + 1) * r[k]
            + (s**3 - 2 * s**2 + s) * h * v[k]
            + (-2 * s**3 + 3 * s**2) * r[k + 1]
            + (s**3 - s**2) * h * v[k + 1]
        )
        sun = (1 - s) * self.sun_m[k] + s * self.sun_m[k + 1]
        moon = None if self.moon_m is None else ((1 - s) * self.moon_m[k] + s * self.moon_m[k + 1])[None]
        return float(solar_fraction(position[None], sun[None], self.eclipse, moon)[0])


def check_height(height_km: NDArray[np.float64]) -> None:
    """Refuse the Earth's radiation on an orbit that goes below the surface of the sphere.

    Parameters
    ----------
    height_km : ndarray, shape (n,)
        Each step's height above the Earth's sphere [km].

    Raises
    ------
    InputError
        A step at or below the surface.

    Examples
    --------
    >>> check_height(np.array([500.0, 510.0]))  # nothing to refuse
    """
    low = float(height_km.min())
    if not low > 0:
        raise InputError(
            f"the orbit reaches {low:.1f} km above the Earth's sphere: no place for its radiation",
            hint="check the orbit (a trajectory in metres, GCRF)",
            parameters=("earth",),
        )


def check_sun(sun_eci: NDArray[np.float64] | None, moon: bool) -> None:
    """Refuse a fixed Sun direction that is not one, or one asked for together with the Moon.

    Parameters
    ----------
    sun_eci : (3,) array_like or None
        The fixed Sun direction (GCRF), or None for the ephemeris.
    moon : bool
        Whether the Moon eclipses the Sun too.

    Raises
    ------
    InputError
        A direction that is not finite and non-zero, or given with ``moon``.

    Examples
    --------
    >>> check_sun([0.0, 0.0, 0.0], False)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: sun_eci [0.0, 0.0, 0.0] must be a finite, non-zero direction
    """
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
    """Altitude [km] above the WGS 84 ellipsoid, geodetic latitude and longitude [deg] at each step.

    GCRF is turned to ITRS by ERFA's IAU 2006/2000A ``c2t06a`` (UT1 = UTC, no polar motion), then
    ``gc2gd`` gives the geodetic place.

    Parameters
    ----------
    trajectory : Trajectory
        The steps' times and GCRF positions.

    Returns
    -------
    ndarray, shape (n, 3)
        Altitude, latitude, longitude of each step.

    Examples
    --------
    >>> from sunwind.forces.orbit import Elements, Epoch, propagate
    >>> path = propagate(Elements.circular(500, 0.0), Epoch.of("2024-03-20T00:00:00Z"), [0.0], "kepler")
    >>> geodetic(path)[0, :2].round(0).tolist()  # on the equator
    [500.0, 0.0]
    """
    epoch, time_s = trajectory.epoch, trajectory.time_s
    rotation = erfa.c2t06a(*epoch.tt(time_s), *epoch.ut1(time_s), 0.0, 0.0)
    fixed = np.einsum("nij,nj->ni", rotation, trajectory.position_m)
    longitude, latitude, height = erfa.gc2gd(1, fixed)
    return np.stack([height / 1e3, np.degrees(latitude), np.degrees(longitude)], axis=1)
