"""Results of several attitudes: one result per attitude, every numeric field stacked by name
(``batch.force_N`` is (n, 3), ``batch.rays`` (n,))."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.results import AttitudeResult, DragResult, SrpResult

R = TypeVar("R", bound=AttitudeResult)


@dataclass(frozen=True, eq=False)
class ResultBatch(Generic[R]):
    """Results of several attitudes, in the order asked; a numeric field of every result stacked is
    the same name on the batch: ``batch.force_N`` is (n, 3), ``batch.rays`` (n,)."""

    results: tuple[R, ...]

    def __len__(self) -> int:
        return len(self.results)

    def __getitem__(self, index: int) -> R:
        return self.results[index]

    def __iter__(self) -> Iterator[R]:
        return iter(self.results)

    def stacked(self, name: str) -> NDArray:
        """Field ``name`` of every result, stacked: (n,) for numbers, (n, 3) for vectors."""
        return np.array([np.asarray(getattr(result, name)) for result in self.results])

    @property
    def direction(self) -> NDArray[np.float64]:
        return self.stacked("direction").reshape(-1, 3)

    @property
    def azel_deg(self) -> NDArray[np.float64]:
        """Azimuth and elevation of every attitude's direction [deg], (n, 2)."""
        return self.stacked("azel_deg").reshape(-1, 2)

    @property
    def force_N(self) -> NDArray[np.float64]:
        return self.stacked("force_N").reshape(-1, 3)

    @property
    def torque_Nm(self) -> NDArray[np.float64]:
        return self.stacked("torque_Nm").reshape(-1, 3)

    @property
    def direct_force_N(self) -> NDArray[np.float64]:
        return self.stacked("direct_force_N").reshape(-1, 3)

    @property
    def direct_torque_Nm(self) -> NDArray[np.float64]:
        return self.stacked("direct_torque_Nm").reshape(-1, 3)

    @property
    def reflected_force_N(self) -> NDArray[np.float64]:
        return self.stacked("reflected_force_N").reshape(-1, 3)

    @property
    def reflected_torque_Nm(self) -> NDArray[np.float64]:
        return self.stacked("reflected_torque_Nm").reshape(-1, 3)

    @property
    def lit_area_m2(self) -> NDArray[np.float64]:
        return self.stacked("lit_area_m2")

    @property
    def projected_area_m2(self) -> NDArray[np.float64]:
        return self.stacked("projected_area_m2")

    @property
    def rays(self) -> NDArray[np.int64]:
        return self.stacked("rays")

    def to_json(self) -> list[dict]:
        """One JSON summary per attitude."""
        return [result.to_json() for result in self.results]


class SrpBatch(ResultBatch[SrpResult]):
    """:class:`SrpResult` of several Sun directions."""

    @property
    def sun_vector(self) -> NDArray[np.float64]:
        return self.direction


class DragBatch(ResultBatch[DragResult]):
    """:class:`DragResult` of several flow velocities."""

    @property
    def velocity_m_s(self) -> NDArray[np.float64]:
        return self.stacked("velocity_m_s").reshape(-1, 3)

    @property
    def force_coefficients(self) -> NDArray[np.float64]:
        return self.stacked("force_coefficients").reshape(-1, 3)

    @property
    def moment_coefficients(self) -> NDArray[np.float64]:
        return self.stacked("moment_coefficients").reshape(-1, 3)
