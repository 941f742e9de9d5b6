"""Interpolation of sweep tables over the sphere of directions, periodic in azimuth and across the poles.

A grid table holds a quantity ``f(az, el)`` at azimuths -180..180 and elevations -90..90 (both ends, regular
steps; METHOD.md "Frames, units and signs": ``az = atan2(d_y, d_x)``, ``el = asin(d_z)``).
:class:`TableInterpolator` evaluates it at any body-frame direction by tensor-product interpolation in
(az, el):

- ``"bilinear"``: 2 x 2 nodes, error O(h^2) in the grid step h;
- ``"bicubic"``: 4 x 4 nodes with the Catmull-Rom (Keys, a = -1/2) kernel, C1, error O(h^3).

Both reproduce the table at its nodes. The map (az, el) -> direction is smooth on the whole plane and obeys
``d(az, el) = d(az + 180, 180 - el)``, so the table continues exactly past each pole: a ghost row at elevation
``90 + k h`` holds the row ``90 - k h`` turned by 180 deg in azimuth (likewise at -90). Azimuth wraps with
period 360 (the duplicated +180 column is dropped; the -180 column stands for both). Each pole row is one
point of the sphere, so its values are replaced by their mean over azimuth and the interpolant is single-
valued there. If 180 deg is not a whole number of azimuth steps, the turned ghost rows are themselves
interpolated in azimuth with the same kernel.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Literal, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.tables.attitudes import step_advice
from sunwind.geometry.errors import InputError

#: Direction prefix of the grid coordinates of each kind of table variable.
PREFIX = {"srp": "sun", "drag": "flow", "earth": "earth"}
#: How each kind is asked of a sweep, in hints.
_ASKED = {"srp": "SRP", "drag": "drag", "earth": "the Earth's radiation"}
METHODS = ("bilinear", "bicubic")
#: Queries evaluated per block, to bound the (n, 4, 4, k) gather in memory.
_BLOCK = 32_768


class GridAxes(NamedTuple):
    """Azimuth/elevation axes of a grid table [deg], as :func:`grid_axes` checks them.

    Attributes
    ----------
    azimuth_deg : ndarray of float64, shape (n_a,)
        Azimuths -180 to 180, both ends.
    elevation_deg : ndarray of float64, shape (n_e,)
        Elevations -90 to 90, both ends.
    azimuth_step_deg, elevation_step_deg : float
        The steps of the two axes [deg].

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.tables.interpolation import GridAxes
    >>> axes = GridAxes(np.linspace(-180, 180, 5), np.linspace(-90, 90, 3), 90.0, 90.0)
    >>> axes.elevation_deg.tolist(), axes.azimuth_step_deg
    ([-90.0, 0.0, 90.0], 90.0)
    """

    azimuth_deg: NDArray[np.float64]  # (n_a,) -180..180, both ends
    elevation_deg: NDArray[np.float64]  # (n_e,) -90..90, both ends
    azimuth_step_deg: float
    elevation_step_deg: float


class InterpolatedLoads(NamedTuple):
    """Force [N] and torque [N m] interpolated in a table (:class:`TableInterpolator`), body frame.

    The torque is about the table's reference point.

    Attributes
    ----------
    force_N, torque_Nm : ndarray, shape (..., 3)
        One vector per direction asked for.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.forces.tables.interpolation import InterpolatedLoads
    >>> force_N, torque_Nm = InterpolatedLoads(np.zeros((2, 3)), np.ones((2, 3)))  # unpacks as a tuple
    >>> force_N.shape, torque_Nm[0].tolist()
    ((2, 3), [1.0, 1.0, 1.0])
    """

    force_N: NDArray[np.float64]  # (..., 3)
    torque_Nm: NDArray[np.float64]  # (..., 3)


def grid_axes(table: xr.Dataset, prefix: str) -> GridAxes:
    """The checked ``{prefix}_azimuth`` / ``{prefix}_elevation`` axes of a grid table.

    Parameters
    ----------
    table : xarray.Dataset
        A grid table.
    prefix : str
        ``"sun"``, ``"flow"`` or ``"earth"`` (:data:`PREFIX`).

    Returns
    -------
    GridAxes
        The axes as exact regular values, and their steps.

    Raises
    ------
    InputError
        A list table (no such grid), or axes that are not regular, ascending and end to end.

    Examples
    --------

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=30.0)
    >>> from sunwind.forces.tables.interpolation import grid_axes
    >>> axes = grid_axes(table, "sun")
    >>> len(axes.azimuth_deg), len(axes.elevation_deg), axes.elevation_step_deg
    (13, 7, 30.0)
    >>> grid_axes(table, "flow")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: the table has no flow_azimuth/flow_elevation grid ...
    """
    az_name, el_name = f"{prefix}_azimuth", f"{prefix}_elevation"
    if az_name not in table.dims or el_name not in table.dims:
        raise InputError(
            f"the table has no {az_name}/{el_name} grid (dimensions: {', '.join(map(str, table.dims))})",
            hint="this needs a grid sweep, not a list of attitudes",
        )
    az, az_step = _regular_axis(table[az_name].values, az_name, 180.0)
    el, el_step = _regular_axis(table[el_name].values, el_name, 90.0)
    return GridAxes(az, el, az_step, el_step)


def check_step(step_deg: float, span_deg: float, name: str, whole_degrees: bool = False) -> int:
    """Number of intervals of ``step_deg`` in ``span_deg``, the step checked.

    Parameters
    ----------
    step_deg : float
        The step [deg].
    span_deg : float
        The span it must divide [deg].
    name : str
        What the step is, named in the error.
    whole_degrees : bool
        Also require a whole number of degrees.

    Returns
    -------
    int
        ``span_deg / step_deg``.

    Raises
    ------
    InputError
        The step does not divide the span (or, with ``whole_degrees``, is not a whole number of degrees);
        the hint suggests steps that do.

    Examples
    --------
    >>> from sunwind.forces.tables.interpolation import check_step
    >>> check_step(30.0, 180.0, "azimuth")
    6
    >>> check_step(7.0, 180.0, "azimuth")
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: azimuth step 7 deg does not divide 180 deg; ...
    """
    count = span_deg / step_deg if step_deg > 0 else np.nan
    divides = bool(np.isfinite(count)) and abs(count - round(count)) < 1e-9 * max(count, 1.0)
    whole = not whole_degrees or abs(step_deg - round(step_deg)) < 1e-9
    if not (divides and whole):
        problem = f"does not divide {span_deg:g} deg" if not divides else "is not a whole number of degrees"
        raise InputError(f"{name} step {step_deg:g} deg {problem}", hint=step_advice(step_deg, whole_degrees))
    return round(count)


def azel_directions(azimuth_deg: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Unit vectors of azimuths and elevations [deg], body frame.

    ``d = (cos el cos az, cos el sin az, sin el)``: azimuth from +x toward +y, elevation from the x-y
    plane toward +z.

    Parameters
    ----------
    azimuth_deg : array_like of float
        Azimuths [deg].
    elevation_deg : array_like of float
        Elevations [deg]; broadcast against ``azimuth_deg``.

    Returns
    -------
    ndarray of float64, shape (..., 3)
        One unit vector per broadcast pair.

    Examples
    --------
    >>> from sunwind.forces.tables.interpolation import azel_directions
    >>> azel_directions([0.0, 90.0], [0.0, 45.0]).round(4) + 0.0
    array([[1.    , 0.    , 0.    ],
           [0.    , 0.7071, 0.7071]])
    """
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    az, el = np.broadcast_arrays(az, el)
    return np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)


