"""Molecules re-emitted diffusely by one side that strike another, and what of them escapes (METHOD.md
"Molecular chains", "Inter-reflection").

The paper treats re-emitted molecules as diffuse light with ``rho = 1``: the same view factors, the same
escape vectors, the same balance in molecules per second. Here the exchange factors ``E`` of the
molecular optics (``rho = 1``, ``beta`` = the share a side mirrors, :class:`~sunwind.forces.gas.chains.
ChainLaws`) carry a diffusely re-emitted molecule on through mirrors with its speed; ``E = F`` where no
side mirrors. A molecule of mass ``m`` re-emitted diffusely at ``T`` leaves along a cosine-law direction
with mean speed ``(3 sqrt(pi)/4) sqrt(2 k T / m)``, so a stream of ``N`` molecules per second carries
momentum ``N m v_mean`` spread like diffuse light: what escapes is ``N m v_mean e_esc`` (``(2/3) N m
v_mean n`` from a side that sees only sky, which is the re-emission term of the panel law).

* First re-emission: side ``i`` re-emits ``N_ik`` molecules of species ``k`` at the temperature its
  gas-surface law gives (``T_r``). The panel law let all of them escape as from an open plate; here
  only ``e_esc,i`` escapes, the rest lands on other sides. What the chains land on a side and it
  re-emits diffusely is a first re-emission too, of which nothing escaped yet.
* Later re-emissions: a molecule that lands on side ``j`` after a first bounce is re-emitted at the
  wall temperature ``T_w,j`` (it arrives already slowed to about the temperature of the side that sent
  it; exact for full energy accommodation ``alpha_E = 1``, an approximation otherwise), the share
  ``rho_d,j`` it does not mirror.

The molecules a side sends through later bounces escape as ``sum_j W_j sqrt(m) c_w,j e_esc,j`` with
``c_w,j = (3 sqrt(pi)/4) sqrt(2 k T_w,j)``, linear in what the first re-emission lands, so the
escaping force and torque per model are ``h^T (sum_k sqrt(m_k) N_k)`` with ``h = E diag(rho_d) M^-T w``
solved once per model, view factors and materials (METHOD.md "Speed").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.forces.gas.atmosphere import BOLTZMANN
from sunwind.forces.radiation.law import LAMBERT_FACTOR
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.forces.reflection.views import model_view_factors
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import ViewFactors

#: Mean speed of molecules effusing from a Maxwellian at ``T``: ``MEAN_SPEED_FACTOR sqrt(2 k T / m)``.
MEAN_SPEED_FACTOR = 3.0 * math.sqrt(math.pi) / 4.0


def mean_momentum(temperature_K: NDArray | float, mass_kg: float) -> NDArray | float:
    """Mean momentum [kg m/s] of a molecule diffusely re-emitted at ``temperature_K``.

    Molecules effusing from a Maxwellian at ``T`` have the mean speed ``(3 sqrt(pi)/4) sqrt(2 k T / m)``.

    Parameters
    ----------
    temperature_K : float or ndarray
        Temperature of the re-emission [K].
    mass_kg : float
        Molecular mass [kg].

    Returns
    -------
    float or ndarray
        ``m`` times the mean speed [kg m/s], the shape of ``temperature_K``.

    Examples
    --------
    >>> import numpy as np
    >>> (mean_momentum(np.array([300.0, 1200.0]), 2.66e-26) / 1e-23).round(4)
    array([1.9733, 3.9466])
    """
    return MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * np.asarray(temperature_K) * mass_kg)


@dataclass(frozen=True)
class ExchangeTotals:
    """What the molecular exchange changes in the panel law's force and torque; body frame, SI.

    Parameters
    ----------
    force_N : (3,) float64
        Change of the force [N].
    torque_Nm : (3,) float64
        Change of the torque about the reference point [N m].

    Examples
    --------
    >>> import numpy as np
    >>> ExchangeTotals(force_N=np.zeros(3), torque_Nm=np.zeros(3)).force_N
    array([0., 0., 0.])
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]


