"""The flow speed: a circular orbit's speed, relative to a still or a co-rotating atmosphere
(METHOD.md "Atmosphere")."""

from __future__ import annotations

import math

from sunwind.forces.gas.atmosphere import finite_number
from sunwind.geometry.errors import InputError

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
#: Fastest ``|v_rel|`` [m/s]: 1000 km/s, over ten times any heliocentric or meteoric speed near a planet,
#: and still far below the speed of light (the laws are Newtonian).
MAX_FLOW_SPEED = 1e6


def flow_speed(speed_m_s: float, name: str = "speed_m_s") -> float:
    """``speed_m_s`` [m/s] as a float, checked to be the speed of a flow: finite and from
    :data:`MIN_FLOW_SPEED` to :data:`MAX_FLOW_SPEED`; ``name`` is the parameter that gave it.

    Raises
    ------
    InputError
        Not a number, not finite, or out of that range.
    """
    speed = finite_number(speed_m_s, name, "m/s")
    if speed < MIN_FLOW_SPEED:
        raise InputError(
            f"{name} gives a speed of {speed:.6g} m/s, below {MIN_FLOW_SPEED:g} m/s: too slow to be a "
            "flow (thermal speeds are ~1 km/s)",
            hint=f"give v_rel of at least {MIN_FLOW_SPEED:g} m/s; an orbit's is ~7.5 km/s",
            parameters=(name,),
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

    Raises
    ------
    InputError
        An altitude [km] that is negative or not finite.
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

    with ``omega = 7.292115e-5 rad/s``. Winds are not included.

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

    Raises
    ------
    InputError
        An argument out of range or not finite.
    """
    altitude = finite_number(altitude_km, "altitude_km", "km", minimum=0.0)
    latitude = math.radians(finite_number(latitude_deg, "latitude_deg", "deg", minimum=-90.0, maximum=90.0))
    heading = math.radians(finite_number(heading_deg, "heading_deg", "deg"))
    if inertial_speed_m_s is None:
        speed = circular_speed(altitude)
    else:
        speed = finite_number(inertial_speed_m_s, "inertial speed", "m/s", minimum=0.0)
    air = EARTH_ROTATION * (EARTH_RADIUS + altitude * 1e3) * math.cos(latitude)
    north = speed * math.cos(heading)
    east = speed * math.sin(heading) - air
    return math.hypot(north, east)
