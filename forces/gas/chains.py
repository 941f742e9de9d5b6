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
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas import chain_kernels as kernels
from sunwind.forces.gas.angular import SpeciesLaws
from sunwind.forces.gas.incident import incident
from sunwind.forces.gas.laws import GasSurfaces, reemission
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


class ChainLaws(NamedTuple):
    """What each gas-surface law does with the molecules it does not accommodate, per law (n_laws,).

    Read from the laws' :class:`~sunwind.forces.gas.laws.Reemission`, so a law's shares are written
    once, in its function in :mod:`sunwind.forces.gas.laws`. A named tuple, so the numba kernels read
    its fields by name.

    Attributes
    ----------
    mirrored : float64
        Share sent on mirrored: ``pressure_scale - 1`` of a law other than CLL (1 for ``specular``,
        ``1 - sigma_n`` for ``schaaf-chambre``).
    cll : bool
        The law is CLL: all sent on, by one draw of its kernel.
    alpha_n, sigma_t : float64
        CLL's accommodations (unused elsewhere).
    diffuse : float64
        Share re-emitted diffusely (to the exchange): the law's ``emission_share``.
    wall_weight, energy_weight : float64
        The temperature of that re-emission for a molecule arriving at speed ``v``: ``wall_weight T_w +
        energy_weight m v^2 / (2 k)`` [K].
    wall_temperature_K : float64
        ``T_w`` [K].

    Examples
    --------
    Built from the laws with :meth:`of` (its example gives the shares of three laws); its fields:

    >>> ChainLaws._fields[:3]
    ('mirrored', 'cll', 'alpha_n')
    """

    mirrored: NDArray[np.float64]
    cll: NDArray[np.bool_]
    alpha_n: NDArray[np.float64]
    sigma_t: NDArray[np.float64]
    diffuse: NDArray[np.float64]
    wall_weight: NDArray[np.float64]
    energy_weight: NDArray[np.float64]
    wall_temperature_K: NDArray[np.float64]

    @classmethod
    def of(cls, surfaces: GasSurfaces) -> ChainLaws:
        """The :class:`ChainLaws` of the laws ``surfaces``.

        Parameters
        ----------
        surfaces : GasSurfaces
            Law and parameters of each of ``n_laws`` laws.

        Returns
        -------
        ChainLaws
            One entry per law.

        Examples
        --------
        >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
        >>> surfaces = GasSurfaces.of({
        ...     "code": [MODEL_CODES["specular"], MODEL_CODES["schaaf-chambre"], MODEL_CODES["sentman"]],
        ...     "energy_accommodation": 0.9, "normal_accommodation": 0.75,
        ...     "tangential_accommodation": 1.0, "wall_temperature_K": 300.0})
        >>> laws = ChainLaws.of(surfaces)
        >>> laws.mirrored.tolist(), laws.diffuse.tolist()
        ([1.0, 0.25, 0.0], [0.0, 0.75, 1.0])
        >>> laws.sends.tolist()
        [True, True, False]
        """
        # the shares and weights do not depend on the stream: any speed ratio and temperature give them
        law = reemission(surfaces, 1.0, 1.0)
        n = len(surfaces)
        is_cll = np.zeros(n, dtype=bool) if law.cll_alpha_n is None else np.isfinite(law.cll_alpha_n)
        return cls(
            mirrored=np.where(is_cll, 0.0, law.pressure_scale - 1.0),
            cll=is_cll,
            alpha_n=np.full(n, np.nan) if law.cll_alpha_n is None else law.cll_alpha_n,
            sigma_t=law.shear_scale,
            diffuse=law.emission_share,
            wall_weight=law.wall_weight,
            energy_weight=law.energy_weight,
            wall_temperature_K=surfaces.wall_temperature_K,
        )

    @property
    def sends(self) -> NDArray[np.bool_]:
        """Laws that send some arriving molecules on unaccommodated, (n_laws,) bool."""
        return self.cll | (self.mirrored > 0.0)


class SpeciesStream(NamedTuple):
    """The free stream by species, as the molecular chains draw it.

    Attributes
    ----------
    mass_kg : (k,) float64
        Molecular mass of each species [kg].
    density_m3 : (k,) float64
        Number density of each species [m^-3].
    speed_m_s : float
        Speed of the flow relative to the body [m/s].

    Examples
    --------
    >>> import numpy as np
    >>> stream = SpeciesStream(np.array([2.66e-26]), np.array([1e15]), 7500.0)
    >>> stream.speed_m_s
    7500.0
    """

    mass_kg: NDArray[np.float64]
    density_m3: NDArray[np.float64]
    speed_m_s: float


