"""Thermal nodes: which sides share one temperature, the conductance links between them, their heat
capacities (METHOD.md "Surfaces and sides").

A *node* is a set of sides at one temperature ``T_k`` [K]. The rules, from the materials file's
``[thermal."GLOB"]`` tables (:class:`sunwind.geometry.spacecraft.ThermalRule`; per part the first rule
whose glob matches wins, as in ``[parts]``; a part no rule matches takes the defaults):

* by default every side is its own node, except that the front and back sides of a **two-sided sheet**
  facet are coupled through the sheet by the conductance per unit area ``h`` = ``conductance_W_m2K``
  [W/(m^2 K)] of the part's rule (default infinite): with ``h`` infinite front and back are **one**
  node; with ``0 < h < inf`` they are two nodes joined by a *link* of conductance ``h A`` [W/K] (``A``
  the facet area), carrying ``h A (T_back - T_front)`` into the front node; with ``h = 0`` two nodes
  and no link. A closed body's facet and a one-sided sheet's facet have one side: their own node
  (the back of a one-sided sheet is no side; IR reaching it is lost, "blind");
* ``isothermal = true`` makes **all** sides of each part the rule matches one node: one node **per
  matched part** (a glob matching three parts makes three nodes); ``conductance_W_m2K`` is then moot;
* ``heat_capacity_J_K`` [J/K] of an isothermal rule is the heat capacity of the parts it matches
  together, shared among their part nodes in proportion to part area (the lumped model of the
  transient, :meth:`sunwind.forces.thermal.model.ThermalModel.step` and
  :func:`sunwind.forces.thermal.transient.integrate`). Every other node has none (0 here): it is taken
  in steady state at every instant. A heat capacity on a rule that is not isothermal is an error;
* a ``[[conductance]]`` table (:class:`sunwind.geometry.materials.Conductance`) joins two parts by a
  link of conductance ``G`` [W/K], carrying ``G (T_b - T_a)`` into part ``a``'s node. Each of its two
  globs must match exactly one part, and both parts must be isothermal (one node each): else a
  :class:`~sunwind.geometry.errors.MaterialError` naming the table and the fix. Links between the same
  two nodes add up.

Node names: ``"part"`` for a part node; ``"part/facet 12"`` for a facet's one side, or the two sides
of a two-sided sheet facet taken as one node; ``"part/facet 12 front"`` and ``"part/facet 12 back"``
for the sides of a sheet facet of finite conductance. Facet numbers are the model's (0-based, into
``craft.faces``). Nodes are ordered: part nodes in part order, then facet nodes, then side nodes, each
by index.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph
from numpy.typing import NDArray

from sunwind.geometry.errors import InputError, MaterialError, combine
from sunwind.geometry.materials import Conductance, part_matches
from sunwind.geometry.sides import TWO_SIDED
from sunwind.geometry.spacecraft import Spacecraft


@dataclass(frozen=True, eq=False)
class ThermalNodes:
    """The nodes of a model and their links.

    Attributes
    ----------
    side_node : (n_sides,) int64
        Node of each side.
    names : (n_nodes,) str array
        Name of each node (module docstring).
    area_m2 : (n_nodes,) float64
        Area of each node's sides [m^2] (a sheet node of both sides counts the facet twice).
    links : (n_links, 2) int64
        Node pairs joined by a conductance: ``(front, back)`` of each two-sided sheet facet of finite
        conductance, then the part nodes of each ``[[conductance]]`` table, in order.
    link_conductance_W_K : (n_links,) float64
        Conductance of each link [W/K]: ``h A`` of a sheet facet, ``G`` of a table.
    heat_capacity_J_K : (n_nodes,) float64
        Heat capacity of each node [J/K]; 0 for a node held in steady state.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
    >>> nodes.n_nodes, str(nodes.names[0]), len(nodes.links)
    (12, 'box/facet 0', 0)
    """

    side_node: NDArray[np.int64]
    names: NDArray[np.str_]
    area_m2: NDArray[np.float64]
    links: NDArray[np.int64]
    link_conductance_W_K: NDArray[np.float64]
    heat_capacity_J_K: NDArray[np.float64]

    @property
    def n_nodes(self) -> int:
        """The number of nodes.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
        >>> nodes.n_nodes
        12
        """
        return len(self.area_m2)

    def gather(self, node_values: NDArray[np.float64]) -> NDArray[np.float64]:
        """Per-side values of per-node values.

        Parameters
        ----------
        node_values : (n_nodes,) array_like
            One value per node.

        Returns
        -------
        (n_sides,) ndarray
            Each side's node's value.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
        >>> nodes.gather(np.arange(12.0))[:3]
        array([0., 1., 2.])
        """
        return np.asarray(node_values)[self.side_node]

    def sum_sides(self, side_values: NDArray[np.float64]) -> NDArray[np.float64]:
        """Per-node sums of per-side values, ``P^T v``.

        Parameters
        ----------
        side_values : (n_sides,) float64
            One value per side.

        Returns
        -------
        (n_nodes,) float64
            The sum over each node's sides.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
        >>> nodes.sum_sides(craft.side_areas)[:3]
        array([0.5, 0.5, 0.5])
        """
        return np.bincount(self.side_node, weights=side_values, minlength=self.n_nodes)

    @cached_property
    def laplacian(self) -> scipy.sparse.csr_matrix:
        """The conduction matrix ``L`` (n_nodes, n_nodes) [W/K]: conduction brings ``-L T`` into the nodes.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
        >>> nodes.laplacian.shape, nodes.laplacian.nnz  # no links, no conduction
        ((12, 12), 0)
        """
        a, b = self.links.T
        g = self.link_conductance_W_K
        n = self.n_nodes
        rows = np.concatenate([a, b, a, b])
        cols = np.concatenate([a, b, b, a])
        values = np.concatenate([g, g, -g, -g])
        return scipy.sparse.csr_matrix((values, (rows, cols)), shape=(n, n))

    @cached_property
    def components(self) -> NDArray[np.int64]:
        """The group of linked nodes each node belongs to, (n_nodes,) int64.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> nodes = thermal_nodes(craft)  # no rules: each of the cube's 12 triangles is a node
        >>> nodes.components[:4]
        array([0, 1, 2, 3])
        """
        if len(self.links) == 0:
            return np.arange(self.n_nodes)
        _, labels = scipy.sparse.csgraph.connected_components(self.laplacian, directed=False)
        return labels.astype(np.int64)


def thermal_nodes(craft: Spacecraft, rules: tuple | None = None) -> ThermalNodes:
    """The :class:`ThermalNodes` of a model under its ``[thermal]`` rules.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft.
    rules : tuple of ThermalRule and Conductance, optional
        Rules in order (the first :class:`ThermalRule` matching a part wins) and conductances between
        parts; default ``craft.thermal``.

    Returns
    -------
    ThermalNodes
        The nodes, their names, areas, links and heat capacities (the module docstring gives the
        rules).

    Raises
    ------
    InputError
        A rule with ``heat_capacity_J_K`` that is not isothermal, a negative heat capacity or
        conductance.
    MaterialError
        A ``[[conductance]]`` whose globs do not match one part each, or joins a part that is not
        isothermal.

    Examples
    --------
    An isothermal rule makes the whole part one node, with the rule's heat capacity:

    >>> import sunwind as sw
    >>> from sunwind.geometry.materials import ThermalRule
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> nodes = thermal_nodes(craft, (ThermalRule("box", isothermal=True, heat_capacity_J_K=900.0),))
    >>> nodes.names.tolist(), nodes.area_m2, nodes.heat_capacity_J_K
    (['box'], array([6.]), array([900.]))

    Two isothermal parts joined by a conductance of 0.5 W/K:

    >>> from dataclasses import replace
    >>> from sunwind.geometry.materials import Conductance
    >>> two = sw.meshes.box()
    >>> two = replace(two, face_part=(two.vertices[two.faces].mean(axis=1)[:, 2] > 0).astype(np.int32),
    ...               part_names=("bottom", "top"))
    >>> craft = sw.load(two, uniform=grey, threads=1).craft
    >>> nodes = thermal_nodes(craft, (ThermalRule("*", isothermal=True), Conductance(("top", "bottom"), 0.5)))
    >>> nodes.names.tolist(), nodes.links.tolist(), nodes.link_conductance_W_K
    (['bottom', 'top'], [[1, 0]], array([0.5]))
    """
    given = tuple(craft.thermal if rules is None else rules)
    joins = tuple(rule for rule in given if isinstance(rule, Conductance))
    rules = tuple(rule for rule in given if not isinstance(rule, Conductance))
    for rule in rules:
        _check_rule(rule, craft.source)
    n_parts = len(craft.part_names)
    # the first rule matching each part (-1: none), parts not sides
    rule_of = np.array(
        [
            next((r for r, rule in enumerate(rules) if part_matches(part, rule.pattern)), -1)
            for part in craft.part_names
        ],
        dtype=np.int64,
    )
    isothermal = np.array([False, *(r.isothermal for r in rules)])[rule_of + 1]
    conductance = np.array([math.inf, *(r.conductance_W_m2K for r in rules)])[rule_of + 1]
    # a rule's heat capacity is of its parts together: each part node takes its share by area
    rule_capacity = np.array([0.0, *(r.heat_capacity_J_K or 0.0 for r in rules)])[rule_of + 1]
    part_area = np.bincount(craft.facet_part, weights=craft.facet_areas, minlength=n_parts)
    ruled = rule_of >= 0
    rule_area = np.bincount(rule_of[ruled], weights=part_area[ruled], minlength=len(rules))
    their_area = np.concatenate([[0.0], rule_area])[rule_of + 1]
    share = np.divide(part_area, their_area, out=np.zeros(n_parts), where=their_area > 0)
    capacity = rule_capacity * share

    facet, sign = craft.side_facet, craft.side_sign
    part = craft.facet_part[facet].astype(np.int64)
    sheet = craft.facet_kind[facet] == TWO_SIDED
    whole = isothermal[part]
    merged = ~whole & sheet & np.isinf(conductance[part])
    n_facets = craft.n_facets
    key = np.where(
        whole, part, np.where(merged, n_parts + facet, n_parts + n_facets + np.arange(craft.n_sides))
    )
    keys, side_node = np.unique(key, return_inverse=True)
    side_node = side_node.astype(np.int64).reshape(-1)
    n_nodes = len(keys)

    # a link per sheet facet of finite positive conductance: its front node to its back node
    coupled = ~whole & sheet & np.isfinite(conductance[part]) & (conductance[part] > 0)
    front = coupled & (sign > 0)
    back_of = np.full(n_facets, -1, dtype=np.int64)
    back_of[facet[coupled & (sign < 0)]] = side_node[coupled & (sign < 0)]
    links = np.column_stack([side_node[front], back_of[facet[front]]]).reshape(-1, 2)
    link_g = conductance[part[front]] * craft.side_areas[front]
    if joins:
        part_node = np.full(n_parts, -1, dtype=np.int64)
        part_node[part[whole]] = side_node[whole]
        # the rules' file: the model's materials file when they are the model's own
        path = craft.materials_source if given == tuple(craft.thermal) else None
        joined = _joined_parts(craft, rules, joins, path)
        links = np.concatenate([links, part_node[joined]])
        link_g = np.concatenate([link_g, [join.conductance_W_K for join in joins]])

    # one representative side per node, for its name and heat capacity
    first = np.zeros(n_nodes, dtype=np.int64)
    first[side_node[::-1]] = np.arange(craft.n_sides)[::-1]
    names = _names(craft, first, whole, merged)
    node_capacity = np.where(whole[first], capacity[part[first]], 0.0)
    area = np.bincount(side_node, weights=craft.side_areas, minlength=n_nodes)
    return ThermalNodes(side_node, names, area, links, link_g, node_capacity)


def _check_rule(rule, source: str) -> None:
    """Refuse a rule whose numbers the node model cannot use."""
    where = f'[thermal."{rule.pattern}"]'
    if not rule.conductance_W_m2K >= 0:
        raise InputError(
            f"{where}: conductance_W_m2K = {rule.conductance_W_m2K} is not a conductance",
            path=source,
            hint="give a number >= 0 [W/(m^2 K)], or inf (front and back at one temperature)",
        )
    capacity = rule.heat_capacity_J_K
    if capacity is not None and not rule.isothermal:
        raise InputError(
            f"{where}: heat_capacity_J_K needs isothermal = true",
            path=source,
            hint="a heat capacity belongs to a part at one temperature: add isothermal = true",
        )
    if capacity is not None and not (capacity >= 0 and math.isfinite(capacity)):
        raise InputError(
            f"{where}: heat_capacity_J_K = {capacity} is not a heat capacity",
            path=source,
            hint="give a finite number >= 0 [J/K]",
        )


def _joined_parts(
    craft: Spacecraft, rules: tuple, joins: tuple[Conductance, ...], path: str | None
) -> NDArray[np.int64]:
    """The two parts (n_joins, 2) each ``[[conductance]]`` joins, both isothermal under ``rules``; every
    problem of every table at once."""
    parts = list(craft.part_names)
    problems = [error for join in joins for error in join.problems(parts, craft.source, path, rules)]
    for join in joins:
        if not (join.conductance_W_K > 0 and math.isfinite(join.conductance_W_K)):
            problems.append(
                MaterialError(
                    f"{join.table}: conductance_W_K = {join.conductance_W_K} is not a conductance",
                    path=path,
                    hint="give a finite number above 0 [W/K]",
                )
            )
    if problems:
        raise combine(problems)
    return np.array([[found[0] for found in join.matched(parts)] for join in joins], dtype=np.int64)


def _names(
    craft: Spacecraft, first: NDArray[np.int64], whole: NDArray[np.bool_], merged: NDArray[np.bool_]
) -> NDArray[np.str_]:
    """Node names from one side of each node (module docstring), built array-wise."""
    facet = craft.side_facet[first]
    part = np.asarray(craft.part_names, dtype=str)[craft.facet_part[facet]]
    facet_name = np.char.add(np.char.add(part, "/facet "), facet.astype(str))
    sheet_side = (craft.facet_kind[facet] == TWO_SIDED) & ~merged[first]
    suffix = np.where(sheet_side, np.where(craft.side_sign[first] > 0, " front", " back"), "")
    return np.where(whole[first], part, np.char.add(facet_name, suffix))
