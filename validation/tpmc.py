"""Test-particle Monte Carlo (TPMC): the reference for free-molecular drag on concave shapes.

It is written apart from the panel solver in ``forces`` and imports nothing from it: it reads only
the triangles and sides of the :class:`sunwind.geometry.spacecraft.Spacecraft` and casts its rays in the
model's Embree scene (``craft.scene``). It is slow and simple on purpose, and unbiased: it samples
the free stream, every wall interaction and every re-emission, and averages nothing analytically,
so it checks the finite-speed-ratio flux integrals, the gas-surface kernels and the multiple
reflections of a panel method at once. One call traces one species; the caller sums species.

Notes
-----
**Free stream** (METHOD.md "Free-molecular flow"). ``u = v_rel / |v_rel|`` is the flow direction in
the body frame; the gas moves relative to the body with bulk velocity ``U = -V u`` and temperature
``T``; molecules of mass ``m`` [kg], number density ``n`` [m^-3]. With ``c_m = sqrt(2 k T / m)`` the
most probable thermal speed, the velocity distribution is the drifting Maxwellian
``f(v) = n / (pi^(3/2) c_m^3) exp(-|v - U|^2 / c_m^2)`` and the speed ratio is ``S = V / c_m``.

**Source.** Molecules enter an axis-aligned box, the model's bounding box grown on every side by
``_MARGIN`` of the model half-size, through its six faces. There are no collisions, so the molecules
inside the box are exactly those that crossed its boundary inward, and a molecule that never meets
the body simply passes. Through a face of area ``A`` with inward unit normal ``e`` and normal speed
ratio ``s = (U . e) / c_m`` the inward number flux is the exact half-range integral

    Gamma(s) = n c_m / (2 sqrt(pi)) [exp(-s^2) + sqrt(pi) s erfc(-s)]     [m^-2 s^-1],

and the total inflow rate is ``N_dot = sum_faces A Gamma(s)`` [1/s]. Each molecule of a batch of
``N`` carries the weight ``N_dot / N`` [1/s]; its face is drawn with probability ``A Gamma / N_dot``
(multinomially), its entry point uniformly on the face. Its velocity has the flux-weighted
half-range Maxwellian distribution of that face: tangential components ``U_t + c_m / sqrt(2) N(0, 1)``,
and normal component ``c_m x`` with ``x > 0`` drawn exactly from ``p(x) ~ x exp(-(x - s)^2)`` by
rejection (:func:`flux_normal_speeds`):

- ``s >= 0``: with ``y = x - s``, ``p ~ (y + s) exp(-y^2)`` on ``y > -s``; propose from
  ``(|y| + s) exp(-y^2)`` on the whole line, the mixture of ``|y| exp(-y^2)`` (weight 1,
  ``|y| = sqrt(-ln U)``, random sign) and ``s exp(-y^2)`` (weight ``s sqrt(pi)``, ``y ~ N(0, 1/2)``);
  accept when ``y > -s`` with probability ``(y + s) / (|y| + s)``. Efficiency ``>= 1/2``.
- ``-1 < s < 0``: with ``a = -s`` and ``y = x + a``, ``p ~ (y - a) exp(-y^2)`` on ``y > a``; propose
  the tail ``y = sqrt(a^2 - ln U)`` of ``y exp(-y^2)`` and accept with probability ``(y - a) / y``.
- ``s <= -1``: ``p ~ x exp(-2 a x) exp(-x^2)``; propose ``x ~ Gamma(2, 1 / (2 a))`` and accept with
  probability ``exp(-x^2)``.

**Wall interaction.** A molecule travelling with ``v_in`` that meets facet ``f`` strikes the side
``craft.struck_sides`` names. A side the model lacks (``BLIND``: the inside of a closed body, the back
of a one-sided sheet) absorbs it: the body takes ``w m v_in`` and the molecule ends there. Otherwise
it is re-emitted with ``v_out`` by the side's kernel and the body takes the impulse rate
``J = w m (v_in - v_out)`` [N] and the torque ``(r - r_ref) x J`` at the hit point ``r``; the
molecule is traced again from ``r`` (the ray origin pushed ``craft.scene.offset_m`` off the surface
along the struck side's outward normal) until it leaves, or until ``max_bounces`` interactions, when
it is *dropped*: its last outgoing momentum is counted as leaving, and the count is reported.

**Maxwell kernel** (default). With probability ``diffuse_fraction`` of the struck side the molecule
is re-emitted diffusely, else specularly (``v_out = v_in - 2 (v_in . n) n``). Diffuse re-emission is
the flux-weighted half-range Maxwellian at rest at the temperature ``T_r`` about the side's outward
normal ``n`` (a cosine-law direction and a speed ``~ c^3 exp(-c^2 / c_r^2)``): normal component
``c_r sqrt(-ln U)``, tangential components ``c_r / sqrt(2) N(0, 1)``, ``c_r = sqrt(2 k T_r / m)``.
Energy accommodation is applied **per molecule**: a Maxwellian flux at ``T_r`` carries ``2 k T_r`` of
kinetic energy per molecule (the "2kT" form of Sentman's model in METHOD.md), so a molecule arriving
with ``E_in = m |v_in|^2 / 2`` is re-emitted at

    T_r = alpha_E T_w + (1 - alpha_E) E_in / (2 k),

and on average leaves with ``alpha_E 2 k T_w + (1 - alpha_E) E_in``. ``alpha_E = 1`` (default) is
full accommodation at the wall temperature ``T_w``. This is not quite the closed-form Sentman model
with ``alpha_E < 1``, which sets one ``T_r`` for a whole surface element from its *mean* incident
energy flux: the mean re-emission speed ``~ E[sqrt(T_r)]`` differs from ``sqrt(E[T_r])`` by the
spread of the incident energies (small at high ``S``).

**CLL kernel** (``kernel="cll"``; Cercignani-Lampis-Lord, sampled by Lord's algorithm, Lord 1991).
With ``c_w = sqrt(2 k T_w / m)``, the normal accommodation ``alpha_n`` and the tangential momentum
accommodation ``sigma_t`` (tangential energy accommodation ``alpha_t = sigma_t (2 - sigma_t)``), the
incident normal speed ``u_i = -v_in . n / c_w`` and tangential velocity ``v_t`` (direction ``t1``,
``t2 = n x t1``)::

    r = sqrt(-alpha_n ln U1),  th = 2 pi U2,  u_m = sqrt(1 - alpha_n) u_i,
    u_n = sqrt(r^2 + u_m^2 + 2 r u_m cos th)
    r = sqrt(-alpha_t ln U3),  th = 2 pi U4,
    u_t1 = (1 - sigma_t) |v_t| / c_w + r cos th,   u_t2 = r sin th
    v_out = c_w (u_n n + u_t1 t1 + u_t2 t2).

``alpha_n = sigma_t = 1`` is diffuse re-emission at ``T_w``, ``alpha_n = sigma_t = 0`` specular; the
mean tangential momentum out is exactly ``(1 - sigma_t)`` of the incident one.

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

__all__ = [
    "BOLTZMANN_J_K",
    "KERNELS",
    "TpmcResult",
    "cll_reemission",
    "flux_normal_speeds",
    "inflow_flux",
    "maxwell_reemission",
    "trace_molecules",
]

#: Boltzmann constant [J/K] (exact, SI 2019).
BOLTZMANN_J_K = 1.380649e-23
#: Gas-surface kernels :func:`trace_molecules` offers.
KERNELS = ("maxwell", "cll")
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


def inflow_flux(s: float) -> float:
    """Inward number flux of a drifting Maxwellian through a plane, over ``n c_m`` [-].

    ``Gamma / (n c_m) = [exp(-s^2) + sqrt(pi) s erfc(-s)] / (2 sqrt(pi))`` with ``s`` the drift
    velocity's component along the plane's inward normal over ``c_m = sqrt(2 k T / m)``.
    """
    return (math.exp(-s * s) + math.sqrt(math.pi) * s * math.erfc(-s)) / (2.0 * math.sqrt(math.pi))


def flux_normal_speeds(s: float, count: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """``count`` exact samples ``x > 0`` of ``p(x) ~ x exp(-(x - s)^2)``, by rejection (module Notes).

    The normal velocity component, over ``c_m``, of molecules of a drifting Maxwellian crossing a
    plane in the direction of its normal, when the drift component along it over ``c_m`` is ``s``.
    """
    out: list[NDArray[np.float64]] = []
    need = count
    while need > 0:
        k = 2 * need + 16
        if s >= 0.0:
            pick_rayleigh = rng.random(k) * (1.0 + s * math.sqrt(math.pi)) < 1.0
            rayleigh = np.sqrt(-np.log1p(-rng.random(k))) * np.where(rng.random(k) < 0.5, -1.0, 1.0)
            y = np.where(pick_rayleigh, rayleigh, rng.standard_normal(k) / math.sqrt(2.0))
            accept = (y > -s) & (rng.random(k) * (np.abs(y) + s) < y + s)
            x = y[accept] + s
        elif s > -1.0:
            a = -s
            y = np.sqrt(a * a - np.log1p(-rng.random(k)))
            x = (y - a)[rng.random(k) * y < y - a]
        else:
            a = -s
            x = rng.gamma(2.0, 1.0 / (2.0 * a), k)
            x = x[rng.random(k) < np.exp(-x * x)]
        x = x[:need]
        out.append(x)
        need -= len(x)
    return np.concatenate(out) if out else np.zeros(0)


def _basis(normals: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two unit tangents completing each unit normal (n, 3) to a right-handed orthonormal frame.

    Duff et al. (2017), "Building an orthonormal basis, revisited".
    """
    x, y, z = normals.T
    sign = np.where(z >= 0.0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    t1 = np.column_stack([1.0 + sign * x * x * a, sign * b, -sign * x])
    t2 = np.column_stack([b, sign + y * y * a, -y])
    return t1, t2


def _dot(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.einsum("ij,ij->i", a, b)


def _per_side(name: str, value: ArrayLike, n_sides: int, low: float, high: float) -> NDArray[np.float64]:
    """``value`` (scalar or (n_sides,)) as a (n_sides,) float64 array, checked to lie in [low, high]."""
    array = np.asarray(value, dtype=np.float64)
    if array.ndim == 0:
        array = np.full(n_sides, float(array))
    if array.shape != (n_sides,):
        raise ValueError(f"{name} must be a scalar or have one value per side ({n_sides}), not {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array < low) or np.any(array > high):
        raise ValueError(f"{name} must lie in [{low}, {high}]")
    return array


def maxwell_reemission(
    v_in: NDArray[np.float64],
    normals: NDArray[np.float64],
    diffuse_fraction: NDArray[np.float64],
    wall_c2: NDArray[np.float64],
    energy_accommodation: NDArray[np.float64],
    rng: np.random.Generator,
) -> NDArray[np.float64]:
    """Maxwell kernel: velocities [m/s] of molecules re-emitted by walls (module Notes).

    Parameters
    ----------
    v_in : (k, 3) float64
        Incident velocities [m/s], toward the walls (``v_in . normals < 0``).
    normals : (k, 3) float64
        Outward unit normals of the struck sides.
    diffuse_fraction : (k,) float64
        Probability of diffuse re-emission [-]; else specular reflection.
    wall_c2 : (k,) float64
        ``c_w^2 = 2 k T_w / m`` [m^2/s^2].
    energy_accommodation : (k,) float64
        ``alpha_E`` [-]: diffuse re-emission at ``c_r^2 = alpha_E c_w^2 + (1 - alpha_E) |v_in|^2 / 2``,
        i.e. ``T_r = alpha_E T_w + (1 - alpha_E) E_in / (2 k)``.
    rng : numpy.random.Generator

    Returns
    -------
    (k, 3) float64
    """
    k = len(v_in)
    vn = _dot(v_in, normals)
    out = v_in - 2.0 * vn[:, None] * normals
    diffuse = rng.random(k) < diffuse_fraction
    alpha = energy_accommodation
    c_r = np.sqrt(alpha * wall_c2 + (1.0 - alpha) * 0.5 * _dot(v_in, v_in))
    t1, t2 = _basis(normals)
    normal = np.sqrt(-np.log1p(-rng.random(k)))
    tangent = rng.standard_normal((k, 2)) / math.sqrt(2.0)
    emitted = c_r[:, None] * (normal[:, None] * normals + tangent[:, :1] * t1 + tangent[:, 1:] * t2)
    out[diffuse] = emitted[diffuse]
    return out


def cll_reemission(
    v_in: NDArray[np.float64],
    normals: NDArray[np.float64],
    wall_c2: NDArray[np.float64],
    normal_accommodation: NDArray[np.float64],
    tangential_accommodation: NDArray[np.float64],
    rng: np.random.Generator,
) -> NDArray[np.float64]:
    """Cercignani-Lampis-Lord kernel by Lord's algorithm: re-emitted velocities [m/s] (module Notes).

    Parameters
    ----------
    v_in : (k, 3) float64
        Incident velocities [m/s], toward the walls (``v_in . normals < 0``).
    normals : (k, 3) float64
        Outward unit normals of the struck sides.
    wall_c2 : (k,) float64
        ``c_w^2 = 2 k T_w / m`` [m^2/s^2].
    normal_accommodation : (k,) float64
        ``alpha_n`` [-], normal kinetic-energy accommodation.
    tangential_accommodation : (k,) float64
        ``sigma_t`` [-], tangential momentum accommodation (energy: ``sigma_t (2 - sigma_t)``).
    rng : numpy.random.Generator

    Returns
    -------
    (k, 3) float64
    """
    k = len(v_in)
    c_w = np.sqrt(wall_c2)
    alpha_n, sigma_t = normal_accommodation, tangential_accommodation
    alpha_t = sigma_t * (2.0 - sigma_t)
    vn = _dot(v_in, normals)
    r = np.sqrt(-alpha_n * np.log1p(-rng.random(k)))
    theta = 2.0 * math.pi * rng.random(k)
    u_m = np.sqrt(1.0 - alpha_n) * (-vn / c_w)
    u_n = np.sqrt(np.maximum(r * r + u_m * u_m + 2.0 * r * u_m * np.cos(theta), 0.0))
    vt = v_in - vn[:, None] * normals
    vt_norm = np.linalg.norm(vt, axis=1)
    along = vt_norm > 0.0
    e1 = np.where(along[:, None], vt / np.where(along, vt_norm, 1.0)[:, None], _basis(normals)[0])
    e2 = np.cross(normals, e1)
    r = np.sqrt(-alpha_t * np.log1p(-rng.random(k)))
    theta = 2.0 * math.pi * rng.random(k)
    u_t1 = (1.0 - sigma_t) * vt_norm / c_w + r * np.cos(theta)
    u_t2 = r * np.sin(theta)
    return c_w[:, None] * (u_n[:, None] * normals + u_t1[:, None] * e1 + u_t2[:, None] * e2)


class _Tracer:
    """The model, the free stream, the source box and the kernels; the trace of one batch."""

    def __init__(
        self,
        craft: Spacecraft,
        flow: NDArray[np.float64],
        speed: float,
        temperature: float,
        density: float,
        mass: float,
        kernel: str,
        kernel_arrays: dict[str, NDArray[np.float64]],
        reference: NDArray[np.float64],
        max_bounces: int,
    ) -> None:
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
        p -= _dot(p - self.corner[f], n)[:, None] * n
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
    *,
    speed_m_s: float,
    temperature_K: float,
    number_density_m3: float,
    mass_kg: float,
    diffuse_fraction: ArrayLike | None,
    wall_temperature_K: ArrayLike,
    energy_accommodation: ArrayLike = 1.0,
    molecules: int = 200_000,
    reference_point_m: ArrayLike | None = None,
    seed: int = 0,
    batches: int = 20,
    max_bounces: int = 100,
    kernel: str = "maxwell",
    normal_accommodation: ArrayLike | None = None,
    tangential_accommodation: ArrayLike | None = None,
) -> TpmcResult:
    """Free-molecular force and torque of one gas species on ``craft`` by test-particle Monte Carlo.

    Parameters
    ----------
    craft : Spacecraft
    flow_direction : (3,) array_like
        ``v_rel``, the spacecraft velocity relative to the atmosphere, body frame (normalised here);
        molecules arrive travelling along ``-v_rel`` on average.
    speed_m_s : float
        ``V = |v_rel|`` [m/s], >= 0 (0 is a gas at rest).
    temperature_K : float
        Free-stream (translational) temperature ``T`` [K], > 0.
    number_density_m3 : float
        Number density ``n`` of the species [m^-3], >= 0.
    mass_kg : float
        Molecular mass ``m`` of the species [kg], > 0.
    diffuse_fraction : float or (n_sides,) array_like, or None
        Maxwell kernel: share of molecules each side re-emits diffusely [-], in [0, 1]; the rest are
        reflected specularly. Must be None for ``kernel="cll"``.
    wall_temperature_K : float or (n_sides,) array_like
        Wall temperature ``T_w`` of each side [K], > 0.
    energy_accommodation : float or (n_sides,) array_like
        Maxwell kernel: ``alpha_E`` [-] of the diffuse re-emission, in [0, 1], applied per molecule
        with 2 k T_r per re-emitted molecule (module Notes); default 1 (re-emission at ``T_w``).
    molecules : int
        Molecules to launch in all; rounded up to a multiple of ``batches``.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default ``craft.default_reference[0]``.
    seed : int
        Seed of the random streams; the same seed gives the same result.
    batches : int
        Independent batches the standard errors come from (>= 2).
    max_bounces : int
        Most wall interactions per molecule (>= 1); molecules still bouncing are ``dropped``.
    kernel : {"maxwell", "cll"}
        Gas-surface interaction kernel (module Notes).
    normal_accommodation, tangential_accommodation : float or (n_sides,) array_like, optional
        CLL kernel only (then required): normal energy accommodation ``alpha_n`` and tangential
        momentum accommodation ``sigma_t`` of each side [-], in [0, 1].

    Returns
    -------
    TpmcResult
    """
    if batches < 2 or molecules < batches or max_bounces < 1:
        raise ValueError("need batches >= 2, molecules >= batches and max_bounces >= 1")
    if not (temperature_K > 0 and mass_kg > 0 and number_density_m3 >= 0 and speed_m_s >= 0):
        raise ValueError("need temperature_K > 0, mass_kg > 0, number_density_m3 >= 0 and speed_m_s >= 0")
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {KERNELS}, not {kernel!r}")
    start = time.perf_counter()
    flow = np.asarray(flow_direction, dtype=np.float64)
    flow = flow / np.linalg.norm(flow)
    reference = np.asarray(
        craft.default_reference[0] if reference_point_m is None else reference_point_m, dtype=np.float64
    )
    n_sides = craft.n_sides
    arrays = {
        "wall_temperature": _per_side("wall_temperature_K", wall_temperature_K, n_sides, 1e-300, np.inf)
    }
    if kernel == "maxwell":
        if (
            diffuse_fraction is None
            or normal_accommodation is not None
            or tangential_accommodation is not None
        ):
            raise ValueError("the Maxwell kernel takes diffuse_fraction (and energy_accommodation) only")
        arrays["diffuse_fraction"] = _per_side("diffuse_fraction", diffuse_fraction, n_sides, 0.0, 1.0)
        arrays["energy_accommodation"] = _per_side(
            "energy_accommodation", energy_accommodation, n_sides, 0.0, 1.0
        )
    else:
        if diffuse_fraction is not None or normal_accommodation is None or tangential_accommodation is None:
            raise ValueError(
                "the CLL kernel takes normal_accommodation and tangential_accommodation, "
                "and diffuse_fraction=None"
            )
        if np.any(np.asarray(energy_accommodation) != 1.0):
            raise ValueError("energy_accommodation is for the Maxwell kernel; CLL uses normal_accommodation")
        arrays["normal_accommodation"] = _per_side(
            "normal_accommodation", normal_accommodation, n_sides, 0, 1
        )
        arrays["tangential_accommodation"] = _per_side(
            "tangential_accommodation", tangential_accommodation, n_sides, 0.0, 1.0
        )
    tracer = _Tracer(
        craft,
        flow,
        float(speed_m_s),
        float(temperature_K),
        float(number_density_m3),
        float(mass_kg),
        kernel,
        arrays,
        reference,
        max_bounces,
    )
    per_batch = -(-molecules // batches)
    streams = [np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(batches)]
    with ThreadPoolExecutor(min(batches, os.cpu_count() or 1)) as pool:
        totals = list(pool.map(lambda rng: tracer.batch(per_batch, rng), streams))
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
