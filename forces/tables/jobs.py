"""What a sweep computes: the settings of every SRP or drag attitude, the quantities recorded at each,
and a job (one quantity over its list of directions). The Earth's radiation (kind ``"earth"``) has its
settings in :mod:`.earth_setup`; its fields are here with the others.

Every attitude is :func:`~sunwind.forces.srp.srp` or :func:`~sunwind.forces.drag.drag` called exactly as
the single-attitude commands call them, so a table entry is the same bits as ``sunwind srp`` or
``sunwind drag`` at that attitude (results do not depend on the thread count). A chunk of attitudes
gives *records*: one array per recorded field, named as the result's attribute, rows in the order of
the directions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.batches import SrpBatch
from sunwind.forces.drag import drag
from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.gas.atmosphere import Atmosphere
from sunwind.forces.gas.flow import flow_speed
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.gas.visible import model_sky
from sunwind.forces.model import Model
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, radiation_pressure, solar_flux
from sunwind.forces.reflection import (
    ReflectionSettings,
    interference,
    model_view_factors,
    reflection_plan,
    resolved_mode,
)
from sunwind.forces.srp import srp
from sunwind.forces.tables.sensitivities import sensitivity_fields, sensitivity_keyword, sensitivity_records
from sunwind.geometry.directions import finite_point
from sunwind.geometry.errors import InputError
from sunwind.geometry.rays.sampling import ShadowSampling

#: Quantities a sweep can tabulate, each over its own direction (the Sun, the flow, the Earth's centre).
KINDS = ("srp", "drag", "earth")
#: The loads and areas every kind records: the result attribute and its width (1: a number, 3: a vector).
_SHARED_FIELDS: dict[str, int] = {
    "force_N": 3,
    "torque_Nm": 3,
    "direct_force_N": 3,
    "direct_torque_Nm": 3,
    "reflected_force_N": 3,
    "reflected_torque_Nm": 3,
    "lit_area_m2": 1,
    "projected_area_m2": 1,
}
#: Fields recorded at every attitude of each kind, as :data:`_SHARED_FIELDS`.
SRP_FIELDS: dict[str, int] = dict(_SHARED_FIELDS)
DRAG_FIELDS: dict[str, int] = {
    **_SHARED_FIELDS,
    "CD": 1,
    "CS": 1,
    "CL": 1,
    "CM": 3,
}
#: The Earth's radiation at every direction of the Earth: albedo plus infrared (plus the thermal recoil
#: with thermal) in ``force_N``/``torque_Nm``, each band apart, the share of the Sun in view.
EARTH_FIELDS: dict[str, int] = {
    "force_N": 3,
    "torque_Nm": 3,
    "albedo_force_N": 3,
    "albedo_torque_Nm": 3,
    "infrared_force_N": 3,
    "infrared_torque_Nm": 3,
    "solar_fraction": 1,
}
#: What the Earth's radiation records besides, with the thermal recoil.
EARTH_THERMAL_FIELDS: dict[str, int] = {"thermal_force_N": 3, "thermal_torque_Nm": 3}
#: What every kind records besides with the default shadow pass: the error it estimates it left in the
#: force and torque, relative (:class:`~sunwind.forces.error_estimate.ErrorEstimate`).
ESTIMATE_FIELDS: dict[str, int] = {"error_estimate_force": 1, "error_estimate_torque": 1}
#: Every field each kind may record (the Earth's with its thermal recoil: the most it records).
FIELDS = {
    "srp": SRP_FIELDS | ESTIMATE_FIELDS,
    "drag": DRAG_FIELDS | ESTIMATE_FIELDS,
    "earth": EARTH_FIELDS | EARTH_THERMAL_FIELDS | ESTIMATE_FIELDS,
}
#: Records of some attitudes: field name -> (n,) or (n, 3) float64.
Records = dict[str, NDArray[np.float64]]


def empty_records(fields: dict[str, int], n: int) -> Records:
    """Unfilled records of some attitudes: one array per field, allocated.

    Parameters
    ----------
    fields : dict of str to int
        Field name -> width (1: a number per attitude, else a row of that many).
    n : int
        Number of attitudes.

    Returns
    -------
    Records
        One uninitialised float64 array per field, of :func:`record_shape`.

    Examples
    --------
    >>> records = empty_records({"force_N": 3, "CD": 1}, 4)
    >>> {name: values.shape for name, values in records.items()}
    {'force_N': (4, 3), 'CD': (4,)}
    """
    return {name: np.empty(record_shape(width, n)) for name, width in fields.items()}


def record_shape(width: int, n: int) -> tuple[int, ...]:
    """The shape of the records of ``n`` attitudes of a field of ``width``.

    Parameters
    ----------
    width : int
        1 for a number per attitude, else the length of its row.
    n : int
        Number of attitudes.

    Returns
    -------
    tuple of int
        ``(n,)`` for width 1, else ``(n, width)``.

    Examples
    --------
    >>> record_shape(1, 5), record_shape(3, 5)
    ((5,), (5, 3))
    """
    return (n,) if width == 1 else (n, width)


def estimate_records(estimates: Sequence[ErrorEstimate | None]) -> Records:
    """The :data:`ESTIMATE_FIELDS` records of attitudes with these error estimates.

    Parameters
    ----------
    estimates : sequence of ErrorEstimate or None
        Each attitude's estimate (None: none made).

    Returns
    -------
    Records
        ``error_estimate_force`` and ``error_estimate_torque``, (n,) float64 each, NaN where the
        estimate is None.

    Examples
    --------
    >>> estimate_records([ErrorEstimate(1e-6, 2e-6), None])["error_estimate_torque"]
    array([2.e-06,    nan])
    """
    missing = ErrorEstimate(math.nan, math.nan)
    rows = [missing if e is None else e for e in estimates]
    return {
        "error_estimate_force": np.array([e.force for e in rows], dtype=np.float64),
        "error_estimate_torque": np.array([e.torque for e in rows], dtype=np.float64),
    }


@dataclass(frozen=True)
class _Setup:
    """What the SRP, drag and Earth settings share, each the keyword of the same name of
    :func:`~sunwind.forces.srp.srp`, :func:`~sunwind.forces.drag.drag` and
    :func:`~sunwind.forces.earth.planet_radiation`.

    Parameters
    ----------
    reference_point_m : (3,) float, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        The shadow pass's sampling (:class:`~sunwind.geometry.rays.sampling.ShadowSampling`); None
        for its defaults.
    reflections : str or ReflectionSettings
        One of :data:`~sunwind.forces.reflection.settings.MODES`, or settings.
    sensitivities : bool
        Also record the derivatives of force and torque with respect to every material's coefficients
        (:mod:`~sunwind.forces.tables.sensitivities`; the keyword of the same name).
    materials : tuple of str
        With sensitivities, the model's material names (the records' widths): set by :meth:`sized`.
    """

    kind: ClassVar[str]
    reference_point_m: tuple[float, float, float] | None = field(default=None, kw_only=True)
    sampling: ShadowSampling = field(default_factory=ShadowSampling, kw_only=True)
    reflections: ReflectionSettings | str = field(default="auto", kw_only=True)
    sensitivities: bool = field(default=False, kw_only=True)
    materials: tuple[str, ...] = field(default=(), kw_only=True, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "sampling", ShadowSampling.of(self.sampling))
        ReflectionSettings.of(self.reflections)
        if self.reference_point_m is not None:
            finite_point(self.reference_point_m, "reference_point_m")

    @property
    def estimates(self) -> dict[str, int]:
        """:data:`ESTIMATE_FIELDS` with the default shadow pass (which estimates its error), none with
        fixed sampling."""
        return ESTIMATE_FIELDS if self.sampling.estimates else {}

    @property
    def settings(self) -> ReflectionSettings:
        """:attr:`reflections` as settings."""
        return ReflectionSettings.of(self.reflections)

    @property
    def computes(self) -> Any:
        """The function every attitude calls: :func:`~sunwind.forces.srp.srp`, unless the kind's own."""
        return srp

    @property
    def sensitivity_fields(self) -> dict[str, int]:
        """The records of the derivatives (:func:`~.sensitivities.sensitivity_fields`), none without
        :attr:`sensitivities`."""
        if not self.sensitivities:
            return {}
        if not self.materials:
            raise InputError(
                "a setup with sensitivities records them per material: size it for its model first",
                hint="setup.sized(model) (sweep does)",
                parameters=("sensitivities",),
            )
        return sensitivity_fields(self.materials)

    def sized(self, model: Model) -> _Setup:
        """These settings for ``model``: with :attr:`sensitivities`, its material names (the width of
        their records), the kind checked to give them.

        Parameters
        ----------
        model : Model
            The model the attitudes evaluate.

        Returns
        -------
        _Setup
            These settings, :attr:`materials` set (the same without sensitivities).

        Raises
        ------
        InputError
            Sensitivities of a kind whose function gives none.

        Examples
        --------
        >>> import sunwind as sw
        >>> cube = sw.load(sw.meshes.box(), uniform=sw.Material("grey", 0.3, 0.0), threads=1)
        >>> SrpSetup(sensitivities=True).sized(cube).sensitivity_fields
        {'sensitivity_force_N': 21, 'sensitivity_torque_Nm': 21}
        """
        if not self.sensitivities:
            return self
        sensitivity_keyword(self.computes, self.kind, True)
        return replace(self, materials=tuple(model.craft.materials.names))

    def keyword(self) -> dict:
        """The ``sensitivities`` keyword of every attitude's call, with :attr:`sensitivities` (else none)."""
        return sensitivity_keyword(self.computes, self.kind, self.sensitivities)

    def precompute(self, model: Model) -> None:
        """What every attitude reuses, made once before the first: the view factors when it reflects."""
        if self.settings.uses_view_factors:
            model_view_factors(model.craft, self.settings)

    def options(self) -> dict:
        """The keyword arguments every attitude's call takes: these settings under their own names."""
        return {
            "reference_point_m": self.reference_point_m,
            "sampling": self.sampling,
            "reflections": self.settings,
        }

    def describe(self) -> dict:
        """JSON-ready settings (the view-factor cache's place left out: it does not change results)."""
        out = asdict(self)
        if not self.sensitivities:  # a run without them is described as before they were
            del out["sensitivities"], out["materials"]
        else:
            out["materials"] = list(self.materials)
        out["reflections"] = asdict(self.settings)
        out["reflections"].pop("cache_dir")
        if self.reference_point_m is not None:  # given as an array or a sequence: JSON numbers either way
            out["reference_point_m"] = [float(x) for x in np.asarray(self.reference_point_m).ravel()]
        return out


