"""Brute-force Monte Carlo photon tracer: the reference for solar-radiation pressure on concave shapes.

It is written apart from the solver in ``forces`` and imports nothing from it: it reads only the
model (triangles, sides, optics) from the :class:`sunwind.geometry.spacecraft.Spacecraft` and casts its rays
in an Embree scene of its own. It is slow and simple on purpose, and unbiased.

Notes
-----
**Source.** Photons travel along ``s = -u_sun`` (METHOD.md "Frames, units and signs"). Bundles start upstream
of the model on the rectangle perpendicular to ``s`` that bounds the projection of its vertices, so
no part of the body is missed and few bundles are wasted on an elongated model.
The positions are stratified: a jittered ``k1 x k2`` grid (cells as square as the rectangle
allows), the ``m - k1 k2`` left over uniform; each of the ``m`` bundles of a batch starts with power
``Phi A_source / m``.

**Interaction.** A ray that meets facet ``f`` travelling along ``d`` strikes its front side when
``d . n_f < 0``, else its back side (``facet_sides[f]``). A side the model lacks (the inside of a
closed body, the back of a one-sided sheet) absorbs everything. Otherwise, with the side's
``(rho, beta, sigma)``, the tracer uses *survival weighting*: the share ``alpha = 1 - rho - sigma``
of the bundle's power ``w`` is absorbed there and the bundle carries on with ``w (rho + sigma)``,
drawing its fate at random in proportion to ``rho beta`` (mirror reflection,
``d' = d - 2 (d . n) n``), ``rho (1 - beta)`` (Lambertian reflection, cosine-weighted about the
struck side's outward normal) and ``sigma`` (transmission: through a sheet it continues along ``d``
from the other side; through a closed body's wall it is not traced and leaves along ``d``, carrying
its momentum away). No Russian roulette: power is conserved exactly, bundle by bundle, so
``incident = absorbed + escaped + cut`` holds to round-off.

**Momentum.** Each interaction at point ``r`` gives the body the impulse rate
``J = (w d - w' d') / c`` [N] (``w'`` and ``d'`` the outgoing power and direction, ``w' = 0`` for
full absorption) and the torque ``(r - r_ref) x J``. Every direction is sampled, never averaged
(no ``2/3`` Lambertian factor appears), so the tracer checks the solver's force law too.

**Radiosity model.** With ``radiosity_model=True`` the tracer follows the paper's radiosity model
instead of the physics: a bundle once reflected diffusely is reflected diffusely ever after,
whatever the ``beta`` of the surfaces it meets, and leaves a sheet it passes through in a Lambertian
spread, as the paper's eq. (12) re-emits the whole ``rho`` and a sheet's ``sigma`` of the diffuse light
a side receives (METHOD.md "The paper's misprints"). The difference between the two runs is that
model's error on mixed finishes. The solver does not make it (its exchange factors follow mirrored
and transmitted diffuse light, see :mod:`sunwind.geometry.views.exchange_factors`) and is checked
against the physics.

**Errors.** The photons are split into independent batches, each with its own stream of random
numbers; each batch's total is an unbiased estimate, and the standard error of the mean is the
batch spread over ``sqrt(batches)``. Batches run in parallel threads (Embree releases the GIL) and
are summed in batch order, so a seed gives the same bits on any machine load.

**Precision.** The scene is float32 in coordinates recentred on the bounding-box centre and
divided by the largest distance ``R`` of a vertex from it. A hit point is rebuilt in float64 from
Embree's distance and projected onto the facet's plane; the next ray starts ``1e-6 R`` off the
surface, on the side it leaves from.
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.sides import SOLID
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.validation.analytic_srp_law import SOLAR_FLUX_1AU_W_M2, SPEED_OF_LIGHT_M_S
from sunwind.validation.sampling import Sampling

__all__ = ["TracerResult", "trace_photons"]

#: Ray origins are pushed off the surface by this share of the model radius ``R`` (module Notes).
_OFFSET = 1e-6


@dataclass(frozen=True, eq=False)
class TracerResult:
    """Monte Carlo solar-radiation-pressure loads on a model at one attitude, body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Mean force [N] and torque [N m] about ``reference_point_m`` over the batches.
    force_se_N, torque_se_Nm : (3,) float64
        Standard errors of each component [N], [N m], from the spread of the batches.
    incident_W : float
        Power that struck the body [W].
    absorbed_W : float
        Power absorbed by the body [W].
    escaped_W : float
        Power that left the body after at least one interaction [W] (including light a closed
        body transmits, which is not traced further).
    cut_W : float
        Power still bouncing when the ``max_bounces`` cap stopped it [W]; its last outgoing
        momentum was counted as escaping.
    photons : int
        Bundles launched (``batches`` times the bundles per batch).
    batches : int
    bounces : (max_bounces + 1,) int64
        ``bounces[k]``: bundles that interacted exactly ``k`` times; ``bounces[0]`` missed the body,
        ``bounces[max_bounces]`` includes those cut.
    seconds : float
        Wall-clock time of the trace [s].
    sun_vector : (3,) float64
        Unit vector spacecraft -> Sun, body frame.
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_point_m : (3,) float64
        Torque reference point [m].

    Examples
    --------
    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> from sunwind.validation.sampling import Sampling
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> result = trace_photons(black, [0.0, 0.0, 1.0], Sampling(2000, batches=4))
    >>> result.photons, result.escaped_W, round(result.absorbed_W, 6)
    (2000, 0.0, 1361.0)
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    force_se_N: NDArray[np.float64]
    torque_se_Nm: NDArray[np.float64]
    incident_W: float
    absorbed_W: float
    escaped_W: float
    cut_W: float
    photons: int
    batches: int
    bounces: NDArray[np.int64]
    seconds: float
    sun_vector: NDArray[np.float64]
    flux_W_m2: float
    reference_point_m: NDArray[np.float64]

    @property
    def force_error_N(self) -> float:
        """Standard error of the force vector, ``sqrt(sum(force_se_N^2))`` [N]."""
        return float(np.linalg.norm(self.force_se_N))

    @property
    def torque_error_Nm(self) -> float:
        """Standard error of the torque vector, ``sqrt(sum(torque_se_Nm^2))`` [N m]."""
        return float(np.linalg.norm(self.torque_se_Nm))

    @property
    def mean_bounces(self) -> float:
        """Mean number of interactions of a bundle that struck the body [-]."""
        k = np.arange(len(self.bounces))
        struck = self.bounces[1:].sum()
        return float((k * self.bounces).sum() / struck) if struck else 0.0

    @property
    def photons_per_second(self) -> float:
        """Bundles launched per second of wall-clock time [1/s]."""
        return self.photons / self.seconds if self.seconds > 0 else math.inf


