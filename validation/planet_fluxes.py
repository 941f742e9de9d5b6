"""Independent references for the pressure of a planet's albedo and infrared light (issue 21).

Reference answers the solver is tested against. The module imports numpy only and nothing of sunwind
(no ``forces``, no other reference). Body frame and SI (METHOD.md "Frames, units and signs"): ``nadir``
is the unit vector from the spacecraft to the planet's centre, ``sun`` the unit vector toward the Sun (at
infinity: the same from every point of the planet), ``n`` a plate's outward unit normal; planet radius
``R``, altitude ``H``, ``r = R + H``, ``sin(theta_0) = R / r``. Vectors are normalised on input.

**Closed forms** of a heat-flux dissertation (``/work/shared/reference/earth-fluxes.md``): :func:`phi_1`
(plate-to-sphere view factor, exact in all three ranges), :func:`f_2`, :func:`f_3`, :func:`f_2_star`,
:func:`f_3_star`, :func:`phi_2` (albedo factor, clamped at 0); for a plate :func:`infrared_factor_closed`
(irradiance ``M phi_1``) and :func:`albedo_factor_closed` (irradiance ``A S phi_2``). ``phi_2`` is exact
only while every visible point is sunlit (``gamma_s <= theta_0``) and the whole disc is in view
(``psi_n <= pi/2 - theta_0``), :func:`albedo_closed_is_exact`; elsewhere it approximates.

**Brute force over the planet's surface** (:func:`cap_nodes`, :func:`plate_moments`,
:func:`plate_irradiance`, :func:`plate_force`). The visible cap is parametrised by the planet-centred
polar angle ``lambda`` from the sub-spacecraft point, in ``[0, arccos(R / r)]``, and the azimuth ``phi``;
an element ``dA = R^2 sin(lambda) dlambda dphi`` at distance ``D``, emission angle ``eps``, subtends
``dOmega = cos(eps) dA / D^2`` in the direction ``omega`` (spacecraft to element). Radiance: albedo
``L = A S max(N . sun, 0) / pi`` (Lambertian, Bond albedo ``A``, ``N`` the element's outward normal),
infrared ``L = M / pi`` (``M = (1 - A) S / 4`` unless given). The kinks (the plate's horizon
``n . omega = 0``, the terminator ``N . sun = 0``) are found in closed form: ``phi`` is split at them on
every circle ``lambda``, ``lambda`` where either curve touches such a circle or the two cross; each piece
gets Gauss-Legendre, in ``lambda`` through ``3 t^2 - 2 t^3`` (smooths the square-root ends). Order 32 is
exact to about 1e-12 relative (the tests show the convergence). A plate's force per unit area applies
METHOD.md "Direct solar pressure", eq. (4), to every direction::

    dF = -(L dOmega / c) (n . omega)+ [ (1 - sigma - rho beta) omega
                                         + (2 rho beta (n . omega) + (2/3) rho (1 - beta)) n ]

**Spheres.** An absorbing sphere of radius ``a`` takes ``F = -(pi a^2 / c) int L omega dOmega``, away from
the planet. Closed forms: infrared ``pi a^2 M sin^2(theta_0) / c`` (:func:`sphere_force_infrared`),
albedo with the Sun at the sub-spacecraft zenith ``pi a^2 A S f_2(theta_0) / c``
(:func:`sphere_force_albedo_subsolar`), both along ``-nadir``; with the whole cap lit (``gamma_s <=
theta_0``) ``-(pi a^2 A S / c) [f_2 cos(gamma_s) nadir + f_3 sin(gamma_s) s_perp]``
(:func:`sphere_force_albedo_lit_cap`). Any Sun: :func:`sphere_force` by the cap quadrature. A convex
sphere of optics ``(rho, beta, sigma)`` takes ``1 - sigma + (4/9) rho (1 - beta)`` times the absorbing
force for every beam, hence for any source (:func:`sphere_optics_factor`; checked by
:func:`sphere_optics_factor_quadrature`, eq. (4) integrated over a sphere under one beam).

**Rays** (:func:`shadowed_plate_irradiance`): light on a plate shadowed by blocker triangles, averaged
over the plate. Points (centroids of a regular subdivision of the plate's triangles) are paired with the
elements of a low-order cap quadrature; a pair counts only if the segment between them misses every
blocker (own vectorised Moller-Trumbore, both sides block). About 1e-4 of the unshadowed irradiance at
the default resolution (the tests measure it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

SPEED_OF_LIGHT_M_S = 299_792_458.0
Array = NDArray[np.float64]


def _scalar(x: Array) -> Array | float:
    """A 0-d array as a Python float, anything else unchanged."""
    return float(x) if np.ndim(x) == 0 else x


def _unit(v: ArrayLike) -> Array:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def theta_0_of(radius_m: ArrayLike, altitude_m: ArrayLike) -> Array | float:
    """Angular radius of the planet seen from the spacecraft [rad]: ``arcsin(R / (R + H))``.

    Parameters
    ----------
    radius_m : float or array_like
        Planet radius ``R`` [m].
    altitude_m : float or array_like
        Altitude ``H`` [m].

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> round(float(np.degrees(theta_0_of(6_371e3, 400e3))), 2)
    70.21
    """
    r = np.asarray(radius_m, dtype=float)
    return _scalar(np.arcsin(r / (r + np.asarray(altitude_m, dtype=float))))


# ----------------------------------------------------------------------------------- closed forms
def phi_1(theta_0: ArrayLike, psi_n: ArrayLike) -> Array | float:
    """View factor ``phi_1`` [-] from a plate to a sphere (eqs. 1.21, 1.25), exact in every range.

    A uniform emitter of exitance ``M`` [W/m^2] gives the plate ``M phi_1``.

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).
    psi_n : float or array_like
        Angle between the plate's normal and nadir [rad], in [0, pi].
        Arrays broadcast.

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    Facing nadir the plate sees the whole disc, ``phi_1 = sin^2(theta_0)``; facing away, nothing:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> bool(np.isclose(phi_1(theta_0, 0.0), np.sin(theta_0) ** 2)), phi_1(theta_0, np.pi)
    (True, 0.0)
    """
    t, p = np.broadcast_arrays(np.asarray(theta_0, dtype=float), np.asarray(psi_n, dtype=float))
    st, ct, cp, sp = np.sin(t), np.cos(t), np.cos(p), np.sin(p)
    with np.errstate(divide="ignore", invalid="ignore"):
        a1 = np.arcsin(np.clip(ct / st * cp / sp, -1.0, 1.0))
        a2 = np.arcsin(np.clip(ct / sp, -1.0, 1.0))
        root = np.sqrt(np.clip(st**2 - cp**2, 0.0, None))
        partial = cp * st**2 / np.pi * (np.pi / 2 + a1) + 0.5 - a2 / np.pi - ct * root / np.pi
    full = cp * st**2
    return _scalar(np.where(p <= np.pi / 2 - t, full, np.where(p <= np.pi / 2 + t, partial, 0.0)))


def f_2(theta_0: ArrayLike) -> Array | float:
    """``f_2(theta_0)`` [-]: albedo factor of a nadir plate with the Sun at the sub-spacecraft zenith.

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> round(f_2(theta_0), 6)
    0.881754
    """
    s = np.sin(np.asarray(theta_0, dtype=float))
    c4 = (1.0 - s**2) ** 2
    return _scalar(0.25 * (1.0 + s**2 + 2.0 * s**3 - c4 / s * np.arctanh(s)))


def f_3(theta_0: ArrayLike) -> Array | float:
    """``f_3(theta_0)`` [-]: the albedo factor's term in ``sin(psi_n) sin(gamma_s) cos(delta_s)``.

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> round(f_3(theta_0), 6)
    0.047264
    """
    s = np.sin(np.asarray(theta_0, dtype=float))
    first = (1.0 - s**2) * (3.0 + s**2) / (8.0 * s) * np.arctanh(s)
    return _scalar(first - (1.0 - s) * (3.0 + 3.0 * s + 2.0 * s**2) / 8.0)


def f_2_star(theta_0: ArrayLike, psi_n: ArrayLike) -> Array | float:
    """``f_2* = f_2(theta_0) phi_1 / sin^2(theta_0)`` [-] (``f_2 cos(psi_n)`` in full view).

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).
    psi_n : float or array_like
        Angle between the plate's normal and nadir [rad], in [0, pi].

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> bool(np.isclose(f_2_star(theta_0, 0.0), f_2(theta_0)))
    True
    """
    t = np.asarray(theta_0, dtype=float)
    return _scalar(f_2(t) * np.asarray(phi_1(t, psi_n)) / np.sin(t) ** 2)


def f_3_star(theta_0: ArrayLike, psi_n: ArrayLike) -> Array | float:
    """``f_3*`` [-]: the albedo factor's ``f_3`` term reduced to the part of the disc in view.

    ``f_3`` in full view, ``f_3 (theta_0 + pi/2 - psi_n) / (2 theta_0)`` in partial view, 0 beyond.

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).
    psi_n : float or array_like
        Angle between the plate's normal and nadir [rad], in [0, pi].

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    Edge-on to nadir the plate sees half the disc, and half of ``f_3``:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> bool(np.isclose(f_3_star(theta_0, np.pi / 2), f_3(theta_0) / 2)), f_3_star(theta_0, np.pi)
    (True, 0.0)
    """
    t, p = np.broadcast_arrays(np.asarray(theta_0, dtype=float), np.asarray(psi_n, dtype=float))
    return _scalar(f_3(t) * np.clip((t + np.pi / 2 - p) / (2.0 * t), 0.0, 1.0))


def phi_2(theta_0: ArrayLike, psi_n: ArrayLike, gamma_s: ArrayLike, delta_s: ArrayLike) -> Array | float:
    """Albedo factor ``phi_2`` [-] (eqs. 1.14-1.20), clamped at 0: the plate's irradiance is ``A S phi_2``.

    Exact only where :func:`albedo_closed_is_exact`.

    Parameters
    ----------
    theta_0 : float or array_like
        Angular radius of the planet [rad], in (0, pi/2).
    psi_n : float or array_like
        Angle between the plate's normal and nadir [rad], in [0, pi].
    gamma_s : float or array_like
        Angle between ``-nadir`` and ``sun`` [rad].
    delta_s : float or array_like
        Angle between the planes (nadir, normal) and (nadir, Sun) [rad], 0 when the plate leans toward
        the sunlit side.

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> theta_0 = earth.theta_0
    >>> bool(np.isclose(phi_2(theta_0, 0.0, 0.0, 0.0), f_2(theta_0)))  # nadir plate, Sun at the zenith
    True
    """
    p, g, d = (np.asarray(x, dtype=float) for x in (psi_n, gamma_s, delta_s))
    value = f_2_star(theta_0, p) * np.cos(g) + f_3_star(theta_0, p) * np.sin(p) * np.sin(g) * np.cos(d)
    return _scalar(np.maximum(value, 0.0))


def _angles(nadir: ArrayLike, sun: ArrayLike, n: ArrayLike) -> tuple[Array, Array, Array]:
    """``psi_n``, ``gamma_s``, ``delta_s`` [rad] of unit vectors (broadcast over leading axes)."""
    d, s, m = _unit(nadir), _unit(sun), _unit(n)
    psi = np.arccos(np.clip(np.sum(m * d, axis=-1), -1.0, 1.0))
    gamma = np.arccos(np.clip(-np.sum(s * d, axis=-1), -1.0, 1.0))
    m_perp = m - np.sum(m * d, axis=-1, keepdims=True) * d
    s_perp = s - np.sum(s * d, axis=-1, keepdims=True) * d
    norms = np.linalg.norm(m_perp, axis=-1) * np.linalg.norm(s_perp, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_delta = np.where(norms > 1e-300, np.sum(m_perp * s_perp, axis=-1) / norms, 0.0)
    return psi, gamma, np.arccos(np.clip(cos_delta, -1.0, 1.0))


def albedo_factor_closed(nadir: ArrayLike, sun: ArrayLike, n: ArrayLike, theta_0: float) -> Array | float:
    """The dissertation's albedo factor ``phi_2`` [-] of a plate from its vectors.

    The plate's albedo irradiance is ``A S phi_2`` [W/m^2]; vectors are normalised here.

    Parameters
    ----------
    nadir : (3,) or (..., 3) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) or (..., 3) array_like
        Direction toward the Sun.
    n : (3,) or (..., 3) array_like
        The plate's outward normal.
    theta_0 : float
        Angular radius of the planet [rad].

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> round(albedo_factor_closed(down, zenith_sun, nadir_plate, earth.theta_0), 6)
    0.881754
    """
    return phi_2(theta_0, *_angles(nadir, sun, n))


def infrared_factor_closed(nadir: ArrayLike, n: ArrayLike, theta_0: float) -> Array | float:
    """The view factor ``phi_1`` [-] of a plate from its vectors (infrared irradiance ``M phi_1`` [W/m^2]).

    Parameters
    ----------
    nadir : (3,) or (..., 3) array_like
        Direction from the spacecraft to the planet's centre.
    n : (3,) or (..., 3) array_like
        The plate's outward normal.
    theta_0 : float
        Angular radius of the planet [rad].

    Returns
    -------
    float or ndarray
        A float for scalar arguments, else an array of their broadcast shape.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> round(infrared_factor_closed(down, nadir_plate, earth.theta_0), 6)
    0.885339
    """
    cos_psi = np.sum(_unit(n) * _unit(nadir), axis=-1)
    return phi_1(theta_0, np.arccos(np.clip(cos_psi, -1.0, 1.0)))


def albedo_closed_is_exact(nadir: ArrayLike, sun: ArrayLike, n: ArrayLike, theta_0: float) -> Array | bool:
    """Whether ``phi_2`` is exact: every visible point sunlit and the whole disc in view.

    That is ``gamma_s <= theta_0`` and ``psi_n <= pi/2 - theta_0``.

    Parameters
    ----------
    nadir : (3,) or (..., 3) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) or (..., 3) array_like
        Direction toward the Sun.
    n : (3,) or (..., 3) array_like
        The plate's outward normal.
    theta_0 : float
        Angular radius of the planet [rad].

    Returns
    -------
    bool or ndarray of bool
        A bool for single vectors, else an array.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> albedo_closed_is_exact(down, zenith_sun, nadir_plate, earth.theta_0)
    True
    >>> albedo_closed_is_exact(down, [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], earth.theta_0)  # Sun at the horizon
    False
    """
    psi, gamma, _ = _angles(nadir, sun, n)
    exact = (gamma <= theta_0) & (psi <= np.pi / 2 - theta_0)
    return bool(exact) if np.ndim(exact) == 0 else exact


# ------------------------------------------------------------------------ brute force over the cap
@dataclass(frozen=True)
class SphericalPlanet:
    """A spherical reference planet with a uniform Lambertian albedo, seen from a spacecraft at an altitude.

    Attributes
    ----------
    radius_m : float
        Planet radius ``R`` [m].
    altitude_m : float
        Spacecraft altitude ``H`` above the surface [m].
    solar_flux_W_m2 : float
        Solar flux ``S`` at the planet [W/m^2].
    albedo : float
        Bond albedo ``A`` [-], reflected Lambertian.
    exitance_W_m2 : float or None
        Infrared exitance ``M`` [W/m^2]; None: ``(1 - A) S / 4``.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> print(f"{np.degrees(earth.theta_0):.2f} deg, M = {earth.exitance:.1f} W/m^2")
    70.21 deg, M = 238.2 W/m^2
    """

    radius_m: float
    altitude_m: float
    solar_flux_W_m2: float = 1361.0
    albedo: float = 0.3
    exitance_W_m2: float | None = None

    @property
    def theta_0(self) -> float:
        """Angular radius of the planet [rad]."""
        return float(theta_0_of(self.radius_m, self.altitude_m))

    @property
    def exitance(self) -> float:
        """Infrared exitance ``M`` [W/m^2]."""
        if self.exitance_W_m2 is not None:
            return float(self.exitance_W_m2)
        return (1.0 - self.albedo) * self.solar_flux_W_m2 / 4.0


@dataclass(frozen=True)
class CapNodes:
    """Quadrature nodes over the visible cap.

    Attributes
    ----------
    omega : (m, 3) float64
        Directions from the spacecraft to the elements [-].
    domega : (m,) float64
        Solid angles [sr].
    normal : (m, 3) float64
        Outward normals of the elements [-].
    point_m : (m, 3) float64
        Positions of the elements relative to the spacecraft [m].

    Examples
    --------
    The solid angles add up to the cap's, ``2 pi (1 - cos(theta_0))``:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> nodes = cap_nodes(down, zenith_sun, nadir_plate, earth)
    >>> bool(np.isclose(nodes.domega.sum(), 2 * np.pi * (1 - np.cos(earth.theta_0))))
    True
    """

    omega: Array
    domega: Array
    normal: Array
    point_m: Array

    def radiance(self, sun: ArrayLike, planet: SphericalPlanet, source: str) -> Array:
        """Radiance ``L`` [W/m^2/sr] of every element for ``source`` 'albedo' or 'infrared'."""
        if source == "infrared":
            return np.full(len(self.domega), planet.exitance / np.pi)
        if source != "albedo":
            raise ValueError(f"source must be 'albedo' or 'infrared', not {source!r}")
        cos_sun = np.maximum(self.normal @ _unit(sun), 0.0)
        return planet.albedo * planet.solar_flux_W_m2 * cos_sun / np.pi


def _frame(nadir: Array) -> Array:
    """Rows e1, e2, e3 with e3 = -nadir (the zenith of the sub-spacecraft point)."""
    e3 = -nadir
    helper = np.array([1.0, 0.0, 0.0]) if abs(e3[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = _unit(np.cross(helper, e3))
    return np.array([e1, np.cross(e3, e1), e3])


def _tangencies(a: Array, c0: float, frame: Array) -> list[float]:
    """Polar angles where the curve ``a . N + c0 = 0`` touches a circle ``lambda = const``."""
    a1, a2, beta = frame @ a
    kappa = np.sqrt(a1**2 + a2**2 + beta**2)
    if kappa == 0.0 or abs(c0) > kappa:
        return []
    chi, acos = np.arctan2(np.hypot(a1, a2), beta), np.arccos(-c0 / kappa)
    return [sg * chi + sa * acos + 2 * np.pi * k for sg in (1, -1) for sa in (1, -1) for k in (-1, 0, 1)]


def _crossings(a: Array, c_a: float, b: Array, c_b: float, frame: Array) -> list[float]:
    """Polar angles where the curves ``a . N + c_a = 0`` and ``b . N + c_b = 0`` cross on the sphere."""
    gram = np.array([[a @ a, a @ b], [a @ b, b @ b]])
    if abs(np.linalg.det(gram)) < 1e-14 * gram[0, 0] * gram[1, 1]:
        return []
    x0 = np.linalg.solve(gram, [-c_a, -c_b]) @ np.array([a, b])
    rest = 1.0 - x0 @ x0
    if rest < 0.0:
        return []
    m = _unit(np.cross(a, b))
    return [float(np.arccos(np.clip((x0 + sg * np.sqrt(rest) * m) @ frame[2], -1, 1))) for sg in (1, -1)]


def _azimuth_roots(a: Array, c0: float, frame: Array, lam: Array) -> Array:
    """(m, 2) azimuths where ``a . N + c0 = 0`` on each circle ``lambda`` (NaN where none)."""
    a1, a2, beta = frame @ a
    rho = np.hypot(a1, a2)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = -(c0 + beta * np.cos(lam)) / (rho * np.sin(lam))
        half = np.where(np.abs(q) <= 1.0, np.arccos(np.clip(q, -1.0, 1.0)), np.nan)
    centre = np.arctan2(a2, a1)
    return np.stack([centre + half, centre - half], axis=-1)


def _gauss01(order: int) -> tuple[Array, Array]:
    x, w = np.polynomial.legendre.leggauss(order)
    return 0.5 * (x + 1.0), 0.5 * w


def cap_nodes(
    nadir: ArrayLike, sun: ArrayLike | None, n: ArrayLike | None, planet: SphericalPlanet, order: int = 32
) -> CapNodes:
    """Quadrature nodes over the part of the planet visible from the spacecraft (module notes).

    Only the planet's radius and altitude are used.

    Parameters
    ----------
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like or None
        Direction toward the Sun: adds the terminator as a kink to split at.
    n : (3,) array_like or None
        A plate's outward normal: adds its horizon ``n . omega = 0`` as a kink to split at.
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    order : int, optional
        Gauss-Legendre nodes per piece of ``lambda`` and per arc of ``phi``.

    Returns
    -------
    CapNodes
        Directions, solid angles, normals and positions of the elements.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> cap_nodes(down, None, None, earth, order=8).omega.shape
    (64, 3)
    """
    nadir = _unit(nadir)
    big_r, r = planet.radius_m, planet.radius_m + planet.altitude_m
    frame, lam_max = _frame(nadir), np.arccos(big_r / r)
    hinges = ([(_unit(n), r / big_r * float(_unit(n) @ nadir))] if n is not None else []) + (
        [(_unit(sun), 0.0)] if sun is not None else []
    )
    cuts = [c for a, c0 in hinges for c in _tangencies(a, c0, frame)]
    if len(hinges) == 2:
        cuts += _crossings(*hinges[0], *hinges[1], frame)
    breaks = np.unique([0.0, lam_max, *(c for c in cuts if 0.0 < c < lam_max)])
    breaks = breaks[np.concatenate([[True], np.diff(breaks) > 1e-13])]
    t, w = _gauss01(order)
    lo, width = breaks[:-1, None], np.diff(breaks)[:, None]
    lam = (lo + width * (3 * t**2 - 2 * t**3)).ravel()
    w_lam = (width * 6 * t * (1 - t) * w).ravel()
    roots = [_azimuth_roots(a, c0, frame, lam) for a, c0 in hinges]
    cuts_phi = np.mod(np.concatenate([np.zeros((len(lam), 1)), *roots], axis=1), 2 * np.pi)
    cuts_phi = np.sort(np.concatenate([np.nan_to_num(cuts_phi), np.full((len(lam), 1), 2 * np.pi)], 1))
    arc_lo, arc_width = cuts_phi[:, :-1, None], np.diff(cuts_phi, axis=1)[:, :, None]
    phi = arc_lo + arc_width * t  # (m, arcs, order)
    weight = w_lam[:, None, None] * arc_width * w
    lam3 = np.broadcast_to(lam[:, None, None], phi.shape)
    keep = weight.ravel() > 0.0
    lam3, phi, weight = lam3.ravel()[keep], phi.ravel()[keep], weight.ravel()[keep]
    local = np.stack([np.sin(lam3) * np.cos(phi), np.sin(lam3) * np.sin(phi), np.cos(lam3)], axis=-1)
    normal = local @ frame
    point = r * nadir + big_r * normal
    dist = np.linalg.norm(point, axis=-1)
    omega = point / dist[:, None]
    cos_eps = np.maximum((r * np.cos(lam3) - big_r) / dist, 0.0)
    domega = weight * big_r**2 * np.sin(lam3) * cos_eps / dist**2
    return CapNodes(omega, domega, normal, point)


@dataclass(frozen=True)
class PlateMoments:
    """The light reaching a plate, per unit area, as eq. (4) needs it for any optics.

    Attributes
    ----------
    normal : (3,) float64
        The plate's outward normal ``n``.
    irradiance_W_m2 : float
        ``E = int L (n . omega)+ dOmega`` [W/m^2].
    vector_W_m2 : (3,) float64
        ``V = int L (n . omega)+ omega dOmega`` [W/m^2].
    second_W_m2 : float
        ``W = int L (n . omega)+^2 dOmega`` [W/m^2].

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> moments = plate_moments(down, zenith_sun, nadir_plate, earth)
    >>> round(moments.irradiance_W_m2, 3)  # A S phi_2 = 0.3 * 1361 * 0.881754
    360.02
    """

    normal: Array
    irradiance_W_m2: float
    vector_W_m2: Array
    second_W_m2: float

    def force_N_m2(self, rho: float = 0.0, beta: float = 0.0, sigma: float = 0.0) -> Array:
        """Force per unit area [N/m^2] for reflectance ``rho``, specular share ``beta``, transmittance
        ``sigma``: ``-[(1 - sigma - rho beta) V + (2 rho beta W + (2/3) rho (1 - beta) E) n] / c``."""
        along_n = 2 * rho * beta * self.second_W_m2 + 2 / 3 * rho * (1 - beta) * self.irradiance_W_m2
        return -((1 - sigma - rho * beta) * self.vector_W_m2 + along_n * self.normal) / SPEED_OF_LIGHT_M_S


def _moments(nodes: CapNodes, radiance: Array, n: Array, seen: Array | float = 1.0) -> PlateMoments:
    """Moments from nodes; ``seen`` (m,) the share of the plate that sees each node."""
    c = np.maximum(nodes.omega @ n, 0.0)
    e = radiance * c * nodes.domega * seen
    return PlateMoments(n, float(e.sum()), e @ nodes.omega, float(e @ c))


def plate_moments(
    nadir: ArrayLike,
    sun: ArrayLike,
    n: ArrayLike,
    planet: SphericalPlanet,
    source: str = "albedo",
    order: int = 32,
) -> PlateMoments:
    """Brute-force :class:`PlateMoments` of the planet's light on an unshadowed plate (module notes).

    Parameters
    ----------
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun (ignored for infrared).
    n : (3,) array_like
        The plate's outward normal.
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    source : {"albedo", "infrared"}, optional
        Which light.
    order : int, optional
        Gauss-Legendre nodes per piece (32: about 1e-12 relative).

    Returns
    -------
    PlateMoments
        ``E``, ``V`` and ``W`` of the plate.

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> moments = plate_moments(down, zenith_sun, nadir_plate, earth, source="infrared")
    >>> bool(np.isclose(moments.irradiance_W_m2, earth.exitance * phi_1(earth.theta_0, 0.0)))
    True
    """
    n = _unit(n)
    nodes = cap_nodes(nadir, sun if source == "albedo" else None, n, planet, order)
    return _moments(nodes, nodes.radiance(sun, planet, source), n)


def plate_irradiance(
    nadir: ArrayLike,
    sun: ArrayLike,
    n: ArrayLike,
    planet: SphericalPlanet,
    source: str = "albedo",
    order: int = 32,
) -> float:
    """Irradiance ``E = int L (n . omega)+ dOmega`` [W/m^2] of a plate by the planet's albedo or infrared.

    Parameters
    ----------
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun (ignored for infrared).
    n : (3,) array_like
        The plate's outward normal.
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    source : {"albedo", "infrared"}, optional
        Which light.
    order : int, optional
        Gauss-Legendre nodes per piece (32: about 1e-12 relative).

    Returns
    -------
    float
        ``E`` [W/m^2].

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> round(plate_irradiance(down, zenith_sun, nadir_plate, earth, source="infrared"), 4)
    210.8656
    """
    return plate_moments(nadir, sun, n, planet, source, order).irradiance_W_m2


def plate_force(
    nadir: ArrayLike,
    sun: ArrayLike,
    n: ArrayLike,
    planet: SphericalPlanet,
    optics: tuple[float, float, float] = (0.0, 0.0, 0.0),
    source: str = "albedo",
    order: int = 32,
) -> Array:
    """Force per unit area [N/m^2] on a plate by eq. (4) applied to every direction.

    Parameters
    ----------
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun (ignored for infrared).
    n : (3,) array_like
        The plate's outward normal.
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    optics : (float, float, float), optional
        ``(rho, beta, sigma)``: reflectance, specular share and transmittance [-].
    source : {"albedo", "infrared"}, optional
        Which light.
    order : int, optional
        Gauss-Legendre nodes per piece (32: about 1e-12 relative).

    Returns
    -------
    (3,) float64
        Force per unit area [N/m^2].

    Examples
    --------
    An absorbing plate facing the planet is pushed away from it [nN/m^2]:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> force = plate_force(down, zenith_sun, nadir_plate, earth, source="infrared")
    >>> (force * 1e9).round(3).tolist()
    [0.0, 0.0, 509.08]
    """
    return plate_moments(nadir, sun, n, planet, source, order).force_N_m2(*optics)


# --------------------------------------------------------------------------------------- spheres
def sphere_force_infrared(a: float, R: float, H: float, M: float) -> float:
    """Magnitude [N] of the infrared force on an absorbing sphere: ``pi a^2 M sin^2(theta_0) / c``.

    Directed along ``-nadir`` (away from the planet).

    Parameters
    ----------
    a : float
        Sphere radius [m].
    R : float
        Planet radius [m].
    H : float
        Altitude [m].
    M : float
        Infrared exitance [W/m^2].

    Returns
    -------
    float
        ``|F|`` [N].

    Examples
    --------
    >>> round(sphere_force_infrared(1.0, 6_371e3, 400e3, 238.2) * 1e6, 4)
    2.2099
    """
    return float(np.pi * a**2 * M * (R / (R + H)) ** 2 / SPEED_OF_LIGHT_M_S)


def sphere_force_albedo_subsolar(a: float, R: float, H: float, A: float, S: float) -> float:
    """Magnitude [N] of the albedo force on an absorbing sphere, Sun at the sub-spacecraft zenith.

    ``sun = -nadir``: ``pi a^2 A S f_2(theta_0) / c``, along ``-nadir``.

    Parameters
    ----------
    a : float
        Sphere radius [m].
    R : float
        Planet radius [m].
    H : float
        Altitude [m].
    A : float
        Bond albedo [-].
    S : float
        Solar flux [W/m^2].

    Returns
    -------
    float
        ``|F|`` [N].

    Examples
    --------
    >>> round(sphere_force_albedo_subsolar(1.0, 6_371e3, 400e3, 0.3, 1361.0) * 1e6, 4)
    3.7727
    """
    return float(np.pi * a**2 * A * S * f_2(theta_0_of(R, H)) / SPEED_OF_LIGHT_M_S)


def sphere_force_albedo_lit_cap(a: float, nadir: ArrayLike, sun: ArrayLike, planet: SphericalPlanet) -> Array:
    """Albedo force [N] on an absorbing sphere, exact while the whole visible cap is lit.

    ``-(pi a^2 A S / c) [f_2 cos(gamma_s) nadir + f_3 sin(gamma_s) s_perp]`` for ``gamma_s <= theta_0``,
    ``s_perp`` the unit part of ``sun`` across ``nadir``.

    Parameters
    ----------
    a : float
        Sphere radius [m].
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun.
    planet : SphericalPlanet
        The planet, its albedo and solar flux, and the spacecraft's altitude.

    Returns
    -------
    (3,) float64
        Force [N].

    Examples
    --------
    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> ((sphere_force_albedo_lit_cap(1.0, down, zenith_sun, earth) * 1e6).round(4) + 0.0).tolist()
    [0.0, 0.0, 3.7727]
    """
    d, s = _unit(nadir), _unit(sun)
    flux = f_2(planet.theta_0) * -(s @ d) * d + f_3(planet.theta_0) * (s - (s @ d) * d)
    return -np.pi * a**2 * planet.albedo * planet.solar_flux_W_m2 * flux / SPEED_OF_LIGHT_M_S


def sphere_optics_factor(rho: float = 0.0, beta: float = 0.0, sigma: float = 0.0) -> float:
    """Force on a convex sphere of optics ``(rho, beta, sigma)`` over that on an absorbing one [-].

    For any beam: ``1 - sigma + (4/9) rho (1 - beta)`` (specular light adds nothing, diffuse 4/9).

    Parameters
    ----------
    rho : float, optional
        Reflectance [-].
    beta : float, optional
        Specular share of the reflected light [-].
    sigma : float, optional
        Transmittance [-].

    Returns
    -------
    float
        The factor [-].

    Examples
    --------
    >>> sphere_optics_factor(1.0, 1.0), round(sphere_optics_factor(1.0, 0.0), 6)
    (1.0, 1.444444)
    """
    return 1.0 - sigma + 4.0 / 9.0 * rho * (1.0 - beta)


def sphere_optics_factor_quadrature(rho: float, beta: float, sigma: float, order: int = 24) -> float:
    """:func:`sphere_optics_factor` by Gauss-Legendre quadrature of eq. (4) over a sphere under one beam.

    The lit hemisphere of a unit sphere under a beam along ``-z`` (Sun at +z), over ``pi`` [-].

    Parameters
    ----------
    rho : float
        Reflectance [-].
    beta : float
        Specular share of the reflected light [-].
    sigma : float
        Transmittance [-].
    order : int, optional
        Gauss-Legendre nodes per dimension.

    Returns
    -------
    float
        The factor [-].

    Examples
    --------
    >>> bool(np.isclose(sphere_optics_factor_quadrature(1.0, 0.0, 0.0), 13 / 9))
    True
    """
    t, w = _gauss01(order)
    mu = t  # cos of the incidence angle; azimuth integrates to 2 pi (components off z cancel)
    along_z = -(1 - sigma - rho * beta) * mu - (2 * rho * beta * mu + 2 / 3 * rho * (1 - beta)) * mu * mu
    return float(-2 * np.pi * np.sum(w * along_z) / np.pi)


def sphere_force(
    a: float,
    nadir: ArrayLike,
    sun: ArrayLike,
    planet: SphericalPlanet,
    optics: tuple[float, float, float] = (0.0, 0.0, 0.0),
    source: str = "albedo",
    order: int = 32,
) -> Array:
    """Force [N] on a convex sphere by the planet's albedo or infrared, by the cap quadrature (any Sun).

    ``-(pi a^2 / c) sphere_optics_factor(*optics) int L omega dOmega``.

    Parameters
    ----------
    a : float
        Sphere radius [m].
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun (ignored for infrared).
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    optics : (float, float, float), optional
        ``(rho, beta, sigma)`` [-].
    source : {"albedo", "infrared"}, optional
        Which light.
    order : int, optional
        Gauss-Legendre nodes per piece (32: about 1e-12 relative).

    Returns
    -------
    (3,) float64
        Force [N].

    Examples
    --------
    With the whole cap lit it agrees with :func:`sphere_force_albedo_lit_cap`:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> force = sphere_force(1.0, down, zenith_sun, earth)
    >>> bool(np.allclose(force, sphere_force_albedo_lit_cap(1.0, down, zenith_sun, earth), rtol=1e-9))
    True
    """
    nodes = cap_nodes(nadir, sun if source == "albedo" else None, None, planet, order)
    flux = (nodes.radiance(sun, planet, source) * nodes.domega) @ nodes.omega
    return -np.pi * a**2 * sphere_optics_factor(*optics) * flux / SPEED_OF_LIGHT_M_S


# ------------------------------------------------------------------------------------------ rays
def plate_points(plate: ArrayLike, grid: int) -> tuple[Array, Array]:
    """Compute the centroids and area shares of a regular subdivision of a plate.

    The plate (a triangle or a planar convex quad) is split into ``grid^2`` equal triangles per
    triangle of its fan.

    Parameters
    ----------
    plate : (3, 3) or (4, 3) array_like
        Corners [m].
    grid : int
        Subdivisions per side of each triangle.

    Returns
    -------
    points : (p, 3) float64
        Centroids [m].
    shares : (p,) float64
        Area shares [-], summing to 1.

    Examples
    --------
    >>> points, shares = plate_points([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], 2)
    >>> points.shape, shares.tolist()
    ((4, 3), [0.25, 0.25, 0.25, 0.25])
    """
    corners = np.asarray(plate, dtype=float)
    ij = np.stack(np.meshgrid(np.arange(grid), np.arange(grid), indexing="ij"), -1).reshape(-1, 2)
    total = ij.sum(axis=1)
    uv = np.concatenate([ij[total <= grid - 1] + 1 / 3, ij[total <= grid - 2] + 2 / 3]) / grid
    points, areas = [], []
    for k in range(1, len(corners) - 1):
        v0, e1, e2 = corners[0], corners[k] - corners[0], corners[k + 1] - corners[0]
        points.append(v0 + uv[:, :1] * e1 + uv[:, 1:] * e2)
        areas.append(np.full(len(uv), 0.5 * np.linalg.norm(np.cross(e1, e2)) / grid**2))
    share = np.concatenate(areas)
    return np.concatenate(points), share / share.sum()


def _blocked(origins: Array, targets: Array, triangles: Array) -> Array:
    """(p, m) whether the segment from each origin (p, 3) to each target (m, 3) hits a triangle
    (k, 3, 3), either side (Moller-Trumbore); hits within 1e-9 m of the origin do not count."""
    d = targets[None, :, :] - origins[:, None, :]  # (p, m, 3), not normalised: t in [0, 1]
    length = np.linalg.norm(d, axis=-1)
    hit = np.zeros(d.shape[:2], dtype=bool)
    for v0, v1, v2 in triangles:
        e1, e2 = v1 - v0, v2 - v0
        pvec = np.cross(d, e2)
        det = pvec @ e1
        ok = np.abs(det) > 1e-300
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        tvec = origins - v0
        u = np.einsum("pmi,pi->pm", pvec, tvec) * inv
        qvec = np.cross(tvec, e1)
        v = np.einsum("pmi,pi->pm", d, qvec) * inv
        t = (qvec @ e2)[:, None] * inv
        hit |= ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t * length > 1e-9) & (t < 1)
    return hit


def shadowed_plate_irradiance(
    blockers: ArrayLike,
    plate: ArrayLike,
    n: ArrayLike,
    nadir: ArrayLike,
    sun: ArrayLike,
    planet: SphericalPlanet,
    source: str = "albedo",
    resolution: tuple[int, int] = (32, 16),
) -> PlateMoments:
    """Ray brute force: the planet's light on a plate shadowed by blockers, averaged over the plate.

    Parameters
    ----------
    blockers : (k, 3, 3) array_like
        Blocker triangles [m] (k may be 0), both sides block; the planet's centre is at ``(R + H) nadir``.
    plate : (3, 3) or (4, 3) array_like
        Corners of the receiving triangle or planar convex quad [m].
    n : (3,) array_like
        The plate's outward normal.
    nadir : (3,) array_like
        Direction from the spacecraft to the planet's centre.
    sun : (3,) array_like
        Direction toward the Sun (ignored for infrared).
    planet : SphericalPlanet
        The planet and the spacecraft's altitude.
    source : {"albedo", "infrared"}, optional
        Which light.
    resolution : (int, int)
        Subdivisions per side of each triangle of the plate, and the cap quadrature's order. The default
        reaches about 1e-4 of the unshadowed irradiance.

    Returns
    -------
    PlateMoments
        Means over the plate: ``irradiance_W_m2`` [W/m^2], ``force_N_m2(rho, beta, sigma)`` [N/m^2]. A
        pair (point, element) counts only if the segment between them misses every blocker; the weights
        use the directions from the origin (the parallax, plate size over distance, is below 1e-5).

    Examples
    --------
    A unit square facing the planet, unshadowed, then under a large triangle between it and the planet:

    >>> earth = SphericalPlanet(6_371e3, 400e3)
    >>> down, zenith_sun, nadir_plate = [0.0, 0.0, -1.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    >>> square = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [-0.5, 0.5, 0.0]]
    >>> free = shadowed_plate_irradiance(
    ...     np.zeros((0, 3, 3)), square, nadir_plate, down, zenith_sun, earth, "infrared", (2, 16)
    ... )
    >>> round(free.irradiance_W_m2, 2)
    210.87
    >>> roof = [[[-10.0, -10.0, -1.0], [10.0, -10.0, -1.0], [0.0, 10.0, -1.0]]]
    >>> shadowed_plate_irradiance(
    ...     roof, square, nadir_plate, down, zenith_sun, earth, "infrared", (2, 16)
    ... ).irradiance_W_m2
    0.0
    """
    n = _unit(n)
    nodes = cap_nodes(nadir, sun if source == "albedo" else None, n, planet, resolution[1])
    facing = nodes.omega @ n > 0.0
    nodes = CapNodes(*(x[facing] for x in (nodes.omega, nodes.domega, nodes.normal, nodes.point_m)))
    points, share = plate_points(plate, resolution[0])
    triangles = np.asarray(blockers, dtype=float).reshape(-1, 3, 3)
    seen = np.zeros(len(nodes.domega))
    chunk = max(1, 400_000 // max(len(nodes.domega), 1))
    for start in range(0, len(points), chunk):
        part = slice(start, start + chunk)
        free = ~_blocked(points[part], nodes.point_m, triangles)
        seen += share[part] @ free
    return _moments(nodes, nodes.radiance(sun, planet, source), n, seen)
