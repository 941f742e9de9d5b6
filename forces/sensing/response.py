"""What each sensor part absorbs of a parallel beam from any direction, condensed once per model
(METHOD.md "Attitude from heat fluxes").

A sensor's absorbed power per unit flux of a beam along ``d`` is the plate law of its sides,
``sum_i a_i A_i max(n_i . d, 0)`` (absorptance ``a_i = 1 - rho - sigma`` in the band), plus a
*correction*: what self-shadowing takes off and inter-reflection adds. The plate law is evaluated
exactly at any direction; the correction is found once per model by the planet-radiation machinery
itself (:func:`~sunwind.forces.planet.loads.band_loads`: one shadow pass, the beam chains and the
diffuse balance, per node of an icosphere of directions) and interpolated linearly on the grid's
triangles, second order in the node spacing. A model that nothing shadows and nothing reflects onto
(a convex body, or the ``plates`` mode) has no correction: its response is exact.
"""

from __future__ import annotations

import fnmatch
import functools
import hashlib
from dataclasses import dataclass, field, replace
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.model import Model, as_model
from sunwind.forces.planet.loads import Source, band_loads
from sunwind.forces.planet.visibility import DirectionGrid, direction_grid
from sunwind.forces.reflection import ReflectionSettings, reflection_plan
from sunwind.forces.thermal import infrared_exchange
from sunwind.geometry.errors import InputError
from sunwind.geometry.parallel import using_threads
from sunwind.geometry.progress import advance, step
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import Spacecraft, infrared_optics
from sunwind.geometry.views.disk_cache import cache_directory, geometry_key, kept_on_disk

#: The optics bands a response keeps: sunlight and albedo (solar), the planet's infrared.
BANDS = ("solar", "infrared")
#: Default icosphere level of the correction's grid (2 562 nodes about 4.3 degrees apart).
DEFAULT_LEVEL = 4


