"""Radiation from the planet below: its albedo and infrared, on the spacecraft with self-shadowing and
inter-reflection, and the power every side absorbs from the Sun, the albedo and the infrared (METHOD.md
"Planet radiation").

The spacecraft sits ``altitude`` above a spherical planet whose centre lies along ``nadir`` (body
frame). Each band's force is its radiance integrated over each side's share of the visible cap
(:class:`~sunwind.forces.planet.cap.Cap`), shadowing and reflections added by cells of the cap about
``cell_deg`` across (:mod:`~sunwind.forces.planet.loads`); sunlight (for the heat budget) is one cell.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.error_estimate import summed
from sunwind.forces.model import Model, as_model
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.planet.cap import Cap, check_cells
from sunwind.forces.planet.loads import (
    BandLoad,
    Source,
    band_loads,
    grid_band_loads,
    solve_reflected,
)
from sunwind.forces.planet.sensitivity import (
    CellShares,
    band_derivatives,
    grid_share_loads,
    planet_sensitivities,
    reflected_derivatives,
)
from sunwind.forces.planet.visibility import Visibility, direction_grid, level_for, visibility
from sunwind.forces.radiation.law import solar_flux
from sunwind.forces.reflection import ReflectionPlan, ReflectionSettings, reflection_plan
from sunwind.forces.reflection.diffuse import DiffuseExchange
from sunwind.forces.result_base import LoadResult
from sunwind.forces.sensitivity import Sensitivities
from sunwind.forces.thermal import ThermalState, infrared_exchange, thermal_model
from sunwind.geometry.directions import unit_vector
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import using_threads
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import Spacecraft, infrared_optics

#: Default size of the cap's cells for shadowing and reflections [deg].
DEFAULT_CELL_DEG = 10.0
#: The ``reflections`` of the plate mode: every side alone, no shadowing or inter-reflection (one of
#: :data:`~sunwind.forces.reflection.settings.MODES`).
PLATES = "plates"
#: The modes whose reflected beams are followed.
BEAM_MODES = ("specular", "full")
#: How the shadowed cap is integrated: over the model's precomputed directional visibility, or by a
#: shadow pass per cell of the cap at every call (the reference).
METHODS = ("visibility", "cells")
#: Altitudes accepted [km]: above the surface, and below 100 times the Moon's distance.
MAX_ALTITUDE_KM = 4.0e7


@dataclass(frozen=True, eq=False)
class PlanetResult(LoadResult):
    """The planet's radiation on the spacecraft at one place and attitude; body frame, SI (a
    :class:`~sunwind.forces.result_base.LoadResult`: ``force_N``, ``torque_Nm``, ``to_json()``,
    ``to_dataset()``).

    Attributes
    ----------
    albedo, infrared : BandLoad
        Force, torque, power balance and per-side power of each band.
    solar : BandLoad
        Sunlight (times the place's ``solar_fraction``), for the heat budget; its force is what
        :func:`~sunwind.forces.srp.srp` gives.
    place : Place
    half_angle_deg : float
        Angular radius of the planet seen from the spacecraft.
    light : PlanetLight
        The planet and its albedo and infrared laws.
    cells : int
        Cells of the cap (shadow directions).
    rays : int
        Shadow and beam rays cast.
    reflections : str
        The inter-reflection mode used ("auto" resolved; "plates" in the plate mode).
    reference_point_m : (3,) float64
        Point the torque is taken about [m], body frame.
    reference_point : str
        Where it came from (as :class:`~sunwind.forces.results.AttitudeResult`).
    craft : Spacecraft
        The model evaluated.
    sensitivities : Sensitivities or None
        d force / d coefficient and d torque / d coefficient of every material, when asked for; else
        None.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> down, up = np.array([0.0, 0.0, -1.0]), np.array([0.0, 0.0, 1.0])
    >>> noon = sw.Place(nadir=down, altitude_km=500.0, sun_vector=up)  # the Sun overhead
    >>> result = sw.planet_radiation(cube, noon, reflections="none")
    >>> bool(result.infrared_force_N[2] > 0), bool(result.albedo_force_N[2] > 0)  # pushed away
    (True, True)
    >>> sorted(result.parts()["box"])
    ['albedo_W', 'area_m2', 'infrared_W', 'reflected_W', 'solar_W']
    """

    albedo: BandLoad
    infrared: BandLoad
    solar: BandLoad
    place: Place
    half_angle_deg: float
    light: PlanetLight
    cells: int
    rays: int
    reflections: str
    reference_point_m: NDArray[np.float64]
    reference_point: str
    craft: Spacecraft = field(repr=False)
    sensitivities: Sensitivities | None = field(default=None, kw_only=True)

    KIND: ClassVar[str] = "planet radiation"
    VARIABLES: ClassVar[tuple[str, ...]] = (
        "force_N",
        "torque_Nm",
        "albedo_force_N",
        "albedo_torque_Nm",
        "infrared_force_N",
        "infrared_torque_Nm",
        "solar_fraction",
        "half_angle_deg",
        "cells",
        "rays",
    )

    @property
    def albedo_force_N(self) -> NDArray[np.float64]:
        """Force of the sunlight the planet reflects [N], (3,)."""
        return self.albedo.force_N

    @property
    def albedo_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of the albedo about the reference point [N m], (3,)."""
        return self.albedo.torque_Nm

    @property
    def infrared_force_N(self) -> NDArray[np.float64]:
        """Force of the planet's infrared [N], (3,)."""
        return self.infrared.force_N

    @property
    def infrared_torque_Nm(self) -> NDArray[np.float64]:
        """Torque of the infrared about the reference point [N m], (3,)."""
        return self.infrared.torque_Nm

    @property
    def solar_fraction(self) -> float:
        """Share of the solar disc in view at the place (0: the planet hides the Sun)."""
        return self.place.solar_fraction

    @property
    def force_N(self) -> NDArray[np.float64]:
        """Albedo plus infrared force [N], (3,)."""
        return self.albedo.force_N + self.infrared.force_N

    @property
    def torque_Nm(self) -> NDArray[np.float64]:
        """Albedo plus infrared torque about the reference point [N m], (3,)."""
        return self.albedo.torque_Nm + self.infrared.torque_Nm

    @property
    def shadow_error(self) -> LoadsError | None:
        """The shadow passes' estimated absolute error in :attr:`force_N` [N] and :attr:`torque_Nm`
        [N m]: the albedo's and the infrared's added (:attr:`BandLoad.shadow_error`); None with fixed
        sampling or plates."""
        return summed([self.albedo.shadow_error, self.infrared.shadow_error])

    def absorbed_side_W(self) -> dict[str, NDArray[np.float64]]:
        """Power each side absorbs [W], (n_sides,) per source: ``solar``, ``albedo``, ``infrared`` as
        they arrive, and ``reflected``: what arrives after reflections, of every band."""
        bands = (self.solar, self.albedo, self.infrared)
        solve_reflected([band.reflections for band in bands])  # the solar and albedo bands in one solve
        return {
            "solar": self.solar.absorbed_side_W,
            "albedo": self.albedo.absorbed_side_W,
            "infrared": self.infrared.absorbed_side_W,
            "reflected": sum(band.reflected_side_W for band in bands),
        }

    def part_absorbed_W(self) -> dict[str, NDArray[np.float64]]:
        """:meth:`absorbed_side_W` summed over each part, (n_parts,) per source, in ``craft.part_names``
        order; the reflected powers by the adjoint of the diffuse balance (no forward solve)."""
        craft = self.craft
        part, count = craft.facet_part[craft.side_facet], len(craft.part_names)
        bands = (self.solar, self.albedo, self.infrared)
        out = {band.name: self.per_part(band.absorbed_side_W) for band in bands}
        out["reflected"] = sum(band.reflections.absorbed_by_group(part, count) for band in bands)
        return out

    def per_part(self, side_values: NDArray[np.float64]) -> NDArray[np.float64]:
        """``side_values`` (n_sides,) summed over the sides of each part, (n_parts,) in
        ``craft.part_names`` order."""
        craft = self.craft
        return np.bincount(craft.facet_part[craft.side_facet], side_values, len(craft.part_names))

    def equilibrium(self, reflections: str | ReflectionSettings = "full") -> ThermalState:
        """Every side's radiative-equilibrium temperature with the power it absorbs here, and the recoil
        of its infrared (:func:`~sunwind.forces.thermal.thermal_model` with ``reflections``: the
        spacecraft's own infrared exchanged through its view factors, or not with ``"none"``).

        Raises
        ------
        MaterialError
            A side's material has no emissivity.
        """
        nodes = thermal_model(self.craft, reflections)
        return nodes.equilibrium(sum(self.absorbed_side_W().values()), self.reference_point_m)

    def part_temperatures(self, temperature_K: NDArray[np.float64]) -> NDArray[np.float64]:
        """Area-weighted mean of the side temperatures ``temperature_K`` [K] (n_sides,) over each part,
        (n_parts,) in ``craft.part_names`` order."""
        areas = self.craft.side_areas
        return self.per_part(areas * temperature_K) / self.per_part(areas)

    def parts(self) -> dict[str, dict[str, float]]:
        """Per part: area [m^2] and the absorbed power of :meth:`absorbed_side_W` summed [W]."""
        table = {"area_m2": self.per_part(self.craft.side_areas)}
        for name, values in self.absorbed_side_W().items():
            table[f"{name}_W"] = self.per_part(values)
        return {
            name: {key: float(column[k]) for key, column in table.items()}
            for k, name in enumerate(self.craft.part_names)
        }

    def to_json(self) -> dict:
        """Plain-JSON summary; keys carry their units."""
        return {
            **super().to_json(),
            "planet": self.light.planet.name,
            "model": self.light.description,
            "nadir": self.place.nadir.tolist(),
            "sun_vector": self.place.sun_vector.tolist(),
            "altitude_km": self.place.altitude_km,
            "half_angle_deg": self.half_angle_deg,
            "flux_W_m2": self.light.solar_flux_W_m2,
            "solar_fraction": self.place.solar_fraction,
            "reflections": self.reflections,
            "cells": self.cells,
            "rays": self.rays,
            "albedo": self.albedo.to_json(),
            "infrared": self.infrared.to_json(),
            "solar": self.solar.to_json(),
            "parts": self.parts(),
        }


def check_altitude(altitude_km: float) -> None:
    """Refuse a height above the planet's surface that is not a number in (0, MAX_ALTITUDE_KM].

    Parameters
    ----------
    altitude_km : float
        Height above the surface [km].

    Raises
    ------
    InputError
        ``altitude_km`` is not a finite number in (0, :data:`MAX_ALTITUDE_KM`] (a bool is refused).

    Examples
    --------
    >>> check_altitude(500.0)
    >>> check_altitude(-1.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: altitude_km -1.0 is not in (0, 4e+07] km; ...
    """
    if (
        isinstance(altitude_km, bool)
        or not isinstance(altitude_km, int | float | np.floating | np.integer)
        or not (math.isfinite(altitude_km) and 0.0 < altitude_km <= MAX_ALTITUDE_KM)
    ):
        raise InputError(
            f"altitude_km {altitude_km} is not in (0, {MAX_ALTITUDE_KM:g}] km",
            hint="give the height above the surface in km, e.g. 500",
            parameters=("altitude_km",),
        )


def check_cell_size(cell_deg: float) -> None:
    """Refuse a cell size of the planet's disc outside (0, 90] degrees.

    Parameters
    ----------
    cell_deg : float
        Size of the cap's cells [deg].

    Raises
    ------
    InputError
        ``cell_deg`` is not a number in (0, 90].

    Examples
    --------
    >>> check_cell_size(10.0)
    >>> check_cell_size(0.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: cell_deg 0.0 is not in (0, 90]; e.g. 10
    """
    number = not isinstance(cell_deg, bool) and isinstance(cell_deg, int | float | np.floating | np.integer)
    if not (number and math.isfinite(cell_deg) and 0.0 < cell_deg <= 90.0):
        raise InputError(f"cell_deg {cell_deg} is not in (0, 90]", hint="e.g. 10", parameters=("cell_deg",))


def check_cells_at(altitude_km: float, cell_deg: float) -> None:
    """Refuse, before any work, a cell size that cuts the Earth's disc into too many cells.

    The Earth's disc seen from ``altitude_km`` has half-angle ``asin(R / (R + h))``;
    :func:`~sunwind.forces.planet.cap.check_cells` counts its cells.

    Parameters
    ----------
    altitude_km : float
        Height above the Earth's surface [km].
    cell_deg : float
        Size of the cap's cells [deg].

    Raises
    ------
    InputError
        Too many cells, naming ``cell_deg``.

    Examples
    --------
    >>> check_cells_at(500.0, 10.0)
    >>> check_cells_at(500.0, 0.1)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: cell_deg 0.1 cuts the planet's disc (68.0 deg half-angle) into ...
    """
    radius = planet("earth").radius_m
    check_cells(math.asin(radius / (radius + altitude_km * 1e3)), cell_deg)


@dataclass(frozen=True)
class CapSampling:
    """How the planet's disc is resolved for shadowing: the step and the method.

    Parameters
    ----------
    cell_deg : float
        Resolution of the shadowing [deg] in (0, 90]: with ``method="visibility"`` the spacing of the
        grid of directions (:func:`~sunwind.forces.planet.visibility.level_for`: 10 gives the 642-node
        grid, 5 the 2562-node one), with ``"cells"`` the size of the cap's cells, one shadow pass each.
        Sides no other side can shadow are exact at any size.
    method : str
        ``"visibility"`` (default): the model's directional visibility, built once per model and
        settings (and kept on disk with the view factors), makes each call a weighted sum with no ray
        cast but the Sun's; its error estimate adds the grid's (the change from the grid a level
        coarser, over 3) to the passes'. ``"cells"``: a shadow pass per cap cell at every call (the
        reference; better for a single call or a model posed anew at each call).

    Raises
    ------
    InputError
        A cell size out of (0, 90] or an unknown method.

    Examples
    --------
    >>> CapSampling(20.0).method
    'visibility'
    >>> CapSampling(5.0, "rays")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: method 'rays' is not one of visibility, cells
    """

    cell_deg: float = DEFAULT_CELL_DEG
    method: str = "visibility"

    def __post_init__(self) -> None:
        check_cell_size(self.cell_deg)
        if self.method not in METHODS:
            raise InputError(
                f"method {self.method!r} is not one of {', '.join(METHODS)}", parameters=("method",)
            )


@dataclass(frozen=True, eq=False)
class Place:
    """Where the spacecraft is relative to the planet and the Sun, in its body frame.

    The directions are normalised when the place is made, and the altitude and solar fraction checked.

    Parameters
    ----------
    nadir : (3,) array_like of float
        Direction from the spacecraft to the planet's centre, body frame (any length but zero).
    altitude_km : float
        Height above the planet's surface [km], in (0, :data:`MAX_ALTITUDE_KM`].
    sun_vector : (3,) array_like of float
        Direction from the spacecraft to the Sun, body frame (any length but zero).
    pole : (3,) array_like of float, optional
        Direction of the planet's north pole, body frame, for latitude-dependent models (Knocke);
        default +z.
    solar_fraction : float, default 1.0
        Share of the solar disc in view, in [0, 1] (0 in the planet's umbra).

    Raises
    ------
    InputError
        A zero or non-finite direction, an altitude out of range, or a solar fraction outside [0, 1].

    Examples
    --------
    >>> import sunwind as sw
    >>> place = sw.Place(nadir=[0.0, 0.0, -2.0], altitude_km=500.0, sun_vector=[3.0, 0.0, 4.0])
    >>> place.nadir, place.sun_vector, place.pole
    (array([ 0.,  0., -1.]), array([0.6, 0. , 0.8]), array([0., 0., 1.]))
    >>> sw.Place([0.0, 0.0, -1.0], 500.0, [1.0, 0.0, 0.0], solar_fraction=1.5)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: solar_fraction 1.5 is not in [0, 1]
    """

    nadir: NDArray[np.float64]
    altitude_km: float
    sun_vector: NDArray[np.float64]
    pole: NDArray[np.float64] | None = None
    solar_fraction: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "nadir", unit_vector(self.nadir, "nadir"))
        object.__setattr__(self, "sun_vector", unit_vector(self.sun_vector, "sun_vector"))
        pole = np.array([0.0, 0.0, 1.0]) if self.pole is None else unit_vector(self.pole, "pole")
        object.__setattr__(self, "pole", pole)
        check_altitude(self.altitude_km)
        if not (math.isfinite(self.solar_fraction) and 0.0 <= self.solar_fraction <= 1.0):
            raise InputError(
                f"solar_fraction {self.solar_fraction} is not in [0, 1]", parameters=("solar_fraction",)
            )