class Molecules(NamedTuple):
    """Molecules on their way, one row each; a named tuple, so the kernels read fields by name.

    Attributes
    ----------
    side : (n,) int64
        Side each arrives at.
    species : (n,) int64
        Its species.
    point : (n, 3) float64
        Where it arrives [m].
    velocity : (n, 3) float64
        Its velocity [m/s].
    weight : (n,) float64
        Molecules per second it stands for [1/s].
    packet : (n,) int64
        Its own number, which keys its random numbers.

    Examples
    --------
    >>> import numpy as np
    >>> one = Molecules(np.arange(2), np.zeros(2, int), np.zeros((2, 3)), np.ones((2, 3)), np.ones(2),
    ...                 np.arange(2))
    >>> len(one.side)
    2
    """

    side: NDArray[np.int64]
    species: NDArray[np.int64]
    point: NDArray[np.float64]
    velocity: NDArray[np.float64]
    weight: NDArray[np.float64]
    packet: NDArray[np.int64]

    def take(self, rows: NDArray) -> Molecules:
        """The molecules ``rows`` (indices or a mask).

        Parameters
        ----------
        rows : (m,) int64 or (n,) bool
            Which molecules.

        Returns
        -------
        Molecules
            Those molecules.

        Examples
        --------
        >>> import numpy as np
        >>> one = Molecules(np.arange(3), np.zeros(3, int), np.zeros((3, 3)), np.ones((3, 3)),
        ...                 np.ones(3), np.arange(3))
        >>> one.take(np.array([True, False, True])).side.tolist()
        [0, 2]
        """
        return Molecules(*(field[rows] for field in self))


