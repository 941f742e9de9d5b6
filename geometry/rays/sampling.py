"""How the shadow pass samples each side: one setting, taken by every force that casts shadow rays
(METHOD.md "Shadowing and sampling")."""

from __future__ import annotations

from dataclasses import dataclass

from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE, check_sampling


@dataclass(frozen=True)
class ShadowSampling:
    """How the shadow pass finds the lit share of each side, checked when made.

    The pass is :meth:`~sunwind.geometry.rays.shadows.SideSampler.illuminate`.

    Parameters
    ----------
    samples : int, optional
        Fixed shadow-ray points per side, rounded up to a square (``level**2`` points, one in each of
        the side's congruent sub-triangles). Default None: the default pass, one ray per side and the
        shadow edges located and cut along the outline (:mod:`sunwind.geometry.rays.shadow_edges`).
    tolerance : float
        The default pass's tolerance: the share of a refined side's area its lit part is found to, in
        [1e-6, 1). The default pass checks itself, and a result's ``error_estimate`` is the error it
        estimates it left; unused with ``samples``.

    Raises
    ------
    InputError
        ``samples`` is not a whole number >= 1, or ``tolerance`` is outside [1e-6, 1).

    Examples
    --------
    >>> ShadowSampling()
    ShadowSampling(samples=None, tolerance=0.001)
    >>> ShadowSampling(samples=16).estimates
    False
    >>> ShadowSampling(tolerance=2.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: tolerance 2.0 must lie in [1e-06, 1); default 1e-3
    """

    samples: int | None = None
    tolerance: float = DEFAULT_TOLERANCE

    def __post_init__(self) -> None:
        check_sampling(self.samples, self.tolerance)

    @property
    def estimates(self) -> bool:
        """Whether the default pass runs (no fixed ``samples``), which estimates the error it leaves."""
        return self.samples is None

    @classmethod
    def of(cls, sampling: ShadowSampling | None) -> ShadowSampling:
        """``sampling`` itself, or the default sampling for None.

        Raises
        ------
        InputError
            ``sampling`` is neither None nor a :class:`ShadowSampling`.

        Examples
        --------
        >>> ShadowSampling.of(None) == ShadowSampling()
        True
        """
        if sampling is None:
            return cls()
        if not isinstance(sampling, ShadowSampling):
            raise InputError(
                f"sampling {sampling!r} is not a ShadowSampling",
                hint="e.g. sampling=ShadowSampling(samples=16) or ShadowSampling(tolerance=1e-4)",
                parameters=("sampling",),
            )
        return sampling
