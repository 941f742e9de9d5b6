"""The panel law of one attitude on unobstructed sides: the free stream by species and how each
gas-surface law answers it, and the laws evaluated once per group of sides of one law and one normal,
summed over species (METHOD.md "Free-molecular flow").

What a side that sees only sky takes is this closed form; :mod:`.visible` takes off what its neighbours
block. Per-group kernels run on the threads of :mod:`sunwind.geometry.parallel` and write their own rows:
results do not depend on the number of threads.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.angular import SpeciesLaws
from sunwind.forces.gas.atmosphere import BOLTZMANN, Atmosphere
from sunwind.forces.gas.exchange import mean_momentum
from sunwind.forces.gas.incident import diffuse_normal
from sunwind.forces.gas.laws import GasSurfaces, reemission
from sunwind.forces.gas.sum_kernels import group_stresses
from sunwind.forces.gas.sums import summed_coefficients
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


def species_streams(atmosphere: Atmosphere) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mass [kg] and number density [m^-3] of each stream of ``atmosphere``: species of equal mass (O
    and anomalous O) move alike, one stream of their summed density; by increasing mass."""
    names = list(atmosphere.number_density_m3)
    mass, species = np.unique([atmosphere.mass_kg[name] for name in names], return_inverse=True)
    return mass, np.bincount(species, weights=list(atmosphere.number_density_m3.values()))


def species_laws(surfaces: GasSurfaces, atmosphere: Atmosphere, speed_m_s: float) -> SpeciesLaws:
    """The free stream of one attitude by species (:func:`species_streams`), and how each law of
    ``surfaces`` answers it (:class:`~sunwind.forces.gas.angular.SpeciesLaws`)."""
    temperature = atmosphere.temperature_K
    mass, density = species_streams(atmosphere)
    ratio = speed_m_s / np.sqrt(2 * BOLTZMANN * temperature / mass)
    n_laws, n_species = len(surfaces), len(mass)
    push, emission = np.empty((n_laws, n_species)), np.empty((n_laws, n_species, 2))
    for k in range(n_species):
        law = reemission(surfaces, float(ratio[k]), temperature)
        push[:, k] = law.diffuse_share * diffuse_normal(1.0, law.temperature_ratio, law.speed_ratio)
        share, re_temperature = law.emission_share, law.emission_temperature_K
        rate = share * density[k] * speed_m_s  # molecules per second and unit area, per unit incident flux
        emission[:, k, 0] = rate * mean_momentum(re_temperature, mass[k])
        emission[:, k, 1] = rate * np.sqrt(mass[k])
    cll_alpha_n = np.full(n_laws, np.nan) if law.cll_alpha_n is None else law.cll_alpha_n
    cll_tau_w = np.zeros(n_laws) if law.cll_tau_w is None else law.cll_tau_w
    return SpeciesLaws(
        speed_ratio=ratio,
        dynamic_pressure_Pa=0.5 * density * mass * speed_m_s**2,
        pressure_scale=law.pressure_scale,
        shear_scale=law.shear_scale,
        push=push,
        emission=emission,
        cll_alpha_n=cll_alpha_n,
        cll_tau_w=cll_tau_w,
    )


def summed_laws(
    groups: GasGroups, gamma: NDArray[np.float64], laws: SpeciesLaws, temperature_K: float
) -> NDArray[np.float64]:
    """The gas-surface laws of each group (``gamma = n . u`` of each) on an unobstructed side, summed over
    the species, each weighted by its dynamic pressure ``q_k`` [Pa]:
    :func:`~sunwind.forces.gas.sums.summed_coefficients`, (n_groups, 4), and two more columns
    (:data:`EMISSION`): per unit area the first re-emission's momentum per second [N/m^2] and its
    molecules per second weighted by the square root of their mass [sqrt(kg)/(s m^2)]
    (:mod:`sunwind.forces.gas.exchange`)."""
    return summed_coefficients(
        groups.surfaces,
        groups.law,
        gamma,
        laws.speed_ratio,
        laws.dynamic_pressure_Pa,
        temperature_K,
        laws.emission,
    )


def closed_loads(
    groups: GasGroups, gamma: NDArray[np.float64], sums: NDArray[np.float64], u: NDArray[np.float64]
) -> NDArray[np.float64]:
    """What the whole incident stream does on an unobstructed side of each group, (n_groups, 5): the
    force per unit area [Pa] (3) from :func:`summed_laws` ``sums`` and the first re-emission (2,
    :data:`EMISSION`)."""
    stresses = group_stresses(gamma, sums, groups.normals, u)
    return np.column_stack([stresses[:, :3] + stresses[:, 3:], sums[:, EMISSION]])
