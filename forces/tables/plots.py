"""Figures of sweep tables (force and torque over azimuth/elevation) and of per-facet pressure on a model.

Figures are drawn on ``matplotlib.figure.Figure`` objects rendered by Agg, without pyplot: no global state,
no display needed.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.drag import drag
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.model import Model, ModelSource
from sunwind.forces.srp import srp
from sunwind.forces.tables.dataset import DIRECTION, kinds_of
from sunwind.forces.tables.interpolation import PREFIX
from sunwind.geometry.directions import unit_vector, vector_to_azel
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import Spacecraft

_DIRECTION_NAME = {"sun": "Sun", "flow": "flow", "earth": "Earth"}
#: The kinds whose facet pressure a 3-D view shows (at one Sun or flow direction).
_VIEWED = ("srp", "drag")


def plot_table(table: xr.Dataset, directory: str | Path) -> list[Path]:
    """Write one PNG per force and torque variable of a sweep table: x, y, z maps over the directions.

    Grid tables are drawn with ``pcolormesh`` over azimuth/elevation [deg]; list tables as points at the
    azimuth/elevation of their Sun or flow vectors; the Earth's radiation over the Earth's directions.
    Files are ``{variable}.png`` (e.g. ``srp_force_N.png``, ``drag_torque_Nm.png``, ``earth_force_N.png``)
    in ``directory``, which is created if needed.

    Raises
    ------
    InputError
        The table has no SRP, drag or Earth force or torque.
    """
    names = [
        (f"{kind}_{quantity}", prefix)
        for kind, prefix in PREFIX.items()
        for quantity in ("force_N", "torque_Nm")
        if f"{kind}_{quantity}" in table.data_vars
    ]
    if not names:
        raise InputError(
            "the table has no srp_* or drag_* force or torque to plot (nor earth_*)", hint="run a sweep first"
        )
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    return [_plot_map(table, name, prefix, out / f"{name}.png") for name, prefix in names]


def plot_facet_pressure(
    craft: Spacecraft,
    pressure_Pa: ArrayLike,
    direction: ArrayLike,
    path: str | Path,
    label: str = "Sun",
) -> Path:
    """Write a 3-D view of the spacecraft with each facet coloured by its pressure, and a colour bar.

    Parameters
    ----------
    craft : Spacecraft
        The model; ``craft.triangles`` (n_facets, 3, 3) [m], body frame.
    pressure_Pa : (n_facets,) float
        Pressure on each facet [Pa].
    direction : (3,) float
        Sun vector or flow vector ``u``, body frame. The arrow, labelled ``label``, comes in from that side
        toward the body, as the photons or molecules do.
    path : path
        PNG file to write.

    Raises
    ------
    InputError
        ``pressure_Pa`` not one finite value per facet, or a zero direction.
    """
    triangles = craft.triangles
    pressure = np.asarray(pressure_Pa, dtype=np.float64)
    if pressure.shape != (len(triangles),) or not np.isfinite(pressure).all():
        raise InputError(
            f"pressure_Pa has shape {pressure.shape}, expected one finite value per facet ({len(triangles)},)"
        )
    d = unit_vector(direction, "direction")
    low, high = view_box(triangles)
    norm = Normalize(*_limits(pressure))
    mappable = ScalarMappable(norm=norm, cmap="viridis")

    fig = Figure(figsize=(7.5, 6.5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(triangles, facecolors=mappable.to_rgba(pressure), linewidths=0))
    model_low, model_high = triangles.reshape(-1, 3).min(axis=0), triangles.reshape(-1, 3).max(axis=0)
    centre = (model_low + model_high) / 2
    tail = centre + _reach(centre, low, high, d) * d  # on the edge of the axes, on the side d points to
    head = centre + _reach(centre, model_low, model_high, d) * d  # on the model's box
    ax.quiver(*tail, *(head - tail), color="tab:red", linewidth=2, arrow_length_ratio=0.25)
    ax.text(*tail, label, color="tab:red")
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), low, high, strict=True):
        set_lim(a, b)
    ax.set_box_aspect(tuple(high - low))  # equal aspect: one metre is as long on every axis
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.set_title(
        f"pressure on each facet [Pa], body frame\n{label} from ({d[0]:.3f}, {d[1]:.3f}, {d[2]:.3f})"
    )
    fig.colorbar(mappable, ax=ax, shrink=0.7, label="pressure [Pa]")
    out = Path(path)
    fig.savefig(out, dpi=110)
    return out


def view_box(triangles: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The limits [m] of a 3-D view of ``triangles`` (n, 3, 3): their bounding box with a margin of 15 % of
    its largest side for the direction arrow, every side at least 10 % of the largest (a flat sheet)."""
    points = triangles.reshape(-1, 3)
    low, high = points.min(axis=0), points.max(axis=0)
    size = float(np.max(high - low)) or 1.0
    half = np.maximum(high - low, 0.1 * size) / 2 + 0.15 * size
    centre = (low + high) / 2
    return centre - half, centre + half