@dataclass(frozen=True, eq=False)
class SensorResponse:
    """Each sensor's absorbed power per unit flux of a parallel beam, from any direction; body frame.

    Attributes
    ----------
    sensors : tuple of str
        The sensor parts, in the order of every per-sensor axis.
    areas_m2 : (p,) float64
        Each sensor's area: its sides' areas summed [m^2] (the fluxes are per this area).
    normals : (u,) float64 array of shape (u, 3)
        The distinct outward normals of the sensors' sides.
    plate_m2 : dict of str to (p, u) float64
        Per band, ``sum a_i A_i`` of each sensor's sides with each normal [m^2].
    grid : DirectionGrid
        The directions the correction is known at.
    correction_m2 : dict of str to (n, p) float64, or None
        Per band, absorbed power per unit flux at each node minus the plate law [m^2]; None when there
        is none (nothing shadows or reflects onto a sensor).
    reflections : str
        The inter-reflection mode the correction follows.
    origin : str
        "computed", or the disk-cache entry it was read from.
    tracer : BeamTracer or None
        Traces one beam exactly (sunlight at a call, the correction's nodes); None with no correction.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=sw.Material("black", 0.07, 0.0, emissivity=0.82),
    ...                threads=1)
    >>> response = sensor_response(cube)
    >>> response.sensors[:2], response.correction_m2 is None  # a convex cube: the plate law is exact
    (('sensor_px', 'sensor_mx'), True)
    >>> np.round(response.collimated("solar", np.array([[1.0, 0.0, 0.0]]))[0] / response.areas_m2, 3)
    array([0.93, 0.  , 0.  , 0.  , 0.  , 0.  ])
    """

    sensors: tuple[str, ...]
    areas_m2: NDArray[np.float64]
    normals: NDArray[np.float64]
    plate_m2: dict[str, NDArray[np.float64]]
    grid: DirectionGrid
    correction_m2: dict[str, NDArray[np.float64]] | None
    reflections: str
    origin: str = field(default="computed", compare=False)
    tracer: BeamTracer | None = field(default=None, compare=False, repr=False)

    BANDS: ClassVar[tuple[str, ...]] = BANDS

    def plate(self, band: str, directions: NDArray[np.float64]) -> NDArray[np.float64]:
        """The plate law alone: ``sum a_i A_i max(n_i . d, 0)`` per sensor [m^2], (k, p).

        Parameters
        ----------
        band : str
            "solar" or "infrared".
        directions : (k, 3) float64
            Unit beam directions (from the spacecraft toward the source), body frame.

        Returns
        -------
        (k, p) float64
            Absorbed power per unit flux [W per W/m^2].

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", 0.5, 0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1)
        >>> sensor_response(cube).plate("solar", np.array([[0.0, 0.6, 0.8]])).round(4)
        array([[0.   , 0.   , 0.003, 0.   , 0.004, 0.   ]])
        """
        return np.maximum(directions @ self.normals.T, 0.0) @ self.plate_m2[band].T

    def correction(self, band: str, directions: NDArray[np.float64]) -> NDArray[np.float64]:
        """The correction for shadowing and reflections, interpolated at ``directions`` [m^2], (k, p).

        Parameters
        ----------
        band : str
            "solar" or "infrared".
        directions : (k, 3) float64
            Unit directions, body frame.

        Returns
        -------
        (k, p) float64
            Zero when the model has no correction.

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", 0.5, 0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1)
        >>> sensor_response(cube).correction("solar", np.eye(3)).shape
        (3, 6)
        """
        if self.correction_m2 is None:
            return np.zeros((len(directions), len(self.sensors)))
        face, share = self.grid.locate(directions)
        corners = self.correction_m2[band][self.grid.faces[face]]  # (k, 3 corners, p)
        return np.einsum("kc,kcp->kp", share, corners)

    def traced(self, band: str, direction: NDArray[np.float64]) -> NDArray[np.float64]:
        """Absorbed power per unit flux of one parallel beam, traced exactly where the model has a
        correction (:class:`BeamTracer`), else the plate law [m^2], (p,).

        Parameters
        ----------
        band : str
            "solar" or "infrared".
        direction : (3,) float64
            Unit beam direction (toward the source), body frame.

        Returns
        -------
        (p,) float64

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", 0.5, 0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1)
        >>> round(float(sensor_response(cube).traced("solar", np.array([0.0, 0.0, 1.0]))[4]), 12)
        0.005
        """
        if self.tracer is None:
            return self.plate(band, direction[None, :])[0]
        return self.tracer.absorbed(band, direction)

    def collimated(self, band: str, directions: NDArray[np.float64]) -> NDArray[np.float64]:
        """Absorbed power per unit flux of a parallel beam along each direction [m^2], (k, p): the plate
        law plus the correction.

        Parameters
        ----------
        band : str
            "solar" or "infrared".
        directions : (k, 3) float64
            Unit beam directions (toward the source), body frame.

        Returns
        -------
        (k, p) float64

        Examples
        --------
        >>> import sunwind as sw
        >>> grey = sw.Material("grey", 0.5, 0.0, emissivity=0.8)
        >>> cube = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1)
        >>> round(float(sensor_response(cube).collimated("solar", np.array([[0.0, 0.0, -1.0]]))[0, 5]), 12)
        0.005
        """
        return self.plate(band, directions) + self.correction(band, directions)


def sensor_parts(craft: Spacecraft, patterns: tuple[str, ...] | None) -> tuple[str, ...]:
    """The parts matching ``patterns`` (shell-style, each must match one at least), in the model's order;
    every part without patterns.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    patterns : tuple of str or None
        Part-name patterns (``fnmatch``: ``sensor_*``).

    Returns
    -------
    tuple of str

    Raises
    ------
    InputError
        A pattern that matches no part (the parts are named).

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", 0.5, 0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1).craft
    >>> sensor_parts(craft, ("sensor_p*",))
    ('sensor_px', 'sensor_py', 'sensor_pz')
    """
    names = craft.part_names
    if not patterns:
        return tuple(names)
    for pattern in patterns:
        if not fnmatch.filter(names, pattern):
            raise InputError(
                f"sensor pattern {pattern!r} matches no part of the model",
                hint=f"the parts are {', '.join(names)}",
                parameters=("sensors",),
            )
    return tuple(name for name in names if any(fnmatch.fnmatchcase(name, p) for p in patterns))


