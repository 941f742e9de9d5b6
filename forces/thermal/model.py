"""Node temperatures in equilibrium and in time, and the recoil of the infrared the spacecraft emits
(issue 21; METHOD.md "Inter-reflection" for the diffuse balance the infrared uses).

**Balance of a node.** Given the external power ``Q_i`` [W] each side absorbs (sunlight, albedo,
planet infrared, inter-reflected light: computed by the caller), the temperature ``T_k`` [K] of each node
``k`` (:mod:`sunwind.forces.thermal.nodes`) satisfies::

    C_k dT_k/dt = sum_{i in k} (Q_i + eps_i G_i) + sum_{links k-l} g_kl (T_l - T_k)
                  - sum_{i in k} eps_i A_i sigma_SB T_k^4

with ``G`` the spacecraft's own infrared arriving at each side, its emission
``e_i = eps_i A_i sigma_SB T_i^4`` after all reflections (:mod:`sunwind.forces.thermal.balance`), and
``C_k`` the node's heat capacity [J/K], ``g_kl`` a link's conductance [W/K] (``h A`` of a sheet facet).
This is the dissertation's eq. (1.1), ``d rho c dT/dt = A_S q + eps q_e - eps sigma T^4`` per unit area,
summed over a node, with the infrared the spacecraft sends itself and the conduction of the links
added.

**Equilibrium** (``dT/dt = 0``; :meth:`ThermalModel.equilibrium`). Without conduction links (no sheet
of finite ``h > 0``, no ``[[conductance]]``) the balance is linear in ``X_k = sigma_SB T_k^4``::

    (sum_{i in k} eps_i A_i) X_k - sum_{i in k} eps_i G_i(X) = sum_{i in k} Q_i

and is solved as one linear system with the infrared balance (its residual at round-off). With links it
is solved by Newton's method on ``T``, the infrared balance inside each step (the joined system of
:func:`~sunwind.forces.thermal.balance.solve_joined`, the node Jacobian ``diag(4 sigma T^3 sum eps A)
+ L`` sparse), starting from the linear solution with every linked group of nodes at one temperature,
until the node residuals beyond each node's rounding (:data:`ROUNDING` of its terms, the stored heat's
``rate T`` and ``rate T_old`` among them) and the infrared residuals sum to at most
:data:`NEWTON_TOLERANCE` of the power through the model, or the temperatures no longer move (without an
exchange no infrared comes back, and a Newton step is the node system alone: dense up to
:data:`DENSE_NODES` nodes). A step takes the slope ``4 sigma T^3`` at the node's temperature (at
:data:`SLOPE_FLOOR_K` at least) and moves no temperature by more than a factor :data:`STEP_FACTOR`. A
group of linked nodes none of whose sides emits (``eps = 0``) has no equilibrium: an error. A node
without heat capacity that no power reaches (no external power, and no infrared or conduction from a
node that has any, directly or through others: a facet facing the sky in eclipse) is at 0 K: set so,
not approached by Newton's steps (which near 0 K only take off a quarter of the temperature each).

**Node-level exchange** (:attr:`ThermalModel.node_exchange`, :mod:`sunwind.forces.thermal.factors`).
With an exchange and at most :data:`EXCHANGE_NODES` nodes the infrared exchange is reduced once per
model to node-level factors (Gebhart's: a solve of the diffuse balance per node), and the linear
solution and every Newton step are dense systems of the node temperatures alone, with no sweep over
the sides: exact, since a node's sides share one temperature (its emission splits among them by
``eps_i A_i``), and equal to the side-level solution to the solves' tolerance. Above
:data:`EXCHANGE_NODES` the side-level joined systems above are solved. :meth:`ThermalModel.state_at`
solves the side-level balance once in both (per-side infrared, recoil).

**Transient.** Nodes without heat capacity (all but isothermal parts given ``heat_capacity_J_K``) are
in equilibrium at every instant (with the others, a DAE of index 1). :meth:`ThermalModel.step` is one
backward-Euler step over ``dt``: ``C_k (T_k - T_k,old) / dt`` on the left, everything else at the new
temperatures, solved by the same Newton iteration (from the old temperatures); unconditionally stable,
first order in ``dt``, no error control. :func:`sunwind.forces.thermal.transient.integrate` follows a
series of times with Alexander's two-stage SDIRK (order 2, L-stable, stiffly accurate), each stage the
same backward-Euler balance with ``rate = C / (gamma h)`` and a shifted ``old``; sub-steps halved by step
doubling until the estimated local error is within a tolerance, the estimate carried along as a global
error; the external power interpolated linearly between the times, sunlight optionally scaled by the
share of the Sun in view at each stage's own time (eclipse edges resolved inside a step). Assumed:
lumped nodes (a part is isothermal or each facet side its own node; no conduction but the links), the
spacecraft's own infrared exchanged instantly. Details in that module.

**Links** join two nodes by a conductance [W/K]: the front and back of a sheet facet of finite
``conductance_W_m2K``, and two isothermal parts named by a materials file's ``[[conductance]]`` table
(:mod:`sunwind.forces.thermal.nodes`); all enter the node Laplacian ``L``.

**Recoil.** The emitted infrared pushes the spacecraft as diffuse light does: once all its reflections
are done, the infrared that escapes carries away momentum ``W_i e_esc,i / c`` (the diffuse balance's
escape vectors), so ``F = -(1/c) sum W_i e_esc,i`` and the torque about ``r_ref``
``-(1/c) sum W_i [(c_i - r_ref) x e_esc,i + m_i]``, with ``W`` the infrared leaving the sides; for a side
that sees only sky this is ``-(2/3) e_i n_i / c``. Without an exchange every side's emission is taken
to escape from an open side: ``F = -(2/3)/c sum e_i n_i``, torque ``sum (c_i - r_ref) x F_i``. The
infrared absorbed on the spacecraft, and its reflections, cancel in pairs (METHOD.md
"Inter-reflection", eq. 9).

**Power balance.** Every state reports ``absorbed = escaped + lost + stored`` [W] (lost: infrared that
reaches sides the model does not have, or is dropped by a truncated exchange chain) and the relative
``imbalance``, round-off in equilibrium.
"""

