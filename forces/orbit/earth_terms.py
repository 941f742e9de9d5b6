"""The Earth's albedo and infrared at an orbit step, the power each part absorbs, and (``thermal``) the
parts' temperatures and thermal recoil (METHOD.md "Planet radiation", "Orbit mode").

``thermal="equilibrium"``: a step's temperatures are the equilibrium with that step's absorbed power,
the limit of parts whose heat capacity is small against the power they exchange over the step.

``thermal="transient"``: the lumped model of the materials file's nodes (``[thermal."GLOB"] isothermal
= true, heat_capacity_J_K = ...``) integrated along the steps by
:func:`~sunwind.forces.thermal.transient.integrate`. The steps run in independent chunks (checkpointed,
possibly on Dask), the integration is sequential: each step records what the integrator needs, per
side, the sunlight it absorbs (its reflections included) with the whole solar disc in view and the
rest (albedo and infrared with their reflections); once every chunk is in, :meth:`EarthTerms.
integrate_thermal` integrates over the steps with the share of the Sun in view at any time in between
(the run's eclipse on interpolated positions). A pure function of the step records: a resumed run gives
bitwise the uninterrupted one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, replace

import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from sunwind.forces.earth import (
    BEAM_MODES,
    DEFAULT_CELL_DEG,
    METHODS,
    CapSampling,
    Place,
    check_cell_size,
    planet_radiation,
)
from sunwind.forces.model import Model
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.reflection import reflection_plan
from sunwind.forces.tables.jobs import Records, SrpSetup
from sunwind.forces.thermal import thermal_model, thermal_nodes
from sunwind.forces.thermal.transient import DEFAULT_TOLERANCE_K, integrate
from sunwind.forces.vocabulary import ABSORBED_SOURCES, PART, SIDE, absorbed_name
from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import count, require
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.spacecraft import infrared_optics

#: Albedo and infrared loads of a step (body frame): record name -> width.
BAND_FIELDS = {
    "albedo_force_body_N": 3,
    "albedo_torque_body_Nm": 3,
    "infrared_force_body_N": 3,
    "infrared_torque_body_Nm": 3,
}
#: Thermal recoil of a step (body frame).
THERMAL_FIELDS = {"thermal_force_body_N": 3, "thermal_torque_body_Nm": 3}
#: Sources of the per-part (and per-side) absorbed powers [W], in order
#: (:data:`~sunwind.forces.vocabulary.ABSORBED_SOURCES`).
PART_SOURCES = tuple(ABSORBED_SOURCES)
#: The thermal modes: each step's equilibrium, or the lumped transient integrated along the steps.
THERMAL_MODES = ("equilibrium", "transient")
#: What a step of the transient records for the integration, per side [W]: the sunlight absorbed with
#: the whole solar disc in view (its reflections included), and the rest (albedo and infrared, with
#: their reflections).
FORCING_FIELDS = ("forcing_sun_side_W", "forcing_planet_side_W")
#: What the transient's integration adds to the records: its estimated error of the node temperatures [K].
TRANSIENT_FIELDS = {"thermal_error_K": 1}
#: What the outputs say (``thermal_initial_temperature_K``) of a transient started from the equilibrium of
#: the first step.
FIRST_EQUILIBRIUM = "equilibrium of the first step"


@dataclass(frozen=True)
class EarthTerms:
    """The Earth's radiation at every step of an orbit.

    Attributes
    ----------
    surface : SrpSetup
        Shadow sampling, reflections and reference point (those of the SRP term); the solar flux is each
        step's (:class:`~sunwind.forces.orbit.steps.OrbitLoads`).
    albedo : float, optional
        Bond albedo instead of the Earth's 0.30.
    infrared_W_m2 : float, optional
        Uniform infrared exitance at the surface [W/m^2] instead of ``(1 - A) S / 4``.
    knocke : bool
        Knocke's zonal, seasonal albedo and emissivity, at each step's date, with latitudes about the
        GCRF z axis.
    cell_deg : float
        Resolution of the shadowing [deg] (:func:`~sunwind.forces.earth.planet_radiation`).
    cap_method : {"auto", "visibility", "cells"}
        How the shadowed cap is integrated (``method`` of :func:`~sunwind.forces.earth.planet_radiation`);
        ``"auto"``: the model's directional visibility, built once, unless a hinge moves (tracks or follows
        a schedule), which poses the model anew at every step, or sensitivities are asked with reflections
        followed (the visibility keeps no derivatives of its chains): then a shadow pass per cell.
    thermal : {None, "equilibrium", "transient"}
        The parts' temperatures and thermal recoil (:data:`THERMAL_MODES`; True is ``"equilibrium"``):
        each step's equilibrium, or the lumped transient integrated along the steps (the module
        docstring), which needs a node with a heat capacity.
    per_side : bool
        Also each side's absorbed power by source at every step (``side_{source}_W``).
    initial_temperature_K : float, optional
        The transient's start: every node at this temperature [K]; default the equilibrium of the first
        step.
    thermal_tolerance_K : float
        The transient's tolerance: largest estimated local error over a step [K] (default 0.01).
    n_sides : int
        Width of the per-side records: the model's number of sides (set by :meth:`sized`, which
        :func:`~sunwind.forces.orbit.flight.fly` calls).

    Raises
    ------
    InputError
        An albedo or infrared out of range, a bad cell size, a thermal mode not one of
        :data:`THERMAL_MODES`, a tolerance or initial temperature not above 0, or either without the
        transient.

    Examples
    --------
    >>> import sunwind as sw
    >>> from sunwind.forces.orbit.earth_terms import EarthTerms
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> earth = EarthTerms(SrpSetup(reflections="none"), thermal=True)
    >>> earth.thermal, list(earth.fields(n_parts=1))[-3:]
    ('equilibrium', ['thermal_force_body_N', 'thermal_torque_body_Nm', 'part_temperature_K'])
    >>> painted = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
    >>> cube = sw.load(sw.meshes.box(), uniform=painted, threads=1)
    >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
    >>> path = sw.orbit.propagate(sw.orbit.Elements.circular(700, 98.2), epoch, [0.0, 60.0], "kepler")
    >>> result = sw.fly(cube, path, sw.orbit.AttitudeLaw.parse("nadir"), sw.orbit.OrbitLoads(earth=earth))
    >>> result.terms, result.part_names
    (('albedo', 'infrared', 'thermal'), ('box',))
    >>> sides = sw.orbit.OrbitLoads(earth=EarthTerms(SrpSetup(reflections="none"), per_side=True))
    >>> sw.fly(cube, path, sw.orbit.AttitudeLaw.parse("nadir"), sides).series["side_solar_W"].shape
    (2, 12)

    The transient needs heat capacities, from the materials file (here given to the spacecraft):

    >>> from dataclasses import replace
    >>> from sunwind.geometry.materials import ThermalRule
    >>> rule = ThermalRule("*", isothermal=True, heat_capacity_J_K=9e3)
    >>> lumped = replace(cube, craft=replace(cube.craft, thermal=(rule,)))
    >>> transient = EarthTerms(SrpSetup(reflections="none"), thermal="transient", initial_temperature_K=250.0)
    >>> run = sw.fly(lumped, path, sw.orbit.AttitudeLaw.parse("nadir"), sw.orbit.OrbitLoads(earth=transient))
    >>> run.series["part_temperature_K"].round(2).ravel(), run.series["thermal_error_K"].round(5)
    (array([250.  , 258.23]), array([0.     , 0.00044]))
    >>> sw.fly(cube, path, sw.orbit.AttitudeLaw.parse("nadir"), sw.orbit.OrbitLoads(earth=transient))
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: the thermal transient needs a node with a heat capacity, and the ...
    >>> EarthTerms(SrpSetup(), albedo=1.5)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: albedo 1.5 is outside [0, 1]...
    """

    surface: SrpSetup
    albedo: float | None = None
    infrared_W_m2: float | None = None
    knocke: bool = False
    cell_deg: float = DEFAULT_CELL_DEG
    thermal: str | None = None
    per_side: bool = False
    initial_temperature_K: float | None = field(default=None, kw_only=True)
    thermal_tolerance_K: float = field(default=DEFAULT_TOLERANCE_K, kw_only=True)
    cap_method: str = field(default="auto", kw_only=True)
    n_sides: int = field(default=0, kw_only=True, repr=False)

    def __post_init__(self) -> None:
        PlanetLight.of(planet("earth"), 1.0, albedo=self.albedo, infrared_W_m2=self.infrared_W_m2)
        check_cell_size(self.cell_deg)
        if self.cap_method not in ("auto", *METHODS):
            raise InputError(
                f"cap_method {self.cap_method!r} is not one of auto, {', '.join(METHODS)}",
                parameters=("cap_method",),
            )
        mode = THERMAL_MODES[0] if self.thermal is True else None if self.thermal is False else self.thermal
        if mode is not None and mode not in THERMAL_MODES:
            raise InputError(
                f"thermal {self.thermal!r} is not one of {', '.join(THERMAL_MODES)}",
                hint="give thermal='equilibrium' (each step's) or 'transient' (the lumped model in time)",
                parameters=("thermal",),
            )
        object.__setattr__(self, "thermal", mode)
        for name, value in (
            ("thermal_tolerance_K", self.thermal_tolerance_K),
            ("initial_temperature_K", self.initial_temperature_K),
        ):
            if value is not None and not _positive(value):
                raise InputError(f"{name} {value!r} is not a temperature above 0 K", parameters=(name,))
        given = self.initial_temperature_K is not None or self.thermal_tolerance_K != DEFAULT_TOLERANCE_K
        if given and not self.transient:
            raise InputError(
                "initial_temperature_K and thermal_tolerance_K are the transient's",
                hint="give them with thermal transient",
                parameters=("initial_temperature_K", "thermal_tolerance_K", "thermal"),
            )

    @property
    def transient(self) -> bool:
        """Whether the temperatures are the lumped transient's (``thermal="transient"``)."""
        return self.thermal == THERMAL_MODES[1]

    def fields(self, n_parts: int) -> dict[str, int]:
        """Record name -> width of a step, for a model of ``n_parts`` parts.

        Parameters
        ----------
        n_parts : int
            The model's number of parts (the width of the per-part records).

        Returns
        -------
        dict of str to int
            :data:`BAND_FIELDS`, the per-part absorbed powers; with ``thermal="equilibrium"``,
            :data:`THERMAL_FIELDS` and the part temperatures; with ``"transient"`` the per-side
            :data:`FORCING_FIELDS` (the integration adds the temperatures and recoil after the run:
            :meth:`integrate_thermal`); with ``per_side``, the per-side absorbed powers.

        Raises
        ------
        InputError
            Per-side records on terms not :meth:`sized` to a model.
        """
        out = dict(BAND_FIELDS) | {absorbed_name(PART, source): n_parts for source in PART_SOURCES}
        if self.thermal == THERMAL_MODES[0]:
            out |= THERMAL_FIELDS | {"part_temperature_K": n_parts}
        if (self.per_side or self.transient) and self.n_sides < 1:
            raise InputError(
                "per-side records need the model's number of sides before the run",
                hint="give the terms .sized(model, steps), or fly them (fly sizes them)",
            )
        if self.transient:
            out |= dict.fromkeys(FORCING_FIELDS, self.n_sides)
        if self.per_side:
            out |= {absorbed_name(SIDE, source): self.n_sides for source in PART_SOURCES}
        return out

    def sized(self, model: Model, steps: int) -> EarthTerms:
        """These terms for a run of ``model`` over ``steps`` steps: the width of the per-side records,
        refused before the run when they would not fit in memory or the transient has no heat capacity.

        The per-side powers take ``steps x sides x 4 x 8`` bytes (float64, four sources); the transient
        ``steps x (4 sides + 2 nodes) x 8`` (its forcing recorded and the integrator's copy, the node
        temperatures and their error estimates), checked with :func:`~sunwind.geometry.memory.require`.

        Parameters
        ----------
        model : Model
            The model to fly.
        steps : int
            The run's number of steps.

        Returns
        -------
        EarthTerms
            ``self`` with :attr:`n_sides` set (unchanged without per-side records).

        Raises
        ------
        InputError
            The records need more than the memory limit (``SUNWIND_MAX_MEMORY``); a transient on a model
            whose materials file gives no heat capacity.

        Examples
        --------
        >>> import os
        >>> import sunwind as sw
        >>> painted = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
        >>> cube = sw.load(sw.meshes.box(), uniform=painted, threads=1)
        >>> EarthTerms(SrpSetup(), per_side=True).sized(cube, steps=100).n_sides
        12
        >>> os.environ["SUNWIND_MAX_MEMORY"] = "1M"
        >>> EarthTerms(SrpSetup(), per_side=True).sized(cube, steps=10**5)
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: not enough memory: needs ~36.6 MiB for the per-side ...
        >>> del os.environ["SUNWIND_MAX_MEMORY"]
        """
        if not (self.per_side or self.transient):
            return self
        sides, parts, fixes = model.craft.n_sides, [], []
        nbytes = 0
        if self.per_side:
            nbytes += steps * sides * len(PART_SOURCES) * 8
            parts.append(
                f"the per-side absorbed powers ({count(steps)} steps x {count(sides)} sides x "
                f"{len(PART_SOURCES)} sources x 8 bytes)"
            )
            fixes.append("drop per_side (the per-part powers stay)")
        if self.transient:
            nodes = self._heat_capacities(model)
            nbytes += steps * (4 * sides + 2 * nodes) * 8
            parts.append(
                f"the transient's forcing and history ({count(steps)} steps x (4 x {count(sides)} sides + "
                f"2 x {count(nodes)} nodes) x 8 bytes)"
            )
            fixes.append("take thermal equilibrium")
        fix = ", ".join(fixes) + ", or fly fewer steps or a coarser mesh"
        require(nbytes, " and ".join(parts), fix, ("per_side", "thermal"))
        return replace(self, n_sides=sides)

    def _heat_capacities(self, model: Model) -> int:
        """The number of the model's nodes; refuse a model none of whose nodes has a heat capacity."""
        craft = model.craft
        nodes = thermal_nodes(craft)
        if not np.any(nodes.heat_capacity_J_K > 0):
            where = "its materials file" if craft.materials_source else "a materials file (-m)"
            raise InputError(  # no parameter named: the fix's [thermal."GLOB"] is no flag
                "the thermal transient needs a node with a heat capacity, and the model has none",
                path=craft.materials_source,
                hint=f'give one in {where}: [thermal."GLOB"] isothermal = true, heat_capacity_J_K = ... '
                "(GLOB the parts that store heat), or take the equilibrium",
            )
        return nodes.n_nodes

    def precompute(self, model: Model) -> None:
        """Refuse a model without emissivities before the first step; make the surface setup's view factors.

        Parameters
        ----------
        model : Model
            The model the steps will pose.

        Raises
        ------
        MaterialError
            A material without an emissivity.
        InputError
            Per-side records :meth:`sized` to a model of another number of sides.
        """
        if (self.per_side or self.transient) and self.n_sides != model.craft.n_sides:
            raise InputError(
                f"per-side records sized to {self.n_sides} sides fly a model of {model.craft.n_sides}",
                hint="size them to the model flown: .sized(model, steps)",
                parameters=("per_side",),
            )
        infrared_optics(model.craft)
        self.surface.precompute(model)

    def evaluate(
        self,
        model: Model,
        place: Place,
        sunlight_W_m2: float,
        julian_tt: float,
        *,
        sensitivities: bool = False,
    ) -> tuple[dict[str, NDArray[np.float64]], LoadsError | None]:
        """One step's records, and the shadow passes' estimated error of its albedo and infrared loads.

        Parameters
        ----------
        model : Model
            The model, posed at the step's hinge angles.
        place : Place
            Where the Earth and Sun are, body frame; its solar fraction is the eclipse.
        sunlight_W_m2 : float
            Solar flux at the spacecraft's distance, without eclipse [W/m^2].
        julian_tt : float
            TT Julian date (Knocke's season).
        sensitivities : bool
            Also the derivatives of the albedo and infrared force and torque with respect to every
            material's coefficients, ``sensitivity_force_N`` and ``sensitivity_torque_Nm`` (n_materials,
            7, 3) among the records.

        Returns
        -------
        records : dict of str to ndarray
            The step's records (:meth:`fields`), body frame.
        error : LoadsError or None
            :attr:`~sunwind.forces.earth.PlanetResult.shadow_error`; None when the shadow pass gives none.

        Examples
        --------
        >>> import sunwind as sw
        >>> from sunwind.forces.earth import Place
        >>> from sunwind.forces.orbit.earth_terms import EarthTerms
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> painted = sw.Material("paint", reflectivity=0.0, specular_fraction=0.0, emissivity=0.9)
        >>> cube = sw.load(sw.meshes.box(), uniform=painted, threads=1)
        >>> earth = EarthTerms(SrpSetup(reflections="none"))
        >>> earth.precompute(cube)
        >>> records, error = earth.evaluate(cube, Place([0, 0, 1], 700.0, [1, 0, 0]), 1361.0, 2460389.5)
        >>> (records["infrared_force_body_N"] * 1e6).round(2) + 0.0  # micronewtons, away from the Earth (-z)
        array([ 0.  ,  0.  , -1.02])
        """
        light = PlanetLight.of(
            planet("earth"),
            sunlight_W_m2,
            albedo=self.albedo,
            infrared_W_m2=self.infrared_W_m2,
            knocke_julian_date=julian_tt if self.knocke else None,
        )
        options = self.surface.options()
        fraction = place.solar_fraction
        if self.transient:  # sunlight with the whole disc in view, for the integration between steps
            place = replace(place, solar_fraction=1.0)
        method = self.cap_method
        if method == "auto":
            moving = any(hinge.law != "fixed" for hinge in model.hinges)
            followed = (
                sensitivities and reflection_plan(model.craft, self.surface.settings).mode in BEAM_MODES
            )
            method = "cells" if moving or followed else "visibility"
        result = planet_radiation(
            model,
            place,
            light,
            cap=CapSampling(self.cell_deg, method),
            sensitivities=sensitivities,
            **options,
        )
        out = {
            "albedo_force_body_N": result.albedo.force_N,
            "albedo_torque_body_Nm": result.albedo.torque_Nm,
            "infrared_force_body_N": result.infrared.force_N,
            "infrared_torque_body_Nm": result.infrared.torque_Nm,
        }
        if sensitivities:
            out["sensitivity_force_N"] = result.sensitivities.force_N
            out["sensitivity_torque_Nm"] = result.sensitivities.torque_Nm
        if not (self.thermal or self.per_side):  # per part only: no forward solve of the diffuse balance
            for source, values in result.part_absorbed_W().items():
                out[absorbed_name(PART, source)] = values
            return out, result.shadow_error
        absorbed = result.absorbed_side_W()
        if self.transient:
            solar, planet_bands = result.solar, (result.albedo, result.infrared)
            out[FORCING_FIELDS[0]] = solar.absorbed_side_W + solar.reflected_side_W
            out[FORCING_FIELDS[1]] = sum(b.absorbed_side_W + b.reflected_side_W for b in planet_bands)
            absorbed["solar"] = fraction * solar.absorbed_side_W
            absorbed["reflected"] = (
                sum(b.reflected_side_W for b in planet_bands) + fraction * solar.reflected_side_W
            )
        for source in PART_SOURCES:
            out[absorbed_name(PART, source)] = result.per_part(absorbed[source])
            if self.per_side:
                out[absorbed_name(SIDE, source)] = absorbed[source]
        if self.thermal == THERMAL_MODES[0]:
            state = result.equilibrium(options["reflections"])
            out["thermal_force_body_N"], out["thermal_torque_body_Nm"] = state.force_N, state.torque_Nm
            out["part_temperature_K"] = result.part_temperatures(state.temperature_K)
        return out, result.shadow_error

    def integrate_thermal(
        self,
        model: Model,
        times_s: NDArray[np.float64],
        records: Records,
        solar_fraction: Callable[[float], float],
        angles: Sequence[dict[str, float]],
        *,
        block: int = 64,
        progress: Callable[[int], None] | None = None,
    ) -> Records:
        """The transient after the run: the lumped model integrated over the steps' records.

        :func:`~sunwind.forces.thermal.transient.integrate` over ``times_s``, the sunlight of each side
        (:data:`FORCING_FIELDS`) interpolated linearly between steps and scaled by ``solar_fraction`` at
        every stage's time, the rest interpolated linearly. The nodes are integrated with the model's
        thermal model (its infrared exchange as loaded); a step whose hinges turn the model to another
        pose takes its recoil from that pose at the integrated node temperatures (a hinge moves sides,
        not nodes: the side count and the nodes are those of every pose). The steps are integrated
        ``block`` intervals at a time, each block going on from the last (bitwise one integration),
        ``progress`` told after each.

        Parameters
        ----------
        model : Model
            The model flown (as loaded).
        times_s : (n,) float64
            The steps' times [s].
        records : dict of str to ndarray
            The steps' records (:meth:`fields`).
        solar_fraction : callable
            ``solar_fraction(t_s)``: the share of the solar disc in view at any time of the run, the
            steps' own at their times.
        angles : sequence of dict
            Each step's hinge angles [deg] by glob (empty without hinges).
        block : int, default 64
            Intervals integrated between two calls of ``progress``, >= 1.
        progress : callable, optional
            Called with the number of steps integrated so far.

        Returns
        -------
        dict of str to ndarray
            ``records`` with :data:`THERMAL_FIELDS`, ``part_temperature_K`` (n, n_parts) (the area-weighted
            mean of each part's side temperatures) and :data:`TRANSIENT_FIELDS` added.

        Raises
        ------
        InputError
            A stage that does not converge (:func:`~sunwind.forces.thermal.transient.integrate`).

        Examples
        --------
        A black cube of 9 kJ/K at 250 K, the Sun on its top face (1361 W) for two minutes, nothing else; it
        emits 1329 W at 250 K:

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from dataclasses import replace
        >>> from sunwind.geometry.materials import ThermalRule
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0, emissivity=1.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> rule = ThermalRule("*", isothermal=True, heat_capacity_J_K=9e3)
        >>> cube = replace(cube, craft=replace(cube.craft, thermal=(rule,)))
        >>> terms = EarthTerms(SrpSetup(reflections="none"), thermal="transient", initial_temperature_K=250.0)
        >>> terms = terms.sized(cube, 3)
        >>> sun = 1361.0 * 0.5 * np.maximum(cube.craft.side_normals @ [0.0, 0.0, 1.0], 0.0)  # [W], on +z
        >>> records = {"forcing_sun_side_W": np.tile(sun, (3, 1)), "forcing_planet_side_W": np.zeros((3, 12))}
        >>> times = np.array([0.0, 60.0, 120.0])
        >>> out = terms.integrate_thermal(cube, times, records, lambda t: 1.0, [{}] * 3)
        >>> out["part_temperature_K"].round(2).ravel(), out["thermal_error_K"].round(4)
        (array([250.  , 250.2 , 250.37]), array([0.    , 0.    , 0.0001]))
        """
        settings = self.surface.settings
        thermal = thermal_model(model.craft, settings)
        sun, rest = records[FORCING_FIELDS[0]], records[FORCING_FIELDS[1]]
        start = self.initial_temperature_K
        history: object = None if start is None else np.full(thermal.nodes.n_nodes, float(start))
        reference = model.reference(self.surface.reference_point_m)[0]
        rows: list[tuple[NDArray[np.float64], ...]] = []
        n = len(times_s)
        for lo in range(0, max(n - 1, 1), block):
            hi = min(lo + block, n - 1) + 1  # times lo to hi - 1: the block's intervals and their ends
            history = integrate(
                thermal,
                times_s[lo:hi],
                rest[lo:hi],
                initial=history,
                solar_W=sun[lo:hi],
                solar_fraction=solar_fraction,
                tolerance_K=self.thermal_tolerance_K,
                reference_m=reference,
            )
            got = (history.node_temperature_K, history.error_K, history.force_N, history.torque_Nm)
            rows.append(tuple(values[min(lo, 1) :] for values in got))  # a block starts at the last end
            if progress is not None:
                progress(hi)
        temperature, error, force, torque = (np.concatenate(columns) for columns in zip(*rows, strict=True))
        for k, pose in enumerate(angles):
            posed = model.posed(pose)
            if posed is not model:  # another pose: its recoil at these node temperatures
                q = rest[k] + solar_fraction(float(times_s[k])) * sun[k]
                at = posed.reference(self.surface.reference_point_m)[0]
                state = thermal_model(posed.craft, settings).state_at(temperature[k], q, at)
                force[k], torque[k] = state.force_N, state.torque_Nm
        return records | {
            "thermal_force_body_N": force,
            "thermal_torque_body_Nm": torque,
            "part_temperature_K": _part_means(model, thermal.nodes.side_node, temperature),
            "thermal_error_K": error,
        }

    def describe(self) -> dict:
        """JSON-ready settings.

        Returns
        -------
        dict
            The fields (the transient's settings with the transient only), the surface setup by its own
            ``describe``.
        """
        out = asdict(self) | {"surface": self.surface.describe()}
        if not self.transient:
            del out["initial_temperature_K"], out["thermal_tolerance_K"]
        return out


def _part_means(
    model: Model, side_node: NDArray[np.int64], temperature: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Area-weighted mean of each part's side temperatures [K], (n, n_parts), from node temperatures
    ``temperature`` (n, n_nodes) and each side's node."""
    craft = model.craft
    part = craft.facet_part[craft.side_facet]
    shape = (len(craft.part_names), temperature.shape[1])
    weights = scipy.sparse.csr_matrix((craft.side_areas, (part, side_node)), shape=shape)
    mean = scipy.sparse.diags(1.0 / np.asarray(weights.sum(axis=1)).ravel()) @ weights
    return np.asarray((mean @ temperature.T).T)


def _positive(value: object) -> bool:
    """Whether ``value`` is a finite number above 0 (a bool is not)."""
    number = not isinstance(value, bool) and isinstance(value, int | float | np.floating | np.integer)
    return number and math.isfinite(value) and value > 0
