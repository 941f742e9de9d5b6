"""A picture of an orbit run: torque and accumulated momentum against time, eclipse shaded."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from sunwind.forces.orbit.results import OrbitResult


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
        axes.grid(alpha=0.3)
        low, high = axes.get_ylim()
        axes.fill_between(hours, low, high, where=s["solar_fraction"] < 1, color="0.85", step="mid", zorder=0)
        axes.set_ylim(low, high)
    top.legend(loc="upper right", ncols=4, fontsize="small")
    bottom.set_xlabel("time from the epoch [h]")
    top.set_title(f"{result.attributes['attitude']} - {result.attributes['terms']}; grey: eclipse")
    figure.savefig(path, dpi=110)
    plt.close(figure)
