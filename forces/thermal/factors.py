"""Node-level exchange factors of the spacecraft's own infrared (Gebhart factors), and the node balance
they make: equilibrium and Newton steps on the node temperatures alone (METHOD.md "Planet radiation",
its "Temperatures and thermal recoil" paragraph).

**Factors.** Every side of node ``k`` is at the node's temperature ``T_k``, so the sides emit
``e = sum_k X_k a_k`` with ``X_k = sigma_SB T_k^4`` and ``a_k`` the emitting areas ``eps_i A_i`` of node
``k``'s sides (0 on the others). The infrared balance ``W = e + diag(1 - eps) E^T W``
(:mod:`sunwind.forces.thermal.balance`) is linear in ``e``, so ``W = sum_k X_k W_k`` with ``W_k`` the
balance solved with the source ``a_k``: one solve per node, made once per model. Of them::

    absorbed_m2[l, k] = sum_{i in l} eps_i (E^T W_k)_i          infrared node l absorbs per unit X_k [m^2]
    sums_m2[k]        = (sum_i W_k,i e_esc,i,  sum_i W_k,i (c_i x e_esc,i + m_i),
                         sum_i W_k,i f_esc,i,  sum_i W_k,i (f_blind,i + f_trunc,i))     [m^2, m^3, m^2, m^2]

``absorbed_m2[l, k] / sum_{i in k} eps_i A_i`` is Gebhart's factor ``B_kl``: of the power node ``k``
emits, the share node ``l`` absorbs after all reflections (:attr:`NodeExchange.gebhart`). What node
``k`` emits is absorbed by the nodes, escapes or is lost: the column sums of ``absorbed_m2`` and the
escaped and lost sums add up to ``sum_{i in k} eps_i A_i``. This is exact, not a model of the exchange:
it only uses that the balance is linear and that a node's sides share one temperature (its emission
splits among its sides by ``eps_i A_i``); the factors differ from the side-level solves by the solves'
tolerance.

**Node balance.** With them the balance of node ``k`` (:mod:`sunwind.forces.thermal.model`) is, in the
node unknowns alone::

    F_k(T) = Q_k + sum_l absorbed_m2[k, l] X_l - a_k X_k - (L T)_k - rate_k (T_k - old_k) = 0

``a_k = sum_{i in k} eps_i A_i``: linear in ``X`` without links and heat capacity (one dense solve), else
Newton's method on ``T`` with the dense Jacobian ``(diag(a) - absorbed_m2) diag(4 sigma T^3) + L +
diag(rate)``. No sweep over the sides is made after the factors.

**Cost** (:data:`sunwind.forces.thermal.model.EXCHANGE_NODES` decides when a model uses them): the
solves are made :func:`block_columns` nodes at a time, the sweeps of the diffuse balance over all of
them together; the factors take ``8 n_nodes (2 n_nodes + 8)`` bytes (with :attr:`NodeExchange.net_m2`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.forces.reflection.diffuse import ABSORBED, MOMENT, MOMENTUM, DiffuseTotals
from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN, InfraredBalance
from sunwind.geometry.errors import InputError

#: Bytes of one block of solved columns (each of ``n_sides``) the factors are made from at a time.
BLOCK_BYTES = 32e6
#: Most columns solved together.
MAX_BLOCK = 64
#: Columns of :attr:`NodeExchange.sums_m2`: momentum (3), moment about the origin (3), escaped, lost.
ESCAPED, LOST = 6, 7


@dataclass(frozen=True, eq=False)
class NodeExchange:
    """The spacecraft's own infrared reduced to its nodes (module docstring).

    Attributes
    ----------
    emitting_m2 : (n_nodes,) float64
        ``a_k = sum_{i in k} eps_i A_i`` [m^2].
    absorbed_m2 : (n_nodes, n_nodes) float64
        Infrared node ``l`` (row) absorbs per unit ``sigma T_k^4`` of node ``k`` (column) [m^2].
    sums_m2 : (n_nodes, 8) float64
        Per unit ``sigma T_k^4`` of node ``k``: the escaping momentum rate (3) [m^2] and its moment about
        the origin (3) [m^3], the escaped and the lost power [m^2].

    Examples
    --------
    A box-wing, a node per part: of what a node emits the others absorb a share, the rest escapes (or is
    lost), and the shares add up to what it emits.

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import ReflectionSettings
    >>> from sunwind.forces.thermal import ThermalModel, infrared_exchange
    >>> from sunwind.geometry.materials import ThermalRule
    >>> plates = sw.meshes.box_wing(facet_size=0.5)
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(plates, uniform=grey, two_sided=["wing*"], threads=1).craft
    >>> coarse = ReflectionSettings("full", rays_per_side=64, cache_dir=False)
    >>> rules = (ThermalRule("*", isothermal=True),)
    >>> model = ThermalModel(craft, infrared_exchange(craft, coarse), rules=rules)
    >>> factors = model.node_exchange
    >>> model.nodes.names.tolist(), factors.absorbed_m2.shape
    (['bus', 'wing_left', 'wing_right'], (3, 3))
    >>> total = factors.absorbed_m2.sum(axis=0) + factors.sums_m2[:, 6] + factors.sums_m2[:, 7]
    >>> bool(np.allclose(total, factors.emitting_m2, rtol=1e-12))
    True
    """

    emitting_m2: NDArray[np.float64]
    absorbed_m2: NDArray[np.float64]
    sums_m2: NDArray[np.float64]

    @property
    def gebhart(self) -> NDArray[np.float64]:
        """Gebhart's factors ``B`` (n_nodes, n_nodes): ``B[k, l]``, the share of the power node ``k``
        emits that node ``l`` absorbs after all reflections (0 from a node that does not emit).

        Examples
        --------
        >>> import numpy as np
        >>> factors = NodeExchange(np.array([2.0, 1.0]), np.array([[0.0, 0.5], [0.4, 0.0]]), np.zeros((2, 8)))
        >>> factors.gebhart  # node 0 sends 0.4 / 2 of its emission to node 1, node 1 0.5 / 1 to node 0
        array([[0. , 0.2],
               [0.5, 0. ]])
        """
        area = self.emitting_m2
        return np.divide(self.absorbed_m2, area, out=np.zeros_like(self.absorbed_m2), where=area > 0).T

    @cached_property
    def net_m2(self) -> NDArray[np.float64]:
        """``diag(a) - absorbed_m2`` [m^2]: the net infrared each node loses per unit ``sigma T^4``.

        Examples
        --------
        >>> import numpy as np
        >>> NodeExchange(np.array([2.0, 1.0]), np.array([[0.0, 0.5], [0.4, 0.0]]), np.zeros((2, 8))).net_m2
        array([[ 2. , -0.5],
               [-0.4,  1. ]])
        """
        return np.diag(self.emitting_m2) - self.absorbed_m2

    def totals(
        self, temperature_K: NDArray[np.float64], reference_m: NDArray[np.float64]
    ) -> tuple[DiffuseTotals, float]:
        """What the emitted infrared does once its reflections are done, at node temperatures.

        Parameters
        ----------
        temperature_K : (n_nodes,) float64
            Node temperatures [K].
        reference_m : (3,) float64
            Torque reference point [m].

        Returns
        -------
        totals : DiffuseTotals
            Force and torque of the escaping infrared [N], [N m], and the escaped power [W] (its
            ``absorbed_W``: what the nodes absorb [W]).
        lost_W : float
            Infrared absorbed by no node [W].

        Examples
        --------
        One node of 1 m^2 at 300 K whose infrared all escapes along +z:

        >>> import numpy as np
        >>> sums = np.array([[0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]])
        >>> one = NodeExchange(np.ones(1), np.zeros((1, 1)), sums)
        >>> totals, lost = one.totals(np.array([300.0]), np.zeros(3))
        >>> round(totals.escaped_W, 2), f"{totals.force_N[2]:.3e}", lost
        (459.3, '-1.532e-06', 0.0)
        """
        x = STEFAN_BOLTZMANN * np.asarray(temperature_K, dtype=np.float64) ** 4
        values = self.sums_m2.T @ x
        lost = float(values[LOST])
        values[ABSORBED] = float(self.absorbed_m2.sum(axis=1) @ x)
        return DiffuseTotals.from_sums(values, np.asarray(reference_m, dtype=np.float64)), lost


def block_columns(n_sides: int, n_nodes: int) -> int:
    """Columns solved together when the factors are made: at most :data:`MAX_BLOCK`, and
    ``n_sides`` floats each within :data:`BLOCK_BYTES`.

    Parameters
    ----------
    n_sides, n_nodes : int
        The model's sides and nodes.

    Returns
    -------
    int
        The block size, at least 1.

    Examples
    --------
    >>> block_columns(27188, 10), block_columns(100_000, 256), block_columns(10**8, 256)
    (10, 40, 1)
    """
    return int(max(1, min(n_nodes, MAX_BLOCK, BLOCK_BYTES // (8 * max(n_sides, 1)))))


def node_sums(side_node: NDArray[np.int64], n_nodes: int) -> scipy.sparse.csr_matrix:
    """``P^T`` (n_nodes, n_sides): sums per-side values into their nodes.

    Parameters
    ----------
    side_node : (n_sides,) int64
        Node of each side.
    n_nodes : int
        The number of nodes.

    Returns
    -------
    scipy.sparse.csr_matrix
        Ones at ``(side_node[i], i)``.

    Examples
    --------
    >>> import numpy as np
    >>> node_sums(np.array([0, 1, 0]), 2) @ np.array([1.0, 2.0, 4.0])
    array([5., 2.])
    """
    n_sides = len(side_node)
    return scipy.sparse.csr_matrix(
        (np.ones(n_sides), (side_node, np.arange(n_sides))), shape=(n_nodes, n_sides)
    )


def node_exchange(balance: InfraredBalance, side_node: NDArray[np.int64], n_nodes: int) -> NodeExchange:
    """Make the node-level factors of a model's infrared (module docstring): a solve per node.

    Parameters
    ----------
    balance : InfraredBalance
        The infrared band, with its exchange.
    side_node : (n_sides,) int64
        Node of each side.
    n_nodes : int
        The number of nodes.

    Returns
    -------
    NodeExchange
        The factors.

    Raises
    ------
    InputError
        The band has no exchange (nothing to reduce: every side's emission escapes), or its balance does
        not converge.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import ReflectionSettings
    >>> from sunwind.forces.thermal import InfraredBalance, infrared_exchange
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=grey, two_sided=["wing*"]).craft
    >>> exchange = infrared_exchange(craft, ReflectionSettings("full", rays_per_side=64, cache_dir=False))
    >>> balance = InfraredBalance(craft, np.full(craft.n_sides, 0.8), exchange)
    >>> part = craft.facet_part[craft.side_facet].astype(np.int64)  # a node per part
    >>> factors = node_exchange(balance, part, 3)
    >>> bool(factors.absorbed_m2[0, 1] > 0), bool(factors.absorbed_m2[1, 2] == 0)  # wings see the bus
    (True, True)
    """
    exchange = balance.exchange
    if exchange is None:
        raise InputError(
            "node exchange factors need an infrared exchange",
            hint="without one every side's emission escapes: nothing to reduce",
        )
    n_sides = len(side_node)
    to_nodes = node_sums(side_node, n_nodes)
    factors = exchange.factors
    weights = np.column_stack(
        [
            exchange.functionals[:, MOMENTUM],
            exchange.functionals[:, MOMENT],
            factors.escape_fraction,
            factors.blind_fraction + factors.truncated_fraction,
        ]
    )
    absorbed, sums = np.zeros((n_nodes, n_nodes)), np.zeros((n_nodes, weights.shape[1]))
    block = block_columns(n_sides, n_nodes)
    for lo in range(0, n_nodes, block):
        hi = min(lo + block, n_nodes)
        inside = np.flatnonzero((side_node >= lo) & (side_node < hi))
        source = np.zeros((n_sides, hi - lo))
        source[inside, side_node[inside] - lo] = balance.emitting_area[inside]
        leaving = exchange.solve(source)  # W_k of the block's nodes, the sweeps over all of them together
        absorbed[:, lo:hi] = to_nodes @ (balance.emissivity[:, None] * (balance.arriving @ leaving))
        sums[lo:hi] = leaving.T @ weights
    return NodeExchange(to_nodes @ balance.emitting_area, absorbed, sums)


def solve_linear(
    factors: NodeExchange, groups: NDArray[np.int64], node_absorbed_W: NDArray[np.float64]
) -> NDArray[np.float64]:
    """``sigma T^4`` [W/m^2] of groups of nodes each at one temperature, balancing ``node_absorbed_W``
    without links or heat capacity: ``S (diag(a) - absorbed_m2) S^T X = S Q`` (``S`` sums the nodes of
    each group), a group that cannot emit taking ``X = S Q`` (only as a first guess).

    Parameters
    ----------
    factors : NodeExchange
        The node factors.
    groups : (n_nodes,) int64
        The group of each node, 0 to n_groups - 1; -1: a node left out (at 0 K, sending nothing).
    node_absorbed_W : (n_nodes,) float64
        External power each node absorbs [W].

    Returns
    -------
    (n_groups,) float64
        ``X`` of each group.

    Examples
    --------
    >>> import numpy as np
    >>> factors = NodeExchange(np.array([2.0, 1.0]), np.array([[0.0, 0.5], [0.5, 0.0]]), np.zeros((2, 8)))
    >>> x = solve_linear(factors, np.arange(2), np.array([7.0, 0.0]))
    >>> x, factors.net_m2 @ x  # node 1 warmed by node 0 alone
    (array([4., 2.]), array([7., 0.]))
    """
    kept = np.flatnonzero(groups >= 0)
    n = int(groups.max()) + 1
    summed = scipy.sparse.csr_matrix((np.ones(len(kept)), (groups[kept], kept)), shape=(n, len(groups)))
    net = np.asarray((summed @ np.asarray(summed @ factors.net_m2).T).T)
    area = summed @ factors.emitting_m2
    net[np.diag_indices(n)] += np.where(area > 0, 0.0, 1.0)
    return np.linalg.solve(net, summed @ node_absorbed_W)
