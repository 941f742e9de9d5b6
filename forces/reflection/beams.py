"""Specular and transmitted light followed from surface to surface (METHOD.md "Inter-reflection").

The direct force law (eq. 4) lets every reflected and transmitted photon leave to infinity. Here the
mirror beam of each lit side, and the beam a lit sheet transmits, are cast as rays. A ray that meets
another side becomes an incident beam there: the absorbed share stays, the diffuse share becomes a
source of the radiosity balance, the specular share is cast again along the mirror direction and a
sheet's transmitted share goes on through it. A chain ends when it escapes, when its power falls
below ``cutoff`` times the power it started with, or after ``depth`` surfaces.

Momentum is counted as METHOD.md says, by what comes from and goes to infinity: the result is the
correction to the direct force, ``+p d / c`` for every first beam that does not escape after all
(eq. 4 had it leave) and ``-p d / c`` for every later beam that does escape, at the point it leaves.

Where first beams start follows the shadow pass. With a fixed count of points per side, first beams
leave from the same points: the lit centroid of each side at one point, else the side's lit points,
one ray each. Adaptive shadows get adaptive first beams: one ray per lit side from the centroid of
its lit part would put a whole side's beam on one landing point, so sides are sampled like shadows:
small models start with many points per side, large ones with one, and a side whose beam is split
(some points escape or land on another material than the rest) or that disagrees with an edge
neighbour is sampled again at twice the level, until its split converges or the likely error of all
split beams together is below ``TOLERANCE`` of the power of all first beams. Each lit point carries an
equal share of the side's beam power, so the beam powers equal those of the direct law exactly.

With fixed sampling, first beams known to escape are not cast (:mod:`~sunwind.forces.reflection.escape`).
Adaptive sampling casts them all: it compares every side's outcome with its neighbours'.

Rays are cast in float32 scene coordinates (:mod:`sunwind.geometry.rays.scene`); the point a beam meets
a side is found again in float64 on the facet's plane.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.reflection import beam_kernels as kernels
from sunwind.forces.reflection import chain_derivatives as derive
from sunwind.forces.reflection.chain_derivatives import ChainDerivatives
from sunwind.forces.reflection.escape import escape_test
from sunwind.forces.reflection.settings import DEFAULT_CUTOFF, DEFAULT_DEPTH
from sunwind.geometry import triangles as tri
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.sides import SOLID
from sunwind.geometry.spacecraft import ESCAPED, Spacecraft

#: Finest sampling of a side's first beam: 4096 points.
MAX_LEVEL = 64
#: First beams cast at the starting level when a model is small: the starting level is the largest
#: power of two giving at most this many rays (one ray per side on large models).
START_RAYS = 1 << 14
#: A split side is final when its escaping share moves by at most this between levels.
TOLERANCE = 1e-4
#: First beams followed together at a fixed sampling level, to bound memory (whole sides at a time).
_BATCH_RAYS = 1 << 20


@dataclass(frozen=True)
class BeamChainTotals:
    """What the chains of one attitude add to the direct result; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Correction to the direct force and torque (torque about the reference point) from beams that
        land somewhere instead of escaping, and from beams that escape after landing.
    diffuse_source_W : (n_sides,) float64
        Power landed beams hand to diffuse reflection on each side (a source of the radiosity balance).
    arrived_W : (n_sides,) float64
        Beam power arriving at each side [W] (it absorbs ``1 - rho - sigma`` of it).
    open_sky_force_N, open_sky_torque_Nm : (3,) float64
        Force and torque if that diffuse light left each landing point to open sky, ``(2/3) n``.
    escaped_W, absorbed_W, truncated_W : float
        Beam power that left the model (first beams included), was absorbed (landed beams, and beams
        reaching a side the model does not have), and was dropped by ``cutoff`` or ``depth``.
    first_W : float
        Power of all first beams.
    rays : int
        Rays cast (first beams, their re-sampling and every later generation).
    depth : int
        Most surfaces any chain met beyond the side that sent it (the generations of beams cast).
    derivatives : ChainDerivatives or None
        Derivatives of the above with respect to every material's ``(rho, beta, sigma)``, when asked
        for (:mod:`~sunwind.forces.reflection.chain_derivatives`).

    Examples
    --------
    A mirrored convex cube: every first beam escapes at once, so no ray is needed and the direct law was
    already right:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> mirror = sw.Material("mirror", reflectivity=1.0, specular_fraction=1.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=mirror, threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.6, 0.8]), 4, None)
    >>> chains = follow_chains(craft, light, 1000.0, np.zeros(3), level=light.level)
    >>> chains.escaped_W, chains.first_W, chains.rays, chains.force_N
    (1400.0, 1400.0, 0, array([0., 0., 0.]))
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    diffuse_source_W: NDArray[np.float64]
    arrived_W: NDArray[np.float64]
    open_sky_force_N: NDArray[np.float64]
    open_sky_torque_Nm: NDArray[np.float64]
    escaped_W: float
    absorbed_W: float
    truncated_W: float
    first_W: float
    rays: int
    depth: int
    derivatives: ChainDerivatives | None = None


