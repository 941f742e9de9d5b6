"""The infrared balance of a spacecraft's own emission, and the linear systems that join it to the node
balances (METHOD.md "Inter-reflection").

**Infrared band.** Side ``i`` absorbs the share ``eps_i`` (its emissivity, Kirchhoff) of the infrared
arriving at it and reflects ``1 - eps_i`` diffusely: no mirror share, no transmission in the infrared.
Its emission ``e_i = eps_i A_i sigma_SB T_i^4`` [W] is a diffuse source, so the infrared leaving the
sides is the diffuse balance of light with the infrared optics ``(rho, beta, sigma) = (1 - eps, 0, 0)``
(:class:`sunwind.forces.reflection.diffuse.DiffuseExchange` made with ``optics=infrared_optics(craft)``;
with no mirrors ``E = F``, the view factors)::

    W = e + diag(1 - eps) E^T W,      G = E^T W,      absorbed at side j:  eps_j G_j

``G_j`` [W] is the infrared arriving at side ``j`` from the spacecraft, its own emission included after
reflections. Of ``W`` the shares ``f_esc`` escape, ``f_blind`` reach sides the model does not have (a
one-sided sheet's back) and ``f_trunc`` were still travelling when a chain was dropped: the last two are
**lost** (absorbed nowhere on a node) and reported. Without an exchange (reflections ``none``, or a
convex body) ``G = 0`` and all emission escapes.

**Joined systems.** With node unknowns ``Y`` (n_nodes,), a node matrix ``H`` (sparse, symmetric
positive definite), a per-node factor ``b`` and per-side sources ``s`` [W], :func:`solve_joined` solves
::

    W - diag(1 - eps) E^T W - eps A b[node] Y[node] = s          (the infrared balance)
    H Y - P^T (eps E^T W) = r                                     (the node balances)

``P^T`` sums sides into their nodes. The node balances of the steady state in ``X = sigma T^4`` are
this with ``b = 1``, ``H = diag(sum_i in k eps_i A_i)``, ``r = P^T Q``, ``s = 0``; each Newton step on the
temperatures is this with ``b = 4 sigma T^3`` (:mod:`sunwind.forces.thermal.model`). Eliminating
``Y = H^-1 (r + P^T eps G)`` leaves one system in ``W``::

    W - K W = s + eps A b[node] (H^-1 r)[node],
    K W = diag(1 - eps) G + eps A b[node] (H^-1 P^T (eps G))[node],      G = E^T W

``K`` maps infrared leaving the sides to infrared leaving them again, reflected or absorbed and
re-emitted; it gives back less than it takes wherever infrared escapes. It is solved as the diffuse
balance is: sweeps ``W <- rhs + K W`` (one reflection or re-emission each) for up to
:data:`SWEEPS`, to a relative step of :data:`TOLERANCE`, then GMRES on ``I - K`` as a linear
operator. Nothing of size ``n_sides^2`` is made: ``E^T`` is the exchange factors' sparse matrix
transposed (a view), ``H`` is sparse and factorised once per system.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse
import scipy.sparse.linalg
from numpy.typing import NDArray

from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import count, require
from sunwind.geometry.spacecraft import Spacecraft

#: Stefan-Boltzmann constant [W m^-2 K^-4] (CODATA 2018, exact in SI).
STEFAN_BOLTZMANN = 5.670374419e-8
#: Relative step (sweeps) and residual (GMRES) at which a joined system counts as solved.
TOLERANCE = 1e-13
#: Fixed-point sweeps before GMRES takes over.
SWEEPS = 200
#: Krylov vectors GMRES keeps before it restarts.
RESTART = 60
_HINT_CAVITY = (
    "a closed cavity whose inside neither lets infrared out nor conducts heat out has no balance: "
    "open it, or couple its inside to its outside (conductance_W_m2K > 0, or the default inf)"
)


class InfraredBalance:
    """The infrared band of one model: emissivities, areas and (optionally) the exchange factors.

    Parameters
    ----------
    craft : Spacecraft
        The spacecraft.
    emissivity : (n_sides,) float64
        ``eps_i`` [-], in [0, 1].
    exchange : DiffuseExchange or None
        The diffuse balance made with the infrared optics ``(1 - eps, 0, 0)``; None: every side's
        emission escapes.

    Attributes
    ----------
    emitting_area : (n_sides,) float64
        ``eps_i A_i`` [m^2].
    arriving : sparse matrix or None
        ``E^T``, a transposed view of the exchange factors; None without an exchange.

    Raises
    ------
    InputError
        An exchange of another model, or one not made with the infrared optics; too little memory.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> balance = InfraredBalance(craft, np.full(craft.n_sides, 0.8), None)  # a convex cube: no exchange
    >>> round(float(balance.emitting_area.sum()), 12)  # 0.8 of the cube's 6 m^2
    4.8
    >>> emitted = np.full(craft.n_sides, 10.0)
    >>> float(balance.leaving(emitted).sum()), float(balance.arrival(emitted).sum())
    (120.0, 0.0)
    """

    def __init__(
        self, craft: Spacecraft, emissivity: NDArray[np.float64], exchange: DiffuseExchange | None
    ) -> None:
        n = craft.n_sides
        # sweeps and GMRES: the Krylov basis and a dozen work vectors of n_sides
        require(
            8.0 * n * (RESTART + 16),
            f"the infrared balance of {count(n)} sides",
            "use a coarser mesh",
        )
        self.craft = craft
        self.emissivity = np.asarray(emissivity, dtype=np.float64)
        self.emitting_area = self.emissivity * craft.side_areas  # eps_i A_i [m^2]
        self.exchange = exchange
        if exchange is not None and exchange.craft is not craft:
            raise InputError(
                "the exchange given is of another model",
                hint="make it for this model: infrared_exchange(craft, reflections)",
            )
        if exchange is not None and not np.allclose(
            exchange.absorptance, self.emissivity, rtol=0, atol=1e-12
        ):
            raise InputError(
                "the exchange given is not the infrared one: its absorptances differ from the emissivities",
                hint="make it with DiffuseExchange(craft, view, optics=infrared_optics(craft))",
            )
        #: ``E^T`` (a transposed view of the sparse exchange factors) or None
        self.arriving = None if exchange is None else exchange.factors.matrix.T

    def arrival(self, leaving_W: NDArray[np.float64]) -> NDArray[np.float64]:
        """The infrared arriving at each side, ``G = E^T W``.

        Parameters
        ----------
        leaving_W : (n_sides,) float64
            Infrared ``W`` leaving each side [W].

        Returns
        -------
        (n_sides,) float64
            Infrared arriving at each side [W]; zeros without an exchange.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> balance = InfraredBalance(craft, np.full(craft.n_sides, 0.8), None)  # a convex cube: no exchange
        >>> float(balance.arrival(np.ones(craft.n_sides)).max())  # nothing comes back to a convex body
        0.0
        """
        if self.arriving is None:
            return np.zeros_like(leaving_W)
        return self.arriving @ leaving_W

    def leaving(self, emitted_W: NDArray[np.float64]) -> NDArray[np.float64]:
        """The infrared leaving each side, ``W``: its emission ``e`` and what it reflects.

        Parameters
        ----------
        emitted_W : (n_sides,) float64
            Emission ``e_i`` of each side [W].

        Returns
        -------
        (n_sides,) float64
            Infrared leaving each side [W], the solution of ``W = e + diag(1 - eps) E^T W``; a copy of
            ``emitted_W`` without an exchange.

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> balance = InfraredBalance(craft, np.full(craft.n_sides, 0.8), None)  # a convex cube: no exchange
        >>> balance.leaving(np.arange(12.0))[-3:]
        array([ 9., 10., 11.])
        """
        if self.exchange is None:
            return np.array(emitted_W, dtype=np.float64)
        return self.exchange.solve(emitted_W)


def solve_joined(
    balance: InfraredBalance,
    side_node: NDArray[np.int64],
    node_matrix: scipy.sparse.spmatrix,
    factor: NDArray[np.float64],
    node_rhs: NDArray[np.float64],
    side_source: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Solve the joined infrared and node system of the module docstring.

    Parameters
    ----------
    balance : InfraredBalance
        The infrared band (``eps``, ``E^T``).
    side_node : (n_sides,) int64
        Node of each side (the map ``P``).
    node_matrix : (n_nodes, n_nodes) sparse
        ``H``, symmetric positive definite [W per unit of ``Y``].
    factor : (n_nodes,) float64
        ``b``: side emission per unit emitting area and unit of ``Y`` [W m^-2 per unit of ``Y``].
    node_rhs : (n_nodes,) float64
        ``r`` [W].
    side_source : (n_sides,) float64
        ``s`` [W].

    Returns
    -------
    W : (n_sides,) float64
        Infrared leaving each side [W].
    Y : (n_nodes,) float64
        The node unknowns.

    Raises
    ------
    InputError
        The iteration did not converge (a closed cavity that can lose no heat).

    References
    ----------
    .. [1] Saad, Y., Schultz, M. H. (1986). "GMRES: a generalized minimal residual algorithm for
       solving nonsymmetric linear systems." *SIAM J. Sci. Stat. Comput.* 7(3), 856-869.

    Examples
    --------
    The steady state of an isothermal grey cube absorbing 952.7 W: one node, ``b = 1``,
    ``H = sum eps A`` and ``r`` the absorbed power give ``Y = sigma T^4``.

    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> balance = InfraredBalance(craft, np.full(craft.n_sides, 0.8), None)  # a convex cube: no exchange
    >>> import scipy.sparse
    >>> one_node = np.zeros(craft.n_sides, dtype=np.int64)
    >>> h = scipy.sparse.diags([balance.emitting_area.sum()])
    >>> leaving, y = solve_joined(balance, one_node, h, np.ones(1), np.array([952.7]), np.zeros(12))
    >>> round(float((y[0] / STEFAN_BOLTZMANN) ** 0.25), 2)  # [K]
    243.23
    """
    solve_nodes = _node_solver(node_matrix)
    n_nodes = node_matrix.shape[0]
    weight = balance.emitting_area * factor[side_node]  # eps_i A_i b[node(i)]
    eps = balance.emissivity

    def absorbed(leaving: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Infrared absorbed per node, ``P^T (eps E^T W)``, and the arrival ``E^T W``."""
        arriving = balance.arrival(leaving)
        return np.bincount(side_node, weights=eps * arriving, minlength=n_nodes), arriving

    def onward(leaving: NDArray[np.float64]) -> NDArray[np.float64]:
        node_absorbed, arriving = absorbed(leaving)
        return (1.0 - eps) * arriving + weight * solve_nodes(node_absorbed)[side_node]

    rhs = side_source + weight * solve_nodes(node_rhs)[side_node]
    leaving = rhs if balance.arriving is None else _fixed_point(onward, rhs, balance.craft.source)
    y = solve_nodes(node_rhs + absorbed(leaving)[0])
    return leaving, y


def _node_solver(matrix: scipy.sparse.spmatrix) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """``v -> H^-1 v``: a division where ``H`` is diagonal, else a sparse factorisation."""
    matrix = scipy.sparse.csc_matrix(matrix)
    diagonal = matrix.diagonal()
    off_diagonal = matrix - scipy.sparse.diags(diagonal)
    if not np.any(off_diagonal.data):
        return lambda v: v / diagonal
    return scipy.sparse.linalg.factorized(matrix)


def _fixed_point(
    onward: Callable[[NDArray[np.float64]], NDArray[np.float64]], rhs: NDArray[np.float64], source: str
) -> NDArray[np.float64]:
    """``(I - K)^-1 rhs`` for ``K`` = ``onward``: sweeps, then GMRES from where they stopped."""
    x = np.array(rhs, dtype=np.float64)
    scale = np.abs(x).max(initial=0.0)
    if scale == 0.0:
        return x
    for _ in range(SWEEPS):
        step = rhs + onward(x) - x
        x += step
        if np.abs(step).max() <= TOLERANCE * np.abs(x).max():
            return x
    n = len(x)
    operator = scipy.sparse.linalg.LinearOperator((n, n), matvec=lambda v: v - onward(v), dtype=np.float64)
    x, _ = scipy.sparse.linalg.gmres(
        operator, rhs, x0=x, rtol=TOLERANCE, atol=0.0, restart=RESTART, maxiter=200
    )
    residual = np.linalg.norm(operator @ x - rhs) / np.linalg.norm(rhs)
    if not residual <= 1e3 * TOLERANCE:
        raise InputError(
            f"the infrared balance of the nodes did not converge (relative residual {residual:.1e})",
            path=source,
            hint=_HINT_CAVITY,
        )
    return x