def sensor_response(
    model: Model | Spacecraft,
    sensors: tuple[str, ...] | None = None,
    reflections: str | ReflectionSettings = "auto",
    level: int = DEFAULT_LEVEL,
    sampling: ShadowSampling | None = None,
) -> SensorResponse:
    """Each sensor part's absorbed power per unit flux of a parallel beam, as a function of direction.

    Parameters
    ----------
    model : Model or Spacecraft
        The loaded model; every sensor's material needs an emissivity (the infrared band).
    sensors : tuple of str, optional
        Part-name patterns (:func:`sensor_parts`); default every part.
    reflections : str or ReflectionSettings
        As for :func:`~sunwind.forces.earth.planet_radiation`.
    level : int
        Icosphere level of the correction's grid (:func:`~sunwind.forces.planet.visibility
        .direction_grid`); 4: 2 562 nodes, one shadow pass and chain trace per node and band.
    sampling : ShadowSampling, optional
        The shadow passes' sampling.

    Returns
    -------
    SensorResponse
        Read from the disk cache when it was made before for the same geometry, optics and settings.

    Raises
    ------
    InputError
        A sensor pattern that matches no part, or a level outside [1, 6].
    MaterialError
        A side without an emissivity.

    Examples
    --------
    A panel hinged on the cube shades its +y sensor from light that comes from above and in front:

    >>> import sunwind as sw
    >>> grey = sw.Material("grey", 0.2, 0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.sensor_cube(panel=True), uniform=grey, threads=1)
    >>> response = sensor_response(craft, sensors=("sensor_py",), level=2)
    >>> response.sensors, response.correction_m2["solar"].shape
    (('sensor_py',), (162, 1))
    """
    if not (isinstance(level, int) and 1 <= level <= 6):
        raise InputError(f"level {level!r} is not an integer in [1, 6]", parameters=("level",))
    model = as_model(model)
    craft = model.craft
    names = sensor_parts(craft, sensors)
    settings = ReflectionSettings.of(reflections)
    shadows = ShadowSampling.of(sampling)
    plain = SensorResponse(names, *_plates(craft, names), direction_grid(level), None, "plates")
    with using_threads(model.threads):
        mode = reflection_plan(craft, settings).mode
        needed = mode not in ("none", "plates") or not bool(np.all(clearance(craft).open_sky))
        if not needed or mode == "plates":
            return replace(plain, reflections=mode)
        index = np.array([craft.part_names.index(name) for name in names])
        tracer = BeamTracer(craft, index, settings, shadows)
        made = _kept_correction(tracer, plain)
    return replace(plain, correction_m2=made.values, reflections=mode, origin=made.origin, tracer=tracer)


@dataclass
class _Correction:
    values: dict[str, NDArray[np.float64]]
    origin: str = "computed"


def _band_optics(craft: Spacecraft) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return craft.side_optics, infrared_optics(craft)


def _kept_correction(tracer: BeamTracer, plain: SensorResponse) -> _Correction:
    """The correction tables of ``plain`` (its plate law and grid), from the disk cache or made (and
    stored)."""
    craft, settings, sampling = tracer.craft, tracer.settings, tracer.sampling
    names, level = plain.sensors, plain.grid.level
    build = functools.partial(_correction, tracer, plain)
    directory = cache_directory(settings.cache_dir)
    if directory is None:
        return build()
    optics = np.concatenate(_band_optics(craft))
    key = {
        "kind": "sensor response",
        "sensors": list(names),
        "level": level,
        "mode": settings.mode,
        "samples": sampling.samples,
        "tolerance": sampling.tolerance,
        "cutoff": settings.cutoff,
        "depth": settings.depth,
        "optics": hashlib.sha256(np.ascontiguousarray(optics, dtype="<f8").tobytes()).hexdigest(),
        "parts": hashlib.sha256(np.ascontiguousarray(craft.facet_part, dtype="<i4").tobytes()).hexdigest(),
    }
    return kept_on_disk(
        directory,
        "sensor_response",
        geometry_key(craft, key),
        build,
        lambda made: made.values,
        lambda arrays, origin: _Correction({band: np.asarray(arrays[band]) for band in BANDS}, origin),
    )


