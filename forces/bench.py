"""Benchmark of SRP and drag on the sample spacecraft: time per attitude, ray rate, raw Embree time,
the cost of inter-reflection (view-factor precompute once, then time per attitude with full
reflections), and free-molecular drag per attitude against SRP with the same reflection setting.

The default shadow pass and a fixed number of points per side (``samples``, 1 by default) are timed
in the same run, attitude by attitude. Every time comes with the error of its setting: force and torque
of each timed attitude against a reference on the same attitude and reflection mode, the default pass
at a tolerance ten times tighter than the default (:data:`REFERENCE_TOLERANCE`), as
:class:`LoadError` (worst and median).

The raw figure casts exactly the rays a fixed-sampling attitude casts (same origins, directions,
threads) with nothing else, so ``overhead = time per attitude / raw Embree time`` is what sunwind adds
around Embree.
"""

from __future__ import annotations

import os
import platform
import resource
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np

from sunwind.forces.drag import drag
from sunwind.forces.gas import circular_speed, nrlmsis
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.gas.visible import model_sky
from sunwind.forces.reflection import ReflectionSettings, model_view_factors
from sunwind.forces.reflection.diffuse import diffuse_exchange
from sunwind.forces.srp import srp
from sunwind.geometry import memory
from sunwind.geometry.parallel import thread_count
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, level_for_samples, side_sampler
from sunwind.geometry.spacecraft import Spacecraft

#: Shadow tolerance of the references the timed settings are measured against: ten times the default's.
REFERENCE_TOLERANCE = DEFAULT_TOLERANCE / 10
#: Drag's reference also samples the open-sky integral and the chains more finely: four times the sky
#: rays per side and sixteen times the core rays and chain molecules per attitude of the default.
REFERENCE_GAS_FACTORS = (4, 16, 16)
#: A result's loads: force [N] and torque [N m], body frame.
Loads = tuple[np.ndarray, np.ndarray]
#: What the benchmark reports on while it runs: (stage, attitudes done, attitudes in the stage).
BenchProgress = Callable[[str, int, int], None]


@dataclass(frozen=True)
class LoadError:
    """Error of a timed setting over its attitudes against the reference of each attitude, worst and median.

    All relative [-]: ``|F - F_ref| / |F_ref|``, ``|M - M_ref| / |M_ref|``, and the torque's on the scale
    of a torque the force could give, ``|M - M_ref| / (|F_ref| L)`` with ``L`` the model's size
    (:attr:`~sunwind.geometry.spacecraft.Spacecraft.diagonal_m`, the diagonal of its box), which stays
    meaningful where the torque is small.

    Attributes
    ----------
    force_worst, force_median : float
        Relative force error, worst and median over the attitudes [-].
    torque_worst, torque_median : float
        Relative torque error, worst and median [-].
    torque_of_force_worst : float
        Worst torque error over ``|F_ref| L`` [-].

    Examples
    --------
    >>> import numpy as np
    >>> exact = [(np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]))]
    >>> close = [(np.array([1.001, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]))]
    >>> error = LoadError.of(close, exact, size_m=1.0)
    >>> round(error.force_worst, 6), error.torque_worst
    (0.001, 0.0)
    """

    force_worst: float
    force_median: float
    torque_worst: float
    torque_median: float
    torque_of_force_worst: float

    @classmethod
    def of(cls, loads: list[Loads], references: list[Loads], size_m: float) -> LoadError:
        """The errors of ``loads`` against the first ``len(loads)`` ``references``, attitude by attitude,
        on a model of size ``size_m`` [m].

        Parameters
        ----------
        loads : list of (force, torque)
            Force [N] and torque [N m], each (3,), of the timed setting at each attitude.
        references : list of (force, torque)
            The reference's loads at the same attitudes (at least as many).
        size_m : float
            The model's size ``L`` [m].

        Returns
        -------
        LoadError
            Worst and median errors.
        """
        got, exact = np.array(loads), np.array(references[: len(loads)])  # (n, 2 loads, 3)
        difference, scale = np.linalg.norm(got - exact, axis=2), np.linalg.norm(exact, axis=2)
        error = difference / scale
        worst, median = error.max(axis=0), np.median(error, axis=0)
        of_force = float(np.max(difference[:, 1] / (scale[:, 0] * size_m)))
        return cls(float(worst[0]), float(median[0]), float(worst[1]), float(median[1]), of_force)

    def __str__(self) -> str:
        return (
            f"error force {self.force_worst:.1e} worst, {self.force_median:.1e} median; "
            f"torque {self.torque_worst:.1e} worst, {self.torque_median:.1e} median, "
            f"{self.torque_of_force_worst:.1e} of |F| L worst"
        )


