"""The forward model of a fit: SRP force and torque at every distinct geometry of the telemetry, and
their derivatives with respect to the free coefficients, for any values of those coefficients.

Rows whose body-frame Sun directions and hinge angles agree to within a resolution share one
evaluation (at their mean direction and angles); the flux and the solar fraction scale the result
(SRP is proportional to both), so the model runs at the flux at 1 au
(:data:`~sunwind.forces.radiation.law.SOLAR_FLUX_1AU`) once per geometry.

With ``reflections`` ``none`` or ``plates`` (or ``auto`` resolved to ``none``) the result is exactly
linear in each material's shares ``(absorbed, specular, diffuse, transmitted) = (1 - rho - sigma,
rho beta, rho (1 - beta), sigma)`` (METHOD.md "Direct solar pressure"). One evaluation with
sensitivities then gives everything (:class:`LinearForward`): the three derivatives with respect to
``(rho, beta, sigma)`` span the shares' plane (their sum is 1), so the result at other coefficients is
the result at the anchor plus the change of the shares times their basis. With inter-reflection the
model is first order in the shares about the anchor: the fit is solved on it, the model run again at
the solution, and so on until the solution stays (a Gauss-Newton iteration whose every step is a whole
fit, a handful of model runs in all).

>>> import numpy as np
>>> shares(np.array([0.5]), np.array([0.2]), np.array([0.1]))
array([[0.4, 0.1, 0.4, 0.1]])
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.fit.telemetry import Telemetry
from sunwind.forces.model import Model
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.forces.reflection import ReflectionSettings, reflection_plan
from sunwind.forces.sensitivity import optics_partials
from sunwind.forces.srp import srp
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling

#: Default angle [deg] within which two rows' Sun directions (and hinge angles) share one evaluation.
RESOLUTION_DEG = 0.01
#: A material's reflectivity below this is moved up for the one linear evaluation (its specular
#: fraction has no effect at ``rho = 0``, so the derivatives would not span the shares).
ANCHOR_MIN_RHO = 0.05


def shares(rho: NDArray, beta: NDArray, sigma: NDArray) -> NDArray[np.float64]:
    """The shares ``(absorbed, specular, diffuse, transmitted)`` of optics, (n, 4).

    Parameters
    ----------
    rho, beta, sigma : (n,) float64
        Reflectivity, specular fraction, transmissivity.

    Returns
    -------
    (n, 4) float64

    Examples
    --------
    >>> shares(np.array([1.0]), np.array([1.0]), np.array([0.0]))
    array([[0., 1., 0., 0.]])
    """
    return np.stack([1.0 - rho - sigma, rho * beta, rho * (1.0 - beta), sigma], axis=1)


@dataclass(frozen=True)
class Geometry:
    """The distinct geometries of a telemetry and the row each belongs to.

    Attributes
    ----------
    row_group : (n,) int64
        The geometry of each row.
    sun_body : (g, 3) float64
        Unit Sun direction of each geometry (the mean of its rows').
    angles : tuple of dict
        Hinge angles [deg] of each geometry (empty dicts without hinges).
    scale : (n,) float64
        Each row's flux times its solar fraction over the flux at 1 au
        (:data:`~sunwind.forces.radiation.law.SOLAR_FLUX_1AU`).

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.fit.telemetry import Telemetry
    >>> t = Telemetry(np.arange(3.0), np.tile([0.0, 0, 1], (3, 1)), np.full(3, 1361.0), np.ones(3),
    ...               {"torque": np.zeros((3, 3))})
    >>> Geometry.of(None, t).sun_body
    array([[0., 0., 1.]])
    """

    row_group: NDArray[np.int64]
    sun_body: NDArray[np.float64]
    angles: tuple[dict[str, float], ...]
    scale: NDArray[np.float64]

    @classmethod
    def of(
        cls, model: Model | None, telemetry: Telemetry, resolution_deg: float = RESOLUTION_DEG
    ) -> Geometry:
        """Group the rows of ``telemetry`` by geometry.

        Parameters
        ----------
        model : Model or None
            The model whose hinges the rows turn (tracking ones to each row's Sun, scheduled ones to
            its time, those of ``hinge:GLOB`` columns to theirs); None: no hinges.
        telemetry : Telemetry
        resolution_deg : float
            Rows within this angle [deg] share a geometry; 0: only identical ones.

        Returns
        -------
        Geometry

        Raises
        ------
        InputError
            A ``hinge:GLOB`` column naming no hinge of the model.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.forces.fit.telemetry import Telemetry
        >>> sun = np.array([[1.0, 0, 0], [1.0, 1e-7, 0], [0, 1.0, 0]])
        >>> t = Telemetry(np.arange(3.0), sun, np.full(3, 1361.0), np.ones(3), {"torque": np.zeros((3, 3))})
        >>> Geometry.of(None, t).row_group.tolist()
        [0, 0, 1]
        """
        hinges = model.hinges if model is not None else ()
        names = [hinge.pattern for hinge in hinges]
        unknown = [glob for glob in telemetry.hinges if glob not in names]
        if unknown:
            raise InputError(
                f"column hinge:{unknown[0]} names no hinge of the model",
                path=telemetry.source,
                hint=f"the hinges are: {', '.join(names) or 'none'} (materials file [articulation])",
            )
        n = len(telemetry)
        angles = np.zeros((n, len(names)))
        if names:
            for k in range(n):
                own = model.angles_at(telemetry.sun_body[k], float(telemetry.time_s[k]))  # type: ignore[union-attr]
                angles[k] = [own[name] for name in names]
            for j, name in enumerate(names):
                if name in telemetry.hinges:
                    angles[:, j] = telemetry.hinges[name]
        step = np.radians(resolution_deg) if resolution_deg > 0 else 0.0
        keys = np.concatenate([telemetry.sun_body, np.radians(angles)], axis=1)
        keys = np.round(keys / step) if step else keys
        _, first, row_group = np.unique(keys, axis=0, return_index=True, return_inverse=True)
        row_group = row_group.ravel()
        order = np.argsort(first)  # geometries in the order of their first rows
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        row_group = rank[row_group]
        count = np.bincount(row_group)
        sun = np.zeros((len(count), 3))
        np.add.at(sun, row_group, telemetry.sun_body)
        sun /= np.linalg.norm(sun, axis=1, keepdims=True)
        mean_angles = np.zeros((len(count), len(names)))
        np.add.at(mean_angles, row_group, angles)
        mean_angles /= count[:, None]
        poses = tuple({name: float(a) for name, a in zip(names, row, strict=True)} for row in mean_angles)
        scale = telemetry.flux_W_m2 * telemetry.solar_fraction / SOLAR_FLUX_1AU
        return cls(row_group.astype(np.int64), sun, poses, scale)

    def __len__(self) -> int:
        return len(self.sun_body)


def with_optics(model: Model, optics: NDArray[np.float64]) -> Model:
    """``model`` with every material's ``(rho, beta, sigma)`` set to the rows of ``optics``.

    Parameters
    ----------
    model : Model
    optics : (n_materials, 3) float64

    Returns
    -------
    Model
        A copy with its own (empty) cache; view factors come back from the disk cache.

    Examples
    --------
    >>> import numpy as np, sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5), threads=1)
    >>> with_optics(model, np.array([[0.2, 0.1, 0.0]])).craft.materials.rho
    array([0.2])
    """
    craft = model.craft
    columns = [np.array(optics[:, k], dtype=np.float64) for k in range(3)]
    table = replace(craft.materials, rho=columns[0], beta=columns[1], sigma=columns[2])
    return replace(model, craft=replace(craft, materials=table))


#: Evaluates a model at the geometries: (loads (g, 6), derivatives (g, n_materials, 3, 6)), the six
#: being force [N] then torque [N m] at 1 au, derivatives with respect to each material's optics.
Evaluator = Callable[[Model, Geometry], tuple[NDArray[np.float64], NDArray[np.float64]]]


def evaluator(settings: ReflectionSettings, sampling: ShadowSampling | None = None) -> Evaluator:
    """The evaluation of the model at the geometries, with its sensitivities.

    Parameters
    ----------
    settings : ReflectionSettings
        Inter-reflection of light.
    sampling : ShadowSampling, optional
        The shadow pass's sampling.

    Returns
    -------
    callable
        ``evaluate(model, geometry)`` giving the loads (g, 6) and their derivatives (g, n_materials,
        3, 6) with respect to each material's ``(rho, beta, sigma)``.

    Examples
    --------
    >>> callable(evaluator(ReflectionSettings.of("none")))
    True
    """

    def evaluate(model: Model, geometry: Geometry) -> tuple[NDArray, NDArray]:
        loads = np.zeros((len(geometry), 6))
        partials = np.zeros((len(geometry), len(model.craft.materials), 3, 6))
        poses: dict[tuple, list[int]] = {}
        for g, angles in enumerate(geometry.angles):
            poses.setdefault(tuple(sorted(angles.items())), []).append(g)
        for key, groups in poses.items():
            posed = model.posed(dict(key))
            batch = srp(
                posed,
                geometry.sun_body[groups],
                flux_W_m2=SOLAR_FLUX_1AU,
                reflections=settings,
                sampling=sampling,
                sensitivities=True,
            )
            for g, result in zip(groups, batch, strict=True):
                loads[g] = np.concatenate([result.force_N, result.torque_Nm])
                s = result.sensitivities
                partials[g] = np.concatenate([s.force_N[:, :3], s.torque_Nm[:, :3]], axis=2)
        return loads, partials

    return evaluate


def is_linear(model: Model, settings: ReflectionSettings) -> bool:
    """Whether SRP is linear in the materials' shares with these settings (no inter-reflection).

    Parameters
    ----------
    model : Model
    settings : ReflectionSettings

    Returns
    -------
    bool

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5), threads=1)
    >>> is_linear(model, ReflectionSettings.of("plates")), is_linear(model, ReflectionSettings.of("full"))
    (True, False)
    """
    if settings.mode in ("none", "plates"):
        return True
    if settings.mode != "auto":
        return False
    return reflection_plan(model.craft, settings).mode == "none"


class LinearForward:
    """The loads at any optics from one evaluation with sensitivities at an anchor: exact with no
    inter-reflection (the loads are linear in the shares), first order with it.

    Parameters
    ----------
    model : Model
    geometry : Geometry
    evaluate : Evaluator
    anchor : (n_materials, 3) float64
        The optics to evaluate at (the reflectivity of ``materials`` raised to at least
        :data:`ANCHOR_MIN_RHO`).
    materials : sequence of int
        The materials whose optics may change (the others stay at the anchor's).

    Examples
    --------
    >>> import numpy as np, sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.5, 0.5), threads=1)
    >>> geometry = Geometry(np.zeros(1, int), np.array([[0.0, 0.0, 1.0]]), ({},), np.ones(1))
    >>> fake = lambda m, g: (np.zeros((1, 6)), np.ones((1, 1, 3, 6)))
    >>> forward = LinearForward(model, geometry, fake, np.array([[0.5, 0.5, 0.0]]), [0])
    >>> loads, jac = forward.at(np.array([[0.5, 0.5, 0.0]]))
    >>> loads.shape, jac.shape
    ((1, 6), (1, 1, 3, 6))
    """

    def __init__(
        self,
        model: Model,
        geometry: Geometry,
        evaluate: Evaluator,
        anchor: NDArray[np.float64],
        materials: Sequence[int],
    ) -> None:
        self.materials = list(materials)
        anchor = np.array(anchor, dtype=np.float64)
        for m in self.materials:
            anchor[m, 0] = max(anchor[m, 0], min(ANCHOR_MIN_RHO, 1.0 - anchor[m, 2]))
        self.anchor = anchor
        self.loads, partials = evaluate(with_optics(model, anchor), geometry)
        rho, beta, sigma = anchor.T
        p = optics_partials(rho, beta)  # (n_materials, 3, 4)
        self.basis = {
            m: np.einsum("sk,gkc->gsc", np.linalg.pinv(p[m]), partials[:, m]) for m in self.materials
        }
        self.anchor_shares = shares(rho, beta, sigma)

    def at(self, optics: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The loads (g, 6) and their derivatives (g, n_materials, 3, 6) at ``optics`` (n_materials, 3).

        Parameters
        ----------
        optics : (n_materials, 3) float64

        Returns
        -------
        loads, derivatives : ndarray
        """
        loads = self.loads.copy()
        partials = np.zeros((len(loads), len(optics), 3, 6))
        now = shares(*optics.T)
        p = optics_partials(optics[:, 0], optics[:, 1])
        for m in self.materials:
            loads += np.einsum("s,gsc->gc", now[m] - self.anchor_shares[m], self.basis[m])
            partials[:, m] = np.einsum("ks,gsc->gkc", p[m], self.basis[m])
        return loads, partials
