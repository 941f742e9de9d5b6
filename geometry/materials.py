"""Optical materials and the TOML file that assigns them to mesh parts (METHOD.md "Surfaces and sides")."""

from __future__ import annotations

import fnmatch
import json
import math
import os
import re
import sys
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.articulation import Hinge, parse_articulation
from sunwind.geometry.errors import MaterialError, SunwindError, combine

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: Optical keys of a ``[materials.NAME]`` table, with the symbol METHOD.md uses.
MATERIAL_KEYS = {
    "reflectivity": "rho",
    "specular_fraction": "beta",
    "transmissivity": "sigma",
}
#: Gas-surface interaction models (``gsi``), in the order of their codes in :class:`MaterialTable`.
GSI_MODELS = ("sentman", "dria", "schaaf-chambre", "cll", "specular")
#: Gas-surface keys of a ``[materials.NAME]`` table and their defaults (README "Materials").
GAS_DEFAULTS = {
    "gsi": "sentman",
    "energy_accommodation": 1.0,  # alpha_E (sentman, dria)
    "normal_accommodation": 1.0,  # sigma_n (schaaf-chambre), alpha_n (cll)
    "tangential_accommodation": 1.0,  # sigma_t (schaaf-chambre, cll)
    "wall_temperature": 300.0,  # T_w [K]
}

#: Hottest wall temperature a material may give [K]: above any surface a spacecraft keeps (tungsten melts
#: at 3695 K); a larger value is a unit slip, not a wall.
MAX_WALL_TEMPERATURE_K = 1e4


#: Most tables and arrays one inside another that a materials file may nest (a real one nests 2).
MAX_TOML_DEPTH = 64


def toml_key(name: str) -> str:
    """``name`` as a TOML key: bare when it may be (``white_paint``), else quoted (``"foil_silver.014"``)."""
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else json.dumps(name, ensure_ascii=False)


@dataclass(frozen=True)
class GasSurface:
    """How a surface finish meets the rarefied gas (METHOD.md "Free-molecular flow").

    Attributes
    ----------
    model : str
        One of :data:`GSI_MODELS`.
    energy_accommodation : float
        ``alpha_E`` [-] in [0, 1], of the diffuse models ``sentman`` and ``dria``.
    normal_accommodation : float
        ``sigma_n`` of ``schaaf-chambre``, normal energy accommodation ``alpha_n`` of ``cll`` [-].
    tangential_accommodation : float
        ``sigma_t`` [-] of ``schaaf-chambre`` and ``cll``.
    wall_temperature_K : float
        ``T_w`` [K], > 0.
    """

    model: str = GAS_DEFAULTS["gsi"]
    energy_accommodation: float = GAS_DEFAULTS["energy_accommodation"]
    normal_accommodation: float = GAS_DEFAULTS["normal_accommodation"]
    tangential_accommodation: float = GAS_DEFAULTS["tangential_accommodation"]
    wall_temperature_K: float = GAS_DEFAULTS["wall_temperature"]

    @classmethod
    def checked(cls, where: str, values: Mapping[str, object], source: str | None = None) -> GasSurface:
        """Gas-surface parameters from ``GAS_DEFAULTS`` keys (missing keys take their defaults).

        ``where`` names the owner in messages, e.g. "material 'white_paint'" or "command line".
        """
        unknown = sorted(set(values) - set(GAS_DEFAULTS))
        if unknown:
            raise MaterialError(f"{where} has unknown gas key '{unknown[0]}'", path=source)
        model = values.get("gsi", GAS_DEFAULTS["gsi"])
        if model not in GSI_MODELS:
            raise MaterialError(
                f"{where}: gsi = {model!r} is not a gas-surface model",
                path=source,
                hint=f"use one of {', '.join(GSI_MODELS)}",
            )
        numbers = {}
        for key in ("energy_accommodation", "normal_accommodation", "tangential_accommodation"):
            numbers[key] = _number(where, key, values.get(key, GAS_DEFAULTS[key]), source, 0.0, 1.0)
        wall = _number(where, "wall_temperature", values.get("wall_temperature", 300.0), source, 0.0, None)
        if wall > MAX_WALL_TEMPERATURE_K:
            raise MaterialError(
                f"{where}: wall_temperature = {wall:g} K is above {MAX_WALL_TEMPERATURE_K:g} K, hotter than "
                "any spacecraft wall",
                path=source,
                hint="give the surface temperature in kelvin",
            )
        return cls(model=str(model), wall_temperature_K=wall, **numbers)

    @property
    def code(self) -> int:
        """Index of :attr:`model` in :data:`GSI_MODELS`."""
        return GSI_MODELS.index(self.model)


