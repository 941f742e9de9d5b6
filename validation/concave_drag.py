"""Concave shapes in free-molecular flow: the panel solver against the test-particle Monte Carlo tracer.

The reference is :mod:`sunwind.validation.tpmc`, which samples molecules from the drifting Maxwellian and
follows every wall interaction. :func:`compare` runs the solver (``sunwind.forces.drag.drag``) with and
without the exchange of re-emitted molecules beside it at one case, law, flow direction and gas;
:mod:`sunwind.validation.drag_matrix` runs the matrix of them. Neither prints anything.

Cases (:data:`DRAG_CASES`): the 90 deg V-groove, the L, the open box and the sample spacecraft's dish of
:mod:`sunwind.validation.concave_meshes`, each a two-sided sheet, and a closed 1 m cube bus with one
two-sided wing 0.2 m beside it, each at three flow directions: into the opening, across it, and last
one off every symmetry plane (the dish is a body of revolution: every flow lies on one of its planes).
Flow directions are the azimuth and elevation of ``v_rel`` (molecules arrive along ``-v_rel``).

Gas-surface laws (:data:`LAWS`), walls at 300 K, each a solver finish and the tracer kernel it stands
for: diffuse re-emission fully accommodated (Sentman, ``alpha_E = 1``), Maxwell's kernel of diffuse share
0.5 (Schaaf-Chambre with ``sigma_n = sigma_t = 0.5``), specular reflection, and Cercignani-Lampis-Lord
with ``alpha_n = sigma_t = 0.2`` and ``0.8``.

Gases (:class:`Gas`): one species (atomic oxygen at 1000 K) at the speed that gives a speed ratio
(:func:`oxygen`), or the NRLMSIS mixture at circular-orbit speed (:func:`msis_mixture`), each species at
its own speed ratio. The tracer traces each species apart and the loads are summed, standard errors in
quadrature.
"""

from __future__ import annotations

import math
import time
import zlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.validation.concave import sun_from_az_el, torque_scale
from sunwind.validation.concave_meshes import box_wing_mesh, dish_mesh, l_mesh, open_box_mesh, v_groove_mesh
from sunwind.validation.sampling import Sampling
from sunwind.validation.tpmc import TpmcResult, trace_molecules
from sunwind.validation.tpmc_kernels import WallInteraction
from sunwind.validation.tpmc_source import SpeciesStream

#: Single-species free stream: the species, its temperature [K] and number density [m^-3].
SPECIES, TEMPERATURE_K, NUMBER_DENSITY_M3 = "O", 1000.0, 1e15
#: Wall temperature [K].
WALL_TEMPERATURE_K = 300.0
#: Solver with re-emission against tracer: largest force and torque difference over their scales.
TOLERANCE = 0.02
#: The tracer's standard errors (force and torque, over the same scales) at most this share of
#: :data:`TOLERANCE`.
SIGMA_SHARE = 0.25
#: Independent batches of every tracer run (its standard errors scatter by ``1 / sqrt(2 (40 - 1))``, 11 %).
BATCHES = 40


@dataclass(frozen=True)
class Law:
    """A gas-surface law as the solver's finish (``surface``) and as the tracer's kernel (``walls``).

    Attributes
    ----------
    surface : GasSurface
        The solver's gas-surface model and parameters.
    walls : WallInteraction
        The same law as the tracer's kernel.

    Examples
    --------
    >>> LAWS["specular"].walls.diffuse_fraction, LAWS["specular"].surface.model
    (0.0, 'specular')
    """

    surface: GasSurface
    walls: WallInteraction


def _cll(accommodation: float) -> Law:
    """CLL with ``alpha_n = sigma_t = accommodation`` in the solver and in the tracer."""
    surface = GasSurface(
        model="cll",
        normal_accommodation=accommodation,
        tangential_accommodation=accommodation,
        wall_temperature_K=WALL_TEMPERATURE_K,
    )
    walls = WallInteraction(
        kernel="cll",
        diffuse_fraction=None,
        normal_accommodation=accommodation,
        tangential_accommodation=accommodation,
        wall_temperature_K=WALL_TEMPERATURE_K,
    )
    return Law(surface, walls)


