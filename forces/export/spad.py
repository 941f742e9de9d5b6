"""SPAD area-vector files for GMAT (``SPADSRPFile``, ``SPADDragFile``) written from a grid sweep table.

Format, as GMAT R2020a's ``SPADFileReader`` (src/base/util/SPADFileReader.cpp) parses it:

- header lines ``key : value`` (one colon each; GMAT reads only ``Analysis Type``, which must be ``Area``,
  skips lines starting ``Current`` and ignores every other key; a key must not start ``Motion`` or
  ``Azimuth``, which end the header);
- ``Motion : 1`` with ``Name : Azimuth`` and ``Motion : 2`` with ``Name : Elevation``, each with
  ``Method : Step``, ``Minimum``, ``Maximum`` (-180/180 and -90/90) and ``Step`` (a positive whole number of
  degrees: GMAT reads it as an integer and looks rows up at integer angles); then ``: END``;
- ``Record count : N``, N = (360 / az step + 1) (180 / el step + 1);
- a title line starting ``Azimuth``, the units line ``degrees degrees m^2 m^2 m^2``, a dashed line;
- rows ``az el Ax Ay Az``, azimuth the outer loop, elevation the inner one, both ends of each range present.

GMAT interpolates bilinearly between the four rows around the direction's (az, el) and multiplies by its
``SPADSRPScaleFactor`` / ``SPADDragScaleFactor``.

SRP (``Spacecraft.GetSPADSRPArea``, ``SolarRadiationPressure``): the row at (az, el) of the body-frame
spacecraft-to-Sun unit vector holds ``A = F_SRP(1 au) / P(1 au)`` [m^2], pointing along the force (away
from the Sun); GMAT's acceleration is ``a = P A / m`` (its flux, shadow and distance scaling applied).

Drag (``Spacecraft.GetSPADDragArea``, ``DragForce``): GMAT looks the table up at the direction of ``-v_rel``
in the body frame and applies ``a = -1/2 rho |v_rel|^2 A / m``. The row at (az, el) therefore holds
``A = -F_drag(u) / q`` for ``u = -dir(az, el)``, i.e. the table's flow grid point (az + 180, -el); the flow
grid must contain it (an azimuth step that divides 180). ``A`` is then about ``C_D x area`` along ``+u``.
The area is exact for the table's density, speed, temperature and composition only: free-molecular
coefficients depend on the speed ratio and the wall temperature.

Torque: none. The rows are area vectors, from which GMAT computes forces only, so the table's torque
reference point does not enter a SPAD file. The header says so (``Holds``), and states the frame
(``Frame``), the reference point and what it is (``Reference Point``) and the provenance (``Version``,
``System``, ``Mesh SHA256``, ``Materials SHA256``): keys GMAT's reader passes over.
"""

from __future__ import annotations

from collections.abc import Sequence
from importlib.metadata import version
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.export.atomic import atomic_text
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, radiation_pressure
from sunwind.forces.tables.dataset import ReferencePoint, kinds_of
from sunwind.forces.tables.interpolation import check_step, grid_axes
from sunwind.geometry.errors import InputError

#: File extension that chooses this format.
EXTENSION = ".spo"
#: Quantities SPAD files hold (one file each).
KINDS = ("srp", "drag")
_TITLE = {"srp": "SRP", "drag": "drag"}
_ROW_FORMAT = "%8.2f %8.2f % .15e % .15e % .15e"


def spad_paths(output_path: str | Path, kinds: Sequence[str]) -> dict[str, Path]:
    """The file names of the SPAD files of a sweep.

    ``NAME.spo`` for one quantity, ``NAME.srp.spo`` and ``NAME.drag.spo`` for both; a path without
    a suffix gets ``.spo``.

    Parameters
    ----------
    output_path : str or Path
        The output path the user gave.
    kinds : sequence of str
        The quantities, ``"srp"`` and/or ``"drag"``.

    Returns
    -------
    dict of str to Path
        Quantity -> file.

    Raises
    ------
    InputError
        No quantity, or one that is not ``"srp"`` or ``"drag"``.

    Examples
    --------
    >>> {kind: path.name for kind, path in spad_paths("out/cube", ["srp"]).items()}
    {'srp': 'cube.spo'}
    >>> {kind: path.name for kind, path in spad_paths("out/cube.spo", ["srp", "drag"]).items()}
    {'srp': 'cube.srp.spo', 'drag': 'cube.drag.spo'}
    """
    path = Path(output_path)
    suffix = path.suffix or ".spo"
    stem = path.stem if path.suffix else path.name
    unknown = [kind for kind in kinds if kind not in KINDS]
    if unknown or not kinds:
        raise InputError(f"unknown SPAD kind(s) {unknown or list(kinds)}", hint="use 'srp' and/or 'drag'")
    if len(kinds) == 1:
        return {kinds[0]: path.with_name(stem + suffix)}
    return {kind: path.with_name(f"{stem}.{kind}{suffix}") for kind in kinds}


