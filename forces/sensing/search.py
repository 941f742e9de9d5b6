"""The Sun and nadir directions that reproduce one row of measured fluxes, over the whole sphere
(METHOD.md "Attitude from heat fluxes").

The misfit ``chi^2 = sum ((q_model - q) / sigma)^2`` is first evaluated at every (nadir, Sun) pair of the
coarse table; its local minima on the product of the two icospheres are the basins. Each basin is then
refined by :func:`scipy.optimize.least_squares` on the flux model, in a chart of the unknowns: two
tangent-plane offsets per free direction, or a rotation vector when the angle between the Sun and the
nadir is known. The distinct minima are ranked by ``chi^2``; their directions' 1-sigma errors come from
the Jacobian of the whitened residuals.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.optimize
import scipy.stats
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sunwind.forces.sensing.coarse import CoarseTable
from sunwind.forces.sensing.forward import FluxModel

#: Basins refined per row, best first: at least the first, and more until a minimum explains the row
#: within the noise (at most the second).
STARTS = (4, 8)
#: Two minima are the same when both their directions agree to this [deg].
SAME_DEG = 2.0
#: Confidence of the "within the noise" test on a minimum's misfit.
CONFIDENCE = 0.99
#: Finite-difference step of the Jacobian [rad].
_STEP = 1e-5


@dataclass(frozen=True)
class Minimum:
    """One local minimum of the misfit.

    Attributes
    ----------
    sun : (3,) float64 or None
        Unit direction to the Sun, body frame; None in eclipse (not observable).
    nadir : (3,) float64
        Unit direction to the planet's centre, body frame.
    chi2 : float
        ``sum ((q_model - q) / sigma)^2``.
    sigma_sun_deg, sigma_nadir_deg : float or None
        1-sigma pointing error of each direction [deg] (None: not observable).
    modelled : (p,) float64
        The model's fluxes there [W/m^2].
    parameters : int
        Unknowns fitted (4 free, 3 with the Sun-nadir angle known, 2 in eclipse).

    Examples
    --------
    >>> m = Minimum(np.array([0.0, 0, 1]), np.array([0.0, 0, -1]), 1.5, 0.2, 0.3, np.zeros(6), 4)
    >>> m.misfit
    0.5
    """

    sun: NDArray[np.float64] | None
    nadir: NDArray[np.float64]
    chi2: float
    sigma_sun_deg: float | None
    sigma_nadir_deg: float | None
    modelled: NDArray[np.float64]
    parameters: int

    @property
    def misfit(self) -> float:
        """RMS of the whitened residuals, ``sqrt(chi2 / p)``: about 1 when the fit is within the noise."""
        return math.sqrt(self.chi2 / len(self.modelled))

    def same_as(self, other: Minimum) -> bool:
        """Whether both directions agree with ``other``'s to :data:`SAME_DEG`.

        Parameters
        ----------
        other : Minimum

        Returns
        -------
        bool

        Examples
        --------
        >>> a = Minimum(None, np.array([0.0, 0, -1]), 1.0, None, 0.3, np.zeros(6), 2)
        >>> a.same_as(a)
        True
        """
        close = math.cos(math.radians(SAME_DEG))
        if float(self.nadir @ other.nadir) < close:
            return False
        if self.sun is None or other.sun is None:
            return self.sun is None and other.sun is None
        return float(self.sun @ other.sun) >= close


@dataclass(frozen=True)
class _Chart:
    """Unknowns ``x`` about a start: ``at(x)`` gives the (Sun, nadir) pair."""

    at: Callable[[NDArray[np.float64]], tuple[NDArray[np.float64], NDArray[np.float64]]]
    size: int


def tangent_basis(u: NDArray[np.float64]) -> NDArray[np.float64]:
    """Two unit vectors perpendicular to a unit vector and to each other: a chart's tangent plane.

    Parameters
    ----------
    u : (3,) float64
        A unit vector.

    Returns
    -------
    (2, 3) float64

    Examples
    --------
    >>> tangent_basis(np.array([0.0, 0.0, 1.0])) + 0.0
    array([[ 0.,  1.,  0.],
           [-1.,  0.,  0.]])
    """
    e1 = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    return np.stack([e1, np.cross(u, e1)])


def moved(u: NDArray[np.float64], basis: NDArray[np.float64], x: NDArray[np.float64]) -> NDArray[np.float64]:
    """A unit vector moved by tangent offsets, and made unit again.

    Parameters
    ----------
    u : (3,) float64
        The unit vector.
    basis : (2, 3) float64
        Its tangent plane (:func:`tangent_basis`).
    x : (2,) float64
        The offsets along the basis.

    Returns
    -------
    (3,) float64

    Examples
    --------
    >>> z = np.array([0.0, 0.0, 1.0])
    >>> moved(z, tangent_basis(z), np.array([1.0, 0.0]))
    array([0.        , 0.70710678, 0.70710678])
    """
    v = u + x @ basis
    return v / np.linalg.norm(v)


def free_chart(sun: NDArray[np.float64], nadir: NDArray[np.float64]) -> _Chart:
    """Both directions free: two tangent offsets each.

    Parameters
    ----------
    sun, nadir : (3,) float64
        The start, unit vectors.

    Returns
    -------
    _Chart
        Four unknowns.

    Examples
    --------
    >>> chart = free_chart(np.array([0.0, 0, 1]), np.array([1.0, 0, 0]))
    >>> chart.size, chart.at(np.zeros(4))[0]
    (4, array([0., 0., 1.]))
    """
    s_basis, n_basis = tangent_basis(sun), tangent_basis(nadir)
    return _Chart(lambda x: (moved(sun, s_basis, x[:2]), moved(nadir, n_basis, x[2:])), 4)


def turned_chart(sun: NDArray[np.float64], nadir: NDArray[np.float64]) -> _Chart:
    """The angle between the two is known: one rotation (a rotation vector, body frame) turns both.

    Parameters
    ----------
    sun, nadir : (3,) float64
        The start, unit vectors at the known angle.

    Returns
    -------
    _Chart
        Three unknowns.

    Examples
    --------
    >>> chart = turned_chart(np.array([0.0, 0, 1]), np.array([1.0, 0, 0]))
    >>> s, n = chart.at(np.array([0.0, 0.0, np.pi / 2]))
    >>> np.round(n, 12) + 0.0
    array([0., 1., 0.])
    """

    def at(x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        turn = Rotation.from_rotvec(x).as_matrix()
        return turn @ sun, turn @ nadir

    return _Chart(at, 3)


def dark_chart(nadir: NDArray[np.float64]) -> _Chart:
    """Eclipse: the nadir alone (the Sun put behind the planet, along the nadir).

    Parameters
    ----------
    nadir : (3,) float64
        The start.

    Returns
    -------
    _Chart
        Two unknowns.

    Examples
    --------
    >>> dark_chart(np.array([0.0, 0, -1])).at(np.zeros(2))[0]
    array([ 0.,  0., -1.])
    """
    basis = tangent_basis(nadir)

    def at(x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        n = moved(nadir, basis, x)
        return n, n

    return _Chart(at, 2)


def refine(
    model: FluxModel,
    chart: _Chart,
    measured: NDArray[np.float64],
    sigma: NDArray[np.float64],
    dark: bool,
    traced: bool = True,
) -> Minimum:
    """The minimum of the misfit nearest the chart's start, with its directions' 1-sigma errors.

    Parameters
    ----------
    model : FluxModel
    chart : _Chart
    measured, sigma : (p,) float64
        The row's fluxes and their 1-sigma errors [W/m^2].
    dark : bool
        An eclipse chart: the Sun is not reported.
    traced : bool
        Sunlight traced at every evaluation (:meth:`~sunwind.forces.sensing.forward.FluxModel.fluxes`).

    Returns
    -------
    Minimum

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> fluxes = flux_model(cube, 500.0)
    >>> sun, nadir = np.array([0.6, 0.0, 0.8]), np.array([0.0, 0.0, -1.0])
    >>> q = fluxes.fluxes(sun, nadir).total
    >>> found = refine(fluxes, free_chart(np.array([0.5, 0.1, 0.86]), nadir), q, 0.01 * q + 1.0, False)
    >>> np.round(found.sun, 6) + 0.0
    array([0.6, 0. , 0.8])
    """

    def residuals(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return (model.fluxes(*chart.at(x), traced=traced).total - measured) / sigma

    method = "lm" if len(measured) >= chart.size else "trf"  # MINPACK's needs no more unknowns than data
    fit = scipy.optimize.least_squares(
        residuals,
        np.zeros(chart.size),
        method=method,
        diff_step=_STEP,
        xtol=1e-8,
        ftol=1e-8,
        max_nfev=25 * chart.size,
    )
    sun, nadir = chart.at(fit.x)
    r = fit.fun
    chi2 = float(r @ r)
    jacobian = fit.jac
    if not np.any(jacobian):  # MINPACK stopped at its start (an exact fit) and kept no Jacobian
        jacobian = np.stack(
            [
                (residuals(fit.x + _STEP * e) - residuals(fit.x - _STEP * e)) / (2 * _STEP)
                for e in np.eye(chart.size)
            ],
            axis=1,
        )
    covariance = fit_covariance(jacobian, chi2, len(r) - chart.size)
    sigma_sun, sigma_nadir = (pointing_sigma(chart, fit.x, covariance, which) for which in (0, 1))
    modelled = r * sigma + measured
    if dark:
        return Minimum(None, nadir, chi2, None, sigma_nadir, modelled, chart.size)
    return Minimum(sun, nadir, chi2, sigma_sun, sigma_nadir, modelled, chart.size)


def polished(
    model: FluxModel, minimum: Minimum, measured: NDArray[np.float64], sigma: NDArray[np.float64]
) -> Minimum:
    """A minimum found with sunlight from the interpolated correction, refined again with sunlight
    traced (unchanged when the model has no correction: the two are the same).

    Parameters
    ----------
    model : FluxModel
    minimum : Minimum
        Found with ``traced=False``: free (4 unknowns) or at a known angle (3).
    measured, sigma : (p,) float64

    Returns
    -------
    Minimum

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> m = Minimum(np.array([0.0, 0, 1]), np.array([0.0, 0, -1]), 1.0, 0.1, 0.1, np.zeros(6), 4)
    >>> polished(flux_model(cube, 500.0), m, np.zeros(6), np.ones(6)) is m
    True
    """
    if model.response.tracer is None or minimum.sun is None:
        return minimum
    chart = free_chart if minimum.parameters == 4 else turned_chart
    return refine(model, chart(minimum.sun, minimum.nadir), measured, sigma, False)


def fit_covariance(jacobian: NDArray[np.float64], chi2: float, dof: int) -> NDArray[np.float64] | None:
    """The covariance of a least-squares fit's unknowns from its whitened residuals' Jacobian.

    ``(J^T J)^-1``, inflated by ``chi2 / dof`` when the fit is worse than the noise can make it (beyond
    the :data:`CONFIDENCE` quantile).

    Parameters
    ----------
    jacobian : (m, k) float64
        Of the whitened residuals.
    chi2 : float
        The residuals' sum of squares.
    dof : int
        Residuals less unknowns.

    Returns
    -------
    (k, k) float64 or None
        None when the unknowns are not all observable (condition above 1e12).

    Examples
    --------
    >>> fit_covariance(np.eye(3)[:, :2] * 2.0, 1.0, 1)
    array([[0.25, 0.  ],
           [0.  , 0.25]])
    """
    normal = jacobian.T @ jacobian
    if not np.all(np.isfinite(normal)) or np.linalg.cond(normal) > 1e12:
        return None
    worse = dof > 0 and chi2 > scipy.stats.chi2.ppf(CONFIDENCE, dof)
    return np.linalg.inv(normal) * (chi2 / dof if worse else 1.0)


def pointing_sigma(
    chart: _Chart, x: NDArray[np.float64], covariance: NDArray | None, which: int
) -> float | None:
    """1-sigma angle of a fitted direction: ``sqrt(trace(D C D^T))``, ``D`` its derivative in the chart.

    Parameters
    ----------
    chart : object
        Its ``at(x)`` gives the (Sun, nadir) pair of the unknowns; ``size`` is their number.
    x : (k,) float64
        The fitted unknowns.
    covariance : (k, k) float64 or None
        Theirs (:func:`fit_covariance`).
    which : int
        0 the Sun, 1 the nadir.

    Returns
    -------
    float or None
        [deg]; None without a covariance.

    Examples
    --------
    >>> chart = free_chart(np.array([0.0, 0, 1]), np.array([1.0, 0, 0]))
    >>> round(pointing_sigma(chart, np.zeros(4), np.eye(4) * np.radians(0.1) ** 2, 0), 6)
    0.141421
    """
    if covariance is None:
        return None
    h = 1e-6
    columns = [
        (chart.at(x + h * e)[which] - chart.at(x - h * e)[which]) / (2 * h) for e in np.eye(chart.size)
    ]
    d = np.stack(columns, axis=1)
    return math.degrees(math.sqrt(max(float(np.trace(d @ covariance @ d.T)), 0.0)))


def basins(
    table: CoarseTable, measured: NDArray[np.float64], sigma: NDArray[np.float64], count: int = STARTS[1]
) -> list[tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """The best ``count`` distinct local minima of the misfit over the table's (nadir, Sun) pairs, as
    (Sun, nadir) starts.

    Parameters
    ----------
    table : CoarseTable
    measured, sigma : (p,) float64
    count : int

    Returns
    -------
    list of (sun, nadir) pairs of (3,) float64

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.coarse import coarse_table
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> fluxes = flux_model(cube, 500.0)
    >>> q = fluxes.fluxes(np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, -1.0])).total
    >>> sun, nadir = basins(coarse_table(fluxes, level=2), q, 0.01 * q + 1)[0]
    >>> bool(sun[2] > 0.95 and nadir[2] < -0.95)
    True
    """
    weight = 1.0 / sigma**2  # chi2 = sum F^2 w - 2 F (q w) + q^2 w: two products with the table
    chi2 = table.squares @ weight - 2.0 * (table.fluxes @ (measured * weight)) + float(measured**2 @ weight)
    lowest = np.minimum(chi2[table.neighbours].min(axis=1), chi2[:, table.neighbours].min(axis=2))
    k, j = np.nonzero(chi2 <= lowest)
    order = np.argsort(chi2[k, j], kind="stable")[: 4 * count]
    starts: list[tuple[NDArray[np.float64], NDArray[np.float64]]] = []
    for sun, nadir in zip(table.nodes[j[order]], table.nodes[k[order]], strict=True):
        if all(float(sun @ s) < 0.99 or float(nadir @ n) < 0.99 for s, n in starts):
            starts.append((sun, nadir))
        if len(starts) == count:
            break
    return starts


def at_known_angle(
    minimum: Minimum, sun_inertial: NDArray[np.float64], nadir_inertial: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The body-frame pair nearest a free minimum's that makes the inertial pair's angle: the inertial
    directions turned back by the rotation that best takes the minimum's onto them.

    Parameters
    ----------
    minimum : Minimum
        A minimum with both directions free.
    sun_inertial, nadir_inertial : (3,) float64
        Unit vectors, one inertial frame.

    Returns
    -------
    sun, nadir : (3,) float64

    Examples
    --------
    >>> m = Minimum(np.array([1.0, 0, 0]), np.array([0.0, 1, 0]), 0.0, 0.1, 0.1, np.zeros(6), 4)
    >>> sun, nadir = at_known_angle(m, np.array([0.0, 0, 1]), np.array([1.0, 0, 0]))
    >>> round(float(sun @ nadir), 12) + 0.0, bool(sun @ m.sun > 0.99)
    (0.0, True)
    """
    turn, _ = Rotation.align_vectors(
        np.stack([sun_inertial, nadir_inertial]), np.stack([minimum.sun, minimum.nadir])
    )
    return turn.inv().apply(sun_inertial), turn.inv().apply(nadir_inertial)


