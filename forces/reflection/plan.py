"""Which inter-reflections an attitude includes, and what they add to the direct result.

Modes (``--reflections``): ``none`` is the direct law, every reflected and transmitted photon leaving
to infinity; ``specular`` follows mirror and transmitted beams from surface to surface and lets
diffuse light leave as from an open plate; ``full`` also solves the diffuse balance with the view
factors; ``auto`` is ``full`` when ``K_IS >= 0.1`` (eq. 8), else ``none``.
"""

from __future__ import annotations

import os
import weakref
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.direct import weight_moments
from sunwind.forces.reflection.beams import (
    DEFAULT_CUTOFF,
    DEFAULT_DEPTH,
    ChainTotals,
    chain_model,
    follow_chains,
)
from sunwind.forces.reflection.diffuse import (
    DiffuseExchange,
    DiffuseTotals,
    diffuse_exchange,
    interference_criterion,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import VIEW_SEED, ViewFactors, view_factors

MODES = ("none", "specular", "full", "auto")
#: ``K_IS`` from which ``auto`` includes inter-reflection, eq. (8).
AUTO_THRESHOLD = 0.1


@dataclass(frozen=True)
class ReflectionSettings:
    """How inter-reflection is computed.

    Attributes
    ----------
    mode : str
        One of :data:`MODES`.
    cutoff : float
        A beam is dropped below this share of the power its chain started with.
    depth : int
        A chain is dropped after meeting this many surfaces.
    rays_per_side : int or None
        Hemisphere rays per side for the view factors; None for the default rule.
    cache_dir : path, None or False
        Where view factors are kept on disk (None: ``SUNWIND_CACHE_DIR`` or the user cache; False:
        not kept).
    """

    mode: str = "auto"
    cutoff: float = DEFAULT_CUTOFF
    depth: int = DEFAULT_DEPTH
    rays_per_side: int | None = None
    cache_dir: str | os.PathLike | bool | None = None

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            hint = f"use one of {', '.join(MODES)}"
            raise InputError(f"--reflections {self.mode!r} is not a mode", hint=hint)
        if not 0 <= self.cutoff < 1:
            raise InputError(f"reflection cutoff {self.cutoff} is not in [0, 1)", hint="default 1e-6")
        if self.depth < 1:
            raise InputError(f"reflection depth {self.depth} must be at least 1", hint="default 32")
        if self.rays_per_side is not None and self.rays_per_side < 1:
            raise InputError(f"--view-rays {self.rays_per_side} must be at least 1", hint="e.g. 1024")


_views: weakref.WeakKeyDictionary[Spacecraft, dict] = weakref.WeakKeyDictionary()


def model_view_factors(craft: Spacecraft, settings: ReflectionSettings) -> ViewFactors:
    """View factors of ``craft`` for ``settings``: from memory, else the disk cache, else computed."""
    kept = _views.setdefault(craft, {})
    key = (settings.rays_per_side, str(settings.cache_dir))
    if key not in kept:
        kept[key] = view_factors(craft, settings.rays_per_side, VIEW_SEED, settings.cache_dir)
    return kept[key]


def interference(craft: Spacecraft, settings: ReflectionSettings) -> float:
    """``K_IS`` of ``craft`` (eq. 7) with its view factors; kept with the model."""
    kept = _views.setdefault(craft, {})
    key = ("k_is", settings.rays_per_side, str(settings.cache_dir))
    if key not in kept:
        kept[key] = interference_criterion(craft, model_view_factors(craft, settings))
    return kept[key]


@dataclass(frozen=True)
class PowerBalance:
    """Where the light that meets the spacecraft goes [W].

    ``incident_W = absorbed_W + escaped_W + truncated_W`` up to round-off; ``truncated_W`` is beam
    power dropped by the chain cutoff and depth (counted as staying on the spacecraft).
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
        return {
            "incident_W": self.incident_W,
            "absorbed_W": self.absorbed_W,
            "escaped_W": self.escaped_W,
            "truncated_W": self.truncated_W,
            "imbalance": self.imbalance,
        }


@dataclass(frozen=True)
class Reflected:
    """What inter-reflection adds to the direct result of one attitude."""

    mode: str
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    power: PowerBalance
    chains: ChainTotals | None
    view: ViewFactors | None
    k_is: float | None


#: Channels of :attr:`ReflectionPlan.side_weights`: power a closed body transmits (it leaves unchanged)
#: and power reflected diffusely, per watt of direct light; with ``full``, from ``NET`` the eight
#: sums of :attr:`sunwind.forces.reflection.diffuse.DiffuseExchange.responses` over that diffuse light, less,
# in the
#: six momentum slots, what eq. (4) took of it (leaving as from an open plate).
PASSED, DIFFUSE, NET = 0, 1, 2


@dataclass(frozen=True)
class ReflectionPlan:
    """Inter-reflection of one model with one setting, resolved before an attitude is cast.

    The direct light hands inter-reflection power on each lit side in proportion to the direct power
    there: ``side_weights`` (n_sides, k) per watt, summed by the direct pass with their block moments
    ``block_weights`` (:func:`sunwind.forces.radiation.direct.weight_moments`); both None for ``none``.
    Channels:
    :data:`PASSED`, :data:`DIFFUSE`, :data:`NET`.
    """

    mode: str  # none, specular or full: auto resolved
    view: ViewFactors | None
    k_is: float | None
    exchange: DiffuseExchange | None
    side_weights: NDArray[np.float64] | None
    block_weights: NDArray[np.float64] | None

    @property
    def channels(self) -> int:
        """Number of weighted sums the direct pass makes for this plan."""
        return 0 if self.side_weights is None else self.side_weights.shape[1]


def reflection_plan(craft: Spacecraft, settings: ReflectionSettings) -> ReflectionPlan:
    """The :class:`ReflectionPlan` of ``craft`` with ``settings``, made once and kept with the model."""
    kept = _views.setdefault(craft, {})
    key = ("plan", settings.mode, settings.rays_per_side, str(settings.cache_dir))
    if key not in kept:
        mode, view, k_is, exchange = settings.mode, None, None, None
        if mode in ("full", "auto"):
            view = model_view_factors(craft, settings)
            k_is = interference(craft, settings)
            if mode == "auto":
                mode = "full" if k_is >= AUTO_THRESHOLD else "none"
        weights = moments = None
        if mode != "none":
            rho, beta, sigma = craft.side_optics.T
            diffuse = rho * (1 - beta)
            columns = [np.where(chain_model(craft).side_sheet, 0.0, sigma), diffuse]
            if mode == "full":
                exchange = diffuse_exchange(craft, view, settings.cache_dir)
                net = exchange.responses.copy()
                net[:, :6] -= exchange.open_sky_functionals[:, :6]
                columns += list((diffuse[:, None] * net).T)
            weights = np.column_stack(columns)
            sampler = craft.sampler
            moments = weight_moments(
                weights, craft.side_normals, craft.side_areas, sampler.side_block, sampler.n_blocks
            )
        kept[key] = ReflectionPlan(mode, view, k_is, exchange, weights, moments)
    return kept[key]


def reflected_part(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    settings: ReflectionSettings,
    plan: ReflectionPlan,
    direct_W: NDArray[np.float64],
) -> Reflected:
    """Inter-reflection's correction to the direct force and torque of one attitude, and the power
    balance. ``direct_W`` holds the incident and the absorbed power of the direct light [W], then its
    sums over the ``plan``'s channels [W], as the direct pass found them."""
    incident, absorbed = float(direct_W[0]), float(direct_W[1])
    channels = direct_W[2:]
    if plan.mode == "none":
        power = PowerBalance(incident, absorbed, incident - absorbed)
        return Reflected(plan.mode, np.zeros(3), np.zeros(3), power, None, plan.view, plan.k_is)
    chains = follow_chains(craft, light, flux_W_m2, reference_m, settings.cutoff, settings.depth, light.level)
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
    return Reflected(plan.mode, force, torque, power, chains, plan.view, plan.k_is)
