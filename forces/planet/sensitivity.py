"""Derivatives of the planet's radiation force and torque with respect to every material's coefficients:
the albedo's through the solar optics ``(rho, beta, sigma)``, the infrared's through the emissivity
(infrared optics ``(1 - eps, 0, 0)``) (METHOD.md "Planet radiation", "Sensitivities").

A band's direct load (every reflected photon escaping: reflections ``none`` and ``plates``) is, side by
side, eq. (4) over the side's shadowed integrals plus the couple of moving its lit force to its lit
centroid, and both are linear in the side's shares ``(alpha, rho_s, rho_d, sigma)``
(:func:`~sunwind.forces.radiation.sensitivity.share_forces`). Summed per material and unit share
(:class:`ShareLoads`: the same cap integrals and shadow losses, the share weights replaced by one), the
load is ``sum_m sum_s share_ms L_ms`` and its derivative with respect to a coefficient of material ``m``
is ``sum_s (d share_s / d coefficient) L_ms``: exact, and from the very shadow passes of the load (the
cells' passes observed as :func:`~sunwind.forces.planet.loads.band_loads` casts them, or the
visibility's per-node couples per material), none cast per coefficient.

The derivative arrays of each band (:func:`band_derivatives`) are summed into a
:class:`~sunwind.forces.sensitivity.Sensitivities` by :func:`planet_sensitivities`, where the
derivatives of the reflected part (beam chains, diffuse balance) are to be added when they exist.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.planet.lit_law import lit_share_torques
from sunwind.forces.planet.loads import BandLoad, Source
from sunwind.forces.planet.visibility import Visibility
from sunwind.forces.radiation.sensitivity import SHARES, per_material, share_forces
from sunwind.forces.reflection.sensitivity import diffuse_emissivity_derivatives, diffuse_optics_derivatives
from sunwind.forces.sensitivity import COEFFICIENTS, OPTICS, Sensitivities, optics_partials
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft

#: d (absorbed, specular, diffuse, transmitted) / d emissivity of the infrared optics ``(1 - eps, 0, 0)``.
EMISSIVITY_PARTIALS = np.array([1.0, 0.0, -1.0, 0.0])
#: Index of the emissivity in :data:`~sunwind.forces.sensitivity.COEFFICIENTS`.
EMISSIVITY = COEFFICIENTS.index("emissivity")


@dataclass(frozen=True)
class ShareLoads:
    """A band's direct load per material and unit share, body frame, SI.

    Attributes
    ----------
    force_N : (n_materials, 4, 3) float64
        Force on the sides of each material were all their light of the band to leave by one share
        (:data:`~sunwind.forces.radiation.sensitivity.SHARES`) [N].
    torque_Nm : (n_materials, 4, 3) float64
        Its torque about the reference point, the lit-centroid couples included [N m].

    Examples
    --------
    Weighted by the materials' shares it is the band's direct load:

    >>> import numpy as np
    >>> loads = ShareLoads(np.ones((1, 4, 3)), np.zeros((1, 4, 3)))
    >>> loads.total(np.array([[0.5, 0.1, 0.3, 0.1]]))[0]
    array([1., 1., 1.])
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]

    def total(self, shares: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Force and torque with each material's ``shares`` (n_materials, 4).

        Parameters
        ----------
        shares : (n_materials, 4) float64
            ``(alpha, rho_s, rho_d, sigma)`` of each material in the band.

        Returns
        -------
        force, torque : (3,) float64
            [N], [N m].

        Examples
        --------
        >>> ShareLoads(np.ones((1, 4, 3)), np.ones((1, 4, 3))).total(np.full((1, 4), 0.25))[1]
        array([1., 1., 1.])
        """
        return np.einsum("ms,msc->c", shares, self.force_N), np.einsum("ms,msc->c", shares, self.torque_Nm)


def share_loads(
    craft: Spacecraft,
    integrals: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    lost: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    lit_torque_Nm: NDArray[np.float64],
    reference_m: NDArray[np.float64],
) -> ShareLoads:
    """A band's :class:`ShareLoads` from its sides' integrals, what shadow takes off them and the lit
    couples per material, as :func:`~sunwind.forces.planet.loads.band_loads` sums its load.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    integrals : tuple of (n_sides,), (n_sides, 3), (n_sides,) float64
        Unshadowed ``I_0, I_1, I_2`` of every side [W/m^2].
    lost : tuple of (n_sides,), (n_sides, 3), (n_sides,) float64
        What shadow takes off them [W/m^2]; a side left with ``I_0 <= 0`` is dark.
    lit_torque_Nm : (n_materials, 4, 3) float64
        Couples of moving the lit forces to the lit centroids, per material and unit share [N m].
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    ShareLoads

    Examples
    --------
    A grey cube with the Sun overhead: the shares weight the load into eq. (4).

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> i0 = 1361.0 * np.maximum(craft.side_normals @ up, 0.0)
    >>> none = (np.zeros(craft.n_sides), np.zeros((craft.n_sides, 3)), np.zeros(craft.n_sides))
    >>> loads = share_loads(craft, (i0, i0[:, None] * up, i0), none, np.zeros((1, 4, 3)), np.zeros(3))
    >>> force, _ = loads.total(np.array([[0.7, 0.0, 0.3, 0.0]]))
    >>> round(float(force[2]) * 1e6, 4)  # [uN]: -(1 + 0.2) 1361 / c on 1 m^2
    -5.4478
    """
    i0, i1, i2 = (a - b for a, b in zip(integrals, lost, strict=True))
    dark = i0 <= 0.0  # as the load: a side that loses more than its exact share is dark
    i0, i1, i2 = np.where(dark, 0.0, i0), np.where(dark[:, None], 0.0, i1), np.where(dark, 0.0, i2)
    forces = share_forces(craft.side_normals, craft.side_areas, i0, i1, i2)
    torques = np.cross((craft.side_centroids - reference_m)[:, None, :], forces)
    count = len(craft.materials)
    return ShareLoads(
        per_material(craft.side_material, forces, count),
        per_material(craft.side_material, torques, count) + lit_torque_Nm,
    )


def grid_share_loads(
    craft: Spacecraft, sources: Sequence[Source], seen: Visibility, reference_m: NDArray[np.float64]
) -> list[ShareLoads]:
    """Each band's :class:`ShareLoads` from the model's directional visibility, as
    :func:`~sunwind.forces.planet.loads.grid_band_loads` takes its load: no ray is cast.

    Parameters
    ----------
    craft : Spacecraft
        The model ``seen`` was built for.
    sources : sequence of Source
        The bands, ``weights`` spread on the grid's nodes.
    seen : Visibility
        The model's visibility; its ``lit_torque_Nm`` gives the lit couples.
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    list of ShareLoads
        One per source.

    Examples
    --------
    A uniform glow about a box-and-wing model: the shares give back the band's direct load.

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.planet.loads import grid_band_loads
    >>> from sunwind.forces.planet.visibility import visibility
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=grey, threads=1).craft
    >>> seen = visibility(craft, 2, sw.ShadowSampling(), sw.ReflectionSettings("none"))
    >>> w = np.ones(len(seen.grid.nodes))
    >>> cos = np.maximum(craft.side_normals @ seen.grid.nodes.T, 0.0)
    >>> glow = Source("albedo", (cos @ w, (cos * w) @ seen.grid.nodes, (cos**2) @ w), w,
    ...               craft.side_optics, beams=False, exchange=None)
    >>> (load,) = grid_band_loads(craft, [glow], seen, np.zeros(3), estimates=False)
    >>> (shares,) = grid_share_loads(craft, [glow], seen, np.zeros(3))
    >>> force, torque = shares.total(np.array([[0.7, 0.0, 0.3, 0.0]]))
    >>> bool(np.allclose(force, load.force_N, rtol=1e-12)), bool(np.allclose(torque, load.torque_Nm))
    (True, True)
    """
    nodes = seen.grid.nodes
    weights = np.column_stack([source.weights for source in sources])  # (n, b)
    n, b = weights.shape
    columns = np.concatenate([weights, (weights[:, :, None] * nodes[:, None, :]).reshape(n, 3 * b)], axis=1)
    lost, lost2 = seen.shadow @ columns, seen.shadow2 @ weights
    out = []
    for k, source in enumerate(sources):
        losses = (lost[:, k], lost[:, b + 3 * k : b + 3 * k + 3], lost2[:, k])
        lit = np.einsum("j,jmsc->msc", weights[:, k], seen.lit_torque_Nm)
        out.append(share_loads(craft, source.integrals, losses, lit, reference_m))
    return out


class CellShares:
    """What each band's :class:`ShareLoads` needs of the cells' shadow passes, gathered as
    :func:`~sunwind.forces.planet.loads.band_loads` casts them (its ``observe``): each side's shadow
    losses and lit couples per unit share, as the load takes them.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    sources : sequence of Source
        The bands, in the order and with the cells given to ``band_loads``.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.planet.loads import band_loads
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=grey, threads=1).craft
    >>> u = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])
    >>> cos = np.maximum(craft.side_normals @ u, 0.0)
    >>> sun = Source("solar", (1361.0 * cos, 1361.0 * cos[:, None] * u, 1361.0 * cos**2),
    ...              np.array([1361.0]), craft.side_optics, beams=False, exchange=None)
    >>> cells = CellShares(craft, [sun])
    >>> shadows, settings = sw.ShadowSampling(), sw.ReflectionSettings("none")
    >>> (load,), _ = band_loads(craft, [sun], u[None, :], np.zeros(3), shadows, settings, cells.observe)
    >>> force, torque = cells.share_loads(np.zeros(3))[0].total(np.array([[0.7, 0.0, 0.3, 0.0]]))
    >>> bool(np.allclose(force, load.force_N, rtol=1e-12)), bool(np.allclose(torque, load.torque_Nm))
    (True, True)
    """

    def __init__(self, craft: Spacecraft, sources: Sequence[Source]) -> None:
        self.craft = craft
        self.sources = list(sources)
        n = craft.n_sides
        self.lost = [(np.zeros(n), np.zeros((n, 3)), np.zeros(n)) for _ in self.sources]
        self.lit = [np.zeros((n, len(SHARES), 3)) for _ in self.sources]

    def observe(self, k: int, light: Illumination) -> None:
        """Take in the shadow pass of cell ``k``.

        Parameters
        ----------
        k : int
            The cell.
        light : Illumination
            Its pass.
        """
        craft, direction = self.craft, light.direction
        facing, share = light.facing, light.facing_share.astype(np.float64)
        dark, dark_share = facing[share < 1.0], share[share < 1.0]
        if not len(dark):
            return
        normals = craft.side_normals[dark]
        cos = normals @ direction
        offset = light.lit_centroid[dark] - craft.side_centroids[dark]
        torques = lit_share_torques(normals, craft.side_areas[dark], direction, (dark_share, offset))
        for source, (i0, i1, i2), lit in zip(self.sources, self.lost, self.lit, strict=True):
            weight = float(source.weights[k])
            if weight > 0:  # the sides of a pass are distinct: plain adds, in the load's order
                lost = weight * cos * (1.0 - dark_share)
                i0[dark] += lost
                i1[dark] += lost[:, None] * direction
                i2[dark] += lost * cos
                lit[dark] += weight * torques

    def share_loads(self, reference_m: NDArray[np.float64]) -> list[ShareLoads]:
        """Each band's :class:`ShareLoads` once every pass has been observed.

        Parameters
        ----------
        reference_m : (3,) float64
            Torque reference point [m].

        Returns
        -------
        list of ShareLoads
            One per source.
        """
        craft, count = self.craft, len(self.craft.materials)
        return [
            share_loads(
                craft, source.integrals, lost, per_material(craft.side_material, lit, count), reference_m
            )
            for source, lost, lit in zip(self.sources, self.lost, self.lit, strict=True)
        ]


def band_derivatives(
    craft: Spacecraft, band: str, loads: ShareLoads
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """d force and d torque of a band's direct load with respect to every material's coefficients.

    Parameters
    ----------
    craft : Spacecraft
        The model (its materials' reflectivity and specular fraction enter the albedo's partials).
    band : str
        "infrared" (the emissivity, through the optics ``(1 - eps, 0, 0)``), or "albedo"/"solar" (the
        optics ``(rho, beta, sigma)``).
    loads : ShareLoads
        The band's direct load per material and unit share.

    Returns
    -------
    force, torque : (n_materials, 7, 3) float64
        ``[material, coefficient, component]`` over :data:`~sunwind.forces.sensitivity.COEFFICIENTS`
        [N, N m per unit coefficient]; the coefficients the band does not depend on are zero.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> loads = ShareLoads(np.ones((1, 4, 3)), np.zeros((1, 4, 3)))
    >>> force, _ = band_derivatives(craft, "infrared", loads)
    >>> force[0, 3], force[0, 0]  # d/d eps: one more absorbed, one less diffused
    (array([0., 0., 0.]), array([0., 0., 0.]))
    >>> force, _ = band_derivatives(craft, "albedo", ShareLoads(np.eye(4, 3)[None], np.zeros((1, 4, 3))))
    >>> force[0, :3]  # rows: d/d rho, d/d beta, d/d sigma
    array([[-1. ,  0. ,  1. ],
           [ 0. ,  0.3, -0.3],
           [-1. ,  0. ,  0. ]])
    """
    count = len(craft.materials)
    force, torque = np.zeros((count, len(COEFFICIENTS), 3)), np.zeros((count, len(COEFFICIENTS), 3))
    if band == "infrared":
        force[:, EMISSIVITY] = np.einsum("s,msc->mc", EMISSIVITY_PARTIALS, loads.force_N)
        torque[:, EMISSIVITY] = np.einsum("s,msc->mc", EMISSIVITY_PARTIALS, loads.torque_Nm)
    else:
        partials = optics_partials(
            craft.materials.rho, craft.materials.beta
        )  # [material, coefficient, share]
        force[:, : len(OPTICS)] = np.einsum("mks,msc->mkc", partials, loads.force_N)
        torque[:, : len(OPTICS)] = np.einsum("mks,msc->mkc", partials, loads.torque_Nm)
    return force, torque


def planet_sensitivities(
    craft: Spacecraft,
    parts: Sequence[tuple[NDArray[np.float64], NDArray[np.float64]]],
    reference_m: NDArray[np.float64],
) -> Sensitivities:
    """The :class:`~sunwind.forces.sensitivity.Sensitivities` of a result: its parts' derivatives summed.

    Parameters
    ----------
    craft : Spacecraft
        The model (its material names).
    parts : sequence of ((n_materials, 7, 3), (n_materials, 7, 3)) float64
        d force and d torque of each part of the load (:func:`band_derivatives` of each band's direct
        load; the reflected parts' when they exist).
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    Sensitivities

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> one = (np.ones((1, 7, 3)), np.zeros((1, 7, 3)))
    >>> planet_sensitivities(craft, [one, one], np.zeros(3)).of("grey.emissivity").force_N
    array([2., 2., 2.])
    """
    total = Sensitivities.zeros(craft.materials.names, reference_m)
    for force, torque in parts:
        total = total + Sensitivities(total.materials, force, torque, total.reference_point_m)
    return total


def reflected_derivatives(
    craft: Spacecraft, mode: str, sources: Sequence[Source], loads: Sequence[BandLoad], reference_m: NDArray
) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """The derivatives of what inter-reflection adds to each band's load, as ``(force, torque)`` pairs of
    (n_materials, 7, 3) for :func:`planet_sensitivities`: the cells' beam chains (traced with their
    derivatives) and, with ``full``, the diffuse balance of the albedo in the solar optics and of the
    infrared in ``(1 - eps, 0, 0)`` (METHOD.md "Sensitivities").

    Parameters
    ----------
    craft : Spacecraft
        The model.
    mode : str
        The reflections, ``"specular"`` or ``"full"``.
    sources : sequence of Source
        The bands, albedo then infrared, with their exchanges.
    loads : sequence of BandLoad
        Their loads from :func:`~sunwind.forces.planet.loads.band_loads` with ``derivatives=True``.
    reference_m : (3,) array_like
        Torque reference point [m].

    Returns
    -------
    list of (force, torque)

    Examples
    --------
    >>> import sunwind as sw
    >>> white = sw.Material("white", 0.6, 0.5, emissivity=0.8)
    >>> model = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=white, threads=1)
    >>> place = sw.Place([0.0, 0.0, -1.0], 500.0, [0.6, 0.3, -0.2])
    >>> cap = sw.CapSampling(30.0, "cells")
    >>> d = sw.planet_radiation(model, place, reflections="full", cap=cap, sensitivities=True).sensitivities
    >>> d.force_N.shape, bool(abs(d.of("white.specular_fraction").force_N).max() > 0)
    ((1, 7, 3), True)
    """
    count, width = len(craft.materials), len(COEFFICIENTS)
    parts = []
    for source, load in zip(sources, loads, strict=True):
        force, torque = np.zeros((count, width, 3)), np.zeros((count, width, 3))
        traced = [c.derivatives for c in load.traced]
        for d in traced:
            force[:, : len(OPTICS)] += d.force_N + (d.open_sky_force_N if mode == "specular" else 0.0)
            torque[:, : len(OPTICS)] += d.torque_Nm + (d.open_sky_torque_Nm if mode == "specular" else 0.0)
        exchange = source.exchange
        if exchange is not None and source.name == "infrared":
            f, t = diffuse_emissivity_derivatives(craft, exchange, load.incident_side_W, reference_m)
            force[:, EMISSIVITY] += f
            torque[:, EMISSIVITY] += t
        elif exchange is not None:
            beams = sum((c.diffuse_source_W for c in load.traced), np.zeros(craft.n_sides))
            derivative = np.zeros((craft.n_sides, 3 * count))
            for d in traced:  # from the compact rows: a dense array per cell, kept by the cell, would add up
                derivative[d.sides] += d.source_rows
            f, t = diffuse_optics_derivatives(
                craft, exchange, load.incident_side_W, beams, derivative, reference_m
            )
            force[:, : len(OPTICS)] += f
            torque[:, : len(OPTICS)] += t
        parts.append((force, torque))
    return parts