def check_request(step_deg: float | None) -> None:
    """Refuse, before a sweep, attitudes SPAD files cannot hold.

    GMAT reads the grid's steps as whole degrees, so a list of attitudes or a step that is not a
    whole number of degrees dividing 180 is refused before any attitude is computed.

    Parameters
    ----------
    step_deg : float or None
        The grid step [deg]; None for a list of attitudes.

    Raises
    ------
    InputError
        A list, or a step that is not a whole number of degrees dividing 180.

    Examples
    --------
    >>> check_request(10.0)
    >>> check_request(7.5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: SPAD grid step 7.5 deg is not a whole number of degrees; ...
    """
    if step_deg is None:
        raise InputError(
            "a SPAD file needs an azimuth/elevation grid, not an attitude list",
            hint="sweep on a grid (a step_deg such as 5) instead of attitudes",
            parameters=("step_deg", "attitudes"),
        )
    check_step(step_deg, 180.0, "SPAD grid", whole_degrees=True)


def write_spad(table: xr.Dataset, path: str | Path, kind: str) -> Path:
    """Write the SRP or drag area table of a grid sweep as a GMAT SPAD file.

    SRP rows hold ``A = F_SRP(1 au) / P(1 au)`` along the force at the Sun direction's (az, el);
    drag rows hold ``A = -F_drag / q`` at the flow grid point opposite (GMAT looks drag up at
    ``-v_rel``). The header states the frame, the reference point (which does not enter) and the
    provenance, in keys GMAT's reader passes over.

    Parameters
    ----------
    table : xarray.Dataset
        Grid sweep table (sunwind contract) with ``srp_force_N`` or ``drag_force_N``.
    path : str or Path
        File to write.
    kind : {"srp", "drag"}
        The quantity.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    InputError
        A list table, missing variables or attributes, a step that is not a whole number of degrees
        dividing 360 / 180, or (drag) a flow grid without the points (az + 180, -el).

    References
    ----------
    .. [1] NASA Goddard Space Flight Center. *General Mission Analysis Tool (GMAT) User Guide*: the SPAD
       file models of solar radiation pressure and drag. https://gmat.gsfc.nasa.gov

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_spad(table, Path(folder) / "cube.spo", "srp")
    ...     lines = path.read_text().splitlines()
    >>> [line for line in lines if line.startswith("Analysis Type")]
    ['Analysis Type      : Area']
    >>> lines[-1].split()  # the Sun overhead: 1.2 m^2 of a grey 1 m cube, pushed along -z
    ['180.00', '90.00', '0.000000000000000e+00', '0.000000000000000e+00', '-1.200000000000000e+00']
    """
    if kind not in KINDS:
        raise InputError(f"unknown SPAD kind {kind!r}", hint="use 'srp' or 'drag'")
    prefix = "sun" if kind == "srp" else "flow"
    name = f"{kind}_force_N"
    if name not in table.data_vars:
        raise InputError(
            f"cannot write a {_TITLE[kind]} SPAD file: the table has no {name}",
            hint=f"run the sweep with {_TITLE[kind]} included",
        )
    if f"{prefix}_azimuth" not in table.dims:
        check_request(None)  # a list table
    axes = grid_axes(table, prefix)
    n_az = check_step(axes.azimuth_step_deg, 360.0, f"{prefix} azimuth", whole_degrees=True)
    check_step(axes.elevation_step_deg, 180.0, f"{prefix} elevation", whole_degrees=True)
    force = table[name].transpose(f"{prefix}_azimuth", f"{prefix}_elevation", "component").values
    if kind == "srp":
        area = _srp_area(force, table.attrs)
    else:
        if n_az % 2:
            raise InputError(
                f"the flow grid has no point opposite each azimuth (step {axes.azimuth_step_deg:g} deg)",
                hint="GMAT looks drag up at -v_rel: use an azimuth step that divides 180",
            )
        area = _drag_area(force, n_az, table.attrs)
    az, el = np.meshgrid(axes.azimuth_deg, axes.elevation_deg, indexing="ij")
    rows = np.column_stack([az.ravel(), el.ravel(), area.reshape(-1, 3)])
    out = Path(path)
    with atomic_text(out, encoding="ascii") as stream:
        stream.write(_header(table, kind, axes.azimuth_step_deg, axes.elevation_step_deg, len(rows)))
        np.savetxt(stream, rows, fmt=_ROW_FORMAT)
    return out


