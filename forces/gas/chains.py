"""Molecules a surface sends on without accommodating them, followed from surface to surface
(METHOD.md "Molecular chains").

The panel law (:mod:`.visible`) lets every re-emitted molecule leave to infinity. Molecules re-emitted
diffusely are followed by the exchange (:mod:`.exchange`); the rest — the mirrored share of Maxwell's
kernel (the ``specular`` law, Schaaf-Chambre's ``1 - sigma_n``) and everything CLL sends back, a lobe
about the mirror direction — are followed here, like the photon beam chains of
:mod:`sunwind.forces.reflection.beams` but with the lobe's width: by sampling.

Each sending side draws ``per_side`` molecules from the free stream's flux onto it (species, speed and
direction exactly from the drifting Maxwellian, stratified over the side and the species), keeps those
that arrive unobstructed (a ray back along their path), and sends each on: the mirrored share along
``v - 2 (v . n) n`` with its speed, or one draw of the CLL kernel (Lord's algorithm). Each leg is cast;
momentum is booked as for light, by what comes from and goes to infinity: a leg's momentum ``w m v`` is
taken as escaping when it leaves and given back if it meets a side. There the struck side's law takes
the molecule: its diffuse share goes to the exchange as a re-emission at the temperature the law gives
this molecule's energy; its mirrored share or CLL draw goes on. A chain ends when it escapes, falls
below ``CUTOFF`` of its first weight or has met ``DEPTH`` surfaces (then it is taken as escaping).

Molecules that diffuse re-emission sends onto a mirror are the exchange's (its exchange factors follow
them through mirrors); the CLL kernel, whose lobe is followed here for the fast molecules of the free
stream, re-emits the slow ones of the exchange diffusely (exact for molecules at the wall's own
temperature arriving from every direction, which it returns as they came).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas import chain_kernels as kernels
from sunwind.forces.gas.angular import SpeciesLaws
from sunwind.forces.gas.incident import incident
from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
from sunwind.forces.gas.panel import GasGroups
from sunwind.forces.reflection.beam_kernels import scene_rays, strike
from sunwind.forces.reflection.beams import chain_model
from sunwind.geometry.memory import count, require
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.spacecraft import Spacecraft

#: Most molecules a sending side draws per attitude.
MAX_PER_SIDE = 256
#: A chain ends below this share of its first weight, or after this many surfaces.
CUTOFF, DEPTH = 1e-6, 64
#: Seed of the chains' random numbers.
CHAIN_SEED = 0xC4A1
#: Peak bytes per molecule drawn: its state (side, species, point, velocity, weight, number), the rays
#: cast back and along each leg, and the bounce's outputs.
MOLECULE_BYTES = 320


@dataclass(frozen=True, eq=False)
class ChainLaws:
    """What each gas-surface law does with a molecule it does not accommodate, per law (n_laws,).

    Attributes
    ----------
    mirrored : float64
        Share sent on mirrored: 1 for ``specular``, ``1 - sigma_n`` for ``schaaf-chambre``.
    cll : bool
        The law is CLL: all sent on, by one draw of its kernel.
    alpha_n, sigma_t : float64
        CLL's accommodations (unused elsewhere).
    diffuse : float64
        Share re-emitted diffusely (to the exchange): 1 for ``sentman`` and ``dria``, ``sigma_n`` for
        ``schaaf-chambre``.
    rule : int64
        Temperature of that re-emission (:data:`~sunwind.forces.gas.chain_kernels.AT_WALL`, ``SENTMAN``,
        ``DRIA``), with ``energy_accommodation`` and ``wall_temperature_K``.
    """

    mirrored: NDArray[np.float64]
    cll: NDArray[np.bool_]
    alpha_n: NDArray[np.float64]
    sigma_t: NDArray[np.float64]
    diffuse: NDArray[np.float64]
    rule: NDArray[np.int64]
    energy_accommodation: NDArray[np.float64]
    wall_temperature_K: NDArray[np.float64]

    @classmethod
    def of(cls, surfaces: GasSurfaces) -> ChainLaws:
        code = surfaces.code
        sigma_n = surfaces.normal_accommodation
        schaaf = code == MODEL_CODES["schaaf-chambre"]
        diffuse_law = (code == MODEL_CODES["sentman"]) | (code == MODEL_CODES["dria"])
        rule = np.where(
            code == MODEL_CODES["sentman"],
            kernels.SENTMAN,
            np.where(code == MODEL_CODES["dria"], kernels.DRIA, kernels.AT_WALL),
        )
        return cls(
            mirrored=np.where(code == MODEL_CODES["specular"], 1.0, np.where(schaaf, 1.0 - sigma_n, 0.0)),
            cll=code == MODEL_CODES["cll"],
            alpha_n=surfaces.normal_accommodation,
            sigma_t=surfaces.tangential_accommodation,
            diffuse=np.where(diffuse_law, 1.0, np.where(schaaf, sigma_n, 0.0)),
            rule=rule.astype(np.int64),
            energy_accommodation=surfaces.energy_accommodation,
            wall_temperature_K=surfaces.wall_temperature_K,
        )

    @property
    def sends(self) -> NDArray[np.bool_]:
        """Laws that send some arriving molecules on unaccommodated."""
        return self.cll | (self.mirrored > 0.0)


@dataclass(frozen=True)
class ChainTotals:
    """What the chains of one attitude change; body frame, SI.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Correction to the panel law's force and torque (about the reference point).
    deposit : (2, n_sides) float64
        Diffuse re-emission of the molecules chains bring to each side: momentum per second [N] and
        sqrt(mass)-weighted molecules per second [sqrt(kg)/s], for the exchange.
    packets : int
        Molecules drawn.
    rays : int
        Rays cast (arrival checks and legs).
    truncated : float
        Share of the first legs' weight still travelling when chains were cut.
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    deposit: NDArray[np.float64]
    packets: int
    rays: int
    truncated: float

    def to_json(self) -> dict:
        """The counts, JSON-ready."""
        return {"molecules": self.packets, "rays": self.rays, "truncated": self.truncated}


