"""Basilisk ``RadiationPressure`` lookup tables (faceted model) written from an SRP sweep table.

Format, as Basilisk's ``parseSRPLookup.SRPLookupTableHandler.parseAndLoadXML`` reads it
(AVSLab/basilisk: src/simulation/dynamics/RadiationPressure/parseSRPLookup.py and the unit-test tables
``_UnitTest/cannonballLookup.xml``, ``cube_lookup.xml`` written by ``makeSphereXML.py``)::

    <srp_values>
       <sHatBValues>  <sHat_B index="i"> <value_1/> <value_2/> <value_3/> </sHat_B> ...  </sHatBValues>
       <forceBValues> <force_B index="i"> ... </force_B> ...                              </forceBValues>
       <torqueBValues><torque_B index="i"> ... </torque_B> ...                            </torqueBValues>
    </srp_values>

Entry ``i`` of each block belongs together; the handler's arrays are then fed one row at a time to
``addSHatLookupBEntry``, ``addForceLookupBEntry`` and ``addTorqueLookupBEntry``.

Conventions (``RadiationPressure::computeLookupModel``, radiationPressure.cpp):

- ``sHat_B`` is the unit spacecraft-to-Sun vector in the body frame B;
- ``force_B`` [N] and ``torque_B`` [N m] are at 1 au; Basilisk scales both by ``(1 au / r)^2`` and by the
  eclipse illumination factor. They are written here at ``SOLAR_FLUX_1AU`` = 1361 W/m^2 (the table's
  force times 1361 / ``flux_W_m2``); Basilisk's cannonball model uses its own 1 au flux constant instead;
- ``torque_B`` is the torque about point B, the origin of the body frame: the format fixes the point, so
  the table's torque about its reference point ``r_ref`` is moved to the origin, ``M_B = M_ref + r_ref x F``.
  Basilisk applies it unchanged as ``torqueExternalPntB_B``; its spacecraft's equations of motion are
  written about B and take the centre of mass from the hub's ``r_BcB_B`` (from B to the centre of mass).
  The mesh origin must therefore be B, and ``r_BcB_B`` the centre of mass in mesh coordinates. A comment
  in the file names the reference point the torques were moved from; one that is not the origin (to the
  micrometre) also gives a :class:`ReferencePointWarning` at write time, saying so and what to set.

Sampling: Basilisk picks the entry whose ``sHat_B`` has the largest dot product with the Sun direction (no
interpolation), so the direction it uses is off by up to half a grid cell's diagonal: about ``h / sqrt(2)``
for equal azimuth and elevation steps ``h`` (less toward the poles, where azimuths crowd). The force error is
that angle times the force's angular rate, ``|dF/dtheta|``, which is of order ``|F|`` per radian for a flat
plate or a wing (the cosine of incidence) and smaller for rounded bodies. For a relative error ``eps`` choose

    h [deg] ~ sqrt(2) * eps / g * (180 / pi),    g = |dF/dtheta| / |F| (about 1)

e.g. 1 % needs ``h`` ~ 0.8 deg (about 65 000 entries), 5 % ``h`` ~ 4 deg (about 2 600). Basilisk searches
all entries at every step, so the lookup costs time in proportion to their number.
"""

from __future__ import annotations

import warnings
from importlib.metadata import version
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.export.atomic import atomic_text
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.forces.tables.dataset import ReferencePoint
from sunwind.forces.tables.interpolation import azel_directions, grid_axes
from sunwind.geometry.errors import InputError, ReferencePointWarning

#: File extension that chooses this format.
EXTENSION = ".xml"
#: Quantities a Basilisk lookup holds.
KINDS = ("srp",)
_ENTRY = (
    '      <{tag} index="%d">\n'
    "         <value_1>%.17g</value_1>\n"
    "         <value_2>%.17g</value_2>\n"
    "         <value_3>%.17g</value_3>\n"
    "      </{tag}>\n"
)


