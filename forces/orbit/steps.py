"""What an orbit run computes, and one step of it, as a sweep job (:mod:`sunwind.forces.tables.jobs`):
each step's inputs (:class:`~sunwind.forces.orbit.inputs.StepInputs`) in, SRP, drag and the Earth's
radiation in the body frame out. Steps run in checkpointed chunks, locally or on Dask, exactly as a
sweep's attitudes (:func:`sunwind.forces.tables.engine.run_jobs`): :class:`OrbitLoads` is the
:class:`~sunwind.forces.tables.jobs.Tabulation` of the steps.

Every step calls :func:`~sunwind.forces.srp.srp`, :func:`~sunwind.forces.drag.drag` and
:func:`~sunwind.forces.earth.planet_radiation` as the single-attitude commands do.
"""

from __future__ import annotations

import warnings
from dataclasses import asdict, dataclass, field, replace
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.drag import drag
from sunwind.forces.earth import Place, planet_radiation
from sunwind.forces.error_estimate import summed
from sunwind.forces.gas.atmosphere import Atmosphere, AtmosphereWarning
from sunwind.forces.gas.msis import (
    DEFAULT_AP,
    DEFAULT_F107_SFU,
    DEFAULT_F107A_SFU,
    DEFAULT_MSIS_VERSION,
    FREE_MOLECULAR_MIN_ALTITUDE_KM,
    MSIS_FITTED_ALTITUDE_KM,
    MSIS_MAX_ALTITUDE_KM,
    nrlmsis,
)
from sunwind.forces.model import Model
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.orbit.inputs import StepInputs
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, solar_flux
from sunwind.forces.srp import srp
from sunwind.forces.tables.jobs import GasOptions, Records, SrpSetup, empty_records
from sunwind.forces.tables.sensitivities import (
    SENSITIVITY_FIELDS,
    flat,
    sensitivity_fields,
    sensitivity_keyword,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.certificate import LoadsError


@dataclass(frozen=True)
class SpaceWeather:
    """NRLMSIS's inputs besides place and time (see :func:`~sunwind.forces.gas.msis.nrlmsis`).

    Its defaults are those of :mod:`sunwind.forces.gas.msis`.

    Attributes
    ----------
    f107, f107a : float
        F10.7 of the day before and its 81-day centred mean [sfu].
    ap : float
        Daily Ap index.
    version : float
        NRLMSIS version.

    Examples
    --------
    >>> SpaceWeather()
    SpaceWeather(f107=150.0, f107a=150.0, ap=4.0, version=2.1)
    """

    f107: float = DEFAULT_F107_SFU
    f107a: float = DEFAULT_F107A_SFU
    ap: float = DEFAULT_AP
    version: float = DEFAULT_MSIS_VERSION

    def check(self, altitude_km: NDArray[np.float64]) -> None:
        """Refuse a run that leaves NRLMSIS's range, and say once (not at every step) where its steps
        are above the altitudes NRLMSIS is fitted to or below the free-molecular limit.

        Parameters
        ----------
        altitude_km : ndarray, shape (n,)
            Geodetic altitude of every step [km].

        Raises
        ------
        InputError
            A step is above :data:`~sunwind.forces.gas.msis.MSIS_MAX_ALTITUDE_KM`.

        Warns
        -----
        AtmosphereWarning
            Steps above the fitted range or below the free-molecular limit, counted.

        Examples
        --------
        >>> SpaceWeather().check(np.array([400.0, 500.0]))  # nothing to say
        """
        top = float(altitude_km.max())
        if top > MSIS_MAX_ALTITUDE_KM:
            raise InputError(
                f"the orbit reaches {top:.0f} km, above {MSIS_MAX_ALTITUDE_KM:g} km where NRLMSIS cannot be "
                "trusted",
                hint="compute SRP alone (--srp), or give a fixed atmosphere (--density ...)",
                parameters=("drag",),
            )
        for outside, what in (
            (
                altitude_km > MSIS_FITTED_ALTITUDE_KM,
                f"above {MSIS_FITTED_ALTITUDE_KM:g} km, where NRLMSIS's exosphere is extrapolated",
            ),
            (
                altitude_km < FREE_MOLECULAR_MIN_ALTITUDE_KM,
                f"below {FREE_MOLECULAR_MIN_ALTITUDE_KM:g} km, where free-molecular flow no longer holds "
                "for a metre-sized body",
            ),
        ):
            if outside.any():
                warnings.warn(
                    f"{int(outside.sum())} of {outside.size} steps are {what}",
                    AtmosphereWarning,
                    stacklevel=3,
                )

    def atmosphere(self, steps: StepInputs, k: int) -> Atmosphere:
        """NRLMSIS at step ``k`` of ``steps``: its geodetic place and time (the range warnings are said
        once per run by :meth:`check`).

        Parameters
        ----------
        steps : StepInputs
            The steps.
        k : int
            Which of them.

        Returns
        -------
        Atmosphere

        Examples
        --------
        >>> from dataclasses import replace
        >>> from sunwind.forces.orbit.clock import Epoch
        >>> steps = StepInputs.at_rest(Epoch.of("2024-03-20T00:00:00Z"), [0.0])
        >>> place = {"altitude_km": [400.0], "latitude_deg": [0.0], "longitude_deg": [0.0]}
        >>> steps = replace(steps, **place)
        >>> f"{SpaceWeather().atmosphere(steps, 0).density_kg_m3:.2e} kg/m^3"  # doctest: +ELLIPSIS
        '...e-12 kg/m^3'
        """
        place = (float(steps.altitude_km[k]), float(steps.latitude_deg[k]), float(steps.longitude_deg[k]))
        when = steps.epoch.at(float(steps.time_s[k]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", AtmosphereWarning)
            return nrlmsis(*place, when, self.f107, self.f107a, self.ap, self.version)


@dataclass(frozen=True)
class OrbitLoads:
    """What an orbit run computes at every step.

    It is the sweep engine's :class:`~sunwind.forces.tables.jobs.Tabulation` of the steps
    (:class:`StepInputs`).

    Attributes
    ----------
    srp : SrpSetup or None
        Shadow sampling, reflections and reference point of SRP (None: no SRP). Its ``flux_W_m2`` (a
        sweep's flux at the spacecraft) stays at its default: each step has its own flux, from
        :attr:`flux_1au_W_m2`.
    drag : GasOptions or None
        The drag settings (None: no drag); each step has its own flow.
    air : SpaceWeather or Atmosphere
        NRLMSIS's space weather (the default), or one fixed atmosphere for every step.
    hinge_step_deg : float
        Step [deg] to which tracked and scheduled hinge angles are rounded (0: exact), so that steps
        share posed models and what their caches hold (view factors are made again at every new pose).
    earth : EarthTerms or None
        The Earth's albedo, infrared and thermal recoil (None: none).
    flux_1au_W_m2 : float
        Solar flux at 1 au [W/m^2], scaled to each step's distance from the Sun and eclipse.
    n_parts : int
        The model's number of parts: the width of the per-part records of the Earth's radiation (set
        by :func:`~sunwind.forces.orbit.flight.fly`, :meth:`sized`).
    sensitivities : bool
        Also record the derivatives of the step's summed force and torque with respect to every
        material's coefficients (``sensitivity_force_N``, ``sensitivity_torque_Nm``): SRP's at the
        step's flux (the solar fraction in it), drag's and the Earth's albedo and infrared's.
    materials : tuple of str
        With sensitivities, the model's material names (set by :meth:`sized`).

    Raises
    ------
    InputError
        A flux that is not one, or an SRP setup (or the Earth's surface setup) with a flux of its own;
        sensitivities of a term whose function gives none, or with the thermal recoil.

    Examples
    --------
    >>> loads = OrbitLoads(SrpSetup(reflections="none"), flux_1au_W_m2=1361.0)
    >>> loads.kind, list(loads.fields)[:2]
    ('orbit', ['srp_force_body_N', 'srp_torque_body_Nm'])
    """

    kind: ClassVar[str] = "orbit"
    #: Records of every run: name -> width.
    base_fields: ClassVar[dict[str, int]] = {
        "srp_force_body_N": 3,
        "srp_torque_body_Nm": 3,
        "drag_force_body_N": 3,
        "drag_torque_body_Nm": 3,
        "density_kg_m3": 1,
        "dynamic_pressure_Pa": 1,
    }
    #: Records of a run whose every term uses the default shadow pass: the passes' estimated absolute
    #: errors of the step's loads, added over its terms [N], [N m].
    estimate_fields: ClassVar[dict[str, int]] = {"shadow_error_force_N": 1, "shadow_error_torque_Nm": 1}
    srp: SrpSetup | None = None
    drag: GasOptions | None = None
    air: SpaceWeather | Atmosphere = field(default_factory=SpaceWeather)
    hinge_step_deg: float = 0.0
    earth: EarthTerms | None = None
    flux_1au_W_m2: float = field(default=SOLAR_FLUX_1AU, kw_only=True)
    n_parts: int = field(default=0, kw_only=True, repr=False)
    sensitivities: bool = field(default=False, kw_only=True)
    materials: tuple[str, ...] = field(default=(), kw_only=True, repr=False)

    def __post_init__(self) -> None:
        solar_flux(self.flux_1au_W_m2)
        surface = None if self.earth is None else self.earth.surface
        for name, setup in (("srp", self.srp), ("earth", surface)):
            if setup is not None and setup.flux_W_m2 != SOLAR_FLUX_1AU:
                raise InputError(
                    f"{name}'s flux_W_m2 {setup.flux_W_m2:g} W/m^2 is a sweep's flux at the spacecraft: an "
                    "orbit scales flux_1au_W_m2 to every step",
                    hint=f"give OrbitLoads(flux_1au_W_m2={setup.flux_W_m2:g}) and leave the setup's flux",
                    parameters=("flux_1au_W_m2",),
                )
        for kind, function in self._terms().items():
            sensitivity_keyword(function, kind, self.sensitivities)
        if self.sensitivities and self.earth is not None and self.earth.thermal:
            raise InputError(
                "sensitivities of the thermal recoil are not available yet",
                hint="leave out the thermal recoil or the sensitivities",
                parameters=("sensitivities", "thermal"),
            )

    def _terms(self) -> dict:
        """The function of each term computed, by its name."""
        terms = {"srp": srp, "drag": drag, "earth": planet_radiation}
        return {kind: terms[kind] for kind in terms if getattr(self, kind) is not None}

    def sized(self, n_parts: int, materials: tuple[str, ...] = ()) -> OrbitLoads:
        """These loads for a model of ``n_parts`` parts (the width of the per-part records) and these
        materials (the width of the derivatives' records, with :attr:`sensitivities`).

        Examples
        --------
        >>> OrbitLoads(SrpSetup()).sized(3).n_parts
        3
        >>> OrbitLoads(SrpSetup(), sensitivities=True).sized(1, ("paint",)).fields["sensitivity_force_N"]
        21
        """
        return replace(self, n_parts=n_parts, materials=tuple(materials))

    @property
    def fields(self) -> dict[str, int]:
        """The records of a step: name -> width (1: a number, else a row of that many)."""
        extra = {} if self.earth is None else self.earth.fields(self.n_parts)
        derivatives = sensitivity_fields(self.materials) if self.sensitivities else {}
        return self.base_fields | extra | (self.estimate_fields if self.estimates else {}) | derivatives

    @property
    def estimates(self) -> bool:
        """Whether every term's shadow pass estimates its error (the default sampling does)."""
        surface = None if self.earth is None else self.earth.surface
        return all(part.sampling.estimates for part in (self.srp, self.drag, surface) if part is not None)

    def precompute(self, model: Model) -> None:
        """View factors, open skies and the Earth's optics, made once before the first step.

        Parameters
        ----------
        model : Model
            The model the steps will pose.
        """
        for part in (self.srp, self.drag, self.earth):
            if part is not None:
                part.precompute(model)

    def evaluate(self, model: Model, inputs: StepInputs) -> Records:
        """The records of the steps ``inputs`` (:attr:`fields`, one row per step).

        Parameters
        ----------
        model : Model
            The model, posed at each step's hinge angles.
        inputs : StepInputs
            The steps (a chunk of a run).

        Returns
        -------
        dict of str to ndarray
            Loads of the terms not computed are zero.
        """
        out = empty_records(self.fields, len(inputs))
        for name in out:
            out[name][:] = 0.0
        asked = {"sensitivities": True} if self.sensitivities else {}
        for i in range(len(inputs)):
            posed = model.posed(self.angles_at(model, inputs, i))
            flux, sun = float(inputs.flux_W_m2[i]), inputs.sun_body[i]
            errors = []
            if self.srp is not None and flux > 0:  # the flux eclipsed: its derivatives too
                light = srp(posed, sun, flux_W_m2=flux, **self.srp.options(), **asked)
                out["srp_force_body_N"][i], out["srp_torque_body_Nm"][i] = light.force_N, light.torque_Nm
                self._add_sensitivities(out, i, light.sensitivities)
                errors.append(light.shadow_error)
            if self.drag is not None:
                air = self.air if isinstance(self.air, Atmosphere) else self.air.atmosphere(inputs, i)
                gas = drag(posed, inputs.velocity_body_m_s[i], air, **self.drag.options(), **asked)
                out["drag_force_body_N"][i], out["drag_torque_body_Nm"][i] = gas.force_N, gas.torque_Nm
                out["density_kg_m3"][i] = air.density_kg_m3
                out["dynamic_pressure_Pa"][i] = gas.dynamic_pressure_Pa
                self._add_sensitivities(out, i, gas.sensitivities)
                errors.append(gas.shadow_error)
            if self.earth is not None:
                errors.append(self._earth(posed, inputs, i, out))
            total = summed(errors)
            if self.estimates and total is not None:
                out["shadow_error_force_N"][i] = total.force_N
                out["shadow_error_torque_Nm"][i] = total.torque_Nm
        return out

    def _add_sensitivities(self, out: Records, i: int, derivatives) -> None:
        """Add a term's derivatives (a :class:`~sunwind.forces.sensitivity.Sensitivities`) to step ``i``'s."""
        if self.sensitivities:
            for name, row in flat(derivatives, self.materials).items():
                out[name][i] += row

    def _earth(self, posed: Model, inputs: StepInputs, i: int, out: Records) -> LoadsError | None:
        """The Earth's radiation at step ``i`` into ``out``; its shadow passes' estimated error."""
        place = Place(
            inputs.nadir_body[i],
            float(inputs.height_km[i]),
            inputs.sun_body[i],
            inputs.pole_body[i],
            float(inputs.solar_fraction[i]),
        )
        julian = float(sum(inputs.epoch.tt(float(inputs.time_s[i]))))
        asked = {"sensitivities": True} if self.sensitivities else {}
        records, error = self.earth.evaluate(posed, place, float(inputs.sunlight_W_m2[i]), julian, **asked)
        for name, value in records.items():
            if name in SENSITIVITY_FIELDS:  # (n_materials, 7, 3): added to the other terms'
                out[name][i] += np.ravel(value)
            else:
                out[name][i] = np.reshape(value, out[name][i].shape)  # one part: a number
        return error

    def angles_at(self, model: Model, inputs: StepInputs, i: int) -> dict[str, float]:
        """Every hinge's angle [deg] at step ``i``, tracked and scheduled ones rounded to
        :attr:`hinge_step_deg`.

        Parameters
        ----------
        model : Model
            The model whose hinges turn.
        inputs : StepInputs
            The steps.
        i : int
            Which of them.

        Returns
        -------
        dict of str to float
            Hinge glob -> angle; empty for a model without hinges.
        """
        sun, time_s = inputs.sun_body[i], float(inputs.time_s[i])
        angles = model.angles_at(sun, time_s) if model.hinges else {}
        step = self.hinge_step_deg
        if step > 0:
            moving = {hinge.pattern for hinge in model.hinges if hinge.law != "fixed"}
            angles = {k: round(a / step) * step if k in moving else a for k, a in angles.items()}
        return angles

    def describe(self) -> dict:
        """JSON-ready settings (a checkpoint's fingerprint and the output's attributes).

        Examples
        --------
        >>> OrbitLoads(SrpSetup()).describe()["air"]
        {'f107': 150.0, 'f107a': 150.0, 'ap': 4.0, 'version': 2.1}
        """
        return {
            "srp": None if self.srp is None else self.srp.describe(),
            "drag": None if self.drag is None else self.drag.describe(),
            "air": self.air.to_json() if isinstance(self.air, Atmosphere) else asdict(self.air),
            "flux_1au_W_m2": self.flux_1au_W_m2,
            "hinge_step_deg": self.hinge_step_deg,
            "earth": None if self.earth is None else self.earth.describe(),
        } | ({"sensitivities": list(self.materials)} if self.sensitivities else {})
