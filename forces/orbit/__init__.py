"""Orbit mode: the loads along an orbit and an attitude history, with eclipse, and the momentum they
build (METHOD.md "Orbit mode").

Modules, each importing only those before it: :mod:`.clock` (epoch and time scales), :mod:`.sun`
(ERFA's ephemeris), :mod:`.eclipse`, :mod:`.trajectory` (Keplerian elements, two-body and J2),
:mod:`.tle` (SGP4), :mod:`.ephemeris_csv`, :mod:`.attitude` (laws and quaternion files),
:mod:`.steps` (one step as a sweep job), :mod:`.results` (series, summary, files) and :mod:`.flight`
(:func:`fly`).

>>> from sunwind.forces import load
>>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, fly, propagate
>>> model = load("meshes/data/sample_spacecraft.usda")  # doctest: +SKIP
>>> path = propagate(Elements.circular(500, 51.6), Epoch.of("2024-03-20T00:00:00Z"), times, "kepler")
>>> fly(model, path, AttitudeLaw.parse("nadir"), Loads(srp=SrpSetup())).summary()  # doctest: +SKIP
"""

from sunwind.forces.orbit.attitude import AttitudeLaw
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.eclipse import ECLIPSE_MODELS, solar_fraction
from sunwind.forces.orbit.ephemeris_csv import ephemeris_trajectory
from sunwind.forces.orbit.flight import fly
from sunwind.forces.orbit.results import SERIES, OrbitResult
from sunwind.forces.orbit.steps import Loads, SpaceWeather
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.orbit.tle import tle_epoch, tle_trajectory
from sunwind.forces.orbit.trajectory import Elements, Trajectory, propagate

__all__ = [
    "AU_M",
    "ECLIPSE_MODELS",
    "SERIES",
    "AttitudeLaw",
    "Elements",
    "Epoch",
    "Loads",
    "OrbitResult",
    "SpaceWeather",
    "Trajectory",
    "ephemeris_trajectory",
    "fly",
    "propagate",
    "solar_fraction",
    "sun_position",
    "tle_epoch",
    "tle_trajectory",
]