@dataclass(frozen=True)
class ChainModel:
    """What the beam kernels need of a spacecraft beyond its own arrays.

    Read by the kernels of :mod:`sunwind.forces.reflection.beam_kernels`.

    Parameters
    ----------
    side_sheet : (n_sides,) bool
        Whether each side belongs to a sheet rather than a closed body.
    facet_offsets : (n_facets,) float64
        ``n . x`` of each facet's plane [m].

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> model = chain_model(craft)
    >>> bool(model.side_sheet.any()), model.facet_offsets[:2]
    (False, array([0.5, 0.5]))
    """

    side_sheet: NDArray[np.bool_]  # (n_sides,) the side belongs to a sheet, not a closed body
    facet_offsets: NDArray[np.float64]  # (n_facets,) ``n . x`` of the facet's plane [m]


def chain_model(craft: Spacecraft) -> ChainModel:
    """Chain model of ``craft``, built once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    ChainModel
        Which sides are sheets, and each facet's plane offset.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> chain_model(craft) is chain_model(craft)
    True
    """
    return craft.cache.get(
        "beam chain model",
        lambda: ChainModel(
            side_sheet=craft.facet_kind[craft.side_facet] != SOLID,
            facet_offsets=np.einsum("nd,nd->n", craft.facet_normals, craft.triangles[:, 0]),
        ),
    )


@dataclass
class _Beams:
    """A generation of rays, each leaving ``origin_m`` (on its surface) along ``direction``."""

    origin_m: NDArray[np.float64]  # (n, 3) surface point
    lift: NDArray[np.float64]  # (n, 3) unit vector the origin is pushed along, off the surface
    direction: NDArray[np.float64]  # (n, 3)
    power_W: NDArray[np.float64]  # (n,)
    start_W: NDArray[np.float64]  # (n,) power its chain started with
    # with derivatives (chain_derivatives.land): (n, q) those of power_W, valid in the columns of the
    # materials of the bit mask dmask (first beams: (n, 3) in the columns of their emitter's material)
    dpower: NDArray[np.float64] | None = None
    dmask: NDArray[np.int64] | None = None

    def __len__(self) -> int:
        return len(self.power_W)

    def take(self, mask: NDArray) -> _Beams:
        return _Beams(*(getattr(self, name)[mask] for name in _BEAM_FIELDS))

    @staticmethod
    def join(parts: list[_Beams]) -> _Beams:
        return _Beams(*(np.concatenate([getattr(p, name) for p in parts]) for name in _BEAM_FIELDS))


_BEAM_FIELDS = ("origin_m", "lift", "direction", "power_W", "start_W")  # first beams carry no more
_NO_COLUMNS = np.zeros(0, dtype=np.int64)


def _cast(craft: Spacecraft, beams: _Beams) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Side each beam meets (``ESCAPED``/``BLIND`` codes of :meth:`Spacecraft.struck_sides`) and
    the point it meets it [m] (zero where it meets no side)."""
    scene = craft.scene
    origins, directions = kernels.scene_rays(
        beams.origin_m, beams.lift, beams.direction, scene.centre, scene.half_size, scene.offset_m
    )
    return kernels.strike(
        scene.first_hit(origins, directions),
        beams.origin_m,
        beams.lift,
        beams.direction,
        scene.offset_m,
        craft.facet_normals,
        chain_model(craft).facet_offsets,
        craft.facet_sides,
    )


@dataclass(frozen=True)
class _Emitters:
    """Lit sides sending a first beam (the specular beam of each, the transmitted beam of sheets), and
    that beam leaving the side's lit centroid."""

    side: NDArray[np.int64]
    beams: _Beams
    escaping_W: float  # power of beams left out as known to escape
    derivatives: derive.FirstBeams | None  # of the beams' power and escaping_W (the beams carry none)
    # emitters [:plain] send the plain model's beams; the rest (with derivatives) derivative-only ones,
    # of power 0, where a share is zero but not its derivative (chain_derivatives)
    plain: int = -1

    @property
    def n_plain(self) -> int:
        return len(self.side) if self.plain < 0 else self.plain