def _loads(result) -> Loads:
    return result.force_N, result.torque_Nm


def _references(
    evaluate: Callable[[np.ndarray], object], directions: np.ndarray, stage: str, progress
) -> list:
    """Loads of ``evaluate(u)`` (a reference setting) at every direction, reporting ``stage``."""
    out = []
    for k, u in enumerate(directions):
        out.append(_loads(evaluate(u)))
        if progress:
            progress(stage, k + 1, len(directions))
    return out


@dataclass(frozen=True)
class BenchReport:
    """Benchmark figures; times in seconds unless the name says ms.

    ``default_*``: the default shadow pass (no ``samples``); ``fixed_*``: ``samples_per_side`` fixed
    points per side, timed beside it; ``full_*``: with full reflections; ``drag_*``: free-molecular drag.

    Attributes
    ----------
    triangles, sides, attitudes, samples_per_side, threads : int
        The model's size and the run's settings.
    load_s, scene_build_s, first_call_s : float
        Time to load the model, build its ray scene and make the first call [s].
    default_ms, default_median_ms, fixed_ms, fixed_median_ms : float
        Mean and median time per attitude of direct SRP [ms].
    default_rays_per_attitude, fixed_rays_per_attitude : float
        Rays cast per attitude.
    default_error, fixed_error : LoadError
        Their errors against the reference.
    default_over_fixed, default_batch_ms, fixed_batch_ms, batch_default_over_fixed : float
        Ratio of the two and the same as a batch of attitudes.
    batch_identical : bool
        Whether the batch gives the same loads as the attitudes one by one.
    fixed_rays_per_s, raw_embree_ms, raw_embree_rays_per_s, overhead : float
        Ray rate, the same rays cast by Embree alone, and the ratio of the two times.
    view_factor_s, view_factor_MB, view_factor_peak_MB, exchange_setup_s : float
        Cost of the view-factor precompute [s, MB] and of setting up the exchange [s].
    view_factor_rays_per_side : int
        Rays per side of the precompute.
    full_ms, full_median_ms, full_over_direct, beam_rays_per_attitude : float
        SRP with full reflections per attitude [ms], its ratio to direct, beam rays per attitude.
    full_error : LoadError
        Its error.
    fixed_full_ms : float
        The same with fixed points per side [ms].
    fixed_full_error : LoadError
        Its error.
    drag_ms, drag_over_srp, fixed_drag_ms, drag_full_ms, drag_full_over_srp_full : float
        Drag per attitude [ms] and its ratio to SRP, without and with exchange.
    drag_error, fixed_drag_error, drag_full_error : LoadError
        Their errors.
    drag_atmosphere : str
        The atmosphere drag was timed in.
    sky_s, sky_MB : float
        Cost of the open-sky precompute [s, MB].
    sky_rays_per_side : int
        Its rays per side.
    peak_memory_MB : float
        Peak resident memory of the process [MB].
    machine : str
        Architecture, cores and Python version.

    Examples
    --------
    A cube and two attitudes (a few seconds, mostly the first call of each solver):

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> report = benchmark(cube.craft, attitudes=2)
    >>> report.triangles, report.attitudes, report.batch_identical
    (12, 2, True)
    """

    triangles: int
    sides: int
    attitudes: int
    samples_per_side: int
    threads: int
    load_s: float
    scene_build_s: float
    first_call_s: float
    default_ms: float
    default_median_ms: float
    default_rays_per_attitude: float
    default_error: LoadError
    fixed_ms: float
    fixed_median_ms: float
    fixed_rays_per_attitude: float
    fixed_error: LoadError
    default_over_fixed: float
    default_batch_ms: float
    fixed_batch_ms: float
    batch_default_over_fixed: float
    batch_identical: bool
    fixed_rays_per_s: float
    raw_embree_ms: float
    raw_embree_rays_per_s: float
    overhead: float
    view_factor_s: float
    view_factor_rays_per_side: int
    view_factor_MB: float
    view_factor_peak_MB: float
    exchange_setup_s: float
    full_ms: float
    full_median_ms: float
    full_over_direct: float
    full_error: LoadError
    beam_rays_per_attitude: float
    fixed_full_ms: float
    fixed_full_error: LoadError
    drag_ms: float
    drag_over_srp: float
    drag_error: LoadError
    fixed_drag_ms: float
    fixed_drag_error: LoadError
    drag_full_ms: float
    drag_full_over_srp_full: float
    drag_full_error: LoadError
    drag_atmosphere: str
    sky_s: float
    sky_rays_per_side: int
    sky_MB: float
    peak_memory_MB: float
    machine: str

    def to_json(self) -> dict:
        """Return the report as a JSON-ready dict (the errors as nested dicts).

        Returns
        -------
        dict
            Every field by name.
        """
        return asdict(self)


