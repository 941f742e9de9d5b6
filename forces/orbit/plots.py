"""Pictures of an orbit run against time, eclipses shaded: torque and accumulated momentum
(:func:`plot_orbit`); each part's absorbed power and temperature, and the power by source
(:func:`plot_thermal`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.orbit.earth_terms import PART_SOURCES
from sunwind.forces.orbit.results import OrbitResult
from sunwind.forces.vocabulary import PART, absorbed_name
from sunwind.geometry.errors import InputError

#: Most parts :func:`plot_thermal` draws one by one; past it, the parts that absorb least are summed.
MAX_PARTS_DRAWN = 10


def plot_orbit(result: OrbitResult, path: str | Path) -> None:
    r"""Write a PNG of an orbit run: body torque (top) and ECI angular impulse (bottom) against time.

    Each panel draws the x, y, z components and the magnitude against hours from the epoch; the shadow
    is shaded grey where the Sun is even partly hidden. Matplotlib is imported (``Agg`` backend) only
    here.

    Parameters
    ----------
    result : OrbitResult
        The run, from :func:`~sunwind.forces.orbit.flight.fly`.
    path : str or Path
        The PNG file to write.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.plots import plot_orbit
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
    >>> nadir = sw.orbit.AttitudeLaw.parse("nadir")
    >>> result = sw.fly(cube, path, nadir, sw.orbit.OrbitLoads(SrpSetup(reflections="none")))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     png = pathlib.Path(folder) / "orbit.png"
    ...     plot_orbit(result, png)
    ...     png.read_bytes()[:4]
    b'\x89PNG'
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = result.series
    hours = s["time_s"] / 3600.0
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 6), constrained_layout=True)
    for axes, name, label in (
        (top, "torque_body_Nm", "torque, body [N m]"),
        (bottom, "angular_impulse_eci_Nms", "angular impulse, ECI [N m s]"),
    ):
        for i, axis in enumerate("xyz"):
            axes.plot(hours, s[name][:, i], label=axis)
        axes.plot(hours, np.linalg.norm(s[name], axis=1), "k--", lw=0.8, label="|.|")
        axes.set_ylabel(label)
        _shade_eclipses(axes, hours, s["solar_fraction"])
    top.legend(loc="upper right", ncols=4, fontsize="small")
    bottom.set_xlabel("time from the epoch [h]")
    top.set_title(f"{result.attributes['attitude']} - {result.attributes['terms']}; grey: eclipse")
    figure.savefig(path, dpi=110)
    plt.close(figure)


def plot_thermal(result: OrbitResult, path: str | Path) -> None:
    r"""Write a PNG of the heat an orbit run's parts take in: their temperatures (with ``thermal``, the
    equilibrium's or the transient's), the power each part absorbs, and the power of each source summed
    over the parts, against time.

    The panels share the time axis (hours from the epoch) and the eclipse shading of :func:`plot_orbit`.
    Each part has one colour in the temperature and power panels; past :data:`MAX_PARTS_DRAWN` parts, those
    that absorb least on average are summed into one line (and their temperatures left out). The bottom
    panel stacks the sources (solar, albedo, infrared, reflected) of the whole spacecraft. Matplotlib is
    imported (``Agg`` backend) only here.

    Parameters
    ----------
    result : OrbitResult
        A run with the Earth's radiation (:class:`~sunwind.forces.orbit.earth_terms.EarthTerms`).
    path : str or Path
        The picture to write.

    Raises
    ------
    InputError
        A run without the Earth's radiation: it has no absorbed powers.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.earth_terms import EarthTerms
    >>> from sunwind.forces.orbit.plots import plot_thermal
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> paint = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
    >>> cube = sw.load(sw.meshes.box(), uniform=paint, threads=1)
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
    >>> earth = EarthTerms(SrpSetup(reflections="none"), thermal=True)
    >>> result = sw.fly(cube, path, sw.orbit.AttitudeLaw.parse("nadir"), sw.orbit.OrbitLoads(earth=earth))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     png = pathlib.Path(folder) / "heat.png"
    ...     plot_thermal(result, png)
    ...     png.read_bytes()[:4]
    b'\x89PNG'
    """
    s = result.series
    if absorbed_name(PART, PART_SOURCES[0]) not in s:
        raise InputError(
            "the run has no absorbed powers to plot: they come with the Earth's radiation",
            hint="fly it with OrbitLoads(earth=EarthTerms(...))",
            parameters=("earth",),
        )
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    hours = s["time_s"] / 3600.0
    by_source = {source: s[absorbed_name(PART, source)] for source in PART_SOURCES}
    total = sum(by_source.values())
    drawn, rest = _parts_drawn(s["time_s"], total)
    temperature = s.get("part_temperature_K")
    rows = 3 if temperature is not None else 2
    figure, panels = plt.subplots(rows, 1, sharex=True, figsize=(10, 2.6 * rows), constrained_layout=True)
    colours = plt.get_cmap("tab10").colors
    if temperature is not None:
        for k, part in enumerate(drawn):
            panels[0].plot(hours, temperature[:, part], color=colours[k], label=result.part_names[part])
        mode = result.attributes.get("thermal", "equilibrium")
        panels[0].set_ylabel(f"temperature [K],\n{mode}")
    power = panels[-2]
    for k, part in enumerate(drawn):
        power.plot(hours, total[:, part], color=colours[k], label=result.part_names[part])
    if len(rest):
        power.plot(hours, total[:, rest].sum(axis=1), "k:", label=f"{len(rest)} other parts, summed")
    power.set_ylabel("absorbed per part [W]")
    power.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    bottom = panels[-1]
    bottom.stackplot(hours, *(v.sum(axis=1) for v in by_source.values()), labels=PART_SOURCES, alpha=0.8)
    bottom.set_ylabel("absorbed by source,\nall parts [W]")
    bottom.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    bottom.set_xlabel("time from the epoch [h]")
    for axes in panels:
        _shade_eclipses(axes, hours, s["solar_fraction"])
    panels[0].set_title(f"{result.attributes['attitude']} - {result.attributes['terms']}; grey: eclipse")
    figure.savefig(path, dpi=110)
    plt.close(figure)


def _parts_drawn(t: NDArray[np.float64], total: NDArray[np.float64]) -> tuple[list[int], NDArray[np.int64]]:
    """The parts drawn one by one (all, or the :data:`MAX_PARTS_DRAWN` - 1 that absorb most on average,
    in the model's order) and the rest."""
    n = total.shape[1]
    if n <= MAX_PARTS_DRAWN:
        return list(range(n)), np.array([], dtype=np.int64)
    mean = total.mean(axis=0) if len(t) < 2 else np.trapezoid(total, t, axis=0)
    order = np.argsort(-mean, kind="stable")
    return sorted(order[: MAX_PARTS_DRAWN - 1].tolist()), np.sort(order[MAX_PARTS_DRAWN - 1 :])


def _shade_eclipses(axes, hours: NDArray[np.float64], solar_fraction: NDArray[np.float64]) -> None:
    """Grid ``axes`` and shade its full height grey where the Sun is even partly hidden."""
    axes.grid(alpha=0.3)
    height = axes.get_xaxis_transform()  # x in data, y from the bottom (0) to the top (1) of the axes
    dark = solar_fraction < 1
    axes.fill_between(hours, 0, 1, where=dark, color="0.85", step="mid", transform=height, lw=0, zorder=0)