class TableInterpolator:
    """Force and torque of a sweep table at any Sun or flow direction.

    Interpolates in (azimuth, elevation), periodic in azimuth and continued across the poles (see the
    module notes); the table's nodes are reproduced exactly.

    Parameters
    ----------
    table : xarray.Dataset or path
        A grid table (sunwind sweep contract), or a netCDF file holding one.
    method : {"bicubic", "bilinear"}
        Tensor-product kernel in (azimuth, elevation); see the module notes.

    Attributes
    ----------
    table : xarray.Dataset
        The table, in memory.
    method : str
        The kernel.

    Raises
    ------
    InputError
        An unknown method.

    References
    ----------
    .. [1] Keys, R. G. (1981). "Cubic convolution interpolation for digital image processing". *IEEE
       Transactions on Acoustics, Speech, and Signal Processing* 29(6), 1153-1160 (the bicubic kernel,
       a = -1/2).
    .. [2] Catmull, E., Rom, R. (1974). "A class of local interpolating splines". In *Computer Aided
       Geometric Design*, 317-326. Academic Press.

    Examples
    --------
    A 30 deg table of a black 1 m cube, against SRP computed at the direction itself:

    >>> import numpy as np
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=30.0)
    >>> interpolator = sw.TableInterpolator(table)
    >>> sun = [[0.0, 0.6, 0.8]]
    >>> force_N, torque_Nm = interpolator.srp(sun)
    >>> (force_N * 1e6).round(2)  # [uN]
    array([[ 0.  , -3.74, -5.08]])
    >>> (sw.srp(cube, sun[0], reflections="none").force_N * 1e6).round(2)
    array([ 0.  , -3.81, -5.08])
    """

    def __init__(
        self, table: xr.Dataset | str | os.PathLike, method: Literal["bilinear", "bicubic"] = "bicubic"
    ) -> None:
        if method not in METHODS:
            raise InputError(
                f"unknown interpolation method {method!r}", hint=f"use one of {', '.join(METHODS)}"
            )
        if isinstance(table, (str, os.PathLike)):
            with xr.open_dataset(table) as opened:
                table = opened.load()
        self.table = table
        self.method = method
        self._grids: dict[tuple[str, ...], _SphereGrid] = {}

    def srp(self, sun_vectors: ArrayLike, flux_W_m2: float | None = None) -> InterpolatedLoads:
        """SRP force [N] and torque [N m] for unit Sun vectors (spacecraft -> Sun, body frame).

        Parameters
        ----------
        sun_vectors : array_like of float, shape (..., 3)
            Directions to the Sun, body frame (normalised here).
        flux_W_m2 : float, optional
            Solar flux [W/m^2]; the loads are scaled from the table's ``flux_W_m2`` (SRP is linear in the
            flux). Default: the table's.

        Returns
        -------
        InterpolatedLoads
            ``force_N`` and ``torque_Nm``, shape (..., 3).

        Raises
        ------
        InputError
            A table without SRP, a list table, or a zero or non-finite direction.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=30.0)
        >>> interpolator = sw.TableInterpolator(table)
        >>> at_half = interpolator.srp([[1.0, 0.0, 0.0]], flux_W_m2=1361.0 / 2).force_N
        >>> (at_half * 1e6).round(3)  # a node: the table's value, halved
        array([[-2.27,  0.  ,  0.  ]])
        """
        values = self.values(["srp_force_N", "srp_torque_Nm"], sun_vectors)
        if flux_W_m2 is not None:
            values = values * (flux_W_m2 / float(self.table.attrs["flux_W_m2"]))
        return InterpolatedLoads(values[..., :3], values[..., 3:])

    def drag(self, flow_vectors: ArrayLike) -> InterpolatedLoads:
        """Drag force [N] and torque [N m] for flow vectors ``u = v_rel / |v_rel|``, body frame.

        Parameters
        ----------
        flow_vectors : array_like of float, shape (..., 3)
            Flow directions, body frame (normalised here).

        Returns
        -------
        InterpolatedLoads
            ``force_N`` and ``torque_Nm``, shape (..., 3), at the table's speed and atmosphere.

        Raises
        ------
        InputError
            A table without drag, a list table, or a zero or non-finite direction.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=30.0)
        >>> sw.TableInterpolator(table).drag([[1.0, 0.0, 0.0]])
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: the table has no drag_force_N, drag_torque_Nm; ...
        """
        values = self.values(["drag_force_N", "drag_torque_Nm"], flow_vectors)
        return InterpolatedLoads(values[..., :3], values[..., 3:])

    def values(self, names: Sequence[str], directions: ArrayLike) -> NDArray[np.float64]:
        """Variables ``names`` at ``directions``, channels concatenated.

        A variable with a ``component`` dimension gives three channels, any other one. The padded grid of
        each group of names is made on first use and kept.

        Parameters
        ----------
        names : sequence of str
            Table variables, all SRP, all drag or all Earth (``srp_*``, ``drag_*``, ``earth_*``).
        directions : array_like of float, shape (..., 3)
            Sun, flow or Earth vectors, body frame (normalised here).

        Returns
        -------
        ndarray of float64, shape (..., k)
            The ``k`` channels of the variables, in order, at each direction.

        Raises
        ------
        InputError
            Variables of different kinds, a variable missing from the table, a list table, or a zero or
            non-finite direction.

        Examples
        --------

        >>> import numpy as np
        >>> import sunwind as sw
        >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
        >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
        >>> table = sw.sweep(cube, srp=sw.SrpSetup(reflections="none"), step_deg=30.0)
        >>> interpolator = sw.TableInterpolator(table, "bilinear")
        >>> interpolator.values(["srp_lit_area_m2", "srp_force_N"], [[0.0, 0.0, 1.0]]).shape
        (1, 4)
        >>> interpolator.values(["srp_lit_area_m2"], [[0.0, 0.0, 1.0]]).round(6)  # a pole node: one face
        array([[1.]])
        """
        key = tuple(names)
        if key not in self._grids:
            self._grids[key] = _SphereGrid.from_table(self.table, key, self.method)
        d = np.asarray(directions, dtype=np.float64)
        if d.shape[-1:] != (3,):
            raise InputError(f"directions must have shape (..., 3), got {d.shape}", hint="one x y z row each")
        flat = d.reshape(-1, 3)
        norms = np.linalg.norm(flat, axis=1)
        if not (np.isfinite(norms).all() and (norms > 0).all()):
            raise InputError("directions must be finite and non-zero", hint="e.g. [[1, 0, 0]]")
        out = self._grids[key](flat / norms[:, None])
        return out.reshape(*d.shape[:-1], out.shape[-1])


