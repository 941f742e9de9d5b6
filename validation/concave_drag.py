"""Concave shapes in free-molecular flow: the panel solver against the test-particle Monte Carlo tracer.

The reference is :mod:`sunwind.validation.tpmc`, which samples molecules from the drifting Maxwellian and
follows every wall interaction. :func:`compare` runs the solver (``sunwind.forces.drag.drag``) with and
without
the exchange of re-emitted molecules beside it; :func:`drag_table` does every case. Both print
nothing.

Cases (:data:`DRAG_CASES`): the 90 deg V-groove, the open box and the sample spacecraft's dish of
:mod:`sunwind.validation.concave_meshes`, each a two-sided sheet, in one species (atomic oxygen at
1000 K) at speed ratio :data:`SPEED_RATIO` unless told, with diffuse re-emission fully accommodated to
the 300 K wall (Sentman, ``alpha_E = 1``: the kernel the tracer follows exactly), with Maxwell's kernel
of diffuse share 0.5 and with specular reflection, at flow directions into the opening and across it.
Flow directions are the azimuth and elevation of ``v_rel`` (molecules arrive along ``-v_rel``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sunwind.forces.gas.atmosphere import BOLTZMANN, SPECIES_MASS_KG, Atmosphere
from sunwind.geometry.materials import GasSurface, Material
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.validation.concave import sun_from_az_el, torque_scale
from sunwind.validation.concave_meshes import dish_mesh, open_box_mesh, v_groove_mesh
from sunwind.validation.sampling import Sampling
from sunwind.validation.tpmc import TpmcResult, trace_molecules
from sunwind.validation.tpmc_kernels import WallInteraction
from sunwind.validation.tpmc_source import SpeciesStream

#: Speed ratio of the comparison (the panel method's flow shadow is a quadrature that is good at large S:
#: METHOD.md "Approximations and limits").
SPEED_RATIO = 8.0
#: Free-stream gas: one species, its temperature [K] and number density [m^-3].
SPECIES, TEMPERATURE_K, NUMBER_DENSITY_M3 = "O", 1000.0, 1e15
#: Wall temperature [K].
WALL_TEMPERATURE_K = 300.0
#: Solver with re-emission against tracer: largest force and torque difference over their scales.
TOLERANCE = 0.02
#: Molecules the tracer launches per comparison.
MOLECULES = 200_000
#: Gas-surface laws compared: the solver's finish and the tracer's diffuse share for each (Maxwell's
#: kernel with diffuse share ``sigma`` is Schaaf-Chambre with ``sigma_n = sigma_t = sigma``).
LAWS = {
    "diffuse": (GasSurface(model="sentman", wall_temperature_K=WALL_TEMPERATURE_K), 1.0),
    "maxwell-0.5": (
        GasSurface(
            model="schaaf-chambre",
            normal_accommodation=0.5,
            tangential_accommodation=0.5,
            wall_temperature_K=WALL_TEMPERATURE_K,
        ),
        0.5,
    ),
    "specular": (GasSurface(model="specular", wall_temperature_K=WALL_TEMPERATURE_K), 0.0),
}


@dataclass(frozen=True)
class DragCase:
    """One concave shape and the flow directions (azimuth, elevation of ``v_rel`` [deg]) it is run at."""

    name: str
    mesh: Callable[[], MeshData]
    flows_deg: tuple[tuple[float, float], ...]
    size_m: float

    def spacecraft(self, law: str) -> Spacecraft:
        """The shape as two-sided sheets with gas-surface law ``law`` (a key of :data:`LAWS`)."""
        return build_spacecraft(
            self.mesh(), uniform=Material("wall", 0.0, 0.0, gas=LAWS[law][0]), two_sided=["*"]
        )


DRAG_CASES = (
    DragCase("v-groove", v_groove_mesh, ((0.0, 90.0), (0.0, 60.0), (35.0, 70.0)), 3.0),
    DragCase("open box", open_box_mesh, ((0.0, 90.0), (20.0, 65.0), (45.0, 40.0)), 1.0),
    DragCase("dish", lambda: dish_mesh(20_000), ((0.0, 90.0), (25.0, 60.0), (140.0, 35.0)), 1.2),
)


def free_stream(speed_ratio: float = SPEED_RATIO) -> tuple[Atmosphere, float]:
    """The comparison's atmosphere and the speed [m/s] that gives ``speed_ratio``."""
    air = Atmosphere({SPECIES: NUMBER_DENSITY_M3}, TEMPERATURE_K, "validation: atomic oxygen")
    speed = speed_ratio * math.sqrt(2 * BOLTZMANN * TEMPERATURE_K / SPECIES_MASS_KG[SPECIES])
    return air, speed