def _emitters(
    craft: Spacecraft, light: Illumination, flux_W_m2: float, derivatives: bool = False, *, cull: bool
) -> _Emitters:
    """The emitters of ``light``; with ``cull``, those of patches whose first beams are known to
    escape are left out and their power is counted in :attr:`_Emitters.escaping_W`. With
    ``derivatives``, :attr:`_Emitters.derivatives` holds the derivatives of both."""
    side_patch = escapes = None
    if cull:
        test = escape_test(craft)
        side_patch = test.side_patch
        escapes = kernels.escaping_patches(
            light.facing,
            light.lit_fraction,
            craft.side_normals,
            craft.side_optics,
            chain_model(craft).side_sheet,
            light.direction,
            side_patch,
            test.patch_low,
            test.patch_high,
            test.patch_normal,
            test.patch_offset,
            test.tree.low,
            test.tree.high,
            test.tree.first_child,
            test.tree.depth,
            test.margin_m,
            test.reach_m,
        )
    side, centroid, direction, lift, power, escaping = kernels.emitters(
        light.facing,
        light.lit_fraction,
        light.lit_centroid,
        craft.side_areas,
        craft.side_normals,
        craft.side_optics,
        chain_model(craft).side_sheet,
        light.direction,
        flux_W_m2,
        side_patch,
        escapes,
    )
    beams = _Beams(centroid, lift, direction, power, power)
    if not derivatives:
        return _Emitters(side, beams, escaping, None)
    plain = len(side)
    optics = _derivative_only_optics(craft)
    if optics is not None:  # some zero shares have derivatives: their sides send derivative-only beams
        if cull:
            escapes = kernels.escaping_patches(
                light.facing,
                light.lit_fraction,
                craft.side_normals,
                optics,
                chain_model(craft).side_sheet,
                light.direction,
                side_patch,
                test.patch_low,
                test.patch_high,
                test.patch_normal,
                test.patch_offset,
                test.tree.low,
                test.tree.high,
                test.tree.first_child,
                test.tree.depth,
                test.margin_m,
                test.reach_m,
            )
        more, centroid, direction, lift, _, _ = kernels.emitters(
            light.facing,
            light.lit_fraction,
            light.lit_centroid,
            craft.side_areas,
            craft.side_normals,
            optics,
            chain_model(craft).side_sheet,
            light.direction,
            flux_W_m2,
            side_patch,
            escapes,
        )
        zero = np.zeros(len(more))
        side = np.concatenate([side, more])
        beams = _Beams.join([beams, _Beams(centroid, lift, direction, zero, zero)])
    through = np.einsum("nd,nd->n", beams.lift, craft.side_normals[side]) < 0
    first = derive.first_beams(craft, light, flux_W_m2, side, through, chain_model(craft).side_sheet)
    return _Emitters(side, beams, escaping, first, plain)


def _derivative_only_optics(craft: Spacecraft) -> NDArray[np.float64] | None:
    """Optics under which exactly the first beams that are derivative-only have a share (of 1): the mirror
    beam where ``rho beta = 0`` but ``rho`` or ``beta`` is not, the transmitted beam of a sheet where
    ``sigma = 0``. None where there are none."""
    rho, beta, sigma = craft.side_optics.T
    mirror = (rho * beta <= 0.0) & ((rho > 0.0) | (beta > 0.0))
    through = chain_model(craft).side_sheet & (sigma <= 0.0)
    if not (mirror.any() or through.any()):
        return None
    return np.stack([mirror, mirror, through], axis=1).astype(np.float64)


