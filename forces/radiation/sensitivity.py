"""Derivatives of the direct solar force and torque, eq. (4) on every lit side, with respect to each
material's optics (METHOD.md "Sensitivities").

Eq. (4) on side ``i`` is linear in its shares: with ``P A f c`` the momentum rate it intercepts,

    dF/d sigma = P A f c u,   dF/d rho_s = -P A f c (2 c n - u),   dF/d rho_d = -(2/3) P A f c n,

and ``rho_s = rho beta``, ``rho_d = rho (1 - beta)`` give the partials in ``(rho, beta, sigma)``
(:func:`~sunwind.forces.sensitivity.optics_partials`). Each side's torque acts at its lit centroid, as
the direct pass's does; the sums run per material.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR
from sunwind.forces.sensitivity import optics_partials
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft


def per_material(
    material: NDArray[np.integer], values: NDArray[np.float64], count: int
) -> NDArray[np.float64]:
    """Sum rows of ``values`` by material.

    Parameters
    ----------
    material : (n,) int
        Material index of each row.
    values : (n, ...) float64
        Values of each row.
    count : int
        Number of materials.

    Returns
    -------
    (count, ...) float64

    Examples
    --------
    >>> per_material(np.array([1, 0, 1]), np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]), 2)
    array([[3., 4.],
           [6., 8.]])
    """
    flat = values.reshape(len(values), -1)
    out = np.zeros((count, flat.shape[1]))
    for column in range(flat.shape[1]):
        out[:, column] = np.bincount(material, weights=flat[:, column], minlength=count)
    return out.reshape((count, *values.shape[1:]))


def direct_optics_derivatives(
    craft: Spacecraft, light: Illumination, pressure_Pa: float, reference_m: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """d force and d torque of the direct light with respect to every material's ``(rho, beta, sigma)``.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    light : Illumination
        Lit shares and lit centroids of the attitude (the plate model: every facing side wholly lit at
        its centroid).
    pressure_Pa : float
        Radiation pressure ``P`` [Pa].
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    force, torque : (n_materials, 3, 3) float64
        ``[material, coefficient, component]`` [N, N m per unit coefficient].

    Examples
    --------
    A black plate facing the Sun: a reflectivity of 1, all diffuse, would add two thirds of the push.

    >>> import sunwind as sw
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box((1.0, 1.0, 1.0)), uniform=black, threads=1).craft
    >>> light = side_sampler(craft).illuminate(np.array([1.0, 0.0, 0.0]))
    >>> force, torque = direct_optics_derivatives(craft, light, 1.0, np.zeros(3))
    >>> force[0, 0].round(6) + 0.0  # d F / d rho with beta = 0: -(2/3) n P A
    array([-0.666667,  0.      ,  0.      ])
    """
    sides, share = light.facing, light.facing_share
    u = light.direction
    normals = craft.side_normals[sides]
    cos = normals @ u
    rate = pressure_Pa * craft.side_areas[sides] * share * cos  # P A f c [N]
    # per-share force directions, [side, share, component]: absorbed, specular, diffuse, transmitted
    per_share = np.zeros((len(sides), 4, 3))
    per_share[:, 0] = -rate[:, None] * u
    per_share[:, 1] = -rate[:, None] * (2.0 * cos[:, None] * normals)
    per_share[:, 2] = -rate[:, None] * (u + LAMBERT_FACTOR * normals)
    rho, beta, _ = craft.side_optics[sides].T
    partials = optics_partials(rho, beta)  # [side, coefficient, share]
    force = np.einsum("ikq,iqc->ikc", partials, per_share)
    arm = light.lit_centroid[sides] - reference_m
    torque = np.cross(arm[:, None, :], force)
    material = craft.side_material[sides]
    count = len(craft.materials)
    return per_material(material, force, count), per_material(material, torque, count)
