"""Derivatives of the beam chains with respect to every material's optics (METHOD.md "Inter-reflection").

:func:`~sunwind.forces.reflection.beams.follow_chains` with ``derivatives=True`` carries, beside each
beam's power, its derivatives with respect to ``(rho, beta, sigma)`` of every material (forward mode):
``3 n_materials`` columns, column ``3 m + k`` for coefficient ``k`` of material ``m``. A first beam's
power is ``Phi A f c rho beta`` (mirror) or ``Phi A f c sigma`` (transmitted) of its emitter's material;
where a beam of power ``p`` meets a side of material ``m`` it splits into the shares absorbed
``1 - rho - sigma``, diffuse ``rho (1 - beta)``, mirrored ``rho beta`` and transmitted ``sigma``, so
each part's derivatives are the share times the beam's, plus ``p`` times the share's partials in the
columns of ``m``. :func:`land` does this in the same pass as the beams' own sums, and follows only the
columns of the materials a chain has met.

A share that is zero casts no beam, yet a small increase of it would start one: so where a first beam
or a continuation has zero power only because its share is zero while the share's derivative is not
(``beta = 0 < rho`` or ``rho = 0 < beta`` for the mirror share ``rho beta``, whose partials are
``(beta, rho, 0)``; ``sigma = 0`` on a sheet, partials ``(0, 0, 1)``), a **derivative-only beam** is
cast: power 0, derivatives ``p`` times the share's partials (``p`` the power of the light it leaves
with; for a first beam the direct power ``Phi A f c`` on its part of the side). It is followed like any
beam, its landings passing on ``share`` times its derivatives (its power being 0, the partials' term
vanishes; a zero share there is of second order and ends it). It adds exactly 0 to every plain sum
(the result keeps its bits), and its rays are counted in :attr:`ChainDerivatives.rays`, not in the
result's. The ``cutoff`` compares its derivative (its one nonzero column: a derivative-only beam
depends on a single coefficient) with its chain's scale, ``start_W``: the power of the chain's first
beam, or, where that first beam is itself derivative-only, the magnitude of its derivative. The latter
is what the model does with the share at ``h > 0`` for any ``h`` (every power of the chain scales with
``h``); the former treats a continuation as the model would at a unit change of the coefficient
(below ``cutoff`` of the chain's power per unit coefficient, it matters less than ``cutoff`` for any
change of a coefficient in [0, 1]), where the model at a vanishing ``h`` would truncate it at once. A
closed body's transmitted share, which leaves at once without a ray, is counted from ``sigma = 0`` on.

These are then the exact derivatives of the function the chains compute with every discrete decision
held where the powers put it: the adaptive sampling of first beams (derivative-only first beams are
sampled by the same rules, but leave the plain beams' sampling as it is), which beams are cast, the
``cutoff`` and ``depth`` ends, and the first beams known to escape without a ray.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import SPEED_OF_LIGHT
from sunwind.forces.reflection import beam_kernels as kernels
from sunwind.forces.reflection.beam_kernels import ABSORBED_W, ESCAPED_W, MOMENTUM, OPEN_SKY, TRUNCATED_W
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import BLIND, ESCAPED, Spacecraft

#: Coefficients of a material the derivatives are taken with respect to, in column order.
OPTICS = ("rho", "beta", "sigma")
#: Most materials whose columns :func:`land` follows by a bit mask (an int64's bits); with more, every
#: column of every beam.
MASKED_MATERIALS = 62


@dataclass(frozen=True, eq=False)
class ChainDerivatives:
    """Derivatives of :class:`~sunwind.forces.reflection.beams.BeamChainTotals` with respect to every
    material's optics ``(rho, beta, sigma)``: reflectivity, specular fraction and transmissivity.

    Index ``[m, k]`` (or column ``3 m + k``) is coefficient ``k`` of :data:`OPTICS` of material ``m``
    (``craft.materials`` order). Body frame, SI, per unit coefficient.

    Attributes
    ----------
    force_N, torque_Nm : (n_materials, 3, 3) float64
        d ``force_N`` and d ``torque_Nm`` (the chains' correction to the direct result); last index
        the component.
    open_sky_force_N, open_sky_torque_Nm : (n_materials, 3, 3) float64
        The same of ``open_sky_force_N`` and ``open_sky_torque_Nm``.
    escaped_W, absorbed_W, truncated_W, first_W : (n_materials, 3) float64
        d ``escaped_W``, ``absorbed_W``, ``truncated_W`` and ``first_W``.
    sides : (k,) int64
        The sides beams arrive at, in increasing order: all others have zero derivatives below.
    arrived_rows : (k, 3 n_materials) float64
        d ``arrived_W`` of ``sides``, the beam power arriving at each.
    source_rows : (k, 3 n_materials) float64
        d ``diffuse_source_W`` of ``sides``: ``d(rho_d) arrived_W + rho_d d(arrived_W)``.
    n_sides : int
        Sides of the model.
    rays : int
        Rays cast for derivative-only beams (module docstring), beside the result's own.
    arrived_W, diffuse_source_W : (n_sides, 3 n_materials) float64
        The same of every side (properties, made when asked for).

    Examples
    --------
    A mirror (``rho = 1``, ``beta = 0.8``) V-groove lit along its bisector: each first beam crosses to
    the other wall and leaves. The light sent back out is ``rho beta`` of the first beams, so ``first_W``
    and ``escaped_W`` grow with ``beta`` by ``rho`` and ``rho^2 2 beta`` of the incident power. The walls
    transmit nothing, but would pass the sunlight (2000 W) and the mirrored beams (1600 W) through and
    out as ``sigma`` grew: derivative-only beams, two rays per lit side:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection.beams import follow_chains
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> corners = np.array([[-1, 0, 1], [0, 0, 0], [0, 1, 0], [-1, 1, 1], [1, 0, 1], [1, 1, 1.0]])
    >>> faces = np.array([[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]])
    >>> walls = MeshData(corners, faces, np.zeros(4, np.int32), ("groove",), np.full(4, -1, np.int32))
    >>> shiny = sw.Material("shiny", reflectivity=1.0, specular_fraction=0.8)
    >>> craft = sw.load(walls, uniform=shiny, two_sided=["*"], threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.0, 1.0]), 1)
    >>> chains = follow_chains(craft, light, 1000.0, np.zeros(3), level=1, derivatives=True)
    >>> chains.first_W, chains.escaped_W
    (1600.0, 1280.0)
    >>> d = chains.derivatives
    >>> d.first_W[0], d.escaped_W[0], d.rays
    (array([1600., 2000., 2000.]), array([2560., 3200., 3600.]), 8)
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    open_sky_force_N: NDArray[np.float64]
    open_sky_torque_Nm: NDArray[np.float64]
    escaped_W: NDArray[np.float64]
    absorbed_W: NDArray[np.float64]
    truncated_W: NDArray[np.float64]
    first_W: NDArray[np.float64]
    sides: NDArray[np.int64]
    arrived_rows: NDArray[np.float64]
    source_rows: NDArray[np.float64]
    n_sides: int
    rays: int = 0

    @cached_property
    def arrived_W(self) -> NDArray[np.float64]:
        """d ``arrived_W``, (n_sides, 3 n_materials): :attr:`arrived_rows` in the rows of :attr:`sides`."""
        return self._dense(self.arrived_rows)

    @cached_property
    def diffuse_source_W(self) -> NDArray[np.float64]:
        """d ``diffuse_source_W``, (n_sides, 3 n_materials): :attr:`source_rows` in the rows of
        :attr:`sides`."""
        return self._dense(self.source_rows)

    def _dense(self, rows: NDArray[np.float64]) -> NDArray[np.float64]:
        dense = np.zeros((self.n_sides, rows.shape[1]))
        dense[self.sides] = rows
        return dense