class _FirstBeams(NamedTuple):
    """First beams with the side each meets (-1: none), where it meets it, the rays cast to find out and
    the emitter of each; with derivatives, the first column of the three its ``beams.dpower`` holds, and
    the rays cast for derivative-only beams (not in ``rays``)."""

    beams: _Beams
    sides: NDArray[np.int64]
    points: NDArray[np.float64]
    rays: int
    owner: NDArray[np.int64]
    dcolumn: NDArray[np.int64] = _NO_COLUMNS
    derivative_rays: int = 0


class _ChainEnds(NamedTuple):
    """Where beam chains stop: below ``cutoff`` of their first power, or after ``depth`` surfaces."""

    cutoff: float
    depth: int


def _fixed_first_beams(
    craft: Spacecraft, light: Illumination, emitters: _Emitters, level: int
) -> Iterator[_FirstBeams]:
    """First beams of every emitter from its lit points at ``level``, in batches of whole emitters."""
    n = len(emitters.side)
    # after its first landing a beam's derivatives (q columns) take about q / 16 beams' memory
    q = derive.columns(craft, emitters.derivatives is not None)
    per_batch = max(1, _BATCH_RAYS // (level**2 * (1 + q // 16)))
    for start in range(0, n, per_batch):
        chosen = slice(start, start + per_batch)
        if level == 1:  # the lit centroids
            beams, owner = emitters.beams.take(chosen), np.arange(n)[chosen]
            sides, points = _cast(craft, beams)
            dead = int(np.count_nonzero(owner >= emitters.n_plain))
            yield _FirstBeams(beams, sides, points, len(beams) - dead, owner, derivative_rays=dead)
        else:
            beams, owner, sides, points, rays = _sample(craft, light, emitters, np.arange(n)[chosen], level)
            yield _FirstBeams(beams, sides, points, rays[0], owner, derivative_rays=rays[1])


def _first_beams(craft: Spacecraft, light: Illumination, emitters: _Emitters) -> _FirstBeams:
    """First beams of every emitter (there must be some), adaptively sampled.

    Derivative-only emitters (power 0) are sampled by the same rules, as the model would sample them at a
    vanishing share: their share escaping is that of their points; they are compared with every
    neighbour, but the plain emitters only with plain ones; and they count in the likely error only
    where there are no plain emitters, by their derivatives' size (powers 0 < h, as h goes to 0). The
    plain emitters' sampling stays as it is without derivatives, starting level included.
    """
    n, plain = len(emitters.side), emitters.n_plain
    level = 1 << max(0, int(np.log2(max(1.0, np.sqrt(START_RAYS / (plain or n))))))
    level = min(level, MAX_LEVEL)
    power = emitters.beams.power_W
    weight, total = power, power[:plain].sum()
    if not plain:  # derivative-only emitters alone: weighed by their derivatives' size
        assert emitters.derivatives is not None
        weight = np.abs(emitters.derivatives.partials).max(axis=1)
        total = weight.sum()
    active = np.arange(n)
    previous_share = np.full(n, np.nan)
    accepted: list[tuple[_Beams, NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]]] = []
    rays = derivative_rays = 0
    first = True
    while len(active):
        beams, owner, sides, points, cast = _sample(craft, light, emitters, active, level)
        rays += cast[0]
        derivative_rays += cast[1]
        outcome = np.where(sides >= 0, craft.side_material[np.maximum(sides, 0)], sides)
        low = np.full(n, np.iinfo(np.int64).max)
        high = np.full(n, np.iinfo(np.int64).min)
        if level == 1:  # one beam per emitter, in order
            low[owner] = high[owner] = outcome
        else:
            np.minimum.at(low, owner, outcome)
            np.maximum.at(high, owner, outcome)
        split = low[active] != high[active]
        escaping = np.bincount(owner, weights=(sides == ESCAPED) * beams.power_W, minlength=n)
        live = active < plain
        share = np.empty(len(active))
        share[live] = escaping[active[live]] / power[active[live]]
        if not live.all():  # derivative-only: the share of their points, which carry equal shares
            out = np.bincount(owner, weights=sides == ESCAPED, minlength=n)
            share[~live] = out[active[~live]] / np.bincount(owner, minlength=n)[active[~live]]
        if first:
            split |= _disagrees_with_neighbour(craft, emitters, active, low, high)
            first = False
        settled = np.abs(share - previous_share[active]) <= TOLERANCE
        again = split & ~settled & (level < MAX_LEVEL)
        counted = active[again & live] if plain else active[again]
        if _split_error(weight[counted], level) <= TOLERANCE * total:
            again[:] = False
        done = np.zeros(n, dtype=bool)
        done[active[~again]] = True
        keep = done[owner]
        accepted.append((beams.take(keep), sides[keep], points[keep], owner[keep]))
        previous_share[active] = share
        active = active[again]
        level *= 2
    return _FirstBeams(
        beams=_Beams.join([a[0] for a in accepted]),
        sides=np.concatenate([a[1] for a in accepted]),
        points=np.concatenate([a[2] for a in accepted]),
        rays=rays,
        owner=np.concatenate([a[3] for a in accepted]),
        derivative_rays=derivative_rays,
    )


