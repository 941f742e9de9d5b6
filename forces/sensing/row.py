"""One row of measured fluxes solved (METHOD.md "Attitude from heat fluxes").

The row's fluxes are matched over the whole sphere (:mod:`~sunwind.forces.sensing.search`): the
distinct minima within the noise are kept and ranked, an eclipse (no sunlight: the nadir alone) is
recognised when it explains the row as well as any sunlit attitude, and with the Sun's and the
nadir's inertial directions the attitude quaternion follows, and with the velocity the pitch, yaw and
roll in the orbital frame.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.stats
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from sunwind.forces.sensing.coarse import CoarseTable
from sunwind.forces.sensing.flux_rows import FluxRows
from sunwind.forces.sensing.forward import FluxModel
from sunwind.forces.sensing.search import (
    CONFIDENCE,
    STARTS,
    Minimum,
    at_known_angle,
    basins,
    dark_basins,
    dark_chart,
    free_chart,
    polished,
    refine,
    turned_chart,
    within_noise,
)

#: An eclipse is tried only when no flux is above this times the most any sensor takes in eclipse at the
#: coarse table's nadirs (plus 5 sigma): the table's nodes may miss the largest by a little.
DARK_MARGIN = 1.05
#: The orbital frame of the pitch, yaw and roll.
ORBITAL_FRAME = (
    "orbital frame: x along the velocity across the radius, y up (from the planet's centre), z = x cross y; "
    "body = orbital turned by pitch about z, then yaw about the new y, then roll about the new x"
)


@dataclass(frozen=True)
class AttitudeSolution:
    """The attitude found for one row of fluxes; body frame of the mesh.

    Attributes
    ----------
    time_s : float
        The row's time [s].
    best : Minimum
        The minimum of lowest misfit.
    alternatives : tuple of Minimum
        The other distinct minima within the noise, best first.
    eclipse : bool
        No sunlight explains the row: the nadir alone is found.
    quaternion : (4,) float64 or None
        Scalar-first, body to inertial (``v_inertial = q v_body q*``), when the row gave the Sun's and the
        nadir's inertial directions (and was not in eclipse).
    pitch_yaw_roll_deg : (3,) float64 or None
        With the velocity too: the body in the orbital frame (:data:`ORBITAL_FRAME`) [deg].
    measured : (p,) float64
        The row's fluxes [W/m^2].
    seconds : float
        Time the row took.

    Examples
    --------
    >>> best = Minimum(np.array([0.0, 0, 1]), np.array([0.0, 0, -1]), 1.5, 0.2, 0.3, np.zeros(6), 4)
    >>> row = AttitudeSolution(10.0, best, (), False, None, None, np.zeros(6), 0.01)
    >>> sorted(row.to_json())[:4]
    ['alternatives', 'ambiguous', 'eclipse', 'explained']
    """

    time_s: float
    best: Minimum
    alternatives: tuple[Minimum, ...]
    eclipse: bool
    quaternion: NDArray[np.float64] | None
    pitch_yaw_roll_deg: NDArray[np.float64] | None
    measured: NDArray[np.float64]
    seconds: float = field(compare=False)

    @property
    def ambiguous(self) -> bool:
        """Whether another distinct attitude fits within the noise."""
        return bool(self.alternatives)

    @property
    def explained(self) -> bool:
        """Whether the best attitude explains the fluxes within the noise: its chi2 below the
        :data:`~sunwind.forces.sensing.search.CONFIDENCE` quantile of chi-squared in the measurements
        less the unknowns (else the answer may be a wrong basin, or the model or the sigmas wrong)."""
        best = self.best
        dof = max(len(self.measured) - best.parameters, 1)
        return bool(best.chi2 <= scipy.stats.chi2.ppf(CONFIDENCE, dof))

    def to_json(self) -> dict:
        """Plain-JSON record; keys carry their units, directions are body-frame unit vectors.

        Returns
        -------
        dict

        Examples
        --------
        >>> best = Minimum(None, np.array([0.0, 0, -1]), 1.5, None, 0.3, np.zeros(6), 2)
        >>> AttitudeSolution(0.0, best, (), True, None, None, np.zeros(6), 0.01).to_json()["sun_body"] is None
        True
        """
        best = self.best
        return {
            "time_s": self.time_s,
            "sun_body": _listed(best.sun),
            "nadir_body": _listed(best.nadir),
            "pitch_yaw_roll_deg": _listed(self.pitch_yaw_roll_deg),
            "quaternion": _listed(self.quaternion),
            "sigma_deg": {"sun": best.sigma_sun_deg, "nadir": best.sigma_nadir_deg},
            "misfit": best.misfit,
            "ambiguous": self.ambiguous,
            "explained": self.explained,
            "eclipse": self.eclipse,
            "alternatives": [
                {"sun_body": _listed(m.sun), "nadir_body": _listed(m.nadir), "misfit": m.misfit}
                for m in self.alternatives
            ],
            "measured_W_m2": self.measured.tolist(),
            "modelled_W_m2": best.modelled.tolist(),
        }


def solve_row(
    fluxes: FluxModel, table: CoarseTable, rows: FluxRows, k: int, sigma: NDArray[np.float64]
) -> AttitudeSolution:
    """The attitude of row ``k`` of ``rows``: every distinct minimum within the noise, ranked.

    Parameters
    ----------
    fluxes : FluxModel
        The sensors' flux model (:func:`~sunwind.forces.sensing.forward.flux_model`), sensors in the order
        of ``rows``.
    table : CoarseTable
        Its coarse table (:func:`~sunwind.forces.sensing.coarse.coarse_table`): the basins' starts.
    rows : FluxRows
        The measured fluxes.
    k : int
        The row.
    sigma : (p,) float64
        Each flux's 1-sigma error [W/m^2].

    Returns
    -------
    AttitudeSolution

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.sensing.coarse import coarse_table
    >>> from sunwind.forces.sensing.forward import flux_model
    >>> black = sw.Material("black", 0.07, 0.0, emissivity=0.82)
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=black, threads=1)
    >>> fluxes = flux_model(cube, 500.0)
    >>> q = fluxes.fluxes(np.array([0.0, 0.6, 0.8]), np.array([0.0, -0.8, 0.6])).total
    >>> rows = FluxRows(np.array([0.0]), fluxes.response.sensors, q[None, :])
    >>> found = solve_row(fluxes, coarse_table(fluxes), rows, 0, 0.01 * q + 1.0)
    >>> np.round(found.best.sun, 3) + 0.0, found.eclipse
    (array([0. , 0.6, 0.8]), False)
    """
    start = time.perf_counter()
    measured = rows.fluxes_W_m2[k]
    inertial = rows.inertial(k)
    cos_known = None if inertial is None else float(inertial[0] @ inertial[1])
    p = len(measured)
    dark_known = cos_known is not None and _dark(fluxes, cos_known)
    dark: list[Minimum] = []
    if dark_known or not np.any(measured > DARK_MARGIN * table.darkest + 5.0 * sigma):  # eclipse possible
        dark = [
            refine(fluxes, dark_chart(n), measured, sigma, True) for n in dark_basins(table, measured, sigma)
        ]
    found: list[Minimum] = []
    if not dark_known:
        found = _refined(fluxes, basins(table, measured, sigma), measured, sigma, dark)
        if inertial is not None:  # each free minimum moved to the known angle, and refined there
            starts = [at_known_angle(m, inertial[0], inertial[1]) for m in _distinct(found)]
            found = [
                refine(fluxes, turned_chart(s, n), measured, sigma, False, traced=False) for s, n in starts
            ]
        found = _polished(fluxes, _distinct(found), measured, sigma)
    found = sorted(_distinct(found), key=lambda m: m.chi2)
    dark = sorted(_distinct(dark), key=lambda m: m.chi2)
    eclipse = dark_known or (
        bool(dark) and dark[0].chi2 <= (within_noise(found[0], p - found[0].parameters) if found else np.inf)
    )
    ranked = dark if eclipse else found
    best = ranked[0]
    limit = within_noise(best, p - best.parameters)
    alternatives = tuple(m for m in ranked[1:] if m.chi2 <= limit)
    quaternion = angles = None
    if inertial is not None and not eclipse:
        quaternion, angles = attitude_of(best.sun, best.nadir, inertial)
    return AttitudeSolution(
        float(rows.time_s[k]),
        best,
        alternatives,
        eclipse,
        quaternion,
        angles,
        measured,
        time.perf_counter() - start,
    )


def _refined(
    fluxes: FluxModel,
    starts: list[tuple[NDArray[np.float64], NDArray[np.float64]]],
    measured: NDArray[np.float64],
    sigma: NDArray[np.float64],
    dark: list[Minimum],
) -> list[Minimum]:
    """The free minima from the starts, best basin first: the first :data:`STARTS` ``[0]`` always, then
    more until one (or an eclipse of ``dark``) explains the row within the noise (its chi2 below the
    :data:`CONFIDENCE` quantile)."""
    enough = float(scipy.stats.chi2.ppf(CONFIDENCE, max(len(measured) - 4, 1)))
    found: list[Minimum] = []
    for k, (sun, nadir) in enumerate(starts):
        if k >= STARTS[0] and min(m.chi2 for m in [*found, *dark]) <= enough:
            break
        found.append(refine(fluxes, free_chart(sun, nadir), measured, sigma, False, traced=False))
    return found


def _polished(
    fluxes: FluxModel, found: list[Minimum], measured: NDArray[np.float64], sigma: NDArray[np.float64]
) -> list[Minimum]:
    """The minima that may rank (within twice the noise band of the best) refined again with sunlight
    traced (:func:`~sunwind.forces.sensing.search.polished`); the others dropped. Nothing changes on a
    model without a correction."""
    if fluxes.response.tracer is None or not found:
        return found
    best = min(found, key=lambda m: m.chi2)
    limit = best.chi2 + 2.0 * (within_noise(best, len(measured) - best.parameters) - best.chi2)
    return [polished(fluxes, m, measured, sigma) for m in found if m.chi2 <= limit]


def _dark(fluxes: FluxModel, cos_known: float) -> bool:
    """Whether the known angle between the Sun and the nadir puts the spacecraft in the umbra."""
    nadir = np.array([[0.0, 0.0, -1.0]])
    sun = np.array([[math.sqrt(max(0.0, 1.0 - cos_known**2)), 0.0, -cos_known]])
    return float(fluxes.solar_fraction(sun, nadir)[0]) == 0.0


def _distinct(minima: list[Minimum]) -> list[Minimum]:
    """The minima with the same directions merged (the lower misfit kept)."""
    kept: list[Minimum] = []
    for m in sorted(minima, key=lambda m: m.chi2):
        if not any(m.same_as(other) for other in kept):
            kept.append(m)
    return kept


def attitude_of(
    sun: NDArray[np.float64],
    nadir: NDArray[np.float64],
    inertial: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None],
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The attitude that takes the body-frame directions onto their inertial ones.

    Parameters
    ----------
    sun, nadir : (3,) float64
        Unit directions to the Sun and the planet's centre, body frame.
    inertial : (sun, nadir, velocity or None)
        The same directions in an inertial frame, and the velocity (:meth:`FluxRows.inertial`).

    Returns
    -------
    quaternion : (4,) float64
        Scalar-first, body to inertial, ``w >= 0``.
    pitch_yaw_roll_deg : (3,) float64 or None
        In the orbital frame (:data:`ORBITAL_FRAME`), with the velocity.

    Examples
    --------
    >>> z, x = np.array([0.0, 0, 1]), np.array([1.0, 0, 0])
    >>> q, angles = attitude_of(z, x, (x, -z, None))  # a quarter turn about y
    >>> np.round(q, 6) + 0.0, angles
    (array([0.707107, 0.      , 0.707107, 0.      ]), None)
    """
    turn, _ = Rotation.align_vectors(np.stack(inertial[:2]), np.stack([sun, nadir]))
    x, y, z, w = turn.as_quat()
    quaternion = np.array([w, x, y, z]) * (1.0 if w >= 0 else -1.0)
    if inertial[2] is None:
        return quaternion, None
    return quaternion, _pitch_yaw_roll(turn.as_matrix(), inertial[1], inertial[2])


def _pitch_yaw_roll(
    body_to_inertial: NDArray[np.float64], nadir_eci: NDArray[np.float64], velocity_eci: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Pitch, yaw and roll of the body in the orbital frame of :data:`ORBITAL_FRAME` [deg]."""
    up = -nadir_eci
    along = velocity_eci - (velocity_eci @ up) * up
    along /= np.linalg.norm(along)
    orbital = np.stack([along, up, np.cross(along, up)], axis=1)  # columns: the orbital axes, inertial
    return Rotation.from_matrix(orbital.T @ body_to_inertial).as_euler("ZYX", degrees=True)


def _listed(vector: NDArray[np.float64] | None) -> list[float] | None:
    return None if vector is None else [float(v) for v in vector]