def _peak_MB() -> float:
    """Peak resident memory of this process so far [MB]."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _timed(
    evaluate: Callable[[np.ndarray, int | None], object], directions: np.ndarray, samples: int | None
) -> dict:
    """Time ``evaluate(u, samples)`` of the default (``samples`` None) and of ``samples`` fixed points
    (none when ``samples`` is None) at every direction, alternating which goes first, after one call
    of each that compiles and keeps what they need. Returns the times [s], loads, shadow rays and beam
    rays (0 without reflections) of each, keyed by "default" and "fixed"."""
    keys = ("default",) if samples is None else ("default", "fixed")
    for key in keys:
        evaluate(directions[0], None if key == "default" else samples)
    out: dict = {key: {"times": [], "loads": [], "rays": [], "beam_rays": []} for key in keys}
    for k, u in enumerate(directions):
        for key in keys[:: 1 if k % 2 == 0 else -1]:
            start = time.perf_counter()
            result = evaluate(u, None if key == "default" else samples)
            out[key]["times"].append(time.perf_counter() - start)
            out[key]["loads"].append(_loads(result))
            out[key]["rays"].append(result.rays)
            chains = getattr(getattr(result, "reflected", None), "chains", None)  # SRP's beam chains
            out[key]["beam_rays"].append(0 if chains is None else chains.rays)
    return out


def _reflection_figures(
    craft: Spacecraft, directions: np.ndarray, samples: int, direct: dict, progress: BenchProgress | None
) -> tuple[dict, list[float]]:
    """View-factor precompute (never from the disk cache), the diffuse balance's one-off solves, and
    time per attitude with full reflections at the default and with ``samples`` points, each with its
    error; and the default's times [s]. ``direct``: the direct-only timings of :func:`_timed`."""
    settings = ReflectionSettings("full", cache_dir=False)
    start = time.perf_counter()
    view = model_view_factors(craft, settings)
    view_s = time.perf_counter() - start
    view_peak = _peak_MB()
    start = time.perf_counter()
    _ = diffuse_exchange(craft, settings).responses
    setup_s = time.perf_counter() - start
    timed = _timed(
        lambda u, n: srp(craft, u, sampling=ShadowSampling(samples=n), reflections=settings),
        directions,
        samples,
    )
    references = _references(
        lambda u: srp(craft, u, sampling=ShadowSampling(tolerance=REFERENCE_TOLERANCE), reflections=settings),
        directions,
        "reference, full reflections",
        progress,
    )
    full, fixed = timed["default"], timed["fixed"]
    return {
        "view_factor_s": view_s,
        "view_factor_rays_per_side": view.rays_per_side,
        "view_factor_MB": view.nbytes / 1e6,
        "view_factor_peak_MB": view_peak,
        "exchange_setup_s": setup_s,
        "full_ms": 1e3 * float(np.mean(full["times"])),
        "full_median_ms": 1e3 * float(np.median(full["times"])),
        "full_over_direct": float(np.median(full["times"]) / np.median(direct["default"]["times"])),
        "full_error": LoadError.of(full["loads"], references, craft.diagonal_m),
        "beam_rays_per_attitude": float(np.mean(full["beam_rays"])),
        "fixed_full_ms": 1e3 * float(np.mean(fixed["times"])),
        "fixed_full_error": LoadError.of(fixed["loads"], references, craft.diagonal_m),
    }, full["times"]


