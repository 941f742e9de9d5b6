"""Which inter-reflections an attitude includes (:mod:`~sunwind.forces.reflection.settings`), what the
direct light hands them, and what they add to the direct result (METHOD.md "Inter-reflection")."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.direct import ChannelWeights, DirectTotals
from sunwind.forces.radiation.moments import weight_moments
from sunwind.forces.reflection.beams import chain_model, follow_chains
from sunwind.forces.reflection.diffuse import MOMENTA, DiffuseExchange, DiffuseTotals, diffuse_exchange
from sunwind.forces.reflection.settings import ReflectionSettings, resolved_mode
from sunwind.forces.reflection.views import interference, model_view_factors
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import ViewFactors


@dataclass(frozen=True)
class PowerBalance:
    """Where the light that meets the spacecraft goes [W].

    ``incident_W = absorbed_W + escaped_W + truncated_W`` up to round-off; ``truncated_W`` is beam power
    dropped by the chain cutoff and depth (counted as staying on the spacecraft).

    Parameters
    ----------
    incident_W : float
        Power of the direct light meeting the lit sides [W].
    absorbed_W : float
        Power absorbed, directly and after reflection [W].
    escaped_W : float
        Power leaving the spacecraft (transmitted or reflected away) [W].
    truncated_W : float, optional
        Beam power dropped by the chains' cutoff and depth [W].

    Examples
    --------
    >>> balance = PowerBalance(100.0, 60.0, 39.0, 0.5)
    >>> round(balance.imbalance, 6)
    0.005
    >>> balance.to_json()["escaped_W"]
    39.0
    """

    incident_W: float
    absorbed_W: float
    escaped_W: float
    truncated_W: float = 0.0

    @property
    def imbalance(self) -> float:
        """``(incident - absorbed - escaped - truncated) / incident``."""
        if self.incident_W == 0:
            return 0.0
        rest = self.incident_W - self.absorbed_W - self.escaped_W - self.truncated_W
        return rest / self.incident_W

    def to_json(self) -> dict:
        """Fields and :attr:`imbalance` as a JSON-ready dict.

        Returns
        -------
        dict
            ``incident_W``, ``absorbed_W``, ``escaped_W``, ``truncated_W`` and ``imbalance``, floats.

        Examples
        --------
        >>> sorted(PowerBalance(1.0, 0.5, 0.5).to_json())
        ['absorbed_W', 'escaped_W', 'imbalance', 'incident_W', 'truncated_W']
        """
        return {
            "incident_W": self.incident_W,
            "absorbed_W": self.absorbed_W,
            "escaped_W": self.escaped_W,
            "truncated_W": self.truncated_W,
            "imbalance": self.imbalance,
        }


@dataclass(frozen=True)
class Reflected:
    """What inter-reflection (light) or the exchange of re-emitted molecules adds to the direct result
    of one attitude: one record for both.

    Parameters
    ----------
    mode : str
        The mode applied: ``none``, ``specular``, ``full`` or ``plates``.
    force_N : (3,) float64
        Force added to the direct force [N].
    torque_Nm : (3,) float64
        Torque added to the direct torque [N m].
    power : PowerBalance or None
        Where the light went; None for molecules.
    chains : BeamChainTotals or MoleculeChainTotals or None
        The chains' totals: mirror and transmitted beams (light), unaccommodated molecules
        (:class:`~sunwind.forces.gas.chains.MoleculeChainTotals`); None without chains.
    view : ViewFactors or None
        The view factors used, if any.
    k_is : float or None
        The interference criterion, where view factors were computed.

    Examples
    --------
    A white convex cube in ``specular`` mode: half the light is absorbed, the rest leaves and reflects
    nothing back:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.radiation.direct import direct_pass
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings("specular", cache_dir=False, rays_per_side=16)
    >>> plan = reflection_plan(craft, settings)
    >>> direct = direct_pass(craft, np.array([0.0, 0.6, 0.8]), np.zeros(3), None, 0.0, plan.weights)
    >>> reflected = reflected_part(craft, direct, 1361.0, np.zeros(3), settings, plan)
    >>> reflected.mode, reflected.force_N, round(reflected.power.escaped_W / reflected.power.incident_W, 6)
    ('specular', array([0., 0., 0.]), 0.5)
    """

    mode: str
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    power: PowerBalance | None
    chains: object | None  # BeamChainTotals, or the gas layer's MoleculeChainTotals
    view: ViewFactors | None
    k_is: float | None


#: Channels of :attr:`ReflectionPlan.weights`: power a closed body transmits (it leaves unchanged)
#: and power reflected diffusely, per watt of direct light; with ``full``, from ``NET`` the eight
#: sums of :attr:`~sunwind.forces.reflection.diffuse.DiffuseExchange.responses` over that diffuse light,
#: less, in the momentum slots, what eq. (4) took of it (leaving as from an open plate).
PASSED, DIFFUSE, NET = 0, 1, 2


@dataclass(frozen=True)
class ReflectionPlan:
    """Inter-reflection of one model with one setting, resolved before an attitude is cast.

    The direct light hands inter-reflection power on each lit side in proportion to the direct power there:
    ``weights`` per watt, summed by the direct pass (None for ``none``). Channels: :data:`PASSED`,
    :data:`DIFFUSE`, :data:`NET`.

    Parameters
    ----------
    mode : str
        ``none``, ``specular``, ``full`` or ``plates``; ``auto`` resolved.
    view : ViewFactors or None
        The model's view factors, where the setting uses them.
    k_is : float or None
        The interference criterion, where view factors were computed.
    exchange : DiffuseExchange or None
        The diffuse exchange, with ``full``.
    weights : ChannelWeights or None
        Per-side channel weights for the direct pass; None with ``none`` or ``plates``.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.radiation.direct import direct_pass
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings("specular", cache_dir=False, rays_per_side=16)
    >>> plan = reflection_plan(craft, settings)
    >>> direct = direct_pass(craft, np.array([0.0, 0.6, 0.8]), np.zeros(3), None, 0.0, plan.weights)
    >>> reflected = reflected_part(craft, direct, 1361.0, np.zeros(3), settings, plan)
    >>> plan.mode, plan.weights.channels, plan.exchange is None
    ('specular', 2, True)
    """

    mode: str  # none, specular, full or plates: auto resolved
    view: ViewFactors | None
    k_is: float | None
    exchange: DiffuseExchange | None
    weights: ChannelWeights | None


def reflection_plan(craft: Spacecraft, settings: ReflectionSettings) -> ReflectionPlan:
    """The :class:`ReflectionPlan` of ``craft`` with ``settings``, made once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        The mode (``auto`` resolved here by the model's ``K_IS``) and the view factors' sampling.

    Returns
    -------
    ReflectionPlan
        The resolved mode, view factors, exchange and channel weights.

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box_wing(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1)
    >>> reflection_plan(model.craft, ReflectionSettings("none")).mode
    'none'
    """
    return craft.cache.get(
        ("reflection plan", settings.mode, *settings.view_key), lambda: _plan(craft, settings)
    )


def _plan(craft: Spacecraft, settings: ReflectionSettings) -> ReflectionPlan:
    view, k_is, exchange = None, None, None
    if settings.uses_view_factors:
        view = model_view_factors(craft, settings)
        k_is = interference(craft, settings)
    mode = resolved_mode(settings.mode, k_is)
    weights = None
    if mode in ("specular", "full"):
        rho, beta, sigma = craft.side_optics.T
        diffuse = rho * (1 - beta)
        columns = [np.where(chain_model(craft).side_sheet, 0.0, sigma), diffuse]
        if mode == "full":
            exchange = diffuse_exchange(craft, settings)
            net = exchange.responses.copy()
            net[:, MOMENTA] -= exchange.open_sky_functionals[:, MOMENTA]
            columns += list((diffuse[:, None] * net).T)
        side = np.column_stack(columns)
        sampler = side_sampler(craft)
        block = weight_moments(
            side, craft.side_normals, craft.side_areas, sampler.side_block, sampler.n_blocks
        )
        weights = ChannelWeights(side, block)
    return ReflectionPlan(mode, view, k_is, exchange, weights)


def reflected_part(
    craft: Spacecraft,
    direct: DirectTotals,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    settings: ReflectionSettings,
    plan: ReflectionPlan,
    derivatives: bool = False,
) -> Reflected:
    """Compute inter-reflection's correction to the direct force and torque of one attitude.

    With the power balance, from the ``direct`` pass made with the ``plan``'s weights under
    ``flux_W_m2``.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    direct : DirectTotals
        The direct pass of the attitude.
    flux_W_m2 : float
        Solar flux [W/m^2].
    reference_m : (3,) float64
        Torque reference point [m].
    settings : ReflectionSettings
        The chains' cutoff and depth.
    plan : ReflectionPlan
        The model's plan under ``settings``; with ``none`` or ``plates`` nothing is added and all the
        light not absorbed escapes.
    derivatives : bool
        Trace the beam chains with their derivatives in every material's optics
        (:attr:`BeamChainTotals.derivatives`).

    Returns
    -------
    Reflected
        Force and torque added to the direct result, and the power balance.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.radiation.direct import direct_pass
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings("specular", cache_dir=False, rays_per_side=16)
    >>> plan = reflection_plan(craft, settings)
    >>> direct = direct_pass(craft, np.array([0.0, 0.6, 0.8]), np.zeros(3), None, 0.0, plan.weights)
    >>> reflected = reflected_part(craft, direct, 1361.0, np.zeros(3), settings, plan)
    >>> balance = reflected.power
    >>> round(balance.absorbed_W, 6), abs(balance.imbalance) < 1e-9
    (952.7, True)
    """
    light = direct.illumination
    power = direct.power(flux_W_m2)
    incident, absorbed, channels = power.incident_W, power.absorbed_W, power.channels_W
    if plan.mode in ("none", "plates"):
        power = PowerBalance(incident, absorbed, incident - absorbed)
        return Reflected(
            mode=plan.mode,
            force_N=np.zeros(3),
            torque_Nm=np.zeros(3),
            power=power,
            chains=None,
            view=plan.view,
            k_is=plan.k_is,
        )
    chains = follow_chains(
        craft,
        light,
        flux_W_m2,
        reference_m,
        settings.cutoff,
        settings.depth,
        light.level,
        derivatives=derivatives,
    )
    escaped = channels[PASSED] + chains.escaped_W
    absorbed += chains.absorbed_W
    if plan.mode == "specular":
        force = chains.force_N + chains.open_sky_force_N
        torque = chains.torque_Nm + chains.open_sky_torque_Nm
        escaped += channels[DIFFUSE] + chains.diffuse_source_W.sum()
    else:
        beams = plan.exchange.totals(chains.diffuse_source_W, reference_m)
        direct = DiffuseTotals.from_sums(channels[NET:], reference_m)
        force = chains.force_N + beams.force_N + direct.force_N
        torque = chains.torque_Nm + beams.torque_Nm + direct.torque_Nm
        escaped += beams.escaped_W + direct.escaped_W
        absorbed += beams.absorbed_W + direct.absorbed_W
    power = PowerBalance(incident, absorbed, float(escaped), chains.truncated_W)
    return Reflected(
        mode=plan.mode,
        force_N=force,
        torque_Nm=torque,
        power=power,
        chains=chains,
        view=plan.view,
        k_is=plan.k_is,
    )
