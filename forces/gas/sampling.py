"""How the open-sky integral and the molecular chains are sampled (METHOD.md "The open-sky integral",
"Molecular chains"): the settings of :func:`sunwind.forces.drag.drag` beyond the shadow pass."""

from __future__ import annotations

from dataclasses import dataclass

from sunwind.geometry.errors import InputError

#: Most rays per side of a model's sky, and most core rays or chain molecules per attitude.
MAX_SKY_RAYS, MAX_PER_ATTITUDE = 65_536, 2**26


@dataclass(frozen=True)
class GasSampling:
    """Sampling of a drag attitude's incident stream and chains.

    Attributes
    ----------
    sky_rays : int or None
        Cosine-weighted rays per side with which each side's open sky is sampled once per model
        (:mod:`sunwind.geometry.views.sky`); None: by model size (36 to 4096).
    core_rays : int
        Most rays per attitude sampling the core cone about the flow beside the exact shadow pass
        (:mod:`sunwind.forces.gas.visible`); a side that can be shadowed casts at least three.
    chain_molecules : int
        First molecules per attitude drawn for the chains of unaccommodated molecules
        (:mod:`sunwind.forces.gas.chains`); each sending side draws at least one.

    Raises
    ------
    InputError
        A count that is not a whole number in range (1 to :data:`MAX_SKY_RAYS` sky rays, 1 to
        :data:`MAX_PER_ATTITUDE` core rays or chain molecules).

    Examples
    --------
    >>> GasSampling(sky_rays=16)
    GasSampling(sky_rays=16, core_rays=262144, chain_molecules=131072)
    >>> GasSampling(core_rays=0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: core_rays 0 must be a whole number from 1 to 67108864
    """

    sky_rays: int | None = None
    core_rays: int = 2**18
    chain_molecules: int = 2**17

    def __post_init__(self) -> None:
        for name, value, high in (
            ("sky_rays", self.sky_rays, MAX_SKY_RAYS),
            ("core_rays", self.core_rays, MAX_PER_ATTITUDE),
            ("chain_molecules", self.chain_molecules, MAX_PER_ATTITUDE),
        ):
            if value is None and name == "sky_rays":
                continue
            if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= high:
                raise InputError(
                    f"{name} {value!r} must be a whole number from 1 to {high}", parameters=(name,)
                )

    @classmethod
    def of(cls, sampling: GasSampling | None) -> GasSampling:
        """``sampling`` itself, or the defaults for None.

        Parameters
        ----------
        sampling : GasSampling or None

        Returns
        -------
        GasSampling

        Raises
        ------
        InputError
            ``sampling`` is neither.

        Examples
        --------
        >>> GasSampling.of(None) == GasSampling()
        True
        """
        if sampling is None:
            return cls()
        if not isinstance(sampling, GasSampling):
            raise InputError("gas_sampling must be a GasSampling", parameters=("gas_sampling",))
        return sampling