class MolecularExchange:
    """The exchange of diffusely re-emitted molecules between the sides of one model (``rho = 1``).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    view : ViewFactors
        View factors of ``craft``'s sides.
    mirrored : (n_sides,) float64
        Share of arriving molecules each side sends on mirrored (:class:`~sunwind.forces.gas.chains.
        ChainLaws`); the exchange factors follow diffusely re-emitted molecules through such mirrors.
    cache_dir : path, bool or None
        Where those exchange factors are kept on disk.

    Examples
    --------
    On a convex body nothing a side re-emits lands on another, so the exchange changes nothing:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import ReflectionSettings
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings("full", rays_per_side=16, cache_dir=False)
    >>> exchange = molecular_exchange(craft, settings, np.zeros(craft.n_sides))
    >>> emitted = np.ones(craft.n_sides)
    >>> totals = exchange.totals(emitted, 1e-13 * emitted, np.zeros(3))
    >>> exchange.escape.shape, bool(np.allclose(totals.force_N, 0.0, atol=1e-12))
    ((12, 6), True)
    """

    def __init__(
        self, craft: Spacecraft, view: ViewFactors, mirrored: NDArray[np.float64], cache_dir=False
    ) -> None:
        self.craft = craft
        self.view = view
        self.balance = DiffuseExchange(craft, view, mirrored=mirrored, cache_dir=cache_dir)
        factors = self.balance.factors
        wall_speed = MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * craft.side_gas["wall_temperature_K"])
        moment = np.cross(craft.side_centroids, factors.escape_vector) + factors.escape_moment
        #: (n_sides, 6): escaping momentum (after mirrors) per unit momentum a side re-emits diffusely,
        #: and its moment about the origin
        self.escape = np.column_stack([factors.escape_vector, moment])
        re_emitted = 1.0 - mirrored
        adjoint = self.balance.adjoint(wall_speed[:, None] * self.escape)
        #: (n_sides, 6): escaping momentum [kg m/s per sqrt(kg)] and its moment about the origin of every
        #: later re-emission, per sqrt(kg)-weighted molecule a side's re-emission sends off
        self.later = np.asarray(factors.matrix @ (re_emitted[:, None] * adjoint))
        open_vector = LAMBERT_FACTOR * craft.side_normals
        #: (n_sides, 6): what the panel law let escape of a unit of momentum re-emitted, and its moment
        self.open_plate = np.column_stack([open_vector, np.cross(craft.side_centroids, open_vector)])

    def totals(
        self,
        momentum_emitted: NDArray[np.float64],
        root_mass_emitted: NDArray[np.float64],
        reference_m: NDArray[np.float64],
        landed: NDArray[np.float64] | None = None,
    ) -> ExchangeTotals:
        """Correction to the panel law for one attitude.

        Parameters
        ----------
        momentum_emitted : (n_sides,)
            ``sum_k N_ik m_k v_mean(T_r,ik)``: momentum per second of each side's first re-emission [N],
            which the panel law let escape as from an open plate.
        root_mass_emitted : (n_sides,)
            ``sum_k N_ik sqrt(m_k)``: molecules per second of the first re-emission, weighted by the
            square root of their mass [sqrt(kg)/s].
        reference_m : (3,)
            Torque reference point [m].
        landed : (2, n_sides), optional
            The same two rates of the diffuse re-emission of molecules the chains brought
            (:class:`~sunwind.forces.gas.chains.MoleculeChainTotals`), which nothing has let escape yet.

        Returns
        -------
        ExchangeTotals
            Change of the panel law's force [N] and torque about ``reference_m`` [N m].

        Examples
        --------
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.reflection import ReflectionSettings
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
        >>> settings = ReflectionSettings("full", rays_per_side=16, cache_dir=False)
        >>> exchange = molecular_exchange(craft, settings, np.zeros(craft.n_sides))
        >>> emitted = np.ones(craft.n_sides)
        >>> totals = exchange.totals(emitted, 1e-13 * emitted, np.zeros(3))
        >>> totals.force_N.shape, totals.torque_Nm.shape
        ((3,), (3,))
        """
        momentum, root_mass = momentum_emitted, root_mass_emitted
        if landed is not None:
            momentum, root_mass = momentum + landed[0], root_mass + landed[1]
        escaping = _escaping(self.escape, momentum, self.later, root_mass)
        escaping -= _escaping(self.open_plate, momentum_emitted, self.later, np.zeros_like(root_mass))
        momentum, moment = escaping[0:3], escaping[3:6]
        return ExchangeTotals(force_N=-momentum, torque_Nm=-(moment - np.cross(reference_m, momentum)))