def _reach(centre: NDArray, low: NDArray, high: NDArray, d: NDArray) -> float:
    """Distance from ``centre`` along the unit vector ``d`` to the box ``low``..``high`` around it."""
    with np.errstate(divide="ignore"):
        steps = np.where(d > 0, (high - centre) / d, np.where(d < 0, (low - centre) / d, np.inf))
    return float(np.min(steps))


def _plot_map(table: xr.Dataset, name: str, prefix: str, path: Path) -> Path:
    variable = table[name]
    units = variable.attrs.get("units", "")
    who = _DIRECTION_NAME[prefix]
    fig = Figure(figsize=(14, 4.2), layout="constrained")
    axes = fig.subplots(1, 3, sharey=True)
    az, el, values = _map_data(table, name, prefix)
    for index, (ax, component) in enumerate(zip(axes, "xyz", strict=True)):
        v = values[..., index]
        limit = float(np.max(np.abs(v))) or 1.0
        style = {"cmap": "RdBu_r", "vmin": -limit, "vmax": limit}
        if v.ndim == 2:
            artist = ax.pcolormesh(az, el, v.T, shading="nearest", **style)
        else:
            artist = ax.scatter(az, el, c=v, s=12, **style)
        fig.colorbar(artist, ax=ax, label=f"{component} [{units}]")
        ax.set_title(f"{component} component")
        ax.set_xlabel(f"{who} azimuth [deg]")
        ax.set_xlim(-180, 180)
        ax.set_ylim(-90, 90)
        ax.set_xticks(np.arange(-180, 181, 90))
        ax.set_yticks(np.arange(-90, 91, 45))
    axes[0].set_ylabel(f"{who} elevation [deg]")
    title = variable.attrs.get("long_name", name)
    frame = "" if "frame" in title else f", {table.attrs.get('frame', 'body frame')}"
    fig.suptitle(f"{title} [{units}]{frame}{_conditions(table, prefix)}")
    fig.savefig(path, dpi=100)
    return path


def _map_data(table: xr.Dataset, name: str, prefix: str) -> tuple[NDArray, NDArray, NDArray]:
    """Azimuths, elevations [deg] and values (..., 3) of a grid (2-D) or list (1-D) table."""
    az_name, el_name = f"{prefix}_azimuth", f"{prefix}_elevation"
    if az_name in table.dims:
        values = table[name].transpose(az_name, el_name, "component").values
        return table[az_name].values, table[el_name].values, values
    vectors = table[f"{prefix}_vector"].transpose(..., "component").values.reshape(-1, 3)
    vectors = vectors / np.linalg.norm(vectors, axis=1, keepdims=True)
    az = np.degrees(np.arctan2(vectors[:, 1], vectors[:, 0]))
    el = np.degrees(np.arcsin(np.clip(vectors[:, 2], -1.0, 1.0)))
    return az, el, table[name].transpose(..., "component").values.reshape(-1, 3)


def _conditions(table: xr.Dataset, prefix: str) -> str:
    attrs = table.attrs
    if prefix == "sun" and "flux_W_m2" in attrs:
        return f"; flux {float(attrs['flux_W_m2']):g} W/m^2"
    if prefix == "flow" and "dynamic_pressure_Pa" in attrs:
        return f"; q = {float(attrs['dynamic_pressure_Pa']):.4g} Pa"
    if prefix == "earth" and "earth_altitude_km" in attrs:
        x, y, z = np.asarray(attrs["earth_sun_vector"], dtype=float)
        height = float(attrs["earth_altitude_km"])
        return f"; altitude {height:g} km, Sun fixed at ({x:.3f}, {y:.3f}, {z:.3f})"
    return ""


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
    return Model(source.load(), source, reference_point_m=reference)


def plot_pressure_views(
    table: xr.Dataset,
    directory: str | Path,
    name: str,
    direction: NDArray[np.float64] | None = None,
    model: Model | None = None,
) -> list[Path]:
    """3-D views of the table's model coloured by facet pressure ``|F_facet| / A``, one per quantity
    (SRP, drag; none of the Earth's radiation), each at ``direction`` (a unit Sun or flow vector),
    default where that quantity's force is largest. ``model`` defaults to :func:`view_model`. PNGs
    ``NAME.KIND.pressure_azAZ_elEL.png``.

    Raises
    ------
    InputError
        What :func:`view_model` refuses.
    """
    model = view_model(table) if model is None else model
    return [
        _pressure_view(table, model, kind, directory, name, direction)
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
    return plot_facet_pressure(craft, pressure, direction, path, "Sun" if kind == "srp" else "flow u")