def write(table: xr.Dataset, path: str | Path) -> list[Path]:
    """Write one SPAD file per quantity of a grid sweep table; the Earth's radiation has none.

    Parameters
    ----------
    table : xarray.Dataset
        Grid sweep table.
    path : str or Path
        The output path (:func:`spad_paths` names the files).

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    InputError
        What :func:`spad_paths` and :func:`write_spad` refuse.

    References
    ----------
    .. [1] NASA Goddard Space Flight Center. *General Mission Analysis Tool (GMAT) User Guide*: the SPAD
       file models of solar radiation pressure and drag. https://gmat.gsfc.nasa.gov

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print([path.name for path in write(table, Path(folder) / "cube")])
    ['cube.spo']
    """
    kinds = [kind for kind in kinds_of(table) if kind in KINDS]  # the Earth's radiation has no SPAD file
    paths = spad_paths(path, kinds)
    return [write_spad(table, paths[kind], kind) for kind in kinds]


def read_spad(path: str | Path) -> xr.Dataset:
    """Read a SPAD area file into an ``area_m2`` table, its header in ``attrs``.

    Reads what :func:`write_spad` writes (and GMAT's sample files); checks that the rows fill the grid
    the Motion blocks declare, in order.

    Parameters
    ----------
    path : str or Path
        The SPAD file.

    Returns
    -------
    xarray.Dataset
        ``area_m2`` (azimuth, elevation, component) [m^2] on the file's grid [deg]; the header's keys
        in ``attrs`` (a list where a key repeats).

    Raises
    ------
    InputError
        An unreadable file, not a SPAD area file, rows that are not numbers or do not fill the grid.

    References
    ----------
    .. [1] NASA Goddard Space Flight Center. *General Mission Analysis Tool (GMAT) User Guide*: the SPAD
       file models of solar radiation pressure and drag. https://gmat.gsfc.nasa.gov

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=90.0)  # 5 x 3 Sun directions
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     back = read_spad(write_spad(table, Path(folder) / "cube.spo", "srp"))
    >>> back["area_m2"].sel(azimuth=0.0, elevation=90.0).values.round(6)
    array([ 0. ,  0. , -1.2])
    >>> back.attrs["Step"]
    ['90', '90']
    """
    try:
        lines = Path(path).read_text(encoding="utf-8-sig").splitlines()  # -sig: a byte-order mark is skipped
    except OSError as error:
        raise InputError(f"cannot read the SPAD file: {error.strerror}", path=str(path)) from None
    except UnicodeDecodeError as error:
        raise InputError(f"the SPAD file is not text ({error.reason})", path=str(path)) from None
    title = next((i for i, line in enumerate(lines) if line.strip().startswith("Azimuth")), None)
    if title is None:
        raise InputError("no 'Azimuth' title line: not a SPAD file", path=str(path))
    header = {}
    for line in lines[:title]:
        key, sep, value = line.partition(":")
        if sep and key.strip():
            header.setdefault(key.strip(), []).append(value.strip())
    try:
        steps = [float(step) for step in header.get("Step", [])]
        data = np.loadtxt(lines[title + 3 :], ndmin=2)
    except ValueError as error:
        raise InputError(f"a Step or a row is not numbers ({error})", path=str(path)) from None
    if data.shape[1:] != (5,):
        raise InputError("the rows do not hold 5 columns (az el Ax Ay Az)", path=str(path))
    usable = len(steps) == 2 and all(0 < step <= 180 for step in steps)  # False for NaN too
    if not usable or len(data) != (round(360 / steps[0]) + 1) * (round(180 / steps[1]) + 1):
        raise InputError("the rows do not fill the Azimuth x Elevation grid of the header", path=str(path))
    az = np.linspace(-180.0, 180.0, round(360 / steps[0]) + 1)
    el = np.linspace(-90.0, 90.0, round(180 / steps[1]) + 1)
    grid = np.stack(np.meshgrid(az, el, indexing="ij"), axis=-1).reshape(-1, 2)
    if not np.allclose(data[:, :2], grid, atol=1e-6):
        raise InputError("rows are not in azimuth-major, elevation-minor order", path=str(path))
    attrs = {key: values[0] if len(values) == 1 else values for key, values in header.items()}
    return xr.Dataset(
        {"area_m2": (("azimuth", "elevation", "component"), data[:, 2:].reshape(len(az), len(el), 3))},
        coords={"azimuth": az, "elevation": el, "component": ["x", "y", "z"]},
        attrs=attrs,
    )