@dataclass(frozen=True, eq=False)
class BeamTracer:
    """The sensors' absorbed power per unit flux of one parallel beam, traced as
    :func:`~sunwind.forces.earth.planet_radiation` traces sunlight: one shadow pass, the beam chains and
    the diffuse balance.

    Attributes
    ----------
    craft : Spacecraft
    index : (p,) int64
        The sensors' part indices.
    settings : ReflectionSettings
    sampling : ShadowSampling

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", 0.2, 0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.sensor_cube(), uniform=grey, threads=1).craft
    >>> tracer = BeamTracer(craft, np.arange(6), sw.ReflectionSettings("none"), sw.ShadowSampling())
    >>> tracer.absorbed("solar", np.array([0.0, 0.0, 1.0])).round(6)  # the top face: 0.8 x 0.01 m^2
    array([0.   , 0.   , 0.   , 0.   , 0.008, 0.   ])
    """

    craft: Spacecraft
    index: NDArray[np.int64]
    settings: ReflectionSettings
    sampling: ShadowSampling

    @functools.cached_property
    def _plan(self) -> tuple[str, dict, dict]:
        """The reflection mode, and each band's diffuse exchange and optics: made on the first trace."""
        plan = reflection_plan(self.craft, self.settings)
        full = plan.mode == "full"
        exchanges = {
            "solar": plan.exchange if full else None,
            "infrared": infrared_exchange(self.craft, self.settings) if full else None,
        }
        return plan.mode, exchanges, dict(zip(BANDS, _band_optics(self.craft), strict=True))

    def absorbed(self, band: str, direction: NDArray[np.float64]) -> NDArray[np.float64]:
        """Each sensor's absorbed power per unit flux of a beam from ``direction`` [m^2], (p,).

        Parameters
        ----------
        band : str
            "solar" or "infrared" (the optics used).
        direction : (3,) float64
            Unit vector toward the source, body frame.

        Returns
        -------
        (p,) float64
        """
        craft = self.craft
        mode, exchanges, optics = self._plan
        cos = np.maximum(craft.side_normals @ direction, 0.0)
        source = Source(
            name=band,
            integrals=(cos, cos[:, None] * direction, cos * cos),
            weights=np.ones(1),
            optics=optics[band],
            beams=mode in ("specular", "full") and band == "solar",
            exchange=exchanges[band],
        )
        (load,), _ = band_loads(
            craft, [source], direction[None, :], np.zeros(3), self.sampling, self.settings
        )
        part, count = craft.facet_part[craft.side_facet], len(craft.part_names)
        total = np.bincount(part, load.absorbed_side_W, count) + load.reflections.absorbed_by_group(
            part, count
        )
        return total[self.index]


def _correction(tracer: BeamTracer, plain: SensorResponse) -> _Correction:
    """One trace per node and band: the sensors' absorbed power per unit flux minus their plate law."""
    nodes = plain.grid.nodes
    values = {}
    with step("sensor response"):
        for k, band in enumerate(BANDS):
            absorbed = np.zeros((len(nodes), len(plain.sensors)))
            for j, direction in enumerate(nodes):
                absorbed[j] = tracer.absorbed(band, direction)
                advance(1, 2 * len(nodes)) if (k * len(nodes) + j) % 64 == 63 else None
            values[band] = absorbed - plain.plate(band, nodes)
    return _Correction(values)


def _plates(
    craft: Spacecraft, names: tuple[str, ...]
) -> tuple[NDArray[np.float64], NDArray[np.float64], dict[str, NDArray[np.float64]]]:
    """Each sensor's area, the distinct normals of the sensors' sides and each band's plate table (the
    fields of :class:`SensorResponse` of those names)."""
    part = craft.facet_part[craft.side_facet]
    sensor_of = np.full(len(craft.part_names), -1)
    sensor_of[[craft.part_names.index(name) for name in names]] = np.arange(len(names))
    mine = np.flatnonzero(sensor_of[part] >= 0)
    areas = np.bincount(sensor_of[part[mine]], craft.side_areas[mine], len(names))
    normals, which = np.unique(craft.side_normals[mine], axis=0, return_inverse=True)
    plate = {}
    for band, optics in zip(BANDS, _band_optics(craft), strict=True):
        absorbed = (1.0 - optics[mine, 0] - optics[mine, 2]) * craft.side_areas[mine]
        table = np.zeros((len(names), len(normals)))
        np.add.at(table, (sensor_of[part[mine]], which.reshape(-1)), absorbed)
        plate[band] = table
    return areas, np.ascontiguousarray(normals), plate
