"""The fit: bounded weighted least squares of the free coefficients (and nuisance terms) to telemetry,
with the analytical Jacobian of the sensitivities (``scipy.optimize.least_squares``, trust region
reflective).

Parameters: the free coefficients, each in [0, 1]; ``rho + sigma <= 1`` is kept by the bounds: a free
``rho`` of a material whose ``sigma`` is held has the upper bound ``1 - sigma`` (and the other way
round), and when both are free ``sigma`` is reparametrised as ``sigma = f (1 - rho)`` with ``f`` in
[0, 1] (estimates, covariance and correlations are reported for ``rho`` and ``sigma`` themselves).
Nuisance terms: a global ``scale`` of SRP (``--scale``), a constant body torque ``bias_torque_Nm``
(``--bias-torque``) and, with momentum data, the momentum at the first sample ``initial_momentum_Nms``.

The model enters through :class:`~.forward.LinearForward` (and :class:`~.drag_forward.LinearDrag` with
drag columns): exact without inter-reflection, first order with it or with free accommodations, when
the model is run again at each solution until no coefficient moves by more than ``RUN_SHARE`` of its
sigma.

Weights: each measurement kind by its given sigma; a kind without one by the RMS of its residual after a
first fit (the fit is then run again with those weights), said in a notice. The covariance is
``(J^T J)^-1`` of the weighted Jacobian at the solution, times ``chi2/dof`` when a weight came from the
residuals (unscaled when every sigma was given).

>>> sorted(LOSSES)
['linear', 'soft_l1']
"""

from __future__ import annotations

import time as clock
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import cumulative_trapezoid
from scipy.optimize import least_squares

from sunwind.forces.fit.drag_forward import FlowGeometry, LinearDrag, accommodations_of
from sunwind.forces.fit.forward import (
    RESOLUTION_DEG,
    Geometry,
    LinearForward,
    evaluator,
    is_linear,
)
from sunwind.forces.fit.report import FitResult, Series, diagnose
from sunwind.forces.fit.telemetry import KINDS, Telemetry, read_telemetry
from sunwind.forces.model import Model, as_model
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensitivity import ACCOMMODATIONS, COEFFICIENTS, OPTICS, Sensitivities
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import Spacecraft

LOSSES = ("linear", "soft_l1")
#: With inter-reflection or drag: most model runs; the fit has settled when no coefficient changed
#: between two runs' solutions by more than RUN_SHARE of its sigma (or RUN_TOLERANCE).
MAX_RUNS, RUN_TOLERANCE, RUN_SHARE = 8, 1e-7, 0.01


@dataclass(frozen=True)
class FitOptions:
    """How :func:`fit` fits.

    Attributes
    ----------
    bias_torque : bool
        Fit a constant body-frame torque [N m] too.
    scale : bool
        Fit one global factor of SRP too.
    sigmas : dict of str to float
        One-sigma noise of each measurement kind (``torque`` [N m], ``momentum`` [N m s], ``accel``
        [m/s^2]); a kind left out is weighted by its residual.
    mass_kg : float or None
        Spacecraft mass [kg], needed with acceleration data.
    loss : str
        ``linear`` or ``soft_l1`` (robust to outliers).
    reflections : str or ReflectionSettings
        Inter-reflection of light (default ``auto``, as :func:`~sunwind.forces.srp.srp`); ``none`` and
        ``plates`` run the model once, the others a few times.
    sampling : ShadowSampling or None
        The shadow pass's sampling.
    resolution_deg : float
        Rows whose Sun directions and hinge angles agree within this [deg] share one evaluation.
    epoch : str or None
        ISO UTC time of ``time_s = 0`` (for the Sun of quaternion telemetry read from a file).
    composition : str
        Mole fractions of the air of drag rows (``"O:1"``, ``"O:0.7,N2:0.3"``).

    Examples
    --------
    >>> FitOptions(loss="soft_l1").loss
    'soft_l1'
    """

    bias_torque: bool = False
    scale: bool = False
    sigmas: dict[str, float] = field(default_factory=dict)
    mass_kg: float | None = None
    loss: str = "linear"
    reflections: str | ReflectionSettings = "auto"
    sampling: ShadowSampling | None = None
    resolution_deg: float = RESOLUTION_DEG
    epoch: str | None = None
    composition: str = "O:1"


