"""The direct pass of one attitude: shadow rays toward the Sun and the sums of eq. (4) over the lit
sides, with what the direct light hands to inter-reflection (METHOD.md "Direct solar pressure").

The shadow pass (:meth:`sunwind.geometry.rays.shadows.SideSampler.illuminate`) calls the sum kernel
(:func:`~sunwind.forces.radiation.moments.accumulate_forces`) on whole blocks of sides as their lit
shares become final, from its worker threads; each block's sums land in its own row, and the rows are
added in block order, so the totals have the same bits whatever the threads did.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import surface_forces
from sunwind.forces.radiation.moments import (
    ABSORBED,
    FORCE,
    LIT_AREA,
    PROJECTED,
    TORQUE,
    TOTALS,
    accumulate_forces,
    block_moments,
)
from sunwind.geometry.rays.shadows import Illumination, side_sampler
from sunwind.geometry.spacecraft import Spacecraft


@dataclass(frozen=True)
class DirectPower:
    """Power of the direct light [W]: what meets the spacecraft, what it absorbs at once, and the channels.

    The channels are the sums over the reflection plan's channels
    (:class:`~sunwind.forces.reflection.plan.ReflectionPlan`).

    Parameters
    ----------
    incident_W : float
        Power meeting the lit sides [W].
    absorbed_W : float
        Power they absorb at once [W].
    channels_W : (k,) float64
        The plan's per-side weights summed over the direct power [W].

    Examples
    --------
    >>> import numpy as np
    >>> DirectPower(1361.0, 1361.0, np.zeros(0)).absorbed_W
    1361.0
    """

    incident_W: float
    absorbed_W: float
    channels_W: NDArray[np.float64]  # (k,)


@dataclass(frozen=True, eq=False)
class DirectTotals:
    """The direct pass of one attitude, summed with ``P = 1`` (multiply forces by the pressure).

    Attributes
    ----------
    illumination : Illumination
        Lit share and lit centroid of every side.
    force, torque : (3,) float64
        Force [N/Pa] and torque about the reference point [N m/Pa] of eq. (4).
    lit_area_m2, projected_area_m2 : float
        Lit area, and lit area projected normal to the Sun.
    absorbed_area_m2 : float
        Projected area weighted by absorptivity: absorbed power over flux.
    channels_m2 : (k,) float64
        The plan's per-side weights summed over the lit projected area: power per unit flux.

    Examples
    --------
    A black unit cube lit along ``(0, 0.6, 0.8)`` shows 1.4 m^2 to the Sun:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> u_sun = np.array([0.0, 0.6, 0.8])
    >>> totals = direct_pass(craft, u_sun, np.zeros(3), None, 0.0)
    >>> totals.force.round(6) + 0.0, totals.lit_area_m2, round(totals.projected_area_m2, 6)
    (array([ 0.  , -0.84, -1.12]), 2.0, 1.4)
    """

    illumination: Illumination
    force: NDArray[np.float64]
    torque: NDArray[np.float64]
    lit_area_m2: float
    projected_area_m2: float
    absorbed_area_m2: float
    channels_m2: NDArray[np.float64]

    def power(self, flux_W_m2: float) -> DirectPower:
        """The powers [W] under ``flux_W_m2``.

        Parameters
        ----------
        flux_W_m2 : float
            Solar flux at the spacecraft [W/m^2].

        Returns
        -------
        DirectPower
            Incident, absorbed and per-channel power [W].

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
        >>> u_sun = np.array([0.0, 0.6, 0.8])
        >>> round(direct_pass(craft, u_sun, np.zeros(3), None, 0.0).power(1000.0).incident_W, 6)
        1400.0
        """
        return DirectPower(
            flux_W_m2 * self.projected_area_m2,
            flux_W_m2 * self.absorbed_area_m2,
            flux_W_m2 * self.channels_m2,
        )


@dataclass(frozen=True, eq=False)
class ChannelWeights:
    """Per-side weights the direct pass sums times each side's direct power per unit flux, and their moments.

    Parameters
    ----------
    side : (n_sides, k) float64
        The weights ``w`` of each side.
    block : (n_blocks, 3 k) float64
        Their block moments (:func:`~sunwind.forces.radiation.moments.weight_moments`).

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> u_sun = np.array([0.0, 0.6, 0.8])
    >>> from sunwind.forces.radiation.moments import weight_moments
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> sampler = side_sampler(craft)
    >>> side = np.ones((craft.n_sides, 1))
    >>> weights = ChannelWeights(side, weight_moments(side, craft.side_normals, craft.side_areas,
    ...     sampler.side_block, sampler.n_blocks))
    >>> totals = direct_pass(craft, u_sun, np.zeros(3), None, 0.0, weights)
    >>> weights.channels, round(float(totals.channels_m2[0]), 6)
    (1, 1.4)
    """

    side: NDArray[np.float64]
    block: NDArray[np.float64]

    @property
    def channels(self) -> int:
        """Number of channels ``k``.

        Returns
        -------
        int
            Columns of :attr:`side`.
        """
        return self.side.shape[1]


def model_block_moments(craft: Spacecraft) -> NDArray[np.float64]:
    """Block moments of ``craft``'s sides in its sampler's blocks, made once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    (n_blocks, MOMENT_SLOTS) ndarray of float64
        :func:`~sunwind.forces.radiation.moments.block_moments` of the blocks of
        :func:`~sunwind.geometry.rays.shadows.side_sampler`.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> u_sun = np.array([0.0, 0.6, 0.8])
    >>> moments = model_block_moments(craft)
    >>> moments.shape[1], model_block_moments(craft) is moments
    (95, True)
    """

    def build() -> NDArray[np.float64]:
        sampler = side_sampler(craft)
        return block_moments(
            craft.side_normals,
            craft.side_areas,
            craft.side_optics,
            craft.side_centroids,
            sampler.side_block,
            sampler.n_blocks,
        )

    return craft.cache.get("block moments", build)


def direct_pass(
    craft: Spacecraft,
    u_sun: NDArray[np.float64],
    reference_m: NDArray[np.float64],
    samples: int | None,
    tolerance: float,
    weights: ChannelWeights | None = None,
) -> DirectTotals:
    """Cast the shadow rays toward the Sun and sum eq. (4) over the lit sides, with the channel weights.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    u_sun : (3,) float64
        Unit vector toward the Sun, body frame.
    reference_m : (3,) float64
        Torque reference point [m].
    samples : int or None
        Shadow samples per side, or None for the adaptive default (see
        :meth:`~sunwind.geometry.rays.shadows.SideSampler.illuminate`).
    tolerance : float
        Tolerance of the adaptive sampling (as for
        :meth:`~sunwind.geometry.rays.shadows.SideSampler.illuminate`).
    weights : ChannelWeights, optional
        Per-side weights to sum times the direct power; None for a kernel compiled without them.

    Returns
    -------
    DirectTotals
        The shadow pass, and force, torque, areas and channel sums with ``P = 1``.

    References
    ----------
    Shmatov and Mordvinkin (2013), eq. (4).

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> u_sun = np.array([0.0, 0.6, 0.8])
    >>> totals = direct_pass(craft, u_sun, np.zeros(3), None, 0.0)
    >>> round(totals.absorbed_area_m2, 6), totals.channels_m2
    (1.4, array([], dtype=float64))
    """
    sampler = side_sampler(craft)
    low, high = sampler.block_normal_bounds
    sides = (craft.side_centroids, craft.side_normals, craft.side_areas, craft.side_optics)
    blocks = (sampler.side_block, low, high, model_block_moments(craft))
    channel = (None, None) if weights is None else (weights.side, weights.block)
    partials = np.zeros((sampler.n_blocks, TOTALS + (0 if weights is None else weights.channels)))

    def force_sum(facing: NDArray[np.int64], share: NDArray, centroid: NDArray) -> None:
        accumulate_forces(facing, share, centroid, *sides, u_sun, reference_m, *blocks, *channel, partials)

    light = sampler.illuminate(u_sun, samples, tolerance, reduce=force_sum)
    totals = partials.sum(axis=0)  # block sums added in block order
    return DirectTotals(
        illumination=light,
        force=totals[FORCE : FORCE + 3],
        torque=totals[TORQUE : TORQUE + 3],
        lit_area_m2=float(totals[LIT_AREA]),
        projected_area_m2=float(totals[PROJECTED]),
        absorbed_area_m2=float(totals[ABSORBED]),
        channels_m2=totals[TOTALS:],
    )


def lit_area_loads(
    craft: Spacecraft,
    u_sun: NDArray[np.float64],
    pressure_Pa: float,
    sides: NDArray[np.int64] | None = None,
) -> NDArray[np.float64]:
    """Force of eq. (4) on one unit of lit area of every side [N/m^2].

    It is what an error in a side's lit area costs
    (:meth:`~sunwind.geometry.rays.certificate.ShadowCheck.loads_error`); zero on the sides facing away
    from ``u_sun``, and on all but ``sides`` when they are given (the check's
    :attr:`~sunwind.geometry.rays.certificate.ShadowCheck.needed`, a few of a large model's).

    Examples
    --------
    A black side facing the Sun is pushed away from it by ``P cos(theta)`` per unit lit area:

    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> plate = MeshData(np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]]),
    ...                  np.zeros(1, np.int32), ("plate",), -np.ones(1, np.int32))
    >>> craft = build_spacecraft(plate, uniform=Material("black", 0.0, 0.0, 0.0), two_sided=["*"])
    >>> lit_area_loads(craft, np.array([0.0, 0.6, 0.8]), 2.0)
    array([[-0.  , -0.96, -1.28],
           [ 0.  ,  0.  ,  0.  ]])

    Parameters
    ----------
    craft : Spacecraft
        The model.
    u_sun : (3,) float64
        Unit vector toward the Sun, body frame.
    pressure_Pa : float
        Solar radiation pressure ``P`` [Pa].
    sides : (m,) int64, optional
        The sides to compute; None for all.

    Returns
    -------
    (n_sides, 3) ndarray of float64
        Force per unit lit area of each side [N/m^2].
    """
    rows = np.arange(craft.n_sides) if sides is None else sides
    normals = craft.side_normals[rows]
    cos_theta = np.maximum(normals @ u_sun, 0.0)
    rho, beta, sigma = craft.side_optics[rows].T
    loads = np.zeros((craft.n_sides, 3))
    unit = np.ones(len(rows))
    loads[rows] = surface_forces(normals, unit, cos_theta, rho, beta, sigma, u_sun, pressure_Pa)
    return loads
