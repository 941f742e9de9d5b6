"""The lumped thermal model integrated in time along a series of absorbed powers (issue 35; METHOD.md
"Planet radiation", its "Transient" paragraph).

**Equations.** The node balance of :mod:`sunwind.forces.thermal.model`, written ``C dT/dt = F(t, T)``:
``C`` the nodes' heat capacities [J/K] (``diag``), ``F`` the net power into each node [W] (absorbed,
spacecraft infrared absorbed, conduction, minus emission). Nodes without heat capacity are in
equilibrium at every instant, ``F_k(t, T) = 0``: with them the system is a DAE of index 1.

**Method.** Alexander's two-stage SDIRK [1]_ with ``gamma = 1 - 1/sqrt(2)``: order 2, L-stable and
stiffly accurate. A step of ``h`` from ``T_n`` at ``t_n`` solves two stages::

    C (Y_1 - T_n) / (gamma h) = F(t_n + gamma h, Y_1)
    C (Y_2 - T~)  / (gamma h) = F(t_n + h, Y_2),      T~ = T_n + (1 - gamma) / gamma (Y_1 - T_n)

and ``T_{n+1} = Y_2``. Each stage is a backward-Euler balance with ``rate = C / (gamma h)`` pulling toward
a shifted ``old`` temperature, solved by the model's Newton iteration with the infrared balance inside
(``T~`` stands for ``T_n + (1 - gamma) h C^-1 F(Y_1)``, so ``F`` is never evaluated outside a solve).
Nodes without heat capacity solve ``F_k = 0`` at every stage: the DAE's algebraic part is consistent at
every stage and at every output time. L-stability means a node of any small heat capacity, over any
step, relaxes to its quasi-steady state instead of oscillating or blowing up.

**Sub-steps and error estimate** (step doubling, [2]_ sec. II.4). Each interval between two given times
is integrated on its own: a sub-step of length ``h`` (a share ``s`` of the interval) is taken once and
as two halves; the two-half result is kept, and its local error is estimated per node by Richardson's
``(T_h - T_{h/2,h/2}) / (2^2 - 1)``, or by ``T_h - T_{h/2,h/2}`` where the share of the Sun changes within
the sub-step (the forcing has an edge there: errors of order ``h``, not ``h^3``). A sub-step is accepted
when its largest estimate among the nodes with a heat capacity is at most ``s * tolerance_K`` (a node
without one is balanced at the sub-step's end: its error follows from theirs, and one near 0 K, whose
temperature a trace of power moves a great deal, must not hold the sub-steps back) and the share of the
Sun changes by at most :data:`MAX_SHARE_CHANGE` over it, else it is halved (at most :data:`MAX_HALVINGS`
times, where it is accepted as it is), so the local errors of an interval sum to at most
``tolerance_K``. The estimates are
carried along as a global error estimate: the error vector ``e`` at the start of a sub-step is moved by
the linearised step (the Newton Jacobian of each stage: ``dY_1 = J_1^-1 (C / (gamma h)) e``, likewise
``dY_2`` from ``dT~``) and the sub-step's local estimate is added. ``error_K`` is its largest node value:
it estimates how far the temperatures are from the exact solution of the lumped model with this
forcing (not the error of the forcing itself: a sampled power's interpolation).

**Speed.** With node-level exchange factors (:attr:`ThermalModel.node_exchange
<sunwind.forces.thermal.model.ThermalModel.node_exchange>`) every stage, its linearisation and the
recoil and power balance recorded at each time are computed on the nodes alone; only the whole state at
the last time (:attr:`TransientHistory.final`) solves the infrared balance on the sides.

**Forcing.** The external power each side absorbs is given at the output times and interpolated
linearly in between. Sunlight may instead be given as ``solar_W`` (what each side would absorb with the
whole solar disc in view, interpolated likewise), times the share ``solar_fraction(t)`` of the disc in
view, called at every stage's own time: an eclipse's edges are resolved inside an interval (a 10 s
penumbra in a 30 s interval is cut into sub-steps over which the share changes by at most
:data:`MAX_SHARE_CHANGE`; a sharp edge is found to ``2^-MAX_HALVINGS`` of the interval) instead of being
smeared by the interpolation over the interval (up to ``P h / 2`` joules). Found only where a stage or
an end of a sub-step sees it: an interval should be shorter than an eclipse. A face's terminator
crossing between two samples of ``solar_W`` (an attitude turning against the Sun) is smoothed by the
interpolation: at 30 s steps, about 0.1 K on a 1 m^2 face of 1.5 kJ/K.

**Determinism and resuming.** An interval's sub-steps, hence its result, depend only on the temperatures
and error at its start and its forcing: integrating ``[t_0, t_m]`` then ``[t_m, t_n]`` from the
returned history gives bitwise the result of one call over ``[t_0, t_n]``.

References
----------
.. [1] Alexander, R. (1977). "Diagonally implicit Runge-Kutta methods for stiff O.D.E.'s." *SIAM J.
   Numer. Anal.* 14(6), 1006-1021.
.. [2] Hairer, E., Norsett, S. P., Wanner, G. (1993). *Solving Ordinary Differential Equations I*,
   2nd ed. Springer.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.thermal.balance import STEFAN_BOLTZMANN
from sunwind.forces.thermal.model import ThermalModel
from sunwind.forces.thermal.state import ThermalState
from sunwind.geometry.errors import InputError

#: ``gamma`` of Alexander's two-stage SDIRK: the stages' diagonal coefficient, and the first stage's time.
GAMMA = 1.0 - 1.0 / math.sqrt(2.0)
#: The method's order: local errors ``O(h^3)``.
ORDER = 2
#: Default largest estimated local error of an interval [K].
DEFAULT_TOLERANCE_K = 0.01
#: Most halvings of an interval: its shortest sub-step is ``2^-MAX_HALVINGS`` of it.
MAX_HALVINGS = 14
#: Largest change of the share of the Sun in view over one sub-step: eclipse edges are resolved to it.
MAX_SHARE_CHANGE = 0.05
_SHIFT = (1.0 - GAMMA) / GAMMA  # T~ = T_n + _SHIFT (Y_1 - T_n)


@dataclass(frozen=True, eq=False)
class TransientHistory:
    """Node temperatures, their error estimate and thermal recoil at each time of :func:`integrate`.

    Attributes
    ----------
    times_s : (n_times,) float64
        The times [s].
    node_names : (n_nodes,) str array
        Names of the nodes (:mod:`sunwind.forces.thermal.nodes`).
    node_temperature_K : (n_times, n_nodes) float64
        Temperature of each node [K].
    node_error_K : (n_times, n_nodes) float64
        Estimated error of each node's temperature [K], signed (computed minus exact): the local
        estimates carried along by the linearised steps (module docstring).
    error_K : (n_times,) float64
        ``max |node_error_K|`` at each time [K].
    step_error_K : (n_times,) float64
        Sum of the local error estimates of the sub-steps that led to each time [K] (0 at the first).
    substeps : (n_times,) int64
        Steps taken over the interval that ends at each time (0 at the first).
    force_N, torque_Nm : (n_times, 3) float64
        Thermal recoil [N], [N m] about ``reference_point_m``, body frame.
    reference_point_m : (3,) float64
        Torque reference point [m].
    absorbed_W, escaped_W, lost_W, stored_W : (n_times,) float64
        The power balance at each time [W] (:class:`~sunwind.forces.thermal.state.ThermalState`);
        ``stored_W`` is ``sum C dT/dt``.
    imbalance : (n_times,) float64
        Relative imbalance at each time [-]: round-off when every node without heat capacity is balanced.
    tolerance_K : float
        The tolerance the sub-steps were held to [K].
    final : ThermalState
        The whole state at the last time: a start for :meth:`ThermalModel.step
        <sunwind.forces.thermal.model.ThermalModel.step>`.

    Examples
    --------
    A grey cube of 9 kJ/K at 200 K, warming in sunlight (more in :func:`integrate`):

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.thermal import ThermalModel
    >>> from sunwind.geometry.materials import ThermalRule
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> model = ThermalModel(craft, None, rules=(ThermalRule("*", isothermal=True, heat_capacity_J_K=9e3),))
    >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
    >>> history = integrate(model, [0.0, 600.0, 1200.0], np.tile(sunlit, (3, 1)), initial=[200.0])
    >>> history.node_temperature_K.round(2), history.stored_W.round(1)
    (array([[200.  ],
           [225.16],
           [236.4 ]]), array([517.2, 253.1, 102.6]))
    >>> history.error_K.round(4), history.force_N.shape
    (array([0.    , 0.005 , 0.0055]), (3, 3))
    """

    times_s: NDArray[np.float64]
    node_names: NDArray[np.str_]
    node_temperature_K: NDArray[np.float64]
    node_error_K: NDArray[np.float64]
    error_K: NDArray[np.float64]
    step_error_K: NDArray[np.float64]
    substeps: NDArray[np.int64]
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]
    absorbed_W: NDArray[np.float64]
    escaped_W: NDArray[np.float64]
    lost_W: NDArray[np.float64]
    stored_W: NDArray[np.float64]
    imbalance: NDArray[np.float64]
    tolerance_K: float
    final: ThermalState


def integrate(
    model: ThermalModel,
    times_s: ArrayLike,
    absorbed_W: ArrayLike,
    *,
    initial: ArrayLike | ThermalState | TransientHistory | None = None,
    solar_W: ArrayLike | None = None,
    solar_fraction: Callable[[float], float] | None = None,
    tolerance_K: float = DEFAULT_TOLERANCE_K,
    reference_m: ArrayLike | None = None,
) -> TransientHistory:
    """Integrate the lumped thermal model over a series of times (method: the module docstring).

    Parameters
    ----------
    model : ThermalModel
        The thermal model; nodes with a heat capacity follow ``C dT/dt``, the others are in equilibrium
        at every instant.
    times_s : (n_times,) array_like
        Times [s], finite and increasing; the result is at these times.
    absorbed_W : (n_times, n_sides) array_like
        External power each side absorbs at each time [W], finite and >= 0, interpolated linearly in
        between; without ``solar_W`` all of it (sunlight included), with it all but direct sunlight.
    initial : array_like, ThermalState or TransientHistory, optional
        The start: node temperatures [K] (n_nodes,), or a state, taken as they are at the first time
        (nodes without heat capacity are balanced from the first step on); a history goes on from its
        last time (which must be ``times_s[0]``) with its error estimate, bitwise as if it had not
        stopped. Default: the equilibrium of the first time's power.
    solar_W : (n_times, n_sides) array_like, optional
        Sunlight each side absorbs at each time with the whole solar disc in view [W], >= 0,
        interpolated linearly; with ``solar_fraction``.
    solar_fraction : callable, optional
        ``solar_fraction(t_s)``: the share of the solar disc in view at time ``t_s`` [s], 0 to 1 (e.g. of
        :func:`~sunwind.forces.planet.shadow.sphere_visible`); called at every stage's own time. With
        ``solar_W``.
    tolerance_K : float, default 0.01
        Largest estimated local error of an interval between two times [K], > 0.
    reference_m : (3,) array_like, optional
        Torque reference point [m]; default the model's reference point.

    Returns
    -------
    TransientHistory
        Node temperatures, error estimates, recoil and power balance at every time.

    Raises
    ------
    InputError
        Times not finite and increasing; powers of the wrong shape, not finite or negative; only one of
        ``solar_W`` and ``solar_fraction``; a share outside [0, 1]; a tolerance not above 0; an initial
        state of another model or a history that ends elsewhere; nodes that neither emit nor store heat;
        a stage that does not converge even on the shortest sub-step.

    Examples
    --------
    A black cube of 9 kJ/K in sunlight for 35 min, then in the dark, sampled every 10 min; the Sun goes
    out inside the fourth interval, where the sub-steps are halved down to the edge:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.thermal import ThermalModel
    >>> from sunwind.geometry.materials import ThermalRule
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0, emissivity=1.0)
    >>> craft = sw.load(sw.meshes.box(), uniform=black, threads=1).craft
    >>> model = ThermalModel(craft, None, rules=(ThermalRule("*", isothermal=True, heat_capacity_J_K=9e3),))
    >>> times = np.arange(0.0, 3601.0, 600.0)
    >>> unit = 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W], Sun on +z
    >>> history = integrate(model, times, np.zeros((7, 12)), initial=[250.0],
    ...                     solar_W=np.tile(unit, (7, 1)), solar_fraction=lambda t: float(t < 2100.0))
    >>> history.node_temperature_K[:, 0].round(2)
    array([250.  , 251.14, 251.41, 251.47, 217.72, 182.34, 162.5 ])
    >>> history.error_K.round(4), history.substeps.tolist()
    (array([0.    , 0.0029, 0.004 , 0.0016, 0.0025, 0.0063, 0.0097]), [0, 4, 2, 2, 42, 12, 6])

    (A tight ``solve_ivp`` of ``C dT/dt = P f(t) - 6 sigma T^4`` gives 162.514 K at one hour: off by the
    0.0097 K estimated.)

    Going on from the history is bitwise the same as one call:

    >>> first = integrate(model, times[:4], np.zeros((4, 12)), initial=[250.0],
    ...                   solar_W=np.tile(unit, (4, 1)), solar_fraction=lambda t: float(t < 2100.0))
    >>> then = integrate(model, times[3:], np.zeros((4, 12)), initial=first,
    ...                  solar_W=np.tile(unit, (4, 1)), solar_fraction=lambda t: float(t < 2100.0))
    >>> bool(np.array_equal(then.node_temperature_K, history.node_temperature_K[3:]))
    True
    """
    times = _times(times_s)
    forcing = _Forcing(model, times, absorbed_W, solar_W, solar_fraction)
    if isinstance(tolerance_K, bool) or not (
        isinstance(tolerance_K, (int, float)) and math.isfinite(tolerance_K) and tolerance_K > 0
    ):
        raise InputError(
            f"tolerance_K = {tolerance_K!r} is not a tolerance",
            hint="give kelvin > 0, e.g. 0.01",
            parameters=("tolerance_K",),
        )
    model._check_emitters(model.nodes.heat_capacity_J_K)
    temperature, error = _start(model, initial, times, forcing)
    stepper = _Stepper(model, forcing, float(tolerance_K))
    n, n_nodes = len(times), model.nodes.n_nodes
    node_temperature, node_error = np.empty((n, n_nodes)), np.empty((n, n_nodes))
    step_error, substeps = np.zeros(n), np.zeros(n, dtype=np.int64)
    if isinstance(initial, TransientHistory):  # its last row, as it was
        step_error[0], substeps[0] = initial.step_error_K[-1], initial.substeps[-1]
    loads, powers = np.empty((2, n, 3)), np.empty((5, n))  # force, torque; the power balance
    reference = None if reference_m is None else np.asarray(reference_m, dtype=np.float64)
    for k in range(n):
        if k > 0:
            temperature, error, substeps[k], step_error[k] = stepper.advance(temperature, error, k - 1)
        node_temperature[k], node_error[k] = temperature, error
        loads[:, k], powers[:, k] = _balance(model, temperature, forcing.at(k, 0.0), reference)
    state = _state(model, temperature, forcing.at(n - 1, 0.0), reference)
    return TransientHistory(
        times_s=times,
        node_names=model.nodes.names,
        node_temperature_K=node_temperature,
        node_error_K=node_error,
        error_K=np.abs(node_error).max(axis=1, initial=0.0),
        step_error_K=step_error,
        substeps=substeps,
        force_N=loads[0],
        torque_Nm=loads[1],
        reference_point_m=state.reference_point_m,
        absorbed_W=powers[0],
        escaped_W=powers[1],
        lost_W=powers[2],
        stored_W=powers[3],
        imbalance=powers[4],
        tolerance_K=float(tolerance_K),
        final=state,
    )


# --- the forcing --------------------------------------------------------------------------------------
class _Forcing:
    """The external power each side absorbs at any time within the given times."""

    def __init__(
        self,
        model: ThermalModel,
        times: NDArray[np.float64],
        absorbed_W: ArrayLike,
        solar_W: ArrayLike | None,
        fraction: Callable[[float], float] | None,
    ) -> None:
        if (solar_W is None) != (fraction is None):
            raise InputError(
                "solar_W and solar_fraction go together",
                hint="give both (sunlight at full Sun, and the share of the Sun in view at any time), "
                "or neither (sunlight inside absorbed_W)",
                parameters=("solar_W", "solar_fraction"),
            )
        if fraction is not None and not callable(fraction):
            raise InputError(
                "solar_fraction must be a function of the time [s]",
                hint="e.g. lambda t: float(sphere_visible(position(t), sun(t), radius)[0])",
                parameters=("solar_fraction",),
            )
        shape = (len(times), model.craft.n_sides)
        self.times = times
        self.absorbed = _powers(absorbed_W, shape, "absorbed_W")
        self.solar = None if solar_W is None else _powers(solar_W, shape, "solar_W")
        self.fraction = fraction
        self._seen: dict[float, float] = {}

    def at(self, k: int, theta: float) -> NDArray[np.float64]:
        """The power [W] per side at the part ``theta`` (0 to 1) of the interval from time ``k``."""
        if theta == 0.0 or theta == 1.0:  # a sample as it is (``at(n - 1, 0)`` is the last)
            j = k if theta == 0.0 else k + 1
            q, solar = self.absorbed[j], None if self.solar is None else self.solar[j]
        else:
            q = (1.0 - theta) * self.absorbed[k] + theta * self.absorbed[k + 1]
            solar = None if self.solar is None else (1.0 - theta) * self.solar[k] + theta * self.solar[k + 1]
        return q if solar is None else q + self._sunlit(self.time(k, theta)) * solar

    def time(self, k: int, theta: float) -> float:
        """The time [s] at the part ``theta`` (0 to 1) of the interval from time ``k``; exact at its ends."""
        if theta == 0.0:
            return float(self.times[k])
        return float((1.0 - theta) * self.times[k] + theta * self.times[k + 1])

    def change(self, k: int, lo: float, hi: float) -> float:
        """How much the share of the Sun in view changes over the parts ``lo`` to ``hi`` of interval ``k``:
        the range of the shares asked for there, its ends included (0: no eclipse edge)."""
        if self.solar is None:
            return 0.0
        first, last = self.time(k, lo), self.time(k, hi)
        seen = [self._sunlit(first), self._sunlit(last)]
        seen += [value for t, value in self._seen.items() if first <= t <= last]
        return max(seen) - min(seen)

    def forget(self) -> None:
        """Drop the shares of the Sun asked for so far (each interval keeps only its own)."""
        self._seen.clear()

    def _sunlit(self, t: float) -> float:
        """``solar_fraction(t)``, checked, asked once per time in an interval."""
        if t in self._seen:
            return self._seen[t]
        value = np.asarray(self.fraction(t), dtype=np.float64).reshape(-1)
        if value.shape != (1,) or not (-1e-12 <= value[0] <= 1.0 + 1e-12):
            raise InputError(
                f"solar_fraction({t!r}) = {value.tolist()} is not a share of the Sun",
                hint="return one number from 0 (umbra) to 1 (full Sun)",
                parameters=("solar_fraction",),
            )
        self._seen[t] = float(min(max(value[0], 0.0), 1.0))
        return self._seen[t]


def _times(times_s: ArrayLike) -> NDArray[np.float64]:
    times = np.array(times_s, dtype=np.float64)
    if times.ndim != 1 or len(times) == 0 or not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
        raise InputError(
            "times_s must be finite times [s] in increasing order",
            hint=f"got shape {times.shape}; give at least one time, each later than the one before",
            parameters=("times_s",),
        )
    return times


def _powers(values: ArrayLike, shape: tuple[int, int], name: str) -> NDArray[np.float64]:
    powers = np.array(values, dtype=np.float64)
    if powers.shape != shape or not np.all(np.isfinite(powers)) or np.any(powers < 0):
        raise InputError(
            f"{name} must be {shape[0]} x {shape[1]} finite powers >= 0 [W], one per time and side",
            hint=f"got shape {powers.shape}",
            parameters=(name,),
        )
    return powers


# --- the start ----------------------------------------------------------------------------------------
def _start(
    model: ThermalModel, initial: object, times: NDArray[np.float64], forcing: _Forcing
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Node temperatures [K] and error estimate [K] at the first time."""
    n_nodes = model.nodes.n_nodes
    if initial is None:
        return model.equilibrium(forcing.at(0, 0.0)).node_temperature_K, np.zeros(n_nodes)
    if isinstance(initial, TransientHistory):
        if initial.times_s[-1] != times[0] or initial.node_temperature_K.shape[1] != n_nodes:
            raise InputError(
                f"the history given as initial ends at {float(initial.times_s[-1])!r} s with "
                f"{initial.node_temperature_K.shape[1]} nodes, not at times_s[0] = {float(times[0])!r} s "
                f"with {n_nodes}",
                hint="go on from a history of this model, with times_s starting at its last time",
                parameters=("initial", "times_s"),
            )
        return model._node_temperatures(initial.node_temperature_K[-1]), initial.node_error_K[-1].copy()
    if isinstance(initial, ThermalState):
        initial = initial.node_temperature_K
    return model._node_temperatures(initial), np.zeros(n_nodes)


