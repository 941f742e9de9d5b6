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

Where first beams start: one ray per lit side from the centroid of its lit part would put a whole
side's beam on one landing point. Sides are sampled like shadows instead: small models start with
many points per side, large ones with one, and a side whose beam is split (some points escape or
land on another material than the rest) or that disagrees with an edge neighbour is sampled again
at twice the level, until its split converges or the likely error of all split beams together is
below ``TOLERANCE`` of the power of all first beams. Each lit point carries an equal share of the side's
beam power, so the beam powers equal those of the direct law exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from geometry import triangles as tri
from geometry.illumination import Illumination
from geometry.sides import SOLID
from geometry.spacecraft import BLIND, ESCAPED, Spacecraft

from .radiation import LAMBERT_FACTOR, SPEED_OF_LIGHT

#: Default end of a chain: a beam below this share of the power its chain started with.
DEFAULT_CUTOFF = 1e-6
#: Default end of a chain: this many surfaces met after the first.
DEFAULT_DEPTH = 32
#: Finest sampling of a side's first beam: 4096 points.
MAX_LEVEL = 64
#: First beams cast at the starting level when a model is small: the starting level is the largest
#: power of two giving at most this many rays (one ray per side on large models).
START_RAYS = 1 << 14
#: A split side is final when its escaping share moves by at most this between levels.
TOLERANCE = 1e-4


@dataclass(frozen=True)
class ChainTotals:
    """What the chains of one attitude add to the direct result; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Correction to the direct force and torque (torque about the reference point) from beams that
        land somewhere instead of escaping, and from beams that escape after landing.
    diffuse_source_W : (n_sides,) float64
        Power landed beams hand to diffuse reflection on each side (a source of the radiosity balance).
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
        Most surfaces any chain met.
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    diffuse_source_W: NDArray[np.float64]
    open_sky_force_N: NDArray[np.float64]
    open_sky_torque_Nm: NDArray[np.float64]
    escaped_W: float
    absorbed_W: float
    truncated_W: float
    first_W: float
    rays: int
    depth: int


@dataclass
class _Beams:
    """A generation of rays, each leaving ``origin_m`` (on its surface) along ``direction``."""

    origin_m: NDArray[np.float64]  # (n, 3) surface point
    lift: NDArray[np.float64]  # (n, 3) unit vector the origin is pushed along, off the surface
    direction: NDArray[np.float64]  # (n, 3)
    power_W: NDArray[np.float64]  # (n,)
    start_W: NDArray[np.float64]  # (n,) power its chain started with

    def __len__(self) -> int:
        return len(self.power_W)

    def take(self, mask: NDArray) -> _Beams:
        return _Beams(self.origin_m[mask], self.lift[mask], self.direction[mask], self.power_W[mask],
                      self.start_W[mask])

    @staticmethod
    def join(parts: list[_Beams]) -> _Beams:
        return _Beams(*(np.concatenate([getattr(p, name) for p in parts]) for name in _BEAM_FIELDS))


_BEAM_FIELDS = ("origin_m", "lift", "direction", "power_W", "start_W")


def _empty_beams() -> _Beams:
    return _Beams(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0), np.zeros(0))


def _cast(craft: Spacecraft, beams: _Beams) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Side each beam meets (``ESCAPED``/``BLIND`` codes of :meth:`Spacecraft.struck_sides`) and
    the point it meets it [m]."""
    scene = craft.scene
    origins = scene.origins(beams.origin_m, beams.lift)
    facets, distance = scene.intersect(origins, beams.direction.astype(np.float32))
    sides = craft.struck_sides(facets, beams.direction)
    points = beams.origin_m + beams.lift * scene.offset_m
    points = points + beams.direction * (distance.astype(np.float64) * scene.half_size)[:, None]
    return sides, points


def _mirror(directions: NDArray[np.float64], normals: NDArray[np.float64]) -> NDArray[np.float64]:
    """Directions (n, 3) reflected on surfaces of unit normals (n, 3)."""
    return directions - 2 * np.einsum("nd,nd->n", directions, normals)[:, None] * normals


@dataclass(frozen=True)
class _Emitters:
    """Lit sides sending a first beam: the specular beam of each, the transmitted beam of sheets."""

    side: NDArray[np.int64]
    direction: NDArray[np.float64]
    lift: NDArray[np.float64]
    power_W: NDArray[np.float64]


def _emitters(craft: Spacecraft, light: Illumination, flux_W_m2: float) -> _Emitters:
    lit = np.flatnonzero(light.lit_fraction > 0)
    rho, beta, sigma = craft.side_optics[lit].T
    incident = flux_W_m2 * craft.side_areas[lit] * light.lit_fraction[lit] * light.cos_incidence[lit]
    normals = craft.side_normals[lit]
    s = np.broadcast_to(-light.direction, normals.shape)
    sheet = craft.facet_kind[craft.side_facet[lit]] != SOLID
    specular = rho * beta > 0
    through = (sigma > 0) & sheet
    return _Emitters(
        side=np.concatenate([lit[specular], lit[through]]),
        direction=np.concatenate([_mirror(s[specular], normals[specular]), s[through]]),
        lift=np.concatenate([normals[specular], -normals[through]]),
        power_W=np.concatenate([(incident * rho * beta)[specular], (incident * sigma)[through]]),
    )