from __future__ import annotations

import hashlib
from functools import cached_property

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph
import scipy.sparse.linalg
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.forces.reflection.views import model_view_factors
from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN, InfraredBalance, solve_joined
from sunwind.forces.thermal.factors import NodeExchange, node_exchange, node_sums, solve_linear
from sunwind.forces.thermal.nodes import ThermalNodes, thermal_nodes
from sunwind.forces.thermal.state import ThermalState
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import Spacecraft, infrared_optics

#: Newton ends when the node and infrared residuals sum to this share of the power through the model.
NEWTON_TOLERANCE = 1e-13
#: A node's residual within this many ulps of its terms is rounding (not counted against the tolerance).
ROUNDING = 8 * np.finfo(float).eps
#: Most Newton steps before the iteration is an error.
NEWTON_STEPS = 100
#: Below this temperature [K] Newton takes the slope ``4 sigma T^3`` at it (a node at 0 K has none).
SLOPE_FLOOR_K = 1e-3
#: A Newton step divides a node's temperature by at most this, and multiplies it (or 1 K) by at most
#: this: from above the root, Newton on ``sigma T^4`` never passes it; from far below it would jump far
#: above (and come back by a quarter a step).
STEP_FACTOR = 10.0
#: Up to this many nodes, a Newton step without an infrared exchange is solved as a dense system.
DENSE_NODES = 64
#: Up to this many nodes a model with an infrared exchange reduces it to node-level factors
#: (:mod:`sunwind.forces.thermal.factors`). The rule: the reduction costs ``n_nodes`` solves of the
#: diffuse balance once, swept together (about what a few side-level Newton steps cost, each a joined
#: solve), and keeps ``8 n_nodes^2`` bytes (0.5 MB); a Newton step is then an LU of ``n_nodes^2``
#: doubles (``n^3 / 3`` = 6 Mflop, about a millisecond, at 256) instead of sweeps over every side. A
#: transient takes tens of Newton steps per output step, so past a few steps the reduction has paid
#: for itself; beyond 256 nodes the dense LU would cost what the sweeps cost.
EXCHANGE_NODES = 256


def infrared_exchange(
    craft: Spacecraft, reflections: str | ReflectionSettings = "full"
) -> DiffuseExchange | None:
    """The infrared :class:`DiffuseExchange` of a model, or None when no infrared is exchanged.

    The view factors of ``reflections`` with the infrared optics ``(1 - eps, 0, 0)``. Any mode but
    ``"none"`` gives the full diffuse balance (there are no mirrors in the infrared). Kept in the
    model's cache.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft; every side's material needs an emissivity.
    reflections : str or ReflectionSettings, default "full"
        The inter-reflection settings whose view factors are used; ``"none"``: no exchange.

    Returns
    -------
    DiffuseExchange or None
        The infrared balance; None for ``reflections="none"`` (every side's emission escapes).

    Raises
    ------
    MaterialError
        A side's material has no emissivity.
    InputError
        Reflection settings out of range.

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> infrared_exchange(craft, "none") is None
    True
    """
    settings = ReflectionSettings.of(reflections)
    if settings.mode == "none":
        return None
    return craft.cache.get(
        ("infrared exchange", *settings.view_key),
        lambda: DiffuseExchange(
            craft,
            model_view_factors(craft, settings),
            optics=infrared_optics(craft),
            cache_dir=settings.cache_dir,
        ),
    )


