"""What an extended source (a planet's albedo or infrared) or the Sun does to the spacecraft: the force
law summed over each side's share of the source, self-shadowing, inter-reflection, and the power each
side absorbs (METHOD.md "Planet radiation").

A source is given per side by its unshadowed integrals ``I_0, I_1, I_2``
(:meth:`~sunwind.forces.planet.cap.Cap.side_integrals`) and by cells, each a direction ``w_k`` and an
irradiance ``W_k`` it sends. Eq. (4) integrated over the source gives the open force on a side of area
``A`` and outward normal ``n``

    F = -(A / c) [ (1 - sigma - rho_s) I_1 + (2 rho_s I_2 + (2/3) rho_d I_0) n ]

(a parallel beam of flux ``Phi`` has ``I_0 = Phi cos``, ``I_1 = Phi cos u``, ``I_2 = Phi cos^2``).
Shadowing is a correction: a shadow pass along each cell direction gives each side's lit share
``f_k``, and the side loses ``(1 - f_k)`` of what cell ``k`` alone would give it (``W_k`` times the
parallel-beam law at ``w_k``), its torque moved to the lit centroid. A side no other side can shadow
keeps its exact integrals; a convex model casts no rays. For the Sun the one cell is the Sun itself,
so the correction is the shadow pass itself. Reflections follow as for sunlight: each cell's mirror and
transmitted beams are followed (:func:`~sunwind.forces.reflection.follow_chains`), diffuse light through
the adjoint of the diffuse balance, and the absorbed power of each side comes from the balance solved
forward.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.error_estimate import summed
from sunwind.forces.planet.lit_law import cell_error, law, open_force
from sunwind.forces.planet.visibility import BANDS, Visibility
from sunwind.forces.reflection import BeamChainTotals, PowerBalance, ReflectionSettings, follow_chains
from sunwind.forces.reflection.diffuse import MOMENTA, DiffuseExchange, DiffuseTotals
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import Illumination, side_sampler
from sunwind.geometry.sides import TWO_SIDED
from sunwind.geometry.spacecraft import Spacecraft


@dataclass(frozen=True)
class Source:
    """One band of light on the spacecraft before shadowing.

    Attributes
    ----------
    name : str
        "solar", "albedo", "infrared".
    integrals : tuple of (n_sides,), (n_sides, 3), (n_sides,) float64
        ``I_0, I_1, I_2`` of every side, unshadowed [W/m^2].
    weights : (k,) float64
        Irradiance of each cell [W/m^2] (cells shared by all sources of one call).
    optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of every side in this band.
    beams : bool
        Whether mirror and transmitted beams are followed (the solar band with reflections).
    exchange : DiffuseExchange or None
        The diffuse balance in this band (``full`` reflections), else None.

    Examples
    --------
    Sunlight is a source of one cell, the Sun, whose integrals are those of a parallel beam:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> cos = np.maximum(craft.side_normals @ up, 0.0)
    >>> i0 = 1361.0 * cos  # the Sun overhead, 1361 W/m^2
    >>> sun = Source("solar", (i0, i0[:, None] * up, i0 * cos), np.array([1361.0]), craft.side_optics,
    ...              beams=False, exchange=None)
    >>> float(sun.integrals[0].sum())  # both triangles of the top face, 1361 W/m^2 each
    2722.0
    """

    name: str
    integrals: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]
    weights: NDArray[np.float64]
    optics: NDArray[np.float64]
    beams: bool
    exchange: DiffuseExchange | None


@dataclass(eq=False)
class ReflectedPower:
    """Where a band's reflected light ends on the spacecraft, the diffuse balance solved on first use.

    Each side absorbs ``(1 - rho - sigma)`` of the beam power that lands on it (``beams_arrived_W``) and of
    the diffuse light that reaches it, ``E^T W`` with ``W = exchange.solve(source_W)`` the diffuse power
    leaving each side. The forces need no forward solve (they come from the adjoint), so it is done only
    when the powers are asked for, and :func:`solve_reflected` does the bands sharing an exchange in one.

    Parameters
    ----------
    absorptance : (n_sides,) float64
        ``1 - rho - sigma`` of each side in the band.
    beams_arrived_W : (n_sides,) float64
        Beam power landing on each side [W].
    beam_lost_W : float
        Beam power lost before the diffuse balance (on no side, or cut off) [W].
    exchange : DiffuseExchange or None
        The band's diffuse balance; None: diffuse light leaves to open sky.
    source_W : (n_sides,) float64 or None
        Diffuse power each side sends into the balance [W].

    Examples
    --------
    >>> import numpy as np
    >>> no_exchange = ReflectedPower(np.full(2, 0.5), np.array([2.0, 0.0]), 0.25, None, None)
    >>> no_exchange.absorbed_side_W(), no_exchange.lost_W()
    (array([1., 0.]), 0.25)
    """

    absorptance: NDArray[np.float64]
    beams_arrived_W: NDArray[np.float64]
    beam_lost_W: float
    exchange: DiffuseExchange | None = None
    source_W: NDArray[np.float64] | None = None
    emitted_W: NDArray[np.float64] | None = field(default=None, repr=False)

    def absorbed_side_W(self) -> NDArray[np.float64]:
        """Power each side absorbs after reflections [W], (n_sides,)."""
        arrived = self.beams_arrived_W
        if self.exchange is not None:
            arrived = arrived + self.exchange.factors.matrix.T @ self._emitted()
        return self.absorptance * arrived

    def lost_W(self) -> float:
        """Reflected power on no side or cut off [W]."""
        if self.exchange is None:
            return self.beam_lost_W
        factors = self.exchange.factors
        return self.beam_lost_W + float(
            self._emitted() @ (factors.blind_fraction + factors.truncated_fraction)
        )

    def absorbed_by_group(self, group: NDArray[np.int64], count: int) -> NDArray[np.float64]:
        """Power each group of sides absorbs after reflections [W], (count,), without the forward solve.

        The diffuse share is a linear functional of the sources: the sides of group ``g`` absorb
        ``(M^-T E (a 1_g))^T S``, so the exchange's responses of the groups
        (:meth:`~sunwind.forces.reflection.diffuse.DiffuseExchange.group_absorption`) make it a dot
        product. Once the balance has been solved forward, its solution is summed instead.

        Parameters
        ----------
        group : (n_sides,) int64
            Group of each side (the part, say), in ``[0, count)``.
        count : int
            Number of groups.

        Returns
        -------
        (count,) float64
            ``absorbed_side_W()`` summed by group.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.reflection import reflection_plan
        >>> white = sw.Material("white", reflectivity=0.8, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=white, threads=1).craft
        >>> exchange = reflection_plan(craft, sw.ReflectionSettings("full")).exchange
        >>> source = np.where(np.arange(craft.n_sides) == 0, 10.0, 0.0)
        >>> dark, nothing = np.full(craft.n_sides, 0.2), np.zeros(craft.n_sides)
        >>> part = craft.facet_part[craft.side_facet]
        >>> by_adjoint = ReflectedPower(dark, nothing, 0.0, exchange, source).absorbed_by_group(part, 3)
        >>> sides = ReflectedPower(dark, nothing, 0.0, exchange, source).absorbed_side_W()
        >>> forward = np.bincount(part, sides, 3)
        >>> bool(np.allclose(by_adjoint, forward, rtol=1e-9))
        True
        """
        beams = np.bincount(group, self.absorptance * self.beams_arrived_W, count)
        if self.exchange is None:
            return beams
        if self.emitted_W is not None:
            return np.bincount(
                group, self.absorptance * (self.exchange.factors.matrix.T @ self.emitted_W), count
            )
        return beams + self.exchange.group_absorption(self.absorptance, group, count).T @ self.source_W

    def _emitted(self) -> NDArray[np.float64]:
        if self.emitted_W is None:
            solve_reflected([self])
        return self.emitted_W


def solve_reflected(powers: Sequence[ReflectedPower]) -> None:
    """Solve the diffuse balances of several bands, one solve (of several columns) per exchange.

    Parameters
    ----------
    powers : sequence of ReflectedPower
        The bands' reflected power (``load.reflections``); those already solved or without an exchange are
        left as they are.

    Returns
    -------
    None
        Each one's ``emitted_W`` is set.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import reflection_plan
    >>> white = sw.Material("white", reflectivity=0.8, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=white, threads=1).craft
    >>> exchange = reflection_plan(craft, sw.ReflectionSettings("full")).exchange
    >>> source = np.where(np.arange(craft.n_sides) == 0, 10.0, 0.0)
    >>> dark, nothing = np.full(craft.n_sides, 0.2), np.zeros(craft.n_sides)
    >>> a, b = (ReflectedPower(dark, nothing, 0.0, exchange, s * source) for s in (1.0, 2.0))
    >>> solve_reflected([a, b])
    >>> bool(np.allclose(2 * a.absorbed_side_W(), b.absorbed_side_W()))
    True
    """
    groups: dict[int, list[ReflectedPower]] = {}
    for power in powers:
        if power.exchange is not None and power.emitted_W is None:
            groups.setdefault(id(power.exchange), []).append(power)
    for group in groups.values():
        emitted = group[0].exchange.solve(np.column_stack([p.source_W for p in group]))
        for k, power in enumerate(group):
            power.emitted_W = emitted[:, k]


@dataclass(frozen=True, eq=False, kw_only=True)
class BandLoad:
    """What one band does at one attitude; body frame, SI.

    Attributes
    ----------
    name : str
        The band: "solar", "albedo" or "infrared" (the :class:`Source`'s name).
    force_N, torque_Nm : (3,) float64
        Totals (torque about the reference point).
    direct_force_N, direct_torque_Nm : (3,) float64
        The law over each side's share of the source, with shadowing, reflected light escaping.
    reflected_force_N, reflected_torque_Nm : (3,) float64
        What inter-reflection changes.
    power : PowerBalance
        Incident (the power the spacecraft intercepts), absorbed, escaped, truncated [W].
    incident_side_W : (n_sides,) float64
        Power arriving at each side from the source, shadowing included [W].
    absorbed_side_W : (n_sides,) float64
        Of it, what each side absorbs [W].
    rays : int
        Shadow and beam rays cast.
    shadow_error : LoadsError or None
        The shadow passes' estimated absolute error in the direct force [N] and torque [N m]: each
        cell's pass's (from its check and the cell's load per unit lit area), added over the cells; 0
        where no side can be shadowed; None with fixed sampling or without shadowing (plates).
    reflections : ReflectedPower
        Where the band's reflected light ends on the spacecraft: :attr:`reflected_side_W` (power each side
        absorbs after one or more reflections [W]) and :attr:`lost_W` (reflected power absorbed where the
        model has no side, inside a closed body, in ``power.absorbed_W``, or dropped by a chain's cutoff,
        ``power.truncated_W`` [W]); the diffuse balance is solved forward on first use.
    traced : tuple of BeamChainTotals
        The cells' beam chains, when they were traced with derivatives (``band_loads(...,
        derivatives=True)``); else empty.

    Examples
    --------
    Made by :func:`band_loads`, as by :func:`~sunwind.forces.earth.planet_radiation` for each band:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> cos = np.maximum(craft.side_normals @ up, 0.0)
    >>> i0 = 1361.0 * cos  # the Sun overhead, 1361 W/m^2
    >>> sun = Source("solar", (i0, i0[:, None] * up, i0 * cos), np.array([1361.0]), craft.side_optics,
    ...              beams=False, exchange=None)
    >>> shadows, settings = sw.ShadowSampling(), sw.ReflectionSettings("none")
    >>> (load,), rays = band_loads(craft, [sun], up[None, :], np.zeros(3), shadows, settings)
    >>> load.name, round(load.power.incident_W, 6), round(load.power.absorbed_W, 6)
    ('solar', 1361.0, 952.7)
    """

    name: str
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    direct_force_N: NDArray[np.float64]
    direct_torque_Nm: NDArray[np.float64]
    reflected_force_N: NDArray[np.float64]
    reflected_torque_Nm: NDArray[np.float64]
    power: PowerBalance
    incident_side_W: NDArray[np.float64]
    absorbed_side_W: NDArray[np.float64]
    rays: int
    shadow_error: LoadsError | None = None
    reflections: ReflectedPower = field(repr=False)
    traced: tuple[BeamChainTotals, ...] = field(default=(), repr=False)

    @property
    def reflected_side_W(self) -> NDArray[np.float64]:
        """Power each side absorbs of the band's light after one or more reflections [W], (n_sides,)
        (the diffuse balance solved forward on first use: :func:`solve_reflected`)."""
        return self.reflections.absorbed_side_W()

    @property
    def lost_W(self) -> float:
        """Reflected power absorbed where the model has no side, or dropped by a chain's cutoff [W]."""
        return self.reflections.lost_W()

    def to_json(self) -> dict:
        """A plain-JSON summary: the totals, the direct and reflected parts and the power balance.

        Returns
        -------
        dict
            ``force_N``, ``torque_Nm``, ``direct`` and ``reflected`` (each with ``force_N`` and
            ``torque_Nm``) as lists, and ``power`` (:meth:`PowerBalance.to_json`); keys carry their units.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> up = np.array([0.0, 0.0, 1.0])
        >>> cos = np.maximum(craft.side_normals @ up, 0.0)
        >>> i0 = 1361.0 * cos  # the Sun overhead, 1361 W/m^2
        >>> sun = Source("solar", (i0, i0[:, None] * up, i0 * cos), np.array([1361.0]), craft.side_optics,
        ...              beams=False, exchange=None)
        >>> shadows, settings = sw.ShadowSampling(), sw.ReflectionSettings("none")
        >>> (load,), _ = band_loads(craft, [sun], up[None, :], np.zeros(3), shadows, settings)
        >>> sorted(load.to_json())
        ['direct', 'force_N', 'power', 'reflected', 'torque_Nm']
        """
        return {
            "force_N": self.force_N.tolist(),
            "torque_Nm": self.torque_Nm.tolist(),
            "direct": {"force_N": self.direct_force_N.tolist(), "torque_Nm": self.direct_torque_Nm.tolist()},
            "reflected": {
                "force_N": self.reflected_force_N.tolist(),
                "torque_Nm": self.reflected_torque_Nm.tolist(),
            },
            "power": self.power.to_json(),
        }


