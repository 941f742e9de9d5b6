"""Every sensor's flux at every pair of Sun and nadir directions of a coarse icosphere: the start of the
global search (METHOD.md "Attitude from heat fluxes").

The planet's cap is integrated by a fixed product rule (Gauss-Legendre in the angle from the nadir,
the trapezoid rule in azimuth) over the sensor response, so that one nadir's cap serves every Sun
direction at once; the table is a map for finding the basins of the misfit, not the answer (the search
refines each basin with :class:`~sunwind.forces.sensing.forward.FluxModel`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.planet.visibility import direction_grid
from sunwind.forces.sensing.forward import FluxModel
from sunwind.geometry.memory import require

#: Icosphere level of the table (642 directions about 8.6 degrees apart).
COARSE_LEVEL = 3
#: The cap's rule: points in the angle from the nadir and in azimuth.
RULE = (10, 24)
#: Nadir directions handled at once (bounds the working memory).
_CHUNK = 16


@dataclass(frozen=True, eq=False)
class CoarseTable:
    """Sensor fluxes at every (nadir, Sun) pair of an icosphere [W/m^2].

    Attributes
    ----------
    nodes : (m, 3) float64
        The icosphere's unit directions, body frame.
    neighbours : (m, 6) int64
        Each node's neighbours on the icosphere (the node itself where it has five).
    solar : (m, p) float64
        Sunlight at full disc along each node.
    planet : (m, m, p) float64
        Albedo plus infrared at nadir ``k`` and Sun ``j``.
    fraction : (m, m) float64
        Solar fraction at nadir ``k`` and Sun ``j``.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> table = coarse_table(flux_model(cube, 500.0), level=1)
    >>> table.planet.shape, table.neighbours.shape
    ((42, 42, 6), (42, 6))
    """

    nodes: NDArray[np.float64]
    neighbours: NDArray[np.int64]
    solar: NDArray[np.float64]
    planet: NDArray[np.float64]
    fraction: NDArray[np.float64]

    @functools.cached_property
    def fluxes(self) -> NDArray[np.float64]:
        """Total flux at every (nadir, Sun) pair [W/m^2], (m, m, p), made on first use.

        Returns
        -------
        (m, m, p) float64

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.sensing.forward import flux_model
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> coarse_table(flux_model(cube, 500.0), level=1).fluxes.shape
        (42, 42, 6)
        """
        return self.planet + self.fraction[:, :, None] * self.solar[None, :, :]

    @functools.cached_property
    def squares(self) -> NDArray[np.float64]:
        """:attr:`fluxes` squared, for the misfit's expansion, (m, m, p).

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.sensing.forward import flux_model
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> table = coarse_table(flux_model(cube, 500.0), level=1)
        >>> bool(np.array_equal(table.squares, table.fluxes**2))
        True
        """
        return self.fluxes**2

    @functools.cached_property
    def darkest(self) -> NDArray[np.float64]:
        """The most each sensor takes in eclipse (the planet's infrared, the Sun behind it) at any
        nadir of the table [W/m^2], (p,).

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.sensing.forward import flux_model
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> coarse_table(flux_model(cube, 500.0), level=1).darkest.round(1)
        array([163.8, 163.8, 163.8, 163.8, 163.8, 163.8])
        """
        m = len(self.nodes)
        return self.planet[np.arange(m), np.arange(m)].max(axis=0)

    @functools.cached_property
    def brightest(self) -> NDArray[np.float64]:
        """An upper bound of what each sensor takes at any attitude [W/m^2], (p,): its most sunlight at
        full disc along the table's directions plus its most albedo and infrared at any pair.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.sensing.forward import flux_model
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8),
        ...                threads=1)
        >>> table = coarse_table(flux_model(cube, 500.0), level=1)
        >>> bool(np.all(table.brightest >= table.fluxes.max(axis=(0, 1))))
        True
        """
        return self.solar.max(axis=0) + self.planet.max(axis=(0, 1))


def coarse_table(model: FluxModel, level: int = COARSE_LEVEL) -> CoarseTable:
    """The flux table of ``model`` on the icosphere of ``level``.

    Parameters
    ----------
    model : FluxModel
        The sensors, planet and altitude.
    level : int
        Icosphere level (3: 642 directions, 412 164 pairs).

    Returns
    -------
    CoarseTable

    Raises
    ------
    MemoryLimitError
        The table would exceed the memory limit (many sensors at a fine level).

    Examples
    --------
    The table agrees with the flux model where the cap rule is exact enough, e.g. the zenith face:

    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> fluxes = flux_model(cube, 500.0)
    >>> table = coarse_table(fluxes, level=1)
    >>> k = int(np.argmax(table.nodes @ [0.0, 0.0, -1.0]))
    >>> exact = fluxes.fluxes(table.nodes[k], table.nodes[k]).total
    >>> round(float(table.planet[k, k, 5]), 1), round(float(exact[5]), 1)
    (163.8, 163.8)
    """
    grid = direction_grid(level)
    nodes, m = grid.nodes, len(grid.nodes)
    response, light = model.response, model.light
    p = len(response.sensors)
    require(8 * m * m * (p + 1) * 2, "the coarse attitude table", "fewer sensors")
    area = response.areas_m2
    solar = light.solar_flux_W_m2 * response.collimated("solar", nodes) / area
    fraction = np.stack([model.solar_fraction(nodes, np.repeat(n[None], m, axis=0)) for n in nodes])
    directions, normals, solid = _cap_rule(model, nodes)  # (m, q, 3), (m, q, 3), (q,)
    q = solid.size
    planet = np.empty((m, m, p))
    laws = (light.albedo, light.infrared)
    for lo in range(0, m, _CHUNK):
        hi = min(lo + _CHUNK, m)
        flat = directions[lo:hi].reshape(-1, 3)
        lit = np.maximum(normals[lo:hi] @ nodes.T, 0.0)  # (c, q, m): cos of the Sun's zenith
        total = np.zeros((hi - lo, m, p))
        for band, law in zip(("solar", "infrared"), laws, strict=True):
            seen = (response.collimated(band, flat) / area).reshape(hi - lo, q, p) * (solid / math.pi)[
                None, :, None
            ]
            total += law.uniform_W_m2 * seen.sum(axis=1)[:, None, :]
            if law.insolation_W_m2:
                total += law.insolation_W_m2 * np.einsum("cqm,cqp->cmp", lit, seen)
        planet[lo:hi] = total
    return CoarseTable(nodes, _neighbours(grid.faces, m), solar, planet, fraction)


def _cap_rule(model: FluxModel, nadirs: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
    """The cap's product rule about each nadir: directions, the ground's outward normal there and each
    point's solid angle."""
    theta0 = model.half_angle
    x, w = np.polynomial.legendre.leggauss(RULE[0])
    theta = theta0 * (x + 1) / 2
    d_theta = theta0 * w / 2
    phi = 2 * math.pi * np.arange(RULE[1]) / RULE[1]
    grid_theta, grid_phi = np.meshgrid(theta, phi, indexing="ij")
    solid = (d_theta * np.sin(theta))[:, None] * np.full(RULE[1], 2 * math.pi / RULE[1])
    local = np.stack(
        [np.sin(grid_theta) * np.cos(grid_phi), np.sin(grid_theta) * np.sin(grid_phi), np.cos(grid_theta)],
        axis=-1,
    ).reshape(-1, 3)
    e1 = np.cross(nadirs, np.where(np.abs(nadirs[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]]))
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(nadirs, e1)
    frames = np.stack([e1, e2, nadirs], axis=1)  # (m, 3, 3): rows are the cap frame's axes
    directions = local @ frames  # (m, q, 3)
    radius, distance = model.light.planet.radius_m, model.distance_m
    cos = local[:, 2]
    reach = distance * cos - np.sqrt(np.maximum(radius**2 - (distance * np.sin(np.arccos(cos))) ** 2, 0.0))
    ground = (-distance * nadirs[:, None, :] + reach[None, :, None] * directions) / radius
    return directions, ground, solid.reshape(-1)


def _neighbours(faces: NDArray[np.int64], m: int) -> NDArray[np.int64]:
    """Each node's neighbours on the triangles, padded with the node itself, (m, 6)."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges = np.unique(np.sort(np.concatenate([edges, edges[:, ::-1]]), axis=1), axis=0)
    pairs = np.concatenate([edges, edges[:, ::-1]])
    order = np.argsort(pairs[:, 0], kind="stable")
    pairs = pairs[order]
    out = np.repeat(np.arange(m)[:, None], 6, axis=1)
    starts = np.searchsorted(pairs[:, 0], np.arange(m))
    rank = np.arange(len(pairs)) - starts[pairs[:, 0]]
    out[pairs[:, 0], rank] = pairs[:, 1]
    return out
