"""The result of one attitude: forces, torques, areas and how they were obtained, body frame, SI."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.radiation.law import surface_forces
from sunwind.forces.reflection.plan import PowerBalance, Reflected, ReflectionSettings, interference
from sunwind.geometry.rays.shadows import Illumination
from sunwind.geometry.spacecraft import Spacecraft

FRAME = "body frame of the mesh"


@dataclass(frozen=True, eq=False)
class SrpResult:
    """Solar-radiation pressure at one attitude; body frame, SI units.

    Attributes
    ----------
    sun_vector : (3,) float64
        Unit vector from the spacecraft toward the Sun.
    flux_W_m2 : float
        Solar flux at the spacecraft.
    pressure_Pa : float
        ``P = flux / c``.
    force_N : (3,) float64
        Total force: direct plus reflected.
    torque_Nm : (3,) float64
        Total torque about ``reference_point_m``: direct plus reflected.
    direct_force_N, direct_torque_Nm : (3,) float64
        The direct law, eq. (4), on the lit sides: every reflected or transmitted photon escapes.
    reflected : Reflected
        What inter-reflection changes: force, torque, power balance, chain and view-factor details.
    settings : ReflectionSettings
        The inter-reflection settings asked for.
    reference_point_m : (3,) float64
        Point the torque is taken about.
    reference_point : str
        Where it came from: "user", "volume centroid" or "area centroid".
    lit_area_m2 : float
        Area of all lit side parts.
    projected_area_m2 : float
        Lit area projected on the plane normal to the Sun vector: the shadow the spacecraft casts.
    rays : int
        Shadow rays cast.
    sampling : str
        How sides were sampled for shadowing.
    craft : Spacecraft
        The model evaluated.
    illumination : Illumination
        Lit share and lit centroid of every side.

    Per-side and per-facet forces and torques (of the direct law) are computed on first access.
    """

    sun_vector: NDArray[np.float64]
    flux_W_m2: float
    pressure_Pa: float
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    direct_force_N: NDArray[np.float64]
    direct_torque_Nm: NDArray[np.float64]
    reflected: Reflected
    settings: ReflectionSettings
    reference_point_m: NDArray[np.float64]
    reference_point: str
    lit_area_m2: float
    projected_area_m2: float
    rays: int
    sampling: str
    craft: Spacecraft = field(repr=False)
    illumination: Illumination = field(repr=False)

    @property
    def reflected_force_N(self) -> NDArray[np.float64]:
        """Force inter-reflection adds to the direct force [N], (3,)."""
        return self.reflected.force_N

    @property
    def reflected_torque_Nm(self) -> NDArray[np.float64]:
        """Torque inter-reflection adds to the direct torque [N m], (3,)."""
        return self.reflected.torque_Nm

    @property
    def reflections(self) -> str:
        """Inter-reflection included: "none", "specular" or "full" ("auto" resolved)."""
        return self.reflected.mode

    @property
    def power(self) -> PowerBalance:
        """Incident, absorbed and escaped power [W]."""
        return self.reflected.power

    @cached_property
    def k_is(self) -> float:
        """Interference criterion ``K_IS`` of eq. (7) (computes the view factors if not yet done)."""
        if self.reflected.k_is is not None:
            return self.reflected.k_is
        return interference(self.craft, self.settings)

    @property
    def side_lit_fraction(self) -> NDArray[np.float64]:
        """Lit share of each side's area, (n_sides,)."""
        return self.illumination.lit_fraction

    @cached_property
    def side_force_N(self) -> NDArray[np.float64]:
        """Direct force on each side [N], (n_sides, 3), by eq. (4) on its lit area."""
        craft, light = self.craft, self.illumination
        lit = np.flatnonzero(light.lit_fraction > 0)
        rho, beta, sigma = craft.side_optics[lit].T
        forces = np.zeros((craft.n_sides, 3))
        forces[lit] = surface_forces(
            craft.side_normals[lit],
            craft.side_areas[lit] * light.lit_fraction[lit],
            light.cos_incidence[lit],
            rho,
            beta,
            sigma,
            self.sun_vector,
            self.pressure_Pa,
        )
        return forces

    @cached_property
    def side_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of each side's direct force about the reference point [N m], (n_sides, 3)."""
        return np.cross(self.illumination.lit_centroid - self.reference_point_m, self.side_force_N)

    @property
    def facet_force_N(self) -> NDArray[np.float64]:
        """Direct force on each facet, both sides summed [N], (n_facets, 3)."""
        return _per_facet(self.craft.side_facet, self.side_force_N, self.craft.n_facets)

    @property
    def facet_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of each facet's direct force about the reference point [N m], (n_facets, 3)."""
        return _per_facet(self.craft.side_facet, self.side_torque_Nm, self.craft.n_facets)

    @property
    def sun_azel_deg(self) -> tuple[float, float]:
        """Azimuth ``atan2(y, x)`` and elevation ``asin(z)`` of the Sun vector [deg]."""
        x, y, z = self.sun_vector
        return float(np.degrees(np.arctan2(y, x))), float(np.degrees(np.arcsin(np.clip(z, -1, 1))))

    def to_json(self) -> dict:
        """Plain-JSON summary; keys carry their units."""
        az, el = self.sun_azel_deg
        return {
            "frame": FRAME,
            "sun_vector": self.sun_vector.tolist(),
            "sun_azimuth_deg": az,
            "sun_elevation_deg": el,
            "flux_W_m2": self.flux_W_m2,
            "pressure_Pa": self.pressure_Pa,
            "force_N": self.force_N.tolist(),
            "torque_Nm": self.torque_Nm.tolist(),
            "direct": {"force_N": self.direct_force_N.tolist(), "torque_Nm": self.direct_torque_Nm.tolist()},
            "reflected": {
                "force_N": self.reflected_force_N.tolist(),
                "torque_Nm": self.reflected_torque_Nm.tolist(),
            },
            "reflections": self.reflections,
            "reflections_requested": self.settings.mode,
            "k_is": self.k_is,
            "power": self.power.to_json(),
            "reference_point_m": self.reference_point_m.tolist(),
            "reference_point": self.reference_point,
            "lit_area_m2": self.lit_area_m2,
            "projected_area_m2": self.projected_area_m2,
            "rays": self.rays,
            "sampling": self.sampling,
            **self._reflection_details(),
        }

    def _reflection_details(self) -> dict:
        """How the reflected part was computed, for the JSON summary."""
        details: dict = {}
        chains, view = self.reflected.chains, self.reflected.view
        if chains is not None:
            details["reflection_rays"] = chains.rays
            details["reflection_depth"] = chains.depth
            details["reflection_cutoff"] = self.settings.cutoff
        if view is not None and self.reflections == "full":
            details["view_factors"] = {
                "rays_per_side": view.rays_per_side,
                "seed": view.seed,
                "origin": view.origin,
                "seconds": view.seconds,
            }
        return details


def _per_facet(side_facet: NDArray[np.int64], values: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """Sum per-side vectors (n_sides, 3) onto their facets, (n, 3)."""
    return np.stack([np.bincount(side_facet, weights=values[:, k], minlength=n) for k in range(3)], axis=1)
