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

    Build one with :meth:`Epoch.of`; times along an orbit are then elapsed SI seconds from it.

    Attributes
    ----------
    utc : datetime
        The instant, UTC.
    jd_utc, jd_tt : (float, float)
        Two-part Julian date in UTC and in TT (ERFA's ``dtf2d``, ``utctai``, ``taitt``).

    References
    ----------
    IAU SOFA Board, *IAU SOFA Software Collection*, through ERFA and pyerfa (METHOD.md [48]).

    Examples
    --------
    >>> import sunwind as sw
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T03:06:00Z")
    >>> epoch.iso()
    '2024-03-20T03:06:00.000Z'
    >>> epoch.jd_utc
    (2460389.5, 0.12916666666666668)
    >>> round((epoch.jd_tt[1] - epoch.jd_utc[1]) * 86400.0, 3)  # TT - UTC in 2024: 37 leap s + 32.184 s
    69.184
    """

    utc: datetime
    jd_utc: tuple[float, float]
    jd_tt: tuple[float, float]

    @classmethod
    def of(cls, time: str | datetime | np.datetime64) -> Epoch:
        """The epoch of an ISO 8601 UTC string ("2024-03-20T03:06:00Z"), a datetime or datetime64.

        Parameters
        ----------
        time : str, datetime or numpy.datetime64
            The instant. A string is UTC unless it carries an offset; a naive datetime is taken as UTC.

        Returns
        -------
        Epoch
            The instant with its two-part UTC and TT Julian dates.

        Raises
        ------
        InputError
            A string that does not parse, a NaT, or a year outside 1958 to 2100.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> Epoch.of(np.datetime64("2024-01-01T12:00:00")).iso()
        '2024-01-01T12:00:00.000Z'
        """
        when = parse_time(time)
        seconds = when.second + when.microsecond * 1e-6
        utc = erfa.dtf2d("UTC", when.year, when.month, when.day, when.hour, when.minute, seconds)
        tt = erfa.taitt(*erfa.utctai(*utc))
        return cls(when, (float(utc[0]), float(utc[1])), (float(tt[0]), float(tt[1])))

    def tt(self, seconds: NDArray[np.float64] | float) -> tuple[NDArray, NDArray]:
        """Two-part TT Julian dates ``seconds`` [s] after the epoch.

        Parameters
        ----------
        seconds : float or ndarray of float64
            Elapsed SI seconds from the epoch, any shape.

        Returns
        -------
        (ndarray, ndarray)
            The whole-day part (the epoch's, repeated) and the fraction, each in the shape of ``seconds``.

        Examples
        --------
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> day, fraction = Epoch.of("2024-03-20T00:00:00Z").tt([0.0, 43200.0])
        >>> day.tolist(), fraction.round(6).tolist()
        ([2460389.5, 2460389.5], [0.000801, 0.500801])
        """
        return np.full(np.shape(seconds), self.jd_tt[0]), self.jd_tt[1] + np.asarray(seconds) / DAY_S

    def ut1(self, seconds: NDArray[np.float64] | float) -> tuple[NDArray, NDArray]:
        """Two-part UT1 (= UTC) Julian dates ``seconds`` [s] after the epoch.

        Parameters
        ----------
        seconds : float or ndarray of float64
            Elapsed SI seconds from the epoch, any shape.

        Returns
        -------
        (ndarray, ndarray)
            The whole-day part (the epoch's, repeated) and the fraction, each in the shape of ``seconds``.

        Examples
        --------
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> day, fraction = Epoch.of("2024-03-20T00:00:00Z").ut1(21600.0)
        >>> float(day), float(fraction)
        (2460389.5, 0.25)
        """
        return np.full(np.shape(seconds), self.jd_utc[0]), self.jd_utc[1] + np.asarray(seconds) / DAY_S

    def at(self, seconds: float) -> datetime:
        """The UTC instant ``seconds`` [s] after the epoch.

        Parameters
        ----------
        seconds : float
            Elapsed SI seconds from the epoch.

        Returns
        -------
        datetime
            Timezone-aware UTC ``datetime`` (leap seconds are not counted, as in Python's own arithmetic).

        Examples
        --------
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> Epoch.of("2024-03-20T03:06:00Z").at(90.0).isoformat()
        '2024-03-20T03:07:30+00:00'
        """
        return self.utc + timedelta(seconds=float(seconds))

    def iso(self) -> str:
        """The epoch as ISO 8601 UTC text ending in Z.

        Returns
        -------
        str
            ``YYYY-MM-DDThh:mm:ss.sssZ``, to the millisecond.

        Examples
        --------
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> Epoch.of("2024-03-20T03:06:00.25+01:00").iso()
        '2024-03-20T02:06:00.250Z'
        """
        return self.utc.strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z"
