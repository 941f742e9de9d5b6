"""Molecules re-emitted by one side that strike another, and what of them escapes (METHOD.md
"Free-molecular flow", "Inter-reflection").

The paper treats re-emitted molecules as diffuse light with ``rho = 1``: the same view factors ``F``,
the same escape vectors, the same balance ``(I - F^T) W = S`` in molecules per second. A diffusely
re-emitted molecule of mass ``m`` at temperature ``T`` leaves along a cosine-law direction with mean
speed ``(3 sqrt(pi)/4) sqrt(2 k T / m)``, so a stream of ``N`` molecules per second carries momentum
``N m v_mean`` spread like diffuse light: what escapes is ``N m v_mean e_esc`` (``(2/3) N m v_mean n``
from a side that sees only sky, which is the re-emission term of the panel law).

* First re-emission: side ``i`` re-emits ``N_ik`` molecules of species ``k`` at the temperature its
  gas-surface law gives (``T_r``). The panel law let all of them escape as from an open plate; here
  only ``e_esc,i`` escapes, the rest lands on other sides.
* Later re-emissions: a molecule that lands on side ``j`` after a first bounce is re-emitted at the
  wall temperature ``T_w,j`` (it arrives already slowed to about the temperature of the side that sent
  it; exact for full energy accommodation ``alpha_E = 1``, an approximation otherwise).

The molecules a side sends through later bounces escape as ``sum_j W_j sqrt(m) c_w,j e_esc,j`` with
``c_w,j = (3 sqrt(pi)/4) sqrt(2 k T_w,j)``, linear in what the first re-emission lands, so the
escaping force and torque per model are ``h^T (sum_k sqrt(m_k) N_k)`` with ``h = F M^-T w`` solved
once per model, view factors and wall temperatures (METHOD.md "Speed").
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
    """Mean momentum [kg m/s] of a molecule diffusely re-emitted at ``temperature_K``."""
    return MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * np.asarray(temperature_K) * mass_kg)


@dataclass(frozen=True)
class ExchangeTotals:
    """What the molecular exchange changes in the panel law's force and torque; body frame, SI."""

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]


class MolecularExchange:
    """The exchange of re-emitted molecules between the sides of one model (``rho = 1``).

    Parameters
    ----------
    craft : Spacecraft
    view : ViewFactors
        View factors of ``craft``'s sides.
    """

    def __init__(self, craft: Spacecraft, view: ViewFactors) -> None:
        self.craft = craft
        self.view = view
        self.balance = DiffuseExchange(craft, view, re_emit_all=True)
        wall_speed = MEAN_SPEED_FACTOR * np.sqrt(2.0 * BOLTZMANN * craft.side_gas["wall_temperature_K"])
        moment = np.cross(craft.side_centroids, view.escape_vector) + view.escape_moment
        weights = wall_speed[:, None] * np.column_stack([view.escape_vector, moment])
        #: (n_sides, 6): escaping momentum [kg m/s per sqrt(kg)] and its moment about the origin
        #: of every later bounce, per sqrt(kg)-weighted molecule the first re-emission sends from a side
        self.later = np.asarray(view.matrix @ self.balance.adjoint(weights))
        open_vector = view.escape_vector - LAMBERT_FACTOR * craft.side_normals
        #: (n_sides, 6): what escapes of a side's first re-emission beyond the open-plate assumption,
        #: per unit momentum re-emitted, and its moment about the origin
        self.first = np.column_stack(
            [open_vector, np.cross(craft.side_centroids, open_vector) + view.escape_moment]
        )

    def totals(
        self,
        momentum_emitted: NDArray[np.float64],
        root_mass_emitted: NDArray[np.float64],
        reference_m: NDArray[np.float64],
    ) -> ExchangeTotals:
        """Correction to the panel law for one attitude.

        Parameters
        ----------
        momentum_emitted : (n_sides,)
            ``sum_k N_ik m_k v_mean(T_r,ik)``: momentum per second of each side's first re-emission [N].
        root_mass_emitted : (n_sides,)
            ``sum_k N_ik sqrt(m_k)``: molecules per second of the first re-emission, weighted by the
            square root of their mass [sqrt(kg)/s].
        reference_m : (3,)
            Torque reference point [m].
        """
        escaping = _escaping(self.first, momentum_emitted, self.later, root_mass_emitted)
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


def gas_interference_criterion(craft: Spacecraft, view: ViewFactors) -> float:
    """``K_IS`` of eq. (7) for molecules (``rho = 1`` on every side): re-emitted molecules that meet
    the spacecraft again over those that escape; 0 for a convex body."""
    escaping = float(np.einsum("i,i->", craft.side_areas, view.escape_fraction))
    returning = float(np.einsum("i,i->", craft.side_areas, 1.0 - view.escape_fraction))
    if returning <= 0.0:
        return 0.0
    return returning / escaping if escaping > 0 else float("inf")


def molecular_exchange(craft: Spacecraft, settings: ReflectionSettings) -> MolecularExchange:
    """The :class:`MolecularExchange` of ``craft`` with its view factors for ``settings``, built once
    and kept in its cache."""
    return craft.cache.get(
        ("molecular exchange", *settings.view_key),
        lambda: MolecularExchange(craft, model_view_factors(craft, settings)),
    )
