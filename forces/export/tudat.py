"""Tudat tabulated aerodynamic coefficient files (angle of attack x sideslip) written from a drag sweep table.

File format, as Tudat's ``readCoefficientsFile`` (tudat src/io/multiDimensionalArrayReader.cpp) reads it for
``readTabulatedAerodynamicCoefficientsFromFiles`` (tudatpy ``aerodynamic_coefficients.tabulated_from_files``):
lines starting with ``#`` are comments; the first other line is the number of independent variables (2);
the next two lines list the values of the first (angle of attack) and second (sideslip) variable; then a
block with one row per angle of attack and one column per sideslip angle. One file per coefficient
component: force files keyed 0, 1, 2 and moment files keyed 0, 1, 2 (x, y, z).

Angles (Tudat ``getAirspeedBasedAerodynamicToBodyFrameTransformationMatrix`` and its unit test, tudat
src/astro/reference_frames/referenceFrameTransformations.cpp): the airspeed-based aerodynamic frame's x-axis,
along the vehicle's velocity relative to the atmosphere, has body-frame components
``(cos(alpha) cos(beta), sin(beta), sin(alpha) cos(beta))``. With the mesh frame as Tudat's body frame and
the table's flow vector ``u = v_rel / |v_rel|`` this gives

    alpha = atan2(u_z, u_x),    beta = asin(u_y),    alpha in [-180, 180], beta in [-90, 90] deg,

in radians in the files. The (alpha, beta) grid covers the sphere once, with its poles at ``u = +-y``.

Coefficients: force ``C_F = F / (q S_ref)`` and moment ``C_M = M / (q S_ref L_ref)`` about the table's
reference point, body frame, positive along the +x, +y, +z body axes. In tudatpy pass
``force_coefficients_frame = body_fixed_frame_coefficients`` (C++: ``areCoefficientsInAerodynamicFrame =
false``, ``areCoefficientsInNegativeAxisDirection = false``; the default, negative aerodynamic-frame
C_D, C_S, C_L, does not apply), ``moment_coefficients_frame = body_fixed_frame_coefficients``,
``independent_variable_names = [angle_of_attack_dependent, angle_of_sideslip_dependent]`` and the reference
area, length and moment reference point returned in :class:`TudatFiles`. Every file repeats these in its
comments.

Reference point: the format takes one, so the moments stay about the table's point ``r_ref``. Given it
as ``moment_reference_point`` (``tabulated_from_files``, whose C++ reader
``readTabulatedAerodynamicCoefficientsFromFiles`` then sets ``addForceContributionToMoments``), Tudat
moves the moments to the body's centre of mass ``r_com`` as it flies, adding ``(r_ref - r_com) x C_F /
L_ref`` (``AerodynamicMomentContributionInterface::getMomentCoefficientsCorrection``); left at its
default, NaN, it takes them as about the centre of mass. The comments name the point and that setting; a
default reference point (a centroid, not the centre of mass) also gives a
:class:`~sunwind.geometry.errors.ReferencePointWarning` at write time, naming what to pass.

Grid: the alpha/beta nodes are not the table's azimuth/elevation nodes, so every value is computed from the
table by :class:`sunwind.forces.tables.interpolation.TableInterpolator` (bicubic by default) at the direction
of each
(alpha, beta) node; Tudat then interpolates linearly between the nodes. The coefficients hold for the
table's atmosphere only (speed ratio, temperature, composition).
"""

from __future__ import annotations

import warnings
from importlib.metadata import version
from pathlib import Path
from typing import Literal, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.export.atomic import atomic_text
from sunwind.forces.tables.dataset import ReferencePoint
from sunwind.forces.tables.interpolation import TableInterpolator, check_step, grid_axes
from sunwind.geometry.errors import InputError, ReferencePointWarning

#: File extension that chooses this format: none (a prefix names six files).
EXTENSION = None
#: Quantities Tudat coefficient files hold.
KINDS = ("drag",)
_COMPONENTS = "xyz"