@dataclass(frozen=True)
class SrpSetup(_Setup):
    """Settings of every SRP attitude of a sweep (see :func:`~sunwind.forces.srp.srp`).

    Parameters
    ----------
    flux_W_m2 : float
        Solar flux at the spacecraft [W/m^2]; default 1 au.
    reference_point_m : (3,) float, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        The shadow pass's sampling (:class:`~sunwind.geometry.rays.sampling.ShadowSampling`); None
        for its defaults.
    reflections : str or ReflectionSettings
        One of :data:`~sunwind.forces.reflection.settings.MODES`, or settings; default ``"auto"``.

    Raises
    ------
    InputError
        A flux, reference point, sampling or reflections out of range.

    Examples
    --------
    >>> from sunwind.geometry.rays.sampling import ShadowSampling
    >>> setup = SrpSetup(sampling=ShadowSampling(samples=4), reflections="none")
    >>> sorted(setup.options()), setup.estimates
    (['reference_point_m', 'reflections', 'sampling'], {})
    """

    kind: ClassVar[str] = "srp"
    flux_W_m2: float = SOLAR_FLUX_1AU

    def __post_init__(self) -> None:
        super().__post_init__()
        solar_flux(self.flux_W_m2)

    @property
    def fields(self) -> dict[str, int]:
        """The records of an attitude: name -> width (:data:`SRP_FIELDS`, the error estimate, the
        derivatives)."""
        return SRP_FIELDS | self.estimates | self.sensitivity_fields

    def evaluate(self, model: Model, directions: NDArray[np.float64]) -> Records:
        """The records of Sun directions ``directions`` (n, 3); a model whose hinges track the Sun is
        posed at each direction's angles first."""
        options = {"flux_W_m2": self.flux_W_m2, **self.options(), **self.keyword()}
        if any(hinge.law == "track" for hinge in model.hinges):
            poses = [model.posed(model.angles_at(u)) for u in directions]
            batch = SrpBatch(
                tuple(srp(posed, u, **options) for posed, u in zip(poses, directions, strict=True))
            )
        else:
            batch = srp(model, directions, **options)
        out = {name: batch.stacked(name) for name in SRP_FIELDS}
        if self.sensitivities:
            out |= sensitivity_records(batch, self.materials or model.craft.materials.names)
        return out | (estimate_records([r.error_estimate for r in batch]) if self.estimates else {})

    def attributes(self, model: Model) -> dict:
        """What a table of this setup states about its environment and the reflection mode it used."""
        tracking = [hinge.pattern for hinge in model.hinges if hinge.law == "track"]
        return {
            "flux_W_m2": self.flux_W_m2,
            "pressure_Pa": radiation_pressure(self.flux_W_m2),
            "srp_reflections": reflection_plan(model.craft, self.settings).mode,
        } | ({"srp_tracking_hinges": ", ".join(tracking)} if tracking else {})


