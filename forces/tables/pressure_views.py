"""3-D views of a spacecraft coloured by the pressure on each facet, for a sweep table's model at one Sun
or flow direction, the camera looking from the side the load comes from (``sunwind plot``).

Figures are drawn on ``matplotlib.figure.Figure`` objects rendered by Agg, without pyplot.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d import proj3d
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.drag import drag
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.model import Model, ModelSource
from sunwind.forces.srp import srp
from sunwind.forces.tables.dataset import DIRECTION, kinds_of
from sunwind.geometry.directions import azel_to_vector, checked_azel, unit_vector, vector_to_azel
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import Spacecraft

#: The kinds whose facet pressure a 3-D view shows (at one Sun or flow direction).
_VIEWED = ("srp", "drag")
#: A 3-D view whose camera is within this angle [deg] of the line of the Sun or flow draws no arrow
#: for it: seen end-on, the arrow would stand on the model.
_END_ON_DEG = 20.0


def plot_facet_pressure(
    craft: Spacecraft,
    pressure_Pa: ArrayLike,
    direction: ArrayLike,
    path: str | Path,
    label: str = "Sun",
    *,
    view_azel: tuple[float, float] | None = None,
) -> Path:
    """Write a 3-D view of the spacecraft with each facet coloured by its pressure, and a colour bar.

    The figure is that of :func:`pressure_figure`.

    Parameters
    ----------
    craft : Spacecraft
        The model; ``craft.triangles`` (n_facets, 3, 3) [m], body frame.
    pressure_Pa : (n_facets,) float
        Pressure on each facet [Pa].
    direction : (3,) float
        Sun vector or flow vector ``u``, body frame: the side the load comes from.
    path : path
        PNG file to write.
    label : str
        What ``direction`` is, in the title and on its arrow.
    view_azel : (float, float), optional
        The camera's azimuth and elevation [deg], body frame (``Axes3D.view_init``). Default: at
        ``direction``, so that the loaded side faces the viewer (from the Sun; for drag, from upstream).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InputError
        ``pressure_Pa`` not one finite value per facet, a zero direction, or a ``view_azel`` that is not
        two finite angles with the elevation within [-90, 90].

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> import os, tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = os.path.join(folder, "p.png")
    ...     path = plot_facet_pressure(cube.craft, np.ones(12), [0.0, 0.0, 1.0], target)
    ...     path.name, path.exists()
    ('p.png', True)
    """
    out = Path(path)
    pressure_figure(craft, pressure_Pa, direction, label, view_azel=view_azel).savefig(out, dpi=110)
    return out


def pressure_figure(
    craft: Spacecraft,
    pressure_Pa: ArrayLike,
    direction: ArrayLike,
    label: str = "Sun",
    *,
    view_azel: tuple[float, float] | None = None,
) -> Figure:
    """The 3-D view of :func:`plot_facet_pressure`, not yet written.

    The camera looks from ``view_azel`` (default: from ``direction``) with an orthographic projection,
    as the Sun's parallel rays see the model; the model fills the frame, with the body axes drawn small
    in a corner and its size in the title. When the camera is more than 20 deg off the line of
    ``direction``, an arrow labelled ``label`` comes in from that side toward the body, as the photons
    or molecules do (seen end-on it would hide the model: the title gives the direction).

    Parameters
    ----------
    craft : Spacecraft
        The model, body frame.
    pressure_Pa : (n_facets,) float
        Pressure on each facet [Pa].
    direction : (3,) float
        Sun vector or flow vector ``u``, body frame.
    label : str, optional
        What ``direction`` is, in the title and on its arrow.
    view_azel : (float, float), optional
        The camera's azimuth and elevation [deg]; default from ``direction``.

    Returns
    -------
    matplotlib.figure.Figure
        One 3-D Axes (the model, its camera at ``ax.azim``, ``ax.elev``), a colour bar and the axes
        inset.

    Raises
    ------
    InputError
        What :func:`plot_facet_pressure` refuses.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> figure = pressure_figure(cube.craft, np.ones(12), [0.0, 0.0, 1.0])
    >>> len(figure.axes)  # the model, the colour bar, the axes inset
    3
    """
    triangles = craft.triangles
    pressure = np.asarray(pressure_Pa, dtype=np.float64)
    if pressure.shape != (len(triangles),) or not np.isfinite(pressure).all():
        raise InputError(
            f"pressure_Pa has shape {pressure.shape}, expected one finite value per facet ({len(triangles)},)"
        )
    d = unit_vector(direction, "direction")
    azimuth, elevation = vector_to_azel(d) if view_azel is None else checked_azel(*view_azel, "view_azel")
    points = triangles.reshape(-1, 3)
    model_low, model_high = points.min(axis=0), points.max(axis=0)
    mappable = ScalarMappable(norm=Normalize(*_limits(pressure)), cmap="viridis")

    fig = Figure(figsize=(7.5, 6.5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(triangles, facecolors=mappable.to_rgba(pressure), linewidths=0))
    facing = float(azel_to_vector(azimuth, elevation) @ d)
    arrow = abs(facing) < math.cos(math.radians(_END_ON_DEG))
    ax.computed_zorder = False  # the facets are sorted by depth among themselves, the arrow as below
    if arrow:
        centre = (model_low + model_high) / 2
        head = centre + _reach(centre, model_low, model_high, d) * d  # on the model's box
        tail = head + 0.25 * float(np.max(model_high - model_low)) * d
        # outside the model's box on the side d points to: in front of the model when the camera is on
        # that side too, else behind it
        style = {"color": "tab:red", "zorder": 3 if facing > 0 else 0}
        ax.quiver(*tail, *(head - tail), linewidth=2, arrow_length_ratio=0.25, **style)
        points = np.vstack([points, tail])
    ax.set_proj_type("ortho")
    ax.view_init(elev=elevation, azim=azimuth)
    _fill(ax, *view_box(triangles), points)
    if arrow:  # the label on the frame's side of the arrow's tail, not over its edge
        x, _, _ = proj3d.proj_transform(*tail, ax.get_proj())
        ax.text(*tail, f" {label} ", ha="right" if x > 0 else "left", va="center", **style)
    ax.set_axis_off()
    _axes_inset(fig, azimuth, elevation)
    size = " x ".join(f"{side:.3g}" for side in model_high - model_low)
    ax.set_title(
        f"pressure on each facet [Pa], body frame; model {size} m\n{label} from ({d[0]:.3f}, {d[1]:.3f}, "
        f"{d[2]:.3f}); seen from az {azimuth:.4g}, el {elevation:.4g} deg"
    )
    fig.colorbar(mappable, ax=ax, shrink=0.7, label="pressure [Pa]")
    return fig


def view_box(triangles: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The limits [m] of a 3-D view of ``triangles``: their bounding box, made at least 10 % deep.

    Every side is at least 10 % of the largest, so a flat sheet gets some depth; the box keeps about
    the same centre.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of the facets [m].

    Returns
    -------
    low : (3,) float64
        Lower corner of the view [m].
    high : (3,) float64
        Upper corner of the view [m].

    Examples
    --------
    >>> low, high = view_box(np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]))
    >>> low.tolist(), high.tolist()
    ([0.0, 0.0, -0.05], [1.0, 1.0, 0.05])
    """
    points = triangles.reshape(-1, 3)
    low, high = points.min(axis=0), points.max(axis=0)
    size = float(np.max(high - low)) or 1.0
    half = np.maximum(high - low, 0.1 * size) / 2
    centre = (low + high) / 2
    return centre - half, centre + half


