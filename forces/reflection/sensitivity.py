"""Derivatives of inter-reflection's force and torque with respect to every material's optics
(METHOD.md "Sensitivities").

The beam chains carry their own derivatives
(:class:`~sunwind.forces.reflection.chain_derivatives.ChainDerivatives`).
The diffuse balance ``M W = S``, ``M = I - diag(rho_d) E^T``, gives the totals ``y = g^T S`` with the
adjoint ``g = M^-T w`` made once per model; differentiating,

    dy = g^T dS + (dw + E diag(d rho_d) g + dE diag(rho_d) g)^T M^-1 S,

The exchange factors ``E`` and the escape functionals ``w`` depend on the mirror share ``rho_s`` and the
transmission ``sigma`` of the sides light passes on from: their derivatives are differenced once per model
and material set (second order, from builds with the same rays and random numbers). Every bracket is
fixed per model, so its adjoint response is solved once (:class:`ExchangeSensitivity`) and an attitude
costs one product with its sources.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import radiation_pressure
from sunwind.forces.radiation.sensitivity import direct_optics_derivatives, per_material
from sunwind.forces.reflection.beams import BeamChainTotals
from sunwind.forces.reflection.diffuse import (
    MOMENTA,
    DiffuseExchange,
    DiffuseTotals,
    escape_functionals,
    weighted_sum,
)
from sunwind.forces.reflection.plan import ReflectionPlan
from sunwind.forces.sensitivity import OPTICS, Sensitivities, optics_partials
from sunwind.geometry.memory import count, require
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.disk_cache import CacheEntryError, cache_directory, geometry_key, kept_on_disk
from sunwind.geometry.views.exchange_factors import compute_exchange_factors

#: Steps of the differenced exchange factors, in ``rho_s`` or ``sigma`` [-]: central differences inside
#: the bounds take a step small enough that no translucent mirror's random pick of a path flips; forward
#: ones from a bound (a share of 0) a step large enough that the new paths are not cut by the chains'
#: cutoff (1e-6 of their first weight) at their first surface.
EXCHANGE_STEP, BOUND_STEP = 1e-7, 1e-4


@dataclass(frozen=True, eq=False)
class ExchangeSensitivity:
    """What the balance does with a change of each material's diffuse share, mirror share and
    transmission, as adjoint responses: ``Z = M^-T U`` with the columns of ``U``, per material ``m``,
    ``E diag(1_m) g`` (a unit change of ``rho_d`` on its sides) and ``V = dw + dE diag(rho_d) g`` for a
    unit change of ``rho_s`` and of ``sigma`` there, momentum slots only; ``Z^T S`` is their effect for the
    sources ``S``.

    Attributes
    ----------
    responses : (n_sides, n_materials * 3 * 6) float64
        Columns ``[material, (rho_d, rho_s, sigma), slot]`` flattened in that order.
    origin : str
        "computed", or the disk cache it was read from or stored in.

    Examples
    --------
    >>> ExchangeSensitivity(np.zeros((4, 18))).responses.shape  # one material, four sides
    (4, 18)
    """

    responses: NDArray[np.float64]
    origin: str = "computed"


def exchange_sensitivity(
    craft: Spacecraft, exchange: DiffuseExchange, onward: bool = True
) -> ExchangeSensitivity:
    """The exchange's dependence on every material's optics, made once per model and material set and
    kept, in memory and on disk beside the exchange factors (``exchange_sensitivity-KEY.npz``, checked on
    read).

    Making it runs the exchange chains twice per material and channel (mirror share, transmission),
    for the rows whose light reaches that material.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    exchange : DiffuseExchange
        Its diffuse exchange for light, in the band of the exchange's own optics.
    onward : bool
        Also the changes of the mirror shares and transmissions (the solar band's free optics); False:
        the diffuse shares alone (the infrared, whose optics ``(1 - eps, 0, 0)`` move only them), their
        columns left zero and no exchange chains run.

    Returns
    -------
    ExchangeSensitivity

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import reflection_plan
    >>> white = sw.Material("white", reflectivity=0.8, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=white, threads=1).craft
    >>> exchange = reflection_plan(craft, sw.ReflectionSettings("full", cache_dir=False)).exchange
    >>> exchange_sensitivity(craft, exchange).responses.shape
    (144, 18)
    """
    # the model's exchanges are kept in this same cache (diffuse_exchange, infrared_exchange): while this
    # entry lives, so does the exchange whose id it names, and clear() drops them together
    key = ("exchange sensitivity", id(exchange), onward)
    return craft.cache.get(key, lambda: _kept(craft, exchange, onward))


def _kept(craft: Spacecraft, exchange: DiffuseExchange, onward: bool) -> ExchangeSensitivity:
    directory = cache_directory(exchange.cache_dir)
    if directory is None or not onward:  # without the chains' runs it is made in a moment
        return _exchange_sensitivity(craft, exchange, onward)
    view = exchange.view
    settings = {
        "kind": "exchange sensitivity",
        "step": [EXCHANGE_STEP, BOUND_STEP],
        "rays_per_side": view.rays_per_side,
        "seed": view.seed,
        "arrays": [
            hashlib.sha256(np.ascontiguousarray(array, dtype="<f8").tobytes()).hexdigest()
            for array in (exchange.optics, view.matrix.data, exchange.factors.matrix.data)
        ]
        + [hashlib.sha256(np.ascontiguousarray(craft.side_material, dtype="<i4").tobytes()).hexdigest()],
    }
    shape = (craft.n_sides, len(craft.materials) * 3 * 6)

    def decoded(arrays, origin: str) -> ExchangeSensitivity:
        responses = np.ascontiguousarray(arrays["responses"], dtype=np.float64)
        if responses.shape != shape or not np.isfinite(responses).all():
            raise CacheEntryError(f"holds responses of shape {responses.shape}, not {shape}, or non-finite")
        return ExchangeSensitivity(responses, origin)

    return kept_on_disk(
        directory,
        "exchange_sensitivity",
        geometry_key(craft, settings),
        lambda: _exchange_sensitivity(craft, exchange, onward),
        lambda value: {"responses": value.responses},
        decoded,
    )


def _exchange_sensitivity(craft: Spacecraft, exchange: DiffuseExchange, onward: bool) -> ExchangeSensitivity:
    rho, beta, sigma = exchange.optics.T
    g = exchange.responses[:, MOMENTA]
    weighted = (rho * (1.0 - beta))[:, None] * g  # diag(rho_d) g
    n_materials = len(craft.materials)
    # the columns, the responses and the solver's working copies of them
    require(
        4 * craft.n_sides * n_materials * 3 * 6 * 8,
        f"the diffuse balance's sensitivities: {count(craft.n_sides)} sides x {n_materials} materials x 18"
        " columns",
        'reflections "specular" (no diffuse balance), or fewer materials in the materials file',
    )
    columns = np.zeros((craft.n_sides, n_materials, 3, 6))
    for m in range(n_materials):
        mine = craft.side_material == m
        if not mine.any():
            continue
        columns[:, m, 0] = exchange.factors.matrix @ np.where(mine[:, None], g, 0.0)
        for channel, base in enumerate((rho * beta, sigma) if onward else ()):
            columns[:, m, 1 + channel] = _differenced(craft, exchange, mine, channel, base, weighted)
    flat = columns.reshape(craft.n_sides, -1)
    used = np.flatnonzero(np.abs(flat).max(axis=0) > 0)
    responses = np.zeros_like(flat)
    responses[:, used] = exchange.adjoint(flat[:, used])
    return ExchangeSensitivity(np.ascontiguousarray(responses))


def _differenced(
    craft: Spacecraft,
    exchange: DiffuseExchange,
    mine: NDArray[np.bool_],
    channel: int,
    base: NDArray[np.float64],
    weighted: NDArray[np.float64],
) -> NDArray[np.float64]:
    """``dw + dE diag(rho_d) g`` for a change of ``channel`` (0: ``rho_s``, 1: ``sigma``) on the sides
    ``mine``: central differences, or second-order forward ones from a bound."""
    value = float(base[mine][0])
    h = EXCHANGE_STEP if value >= EXCHANGE_STEP else BOUND_STEP
    steps, weights = ((-h, h), (-0.5, 0.5)) if value >= h else ((0.0, h, 2 * h), (-1.5, 2.0, -0.5))
    # only rows whose light reaches these sides change (first arrivals and later ones alike)
    rows = np.flatnonzero(exchange.factors.matrix @ mine.astype(np.float64) > 0)
    out = np.zeros((craft.n_sides, 6))
    if not len(rows):
        return out
    for step, weight in zip(steps, weights, strict=True):
        optics = _shifted(exchange.optics, mine, channel, step)
        factors = (
            exchange.factors
            if step == 0.0
            else compute_exchange_factors(craft, exchange.view, optics=optics, rows=rows)
        )
        functionals = escape_functionals(craft, factors)[rows][:, MOMENTA] + (factors.matrix @ weighted)[rows]
        out[rows] += weight / h * functionals
    return out


def _shifted(
    optics: NDArray[np.float64], mine: NDArray[np.bool_], channel: int, step: float
) -> NDArray[np.float64]:
    """``optics`` with ``rho_s`` (channel 0, ``rho_d`` kept) or ``sigma`` (1) moved by ``step`` on
    ``mine``."""
    out = optics.copy()
    rho, beta, sigma = optics[mine].T
    if channel == 1:
        out[mine, 2] = sigma + step
        return out
    specular = rho * beta + step
    total = rho + step
    out[mine, 0] = total
    out[mine, 1] = np.divide(specular, total, out=np.zeros_like(total), where=total > 0)
    return out


def diffuse_optics_derivatives(
    craft: Spacecraft,
    exchange: DiffuseExchange,
    direct_W: NDArray[np.float64],
    beam_source_W: NDArray[np.float64],
    beam_source_derivative_W: NDArray[np.float64] | None,
    reference_m: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """d force and d torque of the diffuse light, beyond eq. (4)'s open-plate share, per material optic.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    exchange : DiffuseExchange
        Its diffuse exchange for light.
    direct_W : (n_sides,) float64
        Direct power on each side, ``Phi A f c`` [W].
    beam_source_W : (n_sides,) float64
        Diffuse sources of the landed beams [W].
    beam_source_derivative_W : (n_sides, 3 n_materials) float64 or None
        Their derivatives, column ``3 m + k`` for coefficient ``k`` of material ``m``; None: no beams.
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    force, torque : (n_materials, 3, 3) float64
        ``[material, coefficient, component]``.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import reflection_plan
    >>> white = sw.Material("white", reflectivity=0.8, specular_fraction=0.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=white, threads=1).craft
    >>> exchange = reflection_plan(craft, sw.ReflectionSettings("full", cache_dir=False)).exchange
    >>> power = np.where(craft.side_normals[:, 2] > 0.5, 1.0, 0.0)  # 1 W on the top
    >>> force, _ = diffuse_optics_derivatives(craft, exchange, power, 0 * power, None, np.zeros(3))
    >>> bool(np.abs(force).max() < 1e-20)  # a convex box: diffuse light leaves as from an open plate
    True
    """
    rho, beta, _ = exchange.optics.T
    count = len(craft.materials)
    g = exchange.responses[:, MOMENTA]
    net = g - exchange.open_sky_functionals[:, MOMENTA]
    d_diffuse = optics_partials(rho, beta)[:, :, 2]  # d rho_d / d (rho, beta, sigma), per side
    # the Sun's diffuse sources beyond eq. (4)'s open plate, per side and coefficient
    per_side = d_diffuse[:, :, None] * (direct_W[:, None] * net)[:, None, :]
    sums = per_material(craft.side_material, per_side, count)  # (count, 3, 6)
    if beam_source_derivative_W is not None:
        sums += (beam_source_derivative_W.T @ g).reshape(count, 3, 6)
    source = rho * (1.0 - beta) * direct_W + beam_source_W
    response = weighted_sum(exchange_sensitivity(craft, exchange).responses, source).reshape(count, 3, 6)
    beta_m, rho_m = _material_column(craft, beta), _material_column(craft, rho)
    sums[:, 0] += (1.0 - beta_m) * response[:, 0] + beta_m * response[:, 1]  # rho moves rho_d and rho_s
    sums[:, 1] += rho_m * (response[:, 1] - response[:, 0])  # beta moves rho_s against rho_d
    sums[:, 2] += response[:, 2]
    return _loads(sums, reference_m)


def diffuse_emissivity_derivatives(
    craft: Spacecraft,
    exchange: DiffuseExchange,
    direct_W: NDArray[np.float64],
    reference_m: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """d force and d torque of diffuse infrared light, beyond eq. (4)'s open-plate share, per material
    emissivity: the infrared optics ``(1 - eps, 0, 0)`` move only the diffuse share, by ``-1``.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    exchange : DiffuseExchange
        Its diffuse exchange in the infrared.
    direct_W : (n_sides,) float64
        Infrared power arriving on each side [W].
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    force, torque : (n_materials, 3) float64
        Per unit emissivity.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.thermal import infrared_exchange
    >>> grey = sw.Material("grey", reflectivity=0.5, specular_fraction=0.0, emissivity=0.6)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> exchange = infrared_exchange(craft, sw.ReflectionSettings("full", cache_dir=False))
    >>> power = np.where(craft.side_normals[:, 2] > 0.5, 1.0, 0.0)
    >>> force, _ = diffuse_emissivity_derivatives(craft, exchange, power, np.zeros(3))
    >>> bool(np.abs(force).max() < 1e-20)  # a convex box: as eq. (4) says
    True
    """
    rho, beta, _ = exchange.optics.T
    count = len(craft.materials)
    g = exchange.responses[:, MOMENTA]
    net = g - exchange.open_sky_functionals[:, MOMENTA]
    sums = -per_material(craft.side_material, direct_W[:, None] * net, count)  # (count, 6)
    source = rho * (1.0 - beta) * direct_W
    response = weighted_sum(exchange_sensitivity(craft, exchange, onward=False).responses, source)
    sums -= response.reshape(count, 3, 6)[:, 0]
    return _loads(sums, reference_m)


def _loads(
    sums: NDArray[np.float64], reference_m: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Force and torque about ``reference_m`` of escaping-momentum sums ``(..., 6)`` (momentum rate and
    its moment about the origin, :data:`~sunwind.forces.reflection.diffuse.MOMENTA`), each ``(..., 3)``."""
    values = np.zeros((sums[..., 0].size, 8))
    values[:, MOMENTA] = sums.reshape(-1, 6)
    totals = [DiffuseTotals.from_sums(row, reference_m) for row in values]
    shape = (*sums.shape[:-1], 3)
    return (
        np.array([t.force_N for t in totals]).reshape(shape),
        np.array([t.torque_Nm for t in totals]).reshape(shape),
    )


def _material_column(craft: Spacecraft, side_values: NDArray[np.float64]) -> NDArray[np.float64]:
    """Each material's value of a per-side property, (n_materials, 1) (0 for a material no side has)."""
    out = np.zeros(len(craft.materials))
    out[craft.side_material] = side_values
    return out[:, None]


def optics_sensitivities(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    plan: ReflectionPlan,
    chains: BeamChainTotals | None,
) -> Sensitivities:
    """The sensitivities of one attitude's solar force and torque: direct light, beam chains and the
    diffuse balance, as the ``plan``'s mode has them.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    light : Illumination
        The attitude's lit shares and centroids.
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_m : (3,) float64
        Torque reference point [m].
    plan : ReflectionPlan
        The model's reflection plan.
    chains : BeamChainTotals or None
        The attitude's beam chains, traced with derivatives (None with ``none`` or ``plates``).

    Returns
    -------
    Sensitivities
        Optics columns filled; emissivity and accommodations zero.

    Examples
    --------
    >>> import sunwind as sw
    >>> white = sw.Material("white", reflectivity=0.5, specular_fraction=0.0)
    >>> model = sw.load(sw.meshes.box(), uniform=white, threads=1)
    >>> result = sw.srp(model, [0.0, 0.0, 1.0], reflections="none", sensitivities=True)
    >>> float(result.sensitivities.of("white.reflectivity").force_N[2])  # -(2/3) P A n, A = 1 m^2
    -3.026538...e-06
    """
    pressure = radiation_pressure(flux_W_m2)
    force, torque = direct_optics_derivatives(craft, light, pressure, reference_m)
    if chains is not None:
        derivatives = chains.derivatives
        force = force + derivatives.force_N
        torque = torque + derivatives.torque_Nm
        if plan.mode == "specular":
            force += derivatives.open_sky_force_N
            torque += derivatives.open_sky_torque_Nm
        else:
            sides = light.facing
            direct_W = np.zeros(craft.n_sides)
            direct_W[sides] = (
                flux_W_m2 * craft.side_areas[sides] * light.facing_share * light.cos_incidence[sides]
            )
            diffuse = diffuse_optics_derivatives(
                craft,
                plan.exchange,
                direct_W,
                chains.diffuse_source_W,
                derivatives.diffuse_source_W,
                reference_m,
            )
            force, torque = force + diffuse[0], torque + diffuse[1]
    out = Sensitivities.zeros(craft.materials.names, reference_m)
    out.force_N[:, : len(OPTICS)] = force
    out.torque_Nm[:, : len(OPTICS)] = torque
    return out
