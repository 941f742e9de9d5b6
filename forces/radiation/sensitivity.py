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

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
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


#: The shares of a side's light, in the order of :func:`share_forces` (and of
#: :func:`~sunwind.forces.sensitivity.optics_partials`).
SHARES = ("absorbed", "specular", "diffuse", "transmitted")


def share_forces(
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    i0: NDArray[np.float64],
    i1: NDArray[np.float64],
    i2: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Find eq. (4) over an extended source (:func:`~sunwind.forces.planet.lit_law.open_force`) per unit
    share: the force on each side were all its light absorbed, mirrored, diffused or transmitted [N].

    The law is linear in the shares ``(alpha, rho_s, rho_d, sigma)`` (:data:`SHARES`; ``1 - sigma - rho_s =
    alpha + rho_d``), so the law is the sum of these times the shares, and its derivative with
    respect to any coefficient the sum times the shares' partials
    (:func:`~sunwind.forces.sensitivity.optics_partials`):

    ``-(A / c) [I_1,  2 I_2 n,  I_1 + (2/3) I_0 n,  0]``.

    Parameters
    ----------
    normals : (m, 3) float64
        Unit outward normals.
    areas : (m,) float64
        Areas [m^2].
    i0, i1, i2 : (m,), (m, 3), (m,) float64
        ``I_0, I_1, I_2`` of each side [W/m^2].

    Returns
    -------
    (m, 4, 3) float64
        ``[side, share, component]`` [N per unit share].

    Examples
    --------
    The shares of a grey plate weight the four forces into eq. (4)'s (:func:`surface_forces`):

    >>> from sunwind.forces.radiation.law import surface_forces
    >>> up = np.array([[0.0, 0.0, 1.0]])
    >>> i0 = np.array([1361.0])
    >>> basis = share_forces(up, np.ones(1), i0, i0[:, None] * up, i0)
    >>> rho, beta, sigma = 0.4, 0.25, 0.1
    >>> shares = np.array([1 - rho - sigma, rho * beta, rho * (1 - beta), sigma])
    >>> optics = [np.array([v]) for v in (rho, beta, sigma)]
    >>> law = surface_forces(up, np.ones(1), np.ones(1), *optics, up[0], 1361 / 299792458)
    >>> bool(np.allclose(shares @ basis[0], law, rtol=1e-14, atol=0))
    True
    """
    scale = -(areas / SPEED_OF_LIGHT)[:, None]
    out = np.zeros((len(areas), len(SHARES), 3))
    out[:, 0] = scale * i1
    out[:, 1] = scale * (2.0 * i2)[:, None] * normals
    out[:, 2] = scale * (i1 + LAMBERT_FACTOR * i0[:, None] * normals)
    return out


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
    irradiance = pressure_Pa * SPEED_OF_LIGHT * cos  # on each side's plane [W/m^2]
    lit_area = craft.side_areas[sides] * share
    per_share = share_forces(normals, lit_area, irradiance, irradiance[:, None] * u, irradiance * cos)
    rho, beta, _ = craft.side_optics[sides].T
    partials = optics_partials(rho, beta)  # [side, coefficient, share]
    force = np.einsum("ikq,iqc->ikc", partials, per_share)
    arm = light.lit_centroid[sides] - reference_m
    torque = np.cross(arm[:, None, :], force)
    material = craft.side_material[sides]
    count = len(craft.materials)
    return per_material(material, force, count), per_material(material, torque, count)
