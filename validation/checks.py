"""What one validation check measured, against which limit: the rows ``sunwind validate`` reports.

A :class:`Check` is one case of a family at one condition (a Sun or flow direction, a speed ratio); it
passes when every :class:`Measure` lies at or below its limit. The limits are those the tests assert
(``tests/validation/``); a :class:`Family` yields its checks one by one, in full or, ``quick``, a
subset (or a tracer at fewer particles, the same limits).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass


@dataclass(frozen=True)
class Measure:
    """One measured quantity and its limits: ``low <= value <= limit`` passes (both dimensionless).

    Attributes
    ----------
    name : str
        What was measured, e.g. ``"force error"``.
    value : float
        The measured value [-]; NaN fails.
    limit : float
        Largest value that passes [-].
    low : float
        Smallest value that passes [-]; minus infinity by default.

    Examples
    --------
    >>> error = Measure("force error", 2e-4, 1e-3)
    >>> error.passed, round(error.share, 6)
    (True, 0.2)
    >>> Measure("force error", float("nan"), 1e-3).share
    inf
    """

    name: str
    value: float
    limit: float
    low: float = -float("inf")

    @property
    def passed(self) -> bool:
        """Whether ``low <= value <= limit`` (a NaN value fails)."""
        return self.low <= self.value <= self.limit  # NaN fails

    @property
    def share(self) -> float:
        """``value / limit``: how much of its limit the measure uses (inf when it fails)."""
        if not self.passed:
            return float("inf")
        return self.value / self.limit if self.limit else 0.0


@dataclass(frozen=True)
class Check:
    """One case of a family at one condition, and what was measured there.

    Attributes
    ----------
    family : str
        Name of the :class:`Family`.
    case : str
        The case, e.g. ``"sphere/diffuse"``.
    at : str
        The condition, e.g. ``"alpha 45 deg"``.
    measures : tuple of Measure
        What was measured; the check passes when every one passes.

    Examples
    --------
    >>> measures = (Measure("force", 1e-4, 1e-3), Measure("torque", 5e-4, 1e-3))
    >>> check = Check("SRP", "plate/specular", "alpha 30", measures)
    >>> check.passed, check.worst.name, check.to_json()["passed"]
    (True, 'torque', True)
    """

    family: str
    case: str
    at: str
    measures: tuple[Measure, ...]

    @property
    def passed(self) -> bool:
        """Whether every measure passes."""
        return all(m.passed for m in self.measures)

    @property
    def worst(self) -> Measure:
        """The measure that uses most of its limit."""
        return max(self.measures, key=lambda m: m.share)

    def to_json(self) -> dict:
        """The check as a JSON-ready dict."""
        return {
            "family": self.family,
            "case": self.case,
            "at": self.at,
            "passed": self.passed,
            "measures": [
                {
                    "name": m.name,
                    "value": m.value,
                    "limit": m.limit,
                    **({"low": m.low} if m.low > -1e308 else {}),
                }
                for m in self.measures
            ],
        }


@dataclass(frozen=True)
class Family:
    """A kind of validation: its name, what it checks against, and the checks it yields.

    Attributes
    ----------
    name : str
        Short name, e.g. ``"SRP closed forms"``.
    reference : str
        What the family checks against, in words.
    checks : callable
        ``checks(quick)`` yields each :class:`Check`; ``quick`` asks for the subset.

    Examples
    --------
    >>> family = Family("demo", "one made-up check", lambda quick: iter([Check("demo", "a", "b", ())]))
    >>> [check.case for check in family.checks(True)]
    ['a']
    """

    name: str
    reference: str
    checks: Callable[[bool], Iterator[Check]]