def _split_error(power_W: NDArray[np.float64], level: int) -> float:
    """Likely error [W] of the escaping power of split beams of powers ``power_W`` sampled at
    ``level``: one point decides a whole beam (half its power at stake) at level 1; stratified points
    make the share of a split beam good to about ``level**-1.5``; independent errors add in quadrature."""
    share_error = 0.5 if level == 1 else level**-1.5
    return float(np.sqrt(np.sum(power_W**2))) * share_error


def _disagrees_with_neighbour(
    craft: Spacecraft, emitters: _Emitters, active: NDArray[np.int64], low: NDArray, high: NDArray
) -> NDArray[np.bool_]:
    """Emitters among ``active`` whose uniform outcome differs from an edge neighbour's sending the
    same kind of beam (mirror or transmitted): the split may fall between their sample points. Plain
    emitters are compared with plain ones only, derivative-only ones with all."""
    a, b = craft.side_neighbours
    index = np.full((2, craft.n_sides), -1)
    kind = (np.einsum("nd,nd->n", emitters.beams.lift, craft.side_normals[emitters.side]) < 0).astype(
        np.int64
    )
    index[kind, emitters.side] = np.arange(len(emitters.side))
    plain = emitters.n_plain
    flagged = np.zeros(len(emitters.side), dtype=bool)
    for k in (0, 1):
        ea, eb = index[k, a], index[k, b]
        both = (ea >= 0) & (eb >= 0)
        ea, eb = ea[both], eb[both]
        differ = (low[ea] == high[ea]) & (low[eb] == high[eb]) & (low[ea] != low[eb])
        if plain < len(emitters.side):  # a derivative-only neighbour flags no plain emitter
            flagged[ea[differ & ((ea >= plain) | (eb < plain))]] = True
            flagged[eb[differ & ((eb >= plain) | (ea < plain))]] = True
            continue
        flagged[ea[differ]] = True
        flagged[eb[differ]] = True
    return flagged[active]


def _sample(
    craft: Spacecraft, light: Illumination, emitters: _Emitters, chosen: NDArray[np.int64], level: int
) -> tuple[_Beams, NDArray[np.int64], NDArray[np.int64], NDArray[np.float64], tuple[int, int]]:
    """First beams of ``chosen`` emitters from their lit points at ``level``, cast.

    Returns the beams, the emitter of each, the side each meets and where, and the rays cast: for plain
    emitters, and for derivative-only ones. At level 1 the point is the lit centroid. A partly lit
    side's points are shadow-tested; a side none of whose points is lit sends its beam from its lit
    centroid.
    """
    rays = dead_rays = 0
    if level == 1:
        beams, owner = emitters.beams.take(chosen), chosen
    else:
        side = emitters.side[chosen]
        bary = tri.subdivision_barycentric(level)
        points = np.einsum("pk,nkd->npd", bary, craft.triangles[craft.side_facet[side]])
        lit = np.ones(points.shape[:2], dtype=bool)
        partly = np.flatnonzero(light.lit_fraction[side] < 1)
        if len(partly):
            scene = craft.scene
            normals = np.repeat(craft.side_normals[side[partly]], level**2, axis=0)
            origins = scene.origins(points[partly].reshape(-1, 3), normals)
            toward = np.broadcast_to(light.direction.astype(np.float32), origins.shape)
            lit[partly] = ~scene.occluded(origins, toward).reshape(len(partly), level**2)
            dead_rays += level**2 * int(np.count_nonzero(chosen[partly] >= emitters.n_plain))
            rays += origins.shape[0] - dead_rays
        none = ~lit.any(axis=1)
        points[none, 0] = light.lit_centroid[side[none]]
        lit[none, 0] = True
        owner_of_point = np.repeat(np.arange(len(side)), level**2)[lit.reshape(-1)]
        owner = chosen[owner_of_point]
        power = (emitters.beams.power_W[chosen] / lit.sum(axis=1))[owner_of_point]
        lift, direction = emitters.beams.lift[owner], emitters.beams.direction[owner]
        beams = _Beams(points[lit], lift, direction, power, power)
    sides, hit_points = _cast(craft, beams)
    dead = int(np.count_nonzero(owner >= emitters.n_plain))
    return beams, owner, sides, hit_points, (rays + len(beams) - dead, dead_rays + dead)


