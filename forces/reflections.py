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

from geometry.errors import InputError
from geometry.illumination import Illumination
from geometry.spacecraft import Spacecraft
from geometry.view_factors import VIEW_SEED, ViewFactors, view_factors

from . import chain_kernels as kernels
from .radiosity import diffuse_exchange, interference_criterion
from .specular_chains import DEFAULT_CUTOFF, DEFAULT_DEPTH, ChainTotals, chain_model, follow_chains

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


@dataclass(frozen=True)
class _DirectPower:
    """Power of the direct light per destination, from the lit shares."""

    incident_W: float
    absorbed_W: float
    passed_W: float  # transmitted by closed bodies: leaves unchanged
    diffuse_W: NDArray[np.float64]  # (n_sides,) first diffuse reflection of each side


def _direct_power(craft: Spacecraft, light: Illumination, flux_W_m2: float) -> _DirectPower:
    diffuse = np.zeros(craft.n_sides)
    incident, absorbed, passed = kernels.direct_power(
        light.facing,
        light.lit_fraction,
        craft.side_areas,
        craft.side_normals,
        craft.side_optics,
        chain_model(craft).side_sheet,
        light.direction,
        flux_W_m2,
        diffuse,
    )
    return _DirectPower(incident, absorbed, passed, diffuse)


def reflected_part(
    craft: Spacecraft,
    light: Illumination,
    flux_W_m2: float,
    reference_m: NDArray[np.float64],
    settings: ReflectionSettings,
    direct_W: tuple[float, float],
) -> Reflected:
    """Inter-reflection's correction to the direct force and torque of one attitude, and the power
    balance; the mode ``auto`` resolved by ``K_IS``. ``direct_W`` is the incident and the absorbed
    power of the direct light [W], as the direct sum found them."""
    mode, view, k_is = settings.mode, None, None
    if mode in ("full", "auto"):
        view = model_view_factors(craft, settings)
        k_is = interference(craft, settings)
        if mode == "auto":
            mode = "full" if k_is >= AUTO_THRESHOLD else "none"
    if mode == "none":
        incident, absorbed = direct_W
        power = PowerBalance(incident, absorbed, incident - absorbed)
        return Reflected(mode, np.zeros(3), np.zeros(3), power, None, view, k_is)
    direct = _direct_power(craft, light, flux_W_m2)
    chains = follow_chains(
        craft, light, flux_W_m2, reference_m, settings.cutoff, settings.depth, light.level
    )
    if mode == "specular":
        force = chains.force_N + chains.open_sky_force_N
        torque = chains.torque_Nm + chains.open_sky_torque_Nm
        escaped = direct.passed_W + direct.diffuse_W.sum() + chains.escaped_W + chains.diffuse_source_W.sum()
        absorbed = direct.absorbed_W + chains.absorbed_W
    else:
        exchange = diffuse_exchange(craft, view, settings.cache_dir)
        diffuse = exchange.totals(direct.diffuse_W + chains.diffuse_source_W, reference_m)
        # eq. (4) let the first diffuse reflection leave as from an open plate; take that back
        assumed = exchange.open_sky_totals(direct.diffuse_W, reference_m)
        force = chains.force_N + diffuse.force_N - assumed.force_N
        torque = chains.torque_Nm + diffuse.torque_Nm - assumed.torque_Nm
        escaped = direct.passed_W + chains.escaped_W + diffuse.escaped_W
        absorbed = direct.absorbed_W + chains.absorbed_W + diffuse.absorbed_W
    power = PowerBalance(direct.incident_W, absorbed, float(escaped), chains.truncated_W)
    return Reflected(mode, force, torque, power, chains, view, k_is)