class ThermalModel:
    """Node temperatures and thermal recoil of one model (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        Every side's material needs an emissivity.
    exchange : DiffuseExchange or None
        The infrared balance, made with ``optics=infrared_optics(craft)`` (:func:`infrared_exchange`);
        None: every side's emission escapes (no reflections, or a convex body).
    rules : tuple of ThermalRule, optional
        Node rules (:func:`~sunwind.forces.thermal.nodes.thermal_nodes`); default ``craft.thermal``.
    node_level : bool, optional
        Whether the infrared exchange is reduced to node-level factors (:attr:`node_exchange`): default
        when the model has at most :data:`EXCHANGE_NODES` nodes; True or False to choose (without an
        exchange there is nothing to reduce: ignored).

    Attributes
    ----------
    nodes : ThermalNodes
        The nodes and their links.
    infrared : InfraredBalance
        The infrared band.
    node_emitting_area_m2 : (n_nodes,) float64
        ``sum_{i in k} eps_i A_i`` of each node [m^2].

    Raises
    ------
    MaterialError
        A side's material has no emissivity.
    InputError
        ``exchange`` is not made with the infrared optics; a bad rule; too little memory.

    Examples
    --------
    A grey cube at one temperature with the Sun overhead absorbs 952.7 W and, in equilibrium, emits it
    all from ``0.8 * 6 m^2``: ``T = (952.7 / (4.8 sigma))^(1/4)``.

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.geometry.materials import ThermalRule
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> one_node = (ThermalRule("*", isothermal=True, heat_capacity_J_K=900.0),)
    >>> thermal = ThermalModel(craft, None, rules=one_node)
    >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
    >>> state = thermal.equilibrium(sunlit)
    >>> state.node_names.tolist(), state.node_temperature_K.round(2)
    (['box'], array([243.23]))
    """

    def __init__(
        self,
        craft: Spacecraft,
        exchange: DiffuseExchange | None = None,
        *,
        rules: tuple | None = None,
        node_level: bool | None = None,
    ) -> None:
        emissivity = 1.0 - infrared_optics(craft)[:, 0]
        self.craft = craft
        self.nodes: ThermalNodes = thermal_nodes(craft, rules)
        self.infrared = InfraredBalance(craft, emissivity, exchange)
        #: ``sum_{i in k} eps_i A_i`` of each node [m^2]
        self.node_emitting_area_m2 = self.nodes.sum_sides(self.infrared.emitting_area)
        chosen = self.nodes.n_nodes <= EXCHANGE_NODES if node_level is None else bool(node_level)
        self._node_level = exchange is not None and chosen
        self._kept: dict[str, NodeExchange] = {}  # the node factors, once looked up

    @property
    def node_exchange(self) -> NodeExchange | None:
        """The node-level exchange factors the model solves with, made on first use (None: the
        side-level path, or no exchange).

        Kept in the model's cache beside the infrared exchange they reduce (a solve of its balance per
        node, :func:`~sunwind.forces.thermal.factors.node_exchange`).

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.reflection import ReflectionSettings
        >>> from sunwind.geometry.materials import ThermalRule
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box_wing(facet_size=0.5), uniform=grey, two_sided=["wing*"]).craft
        >>> exchange = infrared_exchange(craft, ReflectionSettings("full", rays_per_side=64, cache_dir=False))
        >>> parts = (ThermalRule("*", isothermal=True),)
        >>> ThermalModel(craft, exchange, rules=parts).node_exchange.gebhart.shape  # three part nodes
        (3, 3)
        >>> ThermalModel(craft, exchange, rules=parts, node_level=False).node_exchange is None
        True
        """
        if not self._node_level:
            return None
        if "factors" not in self._kept:  # looked up (or made) once, then held here too
            named = self._exchange_key()
            nodes = self.nodes
            build = lambda: node_exchange(self.infrared, nodes.side_node, nodes.n_nodes)  # noqa: E731
            if named is None:  # an exchange made apart: kept with this model alone
                self._kept["factors"] = build()
            else:
                digest = hashlib.sha256(nodes.side_node.tobytes()).hexdigest()[:16]
                key = ("thermal node exchange", *named[1:], digest)
                self._kept["factors"] = self.craft.cache.get(key, build)
        return self._kept["factors"]

    def _exchange_key(self) -> tuple | None:
        """The key the model's cache keeps its infrared exchange under (None: not there)."""
        cache, exchange = self.craft.cache, self.infrared.exchange
        for key in cache:
            if isinstance(key, tuple) and key[:1] == ("infrared exchange",):
                if cache.get(key, lambda: None) is exchange:
                    return key
        return None

    @property
    def exchange(self) -> DiffuseExchange | None:
        """The infrared exchange the model was made with (None: every side's emission escapes).

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.geometry.materials import ThermalRule
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> one_node = (ThermalRule("*", isothermal=True, heat_capacity_J_K=900.0),)
        >>> thermal = ThermalModel(craft, None, rules=one_node)
        >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
        >>> thermal.exchange is None
        True
        """
        return self.infrared.exchange

    def equilibrium(
        self, absorbed_W: NDArray[np.float64], reference_m: NDArray[np.float64] | None = None
    ) -> ThermalState:
        """The steady state under a given external power absorbed by each side.

        Parameters
        ----------
        absorbed_W : (n_sides,) float64
            External power each side absorbs [W], finite and >= 0.
        reference_m : (3,) float64, optional
            Torque reference point [m]; default the model's reference point.

        Returns
        -------
        ThermalState
            Temperatures, the infrared exchanged and its recoil, with ``stored_W`` 0.

        Raises
        ------
        InputError
            ``absorbed_W`` is not (n_sides,) finite and >= 0; a group of nodes that cannot emit; Newton's
            method did not converge.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.geometry.materials import ThermalRule
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> one_node = (ThermalRule("*", isothermal=True, heat_capacity_J_K=900.0),)
        >>> thermal = ThermalModel(craft, None, rules=one_node)
        >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
        >>> state = thermal.equilibrium(sunlit)
        >>> round(state.escaped_W, 6), abs(state.imbalance) < 1e-12
        (952.7, True)
        """
        q = self._absorbed(absorbed_W)
        rate = np.zeros(self.nodes.n_nodes)
        self._check_emitters(rate)
        return self.state_at(self._temperatures(q, rate, None), q, reference_m)

    def step(
        self,
        state: ThermalState,
        absorbed_W: NDArray[np.float64],
        dt_s: float,
        reference_m: NDArray[np.float64] | None = None,
    ) -> ThermalState:
        """The state one backward-Euler step of ``dt_s`` after ``state``.

        Nodes without heat capacity are in equilibrium at the new time.

        Parameters
        ----------
        state : ThermalState
            The state at the start of the step, of this model's nodes.
        absorbed_W : (n_sides,) float64
            External power each side absorbs over the step [W].
        dt_s : float
            Time step [s], > 0.
        reference_m : (3,) float64, optional
            Torque reference point [m]; default the model's reference point.

        Returns
        -------
        ThermalState
            The state at the end of the step; ``stored_W`` is the heat the nodes took up, per second.

        Raises
        ------
        InputError
            ``dt_s`` not finite and > 0; ``state`` of another model; bad ``absorbed_W``; a group of nodes
            that can neither emit nor store heat; Newton's method did not converge.

        Examples
        --------
        A cold cube of 900 J/K in sunlight warms toward its 243 K equilibrium:

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.geometry.materials import ThermalRule
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> one_node = (ThermalRule("*", isothermal=True, heat_capacity_J_K=900.0),)
        >>> thermal = ThermalModel(craft, None, rules=one_node)
        >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
        >>> start = thermal.state_at(np.array([200.0]), sunlit)
        >>> later = thermal.step(start, sunlit, 60.0)
        >>> later.node_temperature_K.round(2), later.stored_W > 0
        (array([220.57]), True)
        """
        if not (np.isfinite(dt_s) and dt_s > 0):
            raise InputError(
                f"dt_s = {dt_s} is not a time step", hint="give seconds > 0", parameters=("dt_s",)
            )
        old = self._node_temperatures(state.node_temperature_K)
        q = self._absorbed(absorbed_W)
        rate = self.nodes.heat_capacity_J_K / dt_s
        self._check_emitters(rate)
        new = self._temperatures(q, rate, old)
        return self.state_at(new, q, reference_m, float(rate @ (new - old)))

    def state_at(
        self,
        node_temperature_K: NDArray[np.float64],
        absorbed_W: NDArray[np.float64],
        reference_m: NDArray[np.float64] | None = None,
        stored_W: float = 0.0,
    ) -> ThermalState:
        """The state at given node temperatures, balanced or not.

        The emission, its infrared exchange and recoil, and the power balance with ``absorbed_W`` and
        ``stored_W`` (the ``imbalance`` says how far the temperatures are from a balance). A start for
        :meth:`step`.

        Parameters
        ----------
        node_temperature_K : (n_nodes,) float64
            Temperature of each node [K], finite and >= 0.
        absorbed_W : (n_sides,) float64
            External power each side absorbs [W].
        reference_m : (3,) float64, optional
            Torque reference point [m]; default the model's reference point.
        stored_W : float, default 0.0
            Heat the nodes take up [W].

        Returns
        -------
        ThermalState
            The state.

        Raises
        ------
        InputError
            Node temperatures or ``absorbed_W`` of the wrong shape, not finite or negative.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.geometry.materials import ThermalRule
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> one_node = (ThermalRule("*", isothermal=True, heat_capacity_J_K=900.0),)
        >>> thermal = ThermalModel(craft, None, rules=one_node)
        >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
        >>> state = thermal.state_at(np.array([300.0]), sunlit)
        >>> round(state.emitted_W_total, 1), bool(state.imbalance < 0)  # too hot: it emits more
        (2204.6, True)
        """
        temperature = self._node_temperatures(node_temperature_K)
        q = self._absorbed(absorbed_W)
        craft, infrared = self.craft, self.infrared
        reference = np.asarray(
            craft.default_reference[0] if reference_m is None else reference_m, dtype=np.float64
        )
        side_temperature = self.nodes.gather(temperature)
        emitted = infrared.emitting_area * STEFAN_BOLTZMANN * side_temperature**4
        leaving = infrared.leaving(emitted)
        absorbed_infrared = infrared.emissivity * infrared.arrival(leaving)
        if infrared.exchange is None:
            push = -(LAMBERT_FACTOR / SPEED_OF_LIGHT) * emitted[:, None] * craft.side_normals
            force = push.sum(axis=0)
            torque = np.cross(craft.side_centroids - reference, push).sum(axis=0)
            escaped, lost = float(emitted.sum()), 0.0
        else:
            totals = infrared.exchange.totals_of(leaving, reference)
            force, torque, escaped = totals.force_N, totals.torque_Nm, totals.escaped_W
            factors = infrared.exchange.factors
            lost = float(leaving @ (factors.blind_fraction + factors.truncated_fraction))
        total = float(q.sum())
        scale = max(total, escaped + lost, np.finfo(float).tiny)
        return ThermalState(
            temperature_K=side_temperature,
            node_temperature_K=temperature,
            node_names=self.nodes.names,
            emitted_W=emitted,
            absorbed_infrared_W=absorbed_infrared,
            force_N=np.asarray(force, dtype=np.float64),
            torque_Nm=np.asarray(torque, dtype=np.float64),
            reference_point_m=reference,
            absorbed_W=total,
            emitted_W_total=float(emitted.sum()),
            escaped_W=escaped,
            lost_W=lost,
            stored_W=float(stored_W),
            imbalance=(total - escaped - lost - stored_W) / scale,
        )

    # --- solving -------------------------------------------------------------------------------------
    def _temperatures(
        self,
        absorbed: NDArray[np.float64],
        rate: NDArray[np.float64],
        old: NDArray[np.float64] | None,
        guess: NDArray[np.float64] | None = None,
    ) -> NDArray[np.float64]:
        """Node temperatures [K] balancing ``absorbed`` [W] per side, with ``rate = C / dt`` [W/K] per
        node pulling toward ``old`` [K] (None: equilibrium, ``rate`` 0); Newton starts from ``guess``
        (default ``old``). Nodes no power reaches are set to 0 K."""
        nodes, factors = self.nodes, self.node_exchange
        node_absorbed = nodes.sum_sides(absorbed)
        dead = self._unreached(node_absorbed, rate)
        if len(nodes.links) == 0 and not np.any(rate):
            if factors is None:
                return self._linear(np.arange(nodes.n_nodes), absorbed)
            if np.all(dead):
                return np.zeros(nodes.n_nodes)
            live = np.where(dead, -1, np.cumsum(~dead) - 1)  # dead nodes left out, at 0 K
            return np.where(dead, 0.0, self._linear(live, absorbed)[np.maximum(live, 0)])
        start = old if guess is None else guess
        if start is None:
            start = self._grouped_guess(absorbed)
        else:
            start = start.copy()
            cold = (start <= 0) & ~dead
            if np.any(cold):
                start[cold] = self._grouped_guess(absorbed)[cold]
        start[dead] = 0.0
        old = np.zeros(nodes.n_nodes) if old is None else old
        if factors is not None:
            return self._node_newton(factors, node_absorbed, rate, old, (start, ~dead))
        return self._newton(absorbed, rate, old, start)

    def _sensitivity(
        self, temperature: NDArray[np.float64], rate: NDArray[np.float64], change: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """How the solution of a step moves, to first order, when its ``old`` temperatures move by
        ``change`` [K]: ``J^-1 (rate * change)`` with ``J`` Newton's Jacobian at ``temperature`` [K]."""
        nodes = self.nodes
        if not np.any(rate):
            return np.zeros(nodes.n_nodes)
        slope = 4.0 * STEFAN_BOLTZMANN * np.maximum(temperature, SLOPE_FLOOR_K) ** 3
        factors = self.node_exchange
        if factors is not None:  # nodes at 0 K without heat capacity (none reaches them) stay there
            index = np.flatnonzero((temperature > 0) | (rate > 0))
            pick = np.ix_(index, index)
            jacobian = factors.net_m2[pick] * slope[index] + self._dense_laplacian[pick]
            moved = np.zeros(nodes.n_nodes)
            moved[index] = np.linalg.solve(jacobian + np.diag(rate[index]), (rate * change)[index])
            return moved
        _, moved = self._solve_linearised(slope, rate, rate * change, np.zeros(self.craft.n_sides))
        return moved

    def _solve_linearised(
        self,
        slope: NDArray[np.float64],
        rate: NDArray[np.float64],
        node_rhs: NDArray[np.float64],
        side_source: NDArray[np.float64],
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """:func:`solve_joined` with ``H = diag(eps A slope + rate) + L`` and ``b = slope`` (a Newton step).
        Without an exchange no infrared comes back: the node system alone, ``H`` built on a kept pattern."""
        nodes, infrared = self.nodes, self.infrared
        diagonal = self.node_emitting_area_m2 * slope + rate
        if infrared.arriving is not None:
            jacobian = scipy.sparse.diags(diagonal) + nodes.laplacian
            return solve_joined(infrared, nodes.side_node, jacobian, slope, node_rhs, side_source)
        if len(nodes.links) == 0:
            change = node_rhs / diagonal
        elif nodes.n_nodes <= DENSE_NODES:
            change = np.linalg.solve(self._dense_laplacian + np.diag(diagonal), node_rhs)
        else:
            indices, indptr, conduction, on_diagonal = self._conduction_pattern
            data = conduction.copy()
            data[on_diagonal] += diagonal
            matrix = scipy.sparse.csc_matrix((data, indices, indptr), shape=(nodes.n_nodes,) * 2)
            change = scipy.sparse.linalg.spsolve(matrix, node_rhs)
        side = nodes.side_node
        return side_source + infrared.emitting_area * slope[side] * change[side], change

    @cached_property
    def _dense_laplacian(self) -> NDArray[np.float64]:
        """``L`` as a dense array (for models of at most :data:`DENSE_NODES` nodes, or
        :data:`EXCHANGE_NODES` with node factors)."""
        return self.nodes.laplacian.toarray()

    @cached_property
    def _conduction_pattern(self) -> tuple[NDArray, NDArray, NDArray[np.float64], NDArray[np.int64]]:
        """``L`` in CSC form with every diagonal entry stored: indices, pointers, values, and where the
        diagonal entries are among the values."""
        n = self.nodes.n_nodes
        pattern = (self.nodes.laplacian + scipy.sparse.identity(n)).tocsc()
        pattern.sort_indices()
        columns = np.repeat(np.arange(n), np.diff(pattern.indptr))
        on_diagonal = np.flatnonzero(pattern.indices == columns)
        conduction = np.asarray(self.nodes.laplacian.tocsr()[pattern.indices, columns]).reshape(-1)
        return pattern.indices, pattern.indptr, conduction, on_diagonal

    def _linear(self, groups: NDArray[np.int64], absorbed: NDArray[np.float64]) -> NDArray[np.float64]:
        """Equilibrium temperatures [K] of groups of nodes (``groups``: each node's, -1 for one left
        out at 0 K) each at one temperature, without links: linear in ``sigma T^4``."""
        factors = self.node_exchange
        if factors is not None:
            x = solve_linear(factors, groups, self.nodes.sum_sides(absorbed))
            return (np.maximum(x, 0.0) / STEFAN_BOLTZMANN) ** 0.25
        side_node = groups[self.nodes.side_node]
        n = int(side_node.max()) + 1
        area = np.bincount(side_node, weights=self.infrared.emitting_area, minlength=n)
        area = np.where(area > 0, area, 1.0)  # a node that cannot emit (only as a first guess)
        _, x = solve_joined(
            self.infrared,
            side_node,
            scipy.sparse.diags(area),
            np.ones(n),
            np.bincount(side_node, weights=absorbed, minlength=n),
            np.zeros(len(side_node)),
        )
        return (np.maximum(x, 0.0) / STEFAN_BOLTZMANN) ** 0.25

    def _grouped_guess(self, absorbed: NDArray[np.float64]) -> NDArray[np.float64]:
        """Equilibrium temperatures [K] with every group of linked nodes at one temperature."""
        groups = self.nodes.components
        return self._linear(groups, absorbed)[groups]

    def _newton(
        self,
        absorbed: NDArray[np.float64],
        rate: NDArray[np.float64],
        old: NDArray[np.float64],
        guess: NDArray[np.float64],
    ) -> NDArray[np.float64]:
        """Newton's method on the node temperatures and the infrared leaving the sides together."""
        nodes, infrared = self.nodes, self.infrared
        eps, emitting = infrared.emissivity, infrared.emitting_area
        area, laplacian = self.node_emitting_area_m2, nodes.laplacian
        node_absorbed = nodes.sum_sides(absorbed)
        temperature = guess.copy()
        leaving = infrared.leaving(emitting * nodes.gather(STEFAN_BOLTZMANN * temperature**4))
        for _ in range(NEWTON_STEPS):
            x = STEFAN_BOLTZMANN * temperature**4
            arriving = infrared.arrival(leaving)
            infrared_residual = leaving - (1.0 - eps) * arriving - emitting * nodes.gather(x)
            stored = rate * (temperature - old)
            node_residual = (
                node_absorbed + nodes.sum_sides(eps * arriving) - laplacian @ temperature - area * x - stored
            )
            flows = (node_absorbed, area * x, stored, rate * (temperature + old))
            if self._converged(node_residual, np.abs(infrared_residual).sum(), flows, temperature):
                return temperature
            slope = 4.0 * STEFAN_BOLTZMANN * np.maximum(temperature, SLOPE_FLOOR_K) ** 3
            d_leaving, d_temperature = self._solve_linearised(slope, rate, node_residual, -infrared_residual)
            updated = _bounded(temperature, d_temperature)
            leaving = leaving + d_leaving
            if np.all(np.abs(updated - temperature) <= 4 * np.finfo(float).eps * temperature):
                return updated  # settled to round-off
            temperature = updated
        raise self._unconverged()

    def _node_newton(
        self,
        factors: NodeExchange,
        node_absorbed: NDArray[np.float64],
        rate: NDArray[np.float64],
        old: NDArray[np.float64],
        start: tuple[NDArray[np.float64], NDArray[np.bool_]],
    ) -> NDArray[np.float64]:
        """Newton's method on the node temperatures alone, the infrared by the node factors: ``start``
        is the first guess [K] and the nodes solved for (the others stay as guessed, at 0 K)."""
        guess, live = start
        index = np.flatnonzero(live)
        pick = np.ix_(index, index)
        net, conduction = factors.net_m2[pick], self._dense_laplacian[pick]
        area = factors.emitting_m2[index]
        q, r, before = node_absorbed[index], rate[index], old[index]
        temperature = guess[index].copy()
        for _ in range(NEWTON_STEPS):
            x = STEFAN_BOLTZMANN * temperature**4
            stored = r * (temperature - before)
            residual = q - net @ x - conduction @ temperature - stored
            flows = (q, area * x, stored, r * (temperature + before))
            if self._converged(residual, 0.0, flows, temperature, index):
                break
            slope = 4.0 * STEFAN_BOLTZMANN * np.maximum(temperature, SLOPE_FLOOR_K) ** 3
            change = np.linalg.solve(net * slope + conduction + np.diag(r), residual)
            updated = _bounded(temperature, change)
            settled = np.all(np.abs(updated - temperature) <= 4 * np.finfo(float).eps * temperature)
            temperature = updated
            if settled:
                break
        else:
            raise self._unconverged()
        result = guess.copy()
        result[index] = temperature
        return result

    def _converged(
        self,
        residual: NDArray[np.float64],
        infrared_W: float,
        flows: tuple[NDArray[np.float64], ...],
        temperature: NDArray[np.float64],
        index: NDArray[np.int64] | slice = slice(None),
    ) -> bool:
        """Whether Newton is done: the node residuals ``residual`` [W] of the nodes ``index`` beyond their
        rounding, and the infrared residuals ``infrared_W`` [W], sum to at most :data:`NEWTON_TOLERANCE`
        of the power through them. ``flows``: each node's absorbed, emitted and stored power and its
        stored heat's terms ``rate (T + T_old)`` [W]; a node's rounding is a few ulps of its terms, the
        stored heat's included (``rate T - rate T_old`` is rounded at the size of either)."""
        absorbed, emitted, stored, storing = flows
        conducted = self._conduction_weights[index] * temperature
        terms = np.abs(absorbed) + emitted + conducted + storing
        beyond = np.maximum(np.abs(residual) - ROUNDING * terms, 0.0).sum()
        through = np.abs(absorbed).sum() + emitted.sum() + np.abs(stored).sum()
        return bool(beyond + infrared_W <= NEWTON_TOLERANCE * through)

    @cached_property
    def _conduction_weights(self) -> NDArray[np.float64]:
        """``sum_j |L_kj|`` of each node ``k`` [W/K]: times ``T_k``, about the size of its conduction
        terms."""
        return np.asarray(abs(self.nodes.laplacian).sum(axis=1)).reshape(-1)

    def _unreached(self, node_absorbed: NDArray[np.float64], rate: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Nodes no power reaches, at 0 K (n_nodes,) bool: without heat capacity or external power, and
        no node that has either sends them infrared or conduction, directly or through others."""
        quiet = (rate == 0) & (node_absorbed == 0)
        n, sends = len(quiet), self._sends
        if not np.any(quiet) or sends.nnz == 0:
            return quiet
        sources = np.flatnonzero(~quiet)
        start = scipy.sparse.csr_matrix(
            (np.ones(len(sources)), (np.full(len(sources), n), sources)), shape=(n + 1, n + 1)
        )
        graph = scipy.sparse.block_diag((sends, scipy.sparse.csr_matrix((1, 1))), format="csr") + start
        reached = scipy.sparse.csgraph.breadth_first_order(graph, n, directed=True, return_predecessors=False)
        quiet[reached[reached < n]] = False
        return quiet

    @cached_property
    def _sends(self) -> scipy.sparse.csr_matrix:
        """Which node can send heat to which, (n_nodes, n_nodes) sparse, ``[k, l]`` nonzero when ``k``
        sends to ``l``: a link either way, or infrared (node factors, else any view factor between
        their sides, which over-counts: nodes are only taken as unreached when they are)."""
        nodes, n = self.nodes, self.nodes.n_nodes
        sends = (nodes.laplacian != 0).astype(np.float64)  # the links, both ways (and the diagonal)
        if self.infrared.exchange is None:
            return sends
        factors = self.node_exchange
        if factors is not None:
            return (sends + scipy.sparse.csr_matrix(factors.absorbed_m2.T != 0)).tocsr()
        to_nodes = node_sums(nodes.side_node, n)
        seen = abs(self.infrared.exchange.factors.matrix)
        return (sends + to_nodes @ seen @ to_nodes.T).tocsr()

    def _unconverged(self) -> InputError:
        return InputError(
            f"the node temperatures did not converge in {NEWTON_STEPS} Newton steps",
            path=self.craft.source,
            hint="check the conductances and heat capacities of the [thermal] rules for extreme values",
        )

    # --- checks --------------------------------------------------------------------------------------
    def _check_emitters(self, rate: NDArray[np.float64]) -> None:
        """Refuse groups of linked nodes that neither emit (``eps = 0`` on every side) nor store heat."""
        nodes = self.nodes
        groups = nodes.components
        able = np.bincount(groups, weights=self.node_emitting_area_m2 + rate)
        stuck = np.flatnonzero(able[groups] <= 0)
        if len(stuck):
            listed = ", ".join(f"'{name}'" for name in nodes.names[stuck[:5]].tolist())
            more = f" and {len(stuck) - 5} more" if len(stuck) > 5 else ""
            raise InputError(
                f"node {listed}{more} has emissivity 0 on every side and no conduction to a node that "
                "emits: it has no thermal equilibrium",
                path=self.craft.source,
                hint="give its material an emissivity above 0, or join it to an emitting node "
                "(conductance_W_m2K > 0, isothermal = true)",
            )

    def _absorbed(self, absorbed_W: NDArray[np.float64]) -> NDArray[np.float64]:
        q = np.asarray(absorbed_W, dtype=np.float64)
        if q.shape != (self.craft.n_sides,) or not np.all(np.isfinite(q)) or np.any(q < 0):
            raise InputError(
                f"absorbed_W must be {self.craft.n_sides} finite powers >= 0 [W], one per side",
                hint=f"got shape {q.shape}",
                parameters=("absorbed_W",),
            )
        return q

    def _node_temperatures(self, temperature_K: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.array(temperature_K, dtype=np.float64)
        if t.shape != (self.nodes.n_nodes,) or not np.all(np.isfinite(t)) or np.any(t < 0):
            raise InputError(
                f"node temperatures must be {self.nodes.n_nodes} finite temperatures >= 0 [K], one per node",
                hint=f"got shape {t.shape}; a state of this model's nodes",
                parameters=("node_temperature_K",),
            )
        return t


def _bounded(temperature: NDArray[np.float64], change: NDArray[np.float64]) -> NDArray[np.float64]:
    """``temperature + change`` [K] kept within :data:`STEP_FACTOR` of ``temperature`` (of 1 K when
    rising): positive, and no jump from a cold guess far above the root."""
    ceiling = STEP_FACTOR * np.maximum(temperature, 1.0)
    return np.clip(temperature + change, temperature / STEP_FACTOR, ceiling)


def thermal_model(craft: Spacecraft, reflections: str | ReflectionSettings = "full") -> ThermalModel:
    """The :class:`ThermalModel` of a model, with its materials file's node rules; cached.

    The node rules are ``craft.thermal`` and the infrared balance is that of ``reflections``
    (:func:`infrared_exchange`). The model is kept in the spacecraft's cache.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft; every side's material needs an emissivity.
    reflections : str or ReflectionSettings, default "full"
        The inter-reflection settings of the infrared exchange; ``"none"``: no exchange.

    Returns
    -------
    ThermalModel
        The thermal model (the same object on a second call with the same settings).

    Raises
    ------
    MaterialError
        A side's material has no emissivity.
    InputError
        Reflection settings out of range, or a bad ``[thermal]`` rule.

    Examples
    --------
    Without rules each side is its own node; with the Sun overhead only the top two are warm:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> thermal = thermal_model(craft, "none")
    >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
    >>> thermal.equilibrium(sunlit).temperature_K.round(1)
    array([  0. ,   0. ,   0. ,   0. ,   0. ,   0. ,   0. ,   0. ,   0. ,   0. , 380.7, 380.7])
    >>> thermal_model(craft, "none") is thermal
    True
    """
    settings = ReflectionSettings.of(reflections)
    return craft.cache.get(
        ("thermal model", settings.mode, *settings.view_key),
        lambda: ThermalModel(craft, infrared_exchange(craft, settings)),
    )