def follow_chains(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    cutoff: float = DEFAULT_CUTOFF,
    depth: int = DEFAULT_DEPTH,
    level: int | None = None,
    derivatives: bool = False,
) -> BeamChainTotals:
    """Trace the mirror and transmitted beams of every lit side until they escape or fade.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    light : Illumination
        Lit shares and lit centroids of the attitude (from the direct computation).
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_m : (3,) float64
        Torque reference point [m].
    cutoff : float
        A beam is dropped below this share of the power its chain started with.
    depth : int
        A chain is dropped after meeting this many surfaces beyond the side that sent it.
    level : int or None
        The shadow pass's fixed sampling level (``level**2`` points per side): first beams leave from
        the same points. None: the shadows were sampled adaptively, and so are the first beams.
    derivatives : bool
        Also take the derivatives of the result with respect to every material's ``(rho, beta,
        sigma)`` in the same pass (:mod:`~sunwind.forces.reflection.chain_derivatives`), every decision
        (sampling, beams cast, cutoff and depth, escape test) as the powers make it. Where a share is
        zero but not its derivative, derivative-only beams (power 0) are cast too, sampled as the
        side's beam would be; the result keeps every bit, ``rays`` and ``depth`` included, and their
        rays are :attr:`ChainDerivatives.rays`.

    Returns
    -------
    BeamChainTotals
        The chains' correction to the direct force and torque, their diffuse sources and power split;
        with ``derivatives``, their :class:`ChainDerivatives`.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> mirror = sw.Material("mirror", reflectivity=1.0, specular_fraction=1.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=mirror, threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.6, 0.8]), 4, None)
    >>> chains = follow_chains(craft, light, 1000.0, np.zeros(3), level=light.level)
    >>> chains.absorbed_W, chains.truncated_W, chains.depth
    (0.0, 0.0, 0)
    >>> chains = follow_chains(craft, light, 1000.0, np.zeros(3), level=light.level, derivatives=True)
    >>> chains.derivatives.first_W
    array([[1400., 1400.,    0.]])
    """
    # beams known to escape need no ray, but adaptive sampling compares every emitter's outcomes
    emitters = _emitters(craft, light, flux_W_m2, derivatives, cull=level is not None)
    if level is not None:
        batches: Iterator[_FirstBeams] | list[_FirstBeams] = _fixed_first_beams(craft, light, emitters, level)
    else:
        batches = [_first_beams(craft, light, emitters)] if len(emitters.side) else []
    q = derive.columns(craft, derivatives)
    sums = _Sums(np.zeros(kernels.N_TOTALS), np.zeros(craft.n_sides))
    if derivatives:
        sums = _Sums(sums.totals, sums.arrived_W, derive.DerivativeSums.empty(craft.n_sides, q))
    sums.totals[kernels.ESCAPED_W] = emitters.escaping_W
    rays = generations = derivative_rays = 0
    ends = _ChainEnds(cutoff=cutoff, depth=depth)
    for first in batches:
        if emitters.derivatives is not None:
            first = _first_derivatives(first, emitters)
        more_rays, chain_generations, more_derivative_rays = _trace(craft, first, reference_m, ends, sums)
        rays += first.rays + more_rays
        derivative_rays += first.derivative_rays + more_derivative_rays
        generations = max(generations, chain_generations)
    totals, arrived = sums.totals, sums.arrived_W
    found = None
    if emitters.derivatives is not None:
        d = sums.derivatives
        found = derive.chain_derivatives(
            craft, d.totals, d.arrivals(), arrived, emitters.derivatives, derivative_rays
        )
    rho, beta, _ = craft.side_optics.T
    momentum, open_sky = kernels.MOMENTUM, kernels.OPEN_SKY
    return BeamChainTotals(
        force_N=totals[momentum : momentum + 3] / SPEED_OF_LIGHT,
        torque_Nm=totals[momentum + 3 : momentum + 6] / SPEED_OF_LIGHT,
        diffuse_source_W=rho * (1.0 - beta) * arrived,
        arrived_W=arrived,
        open_sky_force_N=totals[open_sky : open_sky + 3] / SPEED_OF_LIGHT,
        open_sky_torque_Nm=totals[open_sky + 3 : open_sky + 6] / SPEED_OF_LIGHT,
        escaped_W=float(totals[kernels.ESCAPED_W]),
        absorbed_W=float(totals[kernels.ABSORBED_W]),
        truncated_W=float(totals[kernels.TRUNCATED_W]),
        first_W=float(emitters.beams.power_W[: emitters.n_plain].sum()) + emitters.escaping_W,
        rays=rays,
        depth=generations,
        derivatives=found,
    )