def molecular_chains(
    craft: Spacecraft,
    groups: GasGroups,
    laws: SpeciesLaws,
    stream: tuple[NDArray[np.float64], NDArray[np.float64], float],
    u: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    budget: int,
) -> ChainTotals:
    """Follow the unaccommodated molecules of one attitude (module docstring).

    ``stream`` = species masses [kg], number densities [m^-3] (as ``laws``) and the speed [m/s];
    ``budget`` the molecules drawn in all (at least one per sending side, at most
    :data:`MAX_PER_SIDE`).
    """
    chain_laws = ChainLaws.of(groups.surfaces)
    side_law = groups.law[groups.side]
    senders = np.flatnonzero(chain_laws.sends[side_law] & ~clearance(craft).open_sky)
    molecules = _arrivals(craft, senders, laws, stream, u, budget) if len(senders) else None
    if molecules is None:
        return ChainTotals(np.zeros(3), np.zeros(3), np.zeros((2, craft.n_sides)), 0, 0, 0.0)
    drawn, molecules = molecules
    totals, deposit = np.zeros(6), np.zeros((2, craft.n_sides))
    rays, truncated = _follow(
        craft, molecules, (chain_laws, side_law, stream[0]), reference_m, totals, deposit
    )
    first = float(np.sum(molecules[4]))
    return ChainTotals(
        force_N=totals[:3].copy(),
        torque_Nm=totals[3:].copy(),
        deposit=deposit,
        packets=drawn,
        rays=drawn + rays,
        truncated=truncated / first if first > 0 else 0.0,
    )


