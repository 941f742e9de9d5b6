"""Derivatives of the molecular chains and the re-emission exchange with respect to the accommodation
coefficients, forward mode on the same molecules (METHOD.md "Molecular chains").

With the molecules' draws (their random numbers) and the sides their legs meet held, the chains' force,
torque and deposits are smooth in the laws' numbers: a molecule's weight is the product of the
mirrored shares of the sides it left (``1 - sigma_n`` of ``schaaf-chambre``, 1 of ``specular``); CLL
sends it on with a velocity drawn from its kernel (:func:`~sunwind.forces.gas.chain_kernels.
cll_tangents` gives that velocity's derivative by ``alpha_n``, ``sigma_t`` and the arriving velocity),
which moves where the leg lands on the plane of the side it meets, and so the levers and velocities of
every later leg; where it lands, the side's law takes its diffuse share (``sigma_n``; 1 for ``sentman``
and ``dria``) at ``T_r = wall_weight T_w + energy_weight m v^2 / (2 k)`` (``alpha_E``, ``(1 - alpha_E)
k``). Derivatives are carried beside each molecule's weight (and, with CLL, its velocity and position),
one column per material and direction (:mod:`.tangents`).

The exchange (``full``) is linear in its sources, the panel's first re-emission and the chains'
deposits: its derivative is the exchange of their derivatives, plus, for ``schaaf-chambre``, whose
mirrored share ``1 - sigma_n`` the exchange factors follow through mirrors, the change of the exchange
itself: its escape and later responses are differenced by each such material's mirrored share, built
again with the same rays and random numbers (:func:`exchange_slopes`, second order, once per model and
material set, as the optics' exchange factors are in :mod:`sunwind.forces.reflection.sensitivity`).

CLL at ``normal_accommodation`` 1 or ``tangential_accommodation`` 0 with chains is refused
(:func:`check_covered`): a draw's derivative is infinite there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.forces.gas import chain_kernels as kernels
from sunwind.forces.gas.atmosphere import BOLTZMANN
from sunwind.forces.gas.chains import CHAIN_SEED, ChainLaws, Molecules
from sunwind.forces.gas.exchange import MEAN_SPEED_FACTOR, MolecularExchange, open_plate_recoil
from sunwind.forces.gas.laws import GasSurfaces
from sunwind.forces.gas.panel import GasGroups
from sunwind.forces.gas.tangents import DIRECTIONS, INCIDENT_SHARE, by_material
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GSI_MODELS
from sunwind.geometry.spacecraft import BLIND, Spacecraft
from sunwind.geometry.views.exchange_factors import compute_exchange_factors


def check_covered(surfaces: GasSurfaces, mode: str) -> None:
    """Refuse sensitivities of a law with reflections they do not cover (module docstring).

    Parameters
    ----------
    surfaces : GasSurfaces
        The model's distinct laws.
    mode : str
        The reflections mode resolved (``none``, ``plates``, ``specular`` or ``full``).

    Raises
    ------
    InputError
        CLL with ``specular`` or ``full`` at ``normal_accommodation`` 1 or ``tangential_accommodation``
        0, where the derivative of its draws is infinite.

    Examples
    --------
    >>> from sunwind.forces.gas.laws import MODEL_CODES
    >>> cll = GasSurfaces.of({"code": MODEL_CODES["cll"], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 1.0, "tangential_accommodation": 0.5, "wall_temperature_K": 300.0})
    >>> check_covered(cll, "none")
    >>> check_covered(cll, "full")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: sensitivities of CLL materials with reflections 'full' need ...
    """
    cll = surfaces.code == GSI_MODELS.index("cll")
    edge = (surfaces.normal_accommodation[cll] >= 1.0) | (surfaces.tangential_accommodation[cll] <= 0.0)
    if mode in ("specular", "full") and np.any(edge):
        raise InputError(
            f"sensitivities of CLL materials with reflections '{mode}' need normal_accommodation < 1 and "
            "tangential_accommodation > 0: there the chains' CLL draws move infinitely fast with them",
            hint="use reflections 'none' or 'plates', or accommodations inside (0, 1)",
            parameters=("sensitivities", "reflections"),
        )


@dataclass(frozen=True, eq=False)
class Derivatives:
    """Derivatives of force and torque by material and accommodation, summed as they are found.

    Attributes
    ----------
    craft : Spacecraft
        The model.
    reference_m : (3,) float64
        Torque reference point [m].
    force_N, torque_Nm : (n_materials, 3, 3) float64
        ``[material, accommodation (energy, normal, tangential), component]``.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> Derivatives.zeros(craft, np.zeros(3)).force_N.shape
    (1, 3, 3)
    """

    craft: Spacecraft
    reference_m: NDArray[np.float64]
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]

    @classmethod
    def zeros(cls, craft: Spacecraft, reference_m: NDArray[np.float64]) -> Derivatives:
        """None yet.

        Parameters
        ----------
        craft : Spacecraft
            The model.
        reference_m : (3,) float64
            Torque reference point [m].

        Returns
        -------
        Derivatives

        Examples
        --------
        >>> import sunwind as sw
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> float(Derivatives.zeros(craft, np.zeros(3)).torque_Nm.sum())
        0.0
        """
        shape = (len(craft.materials.names), 3, 3)
        return cls(craft, np.asarray(reference_m, float), np.zeros(shape), np.zeros(shape))

    def add_sides(
        self,
        side_coefficient: NDArray[np.int64],
        side_force: NDArray[np.float64],
        side_torque: NDArray[np.float64],
    ) -> None:
        """Add each side's derivative to its material (:func:`~sunwind.forces.gas.tangents.by_material`).

        Parameters
        ----------
        side_coefficient : (n_sides,) int64
            The accommodation of each side's derivative, -1 for none.
        side_force, side_torque : (n_sides, 3) float64
            Derivatives of each side's force [N] and torque [N m].

        Examples
        --------
        >>> import sunwind as sw
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> d = Derivatives.zeros(craft, np.zeros(3))
        >>> d.add_sides(np.full(12, 2), np.ones((12, 3)), np.zeros((12, 3)))
        >>> d.force_N[0, 2]
        array([12., 12., 12.])
        """
        by_material(self.craft, side_coefficient, side_force, side_torque, (self.force_N, self.torque_Nm))

    def add_reflections(
        self,
        chains: ChainTangent,
        emitted: dict[int, tuple[NDArray[np.float64], NDArray[np.int64]]],
        exchange: tuple | None,
    ) -> None:
        """Add the chains' derivatives and those of what the re-emission does (exchange or open plate).

        Parameters
        ----------
        chains : ChainTangent
            The chains' derivatives, found.
        emitted : dict of int to ((2, n_sides) float64, (n_sides,) int64)
            Per direction, the derivative of each side's first re-emission and the accommodation it is
            by (-1 for none); a direction left out re-emits no differently.
        exchange : (MolecularExchange, dict, (2, n_sides) float64) or None
            With ``full``: the exchange, its :func:`exchange_slopes` and its sources (the first
            re-emission and the chains' deposits, momentum and sqrt(mass)-weighted rates); None for
            ``specular``, whose deposits leave as from an open plate.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> d = Derivatives.zeros(craft, np.zeros(3))
        >>> d.add_reflections(ChainTangent.of(craft, gas_groups(craft)), {}, None)
        >>> float(np.abs(d.force_N).sum())
        0.0
        """
        craft, ref = self.craft, self.reference_m
        zero = np.zeros(craft.n_sides)
        if exchange is not None:
            exchange, slopes, sources = exchange
            for material, slope in slopes.items():  # d mirrored / d sigma_n = -1
                escaping = -(slope[:, :6].T @ sources[0] + slope[:, 6:].T @ sources[1])
                force, moment = -escaping[:3], -(escaping[3:] - np.cross(ref, escaping[:3]))
                coefficient = chains.material_coefficient[material, 0]
                self.force_N[material, coefficient] += force
                self.torque_Nm[material, coefficient] += moment
        for (material, direction), coefficient in np.ndenumerate(chains.material_coefficient):
            if coefficient < 0:
                continue
            column = 2 * material + direction
            self.force_N[material, coefficient] += chains.totals[:3, column]
            self.torque_Nm[material, coefficient] += chains.totals[3:, column]
            deposit = chains.deposit[:, :, column]
            if exchange is None:
                totals = open_plate_recoil(craft, deposit[0], ref)
            elif direction in emitted:
                source, side_coefficient = emitted[direction]
                mine = (craft.side_material == material) & (side_coefficient == coefficient)
                totals = exchange.totals(source[0] * mine, source[1] * mine, ref, deposit)
            else:
                totals = exchange.totals(zero, zero, ref, deposit)
            self.force_N[material, coefficient] += totals.force_N
            self.torque_Nm[material, coefficient] += totals.torque_Nm


@dataclass(frozen=True, eq=False)
class ChainTangent:
    """The chains' derivatives by each material's accommodations (module docstring).

    Column ``2 m + d`` of the derivatives is material ``m``'s accommodation of direction ``d``
    (:data:`~sunwind.forces.gas.tangents.DIRECTIONS`). A molecule's state is its weight, and where a
    law is CLL its velocity and position too: ``(d_weight (n, p), d_velocity (n, 3, p) or None,
    d_point (n, 3, p) or None)``.

    Attributes
    ----------
    laws : ChainLaws
        The chains' laws.
    d_mirrored, d_diffuse, d_wall_weight, d_energy_weight : (n_laws,) float64
        Derivatives of each law's ``mirrored``, ``diffuse``, ``wall_weight`` and ``energy_weight`` by
        its direction-0 accommodation.
    side_material : (n_sides,) int64
        Material of each side.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    material_coefficient : (n_materials, 2) int64
        Each material's accommodation of each direction, -1 for none.
    totals : (6, 2 n_materials) float64
        Derivatives of the chains' force [N] and torque [N m]; summed in place.
    deposit : (2, n_sides, 2 n_materials) float64
        Derivatives of the chains' deposits; summed in place.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> tangent = ChainTangent.of(craft, gas_groups(craft))
    >>> tangent.material_coefficient, tangent.d_wall_weight
    (array([[ 0, -1]]), array([1.]))
    """

    laws: ChainLaws
    d_mirrored: NDArray[np.float64]
    d_diffuse: NDArray[np.float64]
    d_wall_weight: NDArray[np.float64]
    d_energy_weight: NDArray[np.float64]
    side_material: NDArray[np.int64]
    normals: NDArray[np.float64]
    material_coefficient: NDArray[np.int64]
    totals: NDArray[np.float64]
    deposit: NDArray[np.float64]

    @classmethod
    def of(cls, craft: Spacecraft, groups: GasGroups) -> ChainTangent:
        """Zero derivatives for the laws of ``craft``.

        Parameters
        ----------
        craft : Spacecraft
            The model.
        groups : GasGroups
            Its sides grouped by law.

        Returns
        -------
        ChainTangent

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> ChainTangent.of(craft, gas_groups(craft)).deposit.shape
        (2, 12, 2)
        """
        surfaces = groups.surfaces
        n_laws = len(surfaces)
        d = {name: np.zeros(n_laws) for name in ("mirrored", "diffuse", "wall", "energy")}
        for row, code in enumerate(surfaces.code):
            model = GSI_MODELS[code]
            if model == "schaaf-chambre":
                d["mirrored"][row], d["diffuse"][row] = -1.0, 1.0
            elif model in INCIDENT_SHARE:
                d["wall"][row], d["energy"][row] = 1.0, -INCIDENT_SHARE[model]
        coefficient = np.array([DIRECTIONS[g.model] for g in craft.materials.gas], dtype=np.int64)
        columns = 2 * len(coefficient)
        return cls(
            laws=ChainLaws.of(surfaces),
            d_mirrored=d["mirrored"],
            d_diffuse=d["diffuse"],
            d_wall_weight=d["wall"],
            d_energy_weight=d["energy"],
            side_material=craft.side_material.astype(np.int64),
            normals=craft.side_normals,
            material_coefficient=coefficient.reshape(-1, 2),
            totals=np.zeros((6, columns)),
            deposit=np.zeros((2, craft.n_sides, columns)),
        )

    def start(self, n: int) -> tuple:
        """The state of ``n`` molecules drawn from the free stream: no derivative.

        Parameters
        ----------
        n : int
            Molecules.

        Returns
        -------
        tuple
            ``(d_weight, d_velocity, d_point)``; the last two None without CLL.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> d_weight, d_velocity, _ = ChainTangent.of(craft, gas_groups(craft)).start(3)
        >>> d_weight.shape, d_velocity
        ((3, 2), None)
        """
        columns = self.totals.shape[1]
        moving = bool(np.any(self.laws.cll))
        vectors = (np.zeros((n, 3, columns)), np.zeros((n, 3, columns))) if moving else (None, None)
        return (np.zeros((n, columns)), *vectors)

    def bounce(
        self,
        molecules: Molecules,
        state: tuple,
        side_law: NDArray[np.int64],
        out_velocity: NDArray[np.float64],
        mass: NDArray[np.float64],
        reference: tuple[NDArray[np.float64], bool, int],
    ) -> tuple:
        """Derivative of what each molecule sends on, as :func:`~sunwind.forces.gas.chain_kernels.bounce`.

        Parameters
        ----------
        molecules : Molecules
            The molecules arriving.
        state : tuple
            Their derivatives (:meth:`start`).
        side_law : (n_sides,) int64
            Law of each side.
        out_velocity : (n, 3) float64
            The kernel's velocities sent on [m/s].
        mass : (k,) float64
            Mass of each species [kg].
        reference : ((3,) float64, bool, int)
            Torque reference point [m], whether the outgoing momentum is booked, and the depth.

        Returns
        -------
        tuple
            The state of what is sent on: derivatives of weight, velocity (or None) and position (or
            None).

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> tangent = ChainTangent.of(craft, gas_groups(craft))
        >>> none = Molecules(np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros((0, 3)),
        ...     np.zeros((0, 3)), np.zeros(0), np.zeros(0, np.int64))
        >>> tangent.bounce(none, tangent.start(0), np.zeros(12, np.int64), np.zeros((0, 3)),
        ...     np.ones(1), (np.zeros(3), True, 1))[0].shape
        (0, 2)
        """
        d_weight, d_velocity, d_point = state
        reference_m, book, depth = reference
        law = side_law[molecules.side]
        mirrored, cll = self.laws.mirrored[law], self.laws.cll[law]
        d_out = d_weight * np.where(cll, 1.0, mirrored)[:, None]
        rows = np.arange(len(law))
        d_out[rows, 2 * self.side_material[molecules.side]] += molecules.weight * self.d_mirrored[law]
        d_out[~cll & (mirrored <= 0.0)] = 0.0
        d_out_velocity = None
        if d_velocity is not None:
            normal = self.normals[molecules.side]
            d_out_velocity = (
                d_velocity - 2.0 * normal[:, :, None] * np.einsum("id,idp->ip", normal, d_velocity)[:, None]
            )
            d_out_velocity[cll] = 0.0
            column = 2 * self.side_material
            kernels.cll_tangents(molecules, depth, side_law, self.normals, mass, self.laws,
                                 np.uint64(CHAIN_SEED), np.ascontiguousarray(d_velocity), column,
                                 d_out_velocity)  # fmt: skip
        if book:
            m = mass[molecules.species]
            lever = molecules.point - reference_m
            self._book(-d_out * m[:, None], lever, out_velocity)
            if d_velocity is not None:
                self._book_moving(-molecules_weight(molecules, law, self.laws) * m, lever, out_velocity,
                                  (d_point, d_out_velocity))  # fmt: skip
        return d_out, d_out_velocity, d_point

    def land(
        self,
        struck: NDArray[np.int64],
        legs: tuple[Molecules, tuple, NDArray[np.float64]],
        side_law: NDArray[np.int64],
        mass: NDArray[np.float64],
        reference_m: NDArray[np.float64],
    ) -> tuple:
        """Derivatives of what :func:`~sunwind.forces.gas.chain_kernels.land` books of each leg.

        Parameters
        ----------
        struck : (n,) int64
            Side each leg meets (negative: escaped, or ``BLIND``).
        legs : (Molecules, tuple, ((n, 3) float64, (n, 3) float64))
            The legs (``point`` their origins, ``velocity``, ``weight``, ``species``, ``side`` the side
            left), their state (:meth:`bounce`), and where each lands and the origin its ray was cast
            from (lifted off the side) [m].
        side_law : (n_sides,) int64
            Law of each side.
        mass : (k,) float64
            Mass of each species [kg].
        reference_m : (3,) float64
            Torque reference point [m].

        Returns
        -------
        tuple
            The legs' state at their landing points.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> tangent = ChainTangent.of(craft, gas_groups(craft))
        >>> leg = Molecules(np.zeros(1, np.int64), np.zeros(1, np.int64), np.zeros((1, 3)),
        ...     np.array([[0.0, 0.0, -1000.0]]), np.ones(1), np.zeros(1, np.int64))
        >>> at = (np.zeros((1, 3)), np.zeros((1, 3)))
        >>> _ = tangent.land(np.array([2]), (leg, (np.ones((1, 2)), None, None), at),
        ...     np.zeros(12, np.int64), np.array([2.66e-26]), np.zeros(3))
        >>> bool(tangent.deposit[0, 2, 0] > 0.0), round(float(tangent.totals[2, 0]) * 1e23, 6)
        (True, -2.66)
        """
        legs, (d_weight, d_velocity, d_point), landing = legs
        hit = (struck >= 0) | (struck == BLIND)
        m = mass[legs.species]
        lever = legs.point - reference_m
        self._book((d_weight * m[:, None])[hit], lever[hit], legs.velocity[hit])
        d_landing = None
        if d_velocity is not None:
            self._book_moving((legs.weight * m)[hit], lever[hit], legs.velocity[hit],
                              (d_point[hit], d_velocity[hit]))  # fmt: skip
            d_landing = _landing(self.normals, struck, (legs.velocity, *landing), (d_velocity, d_point))
        self._deposit(struck, legs, d_weight, side_law, (mass, d_velocity))
        return d_weight, d_velocity, d_landing

    def _deposit(self, struck, legs, d_weight, side_law, moving) -> None:
        """The derivatives of the legs' deposits (``moving`` = species masses, velocity derivatives)."""
        mass, d_velocity = moving
        at = np.flatnonzero(struck >= 0)
        side = struck[at]
        law = side_law[side]
        share = self.laws.diffuse[law]
        at, side, law, share = at[share > 0.0], side[share > 0.0], law[share > 0.0], share[share > 0.0]
        if not len(at):
            return
        m, weight, material = mass[legs.species[at]], legs.weight[at], self.side_material[side]
        energy = m * np.sum(legs.velocity[at] ** 2, axis=1) / (2.0 * BOLTZMANN)
        wall = self.laws.wall_temperature_K[law]
        temperature = self.laws.wall_weight[law] * wall + self.laws.energy_weight[law] * energy
        momentum = m * MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * temperature / m)
        rows = np.arange(len(at))
        d_rate = d_weight[at] * share[:, None]
        d_rate[rows, 2 * material] += weight * self.d_diffuse[law]
        d_momentum = d_rate * momentum[:, None]
        d_temperature = np.zeros_like(d_rate)
        d_temperature[rows, 2 * material] = (
            self.d_wall_weight[law] * wall + self.d_energy_weight[law] * energy
        )
        if d_velocity is not None:  # T_r moves with the speed squared
            speed_change = np.einsum("id,idp->ip", legs.velocity[at], d_velocity[at])
            d_temperature += (self.laws.energy_weight[law] * m / BOLTZMANN)[:, None] * speed_change
        d_momentum += (weight * share * momentum / (2.0 * temperature))[:, None] * d_temperature
        np.add.at(self.deposit[0], side, d_momentum)
        np.add.at(self.deposit[1], side, d_rate * np.sqrt(m)[:, None])

    def _book(self, scale: NDArray[np.float64], lever: NDArray[np.float64], velocity: NDArray) -> None:
        """Add ``scale[i, p] v_i`` acting at ``lever_i`` from the reference to column ``p`` of
        :attr:`totals`."""
        self.totals[:3] += velocity.T @ scale
        self.totals[3:] += np.cross(lever, velocity).T @ scale

    def _book_moving(self, scale, lever, velocity, moving) -> None:
        """Add the derivative of ``scale_i v_i`` at ``lever_i`` where ``v`` and the lever move
        (``moving`` = their derivatives, (n, 3, p) each)."""
        d_lever, d_velocity = moving
        self.totals[:3] += np.einsum("i,idp->dp", scale, d_velocity)
        turn = _cross(d_lever, velocity[:, :, None]) + _cross(lever[:, :, None], d_velocity)
        self.totals[3:] += np.einsum("i,idp->dp", scale, turn)