def _number(where: str, key: str, value: object, source: str | None, low: float, high: float | None) -> float:
    """``value`` as a float in ``[low, high]`` (``(low, inf)`` when ``high`` is None), else an error."""
    interval = f"[{low:g}, {high:g}]" if high is not None else f"> {low:g}"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise MaterialError(
            f"{where}: {key} = {value!r} is not a number", path=source, hint=f"use {interval}"
        )
    inside = low <= value <= high if high is not None else value > low
    if not math.isfinite(value) or not inside:
        if high is None:  # the wall temperature, in kelvin
            raise MaterialError(f"{where}: {key} = {value:g} K is not above {low:g} K", path=source)
        raise MaterialError(f"{where}: {key} = {value} is outside {interval}", path=source)
    return float(value)


@dataclass(frozen=True)
class Material:
    """Optical properties of one surface finish.

    Attributes
    ----------
    name : str
    reflectivity : float
        ``rho`` [-], share of incident power reflected, in [0, 1].
    specular_fraction : float
        ``beta`` [-], specular share of the reflected power, in [0, 1].
    transmissivity : float
        ``sigma`` [-], share transmitted, in [0, 1]; absorptivity is ``1 - rho - sigma``.
    gas : GasSurface
        Gas-surface interaction; defaults as :data:`GAS_DEFAULTS`.
    """

    name: str
    reflectivity: float
    specular_fraction: float
    transmissivity: float = 0.0
    gas: GasSurface = GasSurface()

    @classmethod
    def checked(cls, name: str, values: Mapping[str, object], source: str | None = None) -> Material:
        """Build a material from a key -> value mapping, rejecting unknown keys and bad values."""
        where = f"material '{name}'"
        unknown = sorted(set(values) - set(MATERIAL_KEYS) - set(GAS_DEFAULTS))
        if unknown:
            raise MaterialError(
                f"{where} has unknown key '{unknown[0]}'",
                path=source,
                hint=f"the keys are {', '.join([*MATERIAL_KEYS, *GAS_DEFAULTS])}",
            )
        gas = GasSurface.checked(where, {k: v for k, v in values.items() if k in GAS_DEFAULTS}, source)
        values = {k: v for k, v in values.items() if k in MATERIAL_KEYS}
        missing = [k for k in ("reflectivity", "specular_fraction") if k not in values]
        if missing:
            raise MaterialError(
                f"{where} lacks '{missing[0]}'",
                path=source,
                hint="give reflectivity, specular_fraction and (optionally) transmissivity",
            )
        numbers = {}
        for key, value in values.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise MaterialError(
                    f"{where}: {key} = {value!r} is not a number", path=source, hint="use a number in [0, 1]"
                )
            if not math.isfinite(value) or not 0.0 <= value <= 1.0:
                raise MaterialError(
                    f"{where}: {key} = {value} is outside [0, 1]", path=source, hint="use a number in [0, 1]"
                )
            numbers[key] = float(value)
        material = cls(name=name, gas=gas, **numbers)
        if material.reflectivity + material.transmissivity > 1.0 + 1e-12:
            raise MaterialError(
                f"{where}: reflectivity + transmissivity = "
                f"{material.reflectivity + material.transmissivity:g} exceeds 1",
                path=source,
                hint="absorptivity 1 - rho - sigma cannot be negative; lower one of them",
            )
        return material

    @property
    def absorptivity(self) -> float:
        """``alpha = 1 - rho - sigma`` [-]."""
        return 1.0 - self.reflectivity - self.transmissivity