def _first_derivatives(first: _FirstBeams, emitters: _Emitters) -> _FirstBeams:
    """``first`` with the derivatives of its beams' power: each carries its share of its emitter's beam
    (a derivative-only emitter's points equal shares). A derivative-only beam's chain starts with the
    size of its derivative (it has one nonzero column), against which ``cutoff`` is taken."""
    assert emitters.derivatives is not None
    owner, beams = first.owner, first.beams
    live = owner < emitters.n_plain
    share = beams.power_W / np.where(live, emitters.beams.power_W[owner], 1.0)
    if not live.all():
        points = np.bincount(owner[~live], minlength=len(emitters.side))
        share[~live] = 1.0 / points[owner[~live]]
    beams.dpower = emitters.derivatives.partials[owner] * share[:, None]
    if not live.all():
        beams.start_W = np.where(live, beams.start_W, np.abs(beams.dpower).max(axis=1))
    return first._replace(dcolumn=emitters.derivatives.column[owner])


@dataclass(frozen=True, eq=False)
class _Sums:
    """What every chain of an attitude adds to: the kernel's running sums (slots of
    :mod:`~sunwind.forces.reflection.beam_kernels`), the beam power arriving at each side [W] and, when
    asked for, their derivatives."""

    totals: NDArray[np.float64]  # (N_TOTALS,)
    arrived_W: NDArray[np.float64]  # (n_sides,)
    derivatives: derive.DerivativeSums | None = None


def _trace(
    craft: Spacecraft,
    first: _FirstBeams,
    reference_m: NDArray[np.float64],
    ends: _ChainEnds,
    sums: _Sums,
) -> tuple[int, int, int]:
    """Follow ``first`` beams, already cast, and all they lead to, until the chains ``ends``; add to
    ``sums``. Returns the rays cast after the first beams, the generations of beams cast (both as
    without derivatives) and the rays cast for derivative-only beams (power 0)."""
    beams, sides, points, dcolumn = first.beams, first.sides, first.points, first.dcolumn
    cutoff, depth = ends.cutoff, ends.depth
    model = chain_model(craft)
    rays = generation = plain_generation = derivative_rays = 0
    while len(beams):
        generation += 1
        if sums.derivatives is None or beams.power_W.any():
            plain_generation = generation
        plain = (
            beams.origin_m,
            beams.direction,
            beams.power_W,
            beams.start_W,
            sides,
            points,
            generation == 1,
            generation >= depth,
            cutoff,
            craft.side_normals,
            craft.side_optics,
            model.side_sheet,
            LAMBERT_FACTOR,
            reference_m,
            sums.totals,
            sums.arrived_W,
        )
        if (d := sums.derivatives) is None:
            beams = _Beams(*kernels.land(*plain))
        else:
            mask = _NO_COLUMNS if beams.dmask is None else beams.dmask
            derivatives = (
                craft.side_material,
                beams.dpower,
                mask,
                dcolumn,
                d.every,
                d.totals,
                d.slot,
                d.rows,
            )
            beams = _Beams(*derive.land(*plain, *derivatives))
            dcolumn = _NO_COLUMNS  # later beams carry their derivatives in all columns
        if len(beams):
            sides, points = _cast(craft, beams)
            dead = 0 if sums.derivatives is None else int(np.count_nonzero(beams.power_W == 0.0))
            rays += len(beams) - dead
            derivative_rays += dead
    return rays, plain_generation, derivative_rays
