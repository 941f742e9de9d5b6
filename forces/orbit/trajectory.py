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

    Made by :func:`propagate`, :func:`~sunwind.forces.orbit.tle.tle_trajectory` or
    :func:`~sunwind.forces.orbit.ephemeris_csv.ephemeris_trajectory`, and flown by
    :func:`~sunwind.forces.orbit.flight.fly`.

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

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
    >>> path.position_m.shape, path.altitude_km.round(3).tolist()
    ((2, 3), [700.0, 700.0])
    >>> round(path.period_s / 60, 2)  # minutes
    98.77
    >>> path.source
    'kepler: a = 7078.137 km, e = 0, i = 98.2 deg, RAAN = 0 deg, argp = 0 deg, nu = 0 deg'
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
    """A trajectory that runs but may not be what was meant (stale elements).

    The command line warns with it when a run lies far from a TLE's epoch; a script can make it an error.

    Examples
    --------
    >>> import warnings
    >>> from sunwind.forces.orbit.trajectory import TrajectoryWarning
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("error", TrajectoryWarning)
    ...     try:
    ...         warnings.warn("elements 400 days old", TrajectoryWarning)
    ...     except TrajectoryWarning as warning:
    ...         print(warning)
    elements 400 days old
    """


@dataclass(frozen=True)
class Elements:
    """Keplerian elements of an orbit about the Earth: a size in metres, angles in degrees.

    The elements are checked when made: a closed orbit (0 <= e < 1), its perigee above the Earth's
    equatorial radius and its semi-major axis inside the Earth's sphere of influence.

    Parameters
    ----------
    a_m : float
        Semi-major axis [m], from the Earth's centre.
    e : float
        Eccentricity, 0 <= e < 1.
    i_deg : float
        Inclination [deg], 0 to 180.
    raan_deg : float
        Right ascension of the ascending node [deg], within [-360, 360].
    argp_deg : float
        Argument of perigee [deg], within [-360, 360].
    nu_deg : float
        True anomaly [deg], within [-360, 360].

    Raises
    ------
    InputError
        A non-finite value, an open orbit, an angle out of range, a semi-major axis beyond
        ``MOST_SEMI_MAJOR_AXIS_M`` or a perigee inside the Earth.

    Examples
    --------
    >>> import sunwind as sw
    >>> orbit = sw.orbit.Elements(7000e3, 0.001, 51.6, 10.0, 20.0, 30.0)
    >>> round(orbit.period_s, 1)
    5828.5
    >>> sw.orbit.Elements(7000.0, 0.0, 51.6, 0.0, 0.0, 0.0)  # km given where metres are wanted
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: the perigee radius 7.0 km is inside the Earth (6378.137 km)...
    """

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
        """A circular orbit at ``altitude_km`` above 6378.137 km.

        Parameters
        ----------
        altitude_km : float
            Height above the Earth's equatorial radius [km], positive.
        inclination_deg : float
            Inclination [deg], 0 to 180.
        raan_deg : float
            Right ascension of the ascending node [deg].
        arg_latitude_deg : float
            Argument of latitude at the epoch [deg], from the ascending node (the true anomaly, with the
            argument of perigee zero).

        Returns
        -------
        Elements
            The elements, eccentricity zero.

        Raises
        ------
        InputError
            A non-positive or non-finite altitude, or an angle out of range.

        Examples
        --------
        >>> from sunwind.forces.orbit.trajectory import Elements
        >>> Elements.circular(500, 97.4, raan_deg=30.0)
        Elements(a_m=6878137.0, e=0.0, i_deg=97.4, raan_deg=30.0, argp_deg=0.0, nu_deg=0.0)
        """
        if not (math.isfinite(altitude_km) and altitude_km > 0):
            raise InputError(f"altitude {altitude_km} km must be a positive number", parameters=("altitude",))
        return cls(EARTH_RADIUS + altitude_km * 1e3, 0.0, inclination_deg, raan_deg, 0.0, arg_latitude_deg)

    @property
    def period_s(self) -> float:
        """Two-body period [s]: ``2 pi sqrt(a^3 / GM)``."""
        return 2 * math.pi * math.sqrt(self.a_m**3 / EARTH_GM)

    def state(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Position [m] and velocity [m/s], GCRF, at the elements' true anomaly.

        Returns
        -------
        position : ndarray of float64, shape (3,)
            Position [m].
        velocity : ndarray of float64, shape (3,)
            Velocity [m/s].

        References
        ----------
        .. [1] Vallado, D. A. (2013). *Fundamentals of Astrodynamics and Applications*, 4th ed., ch. 2
           (the COE2RV algorithm: state in the perifocal frame, then rotated). Microcosm Press.

        Examples
        --------
        >>> from sunwind.forces.orbit.trajectory import Elements
        >>> position, velocity = Elements.circular(700, 90.0).state()
        >>> position.round(1).tolist(), velocity.round(1).tolist()
        ([7078137.0, 0.0, 0.0], [0.0, 0.0, 7504.3])
        """
        p = self.a_m * (1 - self.e**2)
        nu = math.radians(self.nu_deg)
        r = p / (1 + self.e * math.cos(nu))
        position = np.array([r * math.cos(nu), r * math.sin(nu), 0.0])
        scale = math.sqrt(EARTH_GM / p)
        velocity = np.array([-scale * math.sin(nu), scale * (self.e + math.cos(nu)), 0.0])
        rotation = self.perifocal_to_inertial()
        return rotation @ position, rotation @ velocity

    def perifocal_to_inertial(self) -> NDArray[np.float64]:
        """The rotation from the perifocal frame (x to perigee, z along the orbit normal) to GCRF.

        Returns
        -------
        ndarray of float64, shape (3, 3)
            ``R3(-RAAN) R1(-i) R3(-argp)``: a perifocal vector ``v`` becomes ``matrix @ v`` in GCRF.

        References
        ----------
        .. [1] Vallado, D. A. (2013). *Fundamentals of Astrodynamics and Applications*, 4th ed., ch. 2
           (the COE2RV algorithm). Microcosm Press.

        Examples
        --------
        >>> from sunwind.forces.orbit.trajectory import Elements
        >>> Elements.circular(700, 90.0, raan_deg=90.0).perifocal_to_inertial().round(6) + 0.0
        array([[0., 0., 1.],
               [1., 0., 0.],
               [0., 1., 0.]])
        """
        raan, i, argp = (math.radians(v) for v in (self.raan_deg, self.i_deg, self.argp_deg))
        return _rz(raan) @ _rx(i) @ _rz(argp)


def propagate(elements: Elements, epoch: Epoch, time_s: NDArray[np.float64], propagator: str) -> Trajectory:
    """The states at ``time_s`` [s] after ``epoch``, the elements being those at the epoch.

    Parameters
    ----------
    elements : Elements
        Osculating elements at the epoch.
    epoch : Epoch
        Time zero.
    time_s : array_like of float, shape (n,)
        Seconds after the epoch.
    propagator : {"kepler", "j2"}
        ``"kepler"`` solves Kepler's equation at every step; ``"j2"`` integrates two-body motion with the
        Earth's J2 (SciPy's DOP853, relative tolerance 1e-11).

    Returns
    -------
    Trajectory
        Positions and velocities in GCRF, and a ``source`` line naming the elements.

    Raises
    ------
    InputError
        ``propagator`` is not one of ``PROPAGATORS``.

    References
    ----------
    .. [1] Vallado, D. A. (2013). *Fundamentals of Astrodynamics and Applications*, 4th ed. Microcosm
       Press: Kepler's equation (ch. 2) and the J2 acceleration (ch. 8).
    .. [2] Hairer, E., Nørsett, S. P., Wanner, G. (1993). *Solving Ordinary Differential Equations I:
       Nonstiff Problems*, 2nd ed. Springer (DOP853).

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> elements = sw.orbit.Elements.circular(700, 98.2)
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> kepler = sw.orbit.propagate(elements, epoch, np.arange(3) * 60.0, "kepler")
    >>> j2 = sw.orbit.propagate(elements, epoch, np.arange(3) * 60.0, "j2")
    >>> kepler.altitude_km.round(3), j2.altitude_km.round(3)
    (array([700., 700., 700.]), array([700.   , 699.981, 699.925]))
    """
    if propagator not in PROPAGATORS:
        raise InputError(
            f"propagator {propagator!r} is not one of {', '.join(PROPAGATORS)}", parameters=("propagator",)
        )
    time_s = np.atleast_1d(np.asarray(time_s, dtype=float))
    if time_s.ndim != 1 or len(time_s) == 0 or not np.isfinite(time_s).all():
        raise InputError(
            "time_s must be a non-empty list of finite times [s] after the epoch",
            hint="e.g. numpy.arange(0.0, 5400.0, 60.0)",
            parameters=("time_s",),
        )
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

    states = np.empty((len(time_s), 6))
    for side in (time_s >= 0.0, time_s < 0.0):  # forward from the epoch, and backward before it
        if not side.any():
            continue
        end = float(time_s[side].max() if time_s[side][0] >= 0.0 else time_s[side].min())
        span = (0.0, end if end != 0.0 else 1.0)
        solution = solve_ivp(
            rates, span, np.concatenate([r0, v0]), method="DOP853", rtol=1e-11, atol=1e-6, dense_output=True
        )
        states[side] = solution.sol(time_s[side]).T
    return states[:, :3].copy(), states[:, 3:].copy()


def _rz(angle: float) -> NDArray[np.float64]:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _rx(angle: float) -> NDArray[np.float64]:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
