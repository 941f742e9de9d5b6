"""Derivatives of the panel law with respect to the accommodation coefficients, forward mode (METHOD.md
"Free-molecular flow", "The open-sky integral").

Every law acts on the stream through a few numbers per law: ``a`` (``pressure_scale``), ``c``
(``shear_scale``), the diffuse push ``b`` and the first re-emission's two rates per species, and CLL's
reflected normal momentum ``R``; the panel's loads are linear in them, the rays and samples given.
So the derivative of a side's loads with respect to its own law's accommodation is the same sums run
on the derivatives of those numbers, over the same rays (:func:`~sunwind.forces.gas.visible.arrival`'s
``tangents``). A side's loads read only its own law, so one run per direction gives every side's
derivative with respect to its own material's coefficient. Two directions cover every law:

- direction 0: ``energy_accommodation`` of ``sentman`` and ``dria``, ``normal_accommodation`` of
  ``schaaf-chambre`` and ``cll`` (laws read one or the other, never both);
- direction 1: ``tangential_accommodation`` of ``schaaf-chambre`` and ``cll``.

The derivatives of a law (``alpha_E``: ``T_r / T = alpha_E tau_w + (1 - alpha_E) k S^2`` with ``k`` =
2/3 or 1/2; ``sigma_n``: ``a = 2 - sigma_n``, the diffuse share ``sigma_n`` at ``T_w``; ``sigma_t``:
``c``; CLL's ``alpha_n``: the Rice mean's slope, :func:`~sunwind.forces.gas.incident.rice_mean_slope`,
through the same quadratures and tables) are exact; CLL's quadrature nodes, which move with ``alpha_n``,
are held.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.angular import DirectionTables, SpeciesLaws, cll_normal_table, direction_tables
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.core_cone import core_cone
from sunwind.forces.gas.exchange import mean_momentum
from sunwind.forces.gas.incident import cll_reflected_normal, rice_mean_slope
from sunwind.forces.gas.laws import GasSurfaces
from sunwind.forces.gas.panel import GasGroups, closed_loads, species_streams
from sunwind.forces.gas.sum_kernels import species_sums
from sunwind.forces.gas.visible import PanelTangent, StreamTables
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GSI_MODELS
from sunwind.geometry.spacecraft import Spacecraft

#: The accommodation coefficients a law may read, in the order of the derivatives' second axis.
ACCOMMODATIONS = ("energy_accommodation", "normal_accommodation", "tangential_accommodation")
#: Per law, the accommodation (index into :data:`ACCOMMODATIONS`) of direction 0 and of direction 1;
#: -1 where the law has none.
DIRECTIONS: dict[str, tuple[int, int]] = {
    "sentman": (0, -1),
    "dria": (0, -1),
    "schaaf-chambre": (1, 2),
    "cll": (1, 2),
    "specular": (-1, -1),
}
#: ``k`` of ``T_r / T = alpha_E tau_w + (1 - alpha_E) k S^2``.
INCIDENT_SHARE = {"sentman": 2.0 / 3.0, "dria": 0.5}


@dataclass(frozen=True, eq=False)
class StreamTangent:
    """Derivative of one free stream's laws (:class:`~sunwind.forces.gas.visible.StreamTables`) along
    one direction (module docstring).

    Attributes
    ----------
    direction : int
        0 or 1 (module docstring).
    coefficient : (n_laws,) int64
        The accommodation (into :data:`ACCOMMODATIONS`) each law's derivative is taken by; -1 where
        the law reads none in this direction (its derivatives are zero).
    laws : SpeciesLaws
        The stream's species; the derivatives of ``pressure_scale``, ``shear_scale``, ``push`` and
        ``emission``.
    cll_tables : dict of int to ndarray
        Derivative of each CLL law's normal table; empty in direction 1 or without CLL.
    directions : DirectionTables
        The direction tables of the derivatives (``k_P`` itself in the momentum channel).
    gamma_table : (n_laws, 4, GAMMA_POINTS) float64
        Derivative of the core cone's table.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> from sunwind.forces.gas.visible import stream_tables
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> groups = gas_groups(craft)
    >>> stream = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> (energy,) = stream_tangents(craft, groups.surfaces, air, 7500.0, stream)  # sentman: no sigma_t
    >>> energy.direction, energy.coefficient.tolist()
    (0, [0])
    """

    direction: int
    coefficient: NDArray[np.int64]
    laws: SpeciesLaws
    cll_tables: dict[int, NDArray[np.float64]]
    directions: DirectionTables
    gamma_table: NDArray[np.float64]

    def panel(self, closed: NDArray[np.float64]) -> PanelTangent:
        """The :class:`~sunwind.forces.gas.visible.PanelTangent` of this direction.

        Parameters
        ----------
        closed : (n_groups, 5) float64
            :func:`closed_tangent` of the attitude.

        Returns
        -------
        PanelTangent

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.gas.panel import gas_groups
        >>> from sunwind.forces.gas.visible import stream_tables
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
        >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
        >>> groups = gas_groups(craft)
        >>> stream = stream_tables(craft, groups.surfaces, air, 7500.0)
        >>> energy = stream_tangents(craft, groups.surfaces, air, 7500.0, stream)[0]
        >>> energy.panel(np.zeros((6, 5))).pressure_scale
        array([0.])
        """
        return PanelTangent(
            closed=closed,
            channels=self.directions.channels,
            cll=self.directions.cll,
            pressure_scale=self.laws.pressure_scale,
            shear_scale=self.laws.shear_scale,
            gamma_table=self.gamma_table,
        )


def stream_tangents(
    craft: Spacecraft, surfaces: GasSurfaces, atmosphere: Atmosphere, speed_m_s: float, stream: StreamTables
) -> tuple[StreamTangent, ...]:
    """The :class:`StreamTangent` of a free stream, kept in the model's cache beside its tables.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    surfaces : GasSurfaces
        Its distinct laws (``GasGroups.surfaces``).
    atmosphere : Atmosphere
        The free stream.
    speed_m_s : float
        Flow speed [m/s].
    stream : StreamTables
        The stream's tables (:func:`~sunwind.forces.gas.visible.stream_tables`).

    Returns
    -------
    tuple of StreamTangent
        Direction 0 and direction 1 (module docstring), each where some law reads its coefficient.

    Raises
    ------
    InputError
        A CLL law with ``normal_accommodation`` 0, where the derivative is infinite.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> from sunwind.forces.gas.visible import stream_tables
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> groups = gas_groups(craft)
    >>> stream = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> stream_tangents(craft, groups.surfaces, air, 7500.0, stream)[0].directions.channels.shape
    (1, 4097, 4)
    """
    speed = float(f"{speed_m_s:.13g}")
    key = (speed, atmosphere.temperature_K, tuple(atmosphere.number_density_m3.items()))
    kept: dict = craft.cache.get("stream tangents", dict)
    if key not in kept or kept[key][0] is not stream:
        codes = [GSI_MODELS[code] for code in surfaces.code]
        used = [d for d in (0, 1) if any(DIRECTIONS[model][d] >= 0 for model in codes)]
        made = tuple(_tangent(craft, surfaces, atmosphere, speed, stream, d) for d in used)
        kept.clear()
        kept[key] = (stream, made)
    return kept[key][1]


def _tangent(
    craft: Spacecraft,
    surfaces: GasSurfaces,
    atmosphere: Atmosphere,
    speed: float,
    stream: StreamTables,
    direction: int,
) -> StreamTangent:
    coefficient, laws = law_derivatives(surfaces, stream.laws, atmosphere, speed, direction)
    tables = {}
    if direction == 0:
        s_high = float(math.ceil(laws.speed_ratio.max()))
        for law in np.flatnonzero(np.isfinite(laws.cll_alpha_n)):
            alpha, tau = float(laws.cll_alpha_n[law]), float(laws.cll_tau_w[law])
            if alpha <= 0.0:
                raise InputError(
                    "the derivative by a CLL normal_accommodation of 0 is infinite",
                    hint="give normal_accommodation > 0 for sensitivities",
                )
            tables[int(law)] = craft.cache.get(
                ("CLL normal slope table", alpha, tau, s_high),
                lambda a=alpha, t=tau: cll_normal_table(a, t, s_high, rice_mean_slope),
            )
    directions = direction_tables(laws, tables)
    gamma_table = core_cone(laws, tables, stream.cone.half_angle).gamma_table
    return StreamTangent(direction, coefficient, laws, tables, directions, gamma_table)


def law_derivatives(
    surfaces: GasSurfaces, laws: SpeciesLaws, atmosphere: Atmosphere, speed_m_s: float, direction: int
) -> tuple[NDArray[np.int64], SpeciesLaws]:
    """Derivatives of each law's numbers along one direction (module docstring).

    Parameters
    ----------
    surfaces : GasSurfaces
        The distinct laws, (n_laws,).
    laws : SpeciesLaws
        Their answer to the stream (:func:`~sunwind.forces.gas.panel.species_laws`).
    atmosphere : Atmosphere
        The free stream.
    speed_m_s : float
        Flow speed [m/s].
    direction : {0, 1}
        Which derivative.

    Returns
    -------
    coefficient : (n_laws,) int64
        The accommodation each law's derivative is by (into :data:`ACCOMMODATIONS`), -1 for none.
    derivatives : SpeciesLaws
        The stream's species, and the derivatives of ``pressure_scale``, ``shear_scale``, ``push``,
        ``emission``; CLL's ``cll_alpha_n`` and ``cll_tau_w`` as ``laws``.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.laws import MODEL_CODES
    >>> from sunwind.forces.gas.panel import species_laws
    >>> surfaces = GasSurfaces.of({"code": MODEL_CODES["schaaf-chambre"], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 0.8, "tangential_accommodation": 0.9, "wall_temperature_K": 300.0})
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> coefficient, d = law_derivatives(surfaces, species_laws(surfaces, air, 7500.0), air, 7500.0, 0)
    >>> coefficient.tolist(), d.pressure_scale.tolist(), d.shear_scale.tolist()
    ([1], [-1.0], [0.0])
    """
    temperature = atmosphere.temperature_K
    mass, density = species_streams(atmosphere)
    ratio = laws.speed_ratio
    n_laws = len(surfaces)
    coefficient = np.full(n_laws, -1, dtype=np.int64)
    pressure, shear = np.zeros(n_laws), np.zeros(n_laws)
    push, emission = np.zeros_like(laws.push), np.zeros_like(laws.emission)
    rate = density * speed_m_s  # incident molecules per unit flux over n_k V
    for row in range(n_laws):
        model = GSI_MODELS[surfaces.code[row]]
        coefficient[row] = DIRECTIONS[model][direction]
        wall = surfaces.wall_temperature_K[row]
        if coefficient[row] == 2:  # sigma_t: c = sigma_t
            shear[row] = 1.0
        elif model in INCIDENT_SHARE:  # alpha_E
            alpha, tau = surfaces.energy_accommodation[row], wall / temperature
            k = INCIDENT_SHARE[model]
            ratio_t = alpha * tau + (1.0 - alpha) * k * ratio**2
            slope = tau - k * ratio**2
            push[row] = math.sqrt(math.pi) / ratio * slope / (2.0 * np.sqrt(ratio_t))
            momentum = np.array(
                [mean_momentum(temperature * r, m) for r, m in zip(ratio_t, mass, strict=True)]
            )
            emission[row, :, 0] = rate * momentum * slope / (2.0 * ratio_t)
        elif model == "schaaf-chambre":  # sigma_n
            pressure[row] = -1.0
            push[row] = np.sqrt(math.pi * wall / temperature) / ratio
            emission[row, :, 0] = rate * np.array([mean_momentum(wall, m) for m in mass])
            emission[row, :, 1] = rate * np.sqrt(mass)
    derivatives = SpeciesLaws(
        speed_ratio=laws.speed_ratio,
        dynamic_pressure_Pa=laws.dynamic_pressure_Pa,
        pressure_scale=pressure,
        shear_scale=shear,
        push=push,
        emission=emission,
        cll_alpha_n=laws.cll_alpha_n,
        cll_tau_w=laws.cll_tau_w,
    )
    return coefficient, derivatives


def closed_tangent(
    groups: GasGroups,
    gamma: NDArray[np.float64],
    tangent: StreamTangent,
    u: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Derivative of :func:`~sunwind.forces.gas.panel.closed_loads` along ``tangent``'s direction.

    Parameters
    ----------
    groups : GasGroups
        The model's sides grouped by law and normal.
    gamma : (n_groups,) float64
        ``n . u`` of each group.
    tangent : StreamTangent
        The direction.
    u : (3,) float64
        Unit flow vector.

    Returns
    -------
    (n_groups, 5) float64
        Derivative of the force per unit area [Pa] (3) and of the first re-emission (2).

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.gas.panel import gas_groups
    >>> from sunwind.forces.gas.visible import stream_tables
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> groups = gas_groups(craft)
    >>> stream = stream_tables(craft, groups.surfaces, air, 7500.0)
    >>> energy = stream_tangents(craft, groups.surfaces, air, 7500.0, stream)[0]
    >>> u = np.array([1.0, 0.0, 0.0])
    >>> closed_tangent(groups, groups.normals @ u, energy, u).shape
    (6, 5)
    """
    laws = tangent.laws
    row = np.ascontiguousarray(groups.law, dtype=np.int64)
    gamma = np.clip(np.ascontiguousarray(gamma, dtype=np.float64), -1.0, 1.0)
    q = np.ascontiguousarray(laws.dynamic_pressure_Pa)
    sums = np.empty((len(gamma), 6))
    scales = (laws.pressure_scale, np.ascontiguousarray(laws.push), laws.shear_scale)
    species_sums(
        row, gamma, laws.speed_ratio, q, *scales, np.ascontiguousarray(laws.emission), sums, 0, len(gamma)
    )
    cll = np.flatnonzero(np.isfinite(laws.cll_alpha_n[row]) & (tangent.coefficient[row] == 1))
    if len(cll):  # d R / d alpha_n, by the closed form's quadrature
        for ratio, weight in zip(laws.speed_ratio, q, strict=True):
            normal = (gamma[cll], laws.cll_alpha_n[row[cll]], laws.cll_tau_w[row[cll]], float(ratio))
            directed = cll_reflected_normal(*normal, "directed", rice_mean_slope)
            full = cll_reflected_normal(*normal, "full", rice_mean_slope)
            sums[cll, 0] += weight * directed
            sums[cll, 2] += weight * (full - directed)
    return closed_loads(groups, gamma, sums, u)