def fit(
    model: Model | Spacecraft,
    telemetry: Telemetry | str | Path,
    free: Sequence[str],
    options: FitOptions | None = None,
    **settings: object,
) -> FitResult:
    """Fit the free surface coefficients of ``model`` to telemetry.

    Parameters
    ----------
    model : Model or Spacecraft
        The model (its reference point is the torque's: the centre of mass).
    telemetry : Telemetry or path
        The telemetry, or its CSV file (:func:`~sunwind.forces.fit.telemetry.read_telemetry`).
    free : sequence of str
        ``MATERIAL.COEFFICIENT`` names: ``reflectivity``, ``specular_fraction``, ``transmissivity``;
        with drag columns also ``energy_accommodation``, ``normal_accommodation``,
        ``tangential_accommodation``.
    options : FitOptions, optional
        How to fit; or give its fields as keywords.
    **settings
        Fields of :class:`FitOptions`.

    Returns
    -------
    FitResult

    Raises
    ------
    InputError
        An unknown or repeated coefficient, one SRP does not depend on, acceleration data without a
        mass, a sigma that is not positive, fewer measurements than parameters.

    Examples
    --------
    >>> import numpy as np, sunwind as sw
    >>> from sunwind.forces.fit.telemetry import Telemetry
    >>> white = sw.Material("white", 0.5, 0.5)
    >>> plate = sw.load(sw.meshes.plate(divisions=2), uniform=white, two_sided=["*"], threads=1)
    >>> sun = np.array([[0.0, 0.0, 1.0]])
    >>> force = sw.srp(plate, sun, reflections="none").force_N
    >>> t = Telemetry(np.array([0.0]), sun, np.full(1, 1361.0), np.ones(1), {"accel": force / 2.0})
    >>> result = fit(plate, t, ["white.reflectivity"], mass_kg=2.0, reflections="none")
    >>> round(result.estimate("white.reflectivity")[0], 6)
    0.5
    """
    options = options or FitOptions(**settings)  # type: ignore[arg-type]
    started = clock.perf_counter()
    model = as_model(model)
    if not isinstance(telemetry, Telemetry):
        telemetry = read_telemetry(telemetry, options.epoch)
    problem = _Problem.of(model, telemetry, free, options)
    geometry = Geometry.of(model, telemetry, options.resolution_deg)
    reflections = ReflectionSettings.of(options.reflections)
    evaluate = evaluator(reflections, options.sampling)
    gas_free = any(COEFFICIENTS[k] in ACCOMMODATIONS for _, k in problem.free)
    linear = is_linear(model, reflections) and not gas_free
    materials = sorted({m for m, k in problem.free if k < 3})
    flows = None if telemetry.flow is None else FlowGeometry.of(telemetry, geometry, options.resolution_deg)

    def run(x: NDArray) -> None:
        problem.forward = LinearForward(model, geometry, evaluate, problem.optics(x), materials)
        if flows is not None:
            acc = problem.accommodations(x)
            problem.drag = LinearDrag(model, flows, acc, reflections, options.composition)

    problem.geometry, problem.flows = geometry, flows
    run(problem.x0)
    problem.start_momentum()
    evaluated = clock.perf_counter()
    before = problem.residuals(problem.x0)
    sigmas = {kind: options.sigmas.get(kind) for kind in telemetry.kinds}
    x, runs, converged, notices = problem.x0, 1, linear, []
    if len(geometry) < len(telemetry):
        notices.append(
            f"{len(telemetry)} rows share {len(geometry)} model runs: rows whose Sun directions (and hinge "
            f"angles) agree within {options.resolution_deg:g} deg are taken at their mean "
            "(--resolution-deg 0: one run per row)"
        )
    while True:
        weights = {k: s if s is not None else _rms_or_one(before[k]) for k, s in sigmas.items()}
        x_new = problem.solve(x, weights, options.loss)
        if any(value is None for value in sigmas.values()):  # weights from the post-fit residuals
            after = problem.residuals(x_new)
            weights = {k: s if s is not None else _rms_or_one(after[k]) for k, s in sigmas.items()}
            x_new = problem.solve(x_new, weights, options.loss)
        change = np.abs(problem.physical(x_new) - problem.physical(x))[: problem.n_free]
        settled = bool(np.all(change < np.maximum(RUN_TOLERANCE, RUN_SHARE * problem.sigmas(x_new, weights))))
        x = x_new
        if linear or (runs > 1 and settled) or runs == MAX_RUNS:
            converged = converged or settled
            break
        runs += 1  # with inter-reflection or drag: the model again at the solution
        run(x)
    for kind, value in sigmas.items():
        if value is None:
            notices.append(
                f"no sigma of the {kind} given: weighted by its post-fit residual RMS "
                f"{weights[kind]:.4g} {KINDS[kind][1]}; the uncertainties are scaled by sqrt(chi2/dof)"
            )
    series = problem.series(x, before)
    jacobian = problem.weighted_jacobian(x, weights)
    residual = np.concatenate([((series[k].after - series[k].measured) / weights[k]).ravel() for k in series])
    report = diagnose(
        problem.names,
        problem.physical(x),
        problem.initial_physical(),
        jacobian,
        residual,
        scaled=any(value is None for value in sigmas.values()),
    )
    if not converged:
        report["warnings"] += (
            f"the fit did not settle in {MAX_RUNS} model runs (last change of a coefficient "
            f"{change.max():.2g}): the estimates are those of the last run",
        )
    return FitResult(
        **report,
        bounds=problem.physical_bounds(),
        series=series,
        sigmas={k: float(v) for k, v in weights.items()},
        notices=tuple(notices),
        facts={
            "rows": len(telemetry),
            "geometries": len(geometry),
            "flows": 0 if flows is None else len(flows),
            "model_evaluations": runs,
            "reflections": reflections.mode,
            "linear": linear,
            "loss": options.loss,
            "seconds_first_model_run": round(evaluated - started, 3),
            "seconds_total": round(clock.perf_counter() - started, 3),
        },
        materials=tuple(model.craft.materials.names),
    )