@dataclass(frozen=True, eq=False)
class MaterialTable:
    """Materials as columns, so a kernel gathers ``rho[side_material]`` in one step."""

    names: tuple[str, ...]
    rho: NDArray[np.float64]
    beta: NDArray[np.float64]
    sigma: NDArray[np.float64]
    gas: tuple[GasSurface, ...] = ()

    @classmethod
    def from_materials(cls, materials: list[Material]) -> MaterialTable:
        """Stack materials into columns."""

        def column(attr: str) -> NDArray[np.float64]:
            values = np.array([getattr(m, attr) for m in materials], dtype=np.float64)
            values.flags.writeable = False
            return values

        return cls(
            names=tuple(m.name for m in materials),
            rho=column("reflectivity"),
            beta=column("specular_fraction"),
            sigma=column("transmissivity"),
            gas=tuple(m.gas for m in materials),
        )

    def with_gas(self, **changes: object) -> MaterialTable:
        """This table with the given :class:`GasSurface` fields set on every material."""
        gas = tuple(replace(g, **changes) for g in self.gas)
        return replace(self, gas=gas)

    def gas_column(self, attr: str) -> NDArray:
        """One :class:`GasSurface` field of every material, (n_materials,); ``code`` for the model."""
        return np.array([getattr(g, attr) for g in self.gas])

    def __getitem__(self, index: int) -> Material:
        return Material(
            self.names[index],
            float(self.rho[index]),
            float(self.beta[index]),
            float(self.sigma[index]),
            self.gas[index],
        )

    def __len__(self) -> int:
        return len(self.names)


def part_matches(part: str, pattern: str) -> bool:
    """Match a glob against the full part name or, for a path such as a USD prim path, its leaf."""
    leaf = part.rstrip("/").rsplit("/", 1)[-1]
    return fnmatch.fnmatchcase(part, pattern) or fnmatch.fnmatchcase(leaf, pattern)


@dataclass(frozen=True)
class PartRule:
    """One ``[parts]`` entry: a glob and the material(s) of the parts it matches.

    ``"pat" = "m"`` gives material ``m`` (a closed body, or both sides of a sheet the mesh file declares
    two-sided); ``{ front = "a", back = "b" }`` makes a two-sided sheet; ``{ front = "a" }`` makes a
    one-sided sheet whose back is inert (an open surface that light reaches from the front only).
    """

    pattern: str
    front: str
    back: str | None
    sheet: bool

    def matches(self, part: str) -> bool:
        """Whether this rule applies to ``part`` (see :func:`part_matches`)."""
        return part_matches(part, self.pattern)


@dataclass(frozen=True)
class MaterialSpec:
    """A parsed materials file: named materials, the ordered part rules, from its ``[model]`` table the
    centre of mass [m] in the body frame (the torque reference point; None when not given), and the
    hinges of its ``[articulation]`` tables."""

    materials: Mapping[str, Material]
    rules: tuple[PartRule, ...]
    source: str | None = None
    centre_of_mass_m: tuple[float, float, float] | None = None
    hinges: tuple[Hinge, ...] = ()

    def rule_for(self, part: str) -> PartRule | None:
        """The first rule matching ``part``, or None."""
        return next((rule for rule in self.rules if rule.matches(part)), None)


def load_materials(path: str | os.PathLike) -> MaterialSpec:
    """Read a materials TOML file (format in README "Materials"), checking every value.

    Raises
    ------
    MaterialError
        Missing or unparsable file, unknown keys, values outside [0, 1], ``rho + sigma > 1``,
        or a part rule naming a material that is not defined.
    """
    source = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise MaterialError("no such file", path=source, hint="check the materials file's path") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise MaterialError(f"cannot read the file ({exc.__class__.__name__})", path=source) from None
    depth = _nesting(text)
    if depth > MAX_TOML_DEPTH:
        raise MaterialError(
            f"is nested {depth} tables or arrays deep, more than the {MAX_TOML_DEPTH} a materials file may",
            path=source,
            hint="a materials file has [materials.NAME] tables, a [parts] table and a [model] table",
        )
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MaterialError(f"not valid TOML: {exc}", path=source) from None
    except RecursionError:  # nesting that _nesting does not see, e.g. dotted keys
        raise MaterialError("is nested too deeply to read", path=source) from None
    return parse_materials(document, source)