def _maxwell(diffuse_share: float, surface: GasSurface) -> Law:
    """Maxwell's kernel of diffuse share ``diffuse_share`` in the tracer, ``surface`` in the solver."""
    return Law(
        surface, WallInteraction(diffuse_fraction=diffuse_share, wall_temperature_K=WALL_TEMPERATURE_K)
    )


#: Gas-surface laws compared, by name (Maxwell's kernel with diffuse share ``sigma`` is Schaaf-Chambre
#: with ``sigma_n = sigma_t = sigma``).
LAWS = {
    "diffuse": _maxwell(1.0, GasSurface(model="sentman", wall_temperature_K=WALL_TEMPERATURE_K)),
    "maxwell-0.5": _maxwell(
        0.5,
        GasSurface(
            model="schaaf-chambre",
            normal_accommodation=0.5,
            tangential_accommodation=0.5,
            wall_temperature_K=WALL_TEMPERATURE_K,
        ),
    ),
    "specular": _maxwell(0.0, GasSurface(model="specular", wall_temperature_K=WALL_TEMPERATURE_K)),
    "cll-0.2": _cll(0.2),
    "cll-0.8": _cll(0.8),
}


@dataclass(frozen=True)
class DragCase:
    """A shape, the flow directions it is run at, its size and its two-sided parts.

    Attributes
    ----------
    name : str
        Name in reports.
    mesh : callable
        ``mesh()`` builds the geometry.
    flows_deg : tuple of (float, float)
        Azimuth and elevation of ``v_rel`` [deg] of each run.
    size_m : float
        Largest extent [m], for :func:`sunwind.validation.concave.torque_scale`.
    two_sided : tuple of str, optional
        Globs of the parts that are sheets; the rest are closed bodies.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> tiny.mesh().n_faces, tiny.two_sided
    (8, ('*',))
    """

    name: str
    mesh: Callable[[], MeshData]
    flows_deg: tuple[tuple[float, float], ...]
    size_m: float
    two_sided: tuple[str, ...] = ("*",)


DRAG_CASES = (
    DragCase("v-groove", v_groove_mesh, ((0.0, 90.0), (0.0, 60.0), (35.0, 70.0)), 3.0),
    DragCase("L", l_mesh, ((0.0, 45.0), (30.0, 60.0), (160.0, 25.0)), 1.2),
    DragCase("open box", open_box_mesh, ((0.0, 90.0), (45.0, 40.0), (20.0, 65.0)), 1.0),
    DragCase("dish", lambda: dish_mesh(20_000), ((0.0, 90.0), (25.0, 60.0), (140.0, 35.0)), 1.2),
    DragCase("box-wing", box_wing_mesh, ((0.0, 0.0), (-60.0, 20.0), (120.0, 30.0)), 3.2, ("wing",)),
)


@dataclass(frozen=True, eq=False)
class Gas:
    """A row's free stream: the solver's atmosphere, the speed ``|v_rel|`` [m/s] and a name for reports.

    Attributes
    ----------
    name : str
        Name in reports, e.g. ``"O, S 8"``.
    atmosphere : Atmosphere
        Species number densities [m^-3] and temperature [K].
    speed_m_s : float
        ``|v_rel|`` [m/s].

    Examples
    --------
    >>> gas = oxygen(8.0)
    >>> gas.name, gas.speed_ratios, list(gas.streams())
    ('O, S 8', {'O': 8.0}, ['O'])
    """

    name: str
    atmosphere: Atmosphere
    speed_m_s: float

    @property
    def speed_ratios(self) -> dict[str, float]:
        """Speed ratio ``V / sqrt(2 k T / m_k)`` of each species [-]."""
        return self.atmosphere.speed_ratio(self.speed_m_s)

    def streams(self) -> dict[str, SpeciesStream]:
        """The tracer's free stream of each species (all have number density > 0), by name."""
        air = self.atmosphere
        return {
            k: SpeciesStream(self.speed_m_s, air.temperature_K, n, air.mass_kg[k])
            for k, n in air.number_density_m3.items()
        }


