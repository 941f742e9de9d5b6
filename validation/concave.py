"""Concave validation cases, where light reflected by one facet strikes another: cases and comparison.

The reference for these shapes is the Monte Carlo photon tracer of
:mod:`sunwind.validation.photon_tracer`, plus, for a mirror V-groove lit in the plane across its axis,
the exact answer of :mod:`sunwind.validation.analytic_v_groove`. :func:`compare` and
:func:`reflection_table` put the solver (``sunwind.forces.srp.srp`` with ``reflections="full"``) beside
the tracer and return the numbers; they print nothing.

Cases (:data:`CONCAVE_CASES`, meshes in :mod:`sunwind.validation.concave_meshes`): a 90 deg V-groove of
two long plates, an L of two unequal plates, a cube open at the top, and the sample spacecraft's
paraboloidal dish. Every plate is a two-sided sheet meshed 8 x 8 cells or finer; each case is run with
each of its finishes (:data:`FINISHES`) at each of its Sun directions, given as azimuth/elevation
(METHOD.md "Frames, units and signs"), some off every symmetry plane.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes.samples import SAMPLE_OPTICS
from sunwind.validation.analytic_srp_law import Optics
from sunwind.validation.concave_meshes import dish_mesh, l_mesh, open_box_mesh, v_groove_mesh
from sunwind.validation.photon_tracer import TracerResult, trace_photons
from sunwind.validation.sampling import Sampling

__all__ = [
    "CONCAVE_CASES",
    "FINISHES",
    "MC_PHOTONS",
    "TOLERANCE",
    "TORQUE_LEVER",
    "ConcaveCase",
    "ReflectionRow",
    "compare",
    "finished_spacecraft",
    "reflection_table",
    "sun_from_az_el",
    "torque_scale",
    "trace_case",
]

#: Surface finishes of the concave cases, the same on both sides of every sheet unless a case says.
FINISHES: dict[str, Optics] = {
    "specular": Optics(0.9, 1.0, 0.0),
    "diffuse": Optics(0.9, 0.0, 0.0),
    "mixed": Optics(0.8, 0.5, 0.0),
}
#: A translucent film (sigma > 0) for the L's wall in its "translucent wall" finish.
TRANSLUCENT = Optics(0.5, 0.5, 0.3)
#: Solver against tracer: largest difference of force, torque and power, each over its scale [-].
TOLERANCE = 0.01
#: Torque scale where the torque is small: ``|F|`` times this share of the model size (:func:`torque_scale`).
TORQUE_LEVER = 0.25
#: Bundles the tracer launches per comparison; sets its standard error (see :func:`compare`).
MC_PHOTONS = 600_000

#: Part glob -> (front optics, back optics): the materials of one finish of a case.
PartOptics = Mapping[str, tuple[Optics, Optics]]


def sun_from_az_el(azimuth_deg: float, elevation_deg: float) -> NDArray[np.float64]:
    """Unit Sun vector from azimuth ``atan2(u_y, u_x)`` and elevation ``asin(u_z)`` [deg], body frame.

    Parameters
    ----------
    azimuth_deg : float
        Angle from +x toward +y of the vector's projection on the xy-plane [deg].
    elevation_deg : float
        Angle above the xy-plane [deg].

    Returns
    -------
    (3,) float64
        ``(cos el cos az, cos el sin az, sin el)``.

    Examples
    --------
    >>> (sun_from_az_el(90.0, 0.0).round(12) + 0.0).tolist()
    [0.0, 1.0, 0.0]
    """
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


# --------------------------------------------------------------------------------------------- cases


def _both(optics: Optics) -> PartOptics:
    return {"*": (optics, optics)}


@dataclass(frozen=True, eq=False)
class ConcaveCase:
    """A concave model, its finishes and the Sun directions it is checked at.

    Attributes
    ----------
    name : str
    mesh : callable
        ``mesh()`` builds the geometry (every part a sheet).
    finishes : mapping of str -> PartOptics
        Finish name -> part glob -> (front, back) optics; the first matching glob wins.
    suns_deg : tuple of (float, float)
        Sun directions as (azimuth, elevation) [deg].
    size_m : float
        Largest extent of the model [m], for :func:`torque_scale`.
    notes : str
        Sizes and why these Sun directions.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> tiny = ConcaveCase(
    ...     "tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), {"specular": {"*": (mirror, mirror)}},
    ...     ((0.0, 90.0),), size_m=3.0,
    ... )
    >>> tiny.spacecraft("specular")
    <Spacecraft 'tiny groove/specular': 8 facets, 16 sides, 2 parts, 2 materials>
    """

    name: str
    mesh: Callable[[], MeshData]
    finishes: Mapping[str, PartOptics]
    suns_deg: tuple[tuple[float, float], ...]
    size_m: float
    notes: str = ""

    def spacecraft(self, finish: str) -> Spacecraft:
        """The model with the materials of ``finish``; kept for reuse."""
        return _spacecraft(self, finish)


@lru_cache(maxsize=32)
def _spacecraft(case: ConcaveCase, finish: str) -> Spacecraft:
    return finished_spacecraft(case.mesh(), case.finishes[finish], f"{case.name}/{finish}")


def finished_spacecraft(mesh: MeshData, finish: PartOptics, source: str = "<concave>") -> Spacecraft:
    """Build ``mesh`` with ``finish``: every part a two-sided sheet, optics by its first matching glob.

    Parameters
    ----------
    mesh : MeshData
        The geometry, every part a sheet.
    finish : mapping of str to (Optics, Optics)
        Part glob -> (front, back) optics; the first matching glob wins.
    source : str, optional
        Name of the model in messages.

    Returns
    -------
    Spacecraft
        The model, one material per distinct optics.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import l_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> finished_spacecraft(l_mesh(divisions=1), {"*": (mirror, mirror)}, source="corner")
    <Spacecraft 'corner': 4 facets, 8 sides, 2 parts, 2 materials>
    """
    materials, parts = {}, {}
    for k, (glob, (front, back)) in enumerate(finish.items()):
        for side, optics in (("front", front), ("back", back)):
            materials[f"{side}{k}"] = {
                "reflectivity": optics.rho,
                "specular_fraction": optics.beta,
                "transmissivity": optics.sigma,
            }
        parts[glob] = {"front": f"front{k}", "back": f"back{k}"}
    document = {"materials": materials, "parts": parts}
    return build_spacecraft(replace(mesh, source=source), parse_materials(document, source=source))


def _sample_optics(name: str) -> Optics:
    values = SAMPLE_OPTICS[name]
    return Optics(values["reflectivity"], values["specular_fraction"], values["transmissivity"])


_MLI = _sample_optics("mli")

#: Every concave case. Azimuth 0 / 180 with elevation 90 - |psi| light the V-groove across its axis.
CONCAVE_CASES: tuple[ConcaveCase, ...] = (
    ConcaveCase(
        name="v-groove",
        mesh=v_groove_mesh,
        finishes={name: _both(optics) for name, optics in FINISHES.items()},
        suns_deg=((0.0, 90.0), (0.0, 70.0), (180.0, 55.0), (35.0, 60.0)),
        size_m=3.0,
        notes="w 1 m, L 3 m; first three Suns across the axis (psi 0, 20, -35 deg), the last off it",
    ),
    ConcaveCase(
        name="L",
        mesh=l_mesh,
        finishes={
            **{name: _both(optics) for name, optics in FINISHES.items()},
            "translucent wall": {"wall": (TRANSLUCENT, TRANSLUCENT), "floor": (FINISHES["mixed"],) * 2},
        },
        suns_deg=((30.0, 50.0), (-60.0, 25.0), (150.0, 40.0), (20.0, -30.0)),
        size_m=1.2,
        notes="floor 1 x 1.2 m, wall 0.6 m high; Suns on both fronts, the wall's back, the floor's back",
    ),
    ConcaveCase(
        name="open box",
        mesh=open_box_mesh,
        finishes={name: _both(optics) for name, optics in FINISHES.items()},
        suns_deg=((0.0, 90.0), (20.0, 65.0), (200.0, 45.0), (70.0, 15.0)),
        size_m=1.0,
        notes="unit cube without its top, two-sided walls; from straight in to nearly edge-on",
    ),
    ConcaveCase(
        name="dish",
        mesh=dish_mesh,
        finishes={
            **{name: {"*": (optics, _MLI)} for name, optics in FINISHES.items()},
            "sample": {"*": (_sample_optics("reflector_paint"), _MLI)},
        },
        suns_deg=((0.0, 90.0), (25.0, 60.0), (140.0, 35.0), (260.0, 15.0)),
        size_m=1.2,
        notes="the sample's dish, back in its MLI; on axis (specular: no second bounce) to 75 deg off",
    ),
)


# ------------------------------------------------------------------------------------------ comparison


def torque_scale(force_N: ArrayLike, torque_Nm: ArrayLike, size_m: float) -> float:
    """Scale of a torque error [N m]: ``max(|M|, |F| size_m / 4)``.

    The torque's own size, unless symmetry makes it small; then a shift of the force's line of action
    by a quarter of the model size, so that 1 % of the scale is a shift of 0.25 % of the size.

    Parameters
    ----------
    force_N : (3,) array_like
        Force [N].
    torque_Nm : (3,) array_like
        Torque [N m].
    size_m : float
        Largest extent of the model [m].

    Returns
    -------
    float
        The scale [N m].

    Examples
    --------
    >>> torque_scale([0.0, 0.0, 1e-6], [0.0, 0.0, 0.0], size_m=2.0)
    5e-07
    """
    return max(float(np.linalg.norm(torque_Nm)), float(np.linalg.norm(force_N)) * size_m * TORQUE_LEVER)


@dataclass(frozen=True)
class ReflectionRow:
    """Solver against tracer for one case, finish and Sun direction.

    Attributes
    ----------
    case, finish : str
    azimuth_deg, elevation_deg : float
        Sun direction [deg].
    force_solver_N, force_mc_N : float
        ``|F|`` from the solver and from the tracer [N].
    force_difference : float
        ``|F_solver - F_mc| / |F_mc|`` [-].
    force_mc_sigma : float
        Tracer's standard error of the force vector over ``|F_mc|`` [-].
    torque_scale_Nm : float
        :func:`torque_scale` of the tracer's loads [N m].
    torque_difference : float
        ``|M_solver - M_mc|`` over the torque scale [-].
    torque_mc_sigma : float
        Tracer's standard error of the torque vector over the torque scale [-].
    power_difference : float
        Largest difference of incident, absorbed and escaped power over the tracer's incident power [-].
    k_is : float
        The solver's interference criterion ``K_IS``, eq. (7) [-].
    photons : int
        Bundles the tracer launched.
    tracer_seconds, solver_seconds : float
        Wall-clock times [s].

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> tiny = ConcaveCase(
    ...     "tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), {"specular": {"*": (mirror, mirror)}},
    ...     ((0.0, 90.0),), size_m=3.0,
    ... )
    >>> row = compare(tiny, "specular", (0.0, 90.0), photons=2000)
    >>> row.case, row.passed
    ('tiny groove', True)
    """

    case: str
    finish: str
    azimuth_deg: float
    elevation_deg: float
    force_solver_N: float
    force_mc_N: float
    force_difference: float
    force_mc_sigma: float
    torque_scale_Nm: float
    torque_difference: float
    torque_mc_sigma: float
    power_difference: float
    k_is: float
    photons: int
    tracer_seconds: float
    solver_seconds: float

    @property
    def passed(self) -> bool:
        """Force, torque and power within :data:`TOLERANCE`."""
        return max(self.force_difference, self.torque_difference, self.power_difference) <= TOLERANCE


def trace_case(
    case: ConcaveCase,
    finish: str,
    sun_deg: tuple[float, float],
    photons: int = MC_PHOTONS,
    seed: int = 0,
    max_bounces: int = 100,
) -> TracerResult:
    """The tracer's loads for one case, finish and (azimuth, elevation), about the model's default point.

    Parameters
    ----------
    case : ConcaveCase
        The model, its finishes and Sun directions.
    finish : str
        One of ``case.finishes``.
    sun_deg : (float, float)
        Sun azimuth and elevation [deg] (:func:`sun_from_az_el`).
    photons : int, optional
        Bundles the tracer launches.
    seed : int, optional
        Seed of the tracer.
    max_bounces : int, optional
        Most interactions a bundle may have.

    Returns
    -------
    TracerResult
        Force [N] and torque [N m] with their standard errors, at 1361 W/m^2.

    Examples
    --------
    Mirrors, Sun overhead, a tiny mesh and few bundles:

    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> tiny = ConcaveCase(
    ...     "tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), {"specular": {"*": (mirror, mirror)}},
    ...     ((0.0, 90.0),), size_m=3.0,
    ... )
    >>> result = trace_case(tiny, "specular", (0.0, 90.0), photons=2000)
    >>> bool(result.force_N[2] < 0), result.photons
    (True, 2000)
    """
    sampling = Sampling(photons, seed=seed, max_bounces=max_bounces)
    return trace_photons(case.spacecraft(finish), sun_from_az_el(*sun_deg), sampling)


def compare(
    case: ConcaveCase,
    finish: str,
    sun_deg: tuple[float, float],
    photons: int = MC_PHOTONS,
    seed: int = 0,
) -> ReflectionRow:
    """Run the solver (``reflections="full"``) and the tracer (the physics) for one case, finish and Sun.

    Both at 1361 W/m^2, torques about the model's default reference point (its area centroid).

    Parameters
    ----------
    case : ConcaveCase
        The model, its finishes and Sun directions.
    finish : str
        One of ``case.finishes``.
    sun_deg : (float, float)
        Sun azimuth and elevation [deg] (:func:`sun_from_az_el`).
    photons : int, optional
        Bundles the tracer launches.
    seed : int, optional
        Seed of the tracer.

    Returns
    -------
    ReflectionRow
        Both loads, their differences and the tracer's standard errors.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> tiny = ConcaveCase(
    ...     "tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), {"specular": {"*": (mirror, mirror)}},
    ...     ((0.0, 90.0),), size_m=3.0,
    ... )
    >>> row = compare(tiny, "specular", (0.0, 90.0), photons=2000)
    >>> bool(row.force_difference < 1e-9), row.photons
    (True, 2000)
    """
    from sunwind.forces.srp import srp  # the solver under test; imported here so the tracer needs none of it

    craft = case.spacecraft(finish)
    mc = trace_case(case, finish, sun_deg, photons, seed)
    start = time.perf_counter()
    solver = srp(
        craft,
        sun_from_az_el(*sun_deg),
        flux_W_m2=mc.flux_W_m2,
        reference_point_m=mc.reference_point_m,
        reflections="full",
    )
    solver_seconds = time.perf_counter() - start
    f_mc = float(np.linalg.norm(mc.force_N))
    scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)
    power = solver.power
    power_gaps = (
        power.incident_W - mc.incident_W,
        power.absorbed_W - mc.absorbed_W,
        power.escaped_W - (mc.escaped_W + mc.cut_W),
    )
    return ReflectionRow(
        case=case.name,
        finish=finish,
        azimuth_deg=sun_deg[0],
        elevation_deg=sun_deg[1],
        force_solver_N=float(np.linalg.norm(solver.force_N)),
        force_mc_N=f_mc,
        force_difference=float(np.linalg.norm(solver.force_N - mc.force_N)) / f_mc,
        force_mc_sigma=mc.force_error_N / f_mc,
        torque_scale_Nm=scale,
        torque_difference=float(np.linalg.norm(solver.torque_Nm - mc.torque_Nm)) / scale,
        torque_mc_sigma=mc.torque_error_Nm / scale,
        power_difference=max(abs(g) for g in power_gaps) / mc.incident_W,
        k_is=float(solver.k_is),
        photons=mc.photons,
        tracer_seconds=mc.seconds,
        solver_seconds=solver_seconds,
    )


def reflection_table(
    cases: tuple[ConcaveCase, ...] = CONCAVE_CASES,
    photons: int = MC_PHOTONS,
    seed: int = 0,
) -> list[ReflectionRow]:
    """Run :func:`compare` for every case, finish and Sun direction, in that order.

    Parameters
    ----------
    cases : tuple of ConcaveCase, optional
        The cases; default :data:`CONCAVE_CASES` (minutes at the default ``photons``).
    photons : int, optional
        Bundles the tracer launches per row.
    seed : int, optional
        Seed of the tracer.

    Returns
    -------
    list of ReflectionRow
        One row per case, finish and Sun direction.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> mirror = Optics(1.0, 1.0, 0.0)
    >>> tiny = ConcaveCase(
    ...     "tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), {"specular": {"*": (mirror, mirror)}},
    ...     ((0.0, 90.0),), size_m=3.0,
    ... )
    >>> [row.finish for row in reflection_table((tiny,), photons=2000)]
    ['specular']
    """
    return [
        compare(case, finish, sun, photons, seed)
        for case in cases
        for finish in case.finishes
        for sun in case.suns_deg
    ]