def _drag_figures(
    craft: Spacecraft,
    directions: np.ndarray,
    samples: int,
    srp_times: list[float],
    srp_full: list[float],
    progress: BenchProgress | None,
) -> dict:
    """Drag per attitude (NRLMSIS at 400 km, circular-orbit speed, ``v_rel`` along each direction of
    the SRP timing) without re-emission exchange at the default and with ``samples`` points, and with
    full exchange at the default, against default SRP with the same reflection setting, each with its
    error against the reference (shadows to :data:`REFERENCE_TOLERANCE`, the gas sampled
    :data:`REFERENCE_GAS_FACTORS` times more finely); and the sky sampling's time (never from the disk
    cache) and size."""
    air = nrlmsis(400.0)
    speed = circular_speed(400.0)
    start = time.perf_counter()
    sky = model_sky(craft, None, False)
    figures: dict = {
        "drag_atmosphere": air.source,
        "sky_s": time.perf_counter() - start,
        "sky_rays_per_side": sky.rays_per_side,
        "sky_MB": sky.nbytes / 1e6,
    }
    finer = reference_gas(GasSampling(sky.rays_per_side))
    for mode, srp_reference, key in (("none", srp_times, "drag"), ("full", srp_full, "drag_full")):
        settings = ReflectionSettings(mode, cache_dir=False)

        def evaluate(u, n, settings=settings):
            return drag(
                craft,
                speed * u,
                air,
                sampling=ShadowSampling(samples=n),
                reflections=settings,
            )

        timed = _timed(evaluate, directions, samples if mode == "none" else None)  # full: the default only
        references = _references(
            lambda u, settings=settings: drag(
                craft,
                speed * u,
                air,
                sampling=ShadowSampling(tolerance=REFERENCE_TOLERANCE),
                reflections=settings,
                gas_sampling=finer,
            ),
            directions,
            f"reference, drag ({mode})",
            progress,
        )
        times = timed["default"]["times"]
        figures[f"{key}_ms"] = 1e3 * float(np.median(times))
        ratio_key = "drag_over_srp" if mode == "none" else "drag_full_over_srp_full"
        figures[ratio_key] = float(np.median(times) / np.median(srp_reference))
        figures[f"{key}_error"] = LoadError.of(timed["default"]["loads"], references, craft.diagonal_m)
        if mode == "none":
            figures["fixed_drag_ms"] = 1e3 * float(np.median(timed["fixed"]["times"]))
            figures["fixed_drag_error"] = LoadError.of(timed["fixed"]["loads"], references, craft.diagonal_m)
    return figures


def _batch_figures(craft: Spacecraft, directions: np.ndarray, samples: int, one_by_one: list[Loads]) -> dict:
    """Direct SRP per attitude of one call with every direction (a batch: attitudes evaluated two or
    more at once, as sweeps do), default and ``samples`` points, and whether the default's loads are
    those of the attitudes one at a time (``one_by_one``)."""
    figures: dict = {}
    for key, n in (("default", None), ("fixed", samples)):
        start = time.perf_counter()
        batch = srp(craft, directions, sampling=ShadowSampling(samples=n), reflections="none")
        figures[f"{key}_batch_ms"] = 1e3 * (time.perf_counter() - start) / len(directions)
        if n is None:
            figures["batch_identical"] = all(
                np.array_equal(r.force_N, force) and np.array_equal(r.torque_Nm, torque)
                for r, (force, torque) in zip(batch, one_by_one, strict=True)
            )
    figures["batch_default_over_fixed"] = figures["default_batch_ms"] / figures["fixed_batch_ms"]
    return figures


#: Bytes per timed attitude: its direction as drawn and normalised, and four timings.
_ATTITUDE_BYTES = 140