def _fill(ax, low: NDArray[np.float64], high: NDArray[np.float64], points: NDArray[np.float64]) -> None:
    """Limits ``low``..``high`` [m] at equal aspect (one metre as long on every axis), moved across the
    line of sight and zoomed so that ``points`` (n, 3), as the camera sees them, fill 97 % of the frame
    about its middle (the projection is orthographic: their picture moves with the limits and scales
    with the zoom about the limits' centre)."""
    centre = (low + high) / 2
    _set_limits(ax, low, high)
    ax.set_box_aspect(tuple(high - low))
    projection = ax.get_proj()
    x, y, depth = proj3d.proj_transform(*np.vstack([points, centre]).T, projection)
    frame = np.array([ax.viewLim.intervalx, ax.viewLim.intervaly])  # the 2-D limits of the picture
    zoom = 0.97 * float(np.min(np.ptp(frame, axis=1))) / max(np.ptp(x), np.ptp(y))
    # the point to centre the limits on: the points' middle lands on the frame's once zoomed
    middle = np.array([x.min() + x.max(), y.min() + y.max()]) / 2 - frame.mean(axis=1) / zoom
    shift = np.ravel(proj3d.inv_transform(*middle, depth[-1], np.linalg.inv(projection))) - centre
    _set_limits(ax, low + shift, high + shift)
    ax.set_box_aspect(tuple(high - low), zoom=zoom)


def _set_limits(ax, low: NDArray[np.float64], high: NDArray[np.float64]) -> None:
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), low, high, strict=True):
        set_lim(a, b)


def _axes_inset(fig: Figure, azimuth: float, elevation: float) -> None:
    """The body axes x, y, z as the camera sees them, small in the figure's lower left corner."""
    inset = fig.add_axes((0.0, 0.0, 0.14, 0.14), projection="3d")
    inset.set_proj_type("ortho")
    inset.view_init(elev=elevation, azim=azimuth)
    inset.set_axis_off()
    _set_limits(inset, -np.ones(3), np.ones(3))
    inset.set_box_aspect((1.0, 1.0, 1.0))
    ends = np.eye(3)
    inset.quiver(*np.zeros((3, 3)), *ends, color="black", arrow_length_ratio=0.2)
    for end, axis in zip(1.3 * ends, "xyz", strict=True):
        inset.text(*end, axis)


