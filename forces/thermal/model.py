"""Node temperatures in equilibrium and in time, and the recoil of the infrared the spacecraft emits
(issue 21; METHOD.md "Inter-reflection" for the diffuse balance the infrared uses).

**Balance of a node.** Given the external power ``Q_i`` [W] each side absorbs (sunlight, albedo,
planet infrared, inter-reflected light: computed by the caller), the temperature ``T_k`` [K] of each node
``k`` (:mod:`sunwind.forces.thermal.nodes`) satisfies::

    C_k dT_k/dt = sum_{i in k} (Q_i + eps_i G_i) + sum_{links k-l} h A (T_l - T_k)
                  - sum_{i in k} eps_i A_i sigma_SB T_k^4

with ``G`` the spacecraft's own infrared arriving at each side, its emission
``e_i = eps_i A_i sigma_SB T_i^4`` after all reflections (:mod:`sunwind.forces.thermal.balance`), and
``C_k`` the node's heat capacity [J/K]. This is the dissertation's eq. (1.1),
``d rho c dT/dt = A_S q + eps q_e - eps sigma T^4`` per unit area, summed over a node, with the
infrared the spacecraft sends itself and the conduction of sheets added.

**Equilibrium** (``dT/dt = 0``; :meth:`ThermalModel.equilibrium`). Without conduction links (every
``h`` infinite or 0) the balance is linear in ``X_k = sigma_SB T_k^4``::

    (sum_{i in k} eps_i A_i) X_k - sum_{i in k} eps_i G_i(X) = sum_{i in k} Q_i

and is solved as one linear system with the infrared balance (its residual at round-off). With links it
is solved by Newton's method on ``T``, the infrared balance inside each step (the joined system of
:func:`~sunwind.forces.thermal.balance.solve_joined`, the node Jacobian ``diag(4 sigma T^3 sum eps A)
+ L`` sparse), starting from the linear solution with every linked group of nodes at one temperature,
until the node and infrared residuals sum to at most :data:`NEWTON_TOLERANCE` of the power through the
model. A group of linked nodes none of whose sides emits (``eps = 0``) has no equilibrium: an error.

**Transient** (:meth:`ThermalModel.step`). Backward Euler over ``dt``: ``C_k (T_k - T_k,old) / dt`` on
the left, everything else at the new temperatures, solved by the same Newton iteration (from the old
temperatures). Nodes without heat capacity (all but isothermal parts given ``heat_capacity_J_K``) are
in equilibrium at every step. Unconditionally stable; first order in ``dt``.

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

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.forces.radiation.law import LAMBERT_FACTOR, SPEED_OF_LIGHT
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.forces.reflection.views import model_view_factors
from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN, InfraredBalance, solve_joined
from sunwind.forces.thermal.nodes import ThermalNodes, thermal_nodes
from sunwind.forces.thermal.state import ThermalState
from sunwind.geometry.errors import InputError
from sunwind.geometry.spacecraft import Spacecraft, infrared_optics

#: Newton ends when the node and infrared residuals sum to this share of the power through the model.
NEWTON_TOLERANCE = 1e-13
#: Most Newton steps before the iteration is an error.
NEWTON_STEPS = 100
#: Below this temperature [K] Newton takes the slope ``4 sigma T^3`` at it (a node at 0 K has none).
SLOPE_FLOOR_K = 1.0


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
        self, craft: Spacecraft, exchange: DiffuseExchange | None = None, *, rules: tuple | None = None
    ) -> None:
        emissivity = 1.0 - infrared_optics(craft)[:, 0]
        self.craft = craft
        self.nodes: ThermalNodes = thermal_nodes(craft, rules)
        self.infrared = InfraredBalance(craft, emissivity, exchange)
        #: ``sum_{i in k} eps_i A_i`` of each node [m^2]
        self.node_emitting_area_m2 = self.nodes.sum_sides(self.infrared.emitting_area)

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
        self, absorbed: NDArray[np.float64], rate: NDArray[np.float64], old: NDArray[np.float64] | None
    ) -> NDArray[np.float64]:
        """Node temperatures [K] balancing ``absorbed`` [W] per side, with ``rate = C / dt`` [W/K] per
        node pulling toward ``old`` [K] (None: equilibrium, ``rate`` 0)."""
        nodes = self.nodes
        if len(nodes.links) == 0 and not np.any(rate):
            return self._linear(nodes.side_node, absorbed)
        if old is None:
            guess = self._grouped_guess(absorbed)
        else:
            guess = old.copy()
            cold = guess <= 0
            if np.any(cold):
                guess[cold] = self._grouped_guess(absorbed)[cold]
        return self._newton(absorbed, rate, np.zeros(nodes.n_nodes) if old is None else old, guess)

    def _linear(self, side_node: NDArray[np.int64], absorbed: NDArray[np.float64]) -> NDArray[np.float64]:
        """Equilibrium temperatures [K] of nodes ``side_node`` without links: linear in ``sigma T^4``."""
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
        return self._linear(groups[self.nodes.side_node], absorbed)[groups]

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
            through = absorbed.sum() + area @ x + np.abs(stored).sum()
            if np.abs(node_residual).sum() + np.abs(infrared_residual).sum() <= NEWTON_TOLERANCE * through:
                return temperature
            slope = 4.0 * STEFAN_BOLTZMANN * np.maximum(temperature, SLOPE_FLOOR_K) ** 3
            jacobian = scipy.sparse.diags(area * slope + rate) + laplacian
            d_leaving, d_temperature = solve_joined(
                infrared, nodes.side_node, jacobian, slope, node_residual, -infrared_residual
            )
            updated = np.maximum(temperature + d_temperature, 0.1 * temperature)  # stays positive
            leaving = leaving + d_leaving
            if np.all(np.abs(updated - temperature) <= 4 * np.finfo(float).eps * temperature):
                return updated  # settled to round-off
            temperature = updated
        raise InputError(
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
