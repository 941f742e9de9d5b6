"""How inter-reflection is computed: the mode, where beam chains end, how view factors are sampled.

One set of modes serves light (:func:`~sunwind.forces.srp.srp`, the planet's albedo and infrared) and
molecules (:func:`~sunwind.forces.drag.drag`), each read in its own terms (:data:`MODES`, METHOD.md
"Inter-reflection", "Molecular chains"):

``none``
    The surface law on every side with shadowing; every reflected photon and re-emitted molecule
    leaves to infinity.
``specular``
    Light: mirror and transmitted beams followed from surface to surface; diffusely reflected light
    leaves as from an open plate. Molecules: the unaccommodated ones (mirrored, CLL's lobe) followed
    from surface to surface; diffusely re-emitted ones leave as from an open plate (no exchange).
``full``
    ``specular`` and the diffuse balance with the view factors: diffusely reflected light, or diffusely
    re-emitted molecules, exchanged between the sides.
``auto``
    ``full`` when the interference criterion ``K_IS`` >= :data:`AUTO_THRESHOLD` (eq. 8; for molecules
    with ``rho = 1``), else ``none`` (:func:`resolved_mode`).
``plates``
    Every side alone, as the flat-plate (N-plate) models of GMAT and Orekit: no shadowing and no
    inter-reflection; every side facing the Sun wholly lit, every side in the whole free stream (or
    seeing the whole planet); no ray is cast.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from sunwind.geometry.errors import InputError
from sunwind.geometry.views.view_factors import check_rays_per_side

#: Modes of :attr:`ReflectionSettings.mode`, the same for light and molecules (module docstring).
MODES = ("none", "specular", "full", "auto", "plates")
#: The modes that use the view factors (``auto`` for ``K_IS``).
VIEW_MODES = ("full", "auto")
#: ``K_IS`` from which ``auto`` includes inter-reflection, eq. (8).
AUTO_THRESHOLD = 0.1
#: Default end of a chain: a beam below this share of the power its chain started with.
DEFAULT_CUTOFF = 1e-6
#: Default end of a chain: this many surfaces met beyond the side that sent it.
DEFAULT_DEPTH = 32


@dataclass(frozen=True)
class ReflectionSettings:
    """How inter-reflection is computed, for light and for molecules alike.

    Parameters
    ----------
    mode : str
        One of :data:`MODES`: ``none``, ``specular``, ``full``, ``auto`` or ``plates`` (the module
        docstring says what each means for light and for molecules).
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

    Raises
    ------
    InputError
        A mode not in :data:`MODES`, a cutoff outside [0, 1), a depth below 1, or a ray count refused.

    Examples
    --------
    >>> ReflectionSettings("full", depth=8).uses_view_factors
    True
    >>> ReflectionSettings("mirror")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: reflections 'mirror' is not a mode; use one of none, specular, ...
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

    @property
    def uses_view_factors(self) -> bool:
        """Whether the mode needs the view factors: ``full``, and ``auto`` for ``K_IS``."""
        return self.mode in VIEW_MODES

    @classmethod
    def of(cls, reflections: str | ReflectionSettings) -> ReflectionSettings:
        """``reflections`` itself, or the settings of that mode (one of :data:`MODES`) with the defaults.

        Raises
        ------
        InputError
            ``reflections`` is neither settings nor one of :data:`MODES`.

        Examples
        --------
        >>> ReflectionSettings.of("plates").mode
        'plates'
        """
        if isinstance(reflections, ReflectionSettings):
            return reflections
        if not isinstance(reflections, str):
            raise InputError(
                f"reflections {reflections!r} is not a mode",
                hint=f"use one of {', '.join(MODES)}, or ReflectionSettings",
                parameters=("reflections",),
            )
        return cls(reflections)


def resolved_mode(mode: str, k_is: float | None) -> str:
    """The mode applied: ``auto`` resolved by the interference criterion ``k_is``, any other as it is.

    ``auto`` becomes ``full`` when ``k_is >= AUTO_THRESHOLD`` (eq. 8), else ``none``.

    Parameters
    ----------
    mode : str
        One of :data:`MODES`.
    k_is : float or None
        ``K_IS`` of the model (eq. 7; for molecules with ``rho = 1``); needed with ``auto`` only.

    Returns
    -------
    str
        ``none``, ``specular``, ``full`` or ``plates``.

    Examples
    --------
    >>> resolved_mode("auto", 0.25), resolved_mode("auto", 0.0), resolved_mode("specular", None)
    ('full', 'none', 'specular')
    """
    if mode != "auto":
        return mode
    if k_is is None:
        raise ValueError("auto needs K_IS to resolve")
    return "full" if k_is >= AUTO_THRESHOLD else "none"
