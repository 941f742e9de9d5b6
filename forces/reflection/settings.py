"""How inter-reflection is computed: the mode, where beam chains end, how view factors are sampled.

Modes: ``none`` is the direct law, every reflected and transmitted photon leaving to infinity;
``specular`` follows mirror and transmitted beams from surface to surface and lets diffuse light leave
as from an open plate; ``full`` also solves the diffuse balance with the view factors; ``auto`` is
``full`` when ``K_IS >= 0.1`` (eq. 8), else ``none`` (METHOD.md "Inter-reflection").
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from sunwind.geometry.errors import InputError
from sunwind.geometry.views.view_factors import check_rays_per_side

#: Modes of :attr:`ReflectionSettings.mode`.
MODES = ("none", "specular", "full", "auto")
#: ``K_IS`` from which ``auto`` includes inter-reflection, eq. (8).
AUTO_THRESHOLD = 0.1
#: Default end of a chain: a beam below this share of the power its chain started with.
DEFAULT_CUTOFF = 1e-6
#: Default end of a chain: this many surfaces met beyond the side that sent it.
DEFAULT_DEPTH = 32


@dataclass(frozen=True)
class ReflectionSettings:
    """How inter-reflection is computed.

    Attributes
    ----------
    mode : str
        One of :data:`MODES`.
    cutoff : float
        A beam is dropped below this share of the power its chain started with, in [0, 1).
    depth : int
        A chain is dropped after meeting this many surfaces beyond the side that sent it, >= 1.
    rays_per_side : int or None
        Hemisphere rays per side for the view factors, 1 to
        :data:`~sunwind.geometry.views.view_factors.MAX_RAYS_PER_SIDE`; None for the default rule.
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
            raise InputError(
                f"reflections {self.mode!r} is not a mode",
                hint=f"use one of {', '.join(MODES)}",
                parameters=("reflections",),
            )
        if not 0 <= self.cutoff < 1:
            raise InputError(
                f"cutoff {self.cutoff} is not in [0, 1)",
                hint=f"default {DEFAULT_CUTOFF:g}",
                parameters=("cutoff",),
            )
        if self.depth < 1:
            raise InputError(
                f"depth {self.depth} must be at least 1",
                hint=f"default {DEFAULT_DEPTH}",
                parameters=("depth",),
            )
        if self.rays_per_side is not None:
            check_rays_per_side(self.rays_per_side)

    @property
    def view_key(self) -> tuple:
        """What the view factors depend on besides the model: their sampling, and the disk cache
        they are read from or written to."""
        return (self.rays_per_side, str(self.cache_dir))

    @classmethod
    def of(cls, reflections: str | ReflectionSettings) -> ReflectionSettings:
        """``reflections`` itself, or the settings of that mode with the defaults."""
        return reflections if isinstance(reflections, ReflectionSettings) else cls(reflections)
