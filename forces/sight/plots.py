"""Pictures of lines of sight: each point's map of the parts that block it over azimuth and elevation
(METHOD.md "Lines of sight"), drawn with matplotlib's Agg backend."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from sunwind.forces.sight.sky_map import SightMap

#: Most points drawn in one picture (the first ones); the netCDF holds every map.
MOST_PANELS = 12


def plot_maps(view: SightMap, path: str | Path) -> None:
    """Draw each point's map: the part each cell's line meets (white where clear), the edge of its field
    of view, and its blocked fraction with the error estimate in the title.

    Parameters
    ----------
    view : SightMap
        The maps (:func:`~sunwind.forces.sight.sky_map.blocked_map`).
    path : str or pathlib.Path
        The PNG to write; the first ``MOST_PANELS`` points are drawn.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import sunwind as sw
    >>> from sunwind.forces.sight import SightPoints, blocked_map
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
    >>> view = blocked_map(model, SightPoints.of(["top"], [[0.0, 0.0, 0.5]]), step_deg=10.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     png = pathlib.Path(folder) / "map.png"
    ...     plot_maps(view, png)
    ...     png.read_bytes()[:4]
    b'\\x89PNG'
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    names = view.points.names[:MOST_PANELS]
    columns = min(len(names), 3)
    rows = math.ceil(len(names) / columns)
    figure, axes = plt.subplots(
        rows, columns, figsize=(5.2 * columns, 2.9 * rows), squeeze=False, constrained_layout=True
    )
    parts = len(view.part_names)
    colours = ["#ffffff", "#404040"] + [plt.get_cmap("tab20")(k % 20) for k in range(parts)]
    palette = ListedColormap(colours)
    az, el = view.azimuth_deg, view.elevation_deg
    for k, name in enumerate(names):
        ax = axes.flat[k]
        code = view.blocking_part[k].astype(float) + 2  # -2 inside, -1 clear -> 0, 1, then the parts
        code = np.where(code == 1, 0, np.where(code == 0, 1, code))  # clear white, inside grey
        ax.pcolormesh(az, el, code, cmap=palette, vmin=-0.5, vmax=parts + 1.5, shading="nearest")
        if view.points.has_cone[k]:
            ax.contour(az, el, view.in_view[k].astype(float), levels=[0.5], colors="k", linewidths=1)
        ax.set_title(
            f"{name}: blocked {view.blocked_fraction[k]:.4f} +- {view.error_estimate[k]:.1e}", fontsize=9
        )
        ax.set_xlim(-180, 180)
        ax.set_ylim(-90, 90)
        ax.set_xlabel("azimuth atan2(y, x) [deg], body")
        ax.set_ylabel("elevation asin(z) [deg]")
    for ax in list(axes.flat)[len(names) :]:
        ax.axis("off")
    seen = sorted({int(p) for p in np.unique(view.blocking_part[: len(names)]) if p >= 0})
    handles = [plt.Rectangle((0, 0), 1, 1, color=colours[p + 2]) for p in seen]
    if handles:
        figure.legend(handles, [view.part_names[p] for p in seen], loc="outside lower center", ncols=6)
    figure.savefig(path, dpi=110)
    plt.close(figure)
