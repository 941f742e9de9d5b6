"""The paper's Fig. 1: drag and solar-radiation force on a 1 m radius aluminium sphere against altitude.

Both forces come from sunwind itself on a meshed sphere: drag from NRLMSIS 2.1 at the circular-orbit
speed (Sentman, full accommodation to a 300 K wall), sunlight at 1 au. The paper (after Kovtunenko
et al. 1977) finds the atmosphere ahead below about 500 km and sunlight ahead above about 1000 km, the
crossover in between depending on solar activity; here it is found for low, moderate and high
activity (F10.7 = F10.7a = 70, 150, 250 sfu; Ap = 4) at local midnight on the equator (the default
place and time of :func:`sunwind.forces.gas.atmosphere.nrlmsis`). Aluminium: reflectivity 0.85, nine tenths of
it specular (the sphere's SRP depends on the diffuse share only: ``P pi R^2 (1 + 4/9 rho_d)``).

Run ``python -m sunwind.validation.figure1 [-o figure1.png]``: prints the table and the crossover altitudes
and writes the plot.
"""

from __future__ import annotations

import argparse
import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.drag import drag
from sunwind.forces.gas import AtmosphereWarning, circular_speed, nrlmsis
from sunwind.forces.srp import srp
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes.primitives import sphere

#: Altitudes of the figure [km].
ALTITUDES_KM = np.arange(200.0, 1501.0, 50.0)
#: Solar activity levels: name -> F10.7 = F10.7a [sfu].
ACTIVITY = {"low": 70.0, "moderate": 150.0, "high": 250.0}
#: Aluminium: optics (reflectivity, specular share) and gas-surface law.
ALUMINIUM = Material("aluminium", 0.85, 0.9, gas=GasSurface("sentman", wall_temperature_K=300.0))


@dataclass(frozen=True)
class Figure1:
    """Force magnitudes [N] against altitude [km] and the crossover altitude per activity level.

    Attributes
    ----------
    altitudes_km : (n,) float64
        Altitudes [km].
    srp_N : float
        ``|F|`` of solar radiation pressure at 1 au [N], the same at every altitude.
    drag_N : dict of str to (n,) float64
        ``|F|`` of drag at each altitude [N], by activity level (:data:`ACTIVITY`).
    crossover_km : dict of str to float
        Altitude where drag falls to the SRP force [km], by activity level; NaN if it does not.

    Examples
    --------
    >>> result = figure1(np.array([500.0, 900.0]), subdivisions=4)
    >>> list(result.drag_N), result.drag_N["low"].shape
    (['low', 'moderate', 'high'], (2,))
    """

    altitudes_km: NDArray[np.float64]
    srp_N: float
    drag_N: dict[str, NDArray[np.float64]]
    crossover_km: dict[str, float]


def aluminium_sphere(subdivisions: int = 48) -> Spacecraft:
    """The 1 m radius sphere, aluminium all over.

    Parameters
    ----------
    subdivisions : int, optional
        Resolution of :func:`sunwind.meshes.primitives.sphere`.

    Returns
    -------
    Spacecraft
        The sphere with the sample's aluminium optics.

    Examples
    --------
    >>> aluminium_sphere(4)
    <Spacecraft '<sphere>': 40 facets, 40 sides, 1 parts, 1 materials>
    """
    return build_spacecraft(sphere(1.0, subdivisions), uniform=ALUMINIUM)


def crossover(altitudes_km: NDArray, drag_N: NDArray, srp_N: float) -> float:
    """Altitude [km] where drag falls to the SRP force, interpolating ``log(drag)`` linearly; NaN if none.

    Parameters
    ----------
    altitudes_km : (n,) float64
        Altitudes [km], increasing.
    drag_N : (n,) float64
        Drag magnitude at each [N], > 0.
    srp_N : float
        SRP magnitude [N].

    Returns
    -------
    float
        The first crossing [km], or NaN when drag stays above or below ``srp_N``.

    Examples
    --------
    >>> round(crossover(np.array([400.0, 500.0, 600.0]), np.array([1e-4, 1e-5, 1e-6]), 10**-5.5), 6)
    550.0
    """
    excess = np.log(drag_N / srp_N)
    below = np.flatnonzero((excess[:-1] > 0) & (excess[1:] <= 0))
    if len(below) == 0:
        return math.nan
    i = below[0]
    share = excess[i] / (excess[i] - excess[i + 1])
    return float(altitudes_km[i] + share * (altitudes_km[i + 1] - altitudes_km[i]))