def _arrivals(
    craft: Spacecraft,
    senders: NDArray[np.int64],
    laws: SpeciesLaws,
    stream: tuple[NDArray[np.float64], NDArray[np.float64], float],
    u: NDArray[np.float64],
    budget: int,
) -> tuple[int, tuple[NDArray, ...]] | None:
    """Molecules drawn from the free stream onto ``senders`` (species by their mass flux), and of them
    those that arrive unobstructed, a ray cast back along each path: side, species, point [m], velocity
    [m/s], weight [1/s] and number of each; None where no molecule strikes a sender."""
    mass, density, speed = stream
    gamma = craft.side_normals[senders] @ u
    flux = np.column_stack(
        [
            n_k * speed * incident(gamma, float(s_k)).number_flux
            for n_k, s_k in zip(density, laws.speed_ratio, strict=True)
        ]
    )
    pick = flux * mass
    total = pick.sum(axis=1)
    keep = total > 0.0
    if not np.any(keep):
        return None
    senders, flux, pick = senders[keep], flux[keep], pick[keep] / total[keep, None]
    per_side = int(np.clip(budget // len(senders), 1, MAX_PER_SIDE))
    drawn_at_most = len(senders) * per_side
    require(
        MOLECULE_BYTES * drawn_at_most, f"{count(drawn_at_most)} chain molecules", "lower chain_molecules",
        ("chain_molecules",),
    )  # fmt: skip
    drawn = kernels.starts(
        senders, per_side, craft.triangles, craft.side_facet, craft.side_normals, craft.side_areas,
        flux, pick, speed / laws.speed_ratio, -speed * u, np.uint64(CHAIN_SEED),
    )  # fmt: skip
    side, velocity = drawn[0], drawn[3]
    scene = craft.scene
    back = -velocity / np.linalg.norm(velocity, axis=1)[:, None]
    origins, directions = scene_rays(
        drawn[2], craft.side_normals[side], back, scene.centre, scene.half_size, scene.offset_m
    )
    arrived = np.flatnonzero(~scene.occluded(origins, directions))
    return len(side), (*(a[arrived] for a in drawn), arrived.astype(np.int64))


def _follow(
    craft: Spacecraft,
    molecules: tuple[NDArray, ...],
    laws: tuple[ChainLaws, NDArray[np.int64], NDArray[np.float64]],
    reference_m: NDArray[np.float64],
    totals: NDArray[np.float64],
    deposit: NDArray[np.float64],
) -> tuple[int, float]:
    """Send ``molecules`` (side, species, point, velocity, weight, number) on from bounce to bounce,
    booking momentum in ``totals`` and diffuse re-emission in ``deposit``; the rays cast and the weight
    still travelling when chains were cut."""
    chain_laws, side_law, mass = laws
    side, species, point, velocity, weight, packet = molecules
    bounce_laws = (
        chain_laws.mirrored, chain_laws.cll, chain_laws.alpha_n, chain_laws.sigma_t,
        chain_laws.wall_temperature_K,
    )  # fmt: skip
    land_laws = (
        chain_laws.diffuse,
        chain_laws.rule,
        chain_laws.energy_accommodation,
        chain_laws.wall_temperature_K,
    )
    start, rays, truncated = weight.copy(), 0, 0.0
    scene, model = craft.scene, chain_model(craft)
    seed = np.uint64(CHAIN_SEED)
    for depth in range(DEPTH + 1):
        out_velocity, out_weight, sends = kernels.bounce(
            side, species, point, velocity, weight, packet, depth, side_law, craft.side_normals, mass,
            bounce_laws, seed, reference_m, totals, depth > 0,
        )  # fmt: skip
        keep = sends & (out_weight >= CUTOFF * start)
        truncated += float(np.sum(out_weight[sends & ~keep]))
        if depth == DEPTH:
            truncated += float(np.sum(out_weight[keep]))
        if depth == DEPTH or not np.any(keep):
            break
        lift = craft.side_normals[side[keep]]
        leg_velocity, leg_weight, leg_point = out_velocity[keep], out_weight[keep], point[keep]
        direction = leg_velocity / np.linalg.norm(leg_velocity, axis=1)[:, None]
        origins, directions = scene_rays(
            leg_point, lift, direction, scene.centre, scene.half_size, scene.offset_m
        )
        struck, landing = strike(
            scene.first_hit(origins, directions), leg_point, lift, direction, scene.offset_m,
            craft.facet_normals, model.facet_offsets, craft.facet_sides,
        )  # fmt: skip
        rays += len(struck)
        goes_on = kernels.land(
            struck, leg_point, species[keep], leg_velocity, leg_weight, side_law, mass, land_laws,
            reference_m, totals, deposit,
        )  # fmt: skip
        side, species, point = struck[goes_on], species[keep][goes_on], landing[goes_on]
        velocity, weight = leg_velocity[goes_on], leg_weight[goes_on]
        packet, start = packet[keep][goes_on], start[keep][goes_on]
    return rays, truncated
