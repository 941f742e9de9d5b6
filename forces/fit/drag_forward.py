"""The drag part of a fit's forward model: free-molecular force and torque at every distinct flow of the
telemetry (velocity relative to the air, temperature, hinge angles), scaled by each row's density, and
their derivatives with respect to the materials' accommodation coefficients, to first order about an
anchor (the gas-surface laws are not linear in them: the fit runs the model again at its solution, as
with inter-reflected light).

>>> DENSITY_REF_KG_M3
1e-12
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.drag import drag
from sunwind.forces.fit.forward import Geometry
from sunwind.forces.fit.telemetry import Telemetry
from sunwind.forces.gas.atmosphere import explicit
from sunwind.forces.model import Model
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.sensitivity import ACCOMMODATIONS

#: The density [kg/m^3] the model runs at; each row's drag is scaled by its own over this.
DENSITY_REF_KG_M3 = 1e-12
#: Speeds [m/s] and temperatures [K] closer than these share one run.
SPEED_STEP_M_S, TEMPERATURE_STEP_K = 1.0, 1.0


@dataclass(frozen=True)
class FlowGeometry:
    """The distinct flows of a telemetry and the row each belongs to.

    Attributes
    ----------
    row_group : (n,) int64
    velocity_m_s : (g, 3) float64
        Mean velocity relative to the air of each flow, body frame.
    temperature_K : (g,) float64
    angles : tuple of dict
        Hinge angles [deg] of each flow.
    scale : (n,) float64
        Each row's density over :data:`DENSITY_REF_KG_M3`.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.fit.telemetry import Telemetry
    >>> flow = {"velocity_m_s": np.tile([7600.0, 0, 0], (2, 1)), "density_kg_m3": np.full(2, 2e-12),
    ...         "temperature_K": np.full(2, 900.0)}
    >>> t = Telemetry(np.arange(2.0), np.tile([0.0, 0, 1], (2, 1)), np.full(2, 1361.0), np.ones(2),
    ...               {"accel": np.zeros((2, 3))}, flow=flow)
    >>> geometry = FlowGeometry.of(t, Geometry.of(None, t))
    >>> len(geometry), geometry.scale.tolist()
    (1, [2.0, 2.0])
    """

    row_group: NDArray[np.int64]
    velocity_m_s: NDArray[np.float64]
    temperature_K: NDArray[np.float64]
    angles: tuple[dict[str, float], ...]
    scale: NDArray[np.float64]

    @classmethod
    def of(cls, telemetry: Telemetry, geometry: Geometry, resolution_deg: float = 0.01) -> FlowGeometry:
        """Group the rows of ``telemetry`` by flow.

        Parameters
        ----------
        telemetry : Telemetry
            With drag columns (``telemetry.flow``).
        geometry : Geometry
            The rows' Sun geometries, whose hinge angles the flows take.
        resolution_deg : float
            Directions within this angle [deg] share a flow.

        Returns
        -------
        FlowGeometry
        """
        flow = telemetry.flow
        assert flow is not None
        velocity = flow["velocity_m_s"]
        speed = np.linalg.norm(velocity, axis=1)
        step = np.radians(resolution_deg) if resolution_deg > 0 else 0.0
        direction = velocity / np.where(speed > 0, speed, 1.0)[:, None]
        poses = {key: k for k, key in enumerate(dict.fromkeys(tuple(a.items()) for a in geometry.angles))}
        pose = np.array([poses[tuple(geometry.angles[g].items())] for g in geometry.row_group], float)
        keys = np.column_stack(
            [
                np.round(direction / step) if step else direction,
                np.round(speed / SPEED_STEP_M_S),
                np.round(flow["temperature_K"] / TEMPERATURE_STEP_K),
                pose,
            ]
        )
        _, first, group = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        order = np.argsort(first)
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        group = rank[group.ravel()]
        count = np.bincount(group).astype(float)
        mean_velocity = np.zeros((len(count), 3))
        np.add.at(mean_velocity, group, velocity)
        mean_temperature = np.bincount(group, flow["temperature_K"]) / count
        angles = tuple(
            geometry.angles[geometry.row_group[np.flatnonzero(group == g)[0]]] for g in range(len(count))
        )
        return cls(
            group.astype(np.int64),
            mean_velocity / count[:, None],
            mean_temperature,
            angles,
            flow["density_kg_m3"] / DENSITY_REF_KG_M3,
        )

    def __len__(self) -> int:
        return len(self.velocity_m_s)


def with_accommodations(model: Model, accommodations: NDArray[np.float64]) -> Model:
    """``model`` with every material's accommodation coefficients set to the rows of ``accommodations``.

    Parameters
    ----------
    model : Model
    accommodations : (n_materials, 3) float64
        Energy, normal and tangential accommodation of each material.

    Returns
    -------
    Model

    Examples
    --------
    >>> import numpy as np, sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5), threads=1)
    >>> with_accommodations(model, np.array([[0.9, 1.0, 1.0]])).craft.materials.gas[0].energy_accommodation
    0.9
    """
    craft = model.craft
    gas = tuple(
        replace(g, **{name: float(value) for name, value in zip(ACCOMMODATIONS, row, strict=True)})
        for g, row in zip(craft.materials.gas, accommodations, strict=True)
    )
    return replace(model, craft=replace(craft, materials=replace(craft.materials, gas=gas)))


def accommodations_of(model: Model) -> NDArray[np.float64]:
    """The accommodation coefficients of every material, (n_materials, 3).

    Parameters
    ----------
    model : Model

    Returns
    -------
    (n_materials, 3) float64

    Examples
    --------
    >>> import sunwind as sw
    >>> accommodations_of(sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5))).tolist()
    [[1.0, 1.0, 1.0]]
    """
    return np.array([[getattr(g, name) for name in ACCOMMODATIONS] for g in model.craft.materials.gas], float)


class LinearDrag:
    """Drag loads at any accommodations, to first order from one run with sensitivities at an anchor.

    Parameters
    ----------
    model : Model
    geometry : FlowGeometry
    anchor : (n_materials, 3) float64
        The accommodations to run at.
    settings : ReflectionSettings
        Re-emission of molecules.
    composition : str or mapping
        Mole fractions of the air (``"O:1"``, ``"O:0.7,N2:0.3"``).

    Examples
    --------
    >>> import numpy as np, sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5), threads=1)
    >>> geometry = FlowGeometry(np.zeros(1, int), np.array([[7600.0, 0, 0]]), np.full(1, 900.0), ({},),
    ...                         np.ones(1))
    >>> settings = ReflectionSettings.of("none")
    >>> drag_model = LinearDrag(model, geometry, accommodations_of(model), settings, "O:1")
    >>> loads, partials = drag_model.at(accommodations_of(model))
    >>> bool(loads[0, 0] < 0), partials.shape  # drag against the velocity
    (True, (1, 1, 3, 6))
    """

    def __init__(
        self,
        model: Model,
        geometry: FlowGeometry,
        anchor: NDArray[np.float64],
        settings: ReflectionSettings,
        composition: str | Mapping[str, float],
    ) -> None:
        self.anchor = np.array(anchor, dtype=np.float64)
        n_materials = len(model.craft.materials)
        self.loads = np.zeros((len(geometry), 6))
        self.partials = np.zeros((len(geometry), n_materials, 3, 6))
        anchored = with_accommodations(model, self.anchor)
        runs: dict[tuple, list[int]] = {}
        for g, angles in enumerate(geometry.angles):
            runs.setdefault((tuple(sorted(angles.items())), float(geometry.temperature_K[g])), []).append(g)
        for (pose, temperature), groups in runs.items():
            air = explicit(DENSITY_REF_KG_M3, temperature, composition)
            batch = drag(
                anchored.posed(dict(pose)),
                geometry.velocity_m_s[groups],
                air,
                reflections=settings,
                sensitivities=True,
            )
            for g, result in zip(groups, batch, strict=True):
                self.loads[g] = np.concatenate([result.force_N, result.torque_Nm])
                s = result.sensitivities
                self.partials[g] = np.concatenate([s.force_N[:, 4:], s.torque_Nm[:, 4:]], axis=2)

    def at(self, accommodations: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The loads (g, 6) and their derivatives (g, n_materials, 3, 6) at ``accommodations``.

        Parameters
        ----------
        accommodations : (n_materials, 3) float64

        Returns
        -------
        loads, derivatives : ndarray
        """
        loads = self.loads + np.einsum("mk,gmkc->gc", accommodations - self.anchor, self.partials)
        return loads, self.partials
