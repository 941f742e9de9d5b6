"""Maps of sweep tables: every force and torque component over the azimuth and elevation of the Sun,
the flow or the Earth.

Figures are drawn on ``matplotlib.figure.Figure`` objects rendered by Agg, without pyplot: no global state,
no display needed. The 3-D views of facet pressure are in :mod:`sunwind.forces.tables.pressure_views`.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.tables.dataset import ReferencePoint
from sunwind.forces.tables.interpolation import PREFIX
from sunwind.geometry.errors import InputError

_DIRECTION_NAME = {"sun": "Sun", "flow": "flow", "earth": "Earth"}


def plot_table(table: xr.Dataset, directory: str | Path, name: str) -> list[Path]:
    """Write one PNG per force and torque variable of a sweep table: x, y, z maps over the directions.

    Grid tables are drawn with ``pcolormesh`` over azimuth/elevation [deg]; list tables as points at the
    azimuth/elevation of their Sun or flow vectors; the Earth's radiation over the Earth's directions.
    Each title (:func:`map_title`) names what was swept: the torque's reference point, the solar flux,
    the atmosphere and its date, the Earth's altitude and the fixed Sun.

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table (one pose).
    directory : path
        Where the PNGs go; created if needed.
    name : str
        The table's name (its file's stem): files are ``{name}.{variable}.png`` (e.g.
        ``t.srp_force_N.png``, ``t.drag_torque_Nm.png``, ``t.earth_force_N.png``), so that the maps of
        several tables can share a directory.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    InputError
        The table has no SRP, drag or Earth force or torque.

    Examples
    --------
    >>> import tempfile
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     [path.name for path in plot_table(table, folder, "cube")]
    ['cube.srp_force_N.png', 'cube.srp_torque_Nm.png']
    """
    variables = [
        (f"{kind}_{quantity}", prefix)
        for kind, prefix in PREFIX.items()
        for quantity in ("force_N", "torque_Nm")
        if f"{kind}_{quantity}" in table.data_vars
    ]
    if not variables:
        raise InputError(
            "the table has no srp_* or drag_* force or torque to plot (nor earth_*)", hint="run a sweep first"
        )
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    return [
        _plot_map(table, variable, prefix, out / f"{name}.{variable}.png") for variable, prefix in variables
    ]


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
    fig.suptitle(map_title(table, name))
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


def map_title(table: xr.Dataset, name: str) -> str:
    """The title of the map of ``name``, a force or torque variable of ``table``: two lines at most.

    The first says what is mapped, its units and frame, and for a torque the reference point
    (``reference_point_m`` and what it is, ``reference_point``); the second what the sweep held fixed:
    the solar flux (SRP); the dynamic pressure, speed, atmosphere and its date (drag); the altitude, the
    Sun and the date if the table has one (the Earth's radiation). What the table does not record is
    left out.

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table.
    name : str
        ``{kind}_force_N`` or ``{kind}_torque_Nm``, kind ``srp``, ``drag`` or ``earth``.

    Returns
    -------
    str
        The title, its lines joined by a newline.

    Examples
    --------
    >>> import tempfile
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> print(map_title(table, "srp_force_N"))
    SRP force, body frame [N]
    flux 1361 W/m^2
    """
    variable = table[name]
    what = variable.attrs.get("long_name", name)
    frame = "" if "frame" in what else f", {table.attrs.get('frame', 'body frame')}"
    first = f"{what} [{variable.attrs.get('units', '')}]{frame}"
    if name.endswith("_torque_Nm") and "reference_point_m" in table.attrs:
        point = ReferencePoint.of(table.attrs)
        first += f"; reference point ({', '.join(f'{x:g}' for x in point.rounded_m)}) m"
        if point.name:
            first += f": {point.name}"
    conditions = _conditions(table.attrs, PREFIX[name.split("_", 1)[0]])
    return f"{first}\n{conditions}" if conditions else first


def _conditions(attrs: dict, prefix: str) -> str:
    """What a table's sweep of ``prefix`` (sun, flow, earth) held fixed, one line (empty: nothing
    recorded)."""
    air = Atmosphere.from_json(json.loads(attrs["atmosphere"])) if "atmosphere" in attrs else None
    words = []
    if prefix == "sun" and "flux_W_m2" in attrs:
        words.append(f"flux {float(attrs['flux_W_m2']):g} W/m^2")
    if prefix == "flow" and "dynamic_pressure_Pa" in attrs:
        words.append(
            f"q = {float(attrs['dynamic_pressure_Pa']):.4g} Pa at {float(attrs['speed_m_s']):.5g} m/s"
        )
    if prefix == "flow" and air is not None:
        words.append(atmosphere_text(air))
    if prefix == "earth" and "earth_altitude_km" in attrs:
        x, y, z = np.asarray(attrs["earth_sun_vector"], dtype=float)
        words.append(
            f"altitude {float(attrs['earth_altitude_km']):g} km, Sun fixed at ({x:.3f}, {y:.3f}, {z:.3f})"
        )
        if air is not None and "time_utc" in air.inputs:
            words.append(f"date {air.inputs['time_utc']}")
    return "; ".join(words)


def atmosphere_text(air: Atmosphere) -> str:
    """Describe an atmosphere in a few words.

    NRLMSIS with its place, date and indices, or an explicit one's density, temperature and mole
    fractions (which have no date).

    Parameters
    ----------
    air : Atmosphere
        As a table records it (``Atmosphere.from_json`` of its ``atmosphere`` attribute).

    Returns
    -------
    str
        One line, e.g. ``NRLMSIS 2.1 at 400 km, lat 0, lon 0, 2024-01-01T00:00:00Z, F10.7 150 (81-day
        150), Ap 4``.

    Examples
    --------
    >>> from sunwind.forces.gas.atmosphere import Atmosphere
    >>> atmosphere_text(Atmosphere({"O": 1e15}, 1000.0, "atomic oxygen"))
    'explicit atmosphere (no date): 2.657e-11 kg/m^3, 1000 K, mole fractions O 1'
    """
    inputs = air.inputs
    if "time_utc" in inputs:
        return (
            f"{inputs['model']} at {air.altitude_km:g} km, lat {inputs['latitude_deg']:g}, lon "
            f"{inputs['longitude_deg']:g}, {inputs['time_utc']}, F10.7 {inputs['f107_sfu']:g} (81-day "
            f"{inputs['f107a_sfu']:g}), Ap {inputs['ap']:g}"
        )
    fractions = ", ".join(f"{species} {x:.3g}" for species, x in air.mole_fractions.items())
    return (
        f"explicit atmosphere (no date): {air.density_kg_m3:.4g} kg/m^3, {air.temperature_K:.4g} K, "
        f"mole fractions {fractions}"
    )