class TudatFiles(NamedTuple):
    """Files and reference values to hand to Tudat's tabulated aerodynamic coefficient settings.

    Parameters
    ----------
    force : dict of int to Path
        The ``C_Fx``, ``C_Fy``, ``C_Fz`` files, keyed 0, 1, 2.
    moment : dict of int to Path
        The ``C_Mx``, ``C_My``, ``C_Mz`` files, keyed 0, 1, 2.
    reference_area_m2 : float
        ``S_ref`` [m^2] of the coefficients.
    reference_length_m : float
        ``L_ref`` [m] of the moment coefficients.
    moment_reference_point_m : tuple of 3 float
        The table's reference point [m], body frame: Tudat's ``moment_reference_point``.

    Examples
    --------
    >>> from pathlib import Path
    >>> files = TudatFiles({0: Path("c_CFx.txt")}, {0: Path("c_CMx.txt")}, 1.5, 1.0, (0.0, 0.0, 0.0))
    >>> files.reference_area_m2, files.force[0].name
    (1.5, 'c_CFx.txt')
    """

    force: dict[int, Path]  # 0, 1, 2 -> C_Fx, C_Fy, C_Fz files
    moment: dict[int, Path]  # 0, 1, 2 -> C_Mx, C_My, C_Mz files
    reference_area_m2: float
    reference_length_m: float
    moment_reference_point_m: tuple[float, float, float]  # the table's: Tudat's moment_reference_point


def flow_vector(alpha_rad: NDArray, beta_rad: NDArray) -> NDArray[np.float64]:
    """Body-frame unit flow vectors of Tudat angles of attack and sideslip.

    ``u = (cos(alpha) cos(beta), sin(beta), sin(alpha) cos(beta))``, the x-axis of Tudat's
    airspeed-based aerodynamic frame in the body frame.

    Parameters
    ----------
    alpha_rad : array_like of float
        Angles of attack [rad].
    beta_rad : array_like of float
        Sideslip angles [rad], broadcasting with ``alpha_rad``.

    Returns
    -------
    ndarray of float64, shape (..., 3)
        Unit vectors ``u = v_rel / |v_rel|``, body frame.

    References
    ----------
    .. [1] Tudat (TU Delft Astrodynamics Toolbox) documentation: tabulated aerodynamic coefficients,
       coefficient frames and the moment reference point. https://docs.tudat.space

    Examples
    --------
    >>> import numpy as np
    >>> flow_vector(np.radians([0.0, 90.0, 0.0]), np.radians([0.0, 0.0, 90.0])).round(12) + 0.0
    array([[1., 0., 0.],
           [0., 0., 1.],
           [0., 1., 0.]])
    """
    alpha, beta = np.broadcast_arrays(np.asarray(alpha_rad, float), np.asarray(beta_rad, float))
    return np.stack([np.cos(alpha) * np.cos(beta), np.sin(beta), np.sin(alpha) * np.cos(beta)], axis=-1)


def check_request(step_deg: float | None) -> None:
    """Refuse, before a sweep, a list of attitudes: Tudat files need a grid.

    Parameters
    ----------
    step_deg : float or None
        The grid step [deg]; None for a list of attitudes.

    Raises
    ------
    InputError
        A list (``step_deg`` None).

    Examples
    --------
    >>> check_request(5.0)
    >>> check_request(None)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: Tudat coefficient files need a grid of flow directions, ...
    """
    if step_deg is None:
        raise InputError(
            "Tudat coefficient files need a grid of flow directions, not an attitude list",
            hint="sweep on a grid (a step_deg such as 5) instead of attitudes",
            parameters=("step_deg", "attitudes"),
        )


