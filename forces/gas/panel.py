"""The panel law of one attitude: the gas-surface laws evaluated once per group of sides of one law and
one normal, summed over species, and the force and torque they put on every side (METHOD.md
"Free-molecular flow").

Per species ``k`` and side the law gives pressure and shear for the incident drifting Maxwellian, split
exactly into a *directed* stream (a cold beam along the flow) and the *thermal* rest; both are scaled
by the share of the side's incident molecules that arrives unobstructed (:mod:`.shadow`). Per-side
kernels run on the threads of :mod:`sunwind.geometry.parallel` and write per-side results, summed
afterwards: results do not depend on the number of threads.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import BOLTZMANN, Atmosphere
from sunwind.forces.gas.exchange import mean_momentum
from sunwind.forces.gas.laws import GasSurfaces
from sunwind.forces.gas.shadow import MIN_SIDES_PER_CHUNK
from sunwind.forces.gas.sum_kernels import group_stresses, side_forces
from sunwind.forces.gas.sums import diffuse_emission, summed_coefficients
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.spacecraft import Spacecraft

#: Columns of :func:`summed_laws` from which the first re-emission's momentum and molecules follow.
EMISSION = slice(4, None)


@dataclass(frozen=True)
class GasGroups:
    """The sides of one model grouped by gas-surface law and normal (equal bits): sides of a group
    share ``gamma`` and every coefficient, so the laws are evaluated once per group."""

    surfaces: GasSurfaces  # each distinct law, (n_laws,)
    law: NDArray[np.int64]  # law of each group, (n_groups,)
    normals: NDArray[np.float64]  # (n_groups, 3)
    side: NDArray[np.int64]  # group of each side, (n_sides,)


def gas_groups(craft: Spacecraft) -> GasGroups:
    """The :class:`GasGroups` of ``craft``, made once and kept in its cache."""
    return craft.cache.get("gas groups", lambda: _grouped(craft))


def _grouped(craft: Spacecraft) -> GasGroups:
    gas = craft.side_gas
    names = (
        "code",
        "energy_accommodation",
        "normal_accommodation",
        "tangential_accommodation",
        "wall_temperature_K",
    )
    columns = np.column_stack([gas[name].astype(np.float64) for name in names])
    table, side_law = np.unique(columns, axis=0, return_inverse=True)
    keys = np.column_stack([side_law.reshape(-1), craft.side_normals])
    _, first, side_group = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    surfaces = GasSurfaces(
        table[:, 0].astype(np.int64), *(np.ascontiguousarray(table[:, j]) for j in range(1, 5))
    )
    return GasGroups(
        surfaces=surfaces,
        law=side_law.reshape(-1)[first].astype(np.int64),
        normals=np.ascontiguousarray(craft.side_normals[first]),
        side=side_group.reshape(-1).astype(np.int64),
    )


def summed_laws(
    groups: GasGroups, gamma: NDArray[np.float64], atmosphere: Atmosphere, speed_m_s: float, re_emission: bool
) -> NDArray[np.float64]:
    """The gas-surface laws of each group (``gamma = n . u`` of each) summed over the species, each
    weighted by its dynamic pressure ``q_k`` [Pa]: :func:`~sunwind.forces.gas.sums.summed_coefficients`,
    (n_groups, 4), and with ``re_emission`` two more columns (:data:`EMISSION`): per unit area of the
    group and per unit share arriving unobstructed, the first re-emission's momentum per second [N/m^2]
    and its molecules per second weighted by the square root of their mass [sqrt(kg)/(s m^2)]
    (:mod:`sunwind.forces.gas.exchange`)."""
    temperature = atmosphere.temperature_K
    # species of equal mass (O and anomalous O) move alike: one stream of their summed density
    names = list(atmosphere.number_density_m3)
    mass, species = np.unique([atmosphere.mass_kg[name] for name in names], return_inverse=True)
    density = np.bincount(species, weights=list(atmosphere.number_density_m3.values()))
    ratio = speed_m_s / np.sqrt(2 * BOLTZMANN * temperature / mass)
    emission = None
    if re_emission:
        emission = np.empty((len(groups.surfaces), len(mass), 2))
        for k in range(len(mass)):
            share, re_temperature = diffuse_emission(groups.surfaces, ratio[k], temperature)
            rate = (
                share * density[k] * speed_m_s
            )  # molecules per second and unit area, per unit incident flux
            emission[:, k, 0] = rate * mean_momentum(re_temperature, mass[k])
            emission[:, k, 1] = rate * np.sqrt(mass[k])
    q = 0.5 * density * mass * speed_m_s**2
    return summed_coefficients(groups.surfaces, groups.law, gamma, ratio, q, temperature, emission)


@dataclass(frozen=True, eq=False)
class PanelForces:
    """The panel law on every side of one attitude, and its totals; body frame, SI."""

    force_N: NDArray[np.float64]  # (3,)
    torque_Nm: NDArray[np.float64]  # (3,) about the reference point
    side_force_N: NDArray[np.float64]  # (n_sides, 3)
    side_torque_Nm: NDArray[np.float64]  # (n_sides, 3)
    emitted: NDArray[np.float64]  # (k, n_sides): the EMISSION columns times area and arriving share


def panel_forces(
    craft: Spacecraft,
    groups: GasGroups,
    gamma: NDArray[np.float64],
    sums: NDArray[np.float64],
    visible: NDArray[np.float64],
    lit_centroid: NDArray[np.float64],
    u: NDArray[np.float64],
    reference_m: NDArray[np.float64],
) -> PanelForces:
    """Force and torque about ``reference_m`` [m] of every side from its group's :func:`summed_laws`
    ``sums`` (``gamma = n . u`` of each group), on the share ``visible`` (n_sides,) of its incident
    molecules that arrives unobstructed, acting at ``lit_centroid`` (n_sides, 3) on sides facing the flow."""
    stresses = group_stresses(gamma, sums, groups.normals, u)
    side_force, side_torque = np.empty((3, craft.n_sides)), np.empty((3, craft.n_sides))  # sum fast by rows
    emitted = np.empty((sums.shape[1] - 4, craft.n_sides))
    args = (
        groups.side,
        stresses,
        sums[:, EMISSION],
        craft.side_areas,
        visible,
        craft.side_centroids,
        lit_centroid,
    )
    map_ranges(
        lambda lo, hi: side_forces(*args, reference_m, side_force, side_torque, emitted, lo, hi),
        craft.n_sides,
        MIN_SIDES_PER_CHUNK,
    )
    return PanelForces(side_force.sum(axis=1), side_torque.sum(axis=1), side_force.T, side_torque.T, emitted)
