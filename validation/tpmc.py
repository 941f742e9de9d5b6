"""Test-particle Monte Carlo (TPMC): the reference for free-molecular drag on concave shapes.

It is written apart from the panel solver in ``forces`` and imports nothing from it: it reads only
the triangles and sides of the :class:`sunwind.geometry.spacecraft.Spacecraft` and casts its rays in the
model's Embree scene (``craft.scene``). It is slow and simple on purpose, and unbiased: it samples
the free stream, every wall interaction and every re-emission, and averages nothing analytically,
so it checks the finite-speed-ratio flux integrals, the gas-surface kernels and the multiple
reflections of a panel method at once. One call traces one species; the caller sums species.

Notes
-----
**Free stream and source** (:mod:`sunwind.validation.tpmc_source`). The gas moves relative to the
body with bulk velocity ``U = -V u``, ``u = v_rel / |v_rel|``, as a drifting Maxwellian at ``T``;
molecules enter an axis-aligned box, the model's bounding box grown on every side by ``_MARGIN`` of
the model half-size, through its six faces, each face in proportion to its exact inward flux, with
the exact flux-weighted velocity distribution of that face. There are no collisions, so a molecule
that never meets the body simply passes.

**Wall interaction.** A molecule travelling with ``v_in`` that meets facet ``f`` strikes the side
``craft.struck_sides`` names. A side the model lacks (``BLIND``: the inside of a closed body, the back
of a one-sided sheet) absorbs it: the body takes ``w m v_in`` and the molecule ends there. Otherwise
it is re-emitted with ``v_out`` by the side's kernel and the body takes the impulse rate
``J = w m (v_in - v_out)`` [N] and the torque ``(r - r_ref) x J`` at the hit point ``r``; the
molecule is traced again from ``r`` (the ray origin pushed ``craft.scene.offset_m`` off the surface
along the struck side's outward normal) until it leaves, or until ``max_bounces`` interactions, when
it is *dropped*: its last outgoing momentum is counted as leaving, and the count is reported.

The side's kernel, Maxwell (diffuse or specular, per-molecule energy accommodation) or CLL, is that
of :mod:`sunwind.validation.tpmc_kernels`.

**Errors.** The molecules are split into independent batches, each with its own random stream
(``SeedSequence(seed).spawn``); each batch total is an unbiased estimate, and the standard error of
the mean is the batch spread over ``sqrt(batches)``. A batch is traced in chunks of at most
``_CHUNK`` molecules, so memory does not grow with the molecule count. Batches run in parallel
threads (Embree and most numpy work release the GIL) and are summed in batch order, so a seed gives
the same bits on any machine load.

**Precision.** The hit point is rebuilt in float64 from Embree's float32 distance and projected onto
the facet's plane, as in :mod:`sunwind.validation.photon_tracer`.
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft
from sunwind.validation.sampling import Sampling
from sunwind.validation.tpmc_kernels import WallInteraction, cll_reemission, maxwell_reemission
from sunwind.validation.tpmc_source import BOLTZMANN_J_K, SpeciesStream, flux_normal_speeds, inflow_flux

__all__ = ["DEFAULT_SAMPLING", "TpmcResult", "trace_molecules"]

#: Molecules, seed, batches and bounce cap of :func:`trace_molecules` unless told.
DEFAULT_SAMPLING = Sampling(200_000)
#: The source box is the bounding box grown on every side by this share of the model half-size.
_MARGIN = 0.02
#: Most molecules traced at once within a batch (bounds the memory of a batch).
_CHUNK = 65_536


@dataclass(frozen=True, eq=False)
class TpmcResult:
    """Monte Carlo free-molecular loads on a model at one attitude, one species, body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Mean force [N] and torque [N m] about ``reference_point_m`` over the batches.
    force_se_N, torque_se_Nm : (3,) float64
        Standard errors of each component [N], [N m], from the spread of the batches.
    molecules : int
        Molecules launched (``batches`` times the molecules per batch).
    hits : int
        Wall interactions in all (re-emissions and absorptions), first strikes included.
    dropped : int
        Molecules still bouncing when ``max_bounces`` stopped them; their last outgoing momentum was
        counted as leaving.
    absorbed : int
        Molecules that struck a side the model lacks (``BLIND``) and were absorbed there.
    reference_point_m : (3,) float64
        Torque reference point [m].
    bounces : (max_bounces + 1,) int64
        ``bounces[k]``: molecules that met the body exactly ``k`` times; ``bounces[0]`` passed by,
        ``bounces[max_bounces]`` includes those dropped.
    batches : int
    inflow_per_s : float
        Molecules entering the source box per second [1/s]; each carries ``inflow_per_s / molecules``
        of a batch.
    speed_ratio : float
        ``S = V / sqrt(2 k T / m)`` [-].
    flow_direction : (3,) float64
        Unit ``u = v_rel / |v_rel|``, body frame.
    seconds : float
        Wall-clock time of the trace [s].

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> from sunwind.validation.sampling import Sampling
    >>> from sunwind.validation.tpmc_kernels import WallInteraction
    >>> from sunwind.validation.tpmc_source import SpeciesStream
    >>> cube = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> oxygen = SpeciesStream(7500.0, 1000.0, 1e15, 16 * 1.66054e-27)  # V [m/s], T [K], n [m^-3], m [kg]
    >>> diffuse = WallInteraction(diffuse_fraction=1.0, wall_temperature_K=300.0)
    >>> result = trace_molecules(cube, [0.0, 0.0, 1.0], oxygen, diffuse, Sampling(2000, batches=4))
    >>> result.molecules, result.dropped, round(result.speed_ratio, 2)
    (2000, 0, 7.36)
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    force_se_N: NDArray[np.float64]
    torque_se_Nm: NDArray[np.float64]
    molecules: int
    hits: int
    dropped: int
    absorbed: int
    reference_point_m: NDArray[np.float64]
    bounces: NDArray[np.int64]
    batches: int
    inflow_per_s: float
    speed_ratio: float
    flow_direction: NDArray[np.float64]
    seconds: float

    @property
    def struck(self) -> int:
        """Molecules that met the body at least once."""
        return int(self.bounces[1:].sum())

    @property
    def mean_interactions(self) -> float:
        """Mean number of wall interactions of a molecule that met the body [-]."""
        return self.hits / self.struck if self.struck else 0.0

    @property
    def force_error_N(self) -> float:
        """Standard error of the force vector, ``sqrt(sum(force_se_N^2))`` [N]."""
        return float(np.linalg.norm(self.force_se_N))

    @property
    def torque_error_Nm(self) -> float:
        """Standard error of the torque vector, ``sqrt(sum(torque_se_Nm^2))`` [N m]."""
        return float(np.linalg.norm(self.torque_se_Nm))

    @property
    def molecules_per_second(self) -> float:
        """Molecules launched per second of wall-clock time [1/s]."""
        return self.molecules / self.seconds if self.seconds > 0 else math.inf