def _reach(centre: NDArray, low: NDArray, high: NDArray, d: NDArray) -> float:
    """Distance from ``centre`` along the unit vector ``d`` to the box ``low``..``high`` around it."""
    with np.errstate(divide="ignore"):
        steps = np.where(d > 0, (high - centre) / d, np.where(d < 0, (low - centre) / d, np.inf))
    return float(np.min(steps))


def _limits(values: NDArray[np.float64]) -> tuple[float, float]:
    low, high = float(values.min()), float(values.max())
    return (low, high) if high > low else (low - 0.5, high + 0.5)


def view_model(table: xr.Dataset) -> Model:
    """The model of a table for its 3-D views, loaded again from the files the table names.

    Raises
    ------
    InputError
        The mesh file is not there, or it is not the mesh the table was made from (its SHA-256 differs
        from the table's ``mesh_sha256``; likewise for the materials file).

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table made from a model loaded from files.

    Returns
    -------
    Model
        The model, loaded again with the table's settings.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> from sunwind.geometry.io.obj import write_obj
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "cube.obj"
    ...     write_obj(sw.meshes.box(), path)
    ...     table = sw.sweep(sw.load(path, uniform=black, threads=1), srp=sw.SrpSetup(), step_deg=90.0)
    ...     view_model(table).craft.n_facets
    12
    """
    mesh = str(table.attrs["mesh"])
    if not Path(mesh).exists():
        raise InputError(
            "the table's mesh is not there for the 3-D view",
            path=mesh,
            hint="draw the maps only with no_view",
            parameters=("no_view",),
        )
    source = ModelSource.from_attributes(table.attrs)
    for key, found in source.digests().items():
        if key in table.attrs and found is not None and found != table.attrs[key]:
            raise InputError(
                f"the file is not the one the table was made from ({key} differs): the 3-D view would "
                "show another model",
                path=mesh if key == "mesh_sha256" else str(table.attrs.get("materials")),
                hint="restore the file, sweep again, or draw the maps only with no_view",
                parameters=("no_view",),
            )
    reference = np.asarray(table.attrs["reference_point_m"], dtype=np.float64)
    return Model(source.spacecraft(), source, reference_point_m=reference)


def plot_pressure_views(
    table: xr.Dataset,
    directory: str | Path,
    name: str,
    direction: NDArray[np.float64] | None = None,
    model: Model | None = None,
    view_azel: tuple[float, float] | None = None,
) -> list[Path]:
    """Write 3-D views of the table's model coloured by facet pressure ``|F_facet| / A``, one per quantity.

    SRP and drag (none of the Earth's radiation), each at ``direction`` (a unit Sun or flow vector),
    default where that quantity's force is largest, seen from ``view_azel`` (camera azimuth and
    elevation [deg]), default from that direction: from the Sun, or from upstream
    (:func:`pressure_figure`).

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table (one pose).
    directory : str or Path
        Where the PNGs go.
    name : str
        The table's name: files are ``NAME.KIND.pressure_azAZ_elEL.png``, AZ EL those of the direction.
    direction : (3,) float64, optional
        The Sun or flow vector to draw, body frame.
    model : Model, optional
        The table's model; default :func:`view_model`.
    view_azel : (float, float), optional
        Camera azimuth and elevation [deg].

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    InputError
        What :func:`view_model` refuses, or a ``view_azel`` that
        :func:`~sunwind.geometry.directions.checked_azel` refuses.

    Examples
    --------
    >>> import tempfile
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     [path.name for path in plot_pressure_views(table, folder, "cube", model=cube)]
    ['cube.srp.pressure_az+0_el-90.png']
    """
    model = view_model(table) if model is None else model
    return [
        _pressure_view(table, model, kind, directory, name, direction, view_azel)
        for kind in kinds_of(table)
        if kind in _VIEWED
    ]


def _pressure_view(
    table: xr.Dataset,
    model: Model,
    kind: str,
    directory: str | Path,
    name: str,
    direction: NDArray[np.float64] | None,
    view_azel: tuple[float, float] | None,
) -> Path:
    if direction is None:
        force = np.linalg.norm(table[f"{kind}_force_N"].values, axis=-1)
        at = np.unravel_index(int(np.argmax(force)), force.shape)
        direction = table[DIRECTION[kind]].values[at]
    if kind == "srp":
        result = srp(model, direction, flux_W_m2=float(table.attrs["flux_W_m2"]), reflections="none")
    else:
        air = Atmosphere.from_json(json.loads(table.attrs["atmosphere"]))
        result = drag(model, float(table.attrs["speed_m_s"]) * direction, air, reflections="none")
    craft = model.craft
    pressure = np.linalg.norm(result.facet_force_N, axis=1) / craft.facet_areas
    az, el = vector_to_azel(direction)
    path = Path(directory) / f"{name}.{kind}.pressure_az{az:+.0f}_el{el:+.0f}.png"
    label = "Sun" if kind == "srp" else "flow u"
    return plot_facet_pressure(craft, pressure, direction, path, label, view_azel=view_azel)
