"""What one orbit step computes, as a sweep job (:mod:`sunwind.forces.tables.jobs`): each step's row of
inputs in, SRP and drag loads in the body frame out. Steps run in checkpointed chunks, locally or on
Dask, exactly as a sweep's attitudes (:func:`sunwind.forces.tables.engine.run_jobs`).

A row holds what the step needs and nothing it has to look up: the time, the body-frame Sun direction,
the solar flux at the spacecraft (eclipse and distance applied), ``v_rel`` in the body frame, the
geodetic place of the atmosphere, and for the Earth's radiation the body-frame directions to the Earth's
centre and its pole, the height above the sphere, the flux without eclipse and the visible share of the
Sun. Every step calls :func:`~sunwind.forces.srp.srp`, :func:`~sunwind.forces.drag.drag` and
:func:`~sunwind.forces.earth.planet_radiation` as the single-attitude commands do.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.drag import drag
from sunwind.forces.earth import Place
from sunwind.forces.error_estimate import summed
from sunwind.forces.gas.atmosphere import Atmosphere, AtmosphereWarning
from sunwind.forces.gas.msis import (
    FREE_MOLECULAR_MIN_ALTITUDE_KM,
    MSIS_FITTED_ALTITUDE_KM,
    MSIS_MAX_ALTITUDE_KM,
    nrlmsis,
)
from sunwind.forces.model import Model
from sunwind.forces.orbit.clock import Epoch
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.srp import srp
from sunwind.forces.tables.jobs import GasOptions, Records, SrpSetup, empty_records
from sunwind.geometry.errors import InputError

#: Columns of a step's row of inputs.
TIME, SUN, FLUX, VELOCITY, PLACE = 0, slice(1, 4), 4, slice(5, 8), slice(8, 11)
NADIR, HEIGHT, POLE, SUNLIGHT, FRACTION = slice(11, 14), 14, slice(15, 18), 18, 19
ROW_WIDTH = 20


@dataclass(frozen=True)
class SpaceWeather:
    """NRLMSIS's inputs besides place and time: F10.7 of the day before and its 81-day mean [sfu], the
    daily Ap, the model version (see :func:`~sunwind.forces.gas.msis.nrlmsis`)."""

    f107: float = 150.0
    f107a: float = 150.0
    ap: float = 4.0
    version: float = 2.1

    def check(self, altitude_km: NDArray[np.float64]) -> None:
        """Refuse a run that leaves NRLMSIS's range, and say once (not at every step) where its steps
        are above the altitudes NRLMSIS is fitted to or below the free-molecular limit."""
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

    def atmosphere(self, epoch: Epoch, time_s: float, place: NDArray[np.float64]) -> Atmosphere:
        """NRLMSIS at geodetic ``place`` (altitude [km], latitude, longitude [deg]) ``time_s`` after the
        epoch (its range warnings are said once per run by :meth:`check`)."""
        altitude, latitude, longitude = (float(v) for v in place)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", AtmosphereWarning)
            return nrlmsis(
                altitude, latitude, longitude, epoch.at(time_s), self.f107, self.f107a, self.ap, self.version
            )


@dataclass(frozen=True)
class Loads:
    """What an orbit run computes: the SRP settings (None: no SRP; their ``flux_W_m2`` is the flux at
    1 au), the drag settings (None: no drag; each step has its own flow), the air (NRLMSIS space
    weather by default, or one fixed atmosphere), the step [deg] to which tracked and scheduled
    hinge angles are rounded (0: exact), so that steps share posed models and what their caches hold
    (view factors are made again at every new pose), and the Earth's albedo, infrared and thermal
    recoil (None: none)."""

    srp: SrpSetup | None = None
    drag: GasOptions | None = None
    air: SpaceWeather | Atmosphere = field(default_factory=SpaceWeather)
    hinge_step_deg: float = 0.0
    earth: EarthTerms | None = None


@dataclass(frozen=True)
class StepInputs:
    """Each step's row of inputs (n, :data:`ROW_WIDTH`), body-to-GCRF rotation (n, 3, 3) and visible
    share of the Sun (n,)."""

    rows: NDArray[np.float64]
    body_to_eci: NDArray[np.float64]
    solar_fraction: NDArray[np.float64]


@dataclass(frozen=True)
class OrbitSetup:
    """Settings of every orbit step: those of :class:`Loads`, the epoch of the steps' times and the
    number of the model's parts (the width of the per-part records)."""

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
    srp: SrpSetup | None
    drag: GasOptions | None
    air: SpaceWeather | Atmosphere
    epoch: Epoch
    hinge_step_deg: float = 0.0
    earth: EarthTerms | None = None
    n_parts: int = 0

    @classmethod
    def of(cls, loads: Loads, epoch: Epoch, n_parts: int = 0) -> OrbitSetup:
        """The settings of ``loads`` with times from ``epoch``, for a model of ``n_parts`` parts."""
        return cls(loads.srp, loads.drag, loads.air, epoch, loads.hinge_step_deg, loads.earth, n_parts)

    @property
    def fields(self) -> dict[str, int]:
        """The records of a step: name -> width."""
        extra = {} if self.earth is None else self.earth.fields(self.n_parts)
        return self.base_fields | extra | (self.estimate_fields if self.estimates else {})

    @property
    def estimates(self) -> bool:
        """Whether every term uses the default shadow pass, which estimates its error (not ``samples``)."""
        surface = None if self.earth is None else self.earth.surface
        return all(part.samples is None for part in (self.srp, self.drag, surface) if part is not None)

    def precompute(self, model: Model) -> None:
        """View factors and open skies, made once before the first step."""
        for part in (self.srp, self.drag, self.earth):
            if part is not None:
                part.precompute(model)

    def evaluate(self, model: Model, rows: NDArray[np.float64]) -> Records:
        """The records of the steps ``rows`` (n, :data:`ROW_WIDTH`)."""
        out = empty_records(self.fields, len(rows))
        for name in out:
            out[name][:] = 0.0
        for i, row in enumerate(rows):
            posed = model.posed(self.angles(model, row))
            flux = float(row[FLUX])
            errors = []
            if self.srp is not None and flux > 0:
                light = srp(posed, row[SUN], flux_W_m2=flux, **self.srp.options())
                out["srp_force_body_N"][i], out["srp_torque_body_Nm"][i] = light.force_N, light.torque_Nm
                errors.append(light.shadow_error)
            if self.drag is not None:
                air = self.air_at(row)
                gas = drag(posed, row[VELOCITY], air, **self.drag.options())
                out["drag_force_body_N"][i], out["drag_torque_body_Nm"][i] = gas.force_N, gas.torque_Nm
                out["density_kg_m3"][i] = air.density_kg_m3
                out["dynamic_pressure_Pa"][i] = gas.dynamic_pressure_Pa
                errors.append(gas.shadow_error)
            if self.earth is not None:
                place = Place(row[NADIR], float(row[HEIGHT]), row[SUN], row[POLE], float(row[FRACTION]))
                julian = float(sum(self.epoch.tt(float(row[TIME]))))
                records, error = self.earth.evaluate(posed, place, float(row[SUNLIGHT]), julian)
                for name, value in records.items():
                    out[name][i] = np.reshape(value, out[name][i].shape)  # one part: a number
                errors.append(error)
            total = summed(errors)
            if self.estimates and total is not None:
                out["shadow_error_force_N"][i], out["shadow_error_torque_Nm"][i] = (
                    total.force_N,
                    total.torque_Nm,
                )
        return out

    def air_at(self, row: NDArray[np.float64]) -> Atmosphere:
        """The atmosphere of a step."""
        if isinstance(self.air, Atmosphere):
            return self.air
        return self.air.atmosphere(self.epoch, float(row[TIME]), row[PLACE])

    def angles(self, model: Model, row: NDArray[np.float64]) -> dict[str, float]:
        """Every hinge's angle [deg] at a step, tracked and scheduled ones rounded to the hinge step."""
        angles = model.angles_at(row[SUN], float(row[TIME])) if model.hinges else {}
        step = self.hinge_step_deg
        if step > 0:
            moving = {hinge.pattern for hinge in model.hinges if hinge.law != "fixed"}
            angles = {k: round(a / step) * step if k in moving else a for k, a in angles.items()}
        return angles

    def describe(self) -> dict:
        """JSON-ready settings (for a checkpoint's fingerprint and the output's attributes)."""
        air = self.air.to_json() if isinstance(self.air, Atmosphere) else vars(self.air)
        return {
            "srp": None if self.srp is None else self.srp.describe(),
            "drag": None if self.drag is None else self.drag.describe(),
            "air": air,
            "epoch": self.epoch.iso(),
            "hinge_step_deg": self.hinge_step_deg,
            "earth": None if self.earth is None else self.earth.describe(),
        }
