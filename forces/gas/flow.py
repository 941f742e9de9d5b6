"""The flow: a circular orbit's speed, and its velocity relative to a co-rotating atmosphere
(METHOD.md "Atmosphere")."""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import finite_number
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError, UnitWarning

#: Earth's gravitational parameter GM [m^3/s^2] (WGS 84 / IERS Conventions 2010).
EARTH_GM = 3.986004418e14
#: Earth's equatorial radius [m] (WGS 84 semi-major axis).
EARTH_RADIUS = 6378.137e3
#: Earth's mean angular velocity [rad/s] (WGS 84 nominal value).
EARTH_ROTATION = 7.292115e-5
#: Slowest ``|v_rel|`` [m/s] taken as a flow: at 1 m/s the speed ratio in thermospheric air (thermal
#: speed ~1 km/s) is ~1e-3 and the dynamic pressure a 1e-8 share of an orbit's (~7.5 km/s); below it the
#: directed flow the laws and the shadow follow is lost in the thermal motion.
MIN_FLOW_SPEED = 1.0
#: A flow speed below this [m/s] is said to look like km/s: the slowest orbital v_rel is ~3 km/s.
KM_S_SUSPECT_BELOW = 100.0
#: Fastest ``|v_rel|`` [m/s]: 1000 km/s, over ten times any heliocentric or meteoric speed near a planet,
#: and still far below the speed of light (the laws are Newtonian).
MAX_FLOW_SPEED = 1e6
#: A crosswind below this share of the along-track speed is none (round-off of ``cos(90 deg)``).
CROSSWIND_TOLERANCE = 1e-12
#: Largest tilt [deg] of a given nadir from perpendicular to the orbit velocity.
NADIR_TOLERANCE_DEG = 1.0


def flow_speed(speed_m_s: float, name: str = "speed_m_s") -> float:
    """``speed_m_s`` [m/s] as a float, checked to be the speed of a flow.

    Parameters
    ----------
    speed_m_s : float
        The speed [m/s]: finite, at most :data:`MAX_FLOW_SPEED` (below :data:`MIN_FLOW_SPEED` it warns).
    name : str
        The parameter that gave it, named in messages.

    Returns
    -------
    float
        The speed [m/s].

    Raises
    ------
    InputError
        Not a number, not finite, or above :data:`MAX_FLOW_SPEED`.

    Examples
    --------
    >>> flow_speed(7500)
    7500.0
    """
    speed = finite_number(speed_m_s, name, "m/s")
    if speed < MIN_FLOW_SPEED:
        raise InputError(
            f"{name} gives a speed of {speed:.6g} m/s, below {MIN_FLOW_SPEED:g} m/s: too slow to be a "
            "flow (thermal speeds are ~1 km/s)",
            hint=f"give v_rel of at least {MIN_FLOW_SPEED:g} m/s; an orbit's is ~7.5 km/s",
            parameters=(name,),
        )
    if speed < KM_S_SUSPECT_BELOW:
        warnings.warn(
            UnitWarning(
                f"{name} gives a speed of {speed:.6g} m/s: that looks like km/s typed for m/s (an orbit's "
                f"v_rel is ~7 500 m/s); at {speed:.3g} m/s the flow is slower than the molecules' thermal "
                "speed and the drag is mostly their random impacts",
                (name,),
                key=("flow speed", speed),
            ),
            stacklevel=3,
        )
    if speed > MAX_FLOW_SPEED:
        raise InputError(
            f"{name} gives a speed of {speed:.6g} m/s, above {MAX_FLOW_SPEED:g} m/s",
            hint="give v_rel in m/s; an orbit's is ~7.5 km/s",
            parameters=(name,),
        )
    return speed


def circular_speed(altitude_km: float) -> float:
    """Speed [m/s] of a circular orbit ``sqrt(GM / (R + h))`` at an altitude above a spherical Earth.

    ``GM = 3.986004418e14 m^3/s^2`` and ``R = 6378.137 km`` (WGS 84 equatorial radius).

    Parameters
    ----------
    altitude_km : float
        Altitude [km], >= 0.

    Returns
    -------
    float
        The orbital speed [m/s].

    Raises
    ------
    InputError
        An altitude [km] that is negative or not finite.

    Examples
    --------
    >>> round(circular_speed(400.0), 1)
    7668.6
    """
    altitude = finite_number(altitude_km, "altitude_km", "km", minimum=0.0)
    return math.sqrt(EARTH_GM / (EARTH_RADIUS + altitude * 1e3))