class Arrivals(NamedTuple):
    """Derivatives of the beam power arriving at the sides beams meet.

    Attributes
    ----------
    sides : (k,) int64
        The sides, in increasing order.
    rows : (k, 3 n_materials) float64
        The derivatives of the power arriving at each.

    Examples
    --------
    Side 4 met by beams of material 0, whose power grows by 2 W per unit ``rho``:

    >>> Arrivals(np.array([4]), np.array([[2.0, 0.0, 0.0]])).sides
    array([4])
    """

    sides: NDArray[np.int64]
    rows: NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class DerivativeSums:
    """What the derivatives of the chains of an attitude add to (:func:`land`).

    Attributes
    ----------
    totals : (N_TOTALS, 3 n_materials) float64
        Derivatives of the running sums of :mod:`~sunwind.forces.reflection.beam_kernels`.
    slot : (n_sides + 1,) int64
        Row of :attr:`rows` of each side, -1 for none; then the rows used.
    rows : (n_sides, 3 n_materials) float64
        Derivatives of the beam power arriving at the sides given a row.
    every : bool
        Whether there are too many materials for a bit mask (:data:`MASKED_MATERIALS`): every column
        of every beam is followed.

    Examples
    --------
    >>> sums = DerivativeSums.empty(3, 1)
    >>> sums.slot[:] = [1, -1, 0, 2]
    >>> sums.rows[:2] = [[2.0], [1.0]]
    >>> sums.arrivals()
    Arrivals(sides=array([0, 2]), rows=array([[1.],
           [2.]]))
    """

    totals: NDArray[np.float64]
    slot: NDArray[np.int64]
    rows: NDArray[np.float64]
    every: bool

    @staticmethod
    def empty(n_sides: int, n_columns: int) -> DerivativeSums:
        """Nothing yet, for ``n_sides`` sides and ``n_columns`` columns.

        Parameters
        ----------
        n_sides : int
            Sides of the model.
        n_columns : int
            ``3 n_materials``.

        Returns
        -------
        DerivativeSums
            Zero sums, no side given a row.
        """
        slot = np.full(n_sides + 1, -1)
        slot[-1] = 0
        totals, rows = np.zeros((kernels.N_TOTALS, n_columns)), np.empty((n_sides, n_columns))
        return DerivativeSums(totals, slot, rows, every=n_columns // len(OPTICS) > MASKED_MATERIALS)

    def arrivals(self) -> Arrivals:
        """The derivatives of the power arriving at the sides met.

        Returns
        -------
        Arrivals
            Those of the sides given a row.
        """
        sides = np.flatnonzero(self.slot[:-1] >= 0)
        return Arrivals(sides=sides, rows=self.rows[self.slot[sides]])


def columns(craft: Spacecraft, derivatives: bool) -> int:
    """Columns of the derivatives of ``craft``'s beams: ``3 n_materials``, or none without ``derivatives``.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    derivatives : bool
        Whether derivatives are taken.

    Returns
    -------
    int
        The number of columns.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5), threads=1).craft
    >>> columns(craft, True), columns(craft, False)
    (3, 0)
    """
    return len(OPTICS) * len(craft.materials) if derivatives else 0


class FirstBeams(NamedTuple):
    """Derivatives of the power of the first beams of an attitude (:func:`first_beams`).

    Attributes
    ----------
    column : (n,) int64
        First column ``3 m`` of the material of the side sending each beam cast.
    partials : (n, 3) float64
        Derivatives of each beam's power with respect to that material's ``(rho, beta, sigma)`` [W].
    cast : (3 n_materials,) float64
        Derivatives of the power of all beams cast [W].
    culled : (3 n_materials,) float64
        Derivatives of the power of the first beams not cast, known to escape [W].

    Examples
    --------
    One mirror beam cast from a side of material 1 (columns 3 to 5) with ``Phi A f c = 500`` W,
    ``rho = 0.5``, ``beta = 0.2``:

    >>> first = FirstBeams(np.array([3]), np.array([[100.0, 250.0, 0.0]]),
    ...     np.array([0, 0, 0, 100.0, 250.0, 0]), np.zeros(6))
    >>> first.cast + first.culled
    array([  0.,   0.,   0., 100., 250.,   0.])
    """

    column: NDArray[np.int64]
    partials: NDArray[np.float64]
    cast: NDArray[np.float64]
    culled: NDArray[np.float64]


def first_beams(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    sides: NDArray[np.int64],
    through: NDArray[np.bool_],
    sheet: NDArray[np.bool_],
) -> FirstBeams:
    """Derivatives of the power of first beams, ``Phi A f c`` times ``(beta, rho, 0)`` for a mirror beam
    and ``(0, 0, 1)`` for a transmitted one in the columns of the sending side's material: of those
    cast, and summed over those not cast (every lit side's mirror beam and sheet's transmitted beam but
    those cast, derivative-only ones at a zero share included: those of sides with partials not cast
    are known to escape).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    light : Illumination
        Lit shares of the attitude.
    flux_W_m2 : float
        Solar flux [W/m^2].
    sides : (n,) int64
        Side sending each beam cast.
    through : (n,) bool
        Whether it is the beam the side transmits (else its mirror beam).
    sheet : (n_sides,) bool
        Whether each side belongs to a sheet.

    Returns
    -------
    FirstBeams
        The derivatives.

    Examples
    --------
    A convex box lit on its top face: its two triangles' mirror beams escape; cast one, and the other is
    not cast:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("paint", 0.5, 0.2), threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([0.0, 0.0, 1.0]), 1)
    >>> first = first_beams(craft, light, 1000.0, light.facing[:1], np.array([False]),
    ...     np.zeros(craft.n_sides, bool))
    >>> first.partials, first.cast, first.culled
    (array([[100., 250.,   0.]]), array([100., 250.,   0.]), array([100., 250.,   0.]))
    """
    column, partials, cast, culled = _first_beams(
        light.facing,
        light.lit_fraction,
        craft.side_areas,
        craft.side_normals,
        craft.side_optics,
        sheet,
        craft.side_material,
        light.direction,
        flux_W_m2,
        sides,
        through,
        columns(craft, True),
    )
    return FirstBeams(column=column, partials=partials, cast=cast, culled=culled)


@numba.njit(cache=True, nogil=True)
def _first_beams(
    facing: NDArray[np.int64],
    lit_fraction: NDArray[np.float64],
    side_areas: NDArray[np.float64],
    side_normals: NDArray[np.float64],
    side_optics: NDArray[np.float64],
    side_sheet: NDArray[np.bool_],
    side_material: NDArray[np.int32],
    toward_source: NDArray[np.float64],
    flux_W_m2: float,
    sides: NDArray[np.int64],
    through: NDArray[np.bool_],
    n_columns: int,
) -> tuple[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """:func:`first_beams` in one pass over the lit sides: the fields of :class:`FirstBeams`."""
    n_sides = side_areas.shape[0]
    incident = np.zeros(n_sides)
    sent = np.zeros((2, n_sides), dtype=np.bool_)
    for e in range(sides.shape[0]):
        sent[1 if through[e] else 0, sides[e]] = True
    culled = np.zeros(n_columns)
    for k in range(facing.shape[0]):
        s = facing[k]
        if lit_fraction[s] <= 0.0:
            continue
        _, power = kernels._incident(s, lit_fraction, side_areas, side_normals, toward_source, flux_W_m2)
        incident[s] = power
        c, rho, beta = 3 * side_material[s], side_optics[s, 0], side_optics[s, 1]
        if not sent[0, s]:  # zero where rho = beta = 0
            culled[c] += incident[s] * beta
            culled[c + 1] += incident[s] * rho
        if side_sheet[s] and not sent[1, s]:
            culled[c + 2] += incident[s]
    column = np.empty(sides.shape[0], dtype=np.int64)
    partials = np.zeros((sides.shape[0], 3))
    cast = np.zeros(n_columns)
    for e in range(sides.shape[0]):
        s = sides[e]
        column[e] = 3 * side_material[s]
        if through[e]:
            partials[e, 2] = incident[s]
        else:
            partials[e, 0] = incident[s] * side_optics[s, 1]
            partials[e, 1] = incident[s] * side_optics[s, 0]
        for a in range(3):
            cast[column[e] + a] += partials[e, a]
    return column, partials, cast, culled


def chain_derivatives(
    craft: Spacecraft,
    dtotals: NDArray[np.float64],
    arrivals: Arrivals,
    arrived_W: NDArray[np.float64],
    first: FirstBeams,
    rays: int = 0,
) -> ChainDerivatives:
    """The derivatives of the chains of an attitude, from the kernels' sums.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    dtotals : (N_TOTALS, 3 n_materials) float64
        Derivatives of the running sums of :func:`~sunwind.forces.reflection.beam_kernels.land`.
    arrivals : Arrivals
        Derivatives of the beam power arriving at the sides beams meet.
    arrived_W : (n_sides,) float64
        Beam power arriving at each side [W].
    first : FirstBeams
        Derivatives of the power of the first beams (:func:`first_beams`).
    rays : int
        Rays cast for derivative-only beams.

    Returns
    -------
    ChainDerivatives
        The derivatives.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("paint", 0.5, 0.2), threads=1).craft
    >>> first = FirstBeams(np.zeros(0, np.int64), np.zeros((0, 3)), np.zeros(3), np.array([1.0, 2.0, 0.0]))
    >>> arrivals = Arrivals(np.zeros(0, np.int64), np.zeros((0, 3)))
    >>> d = chain_derivatives(craft, np.zeros((kernels.N_TOTALS, 3)), arrivals, np.zeros(craft.n_sides),
    ...     first)
    >>> d.escaped_W, d.force_N.shape
    (array([[1., 2., 0.]]), (1, 3, 3))
    """
    n = len(craft.materials)

    def vectors(slot: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        force = dtotals[slot : slot + 3].T.reshape(n, len(OPTICS), 3) / SPEED_OF_LIGHT
        torque = dtotals[slot + 3 : slot + 6].T.reshape(n, len(OPTICS), 3) / SPEED_OF_LIGHT
        return force, torque

    def scalar(row: NDArray[np.float64]) -> NDArray[np.float64]:
        return row.reshape(n, len(OPTICS))

    hit = arrivals.sides
    rho, beta, _ = craft.side_optics[hit].T
    source = (rho * (1.0 - beta))[:, None] * arrivals.rows
    column, arrived, index = len(OPTICS) * craft.side_material[hit], arrived_W[hit], np.arange(len(hit))
    source[index, column] += (1.0 - beta) * arrived
    source[index, column + 1] -= rho * arrived
    force, torque = vectors(kernels.MOMENTUM)
    open_force, open_torque = vectors(kernels.OPEN_SKY)
    return ChainDerivatives(
        force_N=force,
        torque_Nm=torque,
        open_sky_force_N=open_force,
        open_sky_torque_Nm=open_torque,
        escaped_W=scalar(dtotals[kernels.ESCAPED_W] + first.culled),
        absorbed_W=scalar(dtotals[kernels.ABSORBED_W].copy()),
        truncated_W=scalar(dtotals[kernels.TRUNCATED_W].copy()),
        first_W=scalar(first.cast + first.culled),
        sides=hit,
        arrived_rows=arrivals.rows,
        source_rows=source,
        n_sides=craft.n_sides,
        rays=rays,
    )


@numba.njit(cache=True, nogil=True)
def _materials(mask: int, n_materials: int, active: NDArray[np.int64]) -> int:
    """Put the materials of the bit mask ``mask`` (-1: all) in ``active``; return how many there are."""
    count = 0
    for m in range(n_materials):
        if mask == -1 or (mask >> m) & 1:
            active[count] = m
            count += 1
    return count


@numba.njit(cache=True, nogil=True)
def _row(
    row: NDArray[np.float64],
    dpower: NDArray[np.float64],
    dcolumn: NDArray[np.int64],
    own: int,
    i: int,
    active: NDArray[np.int64],
    n_active: int,
) -> None:
    """``row[0]`` in the columns of the materials ``active[:n_active]``: the derivatives of beam ``i``'s
    power, ``dpower[i]`` where material bit mask ``own`` (-1: all) says they may be nonzero, or its
    compact row put in the three columns from ``dcolumn[i]`` on; zero elsewhere."""
    compact = dcolumn.shape[0] > 0
    for j in range(n_active):
        m = active[j]
        for a in range(3):
            c = 3 * m + a
            if compact:
                row[0, c] = dpower[i, a] if dcolumn[i] == 3 * m else 0.0
            else:
                row[0, c] = dpower[i, c] if own == -1 or (own >> m) & 1 else 0.0


@numba.njit(cache=True, nogil=True)
def _dpush(
    dtotals: NDArray[np.float64],
    slot: int,
    at: NDArray,
    i: int,
    reference: NDArray,
    vector: tuple[float, float, float],
    rows: NDArray[np.float64],
    k: int,
    active: NDArray[np.int64],
    n_active: int,
) -> None:
    """:func:`_push` of ``rows[k, c] * vector`` into column ``c`` of ``dtotals``, for the columns of the
    materials ``active[:n_active]``: the derivatives of a push of ``p * vector``, ``rows[k]`` those of
    ``p``."""
    x, y, z = vector
    r0, r1, r2 = at[i, 0] - reference[0], at[i, 1] - reference[1], at[i, 2] - reference[2]
    m0, m1, m2 = r1 * z - r2 * y, r2 * x - r0 * z, r0 * y - r1 * x
    for j in range(n_active):
        for c in range(3 * active[j], 3 * active[j] + 3):
            w = rows[k, c]
            dtotals[slot, c] += w * x
            dtotals[slot + 1, c] += w * y
            dtotals[slot + 2, c] += w * z
            dtotals[slot + 3, c] += w * m0
            dtotals[slot + 4, c] += w * m1
            dtotals[slot + 5, c] += w * m2


@numba.njit(cache=True, nogil=True)
def _dshare(
    out: NDArray[np.float64],
    k: int,
    share: float,
    row: NDArray[np.float64],
    p: float,
    column: int,
    partials: tuple[float, float, float],
    active: NDArray[np.int64],
    n_active: int,
) -> None:
    """``out[k]`` in the columns of ``active[:n_active]``: derivatives of ``share * p``, ``share`` a share
    of the material whose ``(rho, beta, sigma)`` columns start at ``column`` (one of them; ``partials``
    its derivatives) and ``row[0]`` those of ``p``."""
    for j in range(n_active):
        for c in range(3 * active[j], 3 * active[j] + 3):
            out[k, c] = share * row[0, c]
    for a in range(3):
        out[k, column + a] += p * partials[a]


@numba.njit(cache=True, nogil=True)
def _dadd(
    dtotals: NDArray[np.float64],
    slot: int,
    rows: NDArray[np.float64],
    k: int,
    active: NDArray[np.int64],
    n_active: int,
) -> None:
    """Add ``rows[k]`` to ``dtotals[slot]`` in the columns of the materials ``active[:n_active]``."""
    for j in range(n_active):
        for c in range(3 * active[j], 3 * active[j] + 3):
            dtotals[slot, c] += rows[k, c]


@numba.njit(cache=True, nogil=True)
def _arrival_row(dslot: NDArray[np.int64], drows: NDArray[np.float64], s: int) -> int:
    """Row of ``drows`` of side ``s``, given (and zeroed) if it has none yet: ``dslot[s]``, with
    ``dslot[-1]`` the rows given."""
    if dslot[s] < 0:
        dslot[s] = dslot[-1]
        dslot[-1] += 1
        drows[dslot[s], :] = 0.0
    return dslot[s]


@numba.njit(cache=True, nogil=True)
def _partials(through: bool, rho: float, beta: float) -> tuple[float, float, float]:
    """Derivatives of the share :func:`_share` gives with respect to ``(rho, beta, sigma)``."""
    return (0.0, 0.0, 1.0) if through else (beta, rho, 0.0)


@numba.njit(cache=True, nogil=True)
def _size(rows: NDArray[np.float64], k: int, active: NDArray[np.int64], n_active: int) -> float:
    """Largest ``|rows[k]|`` in the columns of the materials ``active[:n_active]``."""
    size = 0.0
    for j in range(n_active):
        for c in range(3 * active[j], 3 * active[j] + 3):
            size = max(size, abs(rows[k, c]))
    return size


@numba.njit(cache=True, nogil=True)
def _put(
    new_origin: NDArray[np.float64],
    new_lift: NDArray[np.float64],
    new_direction: NDArray[np.float64],
    count: int,
    points_m: NDArray[np.float64],
    i: int,
    normal: tuple[float, float, float],
    direction: tuple[float, float, float],
    through: bool,
) -> None:
    """Row ``count`` of the new beams: leaving ``points_m[i]`` off a side of outward ``normal``, a beam
    of ``direction`` mirrored or (``through``) passed on, as
    :func:`~sunwind.forces.reflection.beam_kernels.land` makes it."""
    n0, n1, n2 = normal
    d0, d1, d2 = direction
    for a in range(3):
        new_origin[count, a] = points_m[i, a]
    sign = -1.0 if through else 1.0
    new_lift[count, 0], new_lift[count, 1], new_lift[count, 2] = sign * n0, sign * n1, sign * n2
    bend = 0.0 if through else 2.0 * (d0 * n0 + d1 * n1 + d2 * n2)
    new_direction[count, 0] = d0 - bend * n0
    new_direction[count, 1] = d1 - bend * n1
    new_direction[count, 2] = d2 - bend * n2


@numba.njit(cache=True, nogil=True)
def land(
    origin_m: NDArray[np.float64],
    direction: NDArray[np.float64],
    power_W: NDArray[np.float64],
    start_W: NDArray[np.float64],
    sides: NDArray[np.int64],
    points_m: NDArray[np.float64],
    first: bool,
    last: bool,
    cutoff: float,
    side_normals: NDArray[np.float64],
    side_optics: NDArray[np.float64],
    side_sheet: NDArray[np.bool_],
    lambert_factor: float,
    reference_m: NDArray[np.float64],
    totals: NDArray[np.float64],
    arrived_W: NDArray[np.float64],
    side_material: NDArray[np.int32],
    dpower: NDArray[np.float64],
    dmask: NDArray[np.int64],
    dcolumn: NDArray[np.int64],
    every: bool,
    dtotals: NDArray[np.float64],
    dslot: NDArray[np.int64],
    drows: NDArray[np.float64],
) -> tuple[
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.int64],
]:
    """:func:`~sunwind.forces.reflection.beam_kernels.land` (one generation of beams counted, the next
    returned: the same arithmetic, the same bits), with derivatives.

    Derivatives go along in the same pass, with every decision (which beams go on, which are
    truncated) as the powers make it: column ``c`` of ``dpower`` is the derivative of each beam's power
    with respect to coefficient ``c % 3`` of ``(rho, beta, sigma)`` of material ``c // 3``; a split
    on a side of material ``m`` adds the derivatives of its shares there (columns ``3 m`` to ``3 m + 2``).
    A beam depends only on the materials its chain met, the bits of ``dmask``: only their columns are
    read, written and summed (with ``every``, all columns). ``dtotals`` takes the derivatives of
    ``totals``, and ``drows`` those of ``arrived_W``, one row a side as sides are first met:
    ``dslot[s]`` is side ``s``'s row (-1: none yet), ``dslot[-1]`` the rows used. A closed body's
    transmitted share, which leaves at once, is differentiated at ``sigma = 0`` too.

    A zero share whose partials are not zero sends a derivative-only beam (power 0, derivatives ``p``
    times the partials), and a beam of power 0 is one: its nonzero shares pass its derivatives on as
    derivative-only beams, its zero shares end it. Such a beam goes on where its derivative's largest
    column is at least ``cutoff * start_W`` (the module docstring says which scale that is), and adds
    exactly 0 to every plain sum.

    The plain arithmetic is :func:`~sunwind.forces.reflection.beam_kernels.land`'s, line for line, so
    that taking derivatives changes no bit of the result (tested): change both together.

    Returns the new beams' origin (n, 3), lift (n, 3), direction (n, 3), power, starting power, the
    derivatives of their power and the materials they depend on.

    Parameters
    ----------
    origin_m : (n, 3) float64
        Where each beam leaves from [m].
    direction : (n, 3) float64
        Unit direction of each beam.
    power_W : (n,) float64
        Power of each beam [W].
    start_W : (n,) float64
        Power its chain started with [W].
    sides : (n,) int64
        Side each beam meets, or ``ESCAPED``/``BLIND``.
    points_m : (n, 3) float64
        Where it meets it [m].
    first : bool
        Whether these are first beams (the direct law let them leave).
    last : bool
        Whether this is the last generation (every new beam truncated).
    cutoff : float
        New beams below this share of their chain's starting power are truncated.
    side_normals : (n_sides, 3) float64
        Outward unit normal of each side.
    side_optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of each side.
    side_sheet : (n_sides,) bool
        Whether each side belongs to a sheet.
    lambert_factor : float
        ``2/3``: the momentum of diffuse light leaving an open plate per unit power.
    reference_m : (3,) float64
        Torque reference point [m].
    totals : (N_TOTALS,) float64
        Running sums (the slots of :mod:`~sunwind.forces.reflection.beam_kernels`); added to.
    arrived_W : (n_sides,) float64
        Beam power arriving at each side [W]; added to.
    side_material : (n_sides,) int32
        Material of each side.
    dpower : (n, q) or (n, 3) float64
        Derivatives of each beam's power in the ``q`` columns of ``dtotals`` (valid in those of the
        materials of ``dmask``); or, given ``dcolumn``, in the three columns from ``dcolumn`` on (a first
        beam depends on one material).
    dmask : (n,) int64
        Bit mask of the materials each beam depends on (-1: all); not read given ``dcolumn``.
    dcolumn : (n,) or (0,) int64
        Where each row of a compact ``dpower`` goes; empty for a full ``dpower``.
    every : bool
        Follow every column of every beam, not those of ``dmask`` (too many materials for a mask).
    dtotals : (N_TOTALS, q) float64
        Derivatives of the running sums, ``q = 3 n_materials`` columns; added to.
    dslot : (n_sides + 1,) int64
        Row of ``drows`` of each side, -1 for none yet, then the rows used; added to.
    drows : (n_sides, q) float64
        Derivatives of ``arrived_W`` of the sides given a row; added to (a new row is zeroed first).

    Returns
    -------
    origin : (k, 3) ndarray of float64
        Where each new beam starts [m].
    lift : (k, 3) ndarray of float64
        Unit vector off the surface on its side.
    direction : (k, 3) ndarray of float64
        Its unit direction.
    power : (k,) ndarray of float64
        Its power [W].
    start : (k,) ndarray of float64
        Its chain's starting power [W].
    dpower : (k, q) ndarray of float64
        The derivatives of its power (valid in the columns of the materials of ``dmask``).
    dmask : (k,) ndarray of int64
        Bit mask of the materials it depends on.

    Examples
    --------
    A 10 W first beam going up meets a mirror (``rho = beta = 1``) facing down at ``z = 1`` and goes on
    down. The mirror beam's power is ``rho beta p``, so it changes by ``beta p = 10`` W per unit ``rho``
    and ``rho p = 10`` W per unit ``beta``; the absorbed power ``(1 - rho - sigma) p`` by ``-p`` per
    unit ``rho`` and per unit ``sigma``:

    >>> from sunwind.forces.reflection.beam_kernels import N_TOTALS
    >>> dtotals = np.zeros((N_TOTALS, 3))
    >>> *_, dpower, dmask = land(np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]]), np.array([10.0]),
    ...     np.array([10.0]), np.array([0]), np.array([[0.0, 0.0, 1.0]]), True, False, 1e-6,
    ...     np.array([[0.0, 0.0, -1.0]]), np.array([[1.0, 1.0, 0.0]]), np.zeros(1, bool), 2 / 3, np.zeros(3),
    ...     np.zeros(N_TOTALS), np.zeros(1), np.zeros(1, np.int32), np.zeros((1, 3)), np.zeros(1, np.int64),
    ...     np.zeros(0, np.int64), False, dtotals, np.array([-1, 0]), np.empty((1, 3)))
    >>> dpower, dmask, dtotals[ABSORBED_W]
    (array([[10., 10.,  0.]]), array([1]), array([-10.,   0., -10.]))
    """
    n = power_W.shape[0]
    q = dtotals.shape[1]
    n_materials = q // 3
    compact = dcolumn.shape[0] > 0
    most = 2 * np.sum(sides >= 0)  # a side sends at most a mirror and a transmitted beam
    new_origin = np.empty((most, 3))
    new_lift = np.empty((most, 3))
    new_direction = np.empty((most, 3))
    new_power = np.empty(most)
    new_start = np.empty(most)
    new_dpower = np.empty((most, q))
    new_dmask = np.zeros(most, dtype=np.int64)
    row = np.empty((1, q))  # derivatives of the power of the beam landing
    work = np.empty((1, q))  # derivatives of one share of it
    active = np.empty(n_materials, dtype=np.int64)  # the materials they may depend on
    n_active = mask = column = 0
    count = 0
    escaped = absorbed = truncated = 0.0
    for i in range(n):
        s, p = sides[i], power_W[i]
        d0, d1, d2 = direction[i, 0], direction[i, 1], direction[i, 2]
        if q:
            own = -1 if every else (1 << (dcolumn[i] // 3) if compact else dmask[i])
            mask = own if s < 0 or every else own | (1 << side_material[s])
            n_active = _materials(mask, n_materials, active)
            _row(row, dpower, dcolumn, own, i, active, n_active)
            column = 3 * side_material[s] if s >= 0 else 0
        if s == ESCAPED:
            if not first:
                kernels._push(totals, MOMENTUM, origin_m, i, reference_m, -p * d0, -p * d1, -p * d2)
                if q:
                    _dpush(
                        dtotals, MOMENTUM, origin_m, i, reference_m, (-d0, -d1, -d2), row, 0, active, n_active
                    )
            escaped += p
            if q:
                _dadd(dtotals, ESCAPED_W, row, 0, active, n_active)
            continue
        if first:
            kernels._push(totals, MOMENTUM, origin_m, i, reference_m, p * d0, p * d1, p * d2)
            if q:
                _dpush(dtotals, MOMENTUM, origin_m, i, reference_m, (d0, d1, d2), row, 0, active, n_active)
        if s == BLIND:
            absorbed += p
            if q:
                _dadd(dtotals, ABSORBED_W, row, 0, active, n_active)
            continue
        rho, beta, sigma = side_optics[s, 0], side_optics[s, 1], side_optics[s, 2]
        n0, n1, n2 = side_normals[s, 0], side_normals[s, 1], side_normals[s, 2]
        absorbed += (1.0 - rho - sigma) * p
        diffuse = rho * (1.0 - beta) * p
        arrived_W[s] += p
        w = -lambert_factor * diffuse
        kernels._push(totals, OPEN_SKY, points_m, i, reference_m, w * n0, w * n1, w * n2)
        if q:
            _dshare(work, 0, 1.0 - rho - sigma, row, p, column, (-1.0, 0.0, -1.0), active, n_active)
            _dadd(dtotals, ABSORBED_W, work, 0, active, n_active)
            _dadd(drows, _arrival_row(dslot, drows, s), row, 0, active, n_active)
            _dshare(work, 0, rho * (1.0 - beta), row, p, column, (1.0 - beta, -rho, 0.0), active, n_active)
            lambert = (-lambert_factor * n0, -lambert_factor * n1, -lambert_factor * n2)
            _dpush(dtotals, OPEN_SKY, points_m, i, reference_m, lambert, work, 0, active, n_active)
        if not side_sheet[s] and sigma > 0.0:
            w = -sigma * p
            kernels._push(totals, MOMENTUM, points_m, i, reference_m, w * d0, w * d1, w * d2)
            escaped += sigma * p
        if q and not side_sheet[s]:  # needs no ray: counted at sigma = 0 too, as sigma grows from it
            _dshare(work, 0, sigma, row, p, column, (0.0, 0.0, 1.0), active, n_active)
            _dpush(dtotals, MOMENTUM, points_m, i, reference_m, (-d0, -d1, -d2), work, 0, active, n_active)
            _dadd(dtotals, ESCAPED_W, work, 0, active, n_active)
        along = d0 * n0 + d1 * n1 + d2 * n2
        for through in (False, True):
            share = kernels._share(side_optics, side_sheet, s, through)
            if q and (p == 0.0 or share <= 0.0):  # derivative-only beams (module docstring)
                if share <= 0.0 and (p == 0.0 or not (side_sheet[s] if through else rho > 0.0 or beta > 0.0)):
                    continue  # no beam of first order (second order, or no partials, or a closed body)
                # share * (derivatives of p) + p * (the share's partials): one of the two terms is 0
                _dshare(work, 0, share, row, p, column, _partials(through, rho, beta), active, n_active)
                if last or _size(work, 0, active, n_active) < cutoff * start_W[i]:
                    _dadd(dtotals, TRUNCATED_W, work, 0, active, n_active)
                    continue
                _put(
                    new_origin,
                    new_lift,
                    new_direction,
                    count,
                    points_m,
                    i,
                    (n0, n1, n2),
                    (d0, d1, d2),
                    through,
                )
                new_power[count] = 0.0
                new_start[count] = start_W[i]
                for j in range(n_active):
                    for c in range(3 * active[j], 3 * active[j] + 3):
                        new_dpower[count, c] = work[0, c]
                new_dmask[count] = mask
                count += 1
                continue
            if share <= 0.0:
                continue
            if last or share * p < cutoff * start_W[i]:
                truncated += share * p
                if q:
                    _dshare(work, 0, share, row, p, column, _partials(through, rho, beta), active, n_active)
                    _dadd(dtotals, TRUNCATED_W, work, 0, active, n_active)
                continue
            new_origin[count, 0], new_origin[count, 1], new_origin[count, 2] = (
                points_m[i, 0],
                points_m[i, 1],
                points_m[i, 2],
            )
            sign = -1.0 if through else 1.0
            new_lift[count, 0], new_lift[count, 1], new_lift[count, 2] = sign * n0, sign * n1, sign * n2
            bend = 0.0 if through else 2.0 * along
            new_direction[count, 0] = d0 - bend * n0
            new_direction[count, 1] = d1 - bend * n1
            new_direction[count, 2] = d2 - bend * n2
            new_power[count] = share * p
            new_start[count] = start_W[i]
            if q:
                _dshare(
                    new_dpower, count, share, row, p, column, _partials(through, rho, beta), active, n_active
                )
                new_dmask[count] = mask
            count += 1
    totals[ESCAPED_W] += escaped
    totals[ABSORBED_W] += absorbed
    totals[TRUNCATED_W] += truncated
    return (
        new_origin[:count],
        new_lift[:count],
        new_direction[:count],
        new_power[:count],
        new_start[:count],
        new_dpower[:count],
        new_dmask[:count],
    )