@dataclass(frozen=True)
class GasOptions(_Setup):
    """How every drag attitude is computed, whatever its flow, as :func:`~sunwind.forces.drag.drag` takes it.

    Parameters
    ----------
    reference_point_m : (3,) float, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        The shadow pass's sampling; None for its defaults.
    reflections : str or ReflectionSettings
        The molecules' reflections: one of :data:`~sunwind.forces.reflection.settings.MODES`, or
        settings; default ``"auto"``.
    gas_sampling : GasSampling, optional
        Sampling of the open-sky integral and the chains
        (:class:`~sunwind.forces.gas.sampling.GasSampling`); None for its defaults.

    Raises
    ------
    InputError
        ``gas_sampling`` that is not a :class:`~sunwind.forces.gas.sampling.GasSampling`, or the other
        settings out of range.

    Examples
    --------
    >>> GasOptions(gas_sampling=GasSampling(sky_rays=36)).options()["gas_sampling"].sky_rays
    36
    """

    gas_sampling: GasSampling = field(default_factory=GasSampling, kw_only=True)

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "gas_sampling", GasSampling.of(self.gas_sampling))

    def precompute(self, model: Model) -> None:
        """The view factors when it reflects, and each side's open sky."""
        super().precompute(model)
        if self.settings.mode != "plates":
            model_sky(model.craft, self.gas_sampling.sky_rays, self.settings.cache_dir)

    def options(self) -> dict:
        """The keyword arguments every attitude's call takes."""
        return super().options() | {"gas_sampling": self.gas_sampling}

    @property
    def computes(self) -> Any:
        """The function every attitude calls, :func:`~sunwind.forces.drag.drag`."""
        return drag


