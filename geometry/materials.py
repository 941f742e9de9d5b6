"""Optical materials and the TOML file that assigns them to mesh parts (METHOD.md "Surfaces and sides");
gas-surface parameters and named finishes are in :mod:`sunwind.geometry.finishes`."""

from __future__ import annotations

import fnmatch
import json
import math
import os
import re
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.articulation import Hinge, parse_articulation
from sunwind.geometry.errors import MaterialError, SunwindError, combine
from sunwind.geometry.finishes import GAS_DEFAULTS, GasSurface, checked_number, finish
from sunwind.geometry.finishes import GSI_MODELS as GSI_MODELS  # re-exported: gas models by code
from sunwind.geometry.finishes import MAX_WALL_TEMPERATURE_K as MAX_WALL_TEMPERATURE_K  # re-exported

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: Optical keys of a ``[materials.NAME]`` table, with the symbol METHOD.md uses; ``emissivity`` is the
#: infrared one (optional). A table may also give ``finish = "NAME"`` (:mod:`sunwind.geometry.finishes`).
MATERIAL_KEYS = {
    "reflectivity": "rho",
    "specular_fraction": "beta",
    "transmissivity": "sigma",
    "emissivity": "eps",
}
#: Keys of a ``[thermal."GLOB"]`` table.
THERMAL_KEYS = ("isothermal", "conductance_W_m2K", "heat_capacity_J_K")
#: Keys of a ``[[conductance]]`` table (a conductance between two isothermal parts).
CONDUCTANCE_KEYS = ("parts", "conductance_W_K")
#: Most tables and arrays one inside another that a materials file may nest (a real one nests 2).
MAX_TOML_DEPTH = 64


def toml_key(name: str) -> str:
    """Write a name as a TOML key: bare when it may be, else quoted.

    Parameters
    ----------
    name : str
        A material or part name.

    Returns
    -------
    str
        ``name`` itself when it is a valid bare key, else a JSON-quoted string.

    Examples
    --------
    >>> toml_key("white_paint"), toml_key("foil_silver.014")
    ('white_paint', '"foil_silver.014"')
    """
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else json.dumps(name, ensure_ascii=False)