def corotation_speed(
    altitude_km: float,
    latitude_deg: float,
    heading_deg: float,
    inertial_speed_m_s: float | None = None,
) -> float:
    """Speed [m/s] of a spacecraft relative to an atmosphere that rotates with the Earth.

    The spacecraft is at radius ``r = R + h`` and latitude ``phi`` (spherical Earth) with a horizontal
    inertial velocity of speed ``V`` and heading ``psi`` (clockwise from north: 90 deg is due east, a
    prograde equatorial orbit). The air moves at ``omega x r``, ``omega r cos(phi)`` due east, so

        |v - omega x r| = sqrt(V^2 - 2 V omega r cos(phi) sin(psi) + (omega r cos(phi))^2)

    with ``omega = 7.292115e-5 rad/s``. Winds are not included. :func:`corotation_velocity` gives the
    vector.

    Parameters
    ----------
    altitude_km : float
        Altitude [km], at least 0.
    latitude_deg : float
        Latitude [deg], -90 to 90.
    heading_deg : float
        Heading of the inertial velocity [deg], clockwise from north.
    inertial_speed_m_s : float, optional
        Inertial speed ``V`` [m/s]; default the circular speed at that altitude.

    Returns
    -------
    float
        ``|v_rel|`` [m/s].

    Raises
    ------
    InputError
        An argument out of range or not finite.

    Examples
    --------
    A prograde equatorial orbit at 400 km meets the air about 0.49 km/s slower:

    >>> round(corotation_speed(400.0, 0.0, 90.0), 1)
    7174.3
    """
    return math.hypot(*_track_components(altitude_km, latitude_deg, heading_deg, inertial_speed_m_s))


def corotation_velocity(
    altitude_km: float,
    latitude_deg: float,
    heading_deg: float,
    velocity_direction: Sequence[float] | NDArray,
    nadir: Sequence[float] | NDArray | None = None,
    inertial_speed_m_s: float | None = None,
) -> NDArray[np.float64]:
    """``v_rel = v - omega x r`` [m/s] in the body frame, relative to an atmosphere rotating with the Earth.

    The orbit is as for :func:`corotation_speed`.

    Along the track ``v_rel`` is ``V - omega r cos(phi) sin(psi)``; across it, the air adds the
    crosswind ``-omega r cos(phi) cos(psi)`` along ``p = v_hat x zenith`` (horizontal, to the right of
    the track seen from above): ``omega r`` ~ 0.49 km/s at 400 km on a polar orbit's equator crossing,
    nothing on an equatorial orbit or at a pole.

    Parameters
    ----------
    altitude_km : float
        Altitude [km], at least 0.
    latitude_deg : float
        Latitude [deg], -90 to 90.
    heading_deg : float
        Heading of the inertial velocity [deg], clockwise from north.
    velocity_direction : (3,) array_like
        Direction of the inertial velocity ``v`` in the body frame (any length).
    nadir : (3,) array_like, optional
        Direction from the spacecraft to the Earth's centre in the body frame, perpendicular to ``v``
        within 1 deg (a circular orbit's velocity is horizontal); needed only where there is a
        crosswind to place.
    inertial_speed_m_s : float, optional
        Inertial speed ``V`` [m/s]; default the circular speed at that altitude.

    Returns
    -------
    (3,) float64
        ``v_rel`` [m/s], body frame.

    Raises
    ------
    InputError
        An argument out of range or not finite; a crosswind with no ``nadir``; a ``nadir`` not
        perpendicular to ``velocity_direction``.

    Examples
    --------
    >>> corotation_velocity(400.0, 0.0, 90.0, [1.0, 0.0, 0.0]).round(1) + 0.0
    array([7174.3,    0. ,    0. ])
    """
    along, across = _track_components(altitude_km, latitude_deg, heading_deg, inertial_speed_m_s)
    v_hat = unit_vector(velocity_direction, "velocity_direction")
    if abs(across) <= CROSSWIND_TOLERANCE * abs(along):
        return along * v_hat
    if nadir is None:
        raise InputError(
            f"the co-rotating air crosses the track at {abs(across):.1f} m/s at latitude "
            f"{float(latitude_deg):g} deg, heading {float(heading_deg):g} deg: placing that crosswind "
            "needs the body-frame direction to the Earth's centre",
            hint="give nadir, the body-frame direction from the spacecraft to the Earth's centre",
            parameters=("nadir",),
        )
    down = unit_vector(nadir, "nadir")
    tilt = math.degrees(math.asin(min(1.0, abs(float(down @ v_hat)))))
    if tilt > NADIR_TOLERANCE_DEG:
        raise InputError(
            f"nadir is {tilt:.3g} deg off perpendicular to velocity_direction; a circular orbit's "
            "velocity is horizontal",
            hint="give the body-frame direction to the Earth's centre, at right angles to the velocity",
            parameters=("nadir", "velocity_direction"),
        )
    down = down - (down @ v_hat) * v_hat
    right = np.cross(down / np.linalg.norm(down), v_hat)  # v_hat x zenith
    return along * v_hat + across * right


def _track_components(
    altitude_km: float, latitude_deg: float, heading_deg: float, inertial_speed_m_s: float | None
) -> tuple[float, float]:
    """``v_rel`` [m/s] along the track and across it (along ``v_hat x zenith``), arguments checked."""
    altitude = finite_number(altitude_km, "altitude_km", "km", minimum=0.0)
    latitude = math.radians(finite_number(latitude_deg, "latitude_deg", "deg", minimum=-90.0, maximum=90.0))
    heading = math.radians(finite_number(heading_deg, "heading_deg", "deg"))
    if inertial_speed_m_s is None:
        speed = circular_speed(altitude)
    else:
        speed = finite_number(inertial_speed_m_s, "inertial speed", "m/s", minimum=0.0)
    air = EARTH_ROTATION * (EARTH_RADIUS + altitude * 1e3) * math.cos(latitude)
    return speed - air * math.sin(heading), -air * math.cos(heading)