@dataclass(frozen=True)
class DragSetup(GasOptions):
    """Settings of every drag attitude of a sweep (see :func:`~sunwind.forces.drag.drag`).

    Each attitude's flow direction ``u`` gives the velocity relative to the atmosphere
    ``v_rel = speed_m_s * u``.

    Parameters
    ----------
    reference_point_m : (3,) float, optional
        Torque reference point [m]; default the model's.
    sampling : ShadowSampling, optional
        The shadow pass's sampling; None for its defaults.
    reflections : str or ReflectionSettings
        The molecules' reflections; default ``"auto"``.
    gas_sampling : GasSampling, optional
        Sampling of the open-sky integral and the chains; None for its defaults.
    speed_m_s : float
        Speed relative to the atmosphere [m/s].
    atmosphere : Atmosphere
        The free stream (:func:`sunwind.explicit_atmosphere`, :func:`sunwind.nrlmsis`).

    Raises
    ------
    InputError
        A speed that is not a number or out of range, or the other settings out of range.

    Examples
    --------
    >>> import sunwind as sw
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> setup = DragSetup(speed_m_s=7600.0, atmosphere=air, reflections="none")
    >>> setup.kind, sorted(setup.options())
    ('drag', ['gas_sampling', 'reference_point_m', 'reflections', 'sampling'])
    >>> setup.describe()["atmosphere"]["density_kg_m3"]
    1e-12
    """

    kind: ClassVar[str] = "drag"
    speed_m_s: float = field(kw_only=True)
    atmosphere: Atmosphere = field(kw_only=True)

    def __post_init__(self) -> None:
        super().__post_init__()
        if isinstance(self.speed_m_s, bool) or not isinstance(self.speed_m_s, int | float):
            raise InputError(
                f"speed_m_s {self.speed_m_s!r} is not a number of m/s", parameters=("speed_m_s",)
            )
        flow_speed(self.speed_m_s)

    @property
    def fields(self) -> dict[str, int]:
        """The records of an attitude: name -> width (:data:`DRAG_FIELDS`, the error estimate, the
        derivatives)."""
        return DRAG_FIELDS | self.estimates | self.sensitivity_fields

    def evaluate(self, model: Model, directions: NDArray[np.float64]) -> Records:
        """The records of flow directions ``u`` (n, 3)."""
        batch = drag(model, self.speed_m_s * directions, self.atmosphere, **self.options(), **self.keyword())
        out = {name: batch.stacked(name) for name in DRAG_FIELDS}
        if self.sensitivities:
            out |= sensitivity_records(batch, self.materials or model.craft.materials.names)
        return out | (estimate_records([r.error_estimate for r in batch]) if self.estimates else {})

    def describe(self) -> dict:
        """JSON-ready settings, the atmosphere in full."""
        out = super().describe()
        out["atmosphere"] = self.atmosphere.to_json()
        return out

    def used_mode(self, model: Model) -> str:
        """The re-emission exchange mode the attitudes used: ``auto`` resolved as
        :func:`~sunwind.forces.drag.drag` resolves it (full when the molecular ``K_IS`` >= the threshold)."""
        settings = self.settings
        k_is = interference(model.craft, settings, molecules=True) if settings.mode == "auto" else None
        return resolved_mode(settings.mode, k_is)

    def attributes(self, model: Model) -> dict:
        """What a table of this setup states about its environment, coefficients and exchange mode."""
        air = self.atmosphere
        area, length = model.reference_sizes
        return {
            "speed_m_s": self.speed_m_s,
            "density_kg_m3": air.density_kg_m3,
            "temperature_K": air.temperature_K,
            "dynamic_pressure_Pa": 0.5 * air.density_kg_m3 * self.speed_m_s**2,
            "altitude_km": air.altitude_km,
            "atmosphere_source": air.source,
            "drag_reflections": self.used_mode(model),
            "atmosphere": air.to_json(),
            "reference_area_m2": area,
            "reference_length_m": length,
        }


