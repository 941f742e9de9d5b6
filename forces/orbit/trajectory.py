"""Where the spacecraft is: positions and velocities in GCRF at the steps of a run, from Keplerian
elements propagated by two-body motion (``kepler``) or with the Earth's J2 (``j2``).

``kepler`` solves Kepler's equation at every step (elliptic orbits). ``j2`` integrates
``a = -mu r / r^3 + a_J2`` (Vallado eq. 8-29; J2 = 1.08262668e-3, R = 6378.137 km, the J2 axis taken as
GCRF's z: the pole's precession since J2000, a third of a degree, is left out) with SciPy's DOP853 at
a relative tolerance of 1e-11, from the osculating state of the elements at the epoch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from sunwind.forces.gas.flow import EARTH_GM, EARTH_RADIUS
from sunwind.forces.orbit.clock import Epoch
from sunwind.geometry.errors import InputError

#: The Earth's second zonal harmonic (EGM 2008, unnormalised).
EARTH_J2 = 1.08262668e-3
#: Largest semi-major axis taken [m]: the radius of the Earth's sphere of influence about the Sun.
MOST_SEMI_MAJOR_AXIS_M = 9.25e8
#: Propagators of Keplerian elements.
PROPAGATORS = ("kepler", "j2")


@dataclass(frozen=True)
class Trajectory:
    """Spacecraft states at the steps of a run.

    Attributes
    ----------
    epoch : Epoch
        Time zero.
    time_s : (n,) float64
        Seconds after the epoch.
    position_m, velocity_m_s : (n, 3) float64
        Position [m] and velocity [m/s], GCRF (Earth-centred inertial).
    source : str
        How it was made, in words (for the output's provenance).
    """

    epoch: Epoch
    time_s: NDArray[np.float64]
    position_m: NDArray[np.float64]
    velocity_m_s: NDArray[np.float64]
    source: str

    @property
    def altitude_km(self) -> NDArray[np.float64]:
        """Height above the Earth's equatorial radius [km] (spherical; the atmosphere uses geodetic)."""
        return (np.linalg.norm(self.position_m, axis=1) - EARTH_RADIUS) / 1e3

    @property
    def period_s(self) -> float:
        """Two-body period [s] of the first state's osculating orbit (inf when it is not bound)."""
        r, v = np.linalg.norm(self.position_m[0]), np.linalg.norm(self.velocity_m_s[0])
        energy = v**2 / 2 - EARTH_GM / r
        if energy >= 0:
            return math.inf
        return 2 * math.pi * math.sqrt((-EARTH_GM / (2 * energy)) ** 3 / EARTH_GM)


class TrajectoryWarning(UserWarning):
    """A trajectory that runs but may not be what was meant (stale elements)."""


@dataclass(frozen=True)
class Elements:
    """Keplerian elements: semi-major axis [m], eccentricity, inclination, right ascension of the
    ascending node, argument of perigee and true anomaly [deg]."""

    a_m: float
    e: float
    i_deg: float
    raan_deg: float
    argp_deg: float
    nu_deg: float

    def __post_init__(self) -> None:
        values = (self.a_m, self.e, self.i_deg, self.raan_deg, self.argp_deg, self.nu_deg)
        if not all(math.isfinite(float(v)) for v in values):
            raise InputError(f"orbital elements {values} must be finite numbers", parameters=("elements",))
        if not 0 <= self.e < 1:
            raise InputError(
                f"eccentricity {self.e:g} is not that of a closed orbit",
                hint="give 0 <= e < 1 (a TLE or an ephemeris file for anything else)",
                parameters=("elements",),
            )
        angles = {"RAAN": self.raan_deg, "argument of perigee": self.argp_deg, "true anomaly": self.nu_deg}
        wide = [f"{name} {value:g}" for name, value in angles.items() if abs(value) > 360]
        if wide:
            raise InputError(
                f"{', '.join(wide)} deg outside [-360, 360]: far beyond a turn a float keeps no fraction "
                "of one",
                hint="give the angles in degrees, e.g. 0 to 360",
                parameters=("elements",),
            )
        if not 0 <= self.i_deg <= 180:
            raise InputError(
                f"inclination {self.i_deg:g} deg is outside 0-180 deg",
                hint="give the angle between the orbit plane and the equator (retrograde orbits above 90)",
                parameters=("elements",),
            )
        if self.a_m > MOST_SEMI_MAJOR_AXIS_M:
            raise InputError(
                f"semi-major axis {self.a_m / 1e3:.3g} km is beyond the Earth's sphere of influence "
                f"({MOST_SEMI_MAJOR_AXIS_M / 1e3:.3g} km), where two-body motion about the Earth fails",
                hint="give the semi-major axis in km (e.g. 6878 for a 500 km circular orbit)",
                parameters=("elements",),
            )
        perigee = self.a_m * (1 - self.e)
        if perigee <= EARTH_RADIUS:
            raise InputError(
                f"the perigee radius {perigee / 1e3:.1f} km is inside the Earth (6378.137 km)",
                hint="give the semi-major axis in km from the Earth's centre, not an altitude",
                parameters=("elements",),
            )

    @classmethod
    def circular(
        cls, altitude_km: float, inclination_deg: float, raan_deg: float = 0.0, arg_latitude_deg: float = 0.0
    ) -> Elements:
        """A circular orbit at ``altitude_km`` above 6378.137 km, starting at argument of latitude
        ``arg_latitude_deg`` (from the ascending node)."""
        if not (math.isfinite(altitude_km) and altitude_km > 0):
            raise InputError(f"altitude {altitude_km} km must be a positive number", parameters=("altitude",))
        return cls(EARTH_RADIUS + altitude_km * 1e3, 0.0, inclination_deg, raan_deg, 0.0, arg_latitude_deg)

    @property
    def period_s(self) -> float:
        """Two-body period [s]."""
        return 2 * math.pi * math.sqrt(self.a_m**3 / EARTH_GM)

    def state(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Position [m] and velocity [m/s], GCRF, at the elements' true anomaly."""
        p = self.a_m * (1 - self.e**2)
        nu = math.radians(self.nu_deg)
        r = p / (1 + self.e * math.cos(nu))
        position = np.array([r * math.cos(nu), r * math.sin(nu), 0.0])
        scale = math.sqrt(EARTH_GM / p)
        velocity = np.array([-scale * math.sin(nu), scale * (self.e + math.cos(nu)), 0.0])
        rotation = self.perifocal_to_inertial()
        return rotation @ position, rotation @ velocity

    def perifocal_to_inertial(self) -> NDArray[np.float64]:
        """The rotation from the perifocal frame (x to perigee, z along the orbit normal) to GCRF."""
        raan, i, argp = (math.radians(v) for v in (self.raan_deg, self.i_deg, self.argp_deg))
        return _rz(raan) @ _rx(i) @ _rz(argp)


def propagate(elements: Elements, epoch: Epoch, time_s: NDArray[np.float64], propagator: str) -> Trajectory:
    """States at ``time_s`` [s] after ``epoch``, the elements being those at the epoch."""
    if propagator not in PROPAGATORS:
        raise InputError(
            f"propagator {propagator!r} is not one of {', '.join(PROPAGATORS)}", parameters=("propagator",)
        )
    time_s = np.asarray(time_s, dtype=float)
    label = (
        f"{propagator}: a = {elements.a_m / 1e3:.3f} km, e = {elements.e:g}, i = {elements.i_deg:g} deg, "
        f"RAAN = {elements.raan_deg:g} deg, argp = {elements.argp_deg:g} deg, nu = {elements.nu_deg:g} deg"
    )
    if propagator == "kepler":
        position, velocity = _two_body(elements, time_s)
    else:
        position, velocity = _with_j2(elements, time_s)
    return Trajectory(epoch, time_s, position, velocity, label)


def _two_body(elements: Elements, time_s: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
    a, e = elements.a_m, elements.e
    n = math.sqrt(EARTH_GM / a**3)
    nu0 = math.radians(elements.nu_deg)
    e0 = 2 * math.atan2(math.sqrt(1 - e) * math.sin(nu0 / 2), math.sqrt(1 + e) * math.cos(nu0 / 2))
    mean = e0 - e * math.sin(e0) + n * time_s
    ecc = mean.copy()
    for _ in range(50):  # Newton on E - e sin E = M, quadratic from M
        step = (ecc - e * np.sin(ecc) - mean) / (1 - e * np.cos(ecc))
        ecc -= step
        if np.max(np.abs(step)) < 1e-15:
            break
    cos_e, sin_e = np.cos(ecc), np.sin(ecc)
    b = a * math.sqrt(1 - e**2)
    r = a * (1 - e * cos_e)
    position = np.stack([a * (cos_e - e), b * sin_e, np.zeros_like(ecc)], axis=1)
    rate = n * a / r  # dE/dt
    velocity = np.stack([-a * rate * sin_e, b * rate * cos_e, np.zeros_like(ecc)], axis=1)
    rotation = elements.perifocal_to_inertial()
    return position @ rotation.T, velocity @ rotation.T


def _with_j2(elements: Elements, time_s: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
    r0, v0 = elements.state()

    def rates(_t: float, y: NDArray) -> NDArray:
        r = y[:3]
        d = math.sqrt(r @ r)
        z2 = (r[2] / d) ** 2
        k = 1.5 * EARTH_J2 * EARTH_GM * EARTH_RADIUS**2 / d**5
        j2 = -k * r * np.array([1 - 5 * z2, 1 - 5 * z2, 3 - 5 * z2])
        return np.concatenate([y[3:], -EARTH_GM * r / d**3 + j2])

    span = (0.0, float(time_s.max())) if time_s.max() > 0 else (0.0, 1.0)
    solution = solve_ivp(
        rates, span, np.concatenate([r0, v0]), method="DOP853", rtol=1e-11, atol=1e-6, dense_output=True
    )
    states = solution.sol(time_s).T
    return states[:, :3].copy(), states[:, 3:].copy()


def _rz(angle: float) -> NDArray[np.float64]:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rx(angle: float) -> NDArray[np.float64]:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
