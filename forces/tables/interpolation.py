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
    """Azimuth/elevation axes of a grid table [deg]."""

    azimuth_deg: NDArray[np.float64]  # (n_a,) -180..180, both ends
    elevation_deg: NDArray[np.float64]  # (n_e,) -90..90, both ends
    azimuth_step_deg: float
    elevation_step_deg: float


class InterpolatedLoads(NamedTuple):
    """Force [N] and torque [N m] interpolated in a table (:class:`TableInterpolator`), body frame;
    torque about the table's reference point.

    Attributes
    ----------
    force_N, torque_Nm : ndarray, shape (..., 3)
        One vector per direction asked for.
    """

    force_N: NDArray[np.float64]  # (..., 3)
    torque_Nm: NDArray[np.float64]  # (..., 3)


def grid_axes(table: xr.Dataset, prefix: str) -> GridAxes:
    """The checked ``{prefix}_azimuth`` / ``{prefix}_elevation`` axes of a grid table.

    Raises
    ------
    InputError
        A list table (no such grid), or axes that are not regular, ascending and end to end.
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
    """Number of intervals of ``step_deg`` in ``span_deg``.

    Raises
    ------
    InputError
        The step does not divide the span (or, with ``whole_degrees``, is not a whole number of degrees).
    """
    count = span_deg / step_deg if step_deg > 0 else np.nan
    divides = bool(np.isfinite(count)) and abs(count - round(count)) < 1e-9 * max(count, 1.0)
    whole = not whole_degrees or abs(step_deg - round(step_deg)) < 1e-9
    if not (divides and whole):
        problem = f"does not divide {span_deg:g} deg" if not divides else "is not a whole number of degrees"
        raise InputError(f"{name} step {step_deg:g} deg {problem}", hint=step_advice(step_deg, whole_degrees))
    return round(count)


def azel_directions(azimuth_deg: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Unit vectors (..., 3) of azimuths and elevations [deg] (broadcast together), body frame."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    az, el = np.broadcast_arrays(az, el)
    return np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)


class TableInterpolator:
    """Force and torque of a sweep table at any Sun or flow direction.

    Parameters
    ----------
    table : xarray.Dataset or path
        A grid table (sunwind sweep contract), or a netCDF file holding one.
    method : {"bicubic", "bilinear"}
        Tensor-product kernel in (azimuth, elevation); see the module notes.

    Examples
    --------
    >>> interp = TableInterpolator("sweep.nc")                      # doctest: +SKIP
    >>> force_N, torque_Nm = interp.srp([[0.0, 0.6, 0.8]])           # doctest: +SKIP
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
        """SRP force [N] and torque [N m] for unit Sun vectors (..., 3) (spacecraft -> Sun, body frame).

        ``flux_W_m2`` rescales from the table's flux (SRP is linear in the flux); default: the table's.
        """
        values = self.values(["srp_force_N", "srp_torque_Nm"], sun_vectors)
        if flux_W_m2 is not None:
            values = values * (flux_W_m2 / float(self.table.attrs["flux_W_m2"]))
        return InterpolatedLoads(values[..., :3], values[..., 3:])

    def drag(self, flow_vectors: ArrayLike) -> InterpolatedLoads:
        """Drag force [N] and torque [N m] for flow vectors ``u = v_rel / |v_rel|`` (..., 3), body frame."""
        values = self.values(["drag_force_N", "drag_torque_Nm"], flow_vectors)
        return InterpolatedLoads(values[..., :3], values[..., 3:])

    def values(self, names: Sequence[str], directions: ArrayLike) -> NDArray[np.float64]:
        """Variables ``names`` (all SRP, all drag or all Earth) at ``directions`` (..., 3) (Sun, flow or
        Earth vectors, body frame), channels concatenated.

        A variable with a ``component`` dimension gives three channels, any other one.

        Raises
        ------
        InputError
            A variable missing from the table, a list table, or a zero/non-finite direction.
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