def molecules_weight(molecules: Molecules, law: NDArray[np.int64], laws: ChainLaws) -> NDArray[np.float64]:
    """The weight each molecule sends on, as :func:`~sunwind.forces.gas.chain_kernels.bounce` gives it.

    Parameters
    ----------
    molecules : Molecules
        The molecules arriving.
    law : (n,) int64
        Law of the side each arrives at.
    laws : ChainLaws
        The chains' laws.

    Returns
    -------
    (n,) float64
        All of it for CLL, the mirrored share for the others.

    Examples
    --------
    >>> from sunwind.forces.gas.laws import MODEL_CODES
    >>> laws = ChainLaws.of(GasSurfaces.of({"code": [MODEL_CODES["schaaf-chambre"]],
    ...     "energy_accommodation": 1.0, "normal_accommodation": 0.25, "tangential_accommodation": 1.0,
    ...     "wall_temperature_K": 300.0}))
    >>> one = Molecules(np.zeros(1, np.int64), np.zeros(1, np.int64), np.zeros((1, 3)), np.zeros((1, 3)),
    ...     np.ones(1), np.zeros(1, np.int64))
    >>> molecules_weight(one, np.zeros(1, np.int64), laws)
    array([0.75])
    """
    return molecules.weight * np.where(laws.cll[law], 1.0, np.maximum(laws.mirrored[law], 0.0))


