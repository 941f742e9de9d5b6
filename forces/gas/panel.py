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
    """Sides of one model grouped by gas-surface law and normal (equal bits).

    Sides of a group share ``gamma = n . u`` and every coefficient, so the laws are evaluated once per group.

    Parameters
    ----------
    surfaces : GasSurfaces
        Each distinct gas-surface law of the model, (n_laws,).
    law : (n_groups,) int64
        Law of each group, into ``surfaces``.
    normals : (n_groups, 3) float64
        Outward unit normal of each group.
    side : (n_sides,) int64
        Group of each side.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> len(groups.surfaces), groups.normals.shape, groups.side.shape
    (1, (6, 3), (12,))
    """

    surfaces: GasSurfaces  # each distinct law, (n_laws,)
    law: NDArray[np.int64]  # law of each group, (n_groups,)
    normals: NDArray[np.float64]  # (n_groups, 3)
    side: NDArray[np.int64]  # group of each side, (n_sides,)


def gas_groups(craft: Spacecraft) -> GasGroups:
    """Group the sides of ``craft`` by gas-surface law and normal, once; kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    GasGroups
        Its sides grouped by gas-surface law and normal.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> gas_groups(craft) is groups
    True
    """
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
    """Mass and number density of each stream of ``atmosphere``, by increasing mass.

    Species of equal mass (O and anomalous O) move alike: one stream of their summed density.

    Parameters
    ----------
    atmosphere : Atmosphere
        Number densities and temperature of the free stream.

    Returns
    -------
    mass : (k,) ndarray of float64
        Molecular mass of each stream [kg].
    density : (k,) ndarray of float64
        Number density of each stream [m^-3].

    Examples
    --------
    >>> import sunwind as sw
    >>> mass, density = species_streams(sw.explicit_atmosphere(1e-12, 1000.0, {"O": 0.5, "N2": 0.5}))
    >>> (mass / 1.66053907e-27).round(2), density / density[0]
    (array([16.  , 28.01]), array([1., 1.]))
    """
    names = list(atmosphere.number_density_m3)
    mass, species = np.unique([atmosphere.mass_kg[name] for name in names], return_inverse=True)
    return mass, np.bincount(species, weights=list(atmosphere.number_density_m3.values()))


def species_laws(surfaces: GasSurfaces, atmosphere: Atmosphere, speed_m_s: float) -> SpeciesLaws:
    """Free stream of one attitude by species, and how each law of ``surfaces`` answers it.

    Parameters
    ----------
    surfaces : GasSurfaces
        The model's distinct gas-surface laws, (n_laws,).
    atmosphere : Atmosphere
        Number densities and temperature of the free stream.
    speed_m_s : float
        Flow speed ``|v_rel|`` [m/s].

    Returns
    -------
    SpeciesLaws
        Speed ratio and dynamic pressure of each stream (:func:`species_streams`), and each law's
        pressure and shear factors, diffuse push and first re-emission.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> laws = species_laws(groups.surfaces, air, 7500.0)
    >>> laws.speed_ratio.round(3), laws.dynamic_pressure_Pa
    (array([7.357]), array([2.8125e-05]))
    """
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
    """Gas-surface laws of each group on an unobstructed side, summed over the species.

    Each species is weighted by its dynamic pressure ``q_k`` [Pa]
    (:func:`~sunwind.forces.gas.sums.summed_coefficients`).

    Parameters
    ----------
    groups : GasGroups
        The model's sides grouped by law and normal.
    gamma : (n_groups,) float64
        ``gamma = n . u`` of each group.
    laws : SpeciesLaws
        The free stream by species and each law's answer (:func:`species_laws`).
    temperature_K : float
        Free-stream temperature [K].

    Returns
    -------
    (n_groups, 6) ndarray of float64
        The four columns of :func:`~sunwind.forces.gas.sums.summed_coefficients`, and two more
        (:data:`EMISSION`): per unit area the first re-emission's momentum per second [N/m^2] and its
        molecules per second weighted by the square root of their mass [sqrt(kg)/(s m^2)]
        (:mod:`sunwind.forces.gas.exchange`).

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> gamma = groups.normals @ u
    >>> laws = species_laws(groups.surfaces, air, 7500.0)
    >>> sums = summed_laws(groups, gamma, laws, air.temperature_K)
    >>> sums.shape
    (6, 6)
    """
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
    """Compute what the whole incident stream does on an unobstructed side of each group.

    Parameters
    ----------
    groups : GasGroups
        The model's sides grouped by law and normal.
    gamma : (n_groups,) float64
        ``gamma = n . u`` of each group.
    sums : (n_groups, 6) float64
        :func:`summed_laws` of the groups.
    u : (3,) float64
        Unit flow vector ``v_rel / |v_rel|``.

    Returns
    -------
    (n_groups, 5) ndarray of float64
        Force per unit area [Pa] (3 columns) and the first re-emission (2 columns, :data:`EMISSION`).

    Examples
    --------
    The face whose normal is ``u`` is pushed back; the face behind it takes nothing:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> groups = gas_groups(craft)
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> gamma = groups.normals @ u
    >>> laws = species_laws(groups.surfaces, air, 7500.0)
    >>> sums = summed_laws(groups, gamma, laws, air.temperature_K)
    >>> loads = closed_loads(groups, gamma, sums, u)
    >>> facing, behind = np.flatnonzero(gamma == 1.0)[0], np.flatnonzero(gamma == -1.0)[0]
    >>> round(float(loads[facing, 0] / laws.dynamic_pressure_Pa[0]), 3), abs(float(loads[behind, 0])) < 1e-20
    (-2.15, True)
    """
    stresses = group_stresses(gamma, sums, groups.normals, u)
    return np.column_stack([stresses[:, :3] + stresses[:, 3:], sums[:, EMISSION]])