def _srp_area(force: NDArray[np.float64], attrs: dict) -> NDArray[np.float64]:
    flux = float(attrs.get("flux_W_m2", np.nan))
    if not flux > 0:
        raise InputError(
            "the table's flux_W_m2 attribute is missing or not positive", hint="re-run the sweep"
        )
    return force * (SOLAR_FLUX_1AU / flux) / radiation_pressure(SOLAR_FLUX_1AU)


def _drag_area(force: NDArray[np.float64], n_az: int, attrs: dict) -> NDArray[np.float64]:
    q = float(attrs.get("dynamic_pressure_Pa", np.nan))
    if not q > 0:
        raise InputError(
            "the table's dynamic_pressure_Pa attribute is missing or not positive", hint="re-run"
        )
    opposite = (np.arange(n_az + 1) + n_az // 2) % n_az  # column of az + 180, wrapped into [-180, 180)
    return -force[opposite, ::-1] / q


def _header(table: xr.Dataset, kind: str, az_step: float, el_step: float, count: int) -> str:
    attrs = table.attrs
    if kind == "srp":
        direction = "spacecraft-to-Sun unit vector, body frame"
        quantity = f"A = F_SRP(1 au) / P(1 au) along the force, P(1 au) = {SOLAR_FLUX_1AU:g} W/m^2 / c"
    else:
        direction = "-v_rel (velocity of the atmosphere relative to the spacecraft), body frame"
        quantity = (
            f"A = -F_drag / q at q = {float(attrs['dynamic_pressure_Pa']):.6g} Pa "
            f"(rho {attrs.get('density_kg_m3', 'n/a')} kg/m^3, {attrs.get('speed_m_s', 'n/a')} m/s, "
            f"{attrs.get('temperature_K', 'n/a')} K)"
        )
    fields = {
        "Version": f"sunwind {attrs.get('sunwind_version', version('sunwind'))}",
        "System": Path(str(attrs.get("mesh", "spacecraft"))).name,
        "Analysis Type": "Area",
        "Pressure": "1",
        "Table": quantity,
        "Direction": direction,
        "Frame": attrs.get("frame", "body frame of the mesh"),
        "Holds": "forces only (area vectors); GMAT computes no torque from a SPAD file",
        "Reference Point": f"{ReferencePoint.of(attrs)}, of the table's torques; it does not enter the areas",
        "Mesh SHA256": attrs.get("mesh_sha256", "n/a"),
        "Materials SHA256": attrs.get("materials_sha256", "n/a"),
    }
    lines = [f"{key:<18} : {_value(value)}" for key, value in fields.items()]
    for number, (name, low, high, step) in enumerate(
        [("Azimuth", -180, 180, az_step), ("Elevation", -90, 90, el_step)], start=1
    ):
        lines += [
            f"Motion    : {number}",
            f"  Name    : {name}",
            "  Method  : Step",
            f"  Minimum : {low}",
            f"  Maximum : {high}",
            f"  Step    : {round(step)}",
        ]
    lines += [": END", "", f"Record count       : {count}", ""]
    lines += [
        "Azimuth Elevation Force(X) Force(Y) Force(Z)",
        "degrees degrees m^2 m^2 m^2",
        "------- --------- ---------------------- ---------------------- ----------------------",
    ]
    return "\n".join(lines) + "\n"


def _value(value: object) -> str:
    """A header value GMAT reads as one ``key : value`` pair: no colon, no line break."""
    return " ".join(str(value).replace(":", " ").split())
