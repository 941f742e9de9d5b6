"""The result of an orbit run: time series of the loads and the momentum they build, their summary,
and the same names in JSON, netCDF and CSV (the orbit guide, docs/guides/orbit.md).

Body-frame loads are about the model's reference point; ECI is GCRF. The angular impulse is the
trapezoidal integral of the torque from the first step (zero there): in the body frame, of the
body-frame torque (what body-fixed wheels absorb when the body does not turn); in ECI, of the torque
turned into GCRF (the inertial momentum the loads build).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.integrate import cumulative_trapezoid

from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.model import Model
from sunwind.forces.orbit.attitude import AttitudeLaw
from sunwind.forces.orbit.earth_terms import FIRST_EQUILIBRIUM, PART_SOURCES
from sunwind.forces.orbit.inputs import StepInputs
from sunwind.forces.orbit.steps import OrbitLoads
from sunwind.forces.orbit.trajectory import Trajectory
from sunwind.forces.radiation.law import radiation_pressure
from sunwind.forces.result_base import Result
from sunwind.forces.sensitivity import COEFFICIENTS
from sunwind.forces.tables.dataset import attribute_text, model_provenance
from sunwind.forces.tables.sensitivities import SENSITIVITY_DIMS, sensitivity_coords
from sunwind.forces.vocabulary import (
    COMPONENT,
    COMPONENT_ATTRS,
    COMPONENTS,
    PART,
    SIDE,
    SIDE_COORDINATES,
    absorbed_name,
    variable_attrs,
)
from sunwind.geometry.rays.certificate import LoadsError

#: Time series of the output, in order, with their units (UDUNITS).
SERIES = {
    "time_s": "s",
    "position_eci_m": "m",
    "velocity_eci_m_s": "m s-1",
    "sun_body": "1",
    "solar_fraction": "1",
    "srp_force_body_N": "N",
    "srp_torque_body_Nm": "N m",
    "drag_force_body_N": "N",
    "drag_torque_body_Nm": "N m",
    "force_body_N": "N",
    "force_eci_N": "N",
    "torque_body_Nm": "N m",
    "angular_impulse_body_Nms": "N m s",
    "angular_impulse_eci_Nms": "N m s",
    "density_kg_m3": "kg m-3",
    "dynamic_pressure_Pa": "Pa",
}
#: Series of a run with the Earth's radiation (``thermal_*`` and ``part_temperature_K`` with thermal
#: recoil, ``thermal_error_K`` with the transient, ``side_*`` with per-side records); ``part_*`` are
#: (n, n_parts), columns in ``part_names`` order, ``side_*`` (n, n_sides), columns in the model's side
#: order (:attr:`OrbitResult.sides`).
EARTH_SERIES = {
    "albedo_force_body_N": "N",
    "albedo_torque_body_Nm": "N m",
    "infrared_force_body_N": "N",
    "infrared_torque_body_Nm": "N m",
    "thermal_force_body_N": "N",
    "thermal_torque_body_Nm": "N m",
    **{absorbed_name(PART, source): "W" for source in PART_SOURCES},
    "part_temperature_K": "K",
    "thermal_error_K": "K",
    **{absorbed_name(SIDE, source): "W" for source in PART_SOURCES},
}
#: Long names of the series the transient (``thermal="transient"``) gives, in place of the equilibrium's.
TRANSIENT_LONG_NAMES = {
    "part_temperature_K": "area-weighted mean of the sides' temperatures of each part, lumped transient "
    "model",
    "thermal_force_body_N": "recoil of the infrared the spacecraft emits, lumped transient model, body frame",
    "thermal_torque_body_Nm": "torque of the thermal recoil, lumped transient model",
    "thermal_error_K": "estimated error of the node temperatures, largest over the nodes: the integrator's "
    "local error estimates carried along its steps",
}
#: Series of a run whose every term uses the default shadow pass: the error the passes estimate they
#: left in the step's total force and torque, relative (:class:`~sunwind.forces.error_estimate.
#: ErrorEstimate` of their absolute errors added over the terms), with their long names.
ESTIMATE_SERIES = {
    "error_estimate_force": "estimated relative error of force_body_N left by the shadow passes, |dF| / |F|",
    "error_estimate_torque": "estimated relative error of torque_body_Nm left by the shadow passes, "
    "|dM| / max(|M|, 0.01 |F| L), L the diagonal of the model's bounding box",
}
#: Series of a run with sensitivities: the derivatives of ``force_body_N`` and ``torque_body_Nm`` with
#: respect to every material's coefficients, (n, n_materials, 7, 3), with units and long names.
SENSITIVITY_SERIES = {
    "sensitivity_force_N": ("N", "d force_body_N / d coefficient, body frame"),
    "sensitivity_torque_Nm": ("N m", "d torque_body_Nm / d coefficient, body frame"),
}
#: Terms a run can add up, each with its force and torque series.
TERMS = ("srp", "drag", "albedo", "infrared", "thermal")


@dataclass(frozen=True)
class OrbitResult(Result):
    """Loads along an orbit, the momentum they build, and what the run was.

    Made by :func:`~sunwind.forces.orbit.flight.fly` (through :meth:`OrbitResult.of`).

    Attributes
    ----------
    series : dict of str to ndarray
        Name -> (n,) or (n, 3) float64 (``part_*``: (n, n_parts)); the output's names are :attr:`names`
        (see :data:`SERIES`, :data:`EARTH_SERIES`, :data:`ESTIMATE_SERIES`), and the series also hold
        ``srp_flux_W_m2`` and ``v_rel_body_m_s`` for the summary.
    body_to_eci : ndarray of float64, shape (n, 3, 3)
        Body-to-GCRF rotation at every step.
    hinge_angles_deg : dict of str to ndarray
        Hinge glob -> (n,) angles used [deg]; empty for a model without hinges.
    attributes : dict of str to object
        What the run was: frame, epoch, trajectory, attitude, terms, reference point, settings and the
        model's provenance; with thermal recoil ``thermal`` (the mode), and for the transient
        ``thermal_tolerance_K`` and ``thermal_initial_temperature_K`` (a temperature [K], or
        ``"equilibrium of the first step"``).
    period_s : float
        Two-body period of the orbit at its first step [s] (inf when not bound).
    flux_1au_W_m2 : float
        Solar flux at 1 au [W/m^2].
    terms : tuple of str
        The terms computed, of :data:`TERMS`.
    part_names : tuple of str
        Columns of the ``part_*`` series (with the Earth's radiation; else empty).
    sides : dict of str to ndarray
        Columns of the ``side_*`` series: each side's :data:`SIDE_COORDINATES` (part name, facet index in
        the model, ``"front"`` or ``"back"``, area [m^2]), (n_sides,) each; empty without per-side records.
    materials : tuple of str
        The materials of the :data:`SENSITIVITY_SERIES` (with sensitivities; else empty).

    Examples
    --------
    >>> from sunwind.forces import load
    >>> from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
    >>> from sunwind.forces.tables.jobs import SrpSetup
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.meshes import box_wing
    >>> model = load(box_wing(facet_size=0.5), uniform=Material("paint", 0.4, 0.5, 0.1), two_sided=["wing*"])
    >>> path = propagate(Elements.circular(700, 98.2), Epoch.of("2024-03-20T00:00:00Z"), [0, 60], "kepler")
    >>> result = fly(model, path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup(reflections="none")))
    >>> result.summary()["steps"], result.to_json()["time_s"]
    (2, [0.0, 60.0])
    >>> result.to_dataset()["torque_body_Nm"].attrs["units"]
    'N m'
    """

    series: dict[str, NDArray[np.float64]]
    body_to_eci: NDArray[np.float64]
    hinge_angles_deg: dict[str, NDArray[np.float64]]
    attributes: dict[str, object]
    period_s: float
    flux_1au_W_m2: float
    terms: tuple[str, ...] = field(default=())
    part_names: tuple[str, ...] = field(default=())
    sides: dict[str, NDArray] = field(default_factory=dict)
    materials: tuple[str, ...] = field(default=(), kw_only=True)

    @property
    def names(self) -> list[str]:
        """The output series of this run, in order (:data:`SERIES`, then those of :data:`EARTH_SERIES`,
        :data:`ESTIMATE_SERIES` and :data:`SENSITIVITY_SERIES` it has)."""
        extra = (*EARTH_SERIES, *ESTIMATE_SERIES, *SENSITIVITY_SERIES)
        return [*SERIES, *(name for name in extra if name in self.series)]

    @classmethod
    def of(
        cls,
        model: Model,
        trajectory: Trajectory,
        attitude: AttitudeLaw,
        setup: OrbitLoads,
        steps: StepInputs,
        records: dict[str, NDArray[np.float64]],
    ) -> OrbitResult:
        """The result of a run from its inputs and the records of its steps.

        Parameters
        ----------
        model : Model
            The model flown.
        trajectory : Trajectory
            The steps' times and GCRF states.
        attitude : AttitudeLaw
            The attitude law (its description goes into the attributes).
        setup : OrbitLoads
            What the steps computed.
        steps : StepInputs
            Each step's inputs.
        records : dict of str to ndarray
            The records of the steps (:attr:`OrbitLoads.fields`).

        Returns
        -------
        OrbitResult
        """
        t, body_to_eci = trajectory.time_s, steps.body_to_eci
        fraction = steps.solar_fraction
        per_step = [setup.angles_at(model, steps, i) for i in range(len(steps))]
        angles = {hinge.pattern: np.array([a[hinge.pattern] for a in per_step]) for hinge in model.hinges}
        asked = {"srp": setup.srp, "drag": setup.drag, "albedo": setup.earth, "infrared": setup.earth}
        asked["thermal"] = setup.earth if setup.earth is not None and setup.earth.thermal else None
        terms = tuple(term for term in TERMS if asked[term] is not None)
        force = sum(records[f"{term}_force_body_N"] for term in terms)
        torque = sum(records[f"{term}_torque_body_Nm"] for term in terms)
        torque_eci = np.einsum("nij,nj->ni", body_to_eci, torque)
        series = {
            "time_s": t,
            "position_eci_m": trajectory.position_m,
            "velocity_eci_m_s": trajectory.velocity_m_s,
            "sun_body": steps.sun_body,
            "solar_fraction": fraction,
            **{name: records[name] for name in ("srp_force_body_N", "srp_torque_body_Nm")},
            **{name: records[name] for name in ("drag_force_body_N", "drag_torque_body_Nm")},
            "force_body_N": force,
            "force_eci_N": np.einsum("nij,nj->ni", body_to_eci, force),
            "torque_body_Nm": torque,
            "angular_impulse_body_Nms": _impulse(t, torque),
            "angular_impulse_eci_Nms": _impulse(t, torque_eci),
            "density_kg_m3": records["density_kg_m3"],
            "dynamic_pressure_Pa": records["dynamic_pressure_Pa"],
            "srp_flux_W_m2": steps.flux_W_m2,
            "v_rel_body_m_s": steps.velocity_body_m_s,
        }
        for name in EARTH_SERIES:
            if name in records:
                values = records[name]
                series[name] = values.reshape(len(t), -1) if _per(name) else values
        if "shadow_error_force_N" in records:
            errors = zip(records["shadow_error_force_N"], records["shadow_error_torque_Nm"], strict=True)
            size = model.craft.diagonal_m
            estimates = [
                ErrorEstimate.of(LoadsError(float(f), float(m)), force[k], torque[k], size)
                for k, (f, m) in enumerate(errors)
            ]
            series["error_estimate_force"] = np.array([e.force for e in estimates])
            series["error_estimate_torque"] = np.array([e.torque for e in estimates])
        for name in SENSITIVITY_SERIES:
            if name in records:  # flat per step: (material, coefficient, component)
                series[name] = records[name].reshape(len(t), -1, len(COEFFICIENTS), 3)
        point, name = model.reference()
        attributes = {
            "frame": "body loads in the body frame, ECI = GCRF",
            "epoch_utc": trajectory.epoch.iso(),
            "trajectory": trajectory.source,
            "attitude": attitude.describe(),
            "terms": ", ".join(terms),
            "reference_point_m": [float(x) for x in point],
            "reference_point": name,
            "settings": setup.describe(),
            **_thermal_attributes(setup),
            **{k: v for k, v in model_provenance(model).items() if v is not None},
        }
        parts = tuple(model.craft.part_names) if setup.earth is not None else ()
        sides = _side_coordinates(model) if absorbed_name(SIDE, PART_SOURCES[0]) in records else {}
        flux = setup.flux_1au_W_m2
        materials = tuple(setup.materials) if setup.sensitivities else ()
        return cls(
            series,
            body_to_eci,
            angles,
            attributes,
            trajectory.period_s,
            flux,
            terms,
            parts,
            sides,
            materials=materials,
        )

    def summary(self, mass_kg: float | None = None) -> dict[str, object]:
        """Orbit averages, eclipses, the largest torque, the momentum per orbit and the effective areas.

        ``C_D A = sum(-F_drag . v_rel_hat) / sum(q)`` over the steps (q the dynamic pressure: the
        coefficient that gives the run's mean drag along the flow); ``C_R A = sum(-F_srp . s) / sum(P)``
        (``s`` the Sun direction, ``P`` the pressure of the visible Sun at the spacecraft). The momentum per
        orbit is the ECI angular impulse at the end scaled to one two-body period. Means are trapezoidal
        time averages.

        Parameters
        ----------
        mass_kg : float, optional
            Spacecraft mass [kg]: adds ``mass_kg`` and the areas per kg, ``ballistic_coefficient_m2_kg``
            (``C_D A / m``) and ``srp_coefficient_m2_kg`` (``C_R A / m``).

        Returns
        -------
        dict of str to object
            JSON-ready: ``steps``, ``duration_s``, ``period_s``, ``sunlit_fraction``, ``shadow_equivalent_s``
            (the seconds of full shadow the loss of sunlight amounts to), ``eclipses_s`` (``[start, end]`` of
            each stretch short of the whole Sun, to the step), ``mean_force_body_N``, ``mean_force_eci_N``,
            ``mean_torque_body_Nm``, ``max_torque_Nm``, ``max_torque_time_s``, ``angular_impulse_body_Nms``,
            ``angular_impulse_eci_Nms`` (at the end); as they apply, ``momentum_per_orbit_Nms`` [N m s],
            ``drag_area_m2``, ``srp_area_m2``, the mean albedo, infrared and thermal loads,
            ``thermal_error_worst_K`` (the transient's largest estimated error [K]), ``error_estimate_worst``
            and ``parts`` (per part: mean absorbed powers [W], temperatures [K]).

        Examples
        --------
        A black 1 m cube on a 700 km orbit, the Sun fixed along GCRF -x:

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
        >>> orbit = sw.orbit.Elements.circular(700, 98.2)
        >>> path = sw.orbit.propagate(orbit, epoch, np.arange(4) * 600.0, "kepler")
        >>> fixed = sw.orbit.AttitudeLaw.parse("inertial:1,0,0,0")
        >>> loads = sw.orbit.OrbitLoads(SrpSetup(reflections="none"))
        >>> result = sw.fly(cube, path, fixed, loads, sun_eci=[-1.0, 0.0, 0.0])  # starts behind the Earth
        >>> summary = result.summary(mass_kg=10.0)
        >>> summary["eclipses_s"], summary["sunlit_fraction"]
        ([[0.0, 1200.0]], 0.5)
        >>> round(summary["srp_area_m2"], 3), round(summary["srp_coefficient_m2_kg"], 4)  # black: C_R A = A
        (1.0, 0.1)
        """
        s, t = self.series, self.series["time_s"]
        magnitude = np.linalg.norm(s["torque_body_Nm"], axis=1)
        peak = int(np.argmax(magnitude))
        duration = float(t[-1] - t[0])
        out: dict[str, object] = {
            "steps": len(t),
            "duration_s": duration,
            "period_s": self.period_s,
            "sunlit_fraction": _mean(t, s["solar_fraction"]),
            "shadow_equivalent_s": _shadow_time(t, s["solar_fraction"]),
            "eclipses_s": _eclipses(t, s["solar_fraction"]),
            "mean_force_body_N": _mean(t, s["force_body_N"]),
            "mean_force_eci_N": _mean(t, s["force_eci_N"]),
            "mean_torque_body_Nm": _mean(t, s["torque_body_Nm"]),
            "max_torque_Nm": float(magnitude[peak]),
            "max_torque_time_s": float(t[peak]),
            "angular_impulse_body_Nms": s["angular_impulse_body_Nms"][-1].tolist(),
            "angular_impulse_eci_Nms": s["angular_impulse_eci_Nms"][-1].tolist(),
        }
        if duration > 0 and math.isfinite(self.period_s):
            per_orbit = s["angular_impulse_eci_Nms"][-1] * self.period_s / duration
            out["momentum_per_orbit_Nms"] = float(np.linalg.norm(per_orbit))
        if "drag" in self.terms:
            v = s["v_rel_body_m_s"]
            along = -np.einsum(
                "ij,ij->i", s["drag_force_body_N"], v / np.linalg.norm(v, axis=1, keepdims=True)
            )
            out["drag_area_m2"] = float(along.sum() / s["dynamic_pressure_Pa"].sum())
        if "srp" in self.terms and s["srp_flux_W_m2"].sum() > 0:
            along = -np.einsum("ij,ij->i", s["srp_force_body_N"], s["sun_body"])
            out["srp_area_m2"] = float(along.sum() / radiation_pressure(1.0) / s["srp_flux_W_m2"].sum())
        for term in ("albedo", "infrared", "thermal"):
            if term in self.terms:
                out[f"mean_{term}_force_body_N"] = _mean(t, s[f"{term}_force_body_N"])
                out[f"mean_{term}_torque_body_Nm"] = _mean(t, s[f"{term}_torque_body_Nm"])
        if "thermal_error_K" in s:
            out["thermal_error_worst_K"] = float(s["thermal_error_K"].max())
        if "error_estimate_force" in s:
            out["error_estimate_worst"] = {
                "force": float(s["error_estimate_force"].max()),
                "torque": float(s["error_estimate_torque"].max()),
            }
        if self.part_names:
            out["parts"] = self._part_summary()
        if mass_kg is not None:
            out["mass_kg"] = mass_kg
            for area, name in (
                ("drag_area_m2", "ballistic_coefficient_m2_kg"),
                ("srp_area_m2", "srp_coefficient_m2_kg"),
            ):
                if area in out:
                    out[name] = out[area] / mass_kg
        return out

    def _part_summary(self) -> dict[str, dict[str, float]]:
        """Per part: the orbit-mean absorbed power by source [W] and the range and mean of the
        temperature [K] (with thermal recoil)."""
        s, t = self.series, self.series["time_s"]
        out: dict[str, dict[str, float]] = {name: {} for name in self.part_names}
        for source in PART_SOURCES:
            for name, mean in zip(
                self.part_names, np.atleast_1d(_mean(t, s[f"part_{source}_W"])), strict=True
            ):
                out[name][f"mean_{source}_W"] = float(mean)
        if "part_temperature_K" in s:
            temperature = s["part_temperature_K"]
            means = np.atleast_1d(_mean(t, temperature))
            for k, name in enumerate(self.part_names):
                out[name] |= {
                    "mean_temperature_K": float(means[k]),
                    "min_temperature_K": float(temperature[:, k].min()),
                    "max_temperature_K": float(temperature[:, k].max()),
                }
        return out

    def to_json(self, mass_kg: float | None = None) -> dict[str, object]:
        """One JSON-ready object of the run: every series, the attributes and the summary.

        Parameters
        ----------
        mass_kg : float, optional
            Spacecraft mass [kg], passed to :meth:`summary`.

        Returns
        -------
        dict of str to object
            Every series of :attr:`names` (one row per step) by its name, ``part_names`` (the columns of the
            ``part_*`` series) with the Earth's radiation, ``sides`` (the columns of the ``side_*`` series,
            :attr:`sides`) with per-side records, ``materials`` and ``coefficients`` (the axes of the
            ``sensitivity_*`` series, ``[step][material][coefficient][component]``) with sensitivities,
            ``hinge_angles_deg`` (by glob) with hinges, then ``attributes`` and ``summary``.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
        >>> orbit = sw.orbit.Elements.circular(700, 98.2)
        >>> path = sw.orbit.propagate(orbit, epoch, np.arange(4) * 600.0, "kepler")
        >>> fixed = sw.orbit.AttitudeLaw.parse("inertial:1,0,0,0")
        >>> loads = sw.orbit.OrbitLoads(SrpSetup(reflections="none"))
        >>> result = sw.fly(cube, path, fixed, loads, sun_eci=[-1.0, 0.0, 0.0])  # starts behind the Earth
        >>> out = result.to_json()
        >>> out["solar_fraction"], out["attributes"]["terms"]
        ([0.0, 0.0, 1.0, 1.0], 'srp')
        """
        out: dict[str, object] = {name: self.series[name].tolist() for name in self.names}
        if self.part_names:
            out["part_names"] = list(self.part_names)
        if self.sides:
            out["sides"] = {name: values.tolist() for name, values in self.sides.items()}
        if self.materials:
            out["materials"], out["coefficients"] = list(self.materials), list(COEFFICIENTS)
        if self.hinge_angles_deg:
            out["hinge_angles_deg"] = {k: v.tolist() for k, v in self.hinge_angles_deg.items()}
        out["attributes"] = self.attributes
        out["summary"] = self.summary(mass_kg)
        return out

    def to_dataset(self, mass_kg: float | None = None) -> xr.Dataset:
        """The series as an xarray Dataset on dimensions ``time``, ``component`` (x, y, z, as in sweep
        tables), ``part`` and ``side`` (and ``material``, ``coefficient`` with sensitivities), with units
        (UDUNITS), long names and comments in attributes.

        The ``time`` coordinate is CF time: seconds since the epoch, ``calendar = "standard"`` (read back as
        UTC times). ``part`` is named by the parts' names; ``side`` (with per-side records) is the side's
        index, with the coordinates :data:`SIDE_COORDINATES` to map each side onto a mesh facet. The
        absorbed powers are ``{part,side}_{source}_W`` [W]
        (:func:`~sunwind.forces.vocabulary.absorbed_name`). The run's attributes and the summary
        (``summary_*``) are the dataset's attributes, and each hinge's angles a ``hinge_angle_deg[GLOB]``
        variable.

        Parameters
        ----------
        mass_kg : float, optional
            Spacecraft mass [kg]: the summary's coefficients per kg.

        Returns
        -------
        xarray.Dataset
            One variable per series of :attr:`names`.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
        >>> orbit = sw.orbit.Elements.circular(700, 98.2)
        >>> path = sw.orbit.propagate(orbit, epoch, np.arange(4) * 600.0, "kepler")
        >>> fixed = sw.orbit.AttitudeLaw.parse("inertial:1,0,0,0")
        >>> loads = sw.orbit.OrbitLoads(SrpSetup(reflections="none"))
        >>> result = sw.fly(cube, path, fixed, loads, sun_eci=[-1.0, 0.0, 0.0])  # starts behind the Earth
        >>> table = result.to_dataset()
        >>> table["force_eci_N"].dims, table["time"].attrs["units"]
        (('time', 'component'), 'seconds since 2024-03-20T00:00:00.000Z')
        """
        variables, units = {}, SERIES | EARTH_SERIES | dict.fromkeys(ESTIMATE_SERIES, "1")
        units |= {name: unit for name, (unit, _) in SENSITIVITY_SERIES.items()}
        long_names = dict(ESTIMATE_SERIES) | {name: text for name, (_, text) in SENSITIVITY_SERIES.items()}
        if self.attributes.get("thermal") == "transient":
            long_names |= TRANSIENT_LONG_NAMES
        for name in self.names:
            values = self.series[name]
            dims = ("time",) if values.ndim == 1 else ("time", _per(name) or COMPONENT)
            if name in SENSITIVITY_SERIES:
                dims = ("time", *SENSITIVITY_DIMS)
            attrs = (
                variable_attrs(name)
                | {"units": units[name]}
                | ({"long_name": long_names[name]} if name in long_names else {})
            )
            variables[name] = xr.Variable(dims, values, attrs)
        for pattern, angles in self.hinge_angles_deg.items():
            variables[f"hinge_angle_deg[{pattern}]"] = xr.Variable(("time",), angles, {"units": "degree"})
        summary = {f"summary_{k}": _attribute(v) for k, v in self.summary(mass_kg).items()}
        attrs = {k: (str(v) if isinstance(v, dict) else v) for k, v in self.attributes.items()}
        time = xr.Variable(
            ("time",),
            self.series["time_s"],
            {
                "standard_name": "time",
                "long_name": "UTC",
                "axis": "T",
                "units": f"seconds since {self.attributes['epoch_utc']}",
                "calendar": "standard",
            },
            encoding={"_FillValue": None},  # CF: no fill value on a coordinate
        )
        coords = {"time": time, COMPONENT: xr.Variable((COMPONENT,), list(COMPONENTS), COMPONENT_ATTRS)}
        if self.part_names:
            coords[PART] = xr.Variable((PART,), list(self.part_names), variable_attrs(PART))
        if self.sides:
            n_sides = len(self.sides["side_facet"])
            coords[SIDE] = xr.Variable((SIDE,), np.arange(n_sides), variable_attrs(SIDE))
            coords |= {k: xr.Variable((SIDE,), v, variable_attrs(k)) for k, v in self.sides.items()}
        if self.materials:
            coords |= sensitivity_coords(self.materials)
        return xr.Dataset(variables, coords=coords, attrs=attrs | summary)

    def write_csv(self, path: Path) -> None:
        """Write the series as CSV: one row per step, the attributes as ``#`` comment lines above the header.

        Vectors are ``name_x``, ``name_y``, ``name_z`` columns, per-part series ``name[PART]``, per-side
        series ``name[PART:FACET:FACE]`` (the side's part, facet index and ``front`` or ``back``), the
        derivatives ``name[MATERIAL.COEFFICIENT]_x`` (and ``_y``, ``_z``) and hinge angles
        ``hinge_angle_deg[GLOB]``.

        Parameters
        ----------
        path : Path
            The file to write (replaced if it exists).

        Examples
        --------
        >>> import pathlib, tempfile
        >>> import numpy as np
        >>> import sunwind as sw
        >>> from sunwind.forces.tables.jobs import SrpSetup
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
        >>> orbit = sw.orbit.Elements.circular(700, 98.2)
        >>> path = sw.orbit.propagate(orbit, epoch, np.arange(4) * 600.0, "kepler")
        >>> fixed = sw.orbit.AttitudeLaw.parse("inertial:1,0,0,0")
        >>> loads = sw.orbit.OrbitLoads(SrpSetup(reflections="none"))
        >>> result = sw.fly(cube, path, fixed, loads, sun_eci=[-1.0, 0.0, 0.0])  # starts behind the Earth
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     csv_path = pathlib.Path(folder) / "orbit.csv"
        ...     result.write_csv(csv_path)
        ...     lines = csv_path.read_text().splitlines()
        >>> lines[0]
        '# frame: body loads in the body frame, ECI = GCRF'
        >>> header = next(line for line in lines if not line.startswith("#"))
        >>> header.split(",")[:4]
        ['time_s', 'position_eci_m_x', 'position_eci_m_y', 'position_eci_m_z']
        """
        columns, header = [], []
        for name in self.names:
            values = self.series[name]
            per = _per(name)
            if per is not None:
                columns += list(values.T)
                header += [f"{name}[{label}]" for label in self._labels(per)]
            elif name in SENSITIVITY_SERIES:
                columns += list(values.reshape(len(values), -1).T)
                header += [
                    f"{name}[{material}.{coefficient}]_{axis}"
                    for material in self.materials
                    for coefficient in COEFFICIENTS
                    for axis in "xyz"
                ]
            elif values.ndim == 2:
                columns += [values[:, i] for i in range(3)]
                header += [f"{name}_{axis}" for axis in "xyz"]
            else:
                columns.append(values)
                header.append(name)
        for pattern, angles in self.hinge_angles_deg.items():
            columns.append(angles)
            header.append(f"hinge_angle_deg[{pattern}]")
        with Path(path).open("w", newline="") as handle:
            handle.writelines(f"# {key}: {attribute_text(value)}\n" for key, value in self.attributes.items())
            writer = csv.writer(handle)
            writer.writerow(header)
            writer.writerows(np.stack(columns, axis=1).tolist())

    def _labels(self, per: str) -> list[str]:
        """Column labels of the series along ``per``: the part names, or ``PART:FACET:FACE`` per side."""
        if per == PART:
            return list(self.part_names)
        s = self.sides
        labels = s["side_part"].astype(str)
        for text in (s["side_facet"].astype(str), s["side_face"].astype(str)):
            labels = np.char.add(np.char.add(labels, ":"), text)
        return labels.tolist()


def _thermal_attributes(setup: OrbitLoads) -> dict[str, object]:
    """The thermal mode (``thermal``) and, for the transient, its tolerance and start, as attributes."""
    earth = setup.earth
    if earth is None or earth.thermal is None:
        return {}
    out: dict[str, object] = {"thermal": earth.thermal}
    if earth.transient:
        start = earth.initial_temperature_K
        out["thermal_tolerance_K"] = earth.thermal_tolerance_K
        out["thermal_initial_temperature_K"] = FIRST_EQUILIBRIUM if start is None else float(start)
    return out


def _per(name: str) -> str | None:
    """The dimension a per-part or per-side series runs along besides time (its name's first word), else
    None."""
    head = name.split("_", 1)[0]
    return head if head in (PART, SIDE) else None


def _side_coordinates(model: Model) -> dict[str, NDArray]:
    """Each side's :data:`SIDE_COORDINATES`: its part's name, its facet, ``front`` or ``back``, its area."""
    craft = model.craft
    part = np.asarray(craft.part_names)[craft.facet_part[craft.side_facet]]
    face = np.where(craft.side_sign > 0, "front", "back")
    values = (part, np.array(craft.side_facet), face, np.array(craft.side_areas))
    return dict(zip(SIDE_COORDINATES, values, strict=True))


def _attribute(value: object) -> object:
    """A summary value as a netCDF attribute: lists flat (the eclipses as start, end pairs), a table as
    its text."""
    if isinstance(value, list):
        return np.asarray(value, dtype=np.float64).ravel()
    return str(value) if isinstance(value, dict) else value


def _impulse(t: NDArray[np.float64], torque: NDArray[np.float64]) -> NDArray[np.float64]:
    if len(t) < 2:
        return np.zeros_like(torque)
    return cumulative_trapezoid(torque, t, axis=0, initial=0.0)


def _mean(t: NDArray[np.float64], values: NDArray[np.float64]) -> float | list[float]:
    """Time average by the trapezoidal rule (the value itself for one step)."""
    if len(t) < 2:
        mean = values[0]
    else:
        mean = np.trapezoid(values, t, axis=0) / (t[-1] - t[0])
    return mean.tolist() if np.ndim(mean) else float(mean)


def _shadow_time(t: NDArray[np.float64], fraction: NDArray[np.float64]) -> float:
    """Seconds of full shadow the run's sunlight loss amounts to (trapezoidal integral of 1 - fraction)."""
    return 0.0 if len(t) < 2 else float(np.trapezoid(1 - fraction, t))


def _eclipses(t: NDArray[np.float64], fraction: NDArray[np.float64]) -> list[list[float]]:
    """``[start, end]`` [s] of each stretch with less than the whole Sun (penumbra included), to the
    step: from its first step short of the whole Sun to the first step with it again (or the run's
    end)."""
    dark = np.concatenate([[False], fraction < 1.0, [False]])
    starts = np.flatnonzero(~dark[:-1] & dark[1:])
    ends = np.flatnonzero(dark[:-1] & ~dark[1:])
    return [[float(t[a]), float(t[min(b, len(t) - 1)])] for a, b in zip(starts, ends, strict=True)]