#: The settings of an SRP or a drag sweep (the Earth's, :class:`~.earth_setup.EarthSetup`, import this
#: module); what the engine runs, whatever it is, is a :class:`Tabulation`.
Setup = SrpSetup | DragSetup


class Inputs(Protocol):
    """What a job evaluates, one entry per row, cut into chunks by a slice.

    An (n, 3) array of unit vectors (a sweep's Sun, flow or Earth directions), or the steps of an orbit
    (:class:`~sunwind.forces.orbit.inputs.StepInputs`): anything with a length and slices of itself.

    Attributes
    ----------
    __len__ : callable
        ``len(inputs)``: the number of rows.
    __getitem__ : callable
        ``inputs[lo:hi]``: the rows of a chunk, of the same kind (what a chunk's
        :meth:`Tabulation.evaluate` is given).

    Examples
    --------
    >>> import numpy as np
    >>> directions = np.eye(3)  # three Sun directions are inputs
    >>> len(directions), directions[1:3].shape
    (3, (2, 3))
    """

    def __len__(self) -> int:
        """The number of rows."""
        ...

    def __getitem__(self, index: slice, /) -> Any:
        """The rows of ``index``, a slice (a chunk)."""
        ...


@runtime_checkable
class Tabulation(Protocol):
    """What the sweep engine runs over a job's inputs, chunk by chunk.

    :func:`~sunwind.forces.tables.engine.run_jobs` runs it locally or on Dask workers (so it pickles),
    and checkpoints it by its description.

    :class:`SrpSetup`, :class:`DragSetup`, :class:`PosedSetup`,
    :class:`~sunwind.forces.tables.earth_setup.EarthSetup` and the orbit's
    :class:`~sunwind.forces.orbit.steps.OrbitLoads` are tabulations.

    Attributes
    ----------
    kind : str
        The name its records are kept under (``"srp"``, ``"drag"``, ``"earth"``, ``"srp@0"``,
        ``"orbit"``): one per job of a run.
    fields : dict of str to int
        The records of one input: name -> width (1: a number, else a row of that many).

    Methods
    -------
    precompute(model)
        Make what every input reuses (view factors, open skies), once, before the first chunk.
    evaluate(model, inputs)
        The records (:data:`Records`, :attr:`fields`) of ``inputs``, a chunk of the job's
        (:class:`Inputs`), one row each in their order.
    describe()
        JSON-ready settings: a checkpoint's fingerprint, a table's attributes.

    Examples
    --------
    >>> isinstance(SrpSetup(), Tabulation), isinstance(object(), Tabulation)
    (True, False)
    """

    @property
    def kind(self) -> str:
        """The name its records are kept under, one per job of a run."""
        ...

    @property
    def fields(self) -> dict[str, int]:
        """The records of one input: name -> width (1: a number, else a row of that many)."""
        ...

    def precompute(self, model: Model) -> None:
        """Make what every input reuses (view factors, open skies), once, before the first chunk."""
        ...

    def evaluate(self, model: Model, inputs: Any) -> Records:
        """The records (:attr:`fields`) of ``inputs``, a chunk of the job's, one row each in their order."""
        ...

    def describe(self) -> dict:
        """JSON-ready settings: a checkpoint's fingerprint, a table's attributes."""
        ...


