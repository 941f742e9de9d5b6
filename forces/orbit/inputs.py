"""What each orbit step is given: a record of column arrays, one row per step, cut into chunks by the
sweep engine as a sweep's directions are (:mod:`sunwind.forces.tables.engine`).

:func:`~sunwind.forces.orbit.flight.fly` fills it from the trajectory, the attitude, the ephemeris and
the eclipse; :class:`~sunwind.forces.orbit.steps.OrbitLoads` reads it, step by step. Everything is in the
body frame but ``body_to_eci``, and nothing in it has to be looked up again at a step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.orbit.clock import Epoch
from sunwind.geometry.errors import InputError


@dataclass(frozen=True, eq=False)
class StepInputs:
    """The inputs of ``n`` orbit steps, column by column (rows in time order).

    Attributes
    ----------
    epoch : Epoch
        The instant ``time_s`` counts from (the same for every step and every chunk).
    time_s : ndarray, shape (n,)
        Seconds after the epoch.
    body_to_eci : ndarray, shape (n, 3, 3)
        Body-to-GCRF rotation.
    sun_body : ndarray, shape (n, 3)
        Unit vector from the spacecraft to the Sun.
    sunlight_W_m2 : ndarray, shape (n,)
        Solar flux at the spacecraft's distance from the Sun, the disc whole [W/m^2].
    solar_fraction : ndarray, shape (n,)
        Share of the solar disc in view (the eclipse), 0 to 1.
    flux_W_m2 : ndarray, shape (n,)
        Solar flux at the spacecraft, ``sunlight_W_m2 * solar_fraction`` [W/m^2].
    velocity_body_m_s : ndarray, shape (n, 3)
        ``v_rel``: the velocity relative to the air turning with the Earth [m/s].
    nadir_body : ndarray, shape (n, 3)
        Unit vector to the Earth's centre.
    pole_body : ndarray, shape (n, 3)
        The GCRF z axis (the Earth's pole).
    height_km : ndarray, shape (n,)
        Height above the Earth's sphere [km] (the Earth's radiation).
    altitude_km, latitude_deg, longitude_deg : ndarray, shape (n,)
        Geodetic place above the WGS 84 ellipsoid (the atmosphere); NaN in a run without drag.

    Examples
    --------
    >>> import numpy as np
    >>> steps = StepInputs.at_rest(Epoch.of("2024-03-20T00:00:00Z"), np.arange(5) * 60.0)
    >>> len(steps), len(steps[1:3]), steps[1:3].time_s
    (5, 2, array([ 60., 120.]))
    >>> StepInputs.concatenate([steps[:2], steps[2:]]).time_s.tolist() == steps.time_s.tolist()
    True
    """

    epoch: Epoch
    time_s: NDArray[np.float64]
    body_to_eci: NDArray[np.float64]
    sun_body: NDArray[np.float64]
    sunlight_W_m2: NDArray[np.float64]
    solar_fraction: NDArray[np.float64]
    flux_W_m2: NDArray[np.float64]
    velocity_body_m_s: NDArray[np.float64]
    nadir_body: NDArray[np.float64]
    pole_body: NDArray[np.float64]
    height_km: NDArray[np.float64]
    altitude_km: NDArray[np.float64]
    latitude_deg: NDArray[np.float64]
    longitude_deg: NDArray[np.float64]

    def __post_init__(self) -> None:
        n = len(self.time_s)
        for name in self.columns():
            value = np.asarray(getattr(self, name), dtype=np.float64)
            if len(value) != n:
                raise InputError(
                    f"step input {name} has {len(value)} rows, time_s {n}", parameters=("steps",)
                )
            object.__setattr__(self, name, value)

    @classmethod
    def columns(cls) -> tuple[str, ...]:
        """The names of the column arrays, in order (all but :attr:`epoch`).

        Returns
        -------
        tuple of str
        """
        return tuple(f.name for f in fields(cls) if f.name != "epoch")

    @classmethod
    def at_rest(cls, epoch: Epoch, time_s: NDArray[np.float64]) -> StepInputs:
        """Steps at ``time_s`` with the body frame on GCRF, the Sun whole along +x at 1361 W/m^2, no
        flow and the Earth 500 km below along -z: a placeholder of the right shape (tests, examples).

        Parameters
        ----------
        epoch : Epoch
            The instant the times count from.
        time_s : array_like, shape (n,)
            Seconds after the epoch.

        Returns
        -------
        StepInputs
        """
        time_s = np.asarray(time_s, dtype=np.float64)
        n = len(time_s)
        flux, none = np.full(n, 1361.0), np.full(n, np.nan)
        body_to_eci, sun = np.tile(np.eye(3), (n, 1, 1)), np.tile([1.0, 0.0, 0.0], (n, 1))
        nadir, pole = np.tile([0.0, 0.0, -1.0], (n, 1)), np.tile([0.0, 0.0, 1.0], (n, 1))
        still, height = np.zeros((n, 3)), np.full(n, 500.0)
        return cls(
            epoch,
            time_s,
            body_to_eci,
            sun,
            flux,
            np.ones(n),
            flux.copy(),
            still,
            nadir,
            pole,
            height,
            none,
            none.copy(),
            none.copy(),
        )

    def __len__(self) -> int:
        return len(self.time_s)

    def __getitem__(self, index: slice) -> StepInputs:
        """The steps of ``index`` (a slice: a chunk), the epoch kept.

        Raises
        ------
        TypeError
            ``index`` is not a slice.
        """
        if not isinstance(index, slice):
            raise TypeError(f"StepInputs are cut by a slice (a chunk), not {type(index).__name__}")
        return StepInputs(self.epoch, **{name: getattr(self, name)[index] for name in self.columns()})

    @classmethod
    def concatenate(cls, parts: Sequence[StepInputs]) -> StepInputs:
        """The steps of ``parts`` one after the other (chunks put back together).

        Parameters
        ----------
        parts : sequence of StepInputs
            At least one, all of one epoch.

        Returns
        -------
        StepInputs

        Raises
        ------
        InputError
            No parts, or parts of different epochs.
        """
        if not parts or any(part.epoch != parts[0].epoch for part in parts):
            raise InputError("step inputs are put together from one or more of one epoch")
        joined = {name: np.concatenate([getattr(part, name) for part in parts]) for name in cls.columns()}
        return cls(parts[0].epoch, **joined)
