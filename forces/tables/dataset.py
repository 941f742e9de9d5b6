"""Sweep results as a table: an ``xarray.Dataset`` with units, frame and provenance (METHOD.md "Outputs
and tables"); the writers of its file formats are :mod:`sunwind.forces.export`.

**Grid tables** have the dimensions ``sun_azimuth, sun_elevation`` for SRP, ``flow_azimuth,
flow_elevation`` for drag and ``earth_azimuth, earth_elevation`` for the Earth's radiation (degrees,
-180..180 and -90..90 with both ends), and ``component`` (x, y, z) for vectors. **List tables** have one
dimension ``attitude`` (rows of the attitude CSV) shared by SRP and drag. Variables are ``srp_*`` (force,
torque, their direct and reflected parts, lit and projected area, ``sun_vector``), ``drag_*`` (the same
parts and areas, the coefficients ``CD, CS, CL`` and ``CM``, ``flow_vector``) and ``earth_*`` (grid tables
only: the albedo plus infrared (plus thermal recoil) force and torque, each band apart, the visible share
of the Sun, ``earth_vector``; the Sun fixed in the body frame, see :mod:`.earth_setup`); with the default
shadow pass, each kind's ``*_error_estimate_force`` and ``*_error_estimate_torque`` (the error the pass
estimates it left, relative); with sensitivities, each kind's ``*_sensitivity_force_N`` and
``*_sensitivity_torque_Nm`` on its dimensions and ``material, coefficient, component``
(:mod:`.sensitivities`). Every variable and coordinate has ``units`` and ``long_name`` (CF-1.8,
``Conventions``); the global attributes hold the frame, the sign conventions (``comment``), reference
point, solar flux, atmosphere (its source and altitude), the Earth's slice, albedo and infrared
(``earth_*``), coefficient references, the reflection mode each quantity used (``srp_reflections``,
``drag_reflections``, ``earth_reflections``: ``auto`` resolved), mesh and materials digests and the
sunwind version.

"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from dataclasses import dataclass
from importlib.metadata import version
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.model import Model
from sunwind.forces.results import FRAME
from sunwind.forces.tables.attitudes import AttitudeList, DirectionGrid
from sunwind.forces.tables.jobs import FIELDS, Records, Setup
from sunwind.forces.tables.sensitivities import sensitivity_variables
from sunwind.forces.vocabulary import (
    COMMENTS,
    COMPONENT,
    COMPONENT_ATTRS,
    COMPONENTS,
    LONG_NAMES,
    units_of,
)
from sunwind.geometry.errors import InputError

#: Long names of an earth table's totals, without and with the thermal recoil.
_EARTH_TOTALS = {
    False: {"force_N": "force, albedo + infrared, body frame", "torque_Nm": "torque, albedo + infrared"},
    True: {
        "force_N": "force, albedo + infrared + thermal recoil, body frame",
        "torque_Nm": "torque, albedo + infrared + thermal recoil",
    },
}
#: What each quantity is called at the head of its variables' long names.
_TITLES = {"srp": "SRP", "drag": "DRAG", "earth": "Earth radiation"}
#: The metadata convention netCDF tables follow (global attribute ``Conventions``).
CF_CONVENTIONS = "CF-1.8"
#: What the table's directions and signs mean, stated in every table (global attribute ``comment``).
CONVENTIONS = (
    "body frame of the mesh, SI units; azimuth = atan2(y, x) from +x toward +y, elevation = asin(z) [deg]; "
    "sun_vector points from the spacecraft to the Sun; flow_vector u = v_rel/|v_rel|, v_rel the spacecraft "
    "velocity relative to the atmosphere (molecules travel along -u); SRP scales with flux_W_m2"
)
#: Added to :data:`CONVENTIONS` in a table of the Earth's radiation.
EARTH_CONVENTIONS = (
    "earth_vector points from the spacecraft to the Earth's centre, the Sun fixed in the body frame "
    "along earth_sun_vector (earth_slice)"
)
#: Dimension names of each quantity's direction in grid tables.
GRID_DIMS = {
    "srp": ("sun_azimuth", "sun_elevation"),
    "drag": ("flow_azimuth", "flow_elevation"),
    "earth": ("earth_azimuth", "earth_elevation"),
}
#: The direction variable of each quantity.
DIRECTION = {"srp": "sun_vector", "drag": "flow_vector", "earth": "earth_vector"}
#: What each quantity's direction is, in the long names of its coordinates and direction variable.
_WHO = {"srp": "Sun", "drag": "flow (v_rel)", "earth": "Earth centre (the Sun fixed in the body frame)"}
_VECTOR = {"srp": "the Sun vector", "drag": "u = v_rel/|v_rel|", "earth": "the Earth vector"}
_TEXT = {
    "srp": "unit vector toward the Sun",
    "drag": "unit flow vector u = v_rel/|v_rel|",
    "earth": "unit vector toward the Earth's centre (the Sun fixed in the body frame)",
}


def _variables(kind: str, records: Records, dims: tuple[str, ...], shape: tuple[int, ...]) -> dict:
    records = dict(records)  # the derivatives taken out: on (..., material, coefficient, component)
    derivatives = sensitivity_variables(records, f"{kind}_", dims, shape, _TITLES[kind])
    out = {}
    names = LONG_NAMES | (_EARTH_TOTALS["thermal_force_N" in records] if kind == "earth" else {})
    for name, values in records.items():
        vector = values.ndim == 2
        data = values.reshape((*shape, 3) if vector else shape)
        attrs = {"units": units_of(name), "long_name": f"{_TITLES[kind]} {names[name]}"}
        if name in COMMENTS:
            attrs["comment"] = COMMENTS[name]
        out[f"{kind}_{name}"] = xr.Variable((*dims, "component") if vector else dims, data, attrs)
    return out | derivatives


def _direction_variable(kind: str, vectors: NDArray[np.float64], dims: tuple[str, ...]) -> xr.Variable:
    attrs = {"units": "1", "long_name": f"{_TEXT[kind]}, body frame"}
    return xr.Variable((*dims, "component"), vectors, attrs)


def grid_table(
    records: Mapping[str, Records], grids: Mapping[str, DirectionGrid], attrs: Mapping[str, object]
) -> xr.Dataset:
    """The grid table of sweep records.

    ``records[kind]`` holds the records of the distinct directions of ``grids[kind]``, in their order
    (:attr:`~sunwind.forces.tables.attitudes.DirectionGrid.distinct`). Every node of the grid gets the
    record of its distinct direction (the poles and azimuth +-180 share one); each kind has its azimuth
    and elevation dimensions (:data:`GRID_DIMS`) and its direction variable (:data:`DIRECTION`).

    Parameters
    ----------
    records : mapping of str to Records
        Kind (``"srp"``, ``"drag"``, ``"earth"``) -> its records, one row per distinct direction.
    grids : mapping of str to DirectionGrid
        Kind -> the grid its directions came from.
    attrs : mapping of str to object
        Global attributes (:func:`table_attributes`); None values are dropped, dicts stored as JSON.

    Returns
    -------
    xarray.Dataset
        Variables ``KIND_FIELD`` on ``(azimuth, elevation)`` or ``(azimuth, elevation, component)``, with
        ``units`` and ``long_name``; CF-1.8 global attributes.

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.attitudes import DirectionGrid
    >>> from sunwind.forces.tables.dataset import grid_table, table_attributes
    >>> setup, grid = sw.SrpSetup(reflections="none"), DirectionGrid(90.0)
    >>> records = setup.evaluate(cube, grid.distinct[0])
    >>> table = grid_table({"srp": records}, {"srp": grid}, table_attributes(cube, [setup], 90.0))
    >>> dict(table.sizes), table["srp_force_N"].attrs["units"]
    ({'sun_azimuth': 5, 'sun_elevation': 3, 'component': 3}, 'N')
    """
    variables, coords = {}, {COMPONENT: (COMPONENT, list(COMPONENTS), COMPONENT_ATTRS)}
    for kind, values in records.items():
        grid = grids[kind]
        az_dim, el_dim = GRID_DIMS[kind]
        who, vector = _WHO[kind], _VECTOR[kind]
        coords[az_dim] = (
            az_dim,
            grid.azimuth_deg,
            {"units": "degree", "long_name": f"{who} azimuth in the body frame, atan2(y, x) of {vector}"},
        )
        coords[el_dim] = (
            el_dim,
            grid.elevation_deg,
            {"units": "degree", "long_name": f"{who} elevation in the body frame, asin(z) of {vector}"},
        )
        shape = (len(grid.azimuth_deg), len(grid.elevation_deg))
        nodes = {name: column[grid.distinct[1]] for name, column in values.items()}
        variables.update(_variables(kind, nodes, (az_dim, el_dim), shape))
        variables[DIRECTION[kind]] = _direction_variable(kind, grid.vectors, (az_dim, el_dim))
    out = xr.Dataset(variables, coords=coords, attrs=_attributes(attrs))
    if "earth" in records:
        out.attrs["comment"] = f"{out.attrs['comment']}; {EARTH_CONVENTIONS}"
    return out


def list_table(
    records: Mapping[str, Records], attitudes: AttitudeList, attrs: Mapping[str, object]
) -> xr.Dataset:
    r"""The list table of sweep records, one row per attitude of ``attitudes``.

    Parameters
    ----------
    records : mapping of str to Records
        Kind (``"srp"``, ``"drag"``) -> its records, one row per attitude.
    attitudes : AttitudeList
        The attitudes (their directions and, if given, quaternions are stored too).
    attrs : mapping of str to object
        Global attributes (:func:`table_attributes`); the list's file is added as ``attitudes``.

    Returns
    -------
    xarray.Dataset
        Variables ``KIND_FIELD`` on ``attitude`` (and ``component``).

    Raises
    ------
    InputError
        Earth records: an attitude list has no Earth direction.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.attitudes import read_attitude_csv
    >>> from sunwind.forces.tables.dataset import list_table, table_attributes
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "attitudes.csv"
    ...     _ = path.write_text("sun_x,sun_y,sun_z\n0,0,1\n1,0,0\n")
    ...     attitudes = read_attitude_csv(path)
    >>> setup = sw.SrpSetup(reflections="none")
    >>> records = setup.evaluate(cube, attitudes.directions("srp"))
    >>> table = list_table({"srp": records}, attitudes, table_attributes(cube, [setup], None))
    >>> (table["srp_force_N"] * 1e6).round(2).values.tolist()  # [uN], away from the Sun
    [[0.0, 0.0, -4.54], [-4.54, 0.0, 0.0]]
    """
    if "earth" in records:
        raise InputError(
            "an attitude list has no Earth direction: the Earth's radiation is tabulated on a grid",
            hint="sweep the earth kind over a grid step",
            parameters=("attitudes",),
        )
    variables = {}
    directions = {"srp": attitudes.sun_vectors, "drag": attitudes.flow_vectors}
    for kind, values in records.items():
        variables.update(_variables(kind, values, ("attitude",), (len(attitudes),)))
        variables[DIRECTION[kind]] = _direction_variable(kind, directions[kind], ("attitude",))
    if attitudes.quaternions is not None:
        variables["quaternion"] = xr.Variable(
            ("attitude", "quaternion_component"),
            attitudes.quaternions,
            {"units": "1", "long_name": "attitude quaternion (w, x, y, z), body relative to inertial"},
        )
    coords = {
        "attitude": (
            "attitude",
            np.arange(len(attitudes)),
            {"long_name": "row of the attitude list, from 0"},
        ),
        COMPONENT: (COMPONENT, list(COMPONENTS), COMPONENT_ATTRS),
    }
    return xr.Dataset(variables, coords=coords, attrs=_attributes({**attrs, "attitudes": attitudes.source}))


def attribute_text(value: object) -> str:
    """An attribute on one line of a CSV header.

    Settings (dicts) as JSON, vectors as numbers to 17 digits, anything else as its text.

    Parameters
    ----------
    value : object
        A table or run attribute.

    Returns
    -------
    str
        One line of text, which reads back to the same numbers.

    Examples
    --------
    >>> from sunwind.forces.tables.dataset import attribute_text
    >>> attribute_text([0.1, 2.0]), attribute_text({"mode": "full"})
    ('0.10000000000000001 2', '{"mode": "full"}')
    """
    if isinstance(value, dict):
        return json.dumps(value)
    if isinstance(value, np.ndarray | list | tuple):
        return " ".join(f"{v:.17g}" if isinstance(v, float) else str(v) for v in np.ravel(value).tolist())
    return str(value)


def _attributes(attrs: Mapping[str, object]) -> dict:
    """netCDF-safe global attributes (None dropped, dicts as JSON text, booleans as 0/1)."""
    out: dict = {"Conventions": CF_CONVENTIONS, "comment": CONVENTIONS}
    for key, value in attrs.items():
        if value is None:
            continue
        if isinstance(value, dict):
            value = json.dumps(value)
        elif isinstance(value, bool):
            value = int(value)
        elif isinstance(value, list | tuple):
            value = np.asarray(value, dtype=np.float64)
        out[key] = value
    return out


def kinds_of(table: xr.Dataset) -> list[str]:
    """The quantities a table holds, in :data:`sunwind.forces.tables.jobs.KINDS` order.

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table.

    Returns
    -------
    list of str
        Each kind whose ``KIND_force_N`` the table has.

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> from sunwind.forces.tables.dataset import kinds_of
    >>> kinds_of(table)
    ['srp']
    """
    return [kind for kind in FIELDS if f"{kind}_force_N" in table]


def table_attributes(model: Model, setups: list[Setup], step_deg: float | None) -> dict:
    """A table's global attributes: frame, reference point, sampling, environment, provenance.

    Parameters
    ----------
    model : Model
        The model swept.
    setups : list of Setup
        What the table holds (the first gives the reference point and sampling; each adds its own
        environment and reflection mode).
    step_deg : float or None
        The grid step [deg]; None for a list table.

    Returns
    -------
    dict
        Attribute name -> value (None where unknown; :func:`grid_table` and :func:`list_table` drop those).

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.dataset import table_attributes
    >>> attrs = table_attributes(cube, [sw.SrpSetup(reflections="none")], 30.0)
    >>> attrs["grid_step_deg"], attrs["reference_point"], attrs["flux_W_m2"]
    (30.0, 'volume centroid (default)', 1361.0)
    """
    first = setups[0]
    point, name = model.reference(first.reference_point_m)
    provenance = model_provenance(model)
    attrs: dict = {
        "title": f"sunwind attitude table of {Path(str(provenance['mesh'])).name}",
        "frame": FRAME,
        "reference_point_m": point,
        "reference_point": name,
        "grid_step_deg": step_deg,
        "samples": "shadow edges located" if first.sampling.samples is None else first.sampling.samples,
        "tolerance": first.sampling.tolerance,
        "reflections_requested": first.settings.mode,  # what each quantity used: srp_/drag_reflections
        **provenance,
    }
    for setup in setups:
        attrs |= setup.attributes(model)
    return attrs


def model_provenance(model: Model) -> dict:
    """Where a result's model came from.

    Parameters
    ----------
    model : Model
        A loaded model.

    Returns
    -------
    dict
        ``mesh``, ``materials``, ``unit``, ``length_unit`` and ``two_sided``, the SHA-256 of mesh and
        materials, the sunwind version, and any uniform material or gas overrides (None where a model
        built in memory has no file).

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> from sunwind.forces.tables.dataset import model_provenance
    >>> origin = model_provenance(cube)
    >>> origin["mesh"], origin["materials"], len(origin["mesh_sha256"])
    ('<box>', None, 64)
    """
    source = model.source.attributes() if model.source else {"mesh": model.craft.source}
    return {
        "mesh": source.pop("mesh"),
        "materials": source.pop("materials", None),
        "unit": source.pop("unit", None),
        "length_unit": model.craft.unit,
        "two_sided": source.pop("two_sided", ""),
        **model.digests(),
        "sunwind_version": version("sunwind"),
        **source,  # the uniform material and gas overrides, where given
    }


def one_pose(table: xr.Dataset, what: str, hint: str = "write the table as netCDF (.nc)") -> xr.Dataset:
    """``table`` at its one pose, hinge dimensions of length 1 dropped.

    A sweep over hinge angles has a dimension ``hinge_deg[GLOB]`` per hinge; those of length 1 are
    squeezed out, their angle kept as a scalar coordinate.

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table.
    what : str
        What needs one pose (a file format), named in the error.
    hint : str
        What to do instead, in the error.

    Returns
    -------
    xarray.Dataset
        The table without hinge dimensions (``table`` itself when it has none).

    Raises
    ------
    InputError
        A hinge with several angles.

    Examples
    --------

    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> from sunwind.forces.tables.dataset import one_pose
    >>> posed = one_pose(table.expand_dims({"hinge_deg[wing*]": [30.0]}), "SPAD")
    >>> "hinge_deg[wing*]" in posed.dims, float(posed["hinge_deg[wing*]"])
    (False, 30.0)
    >>> one_pose(table.expand_dims({"hinge_deg[wing*]": [0.0, 30.0]}), "SPAD")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: SPAD takes one pose; the table has 2 angles along hinge_deg[wing*]...
    """
    hinges = [str(d) for d in table.dims if str(d).startswith("hinge_deg[")]
    several = [d for d in hinges if table.sizes[d] > 1]
    if several:
        raise InputError(
            f"{what} takes one pose; the table has {table.sizes[several[0]]} angles along {several[0]}",
            hint=hint,
            parameters=("format",),
        )
    return table.squeeze(hinges) if hinges else table


def open_table(path: str | os.PathLike) -> xr.Dataset:
    """A table written as netCDF (:func:`sunwind.forces.export.netcdf.write`), loaded into memory.

    Parameters
    ----------
    path : str or path-like
        The ``.nc`` file.

    Returns
    -------
    xarray.Dataset
        The table, read whole (the file is closed).

    Raises
    ------
    InputError
        Not there, not readable as netCDF, or not a sunwind table.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)
    >>> from sunwind.forces.tables.dataset import open_table
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = sw.write(table, pathlib.Path(folder) / "cube.nc")
    ...     again = open_table(pathlib.Path(folder) / "cube.nc")
    >>> again.identical(table)
    True
    """
    path = Path(path)
    if not path.exists():
        raise InputError("no such table file", path=str(path))
    try:
        with xr.open_dataset(path) as table:
            table = table.load()
    except (OSError, ValueError) as error:
        reason = str(error).splitlines()[0] if str(error) else type(error).__name__
        if "did not find a match" in reason:  # xarray has no backend that recognises the bytes
            reason = "it is not a netCDF file"
        raise InputError(
            f"cannot read the table: {reason}", path=str(path), hint="give a .nc file sunwind wrote"
        ) from None
    if not kinds_of(table):
        raise InputError(
            "not a sunwind table (no srp_force_N, drag_force_N or earth_force_N)", path=str(path)
        )
    return table


@dataclass(frozen=True, eq=False)
class ReferencePoint:
    """The torque reference point of a table, as the export formats state it.

    From the attributes ``reference_point_m`` and ``reference_point``; ``str()`` gives
    ``[0.1, 0, 0] m (user)``.

    Parameters
    ----------
    point_m : ndarray, shape (3,)
        The point [m], body frame; the origin when the table states none.
    name : str
        What the point is ("user", "centre of mass (materials file)", "area centroid (default)"); empty
        when the table does not say.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.tables.dataset import ReferencePoint
    >>> point = ReferencePoint(np.array([0.1, -1e-9, 0.0]), "user")
    >>> str(point), point.at_origin
    ('[0.1, 0, 0] m (user)', False)
    >>> str(ReferencePoint.of({}))  # a table that states none
    '[0, 0, 0] m'
    """

    point_m: NDArray[np.float64]
    name: str = ""

    @classmethod
    def of(cls, attrs: Mapping) -> ReferencePoint:
        """The reference point a table's attributes state.

        Parameters
        ----------
        attrs : mapping
            A table's attributes (``reference_point_m``, ``reference_point``).

        Returns
        -------
        ReferencePoint
            The origin, unnamed, for what the attributes leave out.
        """
        point = np.asarray(attrs.get("reference_point_m", (0.0, 0.0, 0.0)), dtype=np.float64).reshape(3)
        return cls(point, str(attrs.get("reference_point", "")))

    @property
    def rounded_m(self) -> NDArray[np.float64]:
        """The point [m] to the micrometre, as the files and figures state it (no -0)."""
        return np.round(self.point_m, 6) + 0.0

    @property
    def coordinates(self) -> str:
        """The point [m] to the micrometre, as a list a Python script takes: ``[0.1, 0, 0]``."""
        return "[" + ", ".join(f"{v:.9g}" for v in self.rounded_m) + "]"

    @property
    def at_origin(self) -> bool:
        """Whether the point is the body-frame origin to the micrometre (a centroid's rounding is)."""
        return not self.rounded_m.any()

    def __str__(self) -> str:
        return f"{self.coordinates} m" + (f" ({self.name})" if self.name else "")