@dataclass(frozen=True)
class Material:
    """Optical properties of one surface finish.

    Attributes
    ----------
    name : str
        Name of the material, as in the materials file.
    reflectivity : float
        ``rho`` [-], share of incident power reflected, in [0, 1].
    specular_fraction : float
        ``beta`` [-], specular share of the reflected power, in [0, 1].
    transmissivity : float
        ``sigma`` [-], share transmitted, in [0, 1]; absorptivity is ``1 - rho - sigma``.
    gas : GasSurface
        Gas-surface interaction; defaults as :data:`GAS_DEFAULTS`.
    emissivity : float or None
        ``eps`` [-], hemispherical infrared emissivity in [0, 1], grey; by Kirchhoff also the infrared
        absorptance, the rest of the infrared reflected diffusely (none transmitted). None: not given.

    Examples
    --------
    >>> white = Material("white", reflectivity=0.8, specular_fraction=0.1, emissivity=0.9)
    >>> round(1 - white.reflectivity - white.transmissivity, 3)
    0.2
    >>> Material.checked("foil", {"reflectivity": 0.9, "specular_fraction": 0.95}).transmissivity
    0.0
    """

    name: str
    reflectivity: float
    specular_fraction: float
    transmissivity: float = 0.0
    gas: GasSurface = field(default_factory=GasSurface)
    emissivity: float | None = None

    @classmethod
    def checked(cls, name: str, values: Mapping[str, object], source: str | None = None) -> Material:
        """Build a material from a key -> value mapping, rejecting unknown keys and bad values. A
        ``finish`` key gives the optical keys of that finish (:func:`~sunwind.geometry.finishes.finish`);
        keys given beside it override its."""
        where = f"material '{name}'"
        unknown = sorted(set(values) - {*MATERIAL_KEYS, "finish", *GAS_DEFAULTS})
        if unknown:
            raise MaterialError(
                f"{where} has unknown key '{unknown[0]}'",
                path=source,
                hint=f"the keys are {', '.join([*MATERIAL_KEYS, 'finish', *GAS_DEFAULTS])}",
            )
        if "finish" in values:
            given = {key: value for key, value in values.items() if key != "finish"}
            values = {**finish(values["finish"], where, source).keys, **given}
        gas = GasSurface.checked(where, {k: v for k, v in values.items() if k in GAS_DEFAULTS}, source)
        values = {k: v for k, v in values.items() if k in MATERIAL_KEYS}
        missing = [k for k in ("reflectivity", "specular_fraction") if k not in values]
        if missing:
            raise MaterialError(
                f"{where} lacks '{missing[0]}'",
                path=source,
                hint="give reflectivity, specular_fraction and (optionally) transmissivity, or a finish",
            )
        numbers = {key: checked_number(where, key, value, source, 0.0, 1.0) for key, value in values.items()}
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
    """Materials as columns, so a kernel gathers ``rho[side_material]`` in one step.

    Attributes
    ----------
    names : tuple of str
        Material names, in index order.
    rho, beta, sigma : (n_materials,) float64
        Reflectivity, specular fraction and transmissivity [-] of each material.
    eps : (n_materials,) float64
        Infrared emissivity [-]; NaN for a material without one.
    gas : tuple of GasSurface
        Gas-surface parameters of each material.

    Examples
    --------
    >>> table = MaterialTable.from_materials([Material("a", 0.3, 0.1),
    ...     Material("b", 0.6, 0.9, emissivity=0.5)])
    >>> len(table), table.rho, table.eps
    (2, array([0.3, 0.6]), array([nan, 0.5]))
    >>> table.infrared([1, 1])
    array([[0.5, 0. , 0. ],
           [0.5, 0. , 0. ]])
    """

    names: tuple[str, ...]
    rho: NDArray[np.float64]
    beta: NDArray[np.float64]
    sigma: NDArray[np.float64]
    eps: NDArray[np.float64]
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
            eps=column("emissivity"),  # None -> NaN
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
            None if math.isnan(self.eps[index]) else float(self.eps[index]),
        )

    def infrared(
        self, material: NDArray, path: str | None = None, model_path: str | None = None
    ) -> NDArray[np.float64]:
        """Infrared ``(rho, beta, sigma) = (1 - eps, 0, 0)`` of the materials ``material`` (indices),
        (len(material), 3): grey, opaque, reflecting diffusely what it does not absorb (Kirchhoff).

        Raises
        ------
        MaterialError
            Naming every material of ``material`` without an emissivity, and ``path``, the materials
            file to fix; without one (None: a uniform material), ``model_path`` and the flag to give.
        """
        material = np.asarray(material, dtype=np.int64)
        missing = [self.names[i] for i in np.unique(material) if np.isnan(self.eps[i])]
        if missing:
            names = ", ".join(f"'{name}'" for name in missing)
            tables = ", ".join(f"[materials.{toml_key(name)}]" for name in missing)
            fix = (
                f'add emissivity = ... (infrared, 0 to 1) to {tables}, or finish = "NAME" from the finishes '
                "library"
                if path is not None
                else "give the uniform material one: --emissivity E (infrared, 0 to 1; Python: "
                "Material(..., emissivity=E)), or a materials file"
            )
            raise MaterialError(
                f"material {names} has no emissivity"
                if len(missing) == 1
                else f"materials {names} have no emissivity",
                path=path if path is not None else model_path,
                hint=fix,
            )
        optics = np.zeros((len(material), 3))
        optics[:, 0] = 1.0 - self.eps[material]
        return optics

    def __len__(self) -> int:
        return len(self.names)


def part_matches(part: str, pattern: str) -> bool:
    """Match a glob against the full part name or, for a path such as a USD prim path, its leaf.

    Parameters
    ----------
    part : str
        Part name, possibly a ``/``-separated path.
    pattern : str
        Case-sensitive :mod:`fnmatch` glob.

    Returns
    -------
    bool
        Whether ``pattern`` matches ``part`` or its last path element.

    Examples
    --------
    >>> part_matches("/World/bus/panel_1", "panel_*"), part_matches("bus", "wing*")
    (True, False)
    """
    leaf = part.rstrip("/").rsplit("/", 1)[-1]
    return fnmatch.fnmatchcase(part, pattern) or fnmatch.fnmatchcase(leaf, pattern)