def planet_radiation(
    model: Model | Spacecraft,
    place: Place,
    light: PlanetLight | None = None,
    *,
    reference_point_m: Sequence[float] | NDArray | None = None,
    sampling: ShadowSampling | None = None,
    reflections: str | ReflectionSettings = "auto",
    cap: CapSampling | None = None,
    sensitivities: bool = False,
) -> PlanetResult:
    """Albedo and infrared force and torque from the planet below, and the power each side absorbs
    from them and from the Sun.

    Parameters
    ----------
    model : Model or Spacecraft
    place : Place
        The planet's and the Sun's directions and the altitude.
    light : PlanetLight, optional
        The planet and its albedo and infrared laws (:meth:`PlanetLight.of`: another planet, albedo,
        infrared exitance, Knocke's model, the solar flux); default the Earth at 1 au.
    reference_point_m : (3,) array_like, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        Shadow sampling of every cell, as for :func:`~sunwind.forces.srp.srp`; the result's
        ``error_estimate`` is the error the cells' passes estimate they left (None with fixed
        ``samples``).
    reflections : str or ReflectionSettings
        As for :func:`~sunwind.forces.srp.srp` (:data:`~sunwind.forces.reflection.settings.MODES`);
        ``auto`` decides by the model's ``K_IS``. ``"plates"``: the fast mode of plate models, every
        side an independent plate that sees the whole planet (its exact integrals, the dissertation's
        closed-form view factors), no self-shadowing and no inter-reflection; no ray is cast.
    cap : CapSampling, optional
        The resolution of the shadowing over the planet's disc and the method
        (:class:`CapSampling`); default the 10-degree visibility.
    sensitivities : bool
        Also give the derivatives of ``force_N`` and ``torque_Nm`` with respect to every material's
        reflectivity, specular fraction and transmissivity (the albedo) and emissivity (the infrared):
        exact, from the same shadow passes (:mod:`~sunwind.forces.planet.sensitivity`), about the
        result's reference point; with reflections ``none`` or ``plates`` only, for now.

    Returns
    -------
    PlanetResult

    Raises
    ------
    InputError
        A cell size, sampling or reflections out of range; ``sensitivities`` with reflections whose
        beams or diffuse balance are followed.
    MaterialError
        A side's material has no emissivity.

    Examples
    --------
    >>> import sunwind as sw
    >>> white = sw.Material("white", reflectivity=0.5, specular_fraction=0.5, emissivity=0.8)
    >>> model = sw.load(sw.meshes.box_wing(), uniform=white, threads=1)
    >>> place = sw.Place([0.0, 0.0, -1.0], 500.0, [1.0, 0.0, 0.0])
    >>> result = sw.planet_radiation(model, place, reflections="plates", cap=sw.CapSampling(30.0))
    >>> result.reflections, result.rays, bool(result.force_N[2] > 0)  # pushed away from the planet
    ('plates', 0, True)
    >>> d = sw.planet_radiation(model, place, reflections="plates", sensitivities=True).sensitivities
    >>> bool(d.of("white.emissivity").force_N[2] < 0)  # a darker infrared: less diffuse push
    True
    """
    model = as_model(model)
    craft = model.craft
    band_optics = (craft.side_optics, infrared_optics(craft))  # no emissivity: an error before any work
    light = PlanetLight.of(planet("earth"), solar_flux()) if light is None else light
    cap = CapSampling() if cap is None else cap
    cell_deg, method = cap.cell_deg, cap.method
    shadows = ShadowSampling.of(sampling)
    reference, reference_name = model.reference(reference_point_m)
    settings = ReflectionSettings.of(reflections)
    if sensitivities:
        _check_sensitivities(settings.mode, cap.method)
    body = light.planet
    distance = body.radius_m + place.altitude_km * 1e3
    caps = [
        Cap(place.nadir, place.sun_vector, place.pole, distance, body.radius_m, law)
        for law in (light.albedo, light.infrared)
    ]
    with using_threads(model.threads):
        plan = reflection_plan(craft, settings)
        if sensitivities:
            _check_sensitivities(plan.mode, method)  # "auto" resolved
        check_cells(caps[0].half_angle, cell_deg)
        seen = None
        if method == "visibility" and plan.mode != PLATES:
            beams = plan.mode in BEAM_MODES
            seen = visibility(craft, level_for(cell_deg), shadows, settings, beams=beams)
            points, values = _spread(caps)
            cells = [seen.grid.weights(points, v) for v in values]
            directions = seen.grid.nodes
        else:
            patches = [cap.patches(cell_deg) for cap in caps]  # one geometry: the same directions
            directions, cells = patches[0][0], [weights for _, weights in patches]
        sources = [
            Source(
                name=name,
                integrals=_side_integrals(craft, cap),
                weights=weights,
                optics=optics,
                beams=name == "albedo" and plan.mode in BEAM_MODES,
                exchange=_exchange(craft, plan, settings, name),
            )
            for name, cap, weights, optics in zip(
                ("albedo", "infrared"), caps, cells, band_optics, strict=True
            )
        ]
        observed = (
            CellShares(craft, sources) if sensitivities and seen is None else None
        )  # the passes' shares
        if seen is None:
            observe = None if observed is None else observed.observe
            traced = sensitivities and plan.mode in BEAM_MODES
            loads, rays = band_loads(
                craft, sources, directions, reference, shadows, settings, observe, traced
            )
        else:
            loads, rays = _visible_loads(craft, sources, seen, (points, values), reference, shadows), 0
        derivatives = None
        if sensitivities:  # the direct parts; the reflected parts' derivatives join them in the sum
            shares = (
                grid_share_loads(craft, sources, seen, reference)
                if observed is None
                else observed.share_loads(reference)
            )
            parts = [band_derivatives(craft, s.name, share) for s, share in zip(sources, shares, strict=True)]
            if plan.mode in BEAM_MODES:
                parts += reflected_derivatives(craft, plan.mode, sources, loads, reference)
            derivatives = planet_sensitivities(craft, parts, reference)
        flux = light.solar_flux_W_m2 * place.solar_fraction
        sun = _sunlight(craft, place.sun_vector, flux, plan, settings)
        solar, solar_rays = band_loads(craft, [sun], place.sun_vector[None, :], reference, shadows, settings)
    return PlanetResult(
        albedo=loads[0],
        infrared=loads[1],
        solar=solar[0],
        place=place,
        half_angle_deg=math.degrees(caps[0].half_angle),
        light=light,
        cells=len(directions),
        rays=rays + solar_rays,
        reflections=plan.mode,
        reference_point_m=reference,
        reference_point=reference_name,
        craft=craft,
        sensitivities=derivatives,
    )


