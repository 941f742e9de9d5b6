"""The free-stream gas for free-molecular forces: its species, their masses, and an :class:`Atmosphere`
of number densities and temperature, from NRLMSIS (:mod:`.msis`) or given explicitly (METHOD.md
"Atmosphere").

Notes
-----
Species and their masses. The gas-surface models sum over O, N2, O2, He, H, N, Ar and anomalous O.
Molecular masses are built from the IUPAC/CIAAW 2021 standard atomic weights (conventional values for
the elements whose standard weight is an interval: H 1.008, N 14.007, O 15.999, Ar 39.95; He
4.002602) times the atomic mass constant (CODATA 2018). Anomalous oxygen ("O*": hot O and O+ that
NRLMSIS lumps together for drag) has the mass of O. The density is always ``sum n_k m_k`` with these
masses, so that the force summed over species and the dynamic pressure ``rho V^2 / 2`` used for
coefficients agree (:mod:`.msis` says how that differs from NRLMSIS's own total).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from sunwind.geometry.errors import InputError

#: Boltzmann constant [J/K] (exact, SI 2019).
BOLTZMANN = 1.380649e-23
#: Atomic mass constant [kg] (CODATA 2018).
ATOMIC_MASS = 1.66053906660e-27
#: Standard atomic weights used here (IUPAC/CIAAW 2021; conventional values where the standard weight is
#: an interval) [g/mol, i.e. in units of the atomic mass constant].
ATOMIC_WEIGHT = MappingProxyType({"H": 1.008, "He": 4.002602, "N": 14.007, "O": 15.999, "Ar": 39.95})

#: Species known to sunwind: canonical name -> molecular mass [kg], in the order reports list them.
SPECIES_MASS_KG = MappingProxyType(
    {
        "O": ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
        "N2": 2 * ATOMIC_WEIGHT["N"] * ATOMIC_MASS,
        "O2": 2 * ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
        "He": ATOMIC_WEIGHT["He"] * ATOMIC_MASS,
        "H": ATOMIC_WEIGHT["H"] * ATOMIC_MASS,
        "N": ATOMIC_WEIGHT["N"] * ATOMIC_MASS,
        "Ar": ATOMIC_WEIGHT["Ar"] * ATOMIC_MASS,
        "O*": ATOMIC_WEIGHT["O"] * ATOMIC_MASS,
    }
)

#: Names a user may type for a species (compared without regard to case) -> canonical name.
_ALIASES = {name.lower(): name for name in SPECIES_MASS_KG} | {
    alias: "O*"
    for alias in (
        "anomalous_o",
        "anomalous-o",
        "anomalous o",
        "anomalouso",
        "anomalous_oxygen",
        "ao",
        "o_anom",
    )
}

#: Effective collision diameter of air [m] for the hard-sphere mean free path (U.S. Standard Atmosphere 1976).
COLLISION_DIAMETER = 3.65e-10


#: Range of free-stream temperatures [K] taken as a neutral gas: from 1 K (colder than the cosmic
#: background) to 1e5 K (beyond it the gas is a plasma; the thermosphere's is 200-2500 K).
TEMPERATURE_RANGE_K = (1.0, 1e5)


class AtmosphereWarning(UserWarning):
    """The atmosphere asked for is usable but outside where its model or free-molecular flow is sound.

    Examples
    --------
    >>> issubclass(AtmosphereWarning, UserWarning)
    True
    """


def species_name(name: str) -> str:
    """The canonical name of a species as a user may type it ("o2", "he", "anomalous_O", "O*").

    Parameters
    ----------
    name : str
        The name, in any case.

    Returns
    -------
    str
        A key of ``SPECIES_MASS_KG``.

    Raises
    ------
    InputError
        A name that is not one of the known species; the message lists them.

    Examples
    --------
    >>> species_name("o2"), species_name("anomalous_O")
    ('O2', 'O*')
    """
    canonical = _ALIASES.get(str(name).strip().lower())
    if canonical is None:
        raise InputError(
            f"unknown species '{name}'",
            hint=f"known species are {', '.join(SPECIES_MASS_KG)} (O* is anomalous oxygen)",
        )
    return canonical


@dataclass(frozen=True)
class Atmosphere:
    """The free-stream gas: number density of each species and the kinetic temperature.

    Parameters
    ----------
    number_density_m3 : dict[str, float]
        Number density [m^-3] of each species present (only ``n > 0``), keyed by canonical name
        (``SPECIES_MASS_KG``), in table order.
    temperature_K : float
        Free-stream kinetic temperature [K], within :data:`TEMPERATURE_RANGE_K`.
    source : str
        Where the values came from, one line, e.g. ``"NRLMSIS 2.1 (pymsis 0.13.0): 400 km, ..."`` or
        ``"user: density ..., temperature ..., composition ..."``.
    altitude_km : float, optional
        Altitude [km] the atmosphere is for, when known.
    inputs : dict[str, float | str]
        The other inputs, kept for reports (latitude, longitude, time, solar and geomagnetic indices).
    model_density_kg_m3 : float, optional
        The source model's own total mass density [kg/m^3] (NRLMSIS's, computed with its own masses).

    Raises
    ------
    InputError
        An unknown or repeated species, a density that is not finite and positive, no species at all,
        or a temperature out of range.

    Examples
    --------
    >>> air = Atmosphere({"o": 2e13, "N2": 1e13}, 1000.0, "example")
    >>> list(air.number_density_m3), f"{air.density_kg_m3:.4e}"
    (['O', 'N2'], '9.9652e-13')
    """

    number_density_m3: dict[str, float]
    temperature_K: float
    source: str
    altitude_km: float | None = None
    inputs: dict[str, float | str] = field(default_factory=dict)
    model_density_kg_m3: float | None = None

    def __post_init__(self) -> None:
        densities: dict[str, float] = {}
        for name, n in self.number_density_m3.items():
            key = species_name(name)
            if key in densities:
                raise InputError(f"species {key} is given twice")
            n = float(n)
            if not math.isfinite(n) or n <= 0:
                raise InputError(f"number density of {key} is {n} m^-3, not a finite positive number")
            densities[key] = n
        if not densities:
            raise InputError("the atmosphere has no species with a positive number density")
        temperature = checked_temperature(self.temperature_K)
        ordered = {k: densities[k] for k in SPECIES_MASS_KG if k in densities}
        object.__setattr__(self, "number_density_m3", ordered)
        object.__setattr__(self, "temperature_K", temperature)
        object.__setattr__(self, "inputs", dict(self.inputs))

    __hash__ = None  # it holds dicts: equal atmospheres compare equal but are not hashable

    @property
    def mass_kg(self) -> dict[str, float]:
        """Molecular mass [kg] of each species present."""
        return {k: SPECIES_MASS_KG[k] for k in self.number_density_m3}

    @property
    def total_number_density_m3(self) -> float:
        """Number density of all species together [m^-3]."""
        return math.fsum(self.number_density_m3.values())

    @property
    def density_kg_m3(self) -> float:
        """Mass density ``rho = sum n_k m_k`` [kg/m^3]."""
        return math.fsum(n * SPECIES_MASS_KG[k] for k, n in self.number_density_m3.items())

    @property
    def mole_fractions(self) -> dict[str, float]:
        """Number (mole) fraction ``n_k / sum n`` of each species; they sum to 1."""
        total = self.total_number_density_m3
        return {k: n / total for k, n in self.number_density_m3.items()}

    @property
    def mean_mass_kg(self) -> float:
        """Mean molecular mass ``rho / sum n`` [kg]."""
        return self.density_kg_m3 / self.total_number_density_m3

    @property
    def mean_free_path_m(self) -> float:
        """Hard-sphere mean free path ``1 / (sqrt(2) pi d^2 n)`` [m], air diameter ``d`` of USSA 1976.

        A rough guide to the Knudsen number ``Kn = lambda / L`` of a body of size ``L``: free-molecular
        flow needs ``Kn`` of about 10 or more.
        """
        return 1.0 / (math.sqrt(2.0) * math.pi * COLLISION_DIAMETER**2 * self.total_number_density_m3)

    def speed_ratio(self, speed_m_s: float) -> dict[str, float]:
        """Molecular speed ratio ``S_k = V / sqrt(2 k T / m_k)`` of each species.

        Parameters
        ----------
        speed_m_s : float
            Speed ``V = |v_rel|`` of the spacecraft relative to the atmosphere [m/s].

        Returns
        -------
        dict[str, float]
            Dimensionless speed ratio per species present.

        Examples
        --------
        >>> air = Atmosphere({"O": 1e14}, 1000.0, "example")
        >>> round(air.speed_ratio(7500.0)["O"], 3)
        7.357
        """
        speed = finite_number(speed_m_s, "speed", "m/s", minimum=0.0)
        return {
            k: speed / math.sqrt(2.0 * BOLTZMANN * self.temperature_K / m) for k, m in self.mass_kg.items()
        }

    def mean_speed_ratio(self, speed_m_s: float) -> float:
        """Speed ratio of the mixture ``V / sqrt(2 k T / m_mean)`` with :attr:`mean_mass_kg`.

        Parameters
        ----------
        speed_m_s : float
            Speed ``V`` [m/s], >= 0.

        Returns
        -------
        float
            The speed ratio [-].
        """
        speed = finite_number(speed_m_s, "speed", "m/s", minimum=0.0)
        return speed / math.sqrt(2.0 * BOLTZMANN * self.temperature_K / self.mean_mass_kg)

    @classmethod
    def from_json(cls, document: dict) -> Atmosphere:
        """The atmosphere :meth:`to_json` describes (numbers round-trip exactly through JSON).

        Parameters
        ----------
        document : dict
            What :meth:`to_json` gave.

        Returns
        -------
        Atmosphere
            The same atmosphere.

        Examples
        --------
        >>> air = Atmosphere({"O": 1e14}, 1000.0, "example")
        >>> Atmosphere.from_json(air.to_json()).number_density_m3 == air.number_density_m3
        True
        """
        return cls(
            document["number_density_m3"],
            document["temperature_K"],
            document["source"],
            document.get("altitude_km"),
            document.get("inputs", {}),
            document.get("model_density_kg_m3"),
        )

    def to_json(self) -> dict:
        """A JSON-ready description: density [kg/m^3], temperature [K], per-species number density [m^-3].

        Returns
        -------
        dict
            Keys carry their units; optional fields only where set.
        """
        out: dict = {
            "source": self.source,
            "density_kg_m3": self.density_kg_m3,
            "temperature_K": self.temperature_K,
            "mean_mass_kg": self.mean_mass_kg,
            "number_density_m3": dict(self.number_density_m3),
            "mole_fractions": self.mole_fractions,
            "species_mass_kg": self.mass_kg,
        }
        if self.altitude_km is not None:
            out["altitude_km"] = self.altitude_km
        if self.inputs:
            out["inputs"] = dict(self.inputs)
        if self.model_density_kg_m3 is not None:
            out["model_density_kg_m3"] = self.model_density_kg_m3
        return out


def explicit(
    density_kg_m3: float,
    temperature_K: float,
    composition: str | Mapping[str, float],
    normalise: bool = False,
) -> Atmosphere:
    """An atmosphere from a given mass density, temperature and composition.

    Parameters
    ----------
    density_kg_m3 : float
        Mass density [kg/m^3], finite and positive.
    temperature_K : float
        Free-stream kinetic temperature [K], within :data:`TEMPERATURE_RANGE_K`.
    composition : str or Mapping[str, float]
        Mole (number) fraction of each species, not mass fraction: ``"O:0.7,N2:0.3"`` means 70 % of the
        molecules are O. Species names as :func:`species_name` accepts them; ``=`` may stand for ``:``.
    normalise : bool
        Rescale the fractions to sum to 1 (``--normalise-composition``). Otherwise they must sum to 1
        within 1e-6 (and are then rescaled exactly).

    Returns
    -------
    Atmosphere
        Number densities ``n_k = x_k rho / m_mean`` with ``m_mean = sum x_k m_k``, so that
        ``sum n_k m_k = rho``.

    Raises
    ------
    InputError
        Unknown species, a fraction that is negative or not finite, fractions that do not sum to 1, a
        density that is not finite and positive, or a temperature out of range.

    Examples
    --------
    >>> air = explicit(1e-12, 1000.0, "O:0.7,N2:0.3")
    >>> {k: f"{n:.3e}" for k, n in air.number_density_m3.items()}
    {'O': '2.150e+13', 'N2': '9.216e+12'}
    """
    rho = finite_number(density_kg_m3, "density_kg_m3", "kg/m^3", positive=True)
    temperature = checked_temperature(temperature_K)
    fractions = parse_composition(composition)
    total = math.fsum(fractions.values())
    if total <= 0:
        raise InputError(
            "composition fractions sum to 0",
            hint="give at least one species a positive fraction",
            parameters=("composition",),
        )
    if not normalise and abs(total - 1.0) > 1e-6:
        raise InputError(
            f"composition mole fractions sum to {total:.9g}, not 1",
            hint="correct them, or set normalise to rescale them to sum to 1",
            parameters=("composition", "normalise"),
        )
    fractions = {k: fractions[k] / total for k in SPECIES_MASS_KG if fractions.get(k, 0.0) > 0}
    mean_mass = math.fsum(x * SPECIES_MASS_KG[k] for k, x in fractions.items())
    n_total = rho / mean_mass
    described = ", ".join(f"{k}:{x:.6g}" for k, x in fractions.items())
    source = (
        f"user: density {rho:.6g} kg/m^3, temperature {temperature:.6g} K, "
        f"composition {described} (mole fractions)"
    )
    return Atmosphere({k: x * n_total for k, x in fractions.items()}, temperature, source)


def parse_composition(composition: str | Mapping[str, float]) -> dict[str, float]:
    """Mole fractions by canonical species name from ``"O:0.7,N2:0.3"`` or a mapping; not normalised.

    Parameters
    ----------
    composition : str or Mapping[str, float]
        ``SPECIES:FRACTION`` entries separated by ``,`` or ``;`` (``=`` may stand for ``:``), or a
        mapping.

    Returns
    -------
    dict[str, float]
        Fraction of each species named, by canonical name.

    Raises
    ------
    InputError
        Unknown or repeated species, an entry that does not read as ``SPECIES:FRACTION``, or a fraction
        that is negative or not finite.

    Examples
    --------
    >>> parse_composition("o:0.7, n2=0.3")
    {'O': 0.7, 'N2': 0.3}
    """
    if isinstance(composition, str):
        pairs: list[tuple[str, object]] = []
        for item in filter(None, (s.strip() for s in re.split(r"[,;]", composition))):
            name, sep, value = item.partition(":") if ":" in item else item.partition("=")
            name, value = name.strip(), value.strip()
            if not sep or not name or not value:
                raise InputError(
                    f"composition entry '{item}' is not SPECIES:FRACTION",
                    hint='e.g. "O:0.7,N2:0.3"',
                    parameters=("composition",),
                )
            pairs.append((name, value))
    else:
        pairs = list(composition.items())
    if not pairs:
        raise InputError("composition is empty", hint='e.g. "O:0.7,N2:0.3"', parameters=("composition",))
    fractions: dict[str, float] = {}
    for name, value in pairs:
        key = species_name(name)
        if key in fractions:
            raise InputError(f"composition gives {key} twice", parameters=("composition",))
        try:
            x = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise InputError(
                f"composition fraction of {key} '{value}' is not a number", parameters=("composition",)
            ) from None
        if not math.isfinite(x) or x < 0:
            raise InputError(
                f"composition fraction of {key} is {x}, not a finite non-negative number",
                parameters=("composition",),
            )
        fractions[key] = x
    return fractions


def checked_temperature(temperature_K: float) -> float:
    """A free-stream temperature [K] as a float, finite and within :data:`TEMPERATURE_RANGE_K`.

    Parameters
    ----------
    temperature_K : float
        The temperature [K].

    Returns
    -------
    float
        The same, checked.

    Raises
    ------
    InputError
        Not a number, not finite, or out of range (naming ``temperature_K``).

    Examples
    --------
    >>> checked_temperature(900)
    900.0
    """
    low, high = TEMPERATURE_RANGE_K
    return finite_number(temperature_K, "temperature_K", "K", minimum=low, maximum=high)


def finite_number(
    value: float,
    name: str,
    unit: str,
    *,
    minimum: float | None = None,
    maximum: float | None = None,
    positive: bool = False,
) -> float:
    """``value`` as a float, checked finite and in range.

    Parameters
    ----------
    value : float
        The number.
    name : str
        The parameter that gave it (named in the error).
    unit : str
        Its unit, for the message ("" for none).
    minimum, maximum : float, optional
        Bounds, inclusive.
    positive : bool
        Whether it must be > 0.

    Returns
    -------
    float
        ``value`` as a float.

    Raises
    ------
    InputError
        Not a number, not finite, or out of range; naming ``name``.

    Examples
    --------
    >>> finite_number("7.5", "speed", "km/s", minimum=0.0)
    7.5
    """
    shown = f"{name} {value}{' ' + unit if unit else ''}"
    named = (name,)
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{shown} is not a number", parameters=named) from None
    if not math.isfinite(x):
        raise InputError(f"{shown} is not a finite number", parameters=named)
    if positive and x <= 0:
        raise InputError(f"{shown} is not positive", hint=f"give {name} greater than 0", parameters=named)
    if minimum is not None and x < minimum:
        raise InputError(
            f"{shown} is below {minimum:g}", hint=f"give {name} of at least {minimum:g}", parameters=named
        )
    if maximum is not None and x > maximum:
        raise InputError(
            f"{shown} is above {maximum:g}", hint=f"give {name} of at most {maximum:g}", parameters=named
        )
    return x