def _state(
    model: ThermalModel,
    temperature: NDArray[np.float64],
    q: NDArray[np.float64],
    reference_m: NDArray[np.float64] | None,
) -> ThermalState:
    """The state at node temperatures ``temperature``, storing what the nodes with a heat capacity gain."""
    state = model.state_at(temperature, q, reference_m)
    nodes = model.nodes
    gained = nodes.sum_sides(q + state.absorbed_infrared_W - state.emitted_W) - nodes.laplacian @ temperature
    return state.with_stored(float(gained[nodes.heat_capacity_J_K > 0].sum()))


def _balance(
    model: ThermalModel,
    temperature: NDArray[np.float64],
    q: NDArray[np.float64],
    reference_m: NDArray[np.float64] | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Force and torque (2, 3), and absorbed, escaped, lost, stored power and imbalance (5,) at node
    temperatures ``temperature``: of :func:`_state`, or with node factors of them alone (no solve
    over the sides; equal to the state's to the solves' tolerance)."""
    factors = model.node_exchange
    if factors is None:
        state = _state(model, temperature, q, reference_m)
        return (
            np.array([state.force_N, state.torque_Nm]),
            np.array([state.absorbed_W, state.escaped_W, state.lost_W, state.stored_W, state.imbalance]),
        )
    reference = model.craft.default_reference[0] if reference_m is None else reference_m
    totals, lost = factors.totals(temperature, reference)
    nodes, x = model.nodes, STEFAN_BOLTZMANN * temperature**4
    node_q = nodes.sum_sides(q)
    gained = node_q - factors.net_m2 @ x - nodes.laplacian @ temperature
    stored = float(gained[nodes.heat_capacity_J_K > 0].sum())
    total, escaped = float(q.sum()), totals.escaped_W
    scale = max(total, escaped + lost, np.finfo(float).tiny)
    imbalance = (total - escaped - lost - stored) / scale
    return np.array([totals.force_N, totals.torque_Nm]), np.array([total, escaped, lost, stored, imbalance])


# --- the steps ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Step:
    """One SDIRK step: its result and what its linearisation needs."""

    temperature: NDArray[np.float64]
    first: NDArray[np.float64]
    rate: NDArray[np.float64]


class _Stepper:
    """SDIRK steps over the shares of one interval, halved until each is within the tolerance."""

    def __init__(self, model: ThermalModel, forcing: _Forcing, tolerance_K: float) -> None:
        self.model, self.forcing, self.tolerance = model, forcing, tolerance_K
        self.capacity = model.nodes.heat_capacity_J_K
        #: the nodes whose local errors decide the sub-steps: those with a heat capacity (an algebraic
        #: node's error follows from theirs)
        self.differential = self.capacity > 0

    def advance(
        self, temperature: NDArray[np.float64], error: NDArray[np.float64], k: int
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], int, float]:
        """From time ``k`` to ``k + 1``: temperatures, error estimate, steps taken, sum of local errors."""
        self.forcing.forget()
        return self._span(temperature, error, k, (0.0, 1.0), None)

    def _span(
        self,
        temperature: NDArray[np.float64],
        error: NDArray[np.float64],
        k: int,
        span: tuple[float, float],
        whole: _Step | None,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], int, float]:
        """The shares ``span`` of interval ``k`` as one step taken as two halves, or halved further;
        ``whole``: the one step over ``span`` when already taken."""
        lo, hi = span
        mid = 0.5 * (lo + hi)
        depth = round(-math.log2(hi - lo))
        whole = self._step(temperature, k, lo, hi) if whole is None else whole
        first = self._step(temperature, k, lo, mid)
        second = None if first is None else self._step(first.temperature, k, mid, hi)
        if whole is not None and second is not None:
            # Richardson's factor for local errors O(h^3); across an eclipse edge they may be O(h)
            change = self.forcing.change(k, lo, hi)
            local = (whole.temperature - second.temperature) / (1 if change else 2**ORDER - 1)
            size = float(np.abs(local[self.differential]).max(initial=0.0))
            fine = size <= self.tolerance * (hi - lo) and change <= MAX_SHARE_CHANGE
            if fine or depth >= MAX_HALVINGS:
                return second.temperature, self._moved(whole, error) + local, 2, size
        elif depth >= MAX_HALVINGS:
            raise InputError(
                f"the node temperatures did not converge over a step of "
                f"{(hi - lo) * (self.forcing.times[k + 1] - self.forcing.times[k]):.3g} s after "
                f"t = {float(self.forcing.times[k])!r} s",
                path=self.model.craft.source,
                hint="check the heat capacities, conductances and powers for extreme values",
            )
        temperature, error, n_first, first_error = self._span(temperature, error, k, (lo, mid), first)
        temperature, error, n_second, second_error = self._span(temperature, error, k, (mid, hi), None)
        return temperature, error, n_first + n_second, first_error + second_error

    def _step(self, temperature: NDArray[np.float64], k: int, lo: float, hi: float) -> _Step | None:
        """One SDIRK step over the shares ``lo`` to ``hi`` of interval ``k``; None if a stage fails."""
        forcing, model = self.forcing, self.model
        rate = self.capacity / (GAMMA * (hi - lo) * (forcing.times[k + 1] - forcing.times[k]))
        early, late = forcing.at(k, lo + GAMMA * (hi - lo)), forcing.at(k, hi)
        try:
            first = model._temperatures(early, rate, temperature)
            shifted = temperature + _SHIFT * (first - temperature)
            last = model._temperatures(late, rate, shifted, first)
        except InputError:  # Newton or the infrared balance did not converge: a shorter step will
            return None
        return _Step(last, first, rate)

    def _moved(self, step: _Step, error: NDArray[np.float64]) -> NDArray[np.float64]:
        """The error ``error`` [K] at the start of ``step`` carried to its end by its linearisation."""
        if not np.any(error):
            return error.copy()
        model = self.model
        first = model._sensitivity(step.first, step.rate, error)
        return model._sensitivity(step.temperature, step.rate, error + _SHIFT * (first - error))
