"""The planet's visible cap seen from the spacecraft, its radiance, and the integrals of that radiance
over each side's share of the cap (METHOD.md "Planet radiation").

Directions ``w`` from the spacecraft toward the planet lie in a cone about the nadir ``e`` of
half-angle ``theta_0``, ``sin(theta_0) = R / r`` (``r`` the distance from the planet's centre). The
ray along ``w`` at angle ``theta`` from ``e`` meets the surface at distance
``d = r cos(theta) - sqrt(R^2 - r^2 sin^2(theta))``, where the outward normal is
``N = (d w - r e) / R``. A surface element there has the radiance

    L = (c_u + c_s max(N . s, 0)) (q_0 + q_1 x + q_2 (3 x^2 - 1) / 2) / pi,   x = N . p

(``s`` the unit vector to the Sun, ``p`` the planet's north pole): ``c_u`` a uniform exitance, ``c_s``
one that follows the insolation (albedo ``A S``, or the Moon's re-emission), and a latitude factor
(Knocke's model; ``q = (1, 0, 0)`` for a uniform planet). The side with outward normal ``n`` receives

    I_0 = int L (n . w)+ dw,   I_1 = int L (n . w)+ w dw,   I_2 = int L (n . w)+^2 dw

over the cap ([W/m^2]), which is all the force law needs. The cap is integrated exactly in its
pieces: on each ring ``theta`` the side's horizon ``n . w = 0`` and the terminator ``N . s = 0`` cut
the azimuth circle at points found in closed form (each is ``cos(phi - phi_0) = t``); the azimuth is
integrated by Gauss-Legendre between cuts, and ``theta`` between the values where a cut appears or
vanishes, under the map ``theta = a + (b - a) sin^2(pi v / 2)``, which makes the square-root onset of
an arc smooth. The integrand is smooth inside every piece, so the rule converges spectrally.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass
from functools import cached_property

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import map_ranges

#: Gauss-Legendre points per ``theta`` piece and per azimuth arc of :meth:`Cap.side_integrals`.
THETA_POINTS = 12
AZIMUTH_POINTS = 12
#: Sides per parallel block of the side integrals.
_BLOCK_SIDES = 2048
#: Rings and points per ring of :meth:`Cap.quadrature` (the rings split among the ``theta`` pieces).
QUADRATURE_RINGS = 48
QUADRATURE_AZIMUTHS = 96
#: Most cells a cap is cut into (about 2 pi (1 - cos theta0) / step^2): a finer step is refused.
MOST_CELLS = 20_000


def check_cells(half_angle: float, cell_deg: float) -> None:
    """Refuse a cell size that would cut the cap into more than ``MOST_CELLS`` cells.

    The count is estimated before any cell is made, as the cap's solid angle
    ``2 pi (1 - cos theta_0)`` over the square of the step.

    Parameters
    ----------
    half_angle : float
        The cap's half-angle ``theta_0`` [rad] (:attr:`Cap.half_angle`).
    cell_deg : float
        The cell size asked for [deg].

    Raises
    ------
    InputError
        Too fine a cell size (or one that is not a positive number), named as ``cell_deg``; the hint gives the
        finest step accepted.

    Examples
    --------
    >>> import math
    >>> check_cells(math.radians(68.0), 10.0)  # the default step from 500 km: accepted
    >>> check_cells(math.radians(68.0), 0.1)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: cell_deg 0.1 cuts the planet's disc (68.0 deg half-angle) into ...
    """
    theta0 = half_angle
    solid = 2 * math.pi * (1 - math.cos(theta0))
    cells = solid / math.radians(cell_deg) ** 2 if cell_deg > 0 else math.inf  # about
    if not cells <= MOST_CELLS:
        least = math.degrees(math.sqrt(solid / MOST_CELLS))
        raise InputError(
            f"cell_deg {cell_deg:g} cuts the planet's disc ({math.degrees(theta0):.1f} deg half-angle) "
            f"into about {cells:.3g} cells, more than {MOST_CELLS}: each is a batch of rays per side",
            hint=f"give a step of at least {least:.2g} deg (10 by default; 2 resolves the terminator)",
            parameters=("cell_deg",),
        )


@dataclass(frozen=True)
class Radiance:
    """The radiance law of one extended source on a planet's surface.

    A surface point of outward unit normal ``N`` sends

        L = (uniform + insolation max(N . s, 0)) (q_0 + q_1 x + q_2 P_2(x)) / pi   [W/(m^2 sr)],

    with ``s`` the unit vector to the Sun, ``x = N . pole`` the sine of the geocentric latitude,
    ``P_2(x) = (3 x^2 - 1) / 2`` and ``(q_0, q_1, q_2)`` = ``latitude``. The ``insolation`` term is
    Lambertian reflection (albedo times solar flux) or re-emission that follows the Sun; the latitude
    factor is Knocke's zonal expansion, ``(1, 0, 0)`` for a uniform planet.

    Parameters
    ----------
    uniform_W_m2 : float
        Exitance sent everywhere, day and night [W/m^2].
    insolation_W_m2 : float
        Exitance under an overhead Sun, scaled by the cosine of the Sun's zenith angle and zero on
        the night side [W/m^2].
    latitude : tuple of 3 float
        ``(q_0, q_1, q_2)``, the Legendre coefficients of the latitude factor [-].

    References
    ----------
    .. [1] Knocke, P. C., Ries, J. C., Tapley, B. D. (1988). "Earth radiation pressure effects on
       satellites." AIAA/AAS Astrodynamics Conference, AIAA 88-4292.

    Examples
    --------
    >>> albedo = Radiance(insolation_W_m2=0.3 * 1361.0)
    >>> round(albedo.insolation_W_m2, 1), albedo.dark
    (408.3, False)
    >>> Radiance().dark
    True
    """

    uniform_W_m2: float = 0.0
    insolation_W_m2: float = 0.0
    latitude: tuple[float, float, float] = (1.0, 0.0, 0.0)

    @property
    def dark(self) -> bool:
        """Whether the source sends nothing at all."""
        return self.uniform_W_m2 == 0.0 and self.insolation_W_m2 == 0.0


@dataclass(frozen=True, eq=False)
class Cap:
    """The visible cap of a spherical planet seen from the spacecraft, with its radiance.

    Directions toward the planet fill a cone about the nadir of half-angle ``theta_0``,
    ``sin(theta_0) = R / r``. :meth:`side_integrals` gives each side's exact integrals ``I_0, I_1,
    I_2`` of the radiance over its share of the cap (see the module's docstring), and :meth:`patches`
    cuts the cap into cells for the shadow passes. All vectors are in the body frame.

    Parameters
    ----------
    nadir : (3,) float64
        Unit vector from the spacecraft to the planet's centre.
    sun : (3,) float64
        Unit vector from the spacecraft (and the planet) to the Sun.
    pole : (3,) float64
        Unit vector along the planet's north pole (used by a latitude-dependent :class:`Radiance`).
    distance_m : float
        Distance of the spacecraft from the planet's centre [m]; above ``radius_m``.
    radius_m : float
        Radius of the planet [m].
    radiance : Radiance
        The radiance law of the source on the surface.

    Examples
    --------
    A uniform emitter of 240 W/m^2 seen from 500 km: a plate facing the nadir receives
    ``M sin^2(theta_0)``, and one facing away receives nothing.

    >>> import math
    >>> import numpy as np
    >>> earth_m = 6_378_137.0
    >>> cap = Cap(
    ...     nadir=np.array([0.0, 0.0, -1.0]), sun=np.array([0.0, 0.0, 1.0]), pole=np.array([1.0, 0.0, 0.0]),
    ...     distance_m=earth_m + 500e3, radius_m=earth_m, radiance=Radiance(uniform_W_m2=240.0),
    ... )
    >>> round(math.degrees(cap.half_angle), 2)
    68.02
    >>> i0, i1, i2 = cap.side_integrals(np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]))
    >>> np.round(i0, 3), round(240.0 * math.sin(cap.half_angle) ** 2, 3)
    (array([206.375,   0.   ]), 206.375)
    """

    nadir: NDArray[np.float64]
    sun: NDArray[np.float64]
    pole: NDArray[np.float64]
    distance_m: float
    radius_m: float
    radiance: Radiance

    @cached_property
    def half_angle(self) -> float:
        """The cap's half-angle ``theta_0 = asin(R / r)`` [rad].

        Examples
        --------
        >>> import math
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=1.0))
        >>> round(math.degrees(cap.half_angle), 6)
        30.0
        """
        return math.asin(self.radius_m / self.distance_m)

    @cached_property
    def frame(self) -> NDArray[np.float64]:
        """The cap's frame, rows ``e, e_1, e_2`` (3, 3).

        ``e`` is the nadir and ``e_1``, ``e_2`` two unit vectors across it, ``e_1`` toward the Sun where
        the Sun is off the nadir line (else across the nadir's smallest component).

        Examples
        --------
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([1.0, 0.0, 1.0]) / np.sqrt(2.0),
        ...           np.array([0.0, 1.0, 0.0]), 2.0, 1.0, Radiance(uniform_W_m2=1.0))
        >>> cap.frame[1]
        array([1., 0., 0.])
        """
        e = self.nadir
        across = self.sun - (self.sun @ e) * e
        if np.linalg.norm(across) < 1e-9:
            across = np.eye(3)[np.argmin(np.abs(e))]
            across = across - (across @ e) * e
        e1 = across / np.linalg.norm(across)
        return np.array([e, e1, np.cross(e, e1)])

    def directions(self, theta: NDArray, phi: NDArray) -> NDArray[np.float64]:
        """Unit vectors at polar angle ``theta`` from the nadir and azimuth ``phi`` about it.

        Parameters
        ----------
        theta, phi : ndarray of float64
            Angles [rad], of one shape; ``phi`` is measured from ``e_1`` of :attr:`frame` toward ``e_2``.

        Returns
        -------
        ndarray of float64, shape (..., 3)
            The unit vectors in the body frame.

        Examples
        --------
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=1.0))
        >>> np.round(cap.directions(np.array([0.0, np.pi / 2]), np.array([0.0, 0.0])), 12) + 0.0
        array([[ 0.,  0., -1.],
               [ 1.,  0.,  0.]])
        """
        e, e1, e2 = self.frame
        st = np.sin(theta)[..., None]
        return np.cos(theta)[..., None] * e + st * (np.cos(phi)[..., None] * e1 + np.sin(phi)[..., None] * e2)

    def radiance_along(self, w: NDArray[np.float64]) -> NDArray[np.float64]:
        """Radiance of the planet's surface seen along unit vectors inside the cap.

        Parameters
        ----------
        w : ndarray of float64, shape (..., 3)
            Unit vectors from the spacecraft, each within :attr:`half_angle` of the nadir.

        Returns
        -------
        ndarray of float64, shape (...)
            The :class:`Radiance` law at the point each ray meets the surface [W/(m^2 sr)].

        Examples
        --------
        A Lambertian emitter of exitance ``M`` has radiance ``M / pi`` everywhere:

        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=np.pi))
        >>> cap.radiance_along(np.array([[0.0, 0.0, -1.0], [0.3, 0.0, -np.sqrt(0.91)]]))
        array([1., 1.])
        """
        r, big_r, e = self.distance_m, self.radius_m, self.nadir
        cos_t = np.clip(w @ e, -1.0, 1.0)
        d = r * cos_t - np.sqrt(np.maximum(big_r**2 - r**2 * (1.0 - cos_t**2), 0.0))
        normal = (d[..., None] * w - r * e) / big_r
        return _radiance(normal, self.sun, self.pole, self.radiance)

    @cached_property
    def theta_breaks(self) -> NDArray[np.float64]:
        """The polar angles where the integrand of :meth:`side_integrals` changes form (k,) [rad].

        ``0``, each ``theta`` at which the terminator starts or stops cutting a ring, and ``theta_0``,
        sorted. A ring at central angle ``beta`` from the sub-spacecraft point is lit where
        ``cos(phi - phi_s) > t = e_s cot(beta) / s_perp`` (``e_s``, ``s_perp``: the Sun along and across
        the nadir); ``t`` is monotone in ``beta``, so each of ``t = -1`` and ``t = +1`` is crossed once at
        most, at ``tan(beta) = e_s / (t s_perp)``, seen from the spacecraft at
        ``theta = atan2(R sin(beta), r - R cos(beta))``. A source without an ``insolation`` term has only
        ``0`` and ``theta_0``.

        Examples
        --------
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=1.0))
        >>> np.degrees(cap.theta_breaks).round(6)
        array([ 0., 30.])

        The Sun on the horizon of the sub-spacecraft point: the terminator crosses every ring from the
        first, and stops cutting none before the cap's edge.

        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
        ...           2.0, 1.0, Radiance(insolation_W_m2=1.0))
        >>> np.degrees(cap.theta_breaks).round(6)
        array([ 0., 30.])
        """
        breaks = [0.0, self.half_angle]
        e_s = float(self.sun @ self.nadir)
        s_perp = float(np.linalg.norm(self.sun - e_s * self.nadir))
        if self.radiance.insolation_W_m2 != 0.0 and s_perp > 1e-12:
            r, big_r = self.distance_m, self.radius_m
            beta_edge = math.acos(big_r / r)
            for level in (-1.0, 1.0):
                beta = math.atan2(e_s, level * s_perp) % math.pi  # the root in [0, pi)
                if 0.0 < beta < beta_edge:
                    breaks.append(math.atan2(big_r * math.sin(beta), r - big_r * math.cos(beta)))
        return np.unique(np.clip(breaks, 0.0, self.half_angle))

    def side_integrals(
        self, normals: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """The integrals ``I_0, I_1, I_2`` of the cap's radiance over each side's unshadowed share of it.

        ``I_0 = int L (n . w)+ dw``, ``I_1 = int L (n . w)+ w dw`` and ``I_2 = int L (n . w)+^2 dw``
        over the cap, by Gauss-Legendre on the pieces cut by the side's horizon and the terminator, so the
        rule converges spectrally. Sides with the same normal are integrated once; the blocks of sides run
        in parallel.

        Parameters
        ----------
        normals : ndarray of float64, shape (n, 3)
            Unit outward normals of the sides, body frame.

        Returns
        -------
        i0 : ndarray of float64, shape (n,)
            Irradiance on each side's plane [W/m^2].
        i1 : ndarray of float64, shape (n, 3)
            Its first moment over the directions of arrival [W/m^2].
        i2 : ndarray of float64, shape (n,)
            Its moment weighted once more by the cosine to the normal [W/m^2].

        Examples
        --------
        The Sun on the horizon: half the cap is lit, and a plate facing the nadir takes its albedo.

        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
        ...           6_878_137.0, 6_378_137.0, Radiance(insolation_W_m2=0.3 * 1361.0))
        >>> i0, i1, i2 = cap.side_integrals(np.array([[0.0, 0.0, -1.0]]))
        >>> np.round(i0, 3), np.round(i1, 3) + 0.0, np.round(i2, 3)
        (array([9.653]), array([[ 5.702,  0.   , -5.945]]), array([5.945]))
        """
        unique, inverse = np.unique(normals, axis=0, return_inverse=True)
        inverse = inverse.reshape(-1)
        out = np.zeros((len(unique), 5))
        if len(unique) and not self.radiance.dark:
            v, wv = _mapped_rule(THETA_POINTS)
            u, wu = _legendre(AZIMUTH_POINTS)
            rad = self.radiance
            coefficients = np.array([rad.uniform_W_m2, rad.insolation_W_m2, *rad.latitude])
            geometry = np.array([self.distance_m, self.radius_m])
            unique = np.ascontiguousarray(unique)
            n_blocks = -(-len(unique) // _BLOCK_SIDES)

            def run(lo: int, hi: int) -> None:
                _integrate(
                    unique, lo * _BLOCK_SIDES, min(hi * _BLOCK_SIDES, len(unique)), self.frame, self.sun,
                    self.pole, geometry, coefficients, self.theta_breaks, v, wv, u, wu, out,
                )  # fmt: skip

            map_ranges(run, n_blocks, 1)
        values = out[inverse]
        return values[:, 0], values[:, 1:4], values[:, 4]

    def quadrature(
        self, rings: int = QUADRATURE_RINGS, azimuths: int = QUADRATURE_AZIMUTHS
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """A product rule over the cap: directions and the solid angle each stands for.

        ``theta`` by Gauss-Legendre in each piece between :attr:`theta_breaks` (under the map that smooths
        the square-root onset of an arc; ``rings`` shared among the pieces by their width, at least 4
        each), the azimuth by the periodic trapezoid rule on ``azimuths`` points.

        Parameters
        ----------
        rings : int
            Points in ``theta``, about.
        azimuths : int
            Points in azimuth per ring.

        Returns
        -------
        directions : (p, 3) float64
            Unit directions, body frame.
        solid_sr : (p,) float64
            Solid angle of each point [sr]; ``sum(radiance_along(directions) * solid_sr)`` is ``int L dw``.

        Examples
        --------
        The solid angles add up to the cap's, ``2 pi (1 - cos theta_0)``:

        >>> import math
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=np.pi))
        >>> directions, solid = cap.quadrature()
        >>> bool(abs(solid.sum() - 2 * math.pi * (1 - math.cos(math.pi / 6))) < 1e-12)
        True
        """
        breaks = self.theta_breaks
        span = breaks[-1] - breaks[0]
        thetas, widths = [], []
        for lo, hi in itertools.pairwise(breaks):
            count = max(4, round(rings * (hi - lo) / span)) if span > 0 else 4
            x, dx = _mapped_rule(count)
            thetas.append(lo + (hi - lo) * x)
            widths.append((hi - lo) * dx)
        theta, d_theta = np.concatenate(thetas), np.concatenate(widths)
        phi = 2 * math.pi * np.arange(azimuths) / azimuths
        grid_theta, grid_phi = np.meshgrid(theta, phi, indexing="ij")
        directions = self.directions(grid_theta, grid_phi).reshape(-1, 3)
        solid = (d_theta * np.sin(theta))[:, None] * np.full(azimuths, 2 * math.pi / azimuths)
        return directions, solid.reshape(-1)

    def patches(self, cell_deg: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The cap cut into cells about ``cell_deg`` across, for the shadow passes.

        Rings of equal ``theta`` width are cut into sectors of about the same width; each cell's
        direction is its mean by solid angle (so caps of one geometry share their cells), and its weight
        is ``int L dw`` over it, the irradiance it sends on a surface normal to that direction.

        Parameters
        ----------
        cell_deg : float
            Cell size [deg].

        Returns
        -------
        directions : ndarray of float64, shape (k, 3)
            Unit mean direction of each cell, body frame.
        weights : ndarray of float64, shape (k,)
            Irradiance each cell sends [W/m^2].

        Raises
        ------
        InputError
            A step that would make more than ``MOST_CELLS`` cells (:func:`check_cells`).

        Examples
        --------
        >>> cap = Cap(np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]),
        ...           2.0, 1.0, Radiance(uniform_W_m2=np.pi))
        >>> directions, weights = cap.patches(20.0)  # a centre cell and a ring of seven
        >>> directions.shape, round(float(weights.sum()), 6)  # int L dw = 2 pi (1 - cos 30 deg)
        ((8, 3), 0.841787)
        """
        theta0 = self.half_angle
        check_cells(theta0, cell_deg)
        rings = max(1, math.ceil(math.degrees(theta0) / cell_deg))
        edges = np.linspace(0.0, theta0, rings + 1)
        v, wv = _legendre(8)
        directions, weights = [], []
        for lo, hi in itertools.pairwise(edges):
            middle = 0.5 * (lo + hi)
            sectors = max(1, round(2 * math.pi * math.sin(middle) / math.radians(cell_deg))) if lo > 0 else 1
            theta = lo + (hi - lo) * (v + 1) / 2
            for k in range(sectors):
                phi = 2 * math.pi * (k + (v + 1) / 2) / sectors
                w = self.directions(*np.meshgrid(theta, phi, indexing="ij"))
                solid = np.outer(wv * (hi - lo) / 2 * np.sin(theta), wv * math.pi / sectors)
                mean = np.einsum("ij,ijk->k", solid, w)
                directions.append(mean / np.linalg.norm(mean))
                weights.append(float((self.radiance_along(w) * solid).sum()))
        return np.array(directions), np.array(weights)