class _SphereGrid:
    """Padded node values (N, n_e + 4, k) of one group of variables, ready for stencil gathers."""

    def __init__(self, values: NDArray[np.float64], axes: GridAxes, method: str) -> None:
        self.method = method
        self.az_step = axes.azimuth_step_deg
        self.el_step = axes.elevation_step_deg
        self.n_el = len(axes.elevation_deg)
        nodes = values[:-1].copy()  # drop the duplicated +180 column
        nodes[:, 0] = nodes[:, 0].mean(axis=0)
        nodes[:, -1] = nodes[:, -1].mean(axis=0)
        n_az = len(nodes)
        rows = [2, 1, self.n_el - 2, self.n_el - 3]  # mirrored across the south, then the north pole
        turned = _periodic_resample(nodes[:, rows], np.arange(n_az) + n_az / 2, method)
        self.nodes = np.concatenate([turned[:, :2], nodes, turned[:, 2:]], axis=1)

    @classmethod
    def from_table(cls, table: xr.Dataset, names: tuple[str, ...], method: str) -> _SphereGrid:
        kinds = {name.split("_", 1)[0] for name in names}
        if len(kinds) != 1 or not kinds <= PREFIX.keys():
            raise InputError(
                f"cannot interpolate {', '.join(names)} together", hint="all srp_*, all drag_* or all earth_*"
            )
        kind = kinds.pop()
        missing = [name for name in names if name not in table.data_vars]
        if missing:
            raise InputError(
                f"the table has no {', '.join(missing)}",
                hint=f"run the sweep with {_ASKED[kind]} included",
            )
        prefix = PREFIX[kind]
        axes = grid_axes(table, prefix)
        if len(axes.elevation_deg) < 3:
            raise InputError(
                f"{prefix}_elevation needs at least 3 rows (-90, 0, 90)", hint="use a finer step"
            )
        grid_dims = (f"{prefix}_azimuth", f"{prefix}_elevation")
        shape = (len(axes.azimuth_deg), len(axes.elevation_deg), -1)
        columns = [table[name].transpose(*grid_dims, ...).values.reshape(shape) for name in names]
        return cls(np.concatenate(columns, axis=-1).astype(np.float64), axes, method)

    def __call__(self, directions: NDArray[np.float64]) -> NDArray[np.float64]:
        """Interpolated values (n, k) at unit directions (n, 3)."""
        return np.concatenate(
            [self._block(directions[i : i + _BLOCK]) for i in range(0, len(directions), _BLOCK)]
            or [np.empty((0, self.nodes.shape[-1]))]
        )

    def _block(self, d: NDArray[np.float64]) -> NDArray[np.float64]:
        az = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
        el = np.degrees(np.arcsin(np.clip(d[:, 2], -1.0, 1.0)))
        n_az = len(self.nodes)
        fa = (az + 180.0) / self.az_step
        ia = np.floor(fa)
        fe = (el + 90.0) / self.el_step
        ie = np.clip(np.floor(fe), 0, self.n_el - 2)
        offsets, wa = _kernel(fa - ia, self.method)
        _, we = _kernel(fe - ie, self.method)
        cols = (ia.astype(np.int64)[:, None] + offsets) % n_az
        rows = ie.astype(np.int64)[:, None] + offsets + 2
        stencil = self.nodes[cols[:, :, None], rows[:, None, :]]
        return np.einsum("na,nb,nabk->nk", wa, we, stencil)


