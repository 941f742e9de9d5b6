"""Attitude from measured heat fluxes, row by row (METHOD.md "Attitude from heat fluxes").

Every row is solved alone (:func:`~sunwind.forces.sensing.row.solve_row`); the rows run as a job of
the sweep engine (:mod:`~sunwind.forces.sensing.tabulation`), so a long run keeps its finished rows in
a checkpoint, resumes after an interrupt and can run on Dask workers. The flux model is then checked
against the full forward model at the first sunlit row's answer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from sunwind.forces.earth import CapSampling, Place, planet_radiation
from sunwind.forces.gas.flow import EARTH_GM
from sunwind.forces.model import Model, as_model
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.radiation.law import solar_flux
from sunwind.forces.sensing.coarse import CoarseTable
from sunwind.forces.sensing.flux_rows import FluxRows
from sunwind.forces.sensing.forward import FluxModel
from sunwind.forces.sensing.row import ORBITAL_FRAME, AttitudeSolution
from sunwind.forces.sensing.smoothing import SmoothedRow, smoothed_rows
from sunwind.forces.sensing.tabulation import AttitudeSearch
from sunwind.forces.tables.engine import SweepRun, run_jobs
from sunwind.forces.tables.jobs import Job
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import Spacecraft

#: Rows whose best attitude is checked against the full forward model (one call each: 25 ms on the cube,
#: 16 s on the 27 000-side sample spacecraft).
CHECKED_ROWS = 1
#: The cells of the cap in that check [deg].
CHECK_CELL_DEG = 5.0
#: A measured flux above this many times the most any attitude gives its sensor is refused: it is in
#: other units (W, mW/m^2), or of another sensor.
IMPLAUSIBLE = 3.0


@dataclass(frozen=True)
class AttitudeFit:
    """Every row's attitude, and what it was found with.

    Attributes
    ----------
    rows : tuple of AttitudeSolution
    sensors : tuple of str
        The sensor parts, in the order of the fluxes.
    altitude_km : float
    relative_sigma : float
        The fluxes' relative 1-sigma error.
    floor_W_m2 : float
        The smallest 1-sigma error of a flux [W/m^2].
    model_error_W_m2 : float
        The flux model's largest difference from the full forward model
        (:func:`~sunwind.forces.earth.planet_radiation`) at the rows' best attitudes [W/m^2], when checked;
        else None.
    smooth_window_s : float or None
        The window the rows were smoothed over with the attitude's rate [s]; None: not smoothed.
    smoothed : tuple of SmoothedRow or None
        With smoothing (:func:`smoothed_attitudes`), each row's; None where a row is in eclipse or its
        window holds too few sunlit rows.

    Examples
    --------
    >>> AttitudeFit((), ("a",), 500.0, 0.01, 1.0, None).to_json()["frame"][:4]
    'body'
    """

    rows: tuple[AttitudeSolution, ...]
    sensors: tuple[str, ...]
    altitude_km: float
    relative_sigma: float
    floor_W_m2: float
    model_error_W_m2: float | None
    smooth_window_s: float | None = None
    smoothed: tuple[SmoothedRow | None, ...] = ()

    def to_json(self) -> dict:
        """``{"rows": [...], ...}`` with the frame, units and settings.

        Returns
        -------
        dict

        Examples
        --------
        >>> sorted(AttitudeFit((), ("a",), 500.0, 0.01, 1.0, None).to_json())[:4]
        ['altitude_km', 'floor_W_m2', 'frame', 'model_error_W_m2']
        """
        return {
            "frame": "body frame of the mesh; directions are unit vectors from the spacecraft",
            "orbital_frame": ORBITAL_FRAME,
            "sensors": list(self.sensors),
            "altitude_km": self.altitude_km,
            "relative_sigma": self.relative_sigma,
            "floor_W_m2": self.floor_W_m2,
            "model_error_W_m2": self.model_error_W_m2,
            "smooth_window_s": self.smooth_window_s,
            "rows": [self._row_json(k) for k in range(len(self.rows))],
        }

    def _row_json(self, k: int) -> dict:
        out = self.rows[k].to_json()
        if self.smooth_window_s is not None:
            smoothed = self.smoothed[k]
            out["smoothed"] = None if smoothed is None else smoothed.to_json()
        return out


def attitude_from_fluxes(
    model: Model | Spacecraft,
    rows: FluxRows,
    altitude_km: float,
    *,
    sigma: float = 0.01,
    floor_W_m2: float = 1.0,
    light: PlanetLight | None = None,
    reflections: str = "auto",
    run: SweepRun | None = None,
) -> AttitudeFit:
    """The Sun and nadir directions (and the attitude, given inertial directions) of every row of
    measured sensor fluxes.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model; the sensors are its parts named by ``rows.sensors``.
    rows : FluxRows
        The measured fluxes [W/m^2 of each sensor's area] and optional inertial directions
        (:func:`~sunwind.forces.sensing.flux_rows.read_flux_rows`).
    altitude_km : float
        Height above the planet [km].
    sigma : float
        Relative 1-sigma error of a flux, in (0, 1).
    floor_W_m2 : float
        Smallest 1-sigma error of a flux [W/m^2] (a sensor's absolute resolution), > 0.
    light : PlanetLight, optional
        Default the Earth at 1 au.
    reflections : str
        As for :func:`~sunwind.forces.earth.planet_radiation`.
    run : SweepRun, optional
        Chunks of rows, a checkpoint kept as they finish, resume, Dask and progress, as for sweeps
        (:class:`~sunwind.forces.tables.SweepRun`); default every row here, nothing kept.

    Returns
    -------
    AttitudeFit

    Raises
    ------
    InputError
        A bad ``sigma`` or ``floor_W_m2``, a sensor that is no part of the model, a bad altitude, a
        flux more than :data:`IMPLAUSIBLE` times the most any attitude gives its sensor.

    Examples
    --------
    Fluxes made by the model itself at one attitude are found again:

    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.flux_rows import FluxRows
    >>> black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    >>> sun, nadir = np.array([0.48, 0.6, 0.64]), np.array([0.0, -0.6, -0.8])
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> q = flux_model(cube, 500.0).fluxes(sun, nadir).total
    >>> rows = FluxRows(np.array([0.0]), cube.craft.part_names, q[None, :])
    >>> found = attitude_from_fluxes(cube, rows, 500.0).rows[0]
    >>> np.round(found.best.sun, 4) + 0.0, np.round(found.best.nadir, 4) + 0.0, found.ambiguous
    (array([0.48, 0.6 , 0.64]), array([ 0. , -0.6, -0.8]), False)
    """
    if not (math.isfinite(sigma) and 0.0 < sigma < 1.0):
        raise InputError(f"sigma {sigma} is not a relative error in (0, 1)", parameters=("sigma",))
    if not (math.isfinite(floor_W_m2) and floor_W_m2 > 0.0):
        raise InputError(f"floor {floor_W_m2} W/m^2 is not > 0", parameters=("floor_W_m2",))
    light = PlanetLight.of(planet("earth"), solar_flux()) if light is None else light
    model = as_model(model)
    rows.check_parts(model.craft.part_names)
    order = tuple(name for name in model.craft.part_names if name in rows.sensors)
    search = AttitudeSearch(order, float(altitude_km), sigma, floor_W_m2, light, reflections)
    fluxes, table = search.prepared(model)
    rows = rows.reordered(order)
    _check_plausible(rows, table, floor_W_m2)
    records = run_jobs(model, [Job(search, rows)], run or SweepRun())[search.kind]
    solved = search.solutions(records)
    error = _model_error(model, fluxes, solved)
    return AttitudeFit(solved, order, float(altitude_km), sigma, floor_W_m2, error)


def smoothed_attitudes(
    fit: AttitudeFit, rows: FluxRows, smooth_s: float, light: PlanetLight | None = None
) -> AttitudeFit:
    """The rows of a fit smoothed with the attitude's rate: each sunlit row fitted again with the sunlit
    rows within ``smooth_s / 2`` of it, the body turning at a constant rate over the window and the
    nadir at the orbit's mean motion (:func:`~sunwind.forces.sensing.smoothing.smoothed_rows`).

    Parameters
    ----------
    fit : AttitudeFit
        The rows solved alone (:func:`attitude_from_fluxes`).
    rows : FluxRows
        The rows it solved: their times and inertial directions (for the quaternions).
    smooth_s : float
        The window [s], > 0.
    light : PlanetLight, optional
        Default the Earth; only the Earth's GM is known (the orbit's mean motion).

    Returns
    -------
    AttitudeFit
        ``fit`` with :attr:`~AttitudeFit.smooth_window_s` and :attr:`~AttitudeFit.smoothed` set.

    Raises
    ------
    InputError
        A bad window, another planet, rows that are not the fit's.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing import read_flux_rows
    >>> black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    >>> rows = read_flux_rows(sw.meshes.sample_path().parent / "sensor_cube_fluxes.csv")[:4]
    >>> smoothed = smoothed_attitudes(attitude_from_fluxes(cube, rows, 500.0), rows, 900.0).smoothed
    >>> [s is not None for s in smoothed], smoothed[1].rows, np.round(smoothed[1].rate_deg_s, 2) + 0.0
    ([False, True, True, False], 3, array([ 0.1 , -0.07,  0.17]))
    """
    light = PlanetLight.of(planet("earth"), solar_flux()) if light is None else light
    motion = mean_motion(smooth_s, light, fit.altitude_km)
    if not np.array_equal(rows.time_s, [row.time_s for row in fit.rows]):
        raise InputError("the rows to smooth are not the rows the fit solved: their times differ")
    inertial = [rows.inertial(k) for k in range(len(rows))]
    return replace(
        fit,
        smooth_window_s=float(smooth_s),
        smoothed=smoothed_rows(fit.rows, float(smooth_s), motion, inertial),
    )


def mean_motion(window_s: float, light: PlanetLight, altitude_km: float) -> float:
    """The mean motion of a circular orbit at ``altitude_km`` about the Earth [rad/s], for smoothing.

    Parameters
    ----------
    window_s : float
        The smoothing window [s], checked: > 0 and finite.
    light : PlanetLight
        Its planet must be the Earth (the one whose GM is known here).
    altitude_km : float
        Height above the planet [km].

    Returns
    -------
    float

    Raises
    ------
    InputError
        A bad window, another planet.

    Examples
    --------
    >>> light = PlanetLight.of(planet("earth"), 1361.0)
    >>> round(360.0 / math.degrees(mean_motion(120.0, light, 500.0)) / 60.0, 1)  # the period [min]
    94.6
    """
    if not (math.isfinite(window_s) and window_s > 0.0):
        raise InputError(
            f"smooth_s {window_s:g} is not a smoothing window > 0 [s]",
            hint="the window is the time over which the attitude's rate is taken as constant, e.g. 120 s",
            parameters=("smooth_s",),
        )
    if light.planet.name != "earth":
        raise InputError(
            f"smoothing needs the orbit's mean motion: the Earth's GM is known, {light.planet.name}'s not",
            parameters=("smooth_s",),
        )
    return math.sqrt(EARTH_GM / (light.planet.radius_m + altitude_km * 1e3) ** 3)


def _check_plausible(rows: FluxRows, table: CoarseTable, floor_W_m2: float) -> None:
    """Refuse a flux more than :data:`IMPLAUSIBLE` times the most its sensor can absorb
    (:attr:`~sunwind.forces.sensing.coarse.CoarseTable.brightest`) and the resolution."""
    most = table.brightest
    over = rows.fluxes_W_m2 > IMPLAUSIBLE * most + floor_W_m2
    if over.any():
        k, p = (int(i[0]) for i in np.nonzero(over))
        raise InputError(
            f"t = {rows.time_s[k]:g} s: {rows.sensors[p]} {rows.fluxes_W_m2[k, p]:g} W/m^2 is more than "
            f"{IMPLAUSIBLE:g} times the most any attitude gives it ({most[p]:.4g} W/m^2; "
            f"{int(over.sum())} of the {over.size} fluxes are above it)",
            path=rows.source,
            hint="give the absorbed flux in W/m^2 of the sensor's area (not W or mW/m^2), each in its "
            "own sensor's column",
        )


def _model_error(model: Model, fluxes: FluxModel, solved: tuple[AttitudeSolution, ...]) -> float | None:
    """The flux model's largest difference from the full forward model (the cap cut into
    :data:`CHECK_CELL_DEG` cells, a shadow pass and trace each) at the best attitudes of the first
    :data:`CHECKED_ROWS` sunlit rows [W/m^2]; None without such a row."""
    craft = model.craft
    index = [craft.part_names.index(name) for name in fluxes.response.sensors]
    worst = None
    for row in [row for row in solved if not row.eclipse][:CHECKED_ROWS]:
        sun, nadir = row.best.sun, row.best.nadir
        approximate = fluxes.fluxes(sun, nadir)
        place = Place(nadir, fluxes.altitude_km, sun, solar_fraction=approximate.solar_fraction)
        full = planet_radiation(
            model,
            place,
            fluxes.light,
            reflections=fluxes.response.reflections,
            cap=CapSampling(CHECK_CELL_DEG, "cells"),
        )
        exact = sum(full.part_absorbed_W().values())[index] / fluxes.response.areas_m2
        difference = float(np.max(np.abs(exact - approximate.total)))
        worst = difference if worst is None else max(worst, difference)
    return worst