@dataclass(frozen=True)
class PartRule:
    """One ``[parts]`` entry: a glob and the material(s) of the parts it matches.

    ``"pat" = "m"`` gives material ``m`` (a closed body, or both sides of a sheet the mesh file declares
    two-sided); ``{ front = "a", back = "b" }`` makes a two-sided sheet; ``{ front = "a" }`` makes a
    one-sided sheet whose back is inert (an open surface that light reaches from the front only).

    Attributes
    ----------
    pattern : str
        Part-name glob (see :func:`part_matches`).
    front : str
        Material of the front side, or of the whole part.
    back : str or None
        Material of a two-sided sheet's back; None for a one-sided part.
    sheet : bool
        Whether the entry declares the parts sheets (a ``{ front = ... }`` table).

    Examples
    --------
    >>> rule = PartRule("wing*", front="cells", back="kapton", sheet=True)
    >>> rule.matches("wing_left"), rule.matches("bus")
    (True, False)
    """

    pattern: str
    front: str
    back: str | None
    sheet: bool

    def matches(self, part: str) -> bool:
        """Whether this rule applies to ``part`` (see :func:`part_matches`)."""
        return part_matches(part, self.pattern)


@dataclass(frozen=True)
class ThermalRule:
    """One ``[thermal."GLOB"]`` table: how the parts its glob matches hold heat.

    Globs match as :class:`PartRule` globs do; the first matching rule applies to a part.

    Attributes
    ----------
    pattern : str
        Part-name glob (see :func:`part_matches`).
    isothermal : bool
        All sides of each matched part are one node, at one temperature; False: each facet side is its
        own node.
    conductance_W_m2K : float
        Front-back conductance per unit area of a two-sided sheet [W/(m^2 K)], > 0; ``math.inf``: the
        front and back of a sheet facet are at one temperature.
    heat_capacity_J_K : float or None
        Heat capacity of the matched parts together [J/K], > 0, for the transient (of isothermal parts);
        None: not given.

    Examples
    --------
    >>> rule = ThermalRule.checked("bus", {"isothermal": True, "heat_capacity_J_K": 900.0})
    >>> rule.isothermal, rule.conductance_W_m2K, rule.matches("bus")
    (True, inf, True)
    """

    pattern: str
    isothermal: bool = False
    conductance_W_m2K: float = math.inf
    heat_capacity_J_K: float | None = None

    def matches(self, part: str) -> bool:
        """Whether this rule's glob matches ``part`` (see :func:`part_matches`)."""
        return part_matches(part, self.pattern)

    @classmethod
    def checked(cls, pattern: str, values: object, source: str | None = None) -> ThermalRule:
        """A rule from its ``[thermal."GLOB"]`` table; :class:`MaterialError` for a table that is not one,
        an unknown key, ``isothermal`` not a boolean, a conductance or heat capacity not above 0."""
        where = f'[thermal] "{pattern}"'
        unknown = sorted(set(values) - set(THERMAL_KEYS)) if isinstance(values, Mapping) else []
        if not isinstance(values, Mapping) or unknown:
            raise MaterialError(
                f"{where} has unknown key '{unknown[0]}'" if unknown else f"{where} must be a table",
                path=source,
                hint=f"write [thermal.{json.dumps(pattern)}] with isothermal = true or false, "
                'conductance_W_m2K = W/(m^2 K) or "inf", heat_capacity_J_K = J/K (each optional)',
            )
        isothermal = values.get("isothermal", False)
        if not isinstance(isothermal, bool):
            raise MaterialError(
                f"{where}: isothermal = {isothermal!r} is not true or false",
                path=source,
                hint="write true or false",
            )
        conductance = values.get("conductance_W_m2K", math.inf)
        try:
            if conductance not in ("inf", math.inf):
                conductance = checked_number(
                    where, "conductance_W_m2K", conductance, source, 0.0, None, " W/(m^2 K)"
                )
        except MaterialError as error:
            hint = 'give a number above 0 W/(m^2 K), or "inf" (front and back of a sheet at one temperature)'
            raise MaterialError(error.message, path=source, hint=hint) from None
        capacity = values.get("heat_capacity_J_K")
        if capacity is not None:
            capacity = checked_number(where, "heat_capacity_J_K", capacity, source, 0.0, None, " J/K")
        return cls(pattern, isothermal, float(conductance), capacity)


