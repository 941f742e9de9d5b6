"""The Earth's albedo and infrared timed on this machine (``sunwind bench --earth``): the directional
visibility's build, time and memory, the time per attitude against SRP with the same reflections, and
the error against the converged cap integral (a shadow pass per 2.5 deg cell), at seeded places 500 km up:
a third with the Sun anywhere, a third near the terminator and a third just out of eclipse."""

from __future__ import annotations

import math
import platform
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np

from sunwind.forces.bench import LoadError
from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.model import Model
from sunwind.forces.planet.shadow import sun_behind
from sunwind.forces.planet.visibility import level_for, visibility
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.srp import srp
from sunwind.geometry.parallel import CORES
from sunwind.geometry.rays.sampling import ShadowSampling

#: Height of the places [km] and the Earth's radius [m].
ALTITUDE_KM = 500.0
_EARTH_M = 6_378_137.0
#: The converged reference: cells of this size [deg].
REFERENCE_STEP_DEG = 2.5


def bench_places(count: int, seed: int = 35) -> list[Place]:
    """Seeded places 500 km up: the Sun anywhere, within 8 deg of the terminator, or 0.3 deg about the
    limb behind the Earth (eclipse exit, the conical shadow's visible share), in turn.

    Parameters
    ----------
    count : int
        Places.
    seed : int
        Seed of the generator.

    Returns
    -------
    list of Place

    Examples
    --------
    >>> [round(p.solar_fraction, 2) for p in bench_places(3)]
    [0.0, 1.0, 0.27]
    """
    rng = np.random.default_rng(seed)
    half_angle = math.degrees(math.asin(_EARTH_M / (_EARTH_M + ALTITUDE_KM * 1e3)))
    out = []
    for k in range(count):
        nadir = _unit(rng.normal(size=3))
        across = _unit(np.cross(nadir, rng.normal(size=3)))
        if k % 3 == 0:
            sun = _unit(rng.normal(size=3))
        else:
            angle = math.radians(
                90.0 + rng.uniform(-8, 8) if k % 3 == 1 else half_angle + rng.uniform(-0.3, 0.3)
            )
            sun = math.cos(angle) * nadir + math.sin(angle) * across
        fraction = sun_behind(nadir, ALTITUDE_KM, sun, _EARTH_M, "conical")
        out.append(Place(nadir, ALTITUDE_KM, sun, solar_fraction=fraction))
    return out


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


@dataclass(frozen=True)
class EarthBenchReport:
    """The Earth terms' figures on one model.

    Attributes
    ----------
    triangles, sides : int
        The model's facets and sides.
    places : int
        Places timed (and compared).
    grid_nodes : int
        Directions of the visibility (the default ``cell_deg``).
    build_s : float
        Building the visibility (shadow passes and beam chains along every node), or reading it [s].
    visibility_origin : str
        "computed", or the disk entry it was read from.
    visibility_MB : float
        Its arrays [MB].
    earth_ms, srp_ms : float
        Median time per attitude of ``planet_radiation`` (albedo and infrared, full reflections) and of
        ``srp`` (full reflections) at the places' Suns [ms].
    earth_over_srp : float
        Their ratio.
    error : LoadError or None
        Force and torque errors against the cells at :data:`REFERENCE_STEP_DEG` (None: not compared).
    torque_scaled_worst : float or None
        Worst torque error over ``max(|M|, 0.01 |F| L)`` (``L`` the model's diagonal).
    estimate_over_error : tuple of float or None
        Smallest and largest ratio of the reported force error estimate to the force error.
    reference_ms : float or None
        Median time per attitude of the reference [ms].
    machine : str
        Processor and cores.

    Examples
    --------
    >>> report = EarthBenchReport(12, 12, 1, 642, 0.1, "computed", 0.0, 2.0, 1.0, 2.0, None, None, None,
    ...                           None, "x86")
    >>> report.to_json()["earth_over_srp"]
    2.0
    """

    triangles: int
    sides: int
    places: int
    grid_nodes: int
    build_s: float
    visibility_origin: str
    visibility_MB: float
    earth_ms: float
    srp_ms: float
    earth_over_srp: float
    error: LoadError | None
    torque_scaled_worst: float | None
    estimate_over_error: tuple[float, float] | None
    reference_ms: float | None
    machine: str

    def to_json(self) -> dict:
        """The report as a JSON-ready dict, its keys the fields'.

        Returns
        -------
        dict
            The fields; ``error`` as a dict of its own.
        """
        return asdict(self)