def _check_sensitivities(mode: str, method: str) -> None:
    """Refuse sensitivities with reflections whose beams or diffuse balance are followed by the
    visibility: its per-node chains are kept without their derivatives."""
    if mode in BEAM_MODES and method == "visibility":
        raise InputError(
            f"sensitivities of the planet's radiation with reflections '{mode}' need the cap's cells",
            hint='use cap=CapSampling(method="cells") (--earth-cap-method cells), or reflections "none" or '
            '"plates"',
            parameters=("sensitivities", "reflections"),
        )


def _side_integrals(
    craft: Spacecraft, cap: Cap
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """:meth:`Cap.side_integrals` of every side, each distinct normal once (found once per model)."""
    unique, inverse = craft.cache.get("distinct side normals", lambda: _distinct(craft.side_normals))
    i0, i1, i2 = cap.side_integrals(unique)
    return i0[inverse], i1[inverse], i2[inverse]


def _distinct(normals: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    unique, inverse = np.unique(normals, axis=0, return_inverse=True)
    return np.ascontiguousarray(unique), inverse.reshape(-1)


def _spread(caps: list[Cap]) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
    """The caps' quadrature points (one geometry: the same for every band) and each band's ``L dw``."""
    points, solid = caps[0].quadrature()
    return points, [cap.radiance_along(points) * solid for cap in caps]


def _visible_loads(
    craft: Spacecraft,
    sources: list[Source],
    seen: Visibility,
    rule: tuple[NDArray[np.float64], list[NDArray[np.float64]]],
    reference: NDArray[np.float64],
    sampling: ShadowSampling,
) -> list[BandLoad]:
    """The bands from the visibility, with the grid's error (from the grid a level coarser)."""
    coarser = None
    if seen.grid.level > 0 and sampling.estimates:
        points, values = rule
        coarse = direction_grid(seen.grid.level - 1)
        coarser = np.zeros((len(seen.grid.nodes), len(values)))
        coarser[: len(coarse.nodes)] = coarse.weights(points, np.column_stack(values))
    return grid_band_loads(craft, sources, seen, reference, sampling.estimates, coarser)


def _exchange(
    craft: Spacecraft, plan: ReflectionPlan, settings: ReflectionSettings, band: str
) -> DiffuseExchange | None:
    """The diffuse balance of ``band`` ("solar"/"albedo" or "infrared") under ``plan`` (made with
    ``settings``) when it is ``full``, else None; kept in the model's cache."""
    if plan.mode != "full":
        return None
    return infrared_exchange(craft, settings) if band == "infrared" else plan.exchange


def _sunlight(
    craft: Spacecraft,
    u_sun: NDArray[np.float64],
    flux: float,
    plan: ReflectionPlan,
    settings: ReflectionSettings,
) -> Source:
    """Sunlight of ``flux`` [W/m^2] along ``u_sun`` as a source of one cell."""
    cos = np.maximum(craft.side_normals @ u_sun, 0.0)
    i0 = flux * cos
    return Source(
        name="solar",
        integrals=(i0, i0[:, None] * u_sun, i0 * cos),
        weights=np.array([flux]),
        optics=craft.side_optics,
        beams=plan.mode in BEAM_MODES and flux > 0,
        exchange=_exchange(craft, plan, settings, "solar"),
    )