class _Running:
    """What the cells of one source add up: shadow corrections, the passes' errors and beam chains."""

    def __init__(self, n_sides: int, shadow_error: LoadsError | None) -> None:
        self.lost_i0 = np.zeros(n_sides)
        self.lost_i1 = np.zeros((n_sides, 3))
        self.lost_i2 = np.zeros(n_sides)
        self.shift_torque = np.zeros(3)  # [N m]: forces moved to the lit centroids
        self.shadow_error = shadow_error
        self.chains: list[BeamChainTotals] = []


def band_loads(
    craft: Spacecraft,
    sources: Sequence[Source],
    directions: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    sampling: ShadowSampling,
    settings: ReflectionSettings,
    observe: Callable[[int, Illumination], None] | None = None,
    derivatives: bool = False,
) -> tuple[list[BandLoad], int]:
    """The load of each band of light on the spacecraft, one shadow pass per cell serving every band.

    Each side starts from its exact unshadowed integrals; a shadow pass along each cell direction
    takes off what the side's dark part misses of that cell (the parallel-beam law), and moves the lit
    part's force to its lit centroid. Mirror and transmitted beams are followed for sources with
    ``beams``, and diffuse light through each source's ``exchange``. A convex model, or the ``plates``
    mode, casts no rays: every side sees the whole source.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft.
    sources : sequence of Source
        The bands, their cells along ``directions`` (each ``weights`` of length k).
    directions : ndarray of float64, shape (k, 3)
        Unit direction of each cell from the spacecraft, body frame.
    reference_m : ndarray of float64, shape (3,)
        Torque reference point [m], body frame.
    sampling : ShadowSampling
        How each cell's shadow pass samples the sides.
    settings : ReflectionSettings
        Where beam chains stop (``cutoff``, ``depth``); the ``plates`` mode shadows nothing.
    observe : callable, optional
        ``observe(k, light)`` is given every shadow pass as it is cast (cell ``k``), so that what else
        depends on the cells' lit shares (the derivatives,
        :class:`~sunwind.forces.planet.sensitivity.CellShares`) needs no pass of its own.
    derivatives : bool
        Trace the beam chains with their derivatives in every material's optics, kept per cell in
        :attr:`BandLoad.traced`.

    Returns
    -------
    loads : list of BandLoad
        One per source, in order.
    rays : int
        Shadow rays cast (beam rays are in each load's ``rays``).

    References
    ----------
    .. [1] Shmatov, S. I., Mordvinkin, A. S. (2013). Joint computation of the aerodynamic and radiation
       force effects on spacecraft. *Vestnik NPO im. S. A. Lavochkina*; eq. (4), the law on a lit area.
    .. [2] Rosborough, G. W., Antreasian, P. G. (1990). "Radiation force modeling for the
       TOPEX/POSEIDON spacecraft." AIAA Paper 90-2895.

    Examples
    --------
    Sunlight overhead on a grey cube, a parallel beam: the law of eq. (4) [1]_, with no ray cast on a
    convex model.

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> cos = np.maximum(craft.side_normals @ up, 0.0)
    >>> i0 = 1361.0 * cos  # the Sun overhead, 1361 W/m^2
    >>> sun = Source("solar", (i0, i0[:, None] * up, i0 * cos), np.array([1361.0]), craft.side_optics,
    ...              beams=False, exchange=None)
    >>> shadows, settings = sw.ShadowSampling(), sw.ReflectionSettings("none")
    >>> (load,), rays = band_loads(craft, [sun], up[None, :], np.zeros(3), shadows, settings)
    >>> rays, np.round(load.force_N * 1e6, 4) + 0.0  # [uN], away from the Sun
    (0, array([ 0.    ,  0.    , -5.4478]))
    """
    samples, tolerance, cutoff, depth = sampling.samples, sampling.tolerance, settings.cutoff, settings.depth
    shadows = settings.mode != "plates"  # plates: every side alone, sees the whole source
    checked = shadows and sampling.estimates  # the default pass estimates its error; 0 when convex
    running = [_Running(craft.n_sides, LoadsError(0.0, 0.0) if checked else None) for _ in sources]
    sampler = side_sampler(craft)
    shadowing = shadows and not bool(np.all(clearance(craft).open_sky))
    rays = 0
    for k, direction in enumerate(directions):
        live = [(s, r) for s, r in zip(sources, running, strict=True) if s.weights[k] > 0]
        if not live or not shadowing:  # on a convex model every side sees the whole source, and every
            continue  # reflected beam escapes
        light = sampler.illuminate(direction, samples, tolerance)
        rays += light.rays
        if observe is not None:
            observe(k, light)
        facing, share = light.facing, light.facing_share.astype(np.float64)
        dark = facing[share < 1.0]
        dark_share = share[share < 1.0]
        for source, sums in live:
            weight = float(source.weights[k])
            if len(dark):
                _shadow(craft, source.optics, direction, weight, dark, dark_share, light.lit_centroid, sums)
            if light.check is not None:
                error = cell_error(craft, source.optics, (direction, weight), light.check, reference_m)
                sums.shadow_error = summed([sums.shadow_error, error])
            if source.beams and shadowing:
                chains = follow_chains(
                    craft, light, weight, reference_m, cutoff, depth, light.level, derivatives=derivatives
                )
                rays += chains.rays
                sums.chains.append(chains)
    return [_finish(craft, s, r, reference_m) for s, r in zip(sources, running, strict=True)], rays


