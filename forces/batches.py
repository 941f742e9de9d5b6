"""Results of several attitudes: one result per attitude, and every per-attitude field stacked by name
(``batch.force_N`` is (n, 3), ``batch.rays`` (n,), ``batch.CD`` (n,)), with the same ``to_json()`` and a
``to_dataset()`` whose variables run along ``attitude``."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, fields, is_dataclass
from functools import cached_property
from typing import Generic, TypeVar

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.result_base import LoadResult, Result, stacked_variable
from sunwind.forces.results import DragResult, SrpResult
from sunwind.forces.vocabulary import ATTITUDE, COMPONENT, COMPONENT_ATTRS, COMPONENTS

R = TypeVar("R", bound=LoadResult)


@dataclass(frozen=True, eq=False)
class ResultBatch(Result, Generic[R]):
    """Results of several attitudes, in the order asked.

    Any per-attitude field or property of the results, asked of the batch, is that field of every
    result stacked: (n,) for numbers, (n, 3) for vectors (``batch.force_N``, ``batch.CD``,
    ``batch.azel_deg`` (n, 2), ``batch.k_is`` with NaN where a result has None). ``batch[k]`` is the
    k-th result itself, bit for bit the single call.

    Attributes
    ----------
    results : tuple of LoadResult
        One result per attitude.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box((1.0, 1.0, 1.0)), uniform=black, threads=1)
    >>> batch = sw.srp(cube, [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], reflections="none")
    >>> batch.force_N.shape, batch.lit_area_m2.round(6).tolist()
    ((2, 3), [1.0, 1.0])
    >>> dict(batch.to_dataset().sizes)
    {'attitude': 2, 'component': 3}
    """

    results: tuple[R, ...]

    def __len__(self) -> int:
        return len(self.results)

    def __getitem__(self, index: int) -> R:
        return self.results[index]

    def __iter__(self) -> Iterator[R]:
        return iter(self.results)

    def __getattr__(self, name: str) -> NDArray:
        # called only for names the batch itself lacks: a per-attitude field of the results
        if name.startswith("_") or name == "results" or not self._per_attitude(name):
            raise AttributeError(f"{type(self).__name__} has no attribute {name!r}")
        return self.stacked(name)

    def __dir__(self) -> list[str]:
        kind = type(self.results[0]) if self.results else LoadResult
        names = [name for name in dir(kind) if not name.startswith("_") and self._per_attitude(name)]
        return sorted({*super().__dir__(), *names})

    def _per_attitude(self, name: str) -> bool:
        """Whether ``name`` is a per-attitude value of the results (not a method or class constant)."""
        if not self.results:
            return False
        kind = type(self.results[0])
        if isinstance(getattr(kind, name, None), property | cached_property):
            return True
        return is_dataclass(kind) and name in {field.name for field in fields(kind)}

    def stacked(self, name: str) -> NDArray:
        """Field ``name`` of every result, stacked: (n,) for numbers, (n, 3) for vectors; a result's
        None (a quantity its call did not compute) is NaN.

        Parameters
        ----------
        name : str
            A field or property of the results, e.g. ``"force_N"``.

        Returns
        -------
        numpy.ndarray
        """
        values = [getattr(result, name) for result in self.results]
        if all(value is None for value in values):
            return np.full(len(values), np.nan)
        return np.array([np.nan if value is None else np.asarray(value) for value in values])

    def to_json(self) -> list[dict]:
        """One JSON summary per attitude (:meth:`~sunwind.forces.result_base.LoadResult.to_json`)."""
        return [result.to_json() for result in self.results]

    def to_dataset(self) -> xr.Dataset:
        """Every per-attitude field of :attr:`~sunwind.forces.result_base.LoadResult.VARIABLES` along the
        dimension ``attitude`` (vectors along ``component``), with the direction's azimuth and
        elevation [deg] as coordinates, units and long names on every variable, and the frame and
        reference point in the attributes (those of the first result).

        Returns
        -------
        xarray.Dataset
        """
        if not self.results:
            return xr.Dataset()
        first = self.results[0]
        variables = {name: stacked_variable(name, self.stacked(name), ATTITUDE) for name in first.VARIABLES}
        coords = {COMPONENT: (COMPONENT, list(COMPONENTS), COMPONENT_ATTRS)}
        if hasattr(first, "azel_deg"):
            azel = self.stacked("azel_deg").reshape(-1, 2)
            coords["azimuth_deg"] = (ATTITUDE, azel[:, 0], {"units": "degree", "long_name": "azimuth"})
            coords["elevation_deg"] = (ATTITUDE, azel[:, 1], {"units": "degree", "long_name": "elevation"})
        attrs = {
            key: value
            for key, value in first.dataset_attrs().items()
            if key not in ("azimuth_deg", "elevation_deg")
        }
        return xr.Dataset(variables, coords=coords, attrs=attrs)


class SrpBatch(ResultBatch[SrpResult]):
    """:class:`~sunwind.forces.results.SrpResult` of several Sun directions.

    Attributes
    ----------
    results : tuple of SrpResult
        One result per Sun direction, in the order asked.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> batch = sw.srp(cube, [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], reflections="none")
    >>> type(batch).__name__, batch.projected_area_m2.round(6).tolist()
    ('SrpBatch', [1.0, 1.414214])
    """


class DragBatch(ResultBatch[DragResult]):
    """:class:`~sunwind.forces.results.DragResult` of several flow velocities.

    Attributes
    ----------
    results : tuple of DragResult
        One result per velocity, in the order asked.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, {"O": 1.0})
    >>> batch = sw.drag(cube, [[7500.0, 0.0, 0.0], [0.0, 7500.0, 0.0]], air, reflections="none")
    >>> batch.CD.round(2).tolist()  # the same face-on drag either way
    [1.64, 1.64]
    """
