"""What a fit gives: the estimates with their uncertainties, correlations, the singular values of the
weighted Jacobian and the combinations the data cannot separate, residuals before and after, as a
record (:class:`FitResult`) with its JSON and text, and the materials file with the fitted values.

>>> UNITS["torque"], JSON_KEYS["momentum"]
('N m', 'momentum_Nms')
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import load_materials, toml_key

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

UNITS = {"torque": "N m", "momentum": "N m s", "accel": "m/s^2"}
JSON_KEYS = {"torque": "torque_Nm", "momentum": "momentum_Nms", "accel": "accel_m_s2"}
#: A singular value of the column-normalised weighted Jacobian below this share of the largest marks a
#: combination of parameters the data cannot separate.
SEPARABLE = 1e-3
#: Parameters correlated beyond this are said to be.
CORRELATED = 0.99
#: Share of a null vector above which a parameter is named in it.
NAMED = 0.2


@dataclass(frozen=True, eq=False)
class Series:
    """One measurement kind along the telemetry: measured, modelled before and after the fit.

    Attributes
    ----------
    time_s : (n,) float64
    measured, before, after : (n, 3) float64

    Examples
    --------
    >>> s = Series(np.arange(2.0), np.ones((2, 3)), np.zeros((2, 3)), np.ones((2, 3)))
    >>> s.rms_before, s.rms_after
    (1.0, 0.0)
    """

    time_s: NDArray[np.float64]
    measured: NDArray[np.float64]
    before: NDArray[np.float64]
    after: NDArray[np.float64]

    @property
    def rms_before(self) -> float:
        """RMS of the residual (model - measured) over every component, before the fit."""
        return float(np.sqrt(np.mean((self.before - self.measured) ** 2)))

    @property
    def rms_after(self) -> float:
        """RMS of the residual after the fit."""
        return float(np.sqrt(np.mean((self.after - self.measured) ** 2)))


def diagnose(
    names: list[str],
    values: NDArray,
    initial: NDArray,
    jacobian: NDArray,
    residual: NDArray,
    scaled: bool,
) -> dict[str, object]:
    """Uncertainties, correlations, singular values and warnings of a solution.

    Parameters
    ----------
    names : list of str
        The parameters.
    values, initial : (p,) float64
        Estimates and starting values.
    jacobian : (m, p) float64
        Weighted Jacobian at the solution, by physical parameter.
    residual : (m,) float64
        Weighted residuals at the solution.
    scaled : bool
        Scale the covariance by chi2/dof (a weight came from the residuals).

    Returns
    -------
    dict
        The fields of :class:`FitResult` it makes.

    Examples
    --------
    >>> out = diagnose(["a", "b"], np.zeros(2), np.zeros(2), np.array([[1.0, 1.0], [2.0, 2.0], [1.0, 1.0]]),
    ...                np.zeros(3), False)
    >>> out["warnings"][0][:41]
    'the data cannot separate a and b (singula'
    """
    m, p = jacobian.shape
    norms = np.linalg.norm(jacobian, axis=0)
    warnings = [
        f"the data do not depend on {names[j]}: fix it or add data that do"
        for j in np.flatnonzero(norms == 0)
    ]
    safe = np.where(norms > 0, norms, 1.0)
    _, s, vt = np.linalg.svd(jacobian / safe, full_matrices=False)
    singular = np.linalg.svd(jacobian, compute_uv=False)
    dof = m - p
    chi2 = float(residual @ residual)
    chi2_dof = chi2 / dof if dof > 0 else math.nan
    top = s[0] if len(s) and s[0] > 0 else 1.0
    kept = s > 1e-12 * top
    inverse = (vt[kept].T / s[kept] ** 2) @ vt[kept]
    covariance = inverse / np.outer(safe, safe) * (chi2_dof if scaled and dof > 0 else 1.0)
    errors = np.sqrt(np.clip(np.diag(covariance), 0.0, None))
    lost = np.zeros(p, bool)
    for i in np.flatnonzero(s < SEPARABLE * top):
        v = vt[i]
        named = np.flatnonzero(np.abs(v) > NAMED)
        if not kept[i]:
            lost[named] = True
        terms = " ".join(f"{v[j]:+.2f} {names[j]}" for j in named)
        warnings.append(
            f"the data cannot separate {' and '.join(names[j] for j in named)} (singular value "
            f"{s[i] / top:.1e} of the largest, column-normalised; the combination {terms} is undetermined): "
            "hold one of them (drop its --free) or add data at other Sun angles"
        )
    errors[lost | (norms == 0)] = math.nan
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = covariance / np.outer(errors, errors)
    for i in range(p):
        for j in range(i + 1, p):
            c = correlation[i, j]
            if np.isfinite(c) and abs(c) > CORRELATED:
                warnings.append(
                    f"{names[i]} and {names[j]} are correlated {c:+.4f}: the data fix mostly a combination"
                    " of them"
                )
    return {
        "names": tuple(names),
        "values": np.asarray(values, float),
        "errors": errors,
        "initial": np.asarray(initial, float),
        "correlation": correlation,
        "singular_values": singular,
        "chi2_dof": chi2_dof,
        "dof": dof,
        "scaled": scaled,
        "warnings": tuple(warnings),
    }


def _number(value: float) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


@dataclass(frozen=True, eq=False)
class FitResult:
    """The outcome of :func:`~sunwind.forces.fit.fit`.

    Attributes
    ----------
    names : tuple of str
        Parameters: the free coefficients, then ``scale``, ``bias_torque_Nm.x..z`` and
        ``initial_momentum_Nms.x..z`` when fitted.
    values, errors, initial : (p,) float64
        Estimates, their one-sigma uncertainties (NaN where the data cannot fix one), starting values.
    correlation : (p, p) float64
    singular_values : (p,) float64
        Of the weighted Jacobian at the solution, largest first.
    chi2_dof : float
        Weighted chi-square per degree of freedom.
    dof : int
    scaled : bool
        Whether the covariance was scaled by ``chi2_dof`` (a sigma came from the residuals).
    warnings : tuple of str
    bounds : list of (float, float)
        Each parameter's physical bounds.
    series : dict of str to Series
        Each measurement kind: measured, modelled before and after.
    sigmas : dict of str to float
        The sigma each kind was weighted by.
    notices : tuple of str
    facts : dict
        Rows, geometries, model evaluations, timing [s].
    materials : tuple of str
        The model's materials.

    Examples
    --------
    >>> result = FitResult(("a.reflectivity",), np.array([0.5]), np.array([0.01]), np.array([0.4]),
    ...     np.eye(1), np.ones(1), 1.0, 10, False, ())
    >>> result.to_json()["estimates"]
    {'a.reflectivity': {'value': 0.5, 'sigma': 0.01, 'initial': 0.4}}
    """

    names: tuple[str, ...]
    values: NDArray[np.float64]
    errors: NDArray[np.float64]
    initial: NDArray[np.float64]
    correlation: NDArray[np.float64]
    singular_values: NDArray[np.float64]
    chi2_dof: float
    dof: int
    scaled: bool
    warnings: tuple[str, ...]
    bounds: list[tuple[float, float]] = field(default_factory=list)
    series: Mapping[str, Series] = field(default_factory=dict)
    sigmas: Mapping[str, float] = field(default_factory=dict)
    notices: tuple[str, ...] = ()
    facts: Mapping[str, object] = field(default_factory=dict)
    materials: tuple[str, ...] = ()

    def estimate(self, name: str) -> tuple[float, float]:
        """The value and one-sigma uncertainty of one parameter.

        Parameters
        ----------
        name : str

        Returns
        -------
        tuple of float

        Examples
        --------
        >>> FitResult(("s",), np.ones(1), np.zeros(1), np.ones(1), np.eye(1), np.ones(1), 1.0, 1, False,
        ...           ()).estimate("s")
        (1.0, 0.0)
        """
        k = self.names.index(name)
        return float(self.values[k]), float(self.errors[k])

    @property
    def coefficients(self) -> dict[str, float]:
        """The fitted coefficients by ``MATERIAL.COEFFICIENT`` (the nuisance terms left out)."""
        nuisance = ("bias_torque_Nm.", "initial_momentum_Nms.")
        return {
            n: float(v)
            for n, v in zip(self.names, self.values, strict=True)
            if n != "scale" and not n.startswith(nuisance)
        }

    def to_json(self) -> dict:
        """The result as plain JSON types (NaN and infinity as null).

        Returns
        -------
        dict
            ``estimates``, ``correlation``, ``singular_values``, ``residual_rms_before``,
            ``residual_rms_after``, ``chi2_dof``, ``warnings`` and what the fit did.

        Examples
        --------
        >>> FitResult(("s",), np.ones(1), np.zeros(1), np.ones(1), np.eye(1), np.ones(1), 1.0, 1, False,
        ...           ()).to_json()["correlation"]
        {'s': {'s': 1.0}}
        """
        names = self.names
        return {
            "estimates": {
                n: {"value": _number(v), "sigma": _number(e), "initial": _number(i)}
                for n, v, e, i in zip(names, self.values, self.errors, self.initial, strict=True)
            },
            "correlation": {
                a: {b: _number(self.correlation[i, j]) for j, b in enumerate(names)}
                for i, a in enumerate(names)
            },
            "singular_values": [_number(s) for s in self.singular_values],
            "residual_rms_before": {JSON_KEYS[k]: s.rms_before for k, s in self.series.items()},
            "residual_rms_after": {JSON_KEYS[k]: s.rms_after for k, s in self.series.items()},
            "sigma_used": {JSON_KEYS[k]: v for k, v in self.sigmas.items()},
            "chi2_dof": _number(self.chi2_dof),
            "dof": self.dof,
            "covariance_scaled_by_chi2_dof": self.scaled,
            "warnings": list(self.warnings),
            "notices": list(self.notices),
            **{key: value for key, value in self.facts.items()},
        }

    def lines(self) -> list[str]:
        """The result as text, one line each.

        Returns
        -------
        list of str

        Examples
        --------
        >>> FitResult(("s",), np.ones(1), np.zeros(1), np.ones(1), np.eye(1), np.ones(1), 1.0, 1, False,
        ...           ()).lines()[1].split()
        ['parameter', 'initial', 'estimate', '1-sigma']
        """
        facts = self.facts
        width = max([len(n) for n in self.names] + [9])
        out = [
            f"fit of {len(self.names)} parameters to {facts.get('rows', '?')} rows "
            f"({facts.get('geometries', '?')} geometries, "
            f"model run {facts.get('model_evaluations', '?')} times)",
            f"  {'parameter':<{width}}  {'initial':>13}  {'estimate':>13}  {'1-sigma':>11}",
        ]
        for n, v, e, i in zip(self.names, self.values, self.errors, self.initial, strict=True):
            sigma = f"{e:11.3e}" if math.isfinite(e) else f"{'undetermined':>11}"
            out.append(f"  {n:<{width}}  {i:13.6g}  {v:13.6g}  {sigma}")
        out.append(f"  {'residual RMS':<{width}}  {'before':>13}  {'after':>13}  {'sigma used':>11}")
        for kind, s in self.series.items():
            label = f"{kind} [{UNITS[kind]}]"
            out.append(
                f"  {label:<{width}}  {s.rms_before:13.4e}  {s.rms_after:13.4e}  {self.sigmas[kind]:11.3e}"
            )
        scaled = " (uncertainties scaled by sqrt(chi2/dof))" if self.scaled else ""
        out.append(f"  chi2/dof {self.chi2_dof:.4f} ({self.dof} degrees of freedom){scaled}")
        out.append(
            "  singular values of the weighted Jacobian: "
            + " ".join(f"{s:.3e}" for s in self.singular_values)
        )
        if len(self.names) > 1:
            out.append("  correlation:")
            for i, n in enumerate(self.names):
                row = " ".join(f"{c:+6.3f}" if math.isfinite(c) else "   nan" for c in self.correlation[i])
                out.append(f"    {n:<{width}}  {row}")
        return out


def write_materials(result: FitResult, source: str | Path | None, path: str | Path) -> Path:
    """Write the materials file ``source`` again with the fitted coefficients, everything else kept.

    Parameters
    ----------
    result : FitResult
    source : path or None
        The materials TOML file the model was loaded with.
    path : path
        Where to write.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        No materials file, or a fitted material without a ``[materials.NAME]`` table in it.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> text = "[materials.wing]\\nreflectivity = 0.3  # rho\\nspecular_fraction = 0.5\\n"
    >>> _ = (folder / "m.toml").write_text(text)
    >>> result = FitResult(("wing.reflectivity",), np.array([0.25]), np.array([0.01]), np.array([0.3]),
    ...                    np.eye(1), np.ones(1), 1.0, 9, False, ())
    >>> print(write_materials(result, folder / "m.toml", folder / "fitted.toml").read_text().splitlines()[1])
    reflectivity = 0.25  # fitted by sunwind fit, +- 0.01 (was 0.3)
    """
    if source is None:
        raise InputError(
            "--write-materials rewrites the materials file, and the model has none",
            hint="load the model with -m MATERIALS.toml",
        )
    lines = Path(source).read_text(encoding="utf-8").splitlines()
    errors = dict(zip(result.names, result.errors, strict=True))
    initial = dict(zip(result.names, result.initial, strict=True))
    for name, value in result.coefficients.items():
        material, _, coefficient = name.rpartition(".")
        start = _table(lines, material)
        if start is None:
            raise InputError(
                f"no [materials.{toml_key(material)}] table for the fitted {name}",
                path=str(source),
                hint="give the material its own table in the materials file",
            )
        end = next((k for k in range(start + 1, len(lines)) if lines[k].lstrip().startswith("[")), len(lines))
        note = f"  # fitted by sunwind fit, +- {errors[name]:.3g} (was {initial[name]:.6g})"
        text = f"{coefficient} = {value!r}{note}"
        key = re.compile(rf"^\s*{coefficient}\s*=")
        found = next((k for k in range(start + 1, end) if key.match(lines[k])), None)
        if found is None:
            lines.insert(start + 1, text)
        else:
            lines[found] = text
    out = Path(path)
    out.write_text("\n".join(lines) + "\n", encoding="utf-8")
    load_materials(out)  # what was written loads
    return out


def _table(lines: list[str], material: str) -> int | None:
    """The line of ``[materials.MATERIAL]``."""
    for k, line in enumerate(lines):
        text = line.strip()
        if not text.startswith("[") or text.startswith("[["):
            continue
        try:
            parsed = tomllib.loads(text)
        except tomllib.TOMLDecodeError:
            continue
        if list(parsed) == ["materials"] and list(parsed["materials"]) == [material]:
            return k
    return None
