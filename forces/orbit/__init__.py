"""Orbit mode: the loads along an orbit and an attitude history, with eclipse, and the momentum they
build (METHOD.md "Orbit mode").

Modules, each importing only those before it: :mod:`.clock` (epoch and time scales), :mod:`.sun`
(ERFA's ephemeris), :mod:`.eclipse`, :mod:`.trajectory` (Keplerian elements, two-body and J2),
:mod:`.tle` (SGP4), :mod:`.ephemeris_csv`, :mod:`.attitude` (laws and quaternion files), :mod:`.inputs`
(each step's inputs), :mod:`.steps` (what the steps compute, as a sweep job), :mod:`.results` (series,
summary, files) and :mod:`.flight` (:func:`fly`).

Examples
--------
Two minutes of a 700 km Sun-synchronous orbit, nadir pointing, SRP and drag on a small box-wing:

>>> import numpy as np
>>> from sunwind.forces import load
>>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
>>> from sunwind.forces.tables.jobs import GasOptions, SrpSetup
>>> from sunwind.geometry.materials import Material
>>> from sunwind.meshes import box_wing
>>> model = load(box_wing(facet_size=0.5), uniform=Material("paint", 0.4, 0.5, 0.1), two_sided=["wing*"])
>>> times = np.arange(3) * 60.0
>>> path = propagate(Elements.circular(700, 98.2), Epoch.of("2024-03-20T00:00:00Z"), times, "kepler")
>>> loads = OrbitLoads(SrpSetup(reflections="none"), GasOptions(reflections="none"))
>>> result = fly(model, path, AttitudeLaw.parse("nadir"), loads)
>>> result.terms, result.summary()["steps"]
(('srp', 'drag'), 3)
>>> result.to_dataset()["force_body_N"].dims
('time', 'component')
"""

from sunwind.forces.orbit.attitude import AttitudeLaw
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.orbit.eclipse import ECLIPSE_MODELS, solar_fraction
from sunwind.forces.orbit.ephemeris_csv import ephemeris_trajectory
from sunwind.forces.orbit.flight import fly
from sunwind.forces.orbit.inputs import StepInputs
from sunwind.forces.orbit.results import SERIES, OrbitResult
from sunwind.forces.orbit.steps import OrbitLoads, SpaceWeather
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.orbit.tle import tle_epoch, tle_trajectory
from sunwind.forces.orbit.trajectory import Elements, Trajectory, propagate

__all__ = [
    "AU_M",
    "ECLIPSE_MODELS",
    "SERIES",
    "AttitudeLaw",
    "EarthTerms",
    "Elements",
    "Epoch",
    "OrbitLoads",
    "OrbitResult",
    "SpaceWeather",
    "StepInputs",
    "Trajectory",
    "ephemeris_trajectory",
    "fly",
    "propagate",
    "solar_fraction",
    "sun_position",
    "tle_epoch",
    "tle_trajectory",
]