def figure1(altitudes_km: NDArray = ALTITUDES_KM, subdivisions: int = 48) -> Figure1:
    """Drag and SRP magnitudes over ``altitudes_km`` for every :data:`ACTIVITY` level.

    The sphere flies at circular-orbit speed through NRLMSIS (default place and time, the level's
    F10.7 as daily and 81-day values); SRP at 1 au; neither reflects between facets.

    Parameters
    ----------
    altitudes_km : (n,) float64, optional
        Altitudes [km]; default :data:`ALTITUDES_KM`.
    subdivisions : int, optional
        Resolution of the sphere (:func:`aluminium_sphere`).

    Returns
    -------
    Figure1
        The forces and the crossover altitudes.

    Examples
    --------
    >>> result = figure1(np.array([500.0, 900.0]), subdivisions=4)
    >>> {level: round(km) for level, km in result.crossover_km.items() if km == km}
    {'moderate': 636, 'high': 737}
    """
    craft = aluminium_sphere(subdivisions)
    direction = np.array([1.0, 0.0, 0.0])
    light = srp(craft, direction, distance_au=1.0, reflections="none")
    srp_N = float(np.linalg.norm(light.force_N))
    drag_N = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AtmosphereWarning)  # extrapolated exosphere above 1000 km: stated
        for level, f107 in ACTIVITY.items():
            forces = []
            for altitude in altitudes_km:
                air = nrlmsis(float(altitude), f107=f107, f107a=f107)
                velocity = circular_speed(float(altitude)) * direction
                forces.append(np.linalg.norm(drag(craft, velocity, air, reflections="none").force_N))
            drag_N[level] = np.array(forces)
    crossings = {level: crossover(altitudes_km, f, srp_N) for level, f in drag_N.items()}
    return Figure1(np.asarray(altitudes_km, dtype=float), srp_N, drag_N, crossings)


def plot(result: Figure1, path: str) -> None:
    """Write the figure as PNG: both forces on a log scale against altitude.

    Parameters
    ----------
    result : Figure1
        The forces to draw.
    path : str
        File to write.

    Examples
    --------
    >>> import os, tempfile
    >>> result = figure1(np.array([500.0, 900.0]), subdivisions=4)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     plot(result, os.path.join(folder, "figure1.png"))
    ...     os.listdir(folder)
    ['figure1.png']
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for level, forces in result.drag_N.items():
        ax.semilogy(result.altitudes_km, forces, "o-", ms=3, label=f"drag, F10.7 = {ACTIVITY[level]:g}")
    ax.axhline(result.srp_N, color="k", ls="--", label="solar radiation, 1 au")
    for altitude in result.crossover_km.values():
        if math.isfinite(altitude):
            ax.axvline(altitude, color="0.7", lw=0.8)
            ax.annotate(f"{altitude:.0f} km", (altitude, result.srp_N), rotation=90, fontsize=7, va="bottom")
    ax.set_xlabel("altitude [km]")
    ax.set_ylabel("force [N]")
    ax.set_title("1 m radius aluminium sphere: drag (NRLMSIS 2.1, circular orbit) and SRP")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv: list[str] | None = None) -> None:
    """Compute the figure, print its table and crossovers, and write it as PNG.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments (``-o``/``--output``: the PNG file; ``--quick``: two altitudes on a
        coarse sphere, a second instead of a minute); default ``sys.argv[1:]``.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> folder = tempfile.TemporaryDirectory()
    >>> main(["--quick", "--output", str(pathlib.Path(folder.name) / "figure1.png")])  # doctest: +ELLIPSIS
    SRP on the sphere at 1 au: ...
    wrote .../figure1.png
    >>> folder.cleanup()
    """
    parser = argparse.ArgumentParser(
        prog="python -m sunwind.validation.figure1", description=__doc__.split("\n")[0]
    )
    parser.add_argument("-o", "--output", default="figure1.png", help="PNG file to write")
    parser.add_argument("--quick", action="store_true", help="two altitudes on a coarse sphere (a check)")
    args = parser.parse_args(argv)
    result = figure1(np.array([300.0, 900.0]), subdivisions=4) if args.quick else figure1()
    print(f"SRP on the sphere at 1 au: {result.srp_N:.4e} N")
    print("altitude_km  " + "  ".join(f"drag_{level}_N" for level in result.drag_N))
    for i, altitude in enumerate(result.altitudes_km):
        print(f"{altitude:11.0f}  " + "  ".join(f"{f[i]:.4e}" for f in result.drag_N.values()))
    for level, altitude in result.crossover_km.items():
        print(f"crossover, {level} activity (F10.7 = {ACTIVITY[level]:g}): {altitude:.0f} km")
    plot(result, args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