@dataclass(frozen=True)
class MoleculeChainTotals:
    """What the molecular chains of one attitude change; body frame, SI.

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

    Examples
    --------
    >>> import numpy as np
    >>> totals = MoleculeChainTotals(force_N=np.zeros(3), torque_Nm=np.zeros(3), deposit=np.zeros((2, 1)),
    ...                              packets=0, rays=0, truncated=0.0)
    >>> totals.packets
    0
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    deposit: NDArray[np.float64]
    packets: int
    rays: int
    truncated: float

    def to_json(self) -> dict:
        """The counts, JSON-ready.

        Returns
        -------
        dict
            ``molecules``, ``rays`` and ``truncated``.

        Examples
        --------
        >>> import numpy as np
        >>> MoleculeChainTotals(force_N=np.zeros(3), torque_Nm=np.zeros(3), deposit=np.zeros((2, 1)),
        ...                     packets=4, rays=9, truncated=0.0).to_json()
        {'molecules': 4, 'rays': 9, 'truncated': 0.0}
        """
        return {"molecules": self.packets, "rays": self.rays, "truncated": self.truncated}


def molecular_chains(
    craft: Spacecraft,
    groups: GasGroups,
    laws: SpeciesLaws,
    stream: SpeciesStream,
    u: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    budget: int,
    tangent=None,
) -> MoleculeChainTotals:
    """Follow the unaccommodated molecules of one attitude (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    groups : GasGroups
        Its sides grouped by law and normal.
    laws : SpeciesLaws
        The free stream by species and each law's answer (species as ``stream``).
    stream : SpeciesStream
        Species masses [kg], number densities [m^-3] and the flow speed [m/s].
    u : (3,) float64
        Unit flow direction, ``v_rel / |v_rel|``.
    reference_m : (3,) float64
        Torque reference point [m].
    budget : int
        Molecules drawn in all (at least one per sending side, at most :data:`MAX_PER_SIDE`).
    tangent : ChainTangent, optional
        Where to sum the derivatives by the accommodations on the same molecules
        (:class:`~sunwind.forces.gas.chain_tangents.ChainTangent`).

    Returns
    -------
    MoleculeChainTotals
        The force and torque they change and what they bring to the exchange.

    Raises
    ------
    MemoryError
        The molecules would not fit in the memory left (:func:`~sunwind.geometry.memory.require`).

    Examples
    --------
    A convex model sends nothing on to another side, so no chain is followed:

    >>> import numpy as np
    >>> from sunwind.forces.gas.atmosphere import Atmosphere
    >>> from sunwind.forces.gas.panel import gas_groups, species_laws, species_streams
    >>> from sunwind.geometry.materials import GasSurface, Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box
    >>> mirror = Material("m", 0.3, 0.5, gas=GasSurface(model="specular"))
    >>> craft = build_spacecraft(box(), uniform=mirror)
    >>> groups = gas_groups(craft)
    >>> air = Atmosphere({"O": 1e15}, 1000.0, "example")
    >>> laws = species_laws(groups.surfaces, air, 7500.0)
    >>> stream = SpeciesStream(*species_streams(air), 7500.0)
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> molecular_chains(craft, groups, laws, stream, u, np.zeros(3), 1000).packets
    0
    """
    chain_laws = ChainLaws.of(groups.surfaces)
    side_law = groups.law[groups.side]
    senders = np.flatnonzero(chain_laws.sends[side_law] & ~clearance(craft).open_sky)
    arrived = _arrivals(craft, senders, laws, stream, u, budget) if len(senders) else None
    if arrived is None:
        return MoleculeChainTotals(
            force_N=np.zeros(3),
            torque_Nm=np.zeros(3),
            deposit=np.zeros((2, craft.n_sides)),
            packets=0,
            rays=0,
            truncated=0.0,
        )
    drawn, molecules = arrived
    followed = _follow(craft, molecules, chain_laws, side_law, stream.mass_kg, reference_m, tangent)
    first = float(np.sum(molecules.weight))
    return MoleculeChainTotals(
        force_N=followed.totals[:3].copy(),
        torque_Nm=followed.totals[3:].copy(),
        deposit=followed.deposit,
        packets=drawn,
        rays=drawn + followed.rays,
        truncated=followed.truncated / first if first > 0 else 0.0,
    )


def _arrivals(
    craft: Spacecraft,
    senders: NDArray[np.int64],
    laws: SpeciesLaws,
    stream: SpeciesStream,
    u: NDArray[np.float64],
    budget: int,
) -> tuple[int, Molecules] | None:
    """Molecules drawn from the free stream onto ``senders`` (species by their mass flux), and of them
    those that arrive unobstructed, a ray cast back along each path; None where no molecule strikes a
    sender."""
    mass, density, speed = stream.mass_kg, stream.density_m3, stream.speed_m_s
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
        MOLECULE_BYTES * drawn_at_most,
        f"{count(drawn_at_most)} chain molecules",
        "lower chain_molecules",
        ("chain_molecules",),
    )
    side, species, point, velocity, weight = kernels.starts(
        senders, per_side, craft.triangles, craft.side_facet, craft.side_normals, craft.side_areas,
        flux, pick, speed / laws.speed_ratio, -speed * u, np.uint64(CHAIN_SEED),
    )  # fmt: skip
    drawn = Molecules(side, species, point, velocity, weight, np.arange(len(side), dtype=np.int64))
    scene = craft.scene
    back = -velocity / np.linalg.norm(velocity, axis=1)[:, None]
    origins, directions = scene_rays(
        point, craft.side_normals[side], back, scene.centre, scene.half_size, scene.offset_m
    )
    return len(side), drawn.take(np.flatnonzero(~scene.occluded(origins, directions)))


class _Followed(NamedTuple):
    """What :func:`_follow` books: force and torque (6,) [N, N m], the exchange's ``deposit`` (2,
    n_sides), the rays cast and the weight still travelling when chains were cut [1/s]."""

    totals: NDArray[np.float64]
    deposit: NDArray[np.float64]
    rays: int
    truncated: float


def _follow(
    craft: Spacecraft,
    molecules: Molecules,
    chain_laws: ChainLaws,
    side_law: NDArray[np.int64],
    mass: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    tangent=None,
) -> _Followed:
    """Send ``molecules`` on from bounce to bounce (``side_law`` the law of each side, ``mass`` of each
    species [kg]), booking momentum and diffuse re-emission (and their derivatives into ``tangent``)."""
    totals, deposit = np.zeros(6), np.zeros((2, craft.n_sides))
    start, rays, truncated = molecules.weight.copy(), 0, 0.0
    scene, model = craft.scene, chain_model(craft)
    seed = np.uint64(CHAIN_SEED)
    state = None if tangent is None else tangent.start(len(molecules.weight))
    for depth in range(DEPTH + 1):
        out_velocity, out_weight, sends = kernels.bounce(
            molecules, depth, side_law, craft.side_normals, mass, chain_laws, seed, reference_m, totals,
            depth > 0,
        )  # fmt: skip
        if tangent is not None:
            booking = (reference_m, depth > 0, depth)
            state = tangent.bounce(molecules, state, side_law, out_velocity, mass, booking)
        keep = sends & (out_weight >= CUTOFF * start)
        truncated += float(np.sum(out_weight[sends & ~keep]))
        if depth == DEPTH:
            truncated += float(np.sum(out_weight[keep]))
        if depth == DEPTH or not np.any(keep):
            break
        leaving = molecules.take(keep)
        leg_velocity, leg_weight, leg_point = out_velocity[keep], out_weight[keep], leaving.point
        lift = craft.side_normals[leaving.side]
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
            struck, leg_point, leaving.species, leg_velocity, leg_weight, side_law, mass, chain_laws,
            reference_m, totals, deposit,
        )  # fmt: skip
        if tangent is not None:
            legs = leaving._replace(velocity=leg_velocity, weight=leg_weight)
            kept = tuple(None if a is None else a[keep] for a in state)
            landed = (landing, leg_point + scene.offset_m * lift)
            state = tangent.land(struck, (legs, kept, landed), side_law, mass, reference_m)
            state = tuple(None if a is None else a[goes_on] for a in state)
        molecules = Molecules(
            side=struck[goes_on],
            species=leaving.species[goes_on],
            point=landing[goes_on],
            velocity=leg_velocity[goes_on],
            weight=leg_weight[goes_on],
            packet=leaving.packet[goes_on],
        )
        start = start[keep][goes_on]
    return _Followed(totals=totals, deposit=deposit, rays=rays, truncated=truncated)