@dataclass(frozen=True)
class PosedSetup:
    """A setup evaluated with hinges held at given angles: one pose of a sweep over hinge angles.

    Its records are kept apart under kind ``"srp@K"`` / ``"drag@K"``, ``K`` the pose's ``index``.

    Parameters
    ----------
    setup : SrpSetup or DragSetup
        What every attitude computes.
    angles : tuple of (str, float)
        ``(glob, deg)`` pairs: each hinge the glob names held at that angle [deg].
    index : int
        The pose's number among the sweep's poses.

    Examples
    --------
    >>> posed = PosedSetup(SrpSetup(reflections="none"), (("wing*", 30.0),), 1)
    >>> posed.kind, posed.describe()["hinge_angles_deg"]
    ('srp@1', {'wing*': 30.0})
    """

    setup: Setup
    angles: tuple[tuple[str, float], ...]
    index: int

    @property
    def kind(self) -> str:
        """The name the pose's records are kept under, ``"KIND@INDEX"``.

        Examples
        --------
        >>> PosedSetup(SrpSetup(), (), 3).kind
        'srp@3'
        """
        return f"{self.setup.kind}@{self.index}"

    @property
    def fields(self) -> dict[str, int]:
        """The records of an attitude, as the wrapped setup's: name -> width.

        Examples
        --------
        >>> PosedSetup(SrpSetup(), (), 0).fields["force_N"]
        3
        """
        return self.setup.fields

    def held(self, model: Model) -> Model:
        """The model with the hinges held at this pose's angles.

        Parameters
        ----------
        model : Model
            The loaded model, with the hinges the globs name.

        Returns
        -------
        Model
            The posed model.

        Raises
        ------
        InputError
            A glob that names no hinge of the model.

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
        >>> PosedSetup(SrpSetup(), (), 0).held(cube).craft.n_sides  # no hinges, nothing to turn
        12
        """
        return model.held(dict(self.angles))

    def precompute(self, model: Model) -> None:
        """Make what every attitude of the pose reuses (the wrapped setup's), on the posed model.

        Parameters
        ----------
        model : Model
            The loaded model.

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
        >>> PosedSetup(SrpSetup(reflections="none"), (), 0).precompute(cube)  # nothing to make
        """
        self.setup.precompute(self.held(model))

    def evaluate(self, model: Model, directions: NDArray[np.float64]) -> Records:
        """The records of directions ``directions`` on the posed model.

        Parameters
        ----------
        model : Model
            The loaded model.
        directions : (n, 3) float64
            Unit Sun (SRP) or flow (drag) directions, body frame.

        Returns
        -------
        Records
            One array per field of :attr:`fields`, a row per direction.

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
        >>> posed = PosedSetup(SrpSetup(reflections="none"), (), 0)
        >>> records = posed.evaluate(cube, np.array([[0.0, 0.0, 1.0]]))  # the Sun overhead
        >>> np.round(records["force_N"] * 1e6, 4) + 0.0  # [uN]
        array([[ 0.    ,  0.    , -5.4478]])
        """
        return self.setup.evaluate(self.held(model), directions)

    def describe(self) -> dict:
        """JSON-ready settings: the wrapped setup's, and the hinge angles.

        Returns
        -------
        dict
            :meth:`SrpSetup.describe` or :meth:`DragSetup.describe` with ``hinge_angles_deg``.

        Examples
        --------
        >>> PosedSetup(SrpSetup(), (("wing*", -15.0),), 2).describe()["hinge_angles_deg"]
        {'wing*': -15.0}
        """
        return self.setup.describe() | {"hinge_angles_deg": dict(self.angles)}


