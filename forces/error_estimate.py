"""The shadow pass's estimated error carried into a result: its force and torque error relative to the
result's loads.

The default shadow pass checks itself (:mod:`sunwind.geometry.rays.certificate`): what its check finds,
times each side's load per unit lit area, is an estimate of the absolute error it leaves in a force and
torque (:class:`~sunwind.geometry.rays.certificate.LoadsError`). A result states it relative to its own
loads as an :class:`ErrorEstimate`; fixed sampling (``samples``) has no check, and no estimate.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.certificate import LoadsError

#: Share of ``|F| L`` (``L`` the model's size) a torque error is measured against where the torque
#: itself is smaller: a torque the force could give.
TORQUE_FLOOR = 0.01
#: What to do about an estimate beyond the tolerance, said with every warning.
ADVICE = "tighten --tolerance (e.g. ten times), or fix the points per side with --samples"


class ShadowErrorWarning(UserWarning):
    """The shadow pass's estimated error exceeds the tolerance the run asked for.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("force error 2.0e-03 above tolerance 1.0e-03", ShadowErrorWarning)
    >>> caught[0].category.__name__
    'ShadowErrorWarning'
    """


@dataclass(frozen=True)
class ErrorEstimate:
    """Estimated error of the shadow pass in a result's force and torque, relative [-].

    Attributes
    ----------
    force : float
        ``|dF| / |F|``: the estimated absolute error of the force (direct law summed over the lit parts
        of the sides) over the result's total force.
    torque : float
        ``|dM| / max(|M|, TORQUE_FLOOR |F| L)``, ``L`` the model's size (the diagonal of its box): against
        the torque itself, or, where that is small, against a torque the force could give.

    Both are 0 when the errors are 0 (a dark model: nothing to get wrong), and infinite when an error
    is not 0 but the load it is measured against is.

    Examples
    --------
    >>> from sunwind.geometry.rays.certificate import LoadsError
    >>> estimate = ErrorEstimate.of(LoadsError(0.25, 0.01), np.array([0.0, 0.0, 2.0]), np.zeros(3), 2.0)
    >>> estimate.force, estimate.torque
    (0.125, 0.25)
    >>> estimate.to_json()
    {'force': 0.125, 'torque': 0.25}
    """

    force: float
    torque: float

    @classmethod
    def of(
        cls,
        error: LoadsError,
        force_N: NDArray[np.float64],
        torque_Nm: NDArray[np.float64],
        diagonal_m: float,
    ) -> ErrorEstimate:
        """The relative estimate of the absolute ``error`` [N, N m] of a result whose total force and
        torque are ``force_N`` and ``torque_Nm`` (3,), on a model whose box has the diagonal
        ``diagonal_m`` [m] (:attr:`~sunwind.geometry.spacecraft.Spacecraft.diagonal_m`)."""
        force = float(np.linalg.norm(force_N))
        torque = max(float(np.linalg.norm(torque_Nm)), TORQUE_FLOOR * force * diagonal_m)
        return cls(_ratio(error.force_N, force), _ratio(error.torque_Nm, torque))

    @property
    def worst(self) -> float:
        """The larger of :attr:`force` and :attr:`torque`."""
        return max(self.force, self.torque)

    def to_json(self) -> dict:
        """``{"force": ..., "torque": ...}``."""
        return {"force": self.force, "torque": self.torque}

    def __str__(self) -> str:
        return f"force {self.force:.1e}, torque {self.torque:.1e} (relative, estimated)"


def _ratio(error: float, scale: float) -> float:
    if error == 0.0:
        return 0.0
    return error / scale if scale > 0.0 else math.inf


def summed(errors: Iterable[LoadsError | None]) -> LoadsError | None:
    """Add the errors of several loads (a bound: they may partly cancel).

    Parameters
    ----------
    errors : iterable of LoadsError or None
        Absolute force [N] and torque [N m] errors of the loads; None for a load without an estimate.

    Returns
    -------
    LoadsError or None
        Their sum; None when any is None, ``LoadsError(0, 0)`` when there are none.

    Examples
    --------
    >>> summed([LoadsError(1.0, 2.0), LoadsError(0.5, 0.25)])
    LoadsError(force_N=1.5, torque_Nm=2.25)
    >>> summed([LoadsError(1.0, 2.0), None]) is None
    True
    """
    force = torque = 0.0
    for error in errors:
        if error is None:
            return None
        force += error.force_N
        torque += error.torque_Nm
    return LoadsError(force, torque)


def scaled(error: LoadsError | None, factor: float) -> LoadsError | None:
    """Scale ``error`` to a load ``factor`` times as large (None stays None).

    Parameters
    ----------
    error : LoadsError or None
        Absolute force [N] and torque [N m] errors of a load, or None for no estimate.
    factor : float
        Factor of the load, >= 0.

    Returns
    -------
    LoadsError or None
        ``factor`` times both errors; None when ``error`` is None.

    Examples
    --------
    >>> scaled(LoadsError(1.0, 2.0), 0.5)
    LoadsError(force_N=0.5, torque_Nm=1.0)
    """
    return None if error is None else LoadsError(factor * error.force_N, factor * error.torque_Nm)
