"""Orbit steps timed on this machine (``sunwind bench --orbit``): a 500 km Sun-synchronous orbit with
the spacecraft nadir pointing, with SRP and drag, each alone, and a GEO orbit with SRP, at the
defaults of ``sunwind orbit``. Each case runs two steps first (compilation, caches), then is timed.
A step is ``srp`` and ``drag`` at that step's inputs, so its error is the single-attitude error that
``sunwind bench`` reports."""

from __future__ import annotations

import platform
import time
from dataclasses import asdict, dataclass

import numpy as np

from sunwind.forces.model import Model
from sunwind.forces.orbit.attitude import AttitudeLaw
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.flight import fly
from sunwind.forces.orbit.steps import OrbitLoads
from sunwind.forces.orbit.trajectory import Elements, propagate
from sunwind.forces.tables.jobs import GasOptions, SrpSetup
from sunwind.geometry.parallel import CORES

#: The timed cases: name -> (elements, step [s], SRP, drag).
CASES = {
    "LEO SRP + drag": (Elements.circular(500.0, 97.4, 30.0), 60.0, True, True),
    "LEO SRP": (Elements.circular(500.0, 97.4, 30.0), 60.0, True, False),
    "LEO drag": (Elements.circular(500.0, 97.4, 30.0), 60.0, False, True),
    "GEO SRP": (Elements(42164.17e3, 0.0, 0.05, 75.0, 0.0, 0.0), 600.0, True, False),
}
EPOCH = "2024-06-21T00:00:00Z"


@dataclass(frozen=True)
class OrbitBenchReport:
    """Milliseconds per step of each case (:data:`CASES`), the steps timed, and the machine.

    Attributes
    ----------
    triangles : int
        Facets of the model timed.
    steps : int
        Steps timed per case (after two untimed ones).
    ms_per_step : dict of str to float
        Case name -> wall time per step [ms].
    machine : str
        Processor and core count.

    Examples
    --------
    >>> from sunwind.forces.orbit.bench import OrbitBenchReport
    >>> report = OrbitBenchReport(12, 2, {"LEO SRP": 3.5}, "x86_64, 2 cores")
    >>> report.to_json()["ms_per_step"]
    {'LEO SRP': 3.5}
    """

    triangles: int
    steps: int
    ms_per_step: dict[str, float]
    machine: str

    def to_json(self) -> dict:
        """The report as a JSON-ready dict, its keys the fields'.

        Returns
        -------
        dict
            ``triangles``, ``steps``, ``ms_per_step`` and ``machine``.
        """
        return asdict(self)


def orbit_benchmark(model: Model, steps: int = 40) -> OrbitBenchReport:
    """Time ``steps`` steps of every case on ``model``.

    Each case (:data:`CASES`: a Sun-synchronous orbit at 500 km with SRP and drag together and alone, a
    GEO orbit with SRP) flies two steps first, untimed (compilation, caches), then ``steps`` steps nadir
    pointing at the defaults of ``sunwind orbit``.

    Parameters
    ----------
    model : Model
        The spacecraft.
    steps : int
        Steps timed per case.

    Returns
    -------
    OrbitBenchReport
        Milliseconds per step of every case.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.bench import orbit_benchmark
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> report = orbit_benchmark(cube, steps=2)
    >>> report.triangles, list(report.ms_per_step)
    (12, ['LEO SRP + drag', 'LEO SRP', 'LEO drag', 'GEO SRP'])
    """
    epoch, nadir = Epoch.of(EPOCH), AttitudeLaw.parse("nadir")
    timings = {}
    for name, (elements, step, with_srp, with_drag) in CASES.items():
        loads = OrbitLoads(SrpSetup() if with_srp else None, GasOptions() if with_drag else None)
        fly(model, propagate(elements, epoch, np.array([0.0, step]), "kepler"), nadir, loads)
        path = propagate(elements, epoch, np.arange(steps) * step, "kepler")
        start = time.perf_counter()
        fly(model, path, nadir, loads)
        timings[name] = 1e3 * (time.perf_counter() - start) / steps
    machine = f"{platform.processor() or platform.machine()}, {CORES} cores"
    return OrbitBenchReport(model.craft.n_facets, steps, timings, machine)
