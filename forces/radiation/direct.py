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
    """The direct light's power [W]: what meets the spacecraft, what it absorbs at once, and the sums
    over the reflection plan's channels (:class:`~sunwind.forces.reflection.plan.ReflectionPlan`)."""

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
    """

    illumination: Illumination
    force: NDArray[np.float64]
    torque: NDArray[np.float64]
    lit_area_m2: float
    projected_area_m2: float
    absorbed_area_m2: float
    channels_m2: NDArray[np.float64]

    def power(self, flux_W_m2: float) -> DirectPower:
        """The powers [W] under ``flux_W_m2``."""
        return DirectPower(
            flux_W_m2 * self.projected_area_m2,
            flux_W_m2 * self.absorbed_area_m2,
            flux_W_m2 * self.channels_m2,
        )


@dataclass(frozen=True, eq=False)
class ChannelWeights:
    """Per-side weights ``w`` (n_sides, k) the direct pass sums times each side's direct power per
    unit flux, and their block moments (n_blocks, 3 k)
    (:func:`~sunwind.forces.radiation.moments.weight_moments`)."""

    side: NDArray[np.float64]
    block: NDArray[np.float64]

    @property
    def channels(self) -> int:
        return self.side.shape[1]


def model_block_moments(craft: Spacecraft) -> NDArray[np.float64]:
    """:func:`~sunwind.forces.radiation.moments.block_moments` of ``craft``'s sides in its sampler's
    blocks, made once and kept in its cache."""

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
    """Cast the shadow rays toward ``u_sun`` (sampled as ``samples`` and ``tolerance`` say: see
    :meth:`~sunwind.geometry.rays.shadows.SideSampler.illuminate`) and sum eq. (4) with torques about
    ``reference_m`` [m], and the ``weights`` (none: a kernel compiled without them)."""
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
    """Force of eq. (4) on one unit of lit area of every side [N/m^2], (n_sides, 3): what an error in a
    side's lit area costs (:meth:`~sunwind.geometry.rays.certificate.ShadowCheck.loads_error`); zero on
    the sides facing away from ``u_sun``, and on all but ``sides`` when they are given (the check's
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
    """
    rows = np.arange(craft.n_sides) if sides is None else sides
    normals = craft.side_normals[rows]
    cos_theta = np.maximum(normals @ u_sun, 0.0)
    rho, beta, sigma = craft.side_optics[rows].T
    loads = np.zeros((craft.n_sides, 3))
    unit = np.ones(len(rows))
    loads[rows] = surface_forces(normals, unit, cos_theta, rho, beta, sigma, u_sun, pressure_Pa)
    return loads