def _rms_or_one(values: NDArray) -> float:
    rms = float(np.sqrt(np.mean(values**2)))
    return rms if rms > 0 else 1.0


class _Problem:
    """The parameters, their bounds, and the weighted residuals of a fit."""

    @classmethod
    def of(cls, model: Model, telemetry: Telemetry, free: Sequence[str], options: FitOptions) -> _Problem:
        materials = model.craft.materials
        index = Sensitivities.zeros(materials.names, np.zeros(3))
        pairs: list[tuple[int, int]] = []
        for name in free:
            m, k = index.index(name)
            gas = COEFFICIENTS[k] in ACCOMMODATIONS and telemetry.flow is not None
            if COEFFICIENTS[k] not in OPTICS and not gas:
                raise InputError(
                    f"--free {name}: SRP does not depend on {COEFFICIENTS[k]}",
                    hint=f"free one of {', '.join(OPTICS)}; the accommodations with drag columns "
                    "(vel_x, vel_y, vel_z, density_kg_m3)",
                )
            if (m, k) in pairs:
                raise InputError(f"--free {name} is given twice", hint="give each coefficient once")
            pairs.append((m, k))
        if not pairs:
            raise InputError("no --free coefficient", hint="give --free MATERIAL.COEFFICIENT")
        if "accel" in telemetry.kinds and (options.mass_kg is None or not options.mass_kg > 0):
            raise InputError(
                f"{telemetry.source}: accel_x, accel_y, accel_z need the spacecraft mass",
                hint="give --mass KG (Python: mass_kg=...), or drop the acceleration columns",
            )
        for kind, value in options.sigmas.items():
            if kind not in KINDS or not (value is not None and np.isfinite(value) and value > 0):
                raise InputError(f"sigma of {kind} must be a positive number, not {value}")
        if options.loss not in LOSSES:
            raise InputError(f"loss {options.loss!r} is not one of {', '.join(LOSSES)}")
        return cls(model, telemetry, pairs, options)

    def __init__(
        self, model: Model, telemetry: Telemetry, free: list[tuple[int, int]], options: FitOptions
    ) -> None:
        self.telemetry, self.free, self.options = telemetry, free, options
        table = model.craft.materials
        self.optics0 = np.stack([table.rho, table.beta, table.sigma], 1).astype(float)
        self.acc0 = accommodations_of(model)
        self.drag: LinearDrag | None = None
        self.flows: FlowGeometry | None = None
        self.names = [f"{table.names[m]}.{COEFFICIENTS[k]}" for m, k in free]
        self.n_free = len(free)
        self.paired = {m for m, k in free if k == 0} & {m for m, k in free if k == 2}
        self.n_scale = int(options.scale)
        self.n_bias = 3 * int(options.bias_torque)
        self.n_h0 = 3 * int("momentum" in telemetry.kinds)
        self.names += ["scale"] * self.n_scale
        self.names += [f"bias_torque_Nm.{a}" for a in "xyz"][: self.n_bias]
        self.names += [f"initial_momentum_Nms.{a}" for a in "xyz"][: self.n_h0]
        lower, upper, x0 = [], [], []
        for m, k in free:
            rho, _, sigma = self.optics0[m]
            value = self.optics0[m, k] if k < 3 else self.acc0[m, k - 4]
            top = 1.0
            if k > 2:  # an accommodation: [0, 1]
                top = 1.0
            elif k == 0 and m not in self.paired:
                top = 1.0 - sigma
            elif k == 2 and m in self.paired:
                value = sigma / (1.0 - rho) if rho < 1.0 else 0.0
            elif k == 2:
                top = 1.0 - rho
            lower.append(0.0)
            upper.append(top)
            x0.append(min(max(value, 0.0), top))
        lower += [0.0] * self.n_scale + [-np.inf] * (self.n_bias + self.n_h0)
        upper += [np.inf] * (self.n_scale + self.n_bias + self.n_h0)
        x0 += [1.0] * self.n_scale + [0.0] * (self.n_bias + self.n_h0)
        self.bounds = (np.array(lower), np.array(upper))
        self.x0 = np.array(x0)

    def start_momentum(self) -> None:
        if self.n_h0:  # the first momentum: the measured one less the modelled impulse, on average
            predicted, _ = self.predict(self.x0)
            offset = np.mean(self.telemetry.measured["momentum"] - predicted["momentum"], axis=0)
            self.x0[-3:] = offset

    # --- parameters -------------------------------------------------------------------------------
    def optics(self, x: NDArray) -> NDArray:
        optics = self.optics0.copy()
        for j, (m, k) in enumerate(self.free):
            if k < 2 or (k == 2 and m not in self.paired):
                optics[m, k] = x[j]
        for j, (m, k) in enumerate(self.free):
            if k == 2 and m in self.paired:
                optics[m, 2] = x[j] * (1.0 - optics[m, 0])
        return optics

    def physical(self, x: NDArray) -> NDArray:
        optics = self.optics(x)
        values = x.copy()
        for j, (m, k) in enumerate(self.free):
            values[j] = optics[m, k] if k < 3 else x[j]
        return values

    def accommodations(self, x: NDArray) -> NDArray:
        acc = self.acc0.copy()
        for j, (m, k) in enumerate(self.free):
            if k > 3:
                acc[m, k - 4] = x[j]
        return acc

    def initial_physical(self) -> NDArray:
        values = self.physical(self.x0)
        values[self.n_free : self.n_free + self.n_scale] = 1.0
        return values

    def physical_bounds(self) -> list[tuple[float, float]]:
        out = [(0.0, 1.0)] * self.n_free + [(0.0, np.inf)] * self.n_scale
        return out + [(-np.inf, np.inf)] * (self.n_bias + self.n_h0)

    def chain(self, x: NDArray) -> NDArray:
        """d physical / d internal parameters."""
        t = np.eye(len(x))
        optics = self.optics(x)
        for j, (m, k) in enumerate(self.free):
            if k == 2 and m in self.paired:
                i = next(i for i, (mm, kk) in enumerate(self.free) if mm == m and kk == 0)
                t[j, j] = 1.0 - optics[m, 0]
                t[j, i] = -x[j]
        return t

    # --- model ------------------------------------------------------------------------------------
    def predict(self, x: NDArray) -> tuple[dict[str, NDArray], dict[str, NDArray]]:
        """Modelled measurements (n, 3) and their derivatives (n, 3, p) by physical parameter."""
        loads_g, partials_g = self.forward.at(self.optics(x))
        cols = np.stack([partials_g[:, m, k] if k < 3 else partials_g[:, 0, 0] * 0 for m, k in self.free], 1)
        rows, scale = self.geometry.row_group, self.geometry.scale
        loads = loads_g[rows] * scale[:, None]
        partials = cols[rows] * scale[:, None, None]  # (n, n_free, 6)
        n, p = len(rows), len(x)
        factor = x[self.n_free] if self.n_scale else 1.0
        gas, gas_partials = np.zeros_like(loads), np.zeros_like(partials)
        if self.drag is not None and self.flows is not None:
            drag_g, drag_partials_g = self.drag.at(self.accommodations(x))
            flow_rows, density = self.flows.row_group, self.flows.scale
            gas = drag_g[flow_rows] * density[:, None]
            for j, (m, k) in enumerate(self.free):
                if k > 3:
                    gas_partials[:, j] = drag_partials_g[flow_rows, m, k - 4] * density[:, None]
        bias = x[self.n_free + self.n_scale : self.n_free + self.n_scale + self.n_bias]
        values, derivatives = {}, {}

        def part(sl: slice) -> tuple[NDArray, NDArray]:
            jac = np.zeros((n, 3, p))
            jac[:, :, : self.n_free] = np.swapaxes(factor * partials[:, :, sl] + gas_partials[:, :, sl], 1, 2)
            if self.n_scale:
                jac[:, :, self.n_free] = loads[:, sl]
            return factor * loads[:, sl] + gas[:, sl], jac

        torque, torque_jac = part(slice(3, 6))
        if self.n_bias:
            torque = torque + bias
            start = self.n_free + self.n_scale
            torque_jac[:, :, start : start + 3] = np.eye(3)
        kinds = self.telemetry.kinds
        if "torque" in kinds:
            values["torque"], derivatives["torque"] = torque, torque_jac
        if "accel" in kinds:
            force, force_jac = part(slice(0, 3))
            mass = float(self.options.mass_kg)  # type: ignore[arg-type]
            values["accel"], derivatives["accel"] = force / mass, force_jac / mass
        if "momentum" in kinds:
            rotation = self.telemetry.rotation
            if rotation is not None:
                torque = np.einsum("nij,nj->ni", rotation, torque)
                torque_jac = np.einsum("nij,njp->nip", rotation, torque_jac)
            t = self.telemetry.time_s
            h = cumulative_trapezoid(torque, t, axis=0, initial=0.0) + x[-3:]
            jac = cumulative_trapezoid(torque_jac, t, axis=0, initial=0.0)
            jac[:, :, -3:] = np.eye(3)
            values["momentum"], derivatives["momentum"] = h, jac
        return values, derivatives

    def sigmas(self, x: NDArray, weights: dict[str, float]) -> NDArray:
        """One-sigma uncertainties of the free coefficients at ``x`` (unscaled)."""
        jacobian = self.weighted_jacobian(x, weights)
        covariance = np.linalg.pinv(jacobian.T @ jacobian)
        return np.sqrt(np.clip(np.diag(covariance), 0.0, None))[: self.n_free]

    def residuals(self, x: NDArray) -> dict[str, NDArray]:
        values, _ = self.predict(x)
        return {kind: values[kind] - self.telemetry.measured[kind] for kind in values}

    def weighted_jacobian(self, x: NDArray, sigmas: dict[str, float]) -> NDArray:
        _, derivatives = self.predict(x)
        return np.concatenate([(derivatives[k] / sigmas[k]).reshape(-1, len(x)) for k in derivatives])

    def solve(self, x0: NDArray, sigmas: dict[str, float], loss: str) -> NDArray:
        n = sum(values.size for values in self.telemetry.measured.values())
        if n <= len(x0):
            raise InputError(
                f"{self.telemetry.source}: {n} measured values for {len(x0)} parameters",
                hint="give more rows, or free fewer coefficients",
            )
        kinds = self.telemetry.kinds

        def both(x: NDArray) -> tuple[NDArray, NDArray]:
            values, derivatives = self.predict(x)
            r = np.concatenate(
                [((values[k] - self.telemetry.measured[k]) / sigmas[k]).ravel() for k in kinds]
            )
            jac = np.concatenate([(derivatives[k] / sigmas[k]).reshape(-1, len(x)) for k in kinds])
            return r, jac @ self.chain(x)

        kept: dict[bytes, tuple[NDArray, NDArray]] = {}

        def memo(x: NDArray) -> tuple[NDArray, NDArray]:
            key = x.tobytes()
            if key not in kept:
                kept.clear()
                kept[key] = both(x)
            return kept[key]

        lower, upper = self.bounds
        start = np.clip(x0, lower, upper)
        solution = least_squares(
            lambda x: memo(x)[0],
            start,
            jac=lambda x: memo(x)[1],
            bounds=(lower, upper),
            loss=loss,
            x_scale="jac",
            xtol=1e-12,
            ftol=1e-12,
            gtol=1e-12,
            max_nfev=200,
        )
        return solution.x

    def series(self, x: NDArray, before: dict[str, NDArray]) -> dict[str, Series]:
        values, _ = self.predict(x)
        time = self.telemetry.time_s
        out = {}
        for kind in values:
            measured = self.telemetry.measured[kind]
            out[kind] = Series(time, measured, measured + before[kind], values[kind])
        return out