@dataclass(frozen=True)
class _Totals:
    """What one batch (or chunk) adds up: force [N], torque [N m] and molecule counts."""

    force: NDArray[np.float64]
    torque: NDArray[np.float64]
    active: NDArray[np.int64]  # active[k]: molecules meeting the body a (k + 1)-th time
    dropped: int
    absorbed: int


class _Tracer:
    """The model, the free stream, the source box and the kernels; the trace of one batch."""

    def __init__(
        self,
        craft: Spacecraft,
        flow: NDArray[np.float64],
        stream: SpeciesStream,
        kernel: str,
        kernel_arrays: dict[str, NDArray[np.float64]],
        reference: NDArray[np.float64],
        max_bounces: int,
    ) -> None:
        speed, temperature = float(stream.speed_m_s), float(stream.temperature_K)
        density, mass = float(stream.number_density_m3), float(stream.mass_kg)
        self.craft = craft
        self.scene = craft.scene
        self.mass = mass
        self.drift = -speed * flow
        self.c_m = math.sqrt(2.0 * BOLTZMANN_J_K * temperature / mass)
        self.kernel = kernel
        self.k = kernel_arrays
        self.wall_c2 = 2.0 * BOLTZMANN_J_K * kernel_arrays["wall_temperature"] / mass  # c_w^2 per side
        self.reference = reference
        self.max_bounces = max_bounces
        self.corner = craft.triangles[:, 0]
        self.normals = craft.facet_normals
        self.side_normals = craft.side_normals
        # source box and its six faces: (axis, coordinate, inward sign, area, s)
        lo, hi = craft.bounds
        margin = _MARGIN * self.scene.half_size
        self.lo, self.hi = lo - margin, hi + margin
        size = self.hi - self.lo
        self.faces: list[tuple[int, float, float, float, float]] = []
        rates = []
        for axis in range(3):
            area = float(np.prod(np.delete(size, axis)))
            for coordinate, sign in ((self.lo[axis], 1.0), (self.hi[axis], -1.0)):
                s = sign * self.drift[axis] / self.c_m
                self.faces.append((axis, float(coordinate), sign, area, s))
                rates.append(area * density * self.c_m * inflow_flux(s))
        self.rates = np.array(rates)
        self.inflow = float(self.rates.sum())

    # --- source -------------------------------------------------------------------------------------
    def source(self, m: int, rng: np.random.Generator) -> tuple[NDArray, NDArray]:
        """Entry points [m] and velocities [m/s] of ``m`` molecules crossing into the box."""
        counts = rng.multinomial(m, self.rates / self.inflow)
        positions, velocities = [], []
        for (axis, coordinate, sign, _, s), count in zip(self.faces, counts, strict=True):
            across = [a for a in range(3) if a != axis]
            p = np.empty((count, 3))
            p[:, axis] = coordinate
            p[:, across] = self.lo[across] + rng.random((count, 2)) * (self.hi[across] - self.lo[across])
            v = np.empty((count, 3))
            v[:, axis] = sign * self.c_m * flux_normal_speeds(s, count, rng)
            v[:, across] = self.drift[across] + self.c_m / math.sqrt(2.0) * rng.standard_normal((count, 2))
            positions.append(p)
            velocities.append(v)
        return np.concatenate(positions), np.concatenate(velocities)

    # --- tracing ------------------------------------------------------------------------------------
    def cast(self, origins: NDArray[np.float64], velocities: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        """Struck side (or ``ESCAPED``/``BLIND``) of each molecule and its hit point [m] (garbage if none)."""
        directions = velocities / np.linalg.norm(velocities, axis=1)[:, None]
        facets, distance = self.scene.intersect(
            self.scene.to_scene(origins), np.ascontiguousarray(directions, dtype=np.float32)
        )
        sides = self.craft.struck_sides(facets, directions)
        hit = facets >= 0
        f = facets[hit]
        points = np.zeros_like(origins)
        p = (
            origins[hit]
            + (distance[hit].astype(np.float64) * self.scene.half_size)[:, None] * directions[hit]
        )
        n = self.normals[f]
        p -= np.einsum("ij,ij->i", p - self.corner[f], n)[:, None] * n
        points[hit] = p
        return sides, points

    def reemit(self, v: NDArray[np.float64], side: NDArray[np.int64], rng: np.random.Generator) -> NDArray:
        """Velocities [m/s] of molecules arriving with ``v`` on ``side`` (valid sides), re-emitted."""
        n = self.side_normals[side]
        if self.kernel == "maxwell":
            return maxwell_reemission(
                v,
                n,
                self.k["diffuse_fraction"][side],
                self.wall_c2[side],
                self.k["energy_accommodation"][side],
                rng,
            )
        return cll_reemission(
            v,
            n,
            self.wall_c2[side],
            self.k["normal_accommodation"][side],
            self.k["tangential_accommodation"][side],
            rng,
        )

    def chunk(self, m: int, weight: float, rng: np.random.Generator) -> _Totals:
        """Trace ``m`` molecules of weight ``weight`` [1/s] each to the end; totals of the chunk."""
        position, velocity = self.source(m, rng)
        force, torque = np.zeros(3), np.zeros(3)
        active = np.zeros(self.max_bounces, dtype=np.int64)
        dropped = absorbed = 0
        for generation in range(self.max_bounces + 1):
            side, point = self.cast(position, velocity)
            struck = side != ESCAPED
            if generation == self.max_bounces:
                dropped = int(struck.sum())
                break
            side, point, v_in = side[struck], point[struck], velocity[struck]
            active[generation] = len(side)
            if not len(side):
                break
            blind = side == BLIND
            absorbed += int(blind.sum())
            live = ~blind
            v_out = np.zeros_like(v_in)
            v_out[live] = self.reemit(v_in[live], side[live], rng)
            impulse = (weight * self.mass) * (v_in - v_out)
            force += impulse.sum(axis=0)
            torque += np.cross(point - self.reference, impulse).sum(axis=0)
            n_out = self.side_normals[side[live]]
            position = point[live] + self.scene.offset_m * n_out
            velocity = v_out[live]
        return _Totals(force, torque, active, dropped, absorbed)

    def batch(self, m: int, rng: np.random.Generator) -> _Totals:
        """Trace ``m`` molecules, ``_CHUNK`` at a time; totals of the batch."""
        weight = self.inflow / m
        parts = [self.chunk(min(_CHUNK, m - lo), weight, rng) for lo in range(0, m, _CHUNK)]
        return _Totals(
            np.sum([p.force for p in parts], axis=0),
            np.sum([p.torque for p in parts], axis=0),
            np.sum([p.active for p in parts], axis=0),
            sum(p.dropped for p in parts),
            sum(p.absorbed for p in parts),
        )


def trace_molecules(
    craft: Spacecraft,
    flow_direction: ArrayLike,
    stream: SpeciesStream,
    walls: WallInteraction,
    sampling: Sampling = DEFAULT_SAMPLING,
    *,
    reference_point_m: ArrayLike | None = None,
) -> TpmcResult:
    """Free-molecular force and torque of one gas species on ``craft`` by test-particle Monte Carlo.

    Parameters
    ----------
    craft : Spacecraft
    flow_direction : (3,) array_like
        ``v_rel``, the spacecraft velocity relative to the atmosphere, body frame (normalised here);
        molecules arrive travelling along ``-v_rel`` on average.
    stream : SpeciesStream
        Speed ``V = |v_rel|`` [m/s] (>= 0; 0 is a gas at rest), temperature [K] (> 0), number
        density [m^-3] (>= 0) and molecular mass [kg] (> 0) of the species.
    walls : WallInteraction
        Gas-surface kernel of the sides and its parameters, scalar or per side.
    sampling : Sampling
        Molecules to launch in all (rounded up to a multiple of the batches), the seed, the batches
        the standard errors come from (>= 2), and the most wall interactions per molecule (>= 1;
        molecules still bouncing then are ``dropped``); default :data:`DEFAULT_SAMPLING`.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default ``craft.default_reference[0]``.

    Returns
    -------
    TpmcResult

    Examples
    --------
    A unit cube flying along +z through atomic oxygen at 7.5 km/s: the drag points along -z and is about
    ``C_D q A`` with ``C_D`` a little above 2 (a tiny run, so only its sign and size are shown):

    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> from sunwind.validation.sampling import Sampling
    >>> from sunwind.validation.tpmc_kernels import WallInteraction
    >>> from sunwind.validation.tpmc_source import SpeciesStream
    >>> cube = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> oxygen = SpeciesStream(7500.0, 1000.0, 1e15, 16 * 1.66054e-27)  # V [m/s], T [K], n [m^-3], m [kg]
    >>> diffuse = WallInteraction(diffuse_fraction=1.0, wall_temperature_K=300.0)
    >>> result = trace_molecules(cube, [0.0, 0.0, 1.0], oxygen, diffuse, Sampling(2000, batches=4))
    >>> q = 0.5 * 1e15 * 16 * 1.66054e-27 * 7500.0**2
    >>> bool(2.0 < -result.force_N[2] / q < 2.5)
    True
    """
    molecules, batches, max_bounces = sampling.particles, sampling.batches, sampling.max_bounces
    speed_m_s, temperature_K = stream.speed_m_s, stream.temperature_K
    number_density_m3, mass_kg = stream.number_density_m3, stream.mass_kg
    if batches < 2 or molecules < batches or max_bounces < 1:
        raise ValueError("need batches >= 2, molecules >= batches and max_bounces >= 1")
    if not (temperature_K > 0 and mass_kg > 0 and number_density_m3 >= 0 and speed_m_s >= 0):
        raise ValueError("need temperature_K > 0, mass_kg > 0, number_density_m3 >= 0 and speed_m_s >= 0")
    start = time.perf_counter()
    flow = np.asarray(flow_direction, dtype=np.float64)
    flow = flow / np.linalg.norm(flow)
    reference = np.asarray(
        craft.default_reference[0] if reference_point_m is None else reference_point_m, dtype=np.float64
    )
    arrays = walls.per_side(craft.n_sides)
    tracer = _Tracer(craft, flow, stream, walls.kernel, arrays, reference, max_bounces)
    per_batch = -(-molecules // batches)
    generators = [np.random.default_rng(s) for s in np.random.SeedSequence(sampling.seed).spawn(batches)]
    with ThreadPoolExecutor(min(batches, os.cpu_count() or 1)) as pool:
        totals = list(pool.map(lambda rng: tracer.batch(per_batch, rng), generators))
    force = np.array([t.force for t in totals])
    torque = np.array([t.torque for t in totals])
    active = np.sum([t.active for t in totals], axis=0)
    launched = per_batch * batches
    return TpmcResult(
        force_N=force.mean(axis=0),
        torque_Nm=torque.mean(axis=0),
        force_se_N=force.std(axis=0, ddof=1) / math.sqrt(batches),
        torque_se_Nm=torque.std(axis=0, ddof=1) / math.sqrt(batches),
        molecules=launched,
        hits=int(active.sum()),
        dropped=sum(t.dropped for t in totals),
        absorbed=sum(t.absorbed for t in totals),
        reference_point_m=reference,
        bounces=-np.diff(np.concatenate([[launched], active, [0]])),
        batches=batches,
        inflow_per_s=tracer.inflow,
        speed_ratio=float(speed_m_s) / tracer.c_m,
        flow_direction=flow,
        seconds=time.perf_counter() - start,
    )
