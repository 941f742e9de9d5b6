"""What every result shares: the same two ways out, :meth:`Result.to_json` and :meth:`Result.to_dataset`,
with the field names and units of :mod:`sunwind.forces.vocabulary` (METHOD.md "Outputs and tables");
and what the loads at one attitude share (:class:`LoadResult`): the totals, the reference point they
are taken about and the error the shadow pass estimates it left.

:class:`~sunwind.forces.results.SrpResult`, :class:`~sunwind.forces.results.DragResult` and
:class:`~sunwind.forces.earth.PlanetResult` are :class:`LoadResult`; a batch of them
(:class:`~sunwind.forces.batches.ResultBatch`) stacks the same fields along ``attitude``, and an orbit's
series (:class:`~sunwind.forces.orbit.results.OrbitResult`) along ``time``: every one a :class:`Result`.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from importlib.metadata import version
from typing import ClassVar

import numpy as np
import xarray as xr

from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.forces.sensitivity import Sensitivities
from sunwind.forces.vocabulary import COMPONENT, COMPONENT_ATTRS, COMPONENTS, variable_attrs

#: The frame every vector is given in.
FRAME = "body frame of the mesh"


class Result(ABC):
    """The base of every result sunwind gives: one attitude's loads (:class:`LoadResult`), a batch of
    them, an orbit's series. Each is written the same two ways, with the names and UDUNITS of
    :mod:`~sunwind.forces.vocabulary`, vectors along ``component``, the frame and the reference point
    stated.

    Examples
    --------
    >>> import sunwind as sw
    >>> sorted(name for name in ("to_json", "to_dataset") if callable(getattr(sw.Result, name)))
    ['to_dataset', 'to_json']
    >>> issubclass(sw.SrpBatch, sw.Result), issubclass(sw.OrbitResult, sw.Result)
    (True, True)
    """

    @abstractmethod
    def to_json(self) -> dict | list:
        """The result as plain JSON types; keys carry their units.

        Returns
        -------
        dict or list
        """

    @abstractmethod
    def to_dataset(self) -> xr.Dataset:
        """The result as an ``xarray.Dataset`` with units and long names on every variable.

        Returns
        -------
        xarray.Dataset
        """


class LoadResult(Result):
    """The base of every result of one attitude: body frame, SI units, units in the field names.

    A subclass is a frozen dataclass with at least ``force_N`` and ``torque_Nm`` (3,) [N, N m],
    ``reference_point_m`` (3,) [m], ``reference_point`` (where it came from), ``craft`` (the model) and
    ``shadow_error`` (the shadow pass's absolute error, or None); it lists in :attr:`VARIABLES` the
    numeric fields :meth:`to_dataset` and batches carry, and names its kind in :attr:`KIND`.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box((1.0, 1.0, 1.0)), uniform=black, threads=1)
    >>> result = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> isinstance(result, sw.LoadResult), result.KIND
    (True, 'srp')
    >>> round(float(result.force_N[0]) * 1e6, 3)  # µN: the flux over c on a black 1 m² face
    -4.54
    >>> result.to_dataset()["force_N"].dims
    ('component',)
    """

    #: What the result is of: "srp", "drag" or "planet radiation".
    KIND: ClassVar[str] = ""
    #: The numeric fields of one result that :meth:`to_dataset` writes and a batch stacks.
    VARIABLES: ClassVar[tuple[str, ...]] = ("force_N", "torque_Nm")

    @property
    def error_estimate(self) -> ErrorEstimate | None:
        """The shadow pass's estimated error relative to the total force and torque (None with fixed
        sampling, or where no shadow pass ran)."""
        error = self.shadow_error
        if error is None:
            return None
        return ErrorEstimate.of(error, self.force_N, self.torque_Nm, self.craft.diagonal_m)

    def to_json(self) -> dict:
        """The result as plain JSON types; keys carry their units, and say the frame and the point the
        torque is taken about.

        Returns
        -------
        dict
            ``frame``, ``force_N``, ``torque_Nm``, ``reference_point_m``, ``reference_point``,
            ``error_estimate`` and what the kind of result adds.
        """
        estimate = self.error_estimate
        return {
            "frame": FRAME,
            "force_N": self.force_N.tolist(),
            "torque_Nm": self.torque_Nm.tolist(),
            "reference_point_m": self.reference_point_m.tolist(),
            "reference_point": self.reference_point,
            "error_estimate": None if estimate is None else estimate.to_json(),
            **({} if self.sensitivities is None else {"sensitivities": self.sensitivities.to_json()}),
        }

    @property
    def sensitivities(self) -> Sensitivities | None:
        """d force and d torque per material coefficient (:class:`~sunwind.forces.sensitivity.Sensitivities`)
        when the result was asked for them; None otherwise (a subclass's field overrides this)."""
        return None

    def dataset_attrs(self) -> dict[str, object]:
        """Global attributes of :meth:`to_dataset`: frame, reference point and kind."""
        return {
            "kind": self.KIND,
            "frame": FRAME,
            "reference_point_m": list(map(float, self.reference_point_m)),
            "reference_point": self.reference_point,
            "sunwind_version": version("sunwind"),  # as sweep tables record it
        }

    def to_dataset(self) -> xr.Dataset:
        """The numeric fields of :attr:`VARIABLES` as an ``xarray.Dataset``: vectors along
        ``component`` (x, y, z), every variable with ``units`` and ``long_name``, the frame and the
        reference point in the attributes.

        Returns
        -------
        xarray.Dataset
        """
        variables = {name: _variable(name, getattr(self, name), ()) for name in self.VARIABLES}
        coords = {COMPONENT: (COMPONENT, list(COMPONENTS), COMPONENT_ATTRS)}
        return xr.Dataset(variables, coords=coords, attrs=self.dataset_attrs())


def _variable(name: str, value: object, dims: tuple[str, ...]) -> xr.Variable:
    """``value`` of field ``name`` as a variable over ``dims`` (and ``component`` if it is a vector);
    None (a quantity not computed) becomes NaN."""
    data = np.asarray(np.nan if value is None else value, dtype=float)
    vector = data.ndim > len(dims)
    return xr.Variable((*dims, COMPONENT) if vector else dims, data, variable_attrs(name))


def stacked_variable(name: str, values: np.ndarray, dim: str) -> xr.Variable:
    """``values`` of field ``name`` for every result of a batch as a variable over ``dim``.

    Parameters
    ----------
    name : str
        The field's name, which gives its units (:func:`~sunwind.forces.vocabulary.variable_attrs`).
    values : (n,) or (n, 3) array
        The field of every result; NaN where one has none.
    dim : str
        The batch's dimension, ``attitude``.

    Returns
    -------
    xarray.Variable
        Over ``dim`` (and ``component`` for vectors), with ``units`` and ``long_name``.

    Examples
    --------
    >>> import numpy as np
    >>> variable = stacked_variable("force_N", np.zeros((2, 3)), "attitude")
    >>> variable.dims, variable.attrs["units"]
    (('attitude', 'component'), 'N')
    """
    return _variable(name, values, (dim,))