def parse_thermal(table: object, source: str | None = None) -> tuple[ThermalRule, ...]:
    """Read the rules of a materials file's ``[thermal]`` table, in order.

    Parameters
    ----------
    table : mapping
        The ``[thermal]`` table, glob -> table of :data:`THERMAL_KEYS`.
    source : str, optional
        The materials file, named in errors.

    Returns
    -------
    tuple of ThermalRule
        One rule per glob, in file order.

    Raises
    ------
    MaterialError
        Every problem of every rule, reported at once.

    Examples
    --------
    >>> rules = parse_thermal({"wing*": {"conductance_W_m2K": 50.0}, "bus": {"isothermal": True}})
    >>> [(rule.pattern, rule.conductance_W_m2K) for rule in rules]
    [('wing*', 50.0), ('bus', inf)]
    """
    if not isinstance(table, Mapping):
        raise MaterialError(
            "[thermal] must hold one table per glob", path=source, hint='write [thermal."bus"] and its keys'
        )
    rules, problems = [], []
    for pattern, values in table.items():
        try:
            rules.append(ThermalRule.checked(pattern, values, source))
        except MaterialError as error:
            problems.append(error)
    if problems:
        raise combine(problems)
    return tuple(rules)


@dataclass(frozen=True)
class Conductance:
    """One ``[[conductance]]`` table: a conductance between two parts, each at one temperature.

    Heat flows ``G (T_b - T_a)`` [W] from part ``b`` into part ``a`` (and the opposite into ``b``): a
    link between their thermal nodes, beside the front-back links of sheets
    (:mod:`sunwind.forces.thermal.nodes`). Both parts must be isothermal (a ``[thermal."GLOB"]`` table
    with ``isothermal = true``).

    Attributes
    ----------
    parts : (2,) tuple of str
        The two parts: names or globs (see :func:`part_matches`), each matching exactly one part.
    conductance_W_K : float
        ``G`` [W/K], > 0 and finite.

    Examples
    --------
    >>> link = Conductance.checked({"parts": ["panel_px", "panel_p*"], "conductance_W_K": 0.5})
    >>> link.table
    '[[conductance]] parts = ["panel_px", "panel_p*"]'
    >>> link.matched(["bus", "panel_px", "panel_py"])
    [[1], [1, 2]]
    """

    parts: tuple[str, str]
    conductance_W_K: float

    @property
    def table(self) -> str:
        """The table as a message names it: ``[[conductance]] parts = ["a", "b"]``."""
        return f"[[conductance]] parts = {json.dumps(list(self.parts), ensure_ascii=False)}"

    def matched(self, parts: Sequence[str]) -> list[list[int]]:
        """The indices into ``parts`` each of the two globs matches."""
        return [[i for i, part in enumerate(parts) if part_matches(part, glob)] for glob in self.parts]

    def problems(
        self, parts: Sequence[str], mesh: str, path: str | None, rules: Sequence[object] = ()
    ) -> list[MaterialError]:
        """An error for each glob that matches no part or more than one, when both match the same part,
        and for each part whose first matching :class:`ThermalRule` of ``rules`` is not isothermal (or
        that none matches); empty when the table joins two isothermal parts of ``parts`` (of the mesh
        ``mesh``)."""
        found = self.matched(parts)
        listed = ", ".join(parts[:20]) + (f", ... ({len(parts)} parts)" if len(parts) > 20 else "")
        errors = []
        for glob, hits in zip(self.parts, found, strict=True):
            if len(hits) != 1:
                which = (
                    "no part" if not hits else f"{len(hits)} parts ({', '.join(parts[i] for i in hits[:5])})"
                )
                errors.append(
                    MaterialError(
                        f'{self.table}: "{glob}" matches {which} of {mesh}',
                        path=path,
                        hint=f"give each of the two parts by a name or a glob that matches one part; "
                        f"the parts are: {listed}",
                    )
                )
        if not errors and found[0] == found[1]:
            errors.append(
                MaterialError(
                    f"{self.table} joins part '{parts[found[0][0]]}' to itself",
                    path=path,
                    hint="a conductance joins two different parts",
                )
            )
        if errors:
            return errors
        thermal = [rule for rule in rules if isinstance(rule, ThermalRule)]
        for hits in found:
            part = parts[hits[0]]
            if not next((rule.isothermal for rule in thermal if rule.matches(part)), False):
                errors.append(
                    MaterialError(
                        f"{self.table}: part '{part}' is not isothermal (a conductance joins two parts "
                        "each at one temperature)",
                        path=path,
                        hint=f"add [thermal.{json.dumps(part)}] with isothermal = true before any other "
                        "[thermal] table that matches it",
                    )
                )
        return errors

    @classmethod
    def checked(cls, values: object, source: str | None = None) -> Conductance:
        """A conductance from its ``[[conductance]]`` table; :class:`MaterialError` for a table that is not
        one, an unknown or missing key, ``parts`` not two part names, a conductance not above 0."""
        hint = 'write [[conductance]] then parts = ["PART_A", "PART_B"] and conductance_W_K = W/K (> 0)'
        if not isinstance(values, Mapping):
            raise MaterialError("[[conductance]] must hold tables", path=source, hint=hint)
        unknown = sorted(set(values) - set(CONDUCTANCE_KEYS))
        missing = [key for key in CONDUCTANCE_KEYS if key not in values]
        parts = values.get("parts")
        where = (
            f"[[conductance]] parts = {json.dumps(parts, ensure_ascii=False)}"
            if isinstance(parts, list) and all(isinstance(p, str) for p in parts)
            else "[[conductance]]"
        )
        if unknown or missing:
            what = f"unknown key '{unknown[0]}'" if unknown else f"no '{missing[0]}'"
            raise MaterialError(f"{where} has {what}", path=source, hint=hint)
        if where == "[[conductance]]" or len(parts) != 2:
            raise MaterialError(
                f"[[conductance]] parts = {parts!r} is not two part names", path=source, hint=hint
            )
        conductance = checked_number(
            where, "conductance_W_K", values["conductance_W_K"], source, 0.0, None, " W/K"
        )
        return cls((parts[0], parts[1]), conductance)