def _radiance(
    normal: NDArray[np.float64], sun: NDArray[np.float64], pole: NDArray[np.float64], radiance: Radiance
) -> NDArray[np.float64]:
    """:class:`Radiance` at surface points of outward unit ``normal`` (..., 3)."""
    x = normal @ pole
    q0, q1, q2 = radiance.latitude
    factor = q0 + q1 * x + q2 * (1.5 * x * x - 0.5)
    lit = np.maximum(normal @ sun, 0.0)
    return (radiance.uniform_W_m2 + radiance.insolation_W_m2 * lit) * factor / math.pi


@functools.lru_cache(maxsize=64)
def _legendre(points: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Gauss-Legendre nodes and weights on [-1, 1], made once per size (read-only)."""
    rule = np.polynomial.legendre.leggauss(points)
    for array in rule:
        array.flags.writeable = False
    return rule


@functools.lru_cache(maxsize=64)
def _mapped_rule(points: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Gauss-Legendre on [0, 1] under ``x = sin^2(pi v / 2)``: nodes ``x`` and weights ``dx``, made once
    per size (read-only)."""
    v, w = _legendre(points)
    v = (v + 1) / 2
    rule = np.sin(np.pi * v / 2) ** 2, w / 2 * (np.pi / 2) * np.sin(np.pi * v)
    for array in rule:
        array.flags.writeable = False
    return rule


@numba.njit(cache=True, nogil=True)
def _integrate(normals, first, last, frame, sun, pole, geometry, coefficients, breaks, v, wv, u, wu, out):
    """Rows ``first`` to ``last - 1`` of ``out``: ``I_0, I_1 (3), I_2`` of each normal (see :class:`Cap`)."""
    r, big_r = geometry[0], geometry[1]
    c_u, c_s, q0, q1, q2 = coefficients[0], coefficients[1], coefficients[2], coefficients[3], coefficients[4]
    e = frame[0]
    e1 = frame[1]
    e2 = frame[2]
    e_s = sun[0] * e[0] + sun[1] * e[1] + sun[2] * e[2]
    s1 = sun[0] * e1[0] + sun[1] * e1[1] + sun[2] * e1[2]
    s2 = sun[0] * e2[0] + sun[1] * e2[1] + sun[2] * e2[2]
    s_perp = math.sqrt(s1 * s1 + s2 * s2)
    phi_s = math.atan2(s2, s1)
    theta0 = breaks[-1]
    pieces = np.empty(len(breaks) + 1)
    cuts = np.empty(4)
    for i in range(first, last):
        n = normals[i]
        a = n[0] * e[0] + n[1] * e[1] + n[2] * e[2]
        b1 = n[0] * e1[0] + n[1] * e1[1] + n[2] * e1[2]
        b2 = n[0] * e2[0] + n[1] * e2[1] + n[2] * e2[2]
        b = math.sqrt(b1 * b1 + b2 * b2)
        phi_n = math.atan2(b2, b1)
        # the horizon cuts rings beyond theta_h; inside it the side sees all (a > 0) or none of each ring
        theta_h = math.atan2(abs(a), b)
        count = 0
        for k in range(len(breaks)):
            pieces[count] = breaks[k]
            count += 1
        if 0.0 < theta_h < theta0:
            pieces[count] = theta_h
            count += 1
        pieces[:count] = np.sort(pieces[:count])
        total = np.zeros(5)
        for p in range(count - 1):
            lo, hi = pieces[p], pieces[p + 1]
            if hi <= lo or (a <= 0.0 and hi <= theta_h):
                continue
            for j in range(len(v)):
                theta = lo + (hi - lo) * v[j]
                weight_t = (hi - lo) * wv[j] * math.sin(theta)
                ct, st = math.cos(theta), math.sin(theta)
                if theta <= theta_h:
                    centre, half = 0.0, math.pi
                else:
                    t = -a * ct / (b * st)
                    centre, half = phi_n, math.acos(min(1.0, max(-1.0, t)))
                if half <= 0.0:
                    continue
                d = r * ct - math.sqrt(max(big_r * big_r - r * r * st * st, 0.0))
                start, stop = centre - half, centre + half
                n_cuts = 0
                if c_s != 0.0 and st * s_perp > 1e-12:
                    t_s = (r * e_s / d - ct * e_s) / (st * s_perp)
                    if -1.0 < t_s < 1.0:
                        w_s = math.acos(t_s)
                        for edge in (phi_s - w_s, phi_s + w_s):
                            x = start + (edge - start) % (2.0 * math.pi)
                            if start < x < stop:
                                cuts[n_cuts] = x
                                n_cuts += 1
                cuts[:n_cuts] = np.sort(cuts[:n_cuts])
                left = start
                for c in range(n_cuts + 1):
                    right = cuts[c] if c < n_cuts else stop
                    scale = 0.5 * (right - left) * weight_t
                    for m in range(len(u)):
                        phi = left + 0.5 * (right - left) * (u[m] + 1.0)
                        cp, sp = math.cos(phi), math.sin(phi)
                        w0 = ct * e[0] + st * (cp * e1[0] + sp * e2[0])
                        w1 = ct * e[1] + st * (cp * e1[1] + sp * e2[1])
                        w2 = ct * e[2] + st * (cp * e1[2] + sp * e2[2])
                        cos_n = n[0] * w0 + n[1] * w1 + n[2] * w2
                        if cos_n <= 0.0:
                            continue
                        big_n0 = (d * w0 - r * e[0]) / big_r
                        big_n1 = (d * w1 - r * e[1]) / big_r
                        big_n2 = (d * w2 - r * e[2]) / big_r
                        x_lat = big_n0 * pole[0] + big_n1 * pole[1] + big_n2 * pole[2]
                        lit = max(big_n0 * sun[0] + big_n1 * sun[1] + big_n2 * sun[2], 0.0)
                        level = (c_u + c_s * lit) * (q0 + q1 * x_lat + q2 * (1.5 * x_lat * x_lat - 0.5))
                        f = scale * wu[m] * level / math.pi * cos_n
                        total[0] += f
                        total[1] += f * w0
                        total[2] += f * w1
                        total[3] += f * w2
                        total[4] += f * cos_n
                    left = right
        out[i] = total
