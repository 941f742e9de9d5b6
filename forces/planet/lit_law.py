"""Eq. (4), the law of light on a lit flat area, as the planet's bands use it: a parallel beam on each
side, the open force of a side's integrals over an extended source, the same per unit share of each way
light leaves (the derivatives' basis), and the error a shadow pass leaves in a cell's load (METHOD.md
"Planet radiation")."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.radiation.sensitivity import share_forces
from sunwind.geometry.rays.certificate import LoadsError, ShadowCheck
from sunwind.geometry.spacecraft import Spacecraft


def cell_error(
    craft: Spacecraft,
    optics: NDArray[np.float64],
    cell: tuple[NDArray[np.float64], float],
    check: ShadowCheck,
    reference_m: NDArray[np.float64],
) -> LoadsError:
    """The error a cell's shadow pass leaves in a source's force and torque.

    What the pass's ``check`` found, with the force of the cell on one unit of each side's lit area as
    the load (:meth:`~sunwind.geometry.rays.certificate.ShadowCheck.loads_error`); linear in the cell's
    irradiance.

    Parameters
    ----------
    craft : Spacecraft
        The model the pass ran on.
    optics : (n_sides, 3) float64
        ``(rho, beta, sigma)`` of every side in the band.
    cell : tuple of ((3,) float64, float)
        The cell's unit direction and irradiance [W/m^2].
    check : ShadowCheck
        The pass's check.
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    LoadsError
        Absolute error estimates [N, N m].

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=grey, threads=1).craft
    >>> u = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])
    >>> light = side_sampler(craft).illuminate(u)
    >>> error = cell_error(craft, craft.side_optics, (u, 1361.0), light.check, np.zeros(3))
    >>> error.force_N >= 0.0, error.torque_Nm >= 0.0
    (True, True)
    """
    direction, weight = cell
    needed = check.needed  # the only rows the check reads
    normals = craft.side_normals[needed]
    cos = np.maximum(normals @ direction, 0.0)
    load = np.zeros((craft.n_sides, 3))
    load[needed] = law(normals, np.ones(len(needed)), optics[needed], weight * cos, direction, cos)
    return check.loads_error(craft, load, reference_m)


def law(
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    optics: NDArray[np.float64],
    i0: NDArray[np.float64],
    direction: NDArray[np.float64],
    cos: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Eq. (4) for a parallel beam of irradiance ``i0 / cos`` on each side (``i0`` on its plane) [N].

    Parameters
    ----------
    normals : (m, 3) float64
        Unit outward normals.
    areas : (m,) float64
        Areas [m^2].
    optics : (m, 3) float64
        ``(rho, beta, sigma)`` of each.
    i0 : (m,) float64
        Irradiance on each side's plane [W/m^2].
    direction : (3,) float64
        Unit direction toward the source.
    cos : (m,) float64
        ``normals @ direction``.

    Returns
    -------
    (m, 3) float64
        Force on each side [N].

    Examples
    --------
    A black plate facing the Sun at 1361 W/m^2 is pushed away with the pressure 1361 / c:

    >>> import numpy as np
    >>> up = np.array([0.0, 0.0, 1.0])
    >>> force = law(up[None, :], np.ones(1), np.zeros((1, 3)), np.array([1361.0]), up, np.ones(1))
    >>> (force * 1e6).round(4) + 0.0
    array([[ 0.    ,  0.    , -4.5398]])
    """
    return open_force(normals, areas, optics, i0, i0[:, None] * direction, i0 * cos)


def open_force(
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    optics: NDArray[np.float64],
    i0: NDArray[np.float64],
    i1: NDArray[np.float64],
    i2: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Eq. (4) over an extended source, from a side's integrals:
    ``F = -(A / c) [(1 - sigma - rho_s) I_1 + (2 rho_s I_2 + (2/3) rho_d I_0) n]`` per side [N].

    Parameters
    ----------
    normals : (m, 3) float64
        Unit outward normals.
    areas : (m,) float64
        Areas [m^2].
    optics : (m, 3) float64
        ``(rho, beta, sigma)`` of each.
    i0, i1, i2 : (m,), (m, 3), (m,) float64
        ``I_0, I_1, I_2`` of each side [W/m^2] (:meth:`~sunwind.forces.planet.cap.Cap.side_integrals`).

    Returns
    -------
    (m, 3) float64
        Force on each side [N].

    Examples
    --------
    A white diffuse plate facing a beam of 1361 W/m^2 along its normal: ``(1 + 2/3) 1361 / c``.

    >>> import numpy as np
    >>> up = np.array([[0.0, 0.0, 1.0]])
    >>> white = np.array([[1.0, 0.0, 0.0]])
    >>> i0 = np.array([1361.0])
    >>> (open_force(up, np.ones(1), white, i0, i0[:, None] * up, i0) * 1e6).round(4) + 0.0
    array([[ 0.    ,  0.    , -7.5663]])
    """
    rho, beta, sigma = optics.T
    rho_s, rho_d = rho * beta, rho * (1 - beta)
    along = (1.0 - sigma - rho_s)[:, None] * i1
    normal = 2.0 * rho_s * i2 + LAMBERT_FACTOR * rho_d * i0
    return -(areas / SPEED_OF_LIGHT)[:, None] * (along + normal[:, None] * normals)


def lit_share_torques(
    normals: NDArray[np.float64],
    areas: NDArray[np.float64],
    direction: NDArray[np.float64],
    lit: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> NDArray[np.float64]:
    """The torque of moving each side's lit force, per unit share, from its centroid to its lit centroid,
    for a parallel beam of unit irradiance along ``direction`` (the couple a shadow pass adds).

    Parameters
    ----------
    normals : (m, 3) float64
        Unit outward normals of sides facing ``direction``.
    areas : (m,) float64
        Areas [m^2].
    direction : (3,) float64
        Unit direction toward the source.
    lit : tuple of ((m,) float64, (m, 3) float64)
        Each side's lit share and its lit centroid's offset from its centroid [m].

    Returns
    -------
    (m, 4, 3) float64
        ``[side, share, component]`` [N m per unit share per W/m^2]; summed with the shares it is the
        torque of :func:`law`'s lit force at the offsets.

    Examples
    --------
    >>> import numpy as np
    >>> up = np.array([[0.0, 0.0, 1.0]])
    >>> torques = lit_share_torques(up, np.ones(1), up[0], (np.array([0.5]), np.array([[0.1, 0.0, 0.0]])))
    >>> optics = np.array([[0.4, 0.25, 0.1]])
    >>> force = law(up, np.ones(1), optics, np.array([0.5]), up[0], np.ones(1))
    >>> shares = np.array([0.5, 0.1, 0.3, 0.1])
    >>> bool(np.allclose(shares @ torques[0], np.cross([0.1, 0.0, 0.0], force[0])))
    True
    """
    share, offset = lit
    cos = normals @ direction
    i0 = cos * share
    forces = share_forces(normals, areas, i0, i0[:, None] * direction, i0 * cos)
    return np.cross(offset[:, None, :], forces)