def parse_conductances(array: object, source: str | None = None) -> tuple[Conductance, ...]:
    """Read a materials file's ``[[conductance]]`` tables, in order.

    Parameters
    ----------
    array : list of mappings
        The ``[[conductance]]`` array of tables, each with :data:`CONDUCTANCE_KEYS`.
    source : str, optional
        The materials file, named in errors.

    Returns
    -------
    tuple of Conductance
        One per table, in file order.

    Raises
    ------
    MaterialError
        Every problem of every table, reported at once.

    Examples
    --------
    >>> links = parse_conductances([{"parts": ["px", "py"], "conductance_W_K": 0.5}])
    >>> links[0].parts, links[0].conductance_W_K
    (('px', 'py'), 0.5)
    """
    if not isinstance(array, list):
        raise MaterialError(
            "[[conductance]] must be an array of tables",
            path=source,
            hint='write [[conductance]] (double brackets) before each parts = ["A", "B"] and conductance_W_K',
        )
    links, problems = [], []
    for values in array:
        try:
            links.append(Conductance.checked(values, source))
        except MaterialError as error:
            problems.append(error)
    if problems:
        raise combine(problems)
    return tuple(links)


def unmatched_thermal(
    rules: Sequence[ThermalRule], parts: Sequence[str], mesh: str, path: str | None
) -> list[MaterialError]:
    """List an error for each ``[thermal]`` rule whose glob matches no part of the mesh, and for each
    ``[[conductance]]`` table that does not join two of its isothermal parts
    (:meth:`Conductance.problems`).

    Parameters
    ----------
    rules : sequence of ThermalRule and Conductance
        The rules to check.
    parts : sequence of str
        Part names of the mesh.
    mesh : str
        The mesh file, named in the messages.
    path : str or None
        The materials file, named in the errors.

    Returns
    -------
    list of MaterialError
        One error per unmatched rule; empty when every rule matches a part.

    Examples
    --------
    >>> errors = unmatched_thermal([ThermalRule("wing*"), ThermalRule("bus")], ["bus"], "craft.obj", None)
    >>> [e.message for e in errors]
    ['[thermal] "wing*" matches no part of craft.obj']
    """
    listed = ", ".join(parts[:20]) + (f", ... ({len(parts)} parts)" if len(parts) > 20 else "")
    links = [rule for rule in rules if isinstance(rule, Conductance)]
    return [
        MaterialError(
            f'[thermal] "{rule.pattern}" matches no part of {mesh}',
            path=path,
            hint=f"the parts are: {listed}",
        )
        for rule in rules
        if not isinstance(rule, Conductance) and not any(rule.matches(part) for part in parts)
    ] + [error for link in links for error in link.problems(list(parts), mesh, path, rules)]


