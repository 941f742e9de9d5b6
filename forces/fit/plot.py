"""The picture of a fit: for each measurement kind, the measured and modelled series (before and after
the fit) per component, and the residuals after it."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from sunwind.forces.fit.report import UNITS, FitResult


def plot_fit(result: FitResult, path: str | Path) -> Path:
    """Plot measured and modelled series and the residuals of a fit to a PNG (or any matplotlib format).

    Parameters
    ----------
    result : FitResult
    path : path
        The file to write; its suffix picks the format.

    Returns
    -------
    Path

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> from sunwind.forces.fit.report import Series
    >>> t = np.arange(5.0)
    >>> series = {"torque": Series(t, np.ones((5, 3)), np.zeros((5, 3)), np.ones((5, 3)))}
    >>> result = FitResult(("a.reflectivity",), np.ones(1), np.zeros(1), np.ones(1), np.eye(1),
    ...                    np.ones(1), 1.0, 14, False, (), series=series, sigmas={"torque": 1.0})
    >>> out = plot_fit(result, pathlib.Path(tempfile.mkdtemp()) / "fit.png")
    >>> out.stat().st_size > 0
    True
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kinds = list(result.series)
    figure, axes = plt.subplots(
        2,
        len(kinds),
        figsize=(max(8.0, 6.0 * len(kinds)), 7.0),
        squeeze=False,
        sharex="col",
        constrained_layout=True,
    )
    colours = ("tab:blue", "tab:orange", "tab:green")
    for column, kind in enumerate(kinds):
        series = result.series[kind]
        hours = (series.time_s - series.time_s[0]) / 3600.0
        top, bottom = axes[0, column], axes[1, column]
        for k, axis in enumerate("xyz"):
            colour = colours[k]
            top.plot(
                hours, series.measured[:, k], ".", ms=2, color=colour, alpha=0.4, label=f"{axis} measured"
            )
            top.plot(hours, series.before[:, k], "--", lw=0.8, color=colour, label=f"{axis} before")
            top.plot(hours, series.after[:, k], "-", lw=1.2, color=colour, label=f"{axis} fitted")
            residual = series.measured[:, k] - series.after[:, k]
            bottom.plot(hours, residual, ".", ms=2, color=colour, label=axis)
        unit = UNITS[kind]
        top.set_title(f"{kind}: RMS residual {series.rms_before:.3g} -> {series.rms_after:.3g} {unit}")
        top.set_ylabel(f"{kind} [{unit}]")
        bottom.set_ylabel(f"measured - fitted [{unit}]")
        bottom.set_xlabel("time [h]")
        bottom.axhline(0.0, color="k", lw=0.5)
        sigma = result.sigmas.get(kind)
        if sigma is not None and np.isfinite(sigma):
            for sign in (-1.0, 1.0):
                bottom.axhline(sign * sigma, color="grey", lw=0.5, ls=":")
        top.legend(fontsize=6, ncol=3)
        bottom.legend(fontsize=6, ncol=3)
    shown = [
        f"{name} {value:.4g} +- {error:.2g}" for name, (value, error) in result_estimates(result).items()
    ]
    lines = [", ".join(shown[k : k + 2]) for k in range(0, len(shown), 2)]
    figure.suptitle("\n".join(["sunwind fit", *lines]), fontsize=8)
    out = Path(path)
    figure.savefig(out, dpi=120)
    plt.close(figure)
    return out


def result_estimates(result: FitResult) -> dict[str, tuple[float, float]]:
    """The fitted coefficients (nuisance terms left out) with their one-sigma uncertainties.

    Parameters
    ----------
    result : FitResult

    Returns
    -------
    dict of str to (float, float)

    Examples
    --------
    >>> result = FitResult(("a.reflectivity", "scale"), np.ones(2), np.zeros(2), np.ones(2), np.eye(2),
    ...                    np.ones(2), 1.0, 14, False, ())
    >>> result_estimates(result)
    {'a.reflectivity': (1.0, 0.0)}
    """
    return {name: result.estimate(name) for name in result.coefficients}
