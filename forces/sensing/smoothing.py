"""A sequence of rows smoothed with the attitude's rate (METHOD.md "Attitude from heat fluxes").

Each sunlit row's directions are fitted again from the rows around it: within a window of time, the
body turns at a constant rate and the planet's centre moves at the orbit's mean motion, and the rows'
own solutions, weighted by their 1-sigma errors, fix the directions at the row and the body's rate. An
ambiguous row takes the alternative the motion agrees with; a row no minimum of which the motion of the
others agrees with (a wrong solution without alternatives) is left out of the fit.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, replace

import numpy as np
import scipy.optimize
import scipy.stats
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sunwind.forces.sensing.row import AttitudeSolution, attitude_of
from sunwind.forces.sensing.search import (
    CONFIDENCE,
    Minimum,
    fit_covariance,
    moved,
    pointing_sigma,
    tangent_basis,
)

#: Rows a window needs (4 measured angles each against 8 unknowns).
LEAST_ROWS = 3
#: Rounds of choosing each row's minimum nearest the fitted motion and fitting again.
ROUNDS = 3
#: Confidence of a row's own chi2 beyond which it does not agree with a motion.
OUTLIER_CONFIDENCE = 0.999
#: Most runs of three neighbouring rows whose motions are tried for a window's consensus.
SEEDS = 8
#: Starts of the orbit normal's angle about the nadir [rad] of a window's first fit: the best is kept
#: (the misfit goes once up and down around the circle: one of two opposite starts is on its way down).
_NORMAL_STARTS = np.radians([0.0, 180.0])
#: Smallest 1-sigma angle a row's direction is weighted with [rad] (a noise-free row's is rounding).
_FLOOR_RAD = 1e-7


@dataclass(frozen=True)
class SmoothedRow:
    """One row's directions fitted with the rows around it, the body turning at a constant rate.

    Attributes
    ----------
    time_s : float
        The row's time [s].
    sun, nadir : (3,) float64
        Unit directions to the Sun and the planet's centre at the row, body frame.
    sigma_sun_deg, sigma_nadir_deg : float or None
        Their 1-sigma errors [deg] (None: not observable).
    rate_deg_s : (3,) float64
        The body's angular velocity relative to inertial space, body axes [deg/s].
    sigma_rate_deg_s : float or None
        Its 1-sigma error, the root of the covariance's trace [deg/s].
    rows : int
        Sunlit rows in the window.
    misfit : float
        RMS of the rows' whitened angle residuals about the fitted motion (about 1 when the motion
        explains them).
    explained : bool
        The residuals' chi2 is within its :data:`~sunwind.forces.sensing.search.CONFIDENCE` quantile:
        the rate is constant over the window as far as the rows can tell.
    switched : int
        Rows of the window whose alternative, not their best minimum, the motion took.
    rejected : int
        Rows of the window left out of the fit: no minimum of theirs agrees with the motion of the others
        (their chi2 beyond its :data:`OUTLIER_CONFIDENCE` quantile).
    outlier : bool
        The row's own solution is one of them: its directions come from the other rows alone.
    quaternion : (4,) float64 or None
        As :attr:`AttitudeSolution.quaternion`, from the smoothed directions.
    pitch_yaw_roll_deg : (3,) float64 or None
        As :attr:`AttitudeSolution.pitch_yaw_roll_deg`.

    Examples
    --------
    >>> z = np.array([0.0, 0.0, 1.0])
    >>> row = SmoothedRow(0.0, z, -z, 0.1, 0.2, np.zeros(3), 0.01, 5, 1.0, True, 0, 0, False, None, None)
    >>> sorted(row.to_json())[:3]
    ['explained', 'misfit', 'nadir_body']
    """

    time_s: float
    sun: NDArray[np.float64]
    nadir: NDArray[np.float64]
    sigma_sun_deg: float | None
    sigma_nadir_deg: float | None
    rate_deg_s: NDArray[np.float64]
    sigma_rate_deg_s: float | None
    rows: int
    misfit: float
    explained: bool
    switched: int
    rejected: int
    outlier: bool
    quaternion: NDArray[np.float64] | None
    pitch_yaw_roll_deg: NDArray[np.float64] | None

    def to_json(self) -> dict:
        """Plain-JSON record; keys carry their units.

        Returns
        -------
        dict
        """

        def listed(values: NDArray[np.float64] | None) -> list[float] | None:
            return None if values is None else [float(v) for v in values]

        return {
            "sun_body": listed(self.sun),
            "nadir_body": listed(self.nadir),
            "sigma_deg": {"sun": self.sigma_sun_deg, "nadir": self.sigma_nadir_deg},
            "rate_deg_s": listed(self.rate_deg_s),
            "sigma_rate_deg_s": self.sigma_rate_deg_s,
            "quaternion": listed(self.quaternion),
            "pitch_yaw_roll_deg": listed(self.pitch_yaw_roll_deg),
            "rows": self.rows,
            "misfit": self.misfit,
            "explained": self.explained,
            "switched": self.switched,
            "rejected": self.rejected,
            "outlier": self.outlier,
        }


def smoothed_rows(
    rows: tuple[AttitudeSolution, ...],
    window_s: float,
    mean_motion_rad_s: float,
    inertial: list | None = None,
) -> tuple[SmoothedRow | None, ...]:
    """Every sunlit row fitted again with the sunlit rows within ``window_s / 2`` of it.

    Parameters
    ----------
    rows : tuple of AttitudeSolution
        The rows solved alone, in time order.
    window_s : float
        The window's length [s]; the body's rate is taken as constant over it.
    mean_motion_rad_s : float
        The orbit's mean motion [rad/s]: the rate at which the nadir turns in inertial space.
    inertial : list, optional
        Per row, its inertial (Sun, nadir, velocity or None) or None
        (:meth:`~sunwind.forces.sensing.flux_rows.FluxRows.inertial`), for the smoothed quaternion.

    Returns
    -------
    tuple of SmoothedRow or None
        None for a row in eclipse, or with fewer than :data:`LEAST_ROWS` sunlit rows in its window.

    Examples
    --------
    Rows of a body turning at 0.5 deg/s about z, the Sun and the nadir found 0.05 deg off at random:

    >>> rng = np.random.default_rng(1)
    >>> def row(t):
    ...     turn = Rotation.from_rotvec([0.0, 0.0, -np.radians(0.5) * t])
    ...     sun, nadir = turn.apply([1.0, 0.0, 0.0]), turn.apply([0.0, 0.6, -0.8])
    ...     off = [v + np.radians(0.05) * rng.normal(size=3) for v in (sun, nadir)]
    ...     off = [v / np.linalg.norm(v) for v in off]
    ...     return AttitudeSolution(t, Minimum(*off, 1.0, 0.05, 0.05, np.zeros(6), 4), (), False, None, None,
    ...                             np.zeros(6), 0.0)
    >>> fitted = smoothed_rows(tuple(row(t) for t in range(0, 100, 10)), 60.0, 0.0)
    >>> np.round(fitted[5].rate_deg_s, 2) + 0.0, fitted[5].rows, fitted[5].sigma_sun_deg < 0.05
    (array([0. , 0. , 0.5]), 7, True)
    """
    times = np.array([row.time_s for row in rows])
    sunlit = np.array([not row.eclipse and row.best.sun is not None for row in rows])
    out: list[SmoothedRow | None] = []
    for k, row in enumerate(rows):
        near = np.flatnonzero(sunlit & (np.abs(times - row.time_s) <= 0.5 * window_s))
        if not sunlit[k] or len(near) < LEAST_ROWS:
            out.append(None)
            continue
        found = _window_fit([rows[i] for i in near], row, mean_motion_rad_s)
        given = None if inertial is None else inertial[k]
        if given is not None:
            quaternion, angles = attitude_of(found.sun, found.nadir, given)
            found = replace(found, quaternion=quaternion, pitch_yaw_roll_deg=angles)
        out.append(found)
    return tuple(out)


class _Motion:
    """The constant-rate motion about one row: unknowns ``x`` = Sun and nadir offsets at the row (two
    tangent components each), the body rate (3, rad/s) and the orbit normal's angle about the nadir.
    A chart of :func:`~sunwind.forces.sensing.search.pointing_sigma`: ``at(x)`` is the row's pair."""

    def __init__(self, sun: NDArray[np.float64], nadir: NDArray[np.float64], mean_motion: float) -> None:
        self.sun, self.nadir, self.mean_motion = sun, nadir, mean_motion
        self.size = 8 if mean_motion > 0.0 else 7  # without the orbit's motion, no normal to fit
        self.sun_basis, self.nadir_basis = tangent_basis(sun), tangent_basis(nadir)

    def at(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The Sun and nadir at the row."""
        return moved(self.sun, self.sun_basis, x[0:2]), moved(self.nadir, self.nadir_basis, x[2:4])

    def predict(
        self, x: NDArray[np.float64], tau: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Sun and nadir (n, 3) at times ``tau`` from the row: the body turned by its rate, the nadir
        besides turned about the orbit normal at the mean motion."""
        sun, nadir = self.at(x)
        body = -np.outer(tau, x[4:7])
        if self.size == 7:
            return _turned(body, sun), _turned(body, nadir)
        normal = self._normal(x, nadir)
        return _turned(body, sun), _turned(body, _turned(np.outer(tau * self.mean_motion, normal), nadir))

    def carried(self, x: NDArray[np.float64], tau: float, there: _Motion) -> NDArray[np.float64]:
        """The unknowns of ``there``, a chart at ``tau`` from the row, for this motion: no offsets, the
        same body rate, the same orbit normal (turned with the body)."""
        if there.size == 7:
            return np.concatenate([np.zeros(4), x[4:7]])
        normal = _turned(-tau * x[None, 4:7], self._normal(x, self.at(x)[1]))[0]
        angle = math.atan2(normal @ there.nadir_basis[1], normal @ there.nadir_basis[0])
        return np.concatenate([np.zeros(4), x[4:7], [angle]])

    def _normal(self, x: NDArray[np.float64], nadir: NDArray[np.float64]) -> NDArray[np.float64]:
        """The orbit normal at the row, body axes: at angle ``x[7]`` about the nadir, across it."""
        normal = math.cos(x[7]) * self.nadir_basis[0] + math.sin(x[7]) * self.nadir_basis[1]
        normal = normal - (normal @ nadir) * nadir
        return normal / np.linalg.norm(normal)


def _turned(rotvec: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    """``v`` turned by each rotation vector of ``rotvec`` (n, 3) (Rodrigues' formula), (n, 3)."""
    theta2 = np.einsum("ij,ij->i", rotvec, rotvec)
    theta = np.sqrt(theta2)
    small = theta < 1e-4
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - theta2 / 6.0, np.sin(safe) / safe)
    b = np.where(small, 0.5 - theta2 / 24.0, (1.0 - np.cos(safe)) / safe**2)
    across = np.cross(rotvec, v)
    return v + a[:, None] * across + b[:, None] * np.cross(rotvec, across)


@dataclass(frozen=True)
class _Fitted:
    """A motion fitted to some of a window's rows: its chart and time, scipy's result, the rows and the
    minimum of each that the fit took."""

    motion: _Motion
    result: scipy.optimize.OptimizeResult
    time_s: float
    rows: list[AttitudeSolution]
    chosen: list[Minimum]

    @property
    def angles(self) -> int:
        """The measured angles: two per observed direction."""
        return 2 * sum(int(w > 0) for m in self.chosen for w in _row_weights(m))

    @property
    def misfit(self) -> float:
        """RMS of the whitened angle residuals."""
        return math.sqrt(float(self.result.fun @ self.result.fun) / max(self.angles, 1))

    @property
    def explained(self) -> bool:
        """The chi2 is within its :data:`~sunwind.forces.sensing.search.CONFIDENCE` quantile."""
        dof = self.angles - len(self.result.x)
        return bool(dof <= 0 or 2.0 * self.result.cost <= scipy.stats.chi2.ppf(CONFIDENCE, dof))

    def chances(self, rows: list[AttitudeSolution], minima: list[Minimum]) -> NDArray[np.float64]:
        """Per row, the chance of a chi2 as large as that of its minimum about the motion (1 for a
        minimum with no direction observed)."""
        tau = np.array([r.time_s - self.time_s for r in rows])
        measured = _Measured.of(minima)
        sun, nadir = measured.whitened(self.motion, self.result.x, tau)
        chi2 = np.sum(sun**2 + nadir**2, axis=1)
        dof = 2 * np.sum(measured.weights > 0, axis=1)
        return np.where(dof > 0, scipy.stats.chi2.sf(chi2, np.maximum(dof, 1)), 1.0)


def _window_fit(window: list[AttitudeSolution], row: AttitudeSolution, mean_motion: float) -> SmoothedRow:
    """The motion fitted to a window's rows, rows that disagree with it left out.

    First the rows are left out one by one (:func:`_leaving_out`); if the rows kept are then not explained,
    the motion most rows agree with is sought from runs of neighbouring rows (:func:`_consensus`), and
    of the fits with a majority of the rows the explained one, else the one of least misfit, is kept."""
    fits = _leaving_out(window, row, mean_motion)
    if not fits[-1].explained:
        fits += _consensus(window, row, mean_motion)
    best = min(
        (f for f in fits if 2 * len(f.rows) > len(window)),
        key=lambda f: (not f.explained, f.misfit, -len(f.rows)),
    )
    return _smoothed(row, window, best)


def _leaving_out(window: list[AttitudeSolution], row: AttitudeSolution, mean_motion: float) -> list[_Fitted]:
    """The motion of all the rows (:func:`_motion_of`), then, while a row's chi2 about the fit is beyond
    the :data:`OUTLIER_CONFIDENCE` quantile, without the row least likely about a robust fit
    (:func:`_outlier`; fewer than half the rows, at least :data:`LEAST_ROWS` kept): every fit made."""
    fits = [_motion_of(window, row, mean_motion)]
    for _ in range(min((len(window) - 1) // 2, len(window) - LEAST_ROWS)):
        worst = _outlier(fits[-1])
        if worst is None:
            break
        kept = fits[-1].rows[:worst] + fits[-1].rows[worst + 1 :]
        fits.append(_motion_of(kept, row, mean_motion))
    return fits


def _consensus(window: list[AttitudeSolution], row: AttitudeSolution, mean_motion: float) -> list[_Fitted]:
    """The motion most rows agree with: the motions of up to :data:`SEEDS` runs of three neighbouring
    rows (:func:`_seeds`) are tried, and the one most rows agree with (:func:`_agreeing`) fitted again to
    those rows until they stay the same. Its fits."""
    kept: list[AttitudeSolution] = []
    for seed in _seeds(window):
        tried = _motion_of(seed, row, mean_motion)
        agreeing = _agreeing(tried, window)
        if len(agreeing) > len(kept):
            kept, current = agreeing, tried
    fits = []
    for _ in range(ROUNDS):
        if len(kept) < LEAST_ROWS:
            break
        current = _choose(current, row, kept)
        fits.append(current)
        kept = _agreeing(current, window)
        if [r.time_s for r in kept] == [r.time_s for r in current.rows]:
            break
    return fits


def _seeds(window: list[AttitudeSolution]) -> list[list[AttitudeSolution]]:
    """Up to :data:`SEEDS` runs of three neighbouring rows, spread over the window."""
    centres = np.unique(np.round(np.linspace(1, len(window) - 2, min(SEEDS, len(window) - 2))).astype(int))
    return [window[c - 1 : c + 2] for c in centres]


def _agreeing(fitted: _Fitted, window: list[AttitudeSolution]) -> list[AttitudeSolution]:
    """The rows one of whose minima is within the :data:`OUTLIER_CONFIDENCE` quantile of its chi2 about
    the motion."""
    pairs = [(r, m) for r in window for m in (r.best, *r.alternatives) if m.sun is not None]
    chances = fitted.chances([r for r, _ in pairs], [m for _, m in pairs])
    agree = {
        id(r) for (r, _), chance in zip(pairs, chances, strict=True) if chance >= 1.0 - OUTLIER_CONFIDENCE
    }
    return [r for r in window if id(r) in agree]


def _motion_of(rows: list[AttitudeSolution], row: AttitudeSolution, mean_motion: float) -> _Fitted:
    """The motion fitted to rows, each row's minimum chosen nearest it.

    The motion is first fitted to the rows with one minimum (their best), when there are enough, anchored
    at the one nearest the row in time; every row then takes its minimum nearest that motion (an
    ambiguous row, the alternative the others agree with), and the motion is fitted to those, charted at
    the row, until the choice stays (:func:`_choose`)."""
    sure = [r for r in rows if not r.alternatives]
    if len(sure) < LEAST_ROWS:
        sure = rows
    anchor = min(sure, key=lambda r: abs(r.time_s - row.time_s))
    first = [r.best for r in sure]
    tau = np.array([r.time_s for r in sure]) - anchor.time_s
    motion = _Motion(anchor.best.sun, anchor.best.nadir, mean_motion)
    result = _fit(motion, first, tau, _rate_start(first, tau))
    return _choose(_Fitted(motion, result, anchor.time_s, sure, first), row, rows)


def _choose(fitted: _Fitted, row: AttitudeSolution, rows: list[AttitudeSolution]) -> _Fitted:
    """Each of ``rows`` takes its minimum nearest the motion, and the motion is fitted to them charted at
    the row (its own minimum when it is among them), until the choice stays."""
    times = np.array([r.time_s for r in rows])
    chosen: list[Minimum] | None = None
    for _ in range(ROUNDS):
        motion, x, shift = fitted.motion, fitted.result.x, fitted.time_s
        nearest = [_nearest(motion, x, r.time_s - shift, [r.best, *r.alternatives]) for r in rows]
        if chosen is not None and all(map(operator.is_, nearest, chosen)):
            break
        chosen = nearest
        own = [m for m, r in zip(chosen, rows, strict=True) if r is row]
        at_row = motion.predict(x, np.array([row.time_s - shift]))
        sun, nadir = (own[0].sun, own[0].nadir) if own else (at_row[0][0], at_row[1][0])
        there = _Motion(sun, nadir, motion.mean_motion)
        start = motion.carried(x, row.time_s - shift, there)
        result = _fit(there, chosen, times - row.time_s, start[4:7], start[7:])
        fitted = _Fitted(there, result, row.time_s, rows, chosen)
    return fitted


def _outlier(fitted: _Fitted) -> int | None:
    """The row least likely about a robust (soft L1) fit of the motion, if some row's chi2 about the
    plain fit is beyond the :data:`OUTLIER_CONFIDENCE` quantile: a large error pulls a plain fit to
    every row, not to its own."""
    if fitted.chances(fitted.rows, fitted.chosen).min() >= 1.0 - OUTLIER_CONFIDENCE:
        return None
    tau = np.array([r.time_s for r in fitted.rows]) - fitted.time_s
    robust = _least_squares(fitted.motion, fitted.chosen, tau, fitted.result.x, loss="soft_l1")
    return int(np.argmin(replace(fitted, result=robust).chances(fitted.rows, fitted.chosen)))


def _smoothed(row: AttitudeSolution, window: list[AttitudeSolution], fitted: _Fitted) -> SmoothedRow:
    """The row's record of a plain least-squares fit of the motion to some of the window's rows."""
    fit, motion = fitted.result, fitted.motion
    chi2, dof = float(fit.fun @ fit.fun), fitted.angles - len(fit.x)
    covariance = fit_covariance(fit.jac, chi2, dof)
    sun, nadir = motion.at(fit.x)
    sigma_sun, sigma_nadir = (pointing_sigma(motion, fit.x, covariance, which) for which in (0, 1))
    sigma_rate = (
        None if covariance is None else math.degrees(math.sqrt(max(np.trace(covariance[4:7, 4:7]), 0.0)))
    )
    return SmoothedRow(
        row.time_s,
        sun,
        nadir,
        sigma_sun,
        sigma_nadir,
        np.degrees(fit.x[4:7]),
        sigma_rate,
        len(window),
        fitted.misfit,
        fitted.explained,
        sum(m is not r.best for m, r in zip(fitted.chosen, fitted.rows, strict=True)),
        len(window) - len(fitted.rows),
        not any(r is row for r in fitted.rows),
        None,
        None,
    )


def _fit(
    motion: _Motion,
    chosen: list[Minimum],
    tau: NDArray[np.float64],
    rate: NDArray[np.float64],
    normal: NDArray[np.float64] | None = None,
) -> scipy.optimize.OptimizeResult:
    """The motion's least-squares fit to the chosen minima from the rate and the orbit normal's angle
    ``normal`` (default each of :data:`_NORMAL_STARTS`), the best kept."""
    starts = ([a] for a in _NORMAL_STARTS) if normal is None else [normal]
    fits = [
        _least_squares(motion, chosen, tau, np.concatenate([np.zeros(4), rate, angle])[: motion.size])
        for angle in (starts if motion.size == 8 else [[]])
    ]
    return min(fits, key=lambda f: float(f.cost))


def _least_squares(
    motion: _Motion,
    chosen: list[Minimum],
    tau: NDArray[np.float64],
    start: NDArray[np.float64],
    loss: str = "linear",
):
    measured = _Measured.of(chosen)

    def residuals(x: NDArray[np.float64]) -> NDArray[np.float64]:
        sun, nadir = measured.whitened(motion, x, tau)
        return np.concatenate([sun.ravel(), nadir.ravel()])

    method = "lm" if loss == "linear" else "trf"  # Levenberg-Marquardt takes no robust loss
    return scipy.optimize.least_squares(
        residuals, start, method=method, loss=loss, x_scale="jac", max_nfev=400
    )


@dataclass(frozen=True)
class _Measured:
    """Minima's directions, (n, 3) each, and 1 / sigma of one tangent component of each, (n, 2)
    (:func:`_row_weights`)."""

    sun: NDArray[np.float64]
    nadir: NDArray[np.float64]
    weights: NDArray[np.float64]

    @classmethod
    def of(cls, minima: list[Minimum]) -> _Measured:
        """The minima's arrays, made once per fit."""
        weights = np.array([_row_weights(m) for m in minima]).reshape(-1, 2)
        return cls(np.stack([m.sun for m in minima]), np.stack([m.nadir for m in minima]), weights)

    def whitened(
        self, motion: _Motion, x: NDArray[np.float64], tau: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The motion's Sun and nadir at times ``tau`` less the minima's, over their 1-sigma: (n, 3)
        each; the sum of squares of a row's six is its chi2."""
        sun, nadir = motion.predict(x, tau)
        return (sun - self.sun) * self.weights[:, :1], (nadir - self.nadir) * self.weights[:, 1:]


def _row_weights(m: Minimum) -> tuple[float, float]:
    """1 / sigma of one tangent component of a minimum's Sun and nadir [1/rad], 0 where not observable.

    A direction's 1-sigma is the root of its covariance's trace, over two tangent components: taken as
    round, each has ``sigma / sqrt(2)``. A unit vector's difference has three components for the two
    angles; their sum of squares is the angle's squared, so the chi2 counts two degrees of freedom."""
    return tuple(
        0.0 if s is None else math.sqrt(2.0) / max(math.radians(s), _FLOOR_RAD)
        for s in (m.sigma_sun_deg, m.sigma_nadir_deg)
    )


def _nearest(motion: _Motion, x: NDArray[np.float64], t: float, minima: list[Minimum]) -> Minimum:
    sun, nadir = (v[0] for v in motion.predict(x, np.array([t])))
    lit = [m for m in minima if m.sun is not None]
    return max(lit, key=lambda m: float(m.sun @ sun + m.nadir @ nadir))


def _rate_start(chosen: list[Minimum], tau: NDArray[np.float64]) -> NDArray[np.float64]:
    """The body rate from consecutive rows' turns, their median [rad/s] (the orbit's motion left out; a
    wrong row spoils two turns, not the median)."""
    rates = []
    for a, b, ta, tb in zip(chosen[:-1], chosen[1:], tau[:-1], tau[1:], strict=True):
        if tb > ta:
            turn, _ = Rotation.align_vectors(np.stack([b.sun, b.nadir]), np.stack([a.sun, a.nadir]))
            rates.append(-turn.as_rotvec() / (tb - ta))
    return np.median(rates, axis=0) if rates else np.zeros(3)