@dataclass(frozen=True, eq=False)
class Job:
    """One quantity over its inputs: the ``setup`` that evaluates each, and the ``inputs``.

    Attributes
    ----------
    setup : Tabulation
        What every input computes.
    inputs : Inputs
        Sun directions (SRP), flow directions (drag) or Earth directions (the Earth's radiation), (n, 3)
        unit vectors; or an orbit's steps (:class:`~sunwind.forces.orbit.inputs.StepInputs`).

    Examples
    --------
    >>> job = Job(SrpSetup(), np.eye(3))
    >>> job.kind, len(job.inputs), job.chunks(2)
    ('srp', 3, [(0, 2), (2, 3)])
    """

    setup: Tabulation
    inputs: Inputs

    @property
    def kind(self) -> str:
        """The setup's kind: the name its records are kept under."""
        return self.setup.kind

    @property
    def fields(self) -> dict[str, int]:
        """The records' fields: name -> width (1: a number, else a row of that many)."""
        return self.setup.fields

    def chunks(self, size: int) -> list[tuple[int, int]]:
        """Index ranges ``[lo, hi)`` of the chunks of at most ``size`` inputs.

        Parameters
        ----------
        size : int
            Inputs per chunk, >= 1.

        Returns
        -------
        list of (int, int)
            ``(lo, hi)`` in order, covering every input once; the last may be short.

        Examples
        --------
        >>> Job(SrpSetup(), np.eye(5)).chunks(2)
        [(0, 2), (2, 4), (4, 5)]
        """
        n = len(self.inputs)
        return [(lo, min(n, lo + size)) for lo in range(0, n, size)]