@numba.njit(cache=True, nogil=True)
def _escaping(
    first: NDArray[np.float64],
    momentum: NDArray[np.float64],
    later: NDArray[np.float64],
    root_mass: NDArray[np.float64],
) -> NDArray[np.float64]:
    """``first^T momentum + later^T root_mass``, (6,), summed side by side (one pass, no BLAS threads)."""
    out = np.zeros(first.shape[1])
    for i in range(first.shape[0]):
        for c in range(first.shape[1]):
            out[c] += first[i, c] * momentum[i] + later[i, c] * root_mass[i]
    return out


def open_plate_recoil(
    craft: Spacecraft, momentum_emitted: NDArray[np.float64], reference_m: NDArray[np.float64]
) -> ExchangeTotals:
    """Recoil of the molecules each side re-emits diffusely when all of them leave as from an open plate.

    That is ``(2/3) n`` per unit momentum, as the panel law lets the first re-emission leave: what the
    chains land is re-emitted so in ``specular`` mode, which exchanges nothing between sides.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    momentum_emitted : (n_sides,) float64
        Momentum per second each side re-emits diffusely [N] (the chains' ``deposit[0]``).
    reference_m : (3,) float64
        Torque reference point [m].

    Returns
    -------
    ExchangeTotals
        Force [N] and torque about ``reference_m`` [N m].

    Examples
    --------
    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1)
    >>> craft = model.craft
    >>> side = int(np.argmax(craft.side_normals[:, 2]))  # a side facing +z
    >>> emitted = np.zeros(craft.n_sides)
    >>> emitted[side] = 3.0
    >>> open_plate_recoil(craft, emitted, craft.side_centroids[side]).force_N.round(12) + 0.0
    array([ 0.,  0., -2.])
    """
    escaping = LAMBERT_FACTOR * momentum_emitted[:, None] * craft.side_normals
    lever = craft.side_centroids - reference_m
    return ExchangeTotals(force_N=-escaping.sum(axis=0), torque_Nm=-np.cross(lever, escaping).sum(axis=0))


def molecular_exchange(
    craft: Spacecraft, settings: ReflectionSettings, mirrored: NDArray[np.float64]
) -> MolecularExchange:
    """Molecular exchange of ``craft`` for ``settings``, built once and kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        The view factors' sampling and disk cache.
    mirrored : (n_sides,) float64
        Share of arriving molecules each side sends on mirrored (fixed by its materials).

    Returns
    -------
    MolecularExchange
        The exchange of diffusely re-emitted molecules between ``craft``'s sides.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> from sunwind.forces.reflection import ReflectionSettings
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings("full", rays_per_side=16, cache_dir=False)
    >>> exchange = molecular_exchange(craft, settings, np.zeros(craft.n_sides))
    >>> emitted = np.ones(craft.n_sides)
    >>> totals = exchange.totals(emitted, 1e-13 * emitted, np.zeros(3))
    >>> molecular_exchange(craft, settings, np.zeros(craft.n_sides)) is exchange
    True
    """
    return craft.cache.get(
        ("molecular exchange", *settings.view_key),
        lambda: MolecularExchange(
            craft, model_view_factors(craft, settings), mirrored, cache_dir=settings.cache_dir
        ),
    )