def oxygen(speed_ratio: float) -> Gas:
    """Atomic oxygen at 1000 K, 1e15 m^-3, at the speed that gives ``speed_ratio``.

    Parameters
    ----------
    speed_ratio : float
        ``S = V / sqrt(2 k T / m)`` [-].

    Returns
    -------
    Gas
        Named ``"O, S <speed_ratio>"``.

    Examples
    --------
    >>> round(oxygen(8.0).speed_m_s, 1)
    8156.0
    """
    air = Atmosphere({SPECIES: NUMBER_DENSITY_M3}, TEMPERATURE_K, "validation: atomic oxygen")
    speed = speed_ratio * math.sqrt(2 * BOLTZMANN * TEMPERATURE_K / SPECIES_MASS_KG[SPECIES])
    return Gas(f"O, S {speed_ratio:g}", air, speed)


@lru_cache(maxsize=4)
def msis_mixture(altitude_km: float = 900.0) -> Gas:
    """NRLMSIS at ``altitude_km`` (default place, time and indices) at circular-orbit speed there.

    Parameters
    ----------
    altitude_km : float, optional
        Geodetic altitude [km].

    Returns
    -------
    Gas
        Every NRLMSIS species with a number density > 0, named ``"NRLMSIS <altitude> km"``; cached.

    Examples
    --------
    >>> msis_mixture(900.0).name
    'NRLMSIS 900 km'
    """
    from sunwind.forces.gas import nrlmsis
    from sunwind.forces.gas.flow import circular_speed

    return Gas(f"NRLMSIS {altitude_km:g} km", nrlmsis(altitude_km), circular_speed(altitude_km))


@lru_cache(maxsize=8)
def spacecraft(case: DragCase, law: str) -> Spacecraft:
    """``case``'s shape with gas-surface law ``law`` (a key of :data:`LAWS`) on every side.

    Parameters
    ----------
    case : DragCase
        The shape and its two-sided parts.
    law : str
        A key of :data:`LAWS`.

    Returns
    -------
    Spacecraft
        The model; cached, the same object for the same arguments.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> spacecraft(tiny, "specular")
    <Spacecraft '<v-groove>': 8 facets, 16 sides, 2 parts, 1 materials>
    """
    material = Material("wall", 0.0, 0.0, gas=LAWS[law].surface)
    return build_spacecraft(case.mesh(), uniform=material, two_sided=case.two_sided)


def run_key(case: DragCase, law: str, flow_deg: tuple[float, float], gas: Gas, species: str) -> str:
    """The name of one species' tracer run, from which its seeds come (:func:`seed_of`).

    Parameters
    ----------
    case : DragCase
        The shape and its two-sided parts.
    law : str
        A key of :data:`LAWS`.
    flow_deg : (float, float)
        Azimuth and elevation of ``v_rel`` [deg].
    gas : Gas
        The free stream.
    species : str
        The species traced.

    Returns
    -------
    str
        ``"<case>/<law>/<azimuth>/<elevation>/<gas>/<species>"``.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> run_key(tiny, "diffuse", (0.0, 90.0), oxygen(8.0), "O")
    'tiny groove/diffuse/0/90/O, S 8/O'
    """
    return f"{case.name}/{law}/{flow_deg[0]:g}/{flow_deg[1]:g}/{gas.name}/{species}"


def seed_of(key: str) -> int:
    """A seed from a run's name: the same on every machine and in every process.

    Parameters
    ----------
    key : str
        The run's name (:func:`run_key`).

    Returns
    -------
    int
        A non-negative seed.

    Examples
    --------
    >>> seed_of("tiny groove/diffuse/0/90/O, S 8/O")
    1812333995
    """
    return zlib.crc32(key.encode())