def _cross(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """``a x b`` along axis 1, broadcast over the others."""
    return np.stack(
        [
            a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1],
            a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
            a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
        ],
        axis=1,
    )


def _landing(normals, struck, legs, moving) -> NDArray[np.float64]:
    """Derivative of where each leg meets the plane of the side it strikes (zero where it strikes none):
    ``x = o + t d`` with ``n . x`` fixed; ``legs`` = velocities, landing points and the rays' origins,
    ``moving`` = the derivatives of velocity and origin."""
    d_velocity, d_point = moving
    velocity, landing, origin = legs
    out = np.zeros_like(d_point)
    at = np.flatnonzero(struck >= 0)
    if not len(at):
        return out
    velocity, d_velocity = velocity[at], d_velocity[at]
    speed = np.linalg.norm(velocity, axis=1)
    direction = velocity / speed[:, None]
    along = np.einsum("id,idp->ip", direction, d_velocity)
    d_direction = (d_velocity - direction[:, :, None] * along[:, None]) / speed[:, None, None]
    n = normals[struck[at]]
    t = np.einsum("id,id->i", landing[at] - origin[at], direction)
    moved = d_point[at] + t[:, None, None] * d_direction
    d_t = -np.einsum("id,idp->ip", n, moved) / np.einsum("id,id->i", n, direction)[:, None]
    out[at] = moved + direction[:, :, None] * d_t[:, None]
    return out


