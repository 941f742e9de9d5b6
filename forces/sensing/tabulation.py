"""The attitude of every row as a job of the sweep engine (:func:`~sunwind.forces.tables.engine.run_jobs`):
rows solved in chunks that a checkpoint keeps as they finish, an interrupted run resumed where it
stopped, locally or on Dask workers (METHOD.md "Attitude from heat fluxes").

A row's solution is kept as fixed-width records: the best minimum and its alternatives in
:data:`MINIMA` slots, the empty ones NaN; :meth:`AttitudeSearch.solutions` reads them back, bit for bit.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from typing import ClassVar

import numpy as np

from sunwind.forces.model import Model
from sunwind.forces.planet.bodies import PlanetLight
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensing.coarse import CoarseTable, coarse_table
from sunwind.forces.sensing.flux_rows import FluxRows
from sunwind.forces.sensing.forward import FluxModel, flux_model
from sunwind.forces.sensing.row import AttitudeSolution, solve_row
from sunwind.forces.sensing.search import STARTS, Minimum
from sunwind.forces.tables.jobs import Records

#: Minima kept per row, the best first: no more than the basins a row refines.
MINIMA = STARTS[1]

#: The last flux model and coarse table made in this process: (the craft, the search's settings, both).
_PREPARED: list[tuple[object, str, FluxModel, CoarseTable]] = []


@dataclass(frozen=True)
class AttitudeSearch:
    """How every row of measured fluxes is solved: a :class:`~sunwind.forces.tables.jobs.Tabulation`
    over :class:`~sunwind.forces.sensing.flux_rows.FluxRows`.

    Parameters
    ----------
    sensors : tuple of str
        The sensor parts, in the model's order (the rows' columns are put in it first).
    altitude_km : float
        Height above the planet [km].
    sigma : float
        Relative 1-sigma error of a flux.
    floor_W_m2 : float
        Smallest 1-sigma error of a flux [W/m^2].
    light : PlanetLight
        The planet and the Sun.
    reflections : str or ReflectionSettings
        As for :func:`~sunwind.forces.earth.planet_radiation`.

    Examples
    --------
    >>> from sunwind.forces.planet.bodies import planet
    >>> search = AttitudeSearch(("a", "b"), 500.0, 0.01, 1.0, PlanetLight.of(planet("earth"), 1361.0))
    >>> search.kind, search.fields["modelled_W_m2"], search.describe()["altitude_km"]
    ('attitude', 16, 500.0)
    """

    kind: ClassVar[str] = "attitude"
    sensors: tuple[str, ...]
    altitude_km: float
    sigma: float
    floor_W_m2: float
    light: PlanetLight
    reflections: str | ReflectionSettings = "auto"

    @property
    def fields(self) -> dict[str, int]:
        """The records of a row: name -> width; the minima's fields hold :data:`MINIMA` slots."""
        p = len(self.sensors)
        return {
            "time_s": 1,
            "seconds": 1,
            "eclipse": 1,
            "quaternion": 4,
            "pitch_yaw_roll_deg": 3,
            "measured_W_m2": p,
            "sun_body": 3 * MINIMA,
            "nadir_body": 3 * MINIMA,
            "chi2": MINIMA,
            "sigma_sun_deg": MINIMA,
            "sigma_nadir_deg": MINIMA,
            "parameters": MINIMA,
            "modelled_W_m2": p * MINIMA,
        }

    def prepared(self, model: Model) -> tuple[FluxModel, CoarseTable]:
        """The flux model and its coarse table, made once per process (the sensors' response is read
        from its disk cache after the first).

        Parameters
        ----------
        model : Model

        Returns
        -------
        (FluxModel, CoarseTable)

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.planet.bodies import planet
        >>> black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
        >>> light = PlanetLight.of(planet("earth"), 1361.0)
        >>> search = AttitudeSearch(cube.craft.part_names[:6], 500.0, 0.01, 1.0, light)
        >>> search.prepared(cube)[0] is search.prepared(cube)[0]
        True
        """
        settings = json.dumps(self.describe(), sort_keys=True)
        for craft, described, fluxes, table in _PREPARED:
            if craft is model.craft and described == settings:
                return fluxes, table
        fluxes = flux_model(model, self.altitude_km, self.light, self.sensors, self.reflections)
        table = coarse_table(fluxes)
        _PREPARED[:] = [(model.craft, settings, fluxes, table)]
        return fluxes, table

    def precompute(self, model: Model) -> None:
        """Make the flux model and its coarse table before the first chunk."""
        self.prepared(model)

    def evaluate(self, model: Model, rows: FluxRows) -> Records:
        """The records of ``rows`` (a chunk; sensors in :attr:`sensors` order), one row each.

        Parameters
        ----------
        model : Model
        rows : FluxRows

        Returns
        -------
        Records
            :attr:`fields`, one row per row.
        """
        fluxes, table = self.prepared(model)
        solved = [
            solve_row(fluxes, table, rows, k, np.maximum(self.sigma * np.abs(flux), self.floor_W_m2))
            for k, flux in enumerate(rows.fluxes_W_m2)
        ]
        return self.records(solved)

    def records(self, solved: list[AttitudeSolution]) -> Records:
        """The records of solved rows (:meth:`solutions` reads them back).

        Parameters
        ----------
        solved : list of AttitudeSolution

        Returns
        -------
        Records
        """
        n, p = len(solved), len(self.sensors)
        out = {name: np.full((n, width), math.nan) for name, width in self.fields.items()}
        for i, row in enumerate(solved):
            out["time_s"][i] = row.time_s
            out["seconds"][i] = row.seconds
            out["eclipse"][i] = float(row.eclipse)
            out["measured_W_m2"][i] = row.measured
            if row.quaternion is not None:
                out["quaternion"][i] = row.quaternion
            if row.pitch_yaw_roll_deg is not None:
                out["pitch_yaw_roll_deg"][i] = row.pitch_yaw_roll_deg
            for j, m in enumerate((row.best, *row.alternatives)):
                if m.sun is not None:
                    out["sun_body"][i, 3 * j : 3 * j + 3] = m.sun
                out["nadir_body"][i, 3 * j : 3 * j + 3] = m.nadir
                out["chi2"][i, j] = m.chi2
                out["sigma_sun_deg"][i, j] = _number(m.sigma_sun_deg)
                out["sigma_nadir_deg"][i, j] = _number(m.sigma_nadir_deg)
                out["parameters"][i, j] = m.parameters
                out["modelled_W_m2"][i, p * j : p * j + p] = m.modelled
        return {name: values[:, 0] if self.fields[name] == 1 else values for name, values in out.items()}

    def solutions(self, records: Records) -> tuple[AttitudeSolution, ...]:
        """The solved rows of records made by :meth:`records` (or kept by a checkpoint).

        Parameters
        ----------
        records : Records

        Returns
        -------
        tuple of AttitudeSolution

        Examples
        --------
        >>> from sunwind.forces.planet.bodies import planet
        >>> search = AttitudeSearch(("a",), 500.0, 0.01, 1.0, PlanetLight.of(planet("earth"), 1361.0))
        >>> best = Minimum(None, np.array([0.0, 0, -1]), 1.5, None, 0.3, np.ones(1), 2)
        >>> row = AttitudeSolution(5.0, best, (), True, None, None, np.ones(1), 0.01)
        >>> back = search.solutions(search.records([row]))[0]
        >>> back.eclipse, back.best.sun, back.best.nadir + 0.0, back.best.chi2, back.best.sigma_sun_deg
        (True, None, array([ 0.,  0., -1.]), 1.5, None)
        """
        p, n = len(self.sensors), len(records["time_s"])
        sun = records["sun_body"].reshape(n, MINIMA, 3)
        nadir = records["nadir_body"].reshape(n, MINIMA, 3)
        modelled = records["modelled_W_m2"].reshape(n, MINIMA, p)
        rows = []
        for i in range(n):
            minima = [
                Minimum(
                    None if np.isnan(sun[i, j, 0]) else sun[i, j].copy(),
                    nadir[i, j].copy(),
                    float(records["chi2"][i, j]),
                    _optional(records["sigma_sun_deg"][i, j]),
                    _optional(records["sigma_nadir_deg"][i, j]),
                    modelled[i, j].copy(),
                    int(records["parameters"][i, j]),
                )
                for j in range(MINIMA)
                if not np.isnan(nadir[i, j, 0])
            ]
            quaternion, angles = records["quaternion"][i], records["pitch_yaw_roll_deg"][i]
            rows.append(
                AttitudeSolution(
                    float(records["time_s"][i]),
                    minima[0],
                    tuple(minima[1:]),
                    bool(records["eclipse"][i]),
                    None if np.isnan(quaternion[0]) else quaternion.copy(),
                    None if np.isnan(angles[0]) else angles.copy(),
                    records["measured_W_m2"].reshape(n, p)[i].copy(),
                    float(records["seconds"][i]),
                )
            )
        return tuple(rows)

    def describe(self) -> dict:
        """JSON-ready settings: a checkpoint's fingerprint (the disk cache's place left out).

        Returns
        -------
        dict
        """
        reflections = asdict(ReflectionSettings.of(self.reflections))
        reflections.pop("cache_dir")
        return {
            "sensors": list(self.sensors),
            "altitude_km": float(self.altitude_km),
            "relative_sigma": float(self.sigma),
            "floor_W_m2": float(self.floor_W_m2),
            "light": self.light.description,
            "solar_flux_W_m2": float(self.light.solar_flux_W_m2),
            "reflections": reflections,
        }


def _number(value: float | None) -> float:
    return math.nan if value is None else value


def _optional(value: float) -> float | None:
    return None if np.isnan(value) else float(value)