def trace_gas(
    case: DragCase, law: str, flow_deg: tuple[float, float], gas: Gas, samplings: Mapping[str, Sampling]
) -> list[TpmcResult]:
    """Trace each species of ``gas`` on ``case`` with ``law``, about the model's default reference point.

    Parameters
    ----------
    case : DragCase
        The shape and its two-sided parts.
    law : str
        A key of :data:`LAWS`.
    flow_deg : (float, float)
        Azimuth and elevation of ``v_rel`` [deg].
    gas : Gas
        The free stream.
    samplings : mapping of str to Sampling
        Molecules, seed and batches of each species.

    Returns
    -------
    list of TpmcResult
        One per species, in the atmosphere's order.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> from sunwind.validation.sampling import Sampling
    >>> runs = trace_gas(tiny, "diffuse", (0.0, 90.0), oxygen(8.0), {"O": Sampling(2000, batches=4)})
    >>> len(runs), runs[0].molecules
    (1, 2000)
    """
    craft, flow = spacecraft(case, law), sun_from_az_el(*flow_deg)
    return [
        trace_molecules(craft, flow, stream, LAWS[law].walls, samplings[k])
        for k, stream in gas.streams().items()
    ]


@dataclass(frozen=True)
class TracedGas:
    """The tracer's loads summed over a gas's species.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64
        Force [N] and torque [N m] about ``reference_point_m``.
    force_se_N, torque_se_Nm : (3,) float64
        Their standard errors, added in quadrature over the species.
    reference_point_m : (3,) float64
        Torque reference point [m].
    molecules : int
        Molecules traced in all.
    seconds : float
        Wall-clock time of the runs [s].

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> from sunwind.validation.sampling import Sampling
    >>> runs = trace_gas(tiny, "diffuse", (0.0, 90.0), oxygen(8.0), {"O": Sampling(2000, batches=4)})
    >>> summed(runs).molecules
    2000
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    force_se_N: NDArray[np.float64]
    torque_se_Nm: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]
    molecules: int
    seconds: float


def summed(results: list[TpmcResult]) -> TracedGas:
    """Sum the loads of the species traced apart; standard errors added in quadrature.

    Parameters
    ----------
    results : list of TpmcResult
        One run per species, all about the same reference point.

    Returns
    -------
    TracedGas
        Their sum.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> from sunwind.validation.sampling import Sampling
    >>> runs = trace_gas(tiny, "diffuse", (0.0, 90.0), oxygen(8.0), {"O": Sampling(2000, batches=4)})
    >>> bool((summed(runs).force_N == runs[0].force_N).all())
    True
    """
    return TracedGas(
        force_N=np.sum([r.force_N for r in results], axis=0),
        torque_Nm=np.sum([r.torque_Nm for r in results], axis=0),
        force_se_N=np.sqrt(np.sum([r.force_se_N**2 for r in results], axis=0)),
        torque_se_Nm=np.sqrt(np.sum([r.torque_se_Nm**2 for r in results], axis=0)),
        reference_point_m=results[0].reference_point_m,
        molecules=sum(r.molecules for r in results),
        seconds=sum(r.seconds for r in results),
    )


@dataclass(frozen=True)
class DragRow:
    """Solver against tracer for one case, law, flow direction and gas; differences over the tracer's scales.

    Attributes
    ----------
    case, law, gas : str
        Names of the case, the law (a key of :data:`LAWS`) and the gas.
    azimuth_deg, elevation_deg : float
        Flow direction [deg].
    speed_ratios : tuple of (str, float)
        Each species and its speed ratio [-].
    force_mc_N : float
        The tracer's ``|F|`` [N].
    force_difference, force_difference_none : float
        ``|F_solver - F_mc| / |F_mc|`` [-] with the exchange of re-emitted molecules and without it
        (every re-emitted molecule escaping).
    force_mc_sigma : float
        The tracer's standard error of the force over ``|F_mc|`` [-].
    torque_difference, torque_difference_none, torque_mc_sigma : float
        Likewise for the torque, over :func:`sunwind.validation.concave.torque_scale` [-].
    molecules : int
        The tracer's molecules in all.
    tracer_seconds, solver_seconds : float
        Wall-clock times of the tracer's runs and of the solver with exchange [s].

    Examples
    --------
    >>> row = DragRow("groove", "diffuse", 0.0, 90.0, "O, S 8", (("O", 8.0),), 8e-3, 0.004, 0.014, 0.003,
    ...               0.003, 0.002, 0.003, 214_560, 1.0, 2.0)
    >>> row.passed
    True
    """

    case: str
    law: str
    azimuth_deg: float
    elevation_deg: float
    gas: str
    speed_ratios: tuple[tuple[str, float], ...]
    force_mc_N: float
    force_difference: float
    force_difference_none: float
    force_mc_sigma: float
    torque_difference: float
    torque_difference_none: float
    torque_mc_sigma: float
    molecules: int
    tracer_seconds: float
    solver_seconds: float

    @property
    def passed(self) -> bool:
        """Force and torque within :data:`TOLERANCE`, the tracer's standard errors within their share."""
        differences = max(self.force_difference, self.torque_difference) <= TOLERANCE
        return differences and max(self.force_mc_sigma, self.torque_mc_sigma) <= SIGMA_SHARE * TOLERANCE