#: Step of the differenced exchange in the mirrored share [-] (as the optics' exchange factors).
EXCHANGE_STEP = 1e-4


def exchange_slopes(
    craft: Spacecraft, exchange: MolecularExchange, mirrored: NDArray[np.float64], cache_key: tuple
) -> dict[int, NDArray[np.float64]]:
    """Derivatives of the exchange's escape and later responses by each ``schaaf-chambre`` material's
    mirrored share, kept in the model's cache.

    The exchange factors follow molecules through mirrors along traced rays: those of the rows whose
    molecules reach the material's sides are built again with the same rays and random numbers at the
    mirrored share moved there, and differenced (central, second order; one-sided second order at a
    bound); the balance's adjoint is linearised about the model's (one solve per material). Once per
    model and material set.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    exchange : MolecularExchange
        Its molecular exchange (view factors and all).
    mirrored : (n_sides,) float64
        The share each side mirrors.
    cache_key : tuple
        What the exchange is kept under (its view factors' settings).

    Returns
    -------
    dict of int to (n_sides, 12) float64
        Per ``schaaf-chambre`` material with sides, ``d escape`` and ``d later`` (6 columns each, as
        :class:`~sunwind.forces.gas.exchange.MolecularExchange`) per unit of its mirrored share.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.exchange import molecular_exchange
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> settings = sw.ReflectionSettings("full", rays_per_side=16, cache_dir=False)
    >>> mirrored = np.zeros(craft.n_sides)
    >>> exchange_slopes(craft, molecular_exchange(craft, settings, mirrored), mirrored, settings.view_key)
    {}
    """
    key = ("molecular exchange slopes", *cache_key)
    return craft.cache.get(key, lambda: _slopes(craft, exchange, mirrored))