def sun_directions(count: int, seed: int = 2026) -> np.ndarray:
    """``count`` seeded random unit vectors, uniform on the sphere.

    Parameters
    ----------
    count : int
        Number of directions.
    seed : int, optional
        Seed of ``numpy.random.default_rng``.

    Returns
    -------
    (count, 3) float64
        Unit vectors.

    Examples
    --------
    >>> sun_directions(2).round(3).tolist()
    [[-0.383, 0.116, -0.916], [0.893, 0.409, -0.187]]
    """
    v = np.random.default_rng(seed).normal(size=(count, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def benchmark(
    craft: Spacecraft,
    attitudes: int = 50,
    samples: int = 1,
    load_s: float = 0.0,
    progress: BenchProgress | None = None,
) -> BenchReport:
    """Time SRP and drag on ``craft`` over seeded random Sun directions, each setting with its error.

    Direct SRP with shadowing at the default and with ``samples`` fixed points per side in the same
    run, then the other settings, each with its error against :data:`REFERENCE_TOLERANCE`.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    attitudes : int, optional
        Sun directions (:func:`sun_directions`).
    samples : int, optional
        Fixed points per side of the fixed setting.
    load_s : float, optional
        Time it took to load the model [s], reported as is.
    progress : callable, optional
        ``progress(stage, done, total)`` hears each attitude of each stage.

    Returns
    -------
    BenchReport
        The figures.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> report = benchmark(cube.craft, attitudes=2)
    >>> report.sides, report.default_error.force_worst < 1e-2
    (12, True)
    """
    what = f"{memory.count(attitudes)} timed Sun directions"
    memory.require(_ATTITUDE_BYTES * attitudes, what, "lower attitudes", ("attitudes",))
    directions = sun_directions(attitudes)
    level = level_for_samples(samples)
    start = time.perf_counter()
    scene = craft.scene
    scene_build = time.perf_counter() - start
    start = time.perf_counter()
    srp(craft, directions[0], reflections="none")  # compiles kernels, keeps origins
    first_call = time.perf_counter() - start
    direct = _timed(
        lambda u, n: srp(craft, u, sampling=ShadowSampling(samples=n), reflections="none"),
        directions,
        samples,
    )
    # the raw figure casts the fixed setting's rays alone, right after each attitude was timed
    raw_times = []
    for k, u in enumerate(directions):
        _, origins = side_sampler(craft).facing_rays(u, level)
        flat = origins.reshape(-1, 3)
        along = np.broadcast_to(u.astype(np.float32), flat.shape)
        srp(craft, u, sampling=ShadowSampling(samples=samples), reflections="none")
        start = time.perf_counter()
        scene.occluded(flat, along)
        raw_times.append(time.perf_counter() - start)
        if progress:
            progress("timing raw Embree", k + 1, attitudes)
    batch = _batch_figures(craft, directions, samples, direct["default"]["loads"])
    references = _references(
        lambda u: srp(craft, u, sampling=ShadowSampling(tolerance=REFERENCE_TOLERANCE), reflections="none"),
        directions,
        "reference, direct",
        progress,
    )
    default, fixed = direct["default"], direct["fixed"]
    reflections, full_times = _reflection_figures(craft, directions, samples, direct, progress)
    gas = _drag_figures(craft, directions, samples, default["times"], full_times, progress)
    fixed_rays = sum(fixed["rays"])
    return BenchReport(
        triangles=craft.n_facets,
        sides=craft.n_sides,
        attitudes=attitudes,
        samples_per_side=level**2,
        threads=thread_count(),
        load_s=load_s,
        scene_build_s=scene_build,
        first_call_s=first_call,
        default_ms=1e3 * float(np.mean(default["times"])),
        default_median_ms=1e3 * float(np.median(default["times"])),
        default_rays_per_attitude=float(np.mean(default["rays"])),
        default_error=LoadError.of(default["loads"], references, craft.diagonal_m),
        fixed_ms=1e3 * float(np.mean(fixed["times"])),
        fixed_median_ms=1e3 * float(np.median(fixed["times"])),
        fixed_rays_per_attitude=fixed_rays / attitudes,
        fixed_error=LoadError.of(fixed["loads"], references, craft.diagonal_m),
        default_over_fixed=float(np.median(default["times"]) / np.median(fixed["times"])),
        **batch,
        fixed_rays_per_s=fixed_rays / float(np.sum(fixed["times"])),
        raw_embree_ms=1e3 * float(np.mean(raw_times)),
        raw_embree_rays_per_s=fixed_rays / float(np.sum(raw_times)),
        overhead=float(np.median(np.array(fixed["times"]) / np.array(raw_times))),
        **reflections,
        **gas,
        peak_memory_MB=_peak_MB(),
        machine=f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
    )


def reference_gas(gas: GasSampling) -> GasSampling:
    """``gas`` sampled :data:`REFERENCE_GAS_FACTORS` times more finely.

    Parameters
    ----------
    gas : GasSampling
        The timed setting; ``gas.sky_rays`` must be set.

    Returns
    -------
    GasSampling
        Four times the sky rays, sixteen times the core rays and chain molecules.

    Examples
    --------
    >>> from sunwind.forces.gas.sampling import GasSampling
    >>> reference_gas(GasSampling(sky_rays=256, core_rays=1024, chain_molecules=512))
    GasSampling(sky_rays=1024, core_rays=16384, chain_molecules=8192)
    """
    sky, core, chains = REFERENCE_GAS_FACTORS
    return GasSampling(gas.sky_rays * sky, gas.core_rays * core, gas.chain_molecules * chains)
