"""Sensitivities in sweeps and orbits: the derivatives of force and torque with respect to every
material's coefficients (METHOD.md "Sensitivities") as records of a step or an attitude, and as table
variables on ``(..., material, coefficient, component)``.

A result's :class:`~sunwind.forces.sensitivity.Sensitivities` is recorded flat, one row of
``n_materials * 7 * 3`` numbers per attitude for the force (``sensitivity_force_N``) and one for the
torque (``sensitivity_torque_Nm``), materials in the model's order and coefficients in
:data:`~sunwind.forces.sensitivity.COEFFICIENTS` order: records of fixed widths, checkpointed as any other.

>>> sensitivity_fields(("white", "black"))
{'sensitivity_force_N': 42, 'sensitivity_torque_Nm': 42}
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterable, Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.sensitivity import COEFFICIENTS, Sensitivities
from sunwind.forces.vocabulary import COMPONENT
from sunwind.geometry.errors import InputError

#: The records of the derivatives: d force / d coefficient [N] and d torque / d coefficient [N m].
SENSITIVITY_FIELDS = ("sensitivity_force_N", "sensitivity_torque_Nm")
#: The dimensions a derivative has besides those of its attitude or step.
SENSITIVITY_DIMS = ("material", "coefficient", COMPONENT)
#: Units and what each record is, in the long names of its variables.
_ATTRS = {
    "sensitivity_force_N": ("N", "d force / d coefficient, body frame"),
    "sensitivity_torque_Nm": ("N m", "d torque about the reference point / d coefficient, body frame"),
}


def sensitivity_fields(materials: Sequence[str]) -> dict[str, int]:
    """The records of the derivatives of a model with these materials: name -> width.

    Parameters
    ----------
    materials : sequence of str
        The model's material names.

    Returns
    -------
    dict of str to int
        :data:`SENSITIVITY_FIELDS`, each ``len(materials) * 7 * 3`` wide.

    Examples
    --------
    >>> sensitivity_fields(["paint"])["sensitivity_torque_Nm"]
    21
    """
    return dict.fromkeys(SENSITIVITY_FIELDS, len(materials) * len(COEFFICIENTS) * 3)


def sensitivity_keyword(function: Callable, kind: str, on: bool) -> dict[str, bool]:
    """The keyword that asks ``function`` for sensitivities, refused when it takes none.

    Parameters
    ----------
    function : callable
        What computes the kind (:func:`~sunwind.forces.srp.srp`, :func:`~sunwind.forces.drag.drag`,
        :func:`~sunwind.forces.earth.planet_radiation`).
    kind : str
        The kind, named in the error.
    on : bool
        Whether sensitivities are asked for.

    Returns
    -------
    dict
        ``{"sensitivities": True}``, or empty when ``on`` is false.

    Raises
    ------
    InputError
        ``on`` and ``function`` has no ``sensitivities`` keyword.

    Examples
    --------
    >>> from sunwind.forces.srp import srp
    >>> sensitivity_keyword(srp, "srp", True), sensitivity_keyword(srp, "srp", False)
    ({'sensitivities': True}, {})
    >>> sensitivity_keyword(print, "print", True)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: sensitivities of print are not available yet...
    """
    if not on:
        return {}
    try:
        takes = "sensitivities" in inspect.signature(function).parameters
    except (TypeError, ValueError):  # a builtin without a signature takes none
        takes = False
    if not takes:
        raise InputError(
            f"sensitivities of {kind} are not available yet ({getattr(function, '__name__', function)}() "
            "takes no sensitivities)",
            hint=f"leave sensitivities out, or compute {kind} without them in a run of its own",
            parameters=("sensitivities",),
        )
    return {"sensitivities": True}


def flat(sensitivities: Sensitivities | None, materials: Sequence[str]) -> dict[str, NDArray[np.float64]]:
    """One attitude's derivatives as records: each of :data:`SENSITIVITY_FIELDS` one flat row.

    Parameters
    ----------
    sensitivities : Sensitivities or None
        A result's derivatives; None for a result not computed (no load, no derivative): zeros.
    materials : sequence of str
        The model's material names, the order of the rows.

    Returns
    -------
    dict of str to ndarray
        ``(len(materials) * 21,)`` float64 each.

    Raises
    ------
    ValueError
        Derivatives of other materials.

    Examples
    --------
    >>> flat(None, ["paint"])["sensitivity_force_N"].shape
    (21,)
    """
    if sensitivities is None:
        return {name: np.zeros(width) for name, width in sensitivity_fields(materials).items()}
    if tuple(sensitivities.materials) != tuple(materials):
        raise ValueError(f"sensitivities of {sensitivities.materials}, not of the model's {tuple(materials)}")
    return {
        "sensitivity_force_N": np.ravel(sensitivities.force_N).astype(np.float64),
        "sensitivity_torque_Nm": np.ravel(sensitivities.torque_Nm).astype(np.float64),
    }


def sensitivity_records(
    results: Iterable[object], materials: Sequence[str]
) -> dict[str, NDArray[np.float64]]:
    """The derivatives of some attitudes' results as records, one row per result.

    Parameters
    ----------
    results : iterable of results
        Each with a ``sensitivities`` attribute (None: zeros).
    materials : sequence of str
        The model's material names.

    Returns
    -------
    dict of str to ndarray
        :data:`SENSITIVITY_FIELDS`, ``(n, len(materials) * 21)`` float64 each.

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.25)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> batch = sw.srp(cube, [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], reflections="none", sensitivities=True)
    >>> sensitivity_records(batch, ["grey"])["sensitivity_force_N"].shape
    (2, 21)
    """
    rows = [flat(result.sensitivities, materials) for result in results]
    return {
        name: np.stack([row[name] for row in rows]).reshape(len(rows), width)
        for name, width in sensitivity_fields(materials).items()
    }


def sensitivity_variables(
    records: dict[str, NDArray[np.float64]],
    prefix: str,
    dims: tuple[str, ...],
    shape: tuple[int, ...],
    title: str,
) -> dict[str, xr.Variable]:
    """Take the derivatives out of ``records`` as table variables.

    Parameters
    ----------
    records : dict of str to ndarray
        Records, ``(n, width)`` for the derivatives; those of :data:`SENSITIVITY_FIELDS` are removed.
    prefix : str
        Put before each variable's name (``"srp_"``; empty for none).
    dims : tuple of str
        The dimensions of the attitudes or steps.
    shape : tuple of int
        Their sizes, multiplying to ``n``.
    title : str
        What the quantity is called at the head of the long names (``"SRP"``; empty for none).

    Returns
    -------
    dict of str to xarray.Variable
        ``PREFIXsensitivity_force_N`` and ``PREFIXsensitivity_torque_Nm`` on
        ``(*dims, material, coefficient, component)``, with ``units`` and ``long_name``; empty when
        ``records`` holds none.

    Examples
    --------
    >>> records = {"sensitivity_force_N": np.zeros((4, 21)), "sensitivity_torque_Nm": np.zeros((4, 21))}
    >>> variables = sensitivity_variables(records, "srp_", ("a", "b"), (2, 2), "SRP")
    >>> variables["srp_sensitivity_force_N"].dims, records
    (('a', 'b', 'material', 'coefficient', 'component'), {})
    >>> variables["srp_sensitivity_torque_Nm"].attrs["units"]
    'N m'
    """
    out = {}
    for name in SENSITIVITY_FIELDS:
        if name not in records:
            continue
        values = records.pop(name)
        units, what = _ATTRS[name]
        data = values.reshape(*shape, -1, len(COEFFICIENTS), 3)
        attrs = {"units": units, "long_name": f"{title} {what}".strip()}
        out[prefix + name] = xr.Variable((*dims, *SENSITIVITY_DIMS), data, attrs)
    return out


def sensitivity_coords(materials: Sequence[str]) -> dict[str, xr.Variable]:
    """The coordinates of the derivatives: the material names and :data:`COEFFICIENTS`.

    Parameters
    ----------
    materials : sequence of str
        The model's material names.

    Returns
    -------
    dict of str to xarray.Variable
        ``material`` and ``coefficient``, with long names.

    Examples
    --------
    >>> sensitivity_coords(["paint"])["coefficient"].values[:2].tolist()
    ['reflectivity', 'specular_fraction']
    """
    return {
        "material": xr.Variable(("material",), list(materials), {"long_name": "material of the model"}),
        "coefficient": xr.Variable(
            ("coefficient",), list(COEFFICIENTS), {"long_name": "surface coefficient of the material"}
        ),
    }


def labelled(table: xr.Dataset, materials: Sequence[str]) -> xr.Dataset:
    """``table`` with the coordinates of its derivatives, when it has any.

    Parameters
    ----------
    table : xarray.Dataset
        A sweep table or an orbit's series.
    materials : sequence of str
        The model's material names.

    Returns
    -------
    xarray.Dataset
        ``table`` itself without a ``material`` dimension, else with :func:`sensitivity_coords`.

    Examples
    --------
    >>> table = xr.Dataset({"d": (("material", "coefficient"), np.zeros((1, 7)))})
    >>> labelled(table, ["paint"]).material.values.tolist()
    ['paint']
    """
    if "material" not in table.dims:
        return table
    return table.assign_coords(sensitivity_coords(materials))