def _first_beams(
    craft: Spacecraft, light: Illumination, emitters: _Emitters
) -> tuple[_Beams, NDArray[np.int64], NDArray[np.float64], int]:
    """First beams of every emitter, adaptively sampled, with the side each meets and where."""
    n = len(emitters.side)
    if n == 0:
        return _empty_beams(), np.zeros(0, np.int64), np.zeros((0, 3)), 0
    level = 1 << max(0, int(np.log2(max(1.0, np.sqrt(START_RAYS / n)))))
    level = min(level, MAX_LEVEL)
    active = np.arange(n)
    previous_share = np.full(n, np.nan)
    accepted: list[tuple[_Beams, NDArray[np.int64], NDArray[np.float64]]] = []
    rays = 0
    first = True
    while len(active):
        beams, owner, sides, points, cast = _sample(craft, light, emitters, active, level)
        rays += cast
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
        share = escaping[active] / emitters.power_W[active]
        if first:
            split |= _disagrees_with_neighbour(craft, emitters, active, low, high)
            first = False
        settled = np.abs(share - previous_share[active]) <= TOLERANCE
        again = split & ~settled & (level < MAX_LEVEL)
        if _split_error(emitters.power_W[active[again]], level) <= TOLERANCE * emitters.power_W.sum():
            again[:] = False
        done = np.zeros(n, dtype=bool)
        done[active[~again]] = True
        keep = done[owner]
        accepted.append((beams.take(keep), sides[keep], points[keep]))
        previous_share[active] = share
        active = active[again]
        level *= 2
    parts = [a[0] for a in accepted]
    return (
        _Beams.join(parts),
        np.concatenate([a[1] for a in accepted]),
        np.concatenate([a[2] for a in accepted]),
        rays,
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
    same kind of beam (mirror or transmitted): the split may fall between their sample points."""
    a, b = craft.side_neighbours
    index = np.full((2, craft.n_sides), -1)
    kind = (np.einsum("nd,nd->n", emitters.lift, craft.side_normals[emitters.side]) < 0).astype(np.int64)
    index[kind, emitters.side] = np.arange(len(emitters.side))
    flagged = np.zeros(len(emitters.side), dtype=bool)
    for k in (0, 1):
        ea, eb = index[k, a], index[k, b]
        both = (ea >= 0) & (eb >= 0)
        ea, eb = ea[both], eb[both]
        differ = (low[ea] == high[ea]) & (low[eb] == high[eb]) & (low[ea] != low[eb])
        flagged[ea[differ]] = True
        flagged[eb[differ]] = True
    return flagged[active]


def _sample(
    craft: Spacecraft, light: Illumination, emitters: _Emitters, chosen: NDArray[np.int64], level: int
) -> tuple[_Beams, NDArray[np.int64], NDArray[np.int64], NDArray[np.float64], int]:
    """First beams of ``chosen`` emitters from their lit points at ``level``, cast.

    Returns the beams, the emitter of each, the side each meets and where, and the rays cast. At level
    1 the point is the lit centroid. A partly lit side's points are shadow-tested; a side none of whose
    points is lit sends its beam from its lit centroid.
    """
    side = emitters.side[chosen]
    rays = 0
    if level == 1:
        points = light.lit_centroid[side][:, None, :]
        lit = np.ones((len(side), 1), dtype=bool)
    else:
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
            rays += origins.shape[0]
        none = ~lit.any(axis=1)
        points[none, 0] = light.lit_centroid[side[none]]
        lit[none, 0] = True
    owner_of_point = np.repeat(np.arange(len(side)), lit.shape[1])[lit.reshape(-1)]
    per_emitter = lit.sum(axis=1)
    owner = chosen[owner_of_point]
    beams = _Beams(
        origin_m=points[lit],
        lift=emitters.lift[owner],
        direction=emitters.direction[owner],
        power_W=(emitters.power_W[chosen] / per_emitter)[owner_of_point],
        start_W=(emitters.power_W[chosen] / per_emitter)[owner_of_point],
    )
    sides, hit_points = _cast(craft, beams)
    return beams, owner, sides, hit_points, rays + len(beams)


def follow_chains(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    cutoff: float = DEFAULT_CUTOFF,
    depth: int = DEFAULT_DEPTH,
) -> ChainTotals:
    """Trace the mirror and transmitted beams of every lit side until they escape or fade.

    Parameters
    ----------
    craft : Spacecraft
    light : Illumination
        Lit shares and lit centroids of the attitude (from the direct computation).
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_m : (3,) float64
        Torque reference point [m].
    cutoff : float
        A beam is dropped below this share of the power its chain started with.
    depth : int
        A chain is dropped after meeting this many surfaces after the first.
    """
    emitters = _emitters(craft, light, flux_W_m2)
    beams, sides, points, rays = _first_beams(craft, light, emitters)
    tally = _Tally(craft.n_sides)
    # eq. (4) had every first beam leave; those that land give that momentum back
    landed = sides != ESCAPED
    tally.add_momentum(beams.origin_m[landed], beams.power_W[landed, None] * beams.direction[landed],
                       reference_m)
    tally.escaped_W += float(beams.power_W[~landed].sum())
    generation = 0
    while len(beams):
        if generation:
            gone = sides == ESCAPED
            tally.leave(beams.origin_m[gone], beams.power_W[gone], beams.direction[gone], reference_m)
        generation += 1
        beams = _land(craft, beams, sides, points, tally, reference_m)
        fading = beams.power_W < cutoff * beams.start_W
        if generation >= depth:
            fading[:] = True
        tally.truncated_W += float(beams.power_W[fading].sum())
        beams = beams.take(~fading)
        if len(beams):
            sides, points = _cast(craft, beams)
            rays += len(beams)
    return ChainTotals(
        force_N=tally.momentum / SPEED_OF_LIGHT,
        torque_Nm=tally.moment / SPEED_OF_LIGHT,
        diffuse_source_W=tally.diffuse_W,
        open_sky_force_N=tally.open_sky_momentum / SPEED_OF_LIGHT,
        open_sky_torque_Nm=tally.open_sky_moment / SPEED_OF_LIGHT,
        escaped_W=tally.escaped_W,
        absorbed_W=tally.absorbed_W,
        truncated_W=tally.truncated_W,
        first_W=float(emitters.power_W.sum()),
        rays=rays,
        depth=generation,
    )


class _Tally:
    """Running sums of a chain trace; momenta in W (divide by c for N)."""

    def __init__(self, n_sides: int) -> None:
        self.momentum = np.zeros(3)
        self.moment = np.zeros(3)
        self.open_sky_momentum = np.zeros(3)
        self.open_sky_moment = np.zeros(3)
        self.diffuse_W = np.zeros(n_sides)
        self.escaped_W = self.absorbed_W = self.truncated_W = 0.0

    def add_momentum(self, at_m: NDArray, momentum_W: NDArray, reference_m: NDArray) -> None:
        """Add momentum rates (n, 3) acting at points (n, 3) [m] to the force and torque sums."""
        self.momentum += momentum_W.sum(axis=0)
        self.moment += np.cross(at_m - reference_m, momentum_W).sum(axis=0)

    def leave(self, at_m: NDArray, power_W: NDArray, direction: NDArray, reference_m: NDArray) -> None:
        """Beams escaping from points ``at_m``: their momentum is lost to the spacecraft."""
        self.add_momentum(at_m, -power_W[:, None] * direction, reference_m)
        self.escaped_W += float(power_W.sum())


def _land(
    craft: Spacecraft,
    beams: _Beams,
    sides: NDArray[np.int64],
    points: NDArray[np.float64],
    tally: _Tally,
    reference_m: NDArray[np.float64],
) -> _Beams:
    """Split the beams that meet a side into absorbed, diffuse, mirror and transmitted parts; return
    the new mirror and transmitted beams."""
    tally.absorbed_W += float(beams.power_W[sides == BLIND].sum())
    hit = sides >= 0
    side, at, power = sides[hit], points[hit], beams.power_W[hit]
    direction, start = beams.direction[hit], beams.start_W[hit]
    rho, beta, sigma = craft.side_optics[side].T
    normals = craft.side_normals[side]
    solid = craft.facet_kind[craft.side_facet[side]] == SOLID
    tally.absorbed_W += float(((1 - rho - sigma) * power).sum())
    diffuse = rho * (1 - beta) * power
    tally.diffuse_W += np.bincount(side, weights=diffuse, minlength=craft.n_sides)
    open_sky = -LAMBERT_FACTOR * diffuse[:, None] * normals
    tally.open_sky_momentum += open_sky.sum(axis=0)
    tally.open_sky_moment += np.cross(at - reference_m, open_sky).sum(axis=0)
    # light a closed body transmits leaves unchanged, as in the direct law
    tally.leave(at[solid], sigma[solid] * power[solid], direction[solid], reference_m)
    mirror = rho * beta > 0
    through = (sigma > 0) & ~solid
    return _Beams(
        origin_m=np.concatenate([at[mirror], at[through]]),
        lift=np.concatenate([normals[mirror], -normals[through]]),
        direction=np.concatenate([_mirror(direction[mirror], normals[mirror]), direction[through]]),
        power_W=np.concatenate([(rho * beta * power)[mirror], (sigma * power)[through]]),
        start_W=np.concatenate([start[mirror], start[through]]),
    )