def write_tudat(
    table: xr.Dataset,
    prefix: str | Path,
    alpha_step_deg: float | None = None,
    beta_step_deg: float | None = None,
    method: Literal["bilinear", "bicubic"] = "bicubic",
) -> TudatFiles:
    """Write the drag of a grid sweep table as six Tudat coefficient files ``{prefix}_C{F,M}{x,y,z}.txt``.

    Every value is interpolated from the table at the flow direction of each (alpha, beta) node
    (:func:`flow_vector`); forces become ``C_F = F / (q S_ref)`` and moments ``C_M = M / (q S_ref
    L_ref)`` about the table's reference point, body frame.

    Parameters
    ----------
    table : xarray.Dataset
        Grid sweep table with ``drag_force_N`` and ``drag_torque_Nm``.
    prefix : str or Path
        Directory and start of the file names.
    alpha_step_deg, beta_step_deg : float, optional
        Steps of the angle-of-attack (-180..180) and sideslip (-90..90) grids [deg]; default the
        table's flow azimuth and elevation steps.
    method : {"bicubic", "bilinear"}
        Interpolation from the table's grid to the alpha/beta nodes.

    Returns
    -------
    TudatFiles
        The six files and the reference area, length and point to give Tudat.

    Raises
    ------
    InputError
        A list table, no drag results, a step that does not divide its range, or missing or
        non-positive ``dynamic_pressure_Pa``, ``reference_area_m2`` or ``reference_length_m``.

    Warns
    -----
    ReferencePointWarning
        The table's reference point is a default (a centroid): Tudat, left without
        ``moment_reference_point``, would take the moments as about the centre of mass.

    References
    ----------
    .. [1] Tudat (TU Delft Astrodynamics Toolbox) documentation: tabulated aerodynamic coefficients,
       coefficient frames and the moment reference point. https://docs.tudat.space

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> setup = sw.DragSetup(
    ...     speed_m_s=7600.0, atmosphere=air, reflections="none", reference_point_m=(0.0, 0.0, 0.0),
    ...     gas_sampling=sw.GasSampling(sky_rays=16, core_rays=1024),
    ... )
    >>> table = sw.sweep(cube, drag=setup, step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     files = write_tudat(table, Path(folder) / "cube")
    ...     rows = [line for line in files.force[0].read_text().splitlines() if not line.startswith("#")]
    >>> files.reference_area_m2, files.moment_reference_point_m
    (1.5, (0.0, 0.0, 0.0))
    >>> rows[0], len(rows[1].split()), len(rows[2].split())  # two variables: 5 alphas, 3 betas
    ('2', 5, 3)
    """
    missing = [name for name in ("drag_force_N", "drag_torque_Nm") if name not in table.data_vars]
    if missing:
        raise InputError(
            f"cannot write Tudat coefficient files: the table has no {', '.join(missing)}",
            hint="run the sweep with drag included",
        )
    if "flow_azimuth" not in table.dims:
        check_request(None)  # a list table
    axes = grid_axes(table, "flow")
    reference = {
        key: float(table.attrs.get(key, np.nan))
        for key in ("dynamic_pressure_Pa", "reference_area_m2", "reference_length_m")
    }
    bad = [key for key, value in reference.items() if not value > 0]
    if bad:
        raise InputError(f"the table's {', '.join(bad)} attribute is missing or not positive", hint="re-run")
    alpha_step = axes.azimuth_step_deg if alpha_step_deg is None else alpha_step_deg
    beta_step = axes.elevation_step_deg if beta_step_deg is None else beta_step_deg
    alpha = np.radians(np.linspace(-180.0, 180.0, check_step(alpha_step, 360.0, "angle-of-attack") + 1))
    beta = np.radians(np.linspace(-90.0, 90.0, check_step(beta_step, 180.0, "sideslip") + 1))
    loads = TableInterpolator(table, method).drag(flow_vector(alpha[:, None], beta[None, :]))
    q_s = reference["dynamic_pressure_Pa"] * reference["reference_area_m2"]
    coefficients = {
        "F": loads.force_N / q_s,
        "M": loads.torque_Nm / (q_s * reference["reference_length_m"]),
    }
    point = ReferencePoint.of(table.attrs)
    comments = _comments(table, reference, point, method)
    base = Path(prefix)
    files: dict[str, dict[int, Path]] = {"F": {}, "M": {}}
    for kind, values in coefficients.items():
        for index, axis in enumerate(_COMPONENTS):
            path = base.with_name(f"{base.name}_C{kind}{axis}.txt")
            header = f"C{kind}{axis}: {'force' if kind == 'F' else 'moment'} coefficient along +{axis}\n"
            with atomic_text(path, encoding="ascii") as stream:
                stream.write("".join(f"# {line}\n" for line in [header.strip(), *comments]))
                stream.write("2\n")
                np.savetxt(stream, alpha[None, :], fmt="%.17g")
                np.savetxt(stream, beta[None, :], fmt="%.17g")
                np.savetxt(stream, values[..., index], fmt="%.17g")
            files[kind][index] = path
    if point.name.endswith("(default)"):
        message = (
            f"Tudat files {base.name}_C*.txt: the moment coefficients are about the {point.name} "
            f"{point.coordinates} m, not the centre of mass: pass moment_reference_point="
            f"{point.coordinates} to Tudat's tabulated_from_files, which then moves them to the body's "
            "centre of mass (left NaN, Tudat takes them as about it), or sweep again with the centre of "
            "mass as reference_point_m"
        )
        warnings.warn(ReferencePointWarning(message, ("reference_point_m",)), stacklevel=2)
    return TudatFiles(
        files["F"],
        files["M"],
        reference["reference_area_m2"],
        reference["reference_length_m"],
        tuple(float(v) for v in point.point_m),
    )