def compare(
    case: DragCase, law: str, flow_deg: tuple[float, float], gas: Gas, molecules: Mapping[str, int]
) -> DragRow:
    """Run the solver (with and without re-emission exchange) against the tracer.

    Traces ``molecules[k]`` of each species ``k`` of ``gas`` (seeds from :func:`run_key`); torques are
    about the tracer's point.

    Parameters
    ----------
    case : DragCase
        The shape and its two-sided parts.
    law : str
        A key of :data:`LAWS`.
    flow_deg : (float, float)
        Azimuth and elevation of ``v_rel`` [deg].
    gas : Gas
        The free stream.
    molecules : mapping of str to int
        Molecules of each species.

    Returns
    -------
    DragRow
        The differences and the tracer's standard errors.

    Examples
    --------
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> row = compare(tiny, "diffuse", (0.0, 90.0), oxygen(8.0), {"O": 2000})
    >>> row.molecules, bool(row.force_difference < 0.05)
    (2000, True)
    """
    samplings = {
        k: Sampling(n, seed_of(run_key(case, law, flow_deg, gas, k)), BATCHES) for k, n in molecules.items()
    }
    mc = summed(trace_gas(case, law, flow_deg, gas, samplings))
    velocity = gas.speed_m_s * sun_from_az_el(*flow_deg)
    full, none, solver_seconds = _solve(spacecraft(case, law), velocity, gas, mc)
    f_mc = float(np.linalg.norm(mc.force_N))
    scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)

    def force_gap(force_N: NDArray[np.float64]) -> float:
        return float(np.linalg.norm(force_N - mc.force_N)) / f_mc

    def torque_gap(torque_Nm: NDArray[np.float64]) -> float:
        return float(np.linalg.norm(torque_Nm - mc.torque_Nm)) / scale

    return DragRow(
        case=case.name,
        law=law,
        azimuth_deg=flow_deg[0],
        elevation_deg=flow_deg[1],
        gas=gas.name,
        speed_ratios=tuple(gas.speed_ratios.items()),
        force_mc_N=f_mc,
        force_difference=force_gap(full.force_N),
        force_difference_none=force_gap(none.force_N),
        force_mc_sigma=float(np.linalg.norm(mc.force_se_N)) / f_mc,
        torque_difference=torque_gap(full.torque_Nm),
        torque_difference_none=torque_gap(none.torque_Nm),
        torque_mc_sigma=float(np.linalg.norm(mc.torque_se_Nm)) / scale,
        molecules=mc.molecules,
        tracer_seconds=mc.seconds,
        solver_seconds=solver_seconds,
    )


def _solve(craft: Spacecraft, velocity_m_s: NDArray[np.float64], gas: Gas, mc: TracedGas):
    """The solver's results with and without exchange about the tracer's point, and the seconds of the
    first."""
    from sunwind.forces.drag import drag  # the solver under test; the tracer needs none of it

    point = mc.reference_point_m
    start = time.perf_counter()
    full = drag(craft, velocity_m_s, gas.atmosphere, reference_point_m=point, reflections="full")
    seconds = time.perf_counter() - start
    none = drag(craft, velocity_m_s, gas.atmosphere, reference_point_m=point, reflections="none")
    return full, none, seconds