@dataclass(frozen=True)
class MaterialSpec:
    """A parsed materials file.

    Attributes
    ----------
    materials : mapping of str to Material
        The ``[materials.NAME]`` tables by name.
    rules : tuple of PartRule
        The ``[parts]`` entries, in order (the first matching a part applies).
    source : str or None
        The file it was read from.
    centre_of_mass_m : (3,) tuple of float or None
        ``[model] centre_of_mass_m`` [m], body frame: the torque reference point; None when not given.
    hinges : tuple of Hinge
        The ``[articulation]`` tables.
    thermal : tuple of ThermalRule and Conductance
        The ``[thermal]`` tables, in order, then the ``[[conductance]]`` tables, in order.

    Examples
    --------
    >>> spec = parse_materials({"materials": {"white": {"reflectivity": 0.8, "specular_fraction": 0.1}},
    ...                         "parts": {"*": "white"}})
    >>> spec.rule_for("bus").front, spec.centre_of_mass_m
    ('white', None)
    """

    materials: Mapping[str, Material]
    rules: tuple[PartRule, ...]
    source: str | None = None
    centre_of_mass_m: tuple[float, float, float] | None = None
    hinges: tuple[Hinge, ...] = ()
    thermal: tuple[ThermalRule | Conductance, ...] = ()

    def rule_for(self, part: str) -> PartRule | None:
        """The first rule matching ``part``, or None."""
        return next((rule for rule in self.rules if rule.matches(part)), None)


def load_materials(path: str | os.PathLike) -> MaterialSpec:
    """Read a materials TOML file (format: the materials guide), checking every value.

    Parameters
    ----------
    path : str or os.PathLike
        The materials file.

    Returns
    -------
    MaterialSpec
        Its materials, part rules, centre of mass, hinges, thermal rules and conductances.

    Raises
    ------
    MaterialError
        Missing or unparsable file, unknown keys, values outside [0, 1], ``rho + sigma > 1``,
        or a part rule naming a material that is not defined.

    Examples
    --------
    >>> from sunwind.meshes import sample_materials_path
    >>> spec = load_materials(sample_materials_path())
    >>> len(spec.materials) > 0, spec.source.endswith(".toml")
    (True, True)
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
    """Check and convert a materials document already parsed from TOML.

    Parameters
    ----------
    document : mapping
        The parsed document: ``materials``, ``parts``, ``model``, ``articulation`` and ``thermal`` tables
        and the ``conductance`` array of tables.
    source : str, optional
        The file it came from, named in errors.

    Returns
    -------
    MaterialSpec
        The checked contents.

    Raises
    ------
    MaterialError
        An unknown table or key, a value out of range, or a part rule naming an undefined material.

    Examples
    --------
    >>> doc = {"materials": {"foil": {"reflectivity": 0.9, "specular_fraction": 0.95, "emissivity": 0.05}},
    ...        "parts": {"wing*": {"front": "foil"}}, "model": {"centre_of_mass_m": [0.0, 0.0, 0.5]}}
    >>> spec = parse_materials(doc)
    >>> spec.materials["foil"].emissivity, spec.rules[0].sheet, spec.centre_of_mass_m
    (0.05, True, (0.0, 0.0, 0.5))
    """
    unknown = sorted(
        set(document) - {"materials", "parts", "model", "articulation", "thermal", "conductance"}
    )
    if unknown:
        raise MaterialError(
            f"unknown top-level table '{unknown[0]}'",
            path=source,
            hint="a materials file has [materials.NAME] tables, a [parts] table, a [model] table, "
            '[articulation."GLOB"] tables, [thermal."GLOB"] tables and [[conductance]] tables',
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
    try:
        thermal = parse_thermal(document.get("thermal", {}), source)
    except MaterialError as error:
        problems.append(error)
    try:
        links = parse_conductances(document.get("conductance", []), source)
    except MaterialError as error:
        problems.append(error)
    if problems:
        raise combine(problems)
    return MaterialSpec(materials, tuple(rules), source, centre, hinges, thermal + links)


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
