"""The thermal state of a spacecraft at one instant: temperatures, its own infrared, their recoil."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

#: The frame every vector is in (as every sunwind result).
FRAME = "body frame of the mesh"


@dataclass(frozen=True, eq=False)
class ThermalState:
    """Temperatures and the spacecraft's own infrared; body frame, SI units.

    Attributes
    ----------
    temperature_K : (n_sides,) float64
        Temperature of each side [K] (its node's).
    node_temperature_K : (n_nodes,) float64
        Temperature of each node [K].
    node_names : (n_nodes,) str array
        Names of the nodes (:mod:`sunwind.forces.thermal.nodes`).
    emitted_W : (n_sides,) float64
        Infrared each side emits, ``e_i = eps_i A_i sigma_SB T_i^4`` [W].
    absorbed_infrared_W : (n_sides,) float64
        Infrared from the spacecraft itself (its emission after reflections) each side absorbs,
        ``eps_i G_i`` [W].
    force_N, torque_Nm : (3,) float64
        Thermal recoil: force and torque about ``reference_point_m`` of the emitted infrared once all
        its reflections are done [N], [N m].
    reference_point_m : (3,) float64
        Torque reference point [m].
    absorbed_W : float
        External power the sides absorb (sunlight, albedo, planet infrared, ...), total [W].
    emitted_W_total : float
        ``sum e_i`` [W].
    escaped_W : float
        Infrared that leaves the spacecraft [W].
    lost_W : float
        Infrared that reaches sides the model does not have or was still travelling when an exchange
        chain was dropped: absorbed by no node [W].
    stored_W : float
        Rate at which the nodes' heat capacities take up heat, ``sum C_k dT_k/dt`` [W] (0 in
        equilibrium).
    imbalance : float
        ``(absorbed - escaped - lost - stored) / max(absorbed, escaped + lost)`` [-]: 0 to round-off
        when every node is balanced.

    Examples
    --------
    Made by :class:`~sunwind.forces.thermal.model.ThermalModel`:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.thermal import thermal_model
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
    >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
    >>> state = thermal_model(craft, "none").equilibrium(sunlit)
    >>> round(state.absorbed_W, 6), round(state.escaped_W, 6)
    (952.7, 952.7)
    >>> np.round(state.force_N * 1e6, 3) + 0.0  # [uN]: the hot top face's infrared pushes down
    array([ 0.   ,  0.   , -2.119])
    """

    temperature_K: NDArray[np.float64]
    node_temperature_K: NDArray[np.float64]
    node_names: NDArray[np.str_]
    emitted_W: NDArray[np.float64]
    absorbed_infrared_W: NDArray[np.float64]
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]
    absorbed_W: float
    emitted_W_total: float
    escaped_W: float
    lost_W: float
    stored_W: float
    imbalance: float

    def with_stored(self, stored_W: float) -> ThermalState:
        """This state with the nodes taking up heat at ``stored_W``, its ``imbalance`` made anew.

        Parameters
        ----------
        stored_W : float
            Rate at which the nodes' heat capacities take up heat [W].

        Returns
        -------
        ThermalState
            A copy with ``stored_W`` and ``imbalance`` changed.

        Examples
        --------
        A cube at 250 K in sunlight emits less than it absorbs; storing the difference balances it:

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.thermal import thermal_model
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> sunlit = 0.7 * 1361.0 * 0.5 * np.maximum(craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W]
        >>> state = thermal_model(craft, "none").state_at(np.full(12, 240.0), sunlit)
        >>> balanced = state.with_stored(state.absorbed_W - state.escaped_W)
        >>> round(balanced.stored_W, 1), abs(balanced.imbalance) < 1e-15
        (49.7, True)
        """
        scale = max(self.absorbed_W, self.escaped_W + self.lost_W, np.finfo(float).tiny)
        imbalance = (self.absorbed_W - self.escaped_W - self.lost_W - stored_W) / scale
        return replace(self, stored_W=float(stored_W), imbalance=imbalance)

    def to_json(self) -> dict:
        """A plain-JSON summary; keys carry their units, node temperatures by node name.

        Returns
        -------
        dict
            The frame, force, torque, reference point, the power balance, the lowest and highest
            temperature and ``node_temperature_K`` (a dict of node name to temperature).

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.thermal import thermal_model
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> craft = sw.load(sw.meshes.box(), uniform=grey, threads=1).craft
        >>> state = thermal_model(craft, "none").state_at(np.full(12, 290.0), np.zeros(12))
        >>> summary = state.to_json()
        >>> summary["temperature_max_K"], summary["node_temperature_K"]["box/facet 0"]
        (290.0, 290.0)
        """
        temperature = self.node_temperature_K
        return {
            "frame": FRAME,
            "force_N": self.force_N.tolist(),
            "torque_Nm": self.torque_Nm.tolist(),
            "reference_point_m": self.reference_point_m.tolist(),
            "absorbed_W": self.absorbed_W,
            "emitted_W": self.emitted_W_total,
            "escaped_W": self.escaped_W,
            "lost_W": self.lost_W,
            "stored_W": self.stored_W,
            "imbalance": self.imbalance,
            "temperature_min_K": float(temperature.min()),
            "temperature_max_K": float(temperature.max()),
            "node_temperature_K": dict(zip(self.node_names.tolist(), temperature.tolist(), strict=True)),
        }