@dataclass(frozen=True)
class DragRow:
    """Solver against tracer for one case, law and flow direction; differences over the tracer's scales.

    ``force_difference`` is ``|F_solver - F_mc| / |F_mc|`` with the exchange of re-emitted molecules,
    ``force_difference_none`` without it (every re-emitted molecule escaping); torques likewise over
    :func:`sunwind.validation.concave.torque_scale`. ``*_sigma`` are the tracer's standard errors on the same
    scales.
    """

    case: str
    law: str
    azimuth_deg: float
    elevation_deg: float
    speed_ratio: float
    force_mc_N: float
    force_difference: float
    force_difference_none: float
    force_mc_sigma: float
    torque_difference: float
    torque_difference_none: float
    torque_mc_sigma: float
    k_is: float
    molecules: int
    tracer_seconds: float
    solver_seconds: float

    @property
    def passed(self) -> bool:
        return max(self.force_difference, self.torque_difference) <= TOLERANCE


def trace_case(
    case: DragCase,
    law: str,
    flow_deg: tuple[float, float],
    molecules: int,
    seed: int,
    speed_ratio: float = SPEED_RATIO,
) -> TpmcResult:
    """The tracer's force and torque for one case, law, flow direction and speed ratio."""
    air, speed = free_stream(speed_ratio)
    stream = SpeciesStream(speed, air.temperature_K, NUMBER_DENSITY_M3, SPECIES_MASS_KG[SPECIES])
    walls = WallInteraction(diffuse_fraction=LAWS[law][1], wall_temperature_K=WALL_TEMPERATURE_K)
    return trace_molecules(
        case.spacecraft(law), sun_from_az_el(*flow_deg), stream, walls, Sampling(molecules, seed=seed)
    )


def compare(
    case: DragCase,
    law: str,
    flow_deg: tuple[float, float],
    molecules: int = MOLECULES,
    seed: int = 0,
    speed_ratio: float = SPEED_RATIO,
) -> DragRow:
    """Solver (with and without re-emission exchange) against tracer at ``speed_ratio``, torques about
    the tracer's point."""
    from sunwind.forces.drag import drag  # the solver under test; the tracer needs none of it

    craft = case.spacecraft(law)
    start = time.perf_counter()
    mc = trace_case(case, law, flow_deg, molecules, seed, speed_ratio)
    tracer_seconds = time.perf_counter() - start
    air, speed = free_stream(speed_ratio)
    velocity = speed * sun_from_az_el(*flow_deg)
    start = time.perf_counter()
    full = drag(craft, velocity, air, reference_point_m=mc.reference_point_m, reflections="full")
    solver_seconds = time.perf_counter() - start
    none = drag(craft, velocity, air, reference_point_m=mc.reference_point_m, reflections="none")
    f_mc = float(np.linalg.norm(mc.force_N))
    scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)

    def force_gap(result) -> float:
        return float(np.linalg.norm(result.force_N - mc.force_N)) / f_mc

    def torque_gap(result) -> float:
        return float(np.linalg.norm(result.torque_Nm - mc.torque_Nm)) / scale

    return DragRow(
        case=case.name,
        law=law,
        azimuth_deg=flow_deg[0],
        elevation_deg=flow_deg[1],
        speed_ratio=speed_ratio,
        force_mc_N=f_mc,
        force_difference=force_gap(full),
        force_difference_none=force_gap(none),
        force_mc_sigma=float(np.linalg.norm(mc.force_se_N)) / f_mc,
        torque_difference=torque_gap(full),
        torque_difference_none=torque_gap(none),
        torque_mc_sigma=float(np.linalg.norm(mc.torque_se_Nm)) / scale,
        k_is=float(full.reflected.k_is),
        molecules=mc.molecules,
        tracer_seconds=tracer_seconds,
        solver_seconds=solver_seconds,
    )


def drag_table(
    cases: tuple[DragCase, ...] = DRAG_CASES, molecules: int = MOLECULES, seed: int = 0
) -> list[DragRow]:
    """:func:`compare` for every case, law and flow direction."""
    return [
        compare(case, law, flow, molecules, seed) for case in cases for law in LAWS for flow in case.flows_deg
    ]