def _slopes(
    craft: Spacecraft, exchange: MolecularExchange, mirrored: NDArray[np.float64]
) -> dict[int, NDArray[np.float64]]:
    """Per material: ``d escape`` from the exchange factors differenced on the rows whose molecules
    reach its sides, and ``d later`` from the balance linearised about the model's (``M^T g = w``, ``M^T
    = I - E diag(rho_d)``: ``dg = M^-T (dw + (dE diag(rho_d) + E diag(d rho_d)) g)``, ``later = E
    diag(rho_d) g``)."""
    out, h = {}, EXCHANGE_STEP
    factors, n = exchange.balance.factors, craft.n_sides
    re_emitted = 1.0 - mirrored
    wall_speed = MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * craft.side_gas["wall_temperature_K"])
    adjoint = None
    for material, gas in enumerate(craft.materials.gas):
        mine = craft.side_material == material
        if gas.model != "schaaf-chambre" or not mine.any():
            continue
        rows = np.flatnonzero(factors.matrix @ mine.astype(np.float64) > 0)
        if not len(rows):
            continue
        value = float(mirrored[mine][0])
        if value < h:
            steps, weights = (0.0, h, 2 * h), (-1.5, 2.0, -0.5)
        elif value > 1.0 - h:
            steps, weights = (0.0, -h, -2 * h), (1.5, -2.0, 0.5)
        else:
            steps, weights = (-h, h), (-0.5, 0.5)
        keep = scipy.sparse.diags(np.isin(np.arange(n), rows).astype(np.float64))
        d_matrix = scipy.sparse.csr_matrix((n, n))
        d_escape = np.zeros((n, 6))
        for step, weight in zip(steps, weights, strict=True):
            moved = factors
            if step != 0.0:
                optics = np.column_stack([np.ones(n), mirrored + step * mine, np.zeros(n)])
                moved = compute_exchange_factors(craft, exchange.view, optics=optics, rows=rows)
            d_matrix = d_matrix + (weight / h) * (keep @ moved.matrix)
            vector = moved.escape_vector[rows]
            moment = np.cross(craft.side_centroids[rows], vector) + moved.escape_moment[rows]
            d_escape[rows] += (weight / h) * np.column_stack([vector, moment])
        d_matrix = d_matrix.tocsr()
        if adjoint is None:
            adjoint = exchange.balance.adjoint(wall_speed[:, None] * exchange.escape)
        d_re_emitted = -mine.astype(np.float64)
        source = d_matrix @ (re_emitted[:, None] * adjoint) + factors.matrix @ (
            d_re_emitted[:, None] * adjoint
        )
        d_adjoint = exchange.balance.adjoint(wall_speed[:, None] * d_escape + source)
        d_later = source + factors.matrix @ (re_emitted[:, None] * d_adjoint)
        out[material] = np.column_stack([d_escape, d_later])
    return out