def dark_basins(
    table: CoarseTable, measured: NDArray[np.float64], sigma: NDArray[np.float64], count: int = 2
) -> list[NDArray[np.float64]]:
    """The best ``count`` local minima over the nadirs with the Sun behind the planet (eclipse).

    Parameters
    ----------
    table : CoarseTable
    measured, sigma : (p,) float64
    count : int

    Returns
    -------
    list of (3,) float64
        Nadir starts.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.coarse import coarse_table
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("b", 0.1, 0.0, emissivity=0.8), threads=1)
    >>> fluxes = flux_model(cube, 500.0)
    >>> down = np.array([0.0, 0.0, -1.0])
    >>> q = fluxes.fluxes(down, down).total
    >>> bool(dark_basins(coarse_table(fluxes, level=2), q, 0.01 * q + 1)[0][2] < -0.95)
    True
    """
    m = len(table.nodes)
    whitened = (table.planet[np.arange(m), np.arange(m)] - measured) / sigma
    chi2 = np.einsum("kp,kp->k", whitened, whitened)
    lowest = chi2[table.neighbours].min(axis=1)
    k = np.flatnonzero(chi2 <= lowest)
    return [table.nodes[i] for i in k[np.argsort(chi2[k], kind="stable")][:count]]


def within_noise(best: Minimum, dof: int) -> float:
    """The largest ``chi2`` of a minimum that the noise cannot tell from ``best``: ``best.chi2`` plus the
    :data:`CONFIDENCE` quantile of chi-squared in the unknowns, scaled by ``best.chi2 / dof`` when the
    best fit is worse than the noise.

    Parameters
    ----------
    best : Minimum
    dof : int
        Measurements minus unknowns.

    Returns
    -------
    float

    Examples
    --------
    >>> best = Minimum(None, np.array([0.0, 0, -1]), 2.0, None, 0.3, np.zeros(6), 4)
    >>> round(within_noise(best, 2), 3)
    15.277
    """
    scale = max(1.0, best.chi2 / dof) if dof > 0 else 1.0
    return best.chi2 + scale * float(scipy.stats.chi2.ppf(CONFIDENCE, best.parameters))