def by_material(
    craft: Spacecraft,
    side_coefficient: NDArray[np.int64],
    side_force: NDArray[np.float64],
    side_torque: NDArray[np.float64],
    out: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> None:
    """Add each side's derivative to its material's entry of the coefficient it is by.

    Parameters
    ----------
    craft : Spacecraft
        The model (``side_material``).
    side_coefficient : (n_sides,) int64
        The accommodation (into :data:`ACCOMMODATIONS`) of each side's derivative, -1 for none.
    side_force, side_torque : (n_sides, 3) float64
        Derivatives of each side's force [N] and torque [N m].
    out : (force, torque), each (n_materials, 3, 3) float64
        Derivatives by material and accommodation; added to in place.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("w", 0.5, 0.5), threads=1).craft
    >>> out = (np.zeros((1, 3, 3)), np.zeros((1, 3, 3)))
    >>> by_material(craft, np.zeros(12, np.int64), np.ones((12, 3)), np.zeros((12, 3)), out)
    >>> out[0][0, 0]
    array([12., 12., 12.])
    """
    at = np.flatnonzero(side_coefficient >= 0)
    bins = craft.side_material[at].astype(np.int64) * 3 + side_coefficient[at]
    size = out[0].shape[0] * 3
    for total, sides in zip(out, (side_force, side_torque), strict=True):
        for c in range(3):
            total[:, :, c] += np.bincount(bins, weights=sides[at, c], minlength=size).reshape(-1, 3)