def _nesting(text: str) -> int:
    """Deepest nesting of ``{`` and ``[`` outside strings and comments (an upper bound; cheap)."""
    text = re.sub(r"#[^\n]*|\"(?:[^\"\\\n]|\\.)*\"|'[^'\n]*'", "", text)
    depth = deepest = 0
    for char in re.findall(r"[\[\]{}]", text):
        depth = depth + 1 if char in "[{" else max(depth - 1, 0)
        deepest = max(deepest, depth)
    return deepest


def parse_materials(document: Mapping[str, object], source: str | None = None) -> MaterialSpec:
    """Check and convert a materials document already parsed from TOML."""
    unknown = sorted(set(document) - {"materials", "parts", "model", "articulation"})
    if unknown:
        raise MaterialError(
            f"unknown top-level table '{unknown[0]}'",
            path=source,
            hint="a materials file has [materials.NAME] tables, a [parts] table, a [model] table and "
            '[articulation."GLOB"] tables',
        )
    tables = document.get("materials", {})
    if not isinstance(tables, Mapping) or not all(isinstance(t, Mapping) for t in tables.values()):
        raise MaterialError(
            "[materials] must hold one table per material",
            path=source,
            hint="write [materials.white_paint] followed by its keys",
        )
    problems: list[SunwindError] = []
    materials = {}
    for name, values in tables.items():
        try:
            materials[name] = Material.checked(name, values, source)
        except MaterialError as error:
            problems.append(error)
    rules_table = document.get("parts", {})
    if not isinstance(rules_table, Mapping):
        problems.append(MaterialError("[parts] must be a table of glob = material", path=source))
        rules_table = {}
    rules = []
    for pattern, value in rules_table.items():
        try:
            rules.append(_parse_rule(pattern, value, materials, set(tables), source))
        except MaterialError as error:
            problems.append(error)
    try:
        centre = _centre_of_mass(document.get("model", {}), source)
    except MaterialError as error:
        problems.append(error)
    try:
        hinges = parse_articulation(document.get("articulation", {}), source)
    except MaterialError as error:
        problems.append(error)
    if problems:
        raise combine(problems)
    return MaterialSpec(materials, tuple(rules), source, centre, hinges)


def _centre_of_mass(table: object, source: str | None) -> tuple[float, float, float] | None:
    """``centre_of_mass_m`` of the ``[model]`` table: three finite numbers [m], or None when absent."""
    if not isinstance(table, Mapping) or set(table) - {"centre_of_mass_m"}:
        raise MaterialError(
            "[model] may hold only centre_of_mass_m",
            path=source,
            hint="write [model] followed by centre_of_mass_m = [x, y, z] (metres, body frame)",
        )
    value = table.get("centre_of_mass_m")
    if value is None:
        return None
    numbers = isinstance(value, list) and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value
    )
    if not numbers or len(value) != 3:
        raise MaterialError(
            f"[model] centre_of_mass_m = {value!r} is not 3 numbers",
            path=source,
            hint="give centre_of_mass_m = [x, y, z], finite, in metres in the body frame",
        )
    return (float(value[0]), float(value[1]), float(value[2]))


def _parse_rule(
    pattern: str, value: object, materials: Mapping[str, Material], defined: set[str], source: str | None
) -> PartRule:
    """Convert one ``[parts]`` entry, checking that the materials it names exist (``defined``: every
    ``[materials]`` table, valid or not, so that a bad material is reported once)."""
    if isinstance(value, str):
        front, back, sheet = value, None, False
    elif isinstance(value, Mapping):
        unknown = sorted(set(value) - {"front", "back"})
        if unknown or "front" not in value:
            raise MaterialError(
                f'[parts] "{pattern}" must be a material name or {{ front = ..., back = ... }}',
                path=source,
                hint=f"unknown key '{unknown[0]}'" if unknown else "give at least 'front'",
            )
        front, back, sheet = value["front"], value.get("back"), True
    else:
        raise MaterialError(f'[parts] "{pattern}" = {value!r} is not a material name', path=source)
    for name in (front, back):
        if name is not None and name not in defined:
            raise MaterialError(
                f"[parts] \"{pattern}\" names material '{name}', which is not defined",
                path=source,
                hint=f"add a [materials.{toml_key(str(name))}] table",
            )
    return PartRule(pattern=pattern, front=front, back=back, sheet=sheet)