def write_basilisk(table: xr.Dataset, path: str | Path) -> Path:
    """Write the SRP of a sweep table (grid or list) as a Basilisk ``RadiationPressure`` lookup XML.

    A grid table gives one entry per distinct direction: the duplicated azimuth +180 column is left out
    and each pole is written once (its row's mean over azimuth). A list table gives one entry per
    attitude. Forces and torques are scaled to 1 au (1361 W/m^2).

    The torques are written about the body-frame origin B, which the format fixes:
    ``M_B = M_ref + r_ref x F`` for the table's reference point ``r_ref``, which a comment names.

    Parameters
    ----------
    table : xarray.Dataset
        Sweep table with ``srp_force_N``, ``srp_torque_Nm`` and a ``flux_W_m2`` attribute.
    path : str or Path
        The file to write.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    InputError
        The table has no SRP results, or no positive ``flux_W_m2``.

    Warns
    -----
    ReferencePointWarning
        The reference point is not the origin: the torques were moved to B, and Basilisk needs the
        centre of mass relative to B in the hub's ``r_BcB_B``.

    References
    ----------
    .. [1] Basilisk astrodynamics framework, Autonomous Vehicle Systems Laboratory, University of
       Colorado Boulder: the ``radiationPressure`` module's lookup-table mode.
       https://github.com/AVSLab/basilisk

    Examples
    --------
    A 90-degree grid holds the cube's six face directions once each:

    >>> import tempfile
    >>> import xml.etree.ElementTree as ElementTree
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> setup = sw.SrpSetup(reflections="none", reference_point_m=(0.0, 0.0, 0.0))  # B: no warning
    >>> table = sw.sweep(cube, srp=setup, step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     root = ElementTree.parse(write_basilisk(table, Path(folder) / "cube.xml")).getroot()
    >>> [len(block) for block in root]
    [6, 6, 6]
    >>> [round(float(value.text) * 1e6, 4) for value in root.find("forceBValues")[-1]]  # Sun overhead [uN]
    [0.0, 0.0, -5.4478]
    """
    missing = [name for name in ("srp_force_N", "srp_torque_Nm") if name not in table.data_vars]
    if missing:
        raise InputError(
            f"cannot write a Basilisk SRP lookup: the table has no {', '.join(missing)}",
            hint="run the sweep with SRP included",
        )
    flux = float(table.attrs.get("flux_W_m2", np.nan))
    if not flux > 0:
        raise InputError(
            "the table's flux_W_m2 attribute is missing or not positive", hint="re-run the sweep"
        )
    sun, force, torque = _entries(table)
    reference = ReferencePoint.of(table.attrs)
    scale = SOLAR_FLUX_1AU / flux
    force_1au = force * scale
    torque_1au = (torque + np.cross(reference.point_m, force)) * scale
    index = np.arange(len(sun), dtype=np.float64)[:, None]
    blocks = [
        f"   <{block}>\n"
        + (_ENTRY.format(tag=tag) * len(values)) % tuple(np.hstack([index, values]).ravel())
        + f"   </{block}>\n"
        for block, tag, values in (
            ("sHatBValues", "sHat_B", sun),
            ("forceBValues", "force_B", force_1au),
            ("torqueBValues", "torque_B", torque_1au),
        )
    ]
    note = (
        f"sunwind {table.attrs.get('sunwind_version', version('sunwind'))}; mesh sha256 "
        f"{table.attrs.get('mesh_sha256', 'n/a')}; sHat_B unit spacecraft-to-Sun, body frame; force_B [N] "
        f"and torque_B [N m] about the body-frame origin B at 1 au ({SOLAR_FLUX_1AU:g} W/m^2), fully lit"
    )
    moved = (
        f"reference point of the table's torques: {reference}; torque_B = M_ref + r_ref x F is about B, "
        "the point the format fixes (B: the mesh origin; the hub's r_BcB_B: the centre of mass from B)"
    )
    out = Path(path)
    with atomic_text(out) as stream:
        stream.write(
            '<?xml version="1.0" encoding="utf-8"?>\n'
            + "".join(f"<!-- {_comment(text)} -->\n" for text in (note, moved))
            + "<srp_values>\n"
            + "".join(blocks)
            + "</srp_values>\n"
        )
    if not reference.at_origin:
        warnings.warn(
            f"Basilisk lookup {out.name}: torque_B is about the body-frame origin B, which the format "
            f"fixes: the torques about the reference point {reference} were moved there "
            "(M_ref + r_ref x F); in Basilisk make B the mesh origin and set the hub's r_BcB_B to the "
            f"centre of mass relative to B ({reference.coordinates} if that is the reference point): the "
            "lookup gives the torque about B, Basilisk's dynamics take the centre of mass from r_BcB_B",
            ReferencePointWarning,
            stacklevel=2,
        )
    return out


def write(table: xr.Dataset, path: str | Path) -> list[Path]:
    """:func:`write_basilisk`, as the export registry calls it.

    Parameters
    ----------
    table : xarray.Dataset
        Sweep table with SRP results.
    path : str or Path
        The file to write.

    Returns
    -------
    list of Path
        The file written.

    Raises
    ------
    InputError
        What :func:`write_basilisk` refuses.

    Warns
    -----
    ReferencePointWarning
        The reference point is not the body-frame origin.

    Examples
    --------
    >>> import tempfile
    >>> import xml.etree.ElementTree as ElementTree
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> setup = sw.SrpSetup(reflections="none", reference_point_m=(0.0, 0.0, 0.0))  # B: no warning
    >>> table = sw.sweep(cube, srp=setup, step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print([path.name for path in write(table, Path(folder) / "cube.xml")])
    ['cube.xml']
    """
    return [write_basilisk(table, path)]


def _entries(table: xr.Dataset) -> tuple[NDArray, NDArray, NDArray]:
    """Unit Sun vectors, forces and torques (n, 3) of the distinct directions of a table."""
    if "sun_azimuth" not in table.dims:
        sun = table["sun_vector"].transpose(..., "component").values.reshape(-1, 3)
        force = table["srp_force_N"].transpose(..., "component").values.reshape(-1, 3)
        torque = table["srp_torque_Nm"].transpose(..., "component").values.reshape(-1, 3)
        return sun / np.linalg.norm(sun, axis=1, keepdims=True), force, torque
    axes = grid_axes(table, "sun")
    dims = ("sun_azimuth", "sun_elevation", "component")
    force, torque = (table[name].transpose(*dims).values[:-1] for name in ("srp_force_N", "srp_torque_Nm"))
    sun = azel_directions(axes.azimuth_deg[:-1, None], axes.elevation_deg[None, 1:-1]).reshape(-1, 3)
    poles = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]])

    def distinct(values: NDArray) -> NDArray:
        pole_values = values[:, [0, -1]].mean(axis=0)
        return np.vstack([values[:, 1:-1].reshape(-1, 3), pole_values])

    return np.vstack([sun, poles]), distinct(force), distinct(torque)


def _comment(text: str) -> str:
    """``text`` as the body of an XML comment, which may hold no ``--``."""
    return text.replace("--", "- -")