def earth_benchmark(
    model: Model,
    places: int = 20,
    compare: bool = True,
    progress: Callable[[str, int, int], None] | None = None,
) -> EarthBenchReport:
    """Time the Earth terms on ``model`` at :func:`bench_places`, with their error.

    Parameters
    ----------
    model : Model
        The spacecraft (its materials need emissivities).
    places : int
        Places timed.
    compare : bool
        Also compute the reference (cells of :data:`REFERENCE_STEP_DEG`, about 200 shadow passes per
        place) and report the errors.
    progress : callable, optional
        ``progress(stage, done, total)``.

    Returns
    -------
    EarthBenchReport

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.5, emissivity=0.8)
    >>> report = earth_benchmark(sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=grey, threads=1), 2,
    ...                          compare=False)
    >>> report.grid_nodes, report.error is None
    (642, True)
    """
    settings = ReflectionSettings("full")
    start = time.perf_counter()
    seen = visibility(model.craft, level_for(10.0), ShadowSampling(), settings, beams=True)
    build = time.perf_counter() - start
    at = bench_places(places)
    planet_radiation(model, at[0], reflections=settings)  # the view factors, exchanges and kernels
    srp(model, at[0].sun_vector, reflections=settings)
    timed = [_timed(lambda p: planet_radiation(model, p, reflections=settings), at, "earth", progress)]
    timed.append(_timed(lambda p: srp(model, p.sun_vector, reflections=settings), at, "srp", progress))
    (results, earth_times), (_, srp_times) = timed
    error = scaled = ratio = reference_ms = None
    if compare:
        reference, reference_times = _timed(
            lambda p: planet_radiation(
                model, p, reflections=settings, cap=CapSampling(REFERENCE_STEP_DEG, "cells")
            ),
            at,
            "reference",
            progress,
        )
        loads = [(r.force_N, r.torque_Nm) for r in results]
        exact = [(r.force_N, r.torque_Nm) for r in reference]
        error = LoadError.of(loads, exact, model.craft.diagonal_m)
        scaled = max(
            np.linalg.norm(a.torque_Nm - b.torque_Nm)
            / max(np.linalg.norm(b.torque_Nm), 0.01 * np.linalg.norm(b.force_N) * model.craft.diagonal_m)
            for a, b in zip(results, reference, strict=True)
        )
        differences = [np.linalg.norm(a.force_N - b.force_N) for a, b in zip(results, reference, strict=True)]
        ratios = [r.shadow_error.force_N / d for r, d in zip(results, differences, strict=True) if d > 0]
        ratio = (float(min(ratios)), float(max(ratios))) if ratios else None
        reference_ms = 1e3 * float(np.median(reference_times))
    earth_ms, srp_ms = 1e3 * float(np.median(earth_times)), 1e3 * float(np.median(srp_times))
    return EarthBenchReport(
        triangles=model.craft.n_facets,
        sides=model.craft.n_sides,
        places=places,
        grid_nodes=len(seen.grid.nodes),
        build_s=build,
        visibility_origin=seen.origin,
        visibility_MB=seen.nbytes / 1e6,
        earth_ms=earth_ms,
        srp_ms=srp_ms,
        earth_over_srp=earth_ms / srp_ms,
        error=error,
        torque_scaled_worst=None if scaled is None else float(scaled),
        estimate_over_error=ratio,
        reference_ms=reference_ms,
        machine=f"{platform.processor() or platform.machine()}, {CORES} cores",
    )


def _timed(call: Callable, places: list[Place], stage: str, progress) -> tuple[list, list[float]]:
    """``call`` at every place: the results and the wall time of each [s]."""
    results, times = [], []
    for k, place in enumerate(places):
        start = time.perf_counter()
        results.append(call(place))
        times.append(time.perf_counter() - start)
        if progress:
            progress(stage, k + 1, len(places))
    return results, times