def _kernel(t: NDArray[np.float64], method: str) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Node offsets (s,) and weights (n, s) at fractional positions ``t`` in [0, 1]."""
    if method == "bilinear":
        return np.array([0, 1]), np.stack([1.0 - t, t], axis=-1)
    t2, t3 = t * t, t * t * t
    weights = np.stack(
        [(-t3 + 2 * t2 - t) / 2, (3 * t3 - 5 * t2 + 2) / 2, (-3 * t3 + 4 * t2 + t) / 2, (t3 - t2) / 2],
        axis=-1,
    )
    return np.array([-1, 0, 1, 2]), weights


def _periodic_resample(values: NDArray[np.float64], positions: NDArray[np.float64], method: str) -> NDArray:
    """``values`` (N, ...) periodic along axis 0, at fractional node ``positions`` (m,)."""
    base = np.floor(positions)
    offsets, weights = _kernel(positions - base, method)
    index = (base.astype(np.int64)[:, None] + offsets) % len(values)
    return np.einsum("ms,ms...->m...", weights, values[index])


def _regular_axis(values: NDArray, name: str, half_span: float) -> tuple[NDArray[np.float64], float]:
    v = np.asarray(values, dtype=np.float64)
    if v.ndim != 1 or len(v) < 2:
        raise InputError(f"{name} must have at least two values, -{half_span:g} and {half_span:g}")
    step = 2 * half_span / (len(v) - 1)
    expected = np.linspace(-half_span, half_span, len(v))
    if not np.allclose(v, expected, rtol=0, atol=1e-6 * step):
        raise InputError(
            f"{name} must run from {-half_span:g} to {half_span:g} deg in equal ascending steps, "
            f"got {v[0]:g}..{v[-1]:g} in {len(v)} values",
            hint="sweep with a step that divides the range, both ends included",
        )
    return expected, step
