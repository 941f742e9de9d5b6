"""Numba kernels of the molecular chains (:mod:`sunwind.forces.gas.chains`).

:func:`starts` draws the molecules that strike each sending side, :func:`bounce` turns arriving
molecules into what a side sends on (the mirrored share, or a CLL draw) and takes their momentum as
escaping, :func:`land` books a leg that meets a side: its momentum stays, its diffuse share goes to the
exchange. Random numbers are counter hashes of ``(seed, side, packet, bounce, slot)``
(:func:`sunwind.geometry.views.hemisphere.uniform`), and every kernel runs its packets in order, so the
results are the same bits whatever the thread count.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.spacecraft import BLIND
from sunwind.geometry.views.hemisphere import side_key, square_to_triangle, uniform

#: Boltzmann constant [J/K] (exact, SI 2019); the same as :data:`sunwind.forces.gas.atmosphere.BOLTZMANN`.
_BOLTZMANN = 1.380649e-23
_SQRT_PI = math.sqrt(math.pi)
#: Mean speed of an effusing Maxwellian stream over ``sqrt(2 k T / m)``.
_MEAN_SPEED = 3.0 * _SQRT_PI / 4.0
#: Random-number slots of one packet and bounce, and bounces of one packet: index = (packet *
#: _BOUNCES + bounce) * _SLOTS + slot.
_SLOTS, _BOUNCES = 64, 1024


@numba.njit(cache=True, nogil=True, inline="always")
def _random(key: np.uint64, packet: int, bounce: int, slot: int) -> float:
    return uniform(key, (packet * _BOUNCES + bounce) * _SLOTS + slot)


@numba.njit(cache=True, nogil=True, inline="always")
def _half_normal(key: np.uint64, packet: int, slot: int) -> float:
    """A normal draw of variance 1/2 (Box-Muller) from slots ``slot``, ``slot + 1`` of bounce 0."""
    radius = math.sqrt(-math.log(1.0 - _random(key, packet, 0, slot)))
    return radius * math.cos(2.0 * math.pi * _random(key, packet, 0, slot + 1))


@numba.njit(cache=True, nogil=True)
def _flux_normal_speed(s: float, key: np.uint64, packet: int, bounce: int) -> float:
    """A draw of ``x > 0`` from ``p(x) ~ x exp(-(x - s)^2)``: the normal speed (over the thermal speed)
    of a molecule of a drifting Maxwellian crossing a plane, drift ``s`` along the crossing. Rejection
    from a proposal that covers ``p`` in each of three ranges of ``s`` (acceptance at least 1/2); at most
    ``_SLOTS / 3 - 1`` tries, the last accepted."""
    slot = 8
    x = 0.0
    for _ in range(18):
        u1, u2 = _random(key, packet, bounce, slot), _random(key, packet, bounce, slot + 1)
        u3 = _random(key, packet, bounce, slot + 2)
        slot += 3
        if s >= 0.0:
            # proposal (|y| + s) exp(-y^2) for y = x - s: |y| exp(-y^2) (weight 1) or s exp(-y^2)
            # (weight s sqrt(pi))
            if u1 * (1.0 + s * _SQRT_PI) < 1.0:
                y = math.sqrt(-math.log(1.0 - u2)) * (1.0 if u3 < 0.5 else -1.0)
                accept = _random(key, packet, bounce, slot)
            else:
                # a normal draw of variance 1/2 from two uniforms (Box-Muller)
                y = math.sqrt(-math.log(1.0 - u2)) * math.cos(2.0 * math.pi * u3)
                accept = _random(key, packet, bounce, slot)
            slot += 1
            x = y + s
            if y > -s and accept * (abs(y) + s) < y + s:
                return x
        elif s > -1.0:
            a = -s
            y = math.sqrt(a * a - math.log(1.0 - u1))
            x = y - a
            if u2 * y < y - a:
                return x
        else:
            a = -s
            x = -(math.log(1.0 - u1) + math.log(1.0 - u2)) / (2.0 * a)  # Gamma(2, 1 / (2 a))
            if u3 < math.exp(-x * x):
                return x
    return max(x, 0.0)


@numba.njit(cache=True, nogil=True)
def _tangents(n: NDArray[np.float64], along: NDArray[np.float64]) -> tuple:
    """Unit tangent ``e1`` along the part of ``along`` in the plane of unit ``n`` (any tangent if none)
    and ``e2 = n x e1``."""
    dot = along[0] * n[0] + along[1] * n[1] + along[2] * n[2]
    t0, t1, t2 = along[0] - dot * n[0], along[1] - dot * n[1], along[2] - dot * n[2]
    size = math.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
    if size <= 1e-12 * max(1.0, math.sqrt(along[0] ** 2 + along[1] ** 2 + along[2] ** 2)):
        helper = (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)
        t0 = helper[1] * n[2] - helper[2] * n[1]
        t1 = helper[2] * n[0] - helper[0] * n[2]
        t2 = helper[0] * n[1] - helper[1] * n[0]
        size = math.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
    e1 = (t0 / size, t1 / size, t2 / size)
    e2 = (n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0])
    return e1, e2


@numba.njit(cache=True, nogil=True)
def starts(
    senders: NDArray[np.int64],
    per_side: int,
    triangles: NDArray[np.float64],
    side_facet: NDArray[np.int64],
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    species_flux: NDArray[np.float64],
    species_pick: NDArray[np.float64],
    thermal_speed: NDArray[np.float64],
    drift: NDArray[np.float64],
    seed: np.uint64,
) -> tuple[NDArray, ...]:
    """``per_side`` molecules striking each of ``senders`` from the free stream (before shadowing).

    Parameters
    ----------
    senders : (n_senders,) int64
        Sides the molecules strike.
    per_side : int
        Molecules drawn per sender.
    triangles : (n_facets, 3, 3) float64
        Corners of each facet [m].
    side_facet : (n_sides,) int64
        Facet of each side.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    areas : (n_sides,) float64
        Area of each side [m^2].
    species_flux : (n_senders, k) float64
        Incident number flux of each species on each sender if unobstructed [1/(s m^2)].
    species_pick : (n_senders, k) float64
        Probability of drawing each species (rows sum to 1).
    thermal_speed : (k,) float64
        ``sqrt(2 k T / m_k)`` [m/s].
    drift : (3,) float64
        The gas velocity relative to the body, ``-V u`` [m/s].
    seed : uint64
        Seed of the random numbers.

    Returns
    -------
    side, species : (n,) int64
    point : (n, 3) float64
        Where on the side it strikes [m] (stratified over the side).
    velocity : (n, 3) float64
        Its velocity [m/s], into the side.
    weight : (n,) float64
        Molecules per second it stands for: ``A N_k / (p_k per_side)``.

    Examples
    --------
    Two molecules onto side 0 of a unit cube (normal -x) from a stream drifting along +x:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> craft.side_normals[0], float(craft.side_areas[0])
    (array([-1.,  0., -0.]), 0.5)
    >>> side, species, point, velocity, weight = starts(np.array([0]), 2, craft.triangles, craft.side_facet,
    ...     craft.side_normals, craft.side_areas, np.array([[1e17]]), np.array([[1.0]]), np.array([1000.0]),
    ...     np.array([7500.0, 0.0, 0.0]), np.uint64(1))
    >>> side, species, weight
    (array([0, 0]), array([0, 0]), array([2.5e+16, 2.5e+16]))
    >>> bool(np.all(velocity @ craft.side_normals[0] < 0.0))  # into the side
    True
    """
    n = senders.shape[0] * per_side
    side = np.empty(n, dtype=np.int64)
    species = np.empty(n, dtype=np.int64)
    point = np.empty((n, 3))
    velocity = np.empty((n, 3))
    weight = np.empty(n)
    k_count = thermal_speed.shape[0]
    for row in range(senders.shape[0]):
        s = senders[row]
        key = side_key(seed, s)
        corners = triangles[side_facet[s]]
        normal = normals[s]
        into = -(drift[0] * normal[0] + drift[1] * normal[1] + drift[2] * normal[2])  # drift into the side
        e1, e2 = _tangents(normal, drift)
        along1 = drift[0] * e1[0] + drift[1] * e1[1] + drift[2] * e1[2]
        along2 = drift[0] * e2[0] + drift[1] * e2[1] + drift[2] * e2[2]
        for m in range(per_side):
            i = row * per_side + m
            side[i] = s
            # species by stratified inversion of the pick probabilities
            target = (m + _random(key, m, 0, 0)) / per_side
            k = 0
            cumulative = species_pick[row, 0]
            while cumulative < target and k < k_count - 1:
                k += 1
                cumulative += species_pick[row, k]
            species[i] = k
            weight[i] = areas[s] * species_flux[row, k] / (species_pick[row, k] * per_side)
            # a point of the side: stratified along one edge, area-preserving square-to-triangle map
            b1, b2 = square_to_triangle((m + _random(key, m, 0, 1)) / per_side, _random(key, m, 0, 2))
            b0 = 1.0 - b1 - b2
            for d in range(3):
                point[i, d] = b0 * corners[0, d] + b1 * corners[1, d] + b2 * corners[2, d]
            c = thermal_speed[k]
            normal_speed = c * _flux_normal_speed(into / c, key, m, 0)
            g1 = math.sqrt(-math.log(1.0 - _random(key, m, 0, 3))) * math.cos(
                2 * math.pi * _random(key, m, 0, 4)
            )
            g2 = math.sqrt(-math.log(1.0 - _random(key, m, 0, 5))) * math.cos(
                2 * math.pi * _random(key, m, 0, 6)
            )
            t1, t2 = along1 + c * g1, along2 + c * g2  # g1, g2: normal draws of variance 1/2
            for d in range(3):
                velocity[i, d] = -normal_speed * normal[d] + t1 * e1[d] + t2 * e2[d]
    return side, species, point, velocity, weight


@numba.njit(cache=True, nogil=True)
def bounce(
    molecules: tuple,
    depth: int,
    side_law: NDArray[np.int64],
    normals: NDArray[np.float64],
    mass: NDArray[np.float64],
    laws: tuple,
    seed: np.uint64,
    reference: NDArray[np.float64],
    totals: NDArray[np.float64],
    book: bool,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """What each arriving molecule sends on: the mirrored share of its law, or one draw of CLL.

    The mirrored share leaves along ``v - 2 (v . n) n`` with the molecule's weight times the share; a
    CLL molecule leaves with one draw of Lord's kernel and its whole weight (random numbers keyed by
    the molecule's ``packet`` number and ``depth``). With ``book``, each outgoing leg's momentum ``w m
    v'`` is taken as escaping: subtracted from ``totals``; without (the first bounce), the panel law has
    taken it so already.

    Parameters
    ----------
    molecules : Molecules
        :class:`~sunwind.forces.gas.chains.Molecules` arriving: ``side``, ``species``, ``point`` [m],
        ``velocity`` [m/s] (into the side), ``weight`` [1/s] and ``packet``, (n,) or (n, 3) each.
    depth : int
        Bounces so far (keys the random numbers).
    side_law : (n_sides,) int64
        Law of each side, into ``laws``.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    mass : (k,) float64
        Mass of each species [kg].
    laws : ChainLaws
        :class:`~sunwind.forces.gas.chains.ChainLaws`: ``mirrored``, ``cll``, ``alpha_n``, ``sigma_t``
        and ``wall_temperature_K`` per law are read.
    seed : uint64
        Seed of the random numbers.
    reference : (3,) float64
        Torque reference point [m].
    totals : (6,) float64
        Force [N] and torque [N m] so far; updated in place.
    book : bool
        Whether the outgoing momentum is booked as escaping.

    Returns
    -------
    out_velocity : (n, 3) float64
        Velocity of what each molecule sends on [m/s].
    out_weight : (n,) float64
        Its weight [1/s].
    sends : (n,) bool
        Which molecules send anything on.

    Examples
    --------
    A mirror sends every molecule on with its normal velocity reversed:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> craft.side_normals[0], float(craft.side_areas[0])
    (array([-1.,  0., -0.]), 0.5)
    >>> side, species, point, velocity, weight = starts(np.array([0]), 2, craft.triangles, craft.side_facet,
    ...     craft.side_normals, craft.side_areas, np.array([[1e17]]), np.array([[1.0]]), np.array([1000.0]),
    ...     np.array([7500.0, 0.0, 0.0]), np.uint64(1))
    >>> from sunwind.forces.gas.chains import ChainLaws, Molecules
    >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
    >>> mirror = ChainLaws.of(GasSurfaces.of({"code": [MODEL_CODES["specular"]], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 1.0, "tangential_accommodation": 1.0, "wall_temperature_K": 300.0}))
    >>> side_law, mass = np.zeros(craft.n_sides, dtype=np.int64), np.array([2.66e-26])
    >>> molecules = Molecules(side, species, point, velocity, weight, np.arange(2))
    >>> totals = np.zeros(6)
    >>> out_velocity, out_weight, sends = bounce(molecules, 0, side_law, craft.side_normals, mass, mirror,
    ...     np.uint64(1), np.zeros(3), totals, False)
    >>> sends, bool(np.allclose(out_velocity[:, 0], -velocity[:, 0])), bool(np.all(totals == 0.0))
    (array([ True,  True]), True, True)
    """
    side, species, point, velocity = molecules.side, molecules.species, molecules.point, molecules.velocity
    weight, packet = molecules.weight, molecules.packet
    mirrored, is_cll, alpha_n, sigma_t = laws.mirrored, laws.cll, laws.alpha_n, laws.sigma_t
    wall = laws.wall_temperature_K
    n = side.shape[0]
    out_velocity = np.zeros((n, 3))
    out_weight = np.zeros(n)
    sends = np.zeros(n, dtype=np.bool_)
    for i in range(n):
        s = side[i]
        law = side_law[s]
        normal = normals[s]
        v = velocity[i]
        vn = v[0] * normal[0] + v[1] * normal[1] + v[2] * normal[2]
        if is_cll[law]:
            key = side_key(seed, packet[i])
            m = mass[species[i]]
            c_w = math.sqrt(2.0 * _BOLTZMANN * wall[law] / m)
            a_n, s_t = alpha_n[law], sigma_t[law]
            a_t = s_t * (2.0 - s_t)
            r = math.sqrt(-a_n * math.log(1.0 - _random(key, 0, depth, 40)))
            theta = 2.0 * math.pi * _random(key, 0, depth, 41)
            u_m = math.sqrt(1.0 - a_n) * (-vn / c_w)
            u_n = math.sqrt(max(r * r + u_m * u_m + 2.0 * r * u_m * math.cos(theta), 0.0))
            e1, e2 = _tangents(normal, v)
            tangential = v[0] * e1[0] + v[1] * e1[1] + v[2] * e1[2]
            r = math.sqrt(-a_t * math.log(1.0 - _random(key, 0, depth, 42)))
            theta = 2.0 * math.pi * _random(key, 0, depth, 43)
            u_1 = (1.0 - s_t) * tangential / c_w + r * math.cos(theta)
            u_2 = r * math.sin(theta)
            for d in range(3):
                out_velocity[i, d] = c_w * (u_n * normal[d] + u_1 * e1[d] + u_2 * e2[d])
            out_weight[i] = weight[i]
        elif mirrored[law] > 0.0:
            for d in range(3):
                out_velocity[i, d] = v[d] - 2.0 * vn * normal[d]
            out_weight[i] = weight[i] * mirrored[law]
        else:
            continue
        sends[i] = True
        if not book:
            continue
        scale = -out_weight[i] * mass[species[i]]
        _push_moment(totals, point[i], reference, scale * out_velocity[i, 0], scale * out_velocity[i, 1],
                     scale * out_velocity[i, 2])  # fmt: skip
    return out_velocity, out_weight, sends


@numba.njit(cache=True, nogil=True, inline="always")
def _push_moment(
    totals: NDArray[np.float64],
    at: NDArray[np.float64],
    reference: NDArray[np.float64],
    x: float,
    y: float,
    z: float,
) -> None:
    """Add the vector ``(x, y, z)`` acting at ``at`` to ``totals[0:3]`` and its moment about ``reference``
    to ``totals[3:6]``."""
    r0, r1, r2 = at[0] - reference[0], at[1] - reference[1], at[2] - reference[2]
    totals[0] += x
    totals[1] += y
    totals[2] += z
    totals[3] += r1 * z - r2 * y
    totals[4] += r2 * x - r0 * z
    totals[5] += r0 * y - r1 * x


@numba.njit(cache=True, nogil=True)
def land(
    struck: NDArray[np.int64],
    origin: NDArray[np.float64],
    species: NDArray[np.int64],
    velocity: NDArray[np.float64],
    weight: NDArray[np.float64],
    side_law: NDArray[np.int64],
    mass: NDArray[np.float64],
    laws: tuple,
    reference: NDArray[np.float64],
    totals: NDArray[np.float64],
    deposit: NDArray[np.float64],
) -> NDArray[np.bool_]:
    """Book each leg that meets a side: its momentum stays, its diffuse share goes to the exchange.

    A leg's momentum ``w m v`` stays with the model (added to ``totals`` with its moment; any point of
    the leg's line gives the same moment), and the diffuse share of the struck side's law is re-emitted
    there at ``T_r = wall_weight T_w + energy_weight m v^2 / (2 k)``, its momentum rate and
    sqrt(mass)-weighted rate added to ``deposit``. A leg meeting a side the model does not have
    (``BLIND``) is absorbed.

    Parameters
    ----------
    struck : (n,) int64
        Side each leg meets; negative where it escapes (``BLIND``: a side the model does not have).
    origin : (n, 3) float64
        Where each leg starts [m].
    species : (n,) int64
        Species of each molecule, into ``mass``.
    velocity : (n, 3) float64
        Velocity of each leg [m/s].
    weight : (n,) float64
        Molecules per second each leg stands for [1/s].
    side_law : (n_sides,) int64
        Law of each side, into ``laws``.
    mass : (k,) float64
        Mass of each species [kg].
    laws : ChainLaws
        :class:`~sunwind.forces.gas.chains.ChainLaws`: ``diffuse``, ``wall_weight``, ``energy_weight``
        and ``wall_temperature_K`` per law are read.
    reference : (3,) float64
        Torque reference point [m].
    totals : (6,) float64
        Force [N] and torque [N m] so far; updated in place.
    deposit : (2, n_sides) float64
        Diffuse re-emission per side: momentum rate [N] and sqrt(mass)-weighted rate [sqrt(kg)/s];
        updated in place.

    Returns
    -------
    goes_on : (n,) bool
        Which legs struck a side whose law sends some of them on.

    Examples
    --------
    Of two legs, one escapes (``struck`` negative) and one meets a mirror, which sends it on:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> craft.side_normals[0], float(craft.side_areas[0])
    (array([-1.,  0., -0.]), 0.5)
    >>> side, species, point, velocity, weight = starts(np.array([0]), 2, craft.triangles, craft.side_facet,
    ...     craft.side_normals, craft.side_areas, np.array([[1e17]]), np.array([[1.0]]), np.array([1000.0]),
    ...     np.array([7500.0, 0.0, 0.0]), np.uint64(1))
    >>> from sunwind.forces.gas.chains import ChainLaws, Molecules
    >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
    >>> mirror = ChainLaws.of(GasSurfaces.of({"code": [MODEL_CODES["specular"]], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 1.0, "tangential_accommodation": 1.0, "wall_temperature_K": 300.0}))
    >>> side_law, mass = np.zeros(craft.n_sides, dtype=np.int64), np.array([2.66e-26])
    >>> totals, deposit = np.zeros(6), np.zeros((2, craft.n_sides))
    >>> land(np.array([-1, 1]), point, species, -velocity, weight, side_law, mass, mirror, np.zeros(3),
    ...     totals, deposit)
    array([False,  True])
    >>> bool(np.any(totals != 0.0)), bool(np.all(deposit == 0.0))
    (True, True)
    """
    diffuse, wall_weight, energy_weight = laws.diffuse, laws.wall_weight, laws.energy_weight
    wall = laws.wall_temperature_K
    n = struck.shape[0]
    goes_on = np.zeros(n, dtype=np.bool_)
    for i in range(n):
        s = struck[i]
        if s < 0 and s != BLIND:  # escaped
            continue
        m = mass[species[i]]
        scale = weight[i] * m
        _push_moment(totals, origin[i], reference, scale * velocity[i, 0], scale * velocity[i, 1],
                     scale * velocity[i, 2])  # fmt: skip
        if s == BLIND:
            continue
        law = side_law[s]
        share = diffuse[law]
        if share > 0.0:
            speed_squared = velocity[i, 0] ** 2 + velocity[i, 1] ** 2 + velocity[i, 2] ** 2
            temperature = wall_weight[law] * wall[law] + energy_weight[law] * m * speed_squared / (
                2.0 * _BOLTZMANN
            )
            rate = weight[i] * share
            deposit[0, s] += rate * m * _MEAN_SPEED * math.sqrt(2.0 * _BOLTZMANN * temperature / m)
            deposit[1, s] += rate * math.sqrt(m)
        goes_on[i] = share < 1.0
    return goes_on


@numba.njit(cache=True, nogil=True)
def cll_tangents(
    molecules: tuple,
    depth: int,
    side_law: NDArray[np.int64],
    normals: NDArray[np.float64],
    mass: NDArray[np.float64],
    laws: tuple,
    seed: np.uint64,
    d_velocity: NDArray[np.float64],
    column: NDArray[np.int64],
    d_out: NDArray[np.float64],
) -> None:
    """Derivatives of the velocities :func:`bounce` draws from CLL's kernel, its random numbers held.

    By the arriving velocities (their derivatives ``d_velocity``) and by the law's ``alpha_n`` and
    ``sigma_t`` (columns ``column[side]`` and ``column[side] + 1``).

    Parameters
    ----------
    molecules : Molecules
        The molecules arriving, as for :func:`bounce`.
    depth : int
        Bounces so far.
    side_law : (n_sides,) int64
        Law of each side.
    normals : (n_sides, 3) float64
        Outward unit normal of each side.
    mass : (k,) float64
        Mass of each species [kg].
    laws : ChainLaws
        :class:`~sunwind.forces.gas.chains.ChainLaws`.
    seed : uint64
        Seed of the random numbers (as for :func:`bounce`).
    d_velocity : (n, 3, p) float64
        Derivatives of the arriving velocities by ``p`` parameters [m/s].
    column : (n_sides,) int64
        Each side's column of ``alpha_n`` (``sigma_t`` the next).
    d_out : (n, 3, p) float64
        Derivatives of the velocities sent on; rows of CLL molecules written.

    Examples
    --------
    A CLL wall that accommodates more sends molecules off more slowly along the flow:

    >>> import numpy as np
    >>> from sunwind.forces.gas.chains import ChainLaws, Molecules
    >>> from sunwind.forces.gas.laws import MODEL_CODES, GasSurfaces
    >>> wall = ChainLaws.of(GasSurfaces.of({"code": [MODEL_CODES["cll"]], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 0.5, "tangential_accommodation": 0.5, "wall_temperature_K": 300.0}))
    >>> one = Molecules(np.zeros(1, np.int64), np.zeros(1, np.int64), np.zeros((1, 3)),
    ...     np.array([[7000.0, 0.0, -1000.0]]), np.ones(1), np.zeros(1, np.int64))
    >>> d_out = np.zeros((1, 3, 2))
    >>> cll_tangents(one, 0, np.zeros(1, np.int64), np.array([[0.0, 0.0, 1.0]]), np.array([2.66e-26]),
    ...     wall, np.uint64(1), np.zeros((1, 3, 2)), np.zeros(1, np.int64), d_out)
    >>> bool(d_out[0, 0, 1] < 0.0)
    True
    """
    side, species, velocity, packet = molecules.side, molecules.species, molecules.velocity, molecules.packet
    is_cll, alpha_n, sigma_t, wall = laws.cll, laws.alpha_n, laws.sigma_t, laws.wall_temperature_K
    n_par = d_velocity.shape[2]
    for i in range(side.shape[0]):
        s = side[i]
        law = side_law[s]
        if not is_cll[law]:
            continue
        normal, v = normals[s], velocity[i]
        vn = v[0] * normal[0] + v[1] * normal[1] + v[2] * normal[2]
        key = side_key(seed, packet[i])
        c_w = math.sqrt(2.0 * _BOLTZMANN * wall[law] / mass[species[i]])
        a_n, s_t = alpha_n[law], sigma_t[law]
        a_t = s_t * (2.0 - s_t)
        r = math.sqrt(-a_n * math.log(1.0 - _random(key, 0, depth, 40)))
        cos_theta = math.cos(2.0 * math.pi * _random(key, 0, depth, 41))
        root = math.sqrt(1.0 - a_n)
        u_m = root * (-vn / c_w)
        u_n = math.sqrt(max(r * r + u_m * u_m + 2.0 * r * u_m * cos_theta, 0.0))
        e1, e2 = _tangents(normal, v)
        tangential = v[0] * e1[0] + v[1] * e1[1] + v[2] * e1[2]
        r_t = math.sqrt(-a_t * math.log(1.0 - _random(key, 0, depth, 42)))
        theta_t = 2.0 * math.pi * _random(key, 0, depth, 43)
        u_1 = (1.0 - s_t) * tangential / c_w + r_t * math.cos(theta_t)
        u_2 = r_t * math.sin(theta_t)
        size = math.sqrt(max(v[0] ** 2 + v[1] ** 2 + v[2] ** 2 - vn * vn, 0.0))
        for p in range(n_par):
            dv = (d_velocity[i, 0, p], d_velocity[i, 1, p], d_velocity[i, 2, p])
            if dv[0] == 0.0 and dv[1] == 0.0 and dv[2] == 0.0:
                continue
            dvn = dv[0] * normal[0] + dv[1] * normal[1] + dv[2] * normal[2]
            d_tangential = dv[0] * e1[0] + dv[1] * e1[1] + dv[2] * e1[2]
            d_u_m = -root * dvn / c_w
            d_u_n = (u_m + r * cos_theta) * d_u_m / u_n if u_n > 0.0 else 0.0
            d_u_1 = (1.0 - s_t) * d_tangential / c_w
            a0 = a1 = a2 = 0.0  # d e1: the turn of the tangential part of v
            if size > 1e-12 * max(1.0, abs(vn)):
                a0 = (dv[0] - dvn * normal[0] - d_tangential * e1[0]) / size
                a1 = (dv[1] - dvn * normal[1] - d_tangential * e1[1]) / size
                a2 = (dv[2] - dvn * normal[2] - d_tangential * e1[2]) / size
            b0 = normal[1] * a2 - normal[2] * a1  # d e2 = n x d e1
            b1 = normal[2] * a0 - normal[0] * a2
            b2 = normal[0] * a1 - normal[1] * a0
            d_out[i, 0, p] = c_w * (d_u_n * normal[0] + d_u_1 * e1[0] + u_1 * a0 + u_2 * b0)
            d_out[i, 1, p] = c_w * (d_u_n * normal[1] + d_u_1 * e1[1] + u_1 * a1 + u_2 * b1)
            d_out[i, 2, p] = c_w * (d_u_n * normal[2] + d_u_1 * e1[2] + u_1 * a2 + u_2 * b2)
        first = column[s]
        if a_n > 0.0 and u_n > 0.0:
            d_r = r / (2.0 * a_n)
            d_u_m = (vn / c_w) / (2.0 * root) if root > 0.0 else 0.0
            d_u_n = (r * d_r + u_m * d_u_m + cos_theta * (d_r * u_m + r * d_u_m)) / u_n
            for d in range(3):
                d_out[i, d, first] += c_w * d_u_n * normal[d]
        if a_t > 0.0:
            d_r_t = r_t / (2.0 * a_t) * (2.0 - 2.0 * s_t)
            d_u_1 = -tangential / c_w + d_r_t * math.cos(theta_t)
            d_u_2 = d_r_t * math.sin(theta_t)
            for d in range(3):
                d_out[i, d, first + 1] += c_w * (d_u_1 * e1[d] + d_u_2 * e2[d])
