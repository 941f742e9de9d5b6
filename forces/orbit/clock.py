"""Time along an orbit: a UTC start (the epoch) and elapsed SI seconds, as the two-part Julian dates
ERFA takes (TT for the Sun and the celestial-to-terrestrial rotation, UTC for the atmosphere).

Elapsed time is counted in SI seconds from the epoch: TT advances with it exactly, UTC too except across
a leap second (one second off after it, far below any step). UT1 is taken as UTC (|UT1 - UTC| < 0.9 s:
at most 66 microradians of Earth rotation, 0.4 km on the ground), which only places the atmosphere.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timedelta

import erfa
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.msis import parse_time

#: Seconds per day.
DAY_S = 86400.0


@dataclass(frozen=True)
class Epoch:
    """A UTC instant (timezone-aware ``datetime``) and its Julian dates.

    Attributes
    ----------
    utc : datetime
        The instant, UTC.
    jd_utc, jd_tt : (float, float)
        Two-part Julian date in UTC and in TT (ERFA's ``dtf2d``, ``utctai``, ``taitt``).
    """

    utc: datetime
    jd_utc: tuple[float, float]
    jd_tt: tuple[float, float]

    @classmethod
    def of(cls, time: str | datetime | np.datetime64) -> Epoch:
        """The epoch of an ISO 8601 UTC string ("2024-03-20T03:06:00Z"), a datetime or datetime64."""
        when = parse_time(time)
        seconds = when.second + when.microsecond * 1e-6
        utc = erfa.dtf2d("UTC", when.year, when.month, when.day, when.hour, when.minute, seconds)
        tt = erfa.taitt(*erfa.utctai(*utc))
        return cls(when, (float(utc[0]), float(utc[1])), (float(tt[0]), float(tt[1])))

    def tt(self, seconds: NDArray[np.float64] | float) -> tuple[NDArray, NDArray]:
        """Two-part TT Julian dates ``seconds`` [s] after the epoch."""
        return np.full(np.shape(seconds), self.jd_tt[0]), self.jd_tt[1] + np.asarray(seconds) / DAY_S

    def ut1(self, seconds: NDArray[np.float64] | float) -> tuple[NDArray, NDArray]:
        """Two-part UT1 (= UTC) Julian dates ``seconds`` [s] after the epoch."""
        return np.full(np.shape(seconds), self.jd_utc[0]), self.jd_utc[1] + np.asarray(seconds) / DAY_S

    def at(self, seconds: float) -> datetime:
        """The UTC instant ``seconds`` [s] after the epoch."""
        return self.utc + timedelta(seconds=float(seconds))

    def iso(self) -> str:
        """The epoch as ISO 8601 UTC text ending in Z."""
        return self.utc.strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"