def grid_band_loads(
    craft: Spacecraft,
    sources: Sequence[Source],
    seen: Visibility,
    reference_m: NDArray[np.float64],
    estimates: bool,
    coarser: NDArray[np.float64] | None = None,
) -> list[BandLoad]:
    """The load of each band from a model's precomputed directional visibility: no ray is cast.

    As :func:`band_loads`, with the cells the nodes of ``seen.grid`` and each source's ``weights`` its
    irradiance spread on them (:meth:`~sunwind.forces.planet.visibility.DirectionGrid.weights`): what
    the sides lose to shadow is ``S W``, the lit-centroid torque and the passes' errors are dot products
    with the per-node values, and the beam chains (sources with ``beams``) are those of the nodes times
    ``W``.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft ``seen`` was built for.
    sources : sequence of Source
        The bands; ``weights`` of length ``len(seen.grid.nodes)``; a source named "infrared" takes the
        infrared values, any other the solar ones.
    seen : Visibility
        The model's visibility (:func:`~sunwind.forces.planet.visibility.visibility`).
    reference_m : (3,) float64
        Torque reference point [m], body frame.
    estimates : bool
        Report the passes' error (the sampling estimates it); else ``shadow_error`` is None.
    coarser : (n, b) float64, optional
        Each source's irradiance spread on the grid a level coarser (its nodes the first of this grid's,
        zero beyond): the interpolation is second order in the spacing, so a third of the change of the
        loads between the two grids (through the same matrices; diffuse exchange left out) is added to each
        band's error as the grid's.

    Returns
    -------
    list of BandLoad
        One per source, in order; ``rays`` 0.

    Examples
    --------
    A uniform source all around a box-and-wing model, spread on the level-2 grid:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.planet.visibility import visibility
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=grey, threads=1).craft
    >>> seen = visibility(craft, 2, sw.ShadowSampling(), sw.ReflectionSettings("none"))
    >>> weights = np.full(len(seen.grid.nodes), 1.0)
    >>> cos = np.maximum(craft.side_normals @ seen.grid.nodes.T, 0.0)  # (n_sides, n)
    >>> i0 = cos @ weights
    >>> integrals = (i0, (cos * weights) @ seen.grid.nodes, (cos**2) @ weights)
    >>> glow = Source("infrared", integrals, weights, craft.side_optics, beams=False, exchange=None)
    >>> (load,) = grid_band_loads(craft, [glow], seen, np.zeros(3), estimates=True)
    >>> bool(load.power.incident_W < float((craft.side_areas * i0).sum()))  # the bus shades the wings
    True
    """
    nodes = seen.grid.nodes
    weights = np.column_stack([source.weights for source in sources])  # (n, b)
    if coarser is not None:  # the same matrices serve the grid's error
        weights = np.concatenate([weights, weights - coarser], axis=1)
    n, b = weights.shape
    columns = np.concatenate([weights, (weights[:, :, None] * nodes[:, None, :]).reshape(n, 3 * b)], axis=1)
    lost, lost2 = seen.shadow @ columns, seen.shadow2 @ weights

    def losses(k: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        return lost[:, k], lost[:, b + 3 * k : b + 3 * k + 3], lost2[:, k]

    reach = float(np.linalg.norm(reference_m))
    out = []
    for k, source in enumerate(sources):
        band = _band(source)
        w = weights[:, k]
        error = None
        if estimates and seen.error_force_N is not None:
            force_error = float(w @ seen.error_force_N[band])
            error = LoadsError(force_error, float(w @ seen.error_torque_Nm[band]) + reach * force_error)
            if coarser is not None:
                j = len(sources) + k
                change = _grid_change(craft, source, seen, losses(j), weights[:, j], reference_m)
                error = summed([error, LoadsError(change.force_N / 3.0, change.torque_Nm / 3.0)])
        sums = _Running(craft.n_sides, error)
        sums.lost_i0, sums.lost_i1, sums.lost_i2 = losses(k)
        sums.shift_torque = w @ seen.shift_torque_Nm[band]
        if source.beams and seen.chains is not None:
            sums.chains.append(_node_chains(seen, w, reference_m))
        out.append(_finish(craft, source, sums, reference_m))
    return out


def _grid_change(
    craft: Spacecraft,
    source: Source,
    seen: Visibility,
    lost: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    difference: NDArray[np.float64],
    reference_m: NDArray[np.float64],
) -> LoadsError:
    """The size of the load node irradiances ``difference`` make (their losses ``lost`` = ``dI_0, dI_1,
    dI_2``): the shadow losses, the lit-centroid torque and the beam chains (diffuse exchange left out)."""
    side_force = -open_force(craft.side_normals, craft.side_areas, source.optics, *lost)
    force = side_force.sum(axis=0)
    band = _band(source)
    lever = craft.side_centroids - reference_m
    torque = np.cross(lever, side_force).sum(axis=0) + difference @ seen.shift_torque_Nm[band]
    if source.beams and seen.chains is not None:
        chains = _node_chains(seen, difference, reference_m)
        force, torque = force + chains.force_N, torque + chains.torque_Nm
    return LoadsError(float(np.linalg.norm(force)), float(np.linalg.norm(torque)))


def _band(source: Source) -> int:
    """Index in :data:`~sunwind.forces.planet.visibility.BANDS` of the optics ``source`` takes."""
    return BANDS.index("infrared" if source.name == "infrared" else "solar")


def _node_chains(
    seen: Visibility, weights: NDArray[np.float64], reference_m: NDArray[np.float64]
) -> BeamChainTotals:
    """The nodes' beam chains at irradiances ``weights``, torques about ``reference_m``."""
    chains = seen.chains
    force, open_force = weights @ chains.force_N, weights @ chains.open_sky_force_N
    live = weights > 0
    return BeamChainTotals(
        force_N=force,
        torque_Nm=weights @ chains.torque_Nm - np.cross(reference_m, force),
        diffuse_source_W=chains.diffuse_source_W @ weights,
        arrived_W=chains.arrived_W @ weights,
        open_sky_force_N=open_force,
        open_sky_torque_Nm=weights @ chains.open_sky_torque_Nm - np.cross(reference_m, open_force),
        escaped_W=float(weights @ chains.escaped_W),
        absorbed_W=float(weights @ chains.absorbed_W),
        truncated_W=float(weights @ chains.truncated_W),
        first_W=float(weights @ chains.first_W),
        rays=0,
        depth=int(chains.depth[live].max(initial=0)),
    )


def _shadow(
    craft: Spacecraft,
    optics: NDArray[np.float64],
    direction: NDArray[np.float64],
    weight: float,
    sides: NDArray[np.int64],
    share: NDArray[np.float64],
    lit_centroid: NDArray[np.float64],
    sums: _Running,
) -> None:
    """Take off what the shadowed part of ``sides`` (lit ``share``) misses of a cell of irradiance
    ``weight`` along ``direction``, and move the lit part's force to its lit centroid."""
    normals = craft.side_normals[sides]
    cos = normals @ direction
    lost = weight * cos * (1.0 - share)
    np.add.at(sums.lost_i0, sides, lost)
    np.add.at(sums.lost_i1, sides, lost[:, None] * direction)
    np.add.at(sums.lost_i2, sides, lost * cos)
    lit_force = law(normals, craft.side_areas[sides], optics[sides], weight * cos * share, direction, cos)
    offset = lit_centroid[sides] - craft.side_centroids[sides]
    sums.shift_torque += np.cross(offset, lit_force).sum(axis=0)


def _finish(craft: Spacecraft, source: Source, sums: _Running, reference_m: NDArray[np.float64]) -> BandLoad:
    """The totals of one source from its integrals and what its cells added."""
    i0, i1, i2 = source.integrals
    i0, i1, i2 = i0 - sums.lost_i0, i1 - sums.lost_i1, i2 - sums.lost_i2
    # a side that sees a sliver of a cell may lose more than its exact share: it is dark
    dark = i0 <= 0.0
    i0, i1, i2 = np.where(dark, 0.0, i0), np.where(dark[:, None], 0.0, i1), np.where(dark, 0.0, i2)
    areas, optics = craft.side_areas, source.optics
    side_force = open_force(craft.side_normals, areas, optics, i0, i1, i2)
    force = side_force.sum(axis=0)
    torque = np.cross(craft.side_centroids - reference_m, side_force).sum(axis=0) + sums.shift_torque
    rho, beta, sigma = optics.T
    incident = areas * i0
    absorbed = (1.0 - rho - sigma) * incident
    closed = craft.facet_kind[craft.side_facet] != TWO_SIDED
    passed = float((sigma * incident)[closed].sum())
    diffuse = rho * (1 - beta) * incident
    total_in, total_absorbed = float(incident.sum()), float(absorbed.sum())
    zero = np.zeros(3)
    if not source.beams and source.exchange is None:
        power = PowerBalance(total_in, total_absorbed, total_in - total_absorbed)
        return BandLoad(
            name=source.name,
            force_N=force,
            torque_Nm=torque,
            direct_force_N=force,
            direct_torque_Nm=torque,
            reflected_force_N=zero,
            reflected_torque_Nm=zero,
            power=power,
            incident_side_W=incident,
            absorbed_side_W=absorbed,
            rays=0,
            shadow_error=sums.shadow_error,
            reflections=ReflectedPower(1.0 - rho - sigma, np.zeros(craft.n_sides), 0.0),
        )
    chains = _sum_chains(sums.chains, craft.n_sides)
    r_force, r_torque = chains.force_N.copy(), chains.torque_Nm.copy()
    # first beams as the integrals give them; the cells' beams stand for them, and the difference
    # (the cells' quadrature error, or all of them on a convex model) escapes as the direct law says
    first = float(((rho * beta + np.where(closed, 0.0, sigma)) * incident).sum())
    escaped = passed + chains.escaped_W + first - chains.first_W
    total_absorbed += chains.absorbed_W
    if source.exchange is None:
        r_force += chains.open_sky_force_N
        r_torque += chains.open_sky_torque_Nm
        escaped += float(diffuse.sum() + chains.diffuse_source_W.sum())
    else:
        exchange = source.exchange
        net = exchange.responses.copy()
        net[:, MOMENTA] -= exchange.open_sky_functionals[:, MOMENTA]
        from_direct = DiffuseTotals.from_sums(net.T @ diffuse, reference_m)
        from_beams = exchange.totals(chains.diffuse_source_W, reference_m)
        r_force += from_direct.force_N + from_beams.force_N
        r_torque += from_direct.torque_Nm + from_beams.torque_Nm
        escaped += from_direct.escaped_W + from_beams.escaped_W
        total_absorbed += from_direct.absorbed_W + from_beams.absorbed_W
    absorptance = 1.0 - rho - sigma
    lost = chains.truncated_W + chains.absorbed_W - float((absorptance * chains.arrived_W).sum())
    sent = None if source.exchange is None else diffuse + chains.diffuse_source_W
    reflections = ReflectedPower(absorptance, chains.arrived_W, lost, source.exchange, sent)
    power = PowerBalance(total_in, total_absorbed, float(escaped), chains.truncated_W)
    return BandLoad(
        name=source.name,
        force_N=force + r_force,
        torque_Nm=torque + r_torque,
        direct_force_N=force,
        direct_torque_Nm=torque,
        reflected_force_N=r_force,
        reflected_torque_Nm=r_torque,
        power=power,
        incident_side_W=incident,
        absorbed_side_W=absorbed,
        rays=chains.rays,
        shadow_error=sums.shadow_error,
        reflections=reflections,
        traced=tuple(c for c in sums.chains if c.derivatives is not None),
    )


def _sum_chains(chains: list[BeamChainTotals], n_sides: int) -> BeamChainTotals:
    """The chains of all cells as one."""
    zero3, zero = np.zeros(3), np.zeros(n_sides)
    return BeamChainTotals(
        force_N=sum((c.force_N for c in chains), zero3),
        torque_Nm=sum((c.torque_Nm for c in chains), zero3),
        diffuse_source_W=sum((c.diffuse_source_W for c in chains), zero),
        arrived_W=sum((c.arrived_W for c in chains), zero),
        open_sky_force_N=sum((c.open_sky_force_N for c in chains), zero3),
        open_sky_torque_Nm=sum((c.open_sky_torque_Nm for c in chains), zero3),
        escaped_W=sum(c.escaped_W for c in chains),
        absorbed_W=sum(c.absorbed_W for c in chains),
        truncated_W=sum(c.truncated_W for c in chains),
        first_W=sum(c.first_W for c in chains),
        rays=sum(c.rays for c in chains),
        depth=max((c.depth for c in chains), default=0),
    )