@dataclass(frozen=True)
class _BatchTotals:
    """What one batch adds up: force [N], torque [N m], powers [W] and the bounce histogram."""

    force: NDArray[np.float64]
    torque: NDArray[np.float64]
    incident: float
    absorbed: float
    escaped: float
    cut: float
    bounces: NDArray[np.int64]


def _basis(normals: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two unit tangents completing each unit normal (n, 3) to a right-handed orthonormal frame.

    Duff et al. (2017), "Building an orthonormal basis, revisited": no branch, no division by a
    vanishing number.
    """
    x, y, z = normals.T
    sign = np.where(z >= 0.0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    t1 = np.column_stack([1.0 + sign * x * x * a, sign * b, -sign * x])
    t2 = np.column_stack([b, sign + y * y * a, -y])
    return t1, t2


class _Tracer:
    """The model's own Embree scene and optics, and the trace of one batch of bundles."""

    def __init__(self, craft: Spacecraft) -> None:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        triangles = craft.triangles
        lo, hi = craft.bounds
        self.vertices = craft.vertices
        self.centre = (lo + hi) / 2
        self.radius = float(max(np.linalg.norm(craft.vertices - self.centre, axis=1).max(), 1e-300))
        self.offset = _OFFSET * self.radius
        self.scene = rtcore_scene.EmbreeScene()
        scene_triangles = ((triangles - self.centre) / self.radius).astype(np.float32)
        TriangleMesh(self.scene, np.ascontiguousarray(scene_triangles))
        self.corner = triangles[:, 0]
        self.normals = craft.facet_normals
        self.sides = craft.facet_sides
        self.optics = craft.side_optics
        self.solid = craft.facet_kind == SOLID

    def cast(self, origins: NDArray[np.float64], directions: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        """First facet each ray meets (-1 if none) and the hit point [m], float64 on the facet's plane."""
        scene_origins = ((origins - self.centre) / self.radius).astype(np.float32)
        hit = self.scene.run(scene_origins, directions.astype(np.float32), output=True)
        facet = hit["primID"].astype(np.int64)
        struck = facet >= 0
        facet[~struck] = -1
        f = facet[struck]
        points = (
            origins[struck]
            + (hit["tfar"][struck].astype(np.float64) * self.radius)[:, None] * (directions[struck])
        )
        n = self.normals[f]
        points -= np.einsum("ij,ij->i", points - self.corner[f], n)[:, None] * n
        return facet, points

    def source(
        self, sun: NDArray[np.float64], m: int, rng: np.random.Generator
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
        """Origins [m] and directions of ``m`` bundles on the stratified source, and its area [m^2]."""
        e1, e2 = _basis(sun[None, :])
        relative = self.vertices - self.centre
        across = relative @ np.column_stack([e1[0], e2[0]])
        lo, hi = across.min(axis=0), across.max(axis=0)
        size = hi - lo
        k1 = max(1, min(m, round(math.sqrt(m * size[0] / max(size[1], 1e-12 * self.radius)))))
        k2 = m // k1
        i, j = np.divmod(np.arange(k1 * k2), k2)
        left = m - k1 * k2
        a = np.concatenate([(i + rng.random(k1 * k2)) / k1, rng.random(left)])
        b = np.concatenate([(j + rng.random(k1 * k2)) / k2, rng.random(left)])
        upstream = (relative @ sun).max() + self.radius
        origins = (
            self.centre
            + upstream * sun
            + (lo[0] + a * size[0])[:, None] * e1
            + (lo[1] + b * size[1])[:, None] * e2
        )
        return origins, np.broadcast_to(-sun, (m, 3)).copy(), float(size[0] * size[1])

    def batch(
        self,
        sun: NDArray[np.float64],
        m: int,
        flux: float,
        reference: NDArray[np.float64],
        max_bounces: int,
        radiosity_model: bool,
        rng: np.random.Generator,
    ) -> _BatchTotals:
        """Trace ``m`` bundles to the end; totals of the batch."""
        position, direction, area = self.source(sun, m, rng)
        weight = np.full(m, flux * area / m)
        diffused = np.zeros(m, dtype=bool)  # reflected diffusely before (for ``radiosity_model``)
        force, torque = np.zeros(3), np.zeros(3)
        incident = absorbed = escaped = cut = 0.0
        active = np.zeros(max_bounces, dtype=np.int64)  # bundles meeting the body a (k + 1)-th time
        for generation in range(max_bounces + 1):
            facet, point = self.cast(position, direction)
            struck = facet >= 0
            if generation == 0:
                incident = float(weight[struck].sum())
            else:
                escaped += float(weight[~struck].sum())
            facet, w, d, was_diffused = facet[struck], weight[struck], direction[struck], diffused[struck]
            if generation == max_bounces:
                cut = float(w.sum())
                break
            active[generation] = len(facet)
            if not len(facet):
                break
            n = self.normals[facet]
            back = np.einsum("ij,ij->i", d, n) > 0
            side = self.sides[facet, back.astype(np.int64)]
            blind = side < 0
            rho, beta, sigma = np.where(blind[:, None], 0.0, self.optics[side]).T
            n_out = np.where(back[:, None], -n, n)  # outward normal of the struck side
            kept = rho + sigma
            absorbed += float((w * (1.0 - kept)).sum())
            w_out = w * kept
            draw = rng.random(len(w)) * kept
            specular = draw < rho * beta
            if radiosity_model:
                specular &= ~was_diffused
            diffuse = ~specular & (draw < rho)
            transmitted = ~specular & ~diffuse
            d_out = d.copy()
            d_out[specular] -= 2.0 * np.einsum("ij,ij->i", d[specular], n[specular])[:, None] * n[specular]
            d_out[diffuse] = _lambert(n_out[diffuse], rng)
            if radiosity_model:
                spread = transmitted & was_diffused & ~self.solid[facet]
                d_out[spread] = _lambert(-n_out[spread], rng)
            impulse = (w[:, None] * d - w_out[:, None] * d_out) / SPEED_OF_LIGHT_M_S
            force += impulse.sum(axis=0)
            torque += np.cross(point - reference, impulse).sum(axis=0)
            gone = transmitted & self.solid[facet]  # through a closed body's wall: leaves untraced
            escaped += float(w_out[gone].sum())
            carry_on = (w_out > 0) & ~gone
            side_sign = np.where(transmitted, -1.0, 1.0)[:, None]  # leave from the far side if through
            position = (point + self.offset * side_sign * n_out)[carry_on]
            direction, weight = d_out[carry_on], w_out[carry_on]
            diffused = (was_diffused | diffuse)[carry_on]
        bounces = -np.diff(np.concatenate([[m], active, [0]]))
        return _BatchTotals(force, torque, incident, absorbed, escaped, cut, bounces)


def _lambert(normals: NDArray[np.float64], rng: np.random.Generator) -> NDArray[np.float64]:
    """Cosine-weighted random directions about unit ``normals`` (n, 3)."""
    a, b = rng.random(len(normals)), rng.random(len(normals))
    r, phi = np.sqrt(a), 2 * np.pi * b
    t1, t2 = _basis(normals)
    return (
        (r * np.cos(phi))[:, None] * t1
        + (r * np.sin(phi))[:, None] * t2
        + np.sqrt(1.0 - a)[:, None] * normals
    )


def trace_photons(
    craft: Spacecraft,
    sun_vector: ArrayLike,
    sampling: Sampling,
    *,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    reference_point_m: ArrayLike | None = None,
    radiosity_model: bool = False,
) -> TracerResult:
    """Solar-radiation-pressure force and torque on ``craft`` by Monte Carlo photon tracing.

    Parameters
    ----------
    craft : Spacecraft
    sun_vector : (3,) array_like
        Direction spacecraft -> Sun, body frame (normalised here).
    sampling : Sampling
        Photon bundles to launch in all (rounded up to a multiple of the batches; the share that
        meets the body is its projected area over the source rectangle's), the seed, the batches
        the standard errors come from (>= 2), and the most interactions a bundle may have (the
        power still travelling then is ``cut_W``).
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default ``craft.default_reference[0]``.
    radiosity_model : bool
        Trace the paper's radiosity model, its eq. (12), instead of the physics: once a bundle
        has been reflected diffusely, every later reflection of it is Lambertian (the whole ``rho``
        re-emitted diffusely) and its transmission through a sheet leaves the far side Lambertian.
        Measures what that model misses on mixed finishes.

    Returns
    -------
    TracerResult

    Examples
    --------
    A black unit cube, Sun overhead: every bundle is absorbed, ``F = -P A u`` with ``P = flux / c`` [uN]:

    >>> from sunwind.geometry import Material, build_spacecraft
    >>> from sunwind.meshes.primitives import box
    >>> from sunwind.validation.sampling import Sampling
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> result = trace_photons(black, [0.0, 0.0, 1.0], Sampling(2000, batches=4))
    >>> ((result.force_N * 1e6).round(4) + 0.0).tolist()
    [0.0, 0.0, -4.5398]
    """
    photons, batches, max_bounces = sampling.particles, sampling.batches, sampling.max_bounces
    if batches < 2 or photons < batches or max_bounces < 1:
        raise ValueError("need batches >= 2, photons >= batches and max_bounces >= 1")
    start = time.perf_counter()
    sun = np.asarray(sun_vector, dtype=np.float64)
    sun = sun / np.linalg.norm(sun)
    reference = np.asarray(
        craft.default_reference[0] if reference_point_m is None else reference_point_m, dtype=np.float64
    )
    tracer = _Tracer(craft)
    per_batch = -(-photons // batches)
    streams = [np.random.default_rng(s) for s in np.random.SeedSequence(sampling.seed).spawn(batches)]

    def run(rng: np.random.Generator) -> _BatchTotals:
        return tracer.batch(sun, per_batch, flux_W_m2, reference, max_bounces, radiosity_model, rng)

    with ThreadPoolExecutor(min(batches, os.cpu_count() or 1)) as pool:
        totals = list(pool.map(run, streams))
    force = np.array([t.force for t in totals])
    torque = np.array([t.torque for t in totals])

    def mean(name: str) -> float:
        return float(np.mean([getattr(t, name) for t in totals]))

    return TracerResult(
        force_N=force.mean(axis=0),
        torque_Nm=torque.mean(axis=0),
        force_se_N=force.std(axis=0, ddof=1) / math.sqrt(batches),
        torque_se_Nm=torque.std(axis=0, ddof=1) / math.sqrt(batches),
        incident_W=mean("incident"),
        absorbed_W=mean("absorbed"),
        escaped_W=mean("escaped"),
        cut_W=mean("cut"),
        photons=per_batch * batches,
        batches=batches,
        bounces=np.sum([t.bounces for t in totals], axis=0),
        seconds=time.perf_counter() - start,
        sun_vector=sun,
        flux_W_m2=float(flux_W_m2),
        reference_point_m=reference,
    )