def write(table: xr.Dataset, path: str | Path) -> list[Path]:
    """:func:`write_tudat` with its default grid and interpolation.

    Parameters
    ----------
    table : xarray.Dataset
        Grid sweep table with drag results.
    path : str or Path
        Directory and start of the file names.

    Returns
    -------
    list of Path
        The six files written: the force coefficients, then the moment coefficients.

    Raises
    ------
    InputError
        What :func:`write_tudat` refuses.

    Warns
    -----
    ReferencePointWarning
        The table's reference point is a default.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> setup = sw.DragSetup(
    ...     speed_m_s=7600.0, atmosphere=air, reflections="none", reference_point_m=(0.0, 0.0, 0.0),
    ...     gas_sampling=sw.GasSampling(sky_rays=16, core_rays=1024),
    ... )
    >>> table = sw.sweep(cube, drag=setup, step_deg=90.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     print([path.name for path in write(table, Path(folder) / "cube")])
    ['cube_CFx.txt', 'cube_CFy.txt', 'cube_CFz.txt', 'cube_CMx.txt', 'cube_CMy.txt', 'cube_CMz.txt']
    """
    files = write_tudat(table, path)
    return [*files.force.values(), *files.moment.values()]


def _comments(
    table: xr.Dataset, reference: dict[str, float], point: ReferencePoint, method: str
) -> list[str]:
    attrs = table.attrs
    release = attrs.get("sunwind_version", version("sunwind"))
    return [
        f"sunwind {release}, mesh sha256 {attrs.get('mesh_sha256', 'n/a')}",
        "independent variables: angle_of_attack_dependent [rad] (rows), angle_of_sideslip_dependent [rad] "
        "(columns)",
        "u = v_rel/|v_rel| in the body frame = (cos(alpha) cos(beta), sin(beta), sin(alpha) cos(beta))",
        "frame: body_fixed_frame_coefficients (positive along +x, +y, +z body axes) for forces and moments",
        f"C_F = F / (q S_ref), C_M = M / (q S_ref L_ref), q = {reference['dynamic_pressure_Pa']:.9g} Pa, "
        f"S_ref = {reference['reference_area_m2']:.9g} m^2, L_ref = {reference['reference_length_m']:.9g} m",
        f"moment reference point: {point}; pass moment_reference_point={point.coordinates} to Tudat's "
        "tabulated_from_files: Tudat then moves the moments to the body's centre of mass r_com, adding "
        "(r_ref - r_com) x C_F / L_ref (left NaN, it takes them as about the centre of mass)",
        f"atmosphere: rho {attrs.get('density_kg_m3', 'n/a')} kg/m^3, "
        f"speed {attrs.get('speed_m_s', 'n/a')} m/s, T {attrs.get('temperature_K', 'n/a')} K; "
        f"values {method}-interpolated from the sweep table",
    ]
