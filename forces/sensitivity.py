"""Sensitivities: the derivative of a result's force and torque with respect to each material's surface
coefficients (METHOD.md "Sensitivities"), one record for SRP, drag and the planet's radiation.

A coefficient is named ``MATERIAL.COEFFICIENT``; material names may hold dots, so the name is split at
its last dot (:func:`split_name`).

>>> split_name("mli.kapton.reflectivity")
('mli.kapton', 'reflectivity')
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from sunwind.forces.vocabulary import COMPONENT, COMPONENT_ATTRS, COMPONENTS
from sunwind.geometry.errors import InputError

#: The coefficients a material has a sensitivity to, in the order of :attr:`Sensitivities.coefficients`:
#: the solar optics ``(rho, beta, sigma)``, the infrared emissivity and the gas law's accommodations.
COEFFICIENTS = (
    "reflectivity",
    "specular_fraction",
    "transmissivity",
    "emissivity",
    "energy_accommodation",
    "normal_accommodation",
    "tangential_accommodation",
)
#: The optics, in the column order of ``Spacecraft.side_optics``.
OPTICS = COEFFICIENTS[:3]
#: The gas law's accommodation coefficients, in the order of :data:`COEFFICIENTS`.
ACCOMMODATIONS = COEFFICIENTS[4:]


def split_name(name: str) -> tuple[str, str]:
    """Split ``MATERIAL.COEFFICIENT`` at its last dot.

    Parameters
    ----------
    name : str
        For example ``"wing.reflectivity"``.

    Returns
    -------
    tuple of str
        The material and the coefficient.

    Raises
    ------
    InputError
        No dot, or a coefficient not in :data:`COEFFICIENTS`.

    Examples
    --------
    >>> split_name("wing.specular_fraction")
    ('wing', 'specular_fraction')
    """
    material, dot, coefficient = name.rpartition(".")
    if not dot or not material:
        raise InputError(
            f"'{name}' is not MATERIAL.COEFFICIENT",
            hint=f"for example wing.reflectivity; coefficients: {', '.join(COEFFICIENTS)}",
        )
    if coefficient not in COEFFICIENTS:
        raise InputError(
            f"'{name}': unknown coefficient '{coefficient}'", hint=f"one of {', '.join(COEFFICIENTS)}"
        )
    return material, coefficient


@dataclass(frozen=True, eq=False)
class Sensitivities:
    """Derivatives of force and torque with respect to every material's coefficients, body frame.

    Attributes
    ----------
    materials : tuple of str
        Material names, the model's order.
    force_N : (n_materials, 7, 3) float64
        d force / d coefficient [N per unit coefficient], coefficients in :data:`COEFFICIENTS` order.
    torque_Nm : (n_materials, 7, 3) float64
        d torque / d coefficient [N m per unit], about ``reference_point_m``.
    reference_point_m : (3,) float64
        The torque reference point [m].

    Examples
    --------
    >>> import numpy as np
    >>> s = Sensitivities(("white",), np.ones((1, 7, 3)), np.zeros((1, 7, 3)), np.zeros(3))
    >>> s.of("white.reflectivity").force_N
    array([1., 1., 1.])
    >>> s.to_dataset()["force_N"].dims
    ('material', 'coefficient', 'component')
    """

    materials: tuple[str, ...]
    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    reference_point_m: NDArray[np.float64]

    @property
    def coefficients(self) -> tuple[str, ...]:
        """The coefficients, :data:`COEFFICIENTS`."""
        return COEFFICIENTS

    @classmethod
    def zeros(cls, materials: Sequence[str], reference_point_m: NDArray[np.float64]) -> Sensitivities:
        """No dependence on any coefficient.

        Parameters
        ----------
        materials : sequence of str
            Material names.
        reference_point_m : (3,) array_like
            The torque reference point [m].

        Returns
        -------
        Sensitivities

        Examples
        --------
        >>> Sensitivities.zeros(["a", "b"], [0, 0, 0]).force_N.shape
        (2, 7, 3)
        """
        shape = (len(materials), len(COEFFICIENTS), 3)
        return cls(tuple(materials), np.zeros(shape), np.zeros(shape), np.asarray(reference_point_m, float))

    def index(self, name: str) -> tuple[int, int]:
        """Material and coefficient indices of ``MATERIAL.COEFFICIENT``.

        Parameters
        ----------
        name : str
            For example ``"wing.reflectivity"``.

        Returns
        -------
        tuple of int

        Raises
        ------
        InputError
            An unknown material or coefficient, naming those there are.

        Examples
        --------
        >>> Sensitivities.zeros(["a", "b"], [0, 0, 0]).index("b.emissivity")
        (1, 3)
        """
        material, coefficient = split_name(name)
        if material not in self.materials:
            raise InputError(
                f"'{name}': the model has no material '{material}'",
                hint=f"materials: {', '.join(self.materials)}",
            )
        return self.materials.index(material), COEFFICIENTS.index(coefficient)

    def of(self, name: str) -> Derivative:
        """The derivative with respect to one coefficient.

        Parameters
        ----------
        name : str
            ``MATERIAL.COEFFICIENT``.

        Returns
        -------
        Derivative

        Examples
        --------
        >>> Sensitivities.zeros(["a"], [0, 0, 0]).of("a.reflectivity").torque_Nm
        array([0., 0., 0.])
        """
        m, k = self.index(name)
        return Derivative(self.force_N[m, k].copy(), self.torque_Nm[m, k].copy())

    def __add__(self, other: Sensitivities) -> Sensitivities:
        if other.materials != self.materials:
            raise ValueError("sensitivities of different material sets")
        return Sensitivities(
            self.materials,
            self.force_N + other.force_N,
            self.torque_Nm + other.torque_Nm,
            self.reference_point_m,
        )

    def scaled(self, factor: float) -> Sensitivities:
        """These derivatives times ``factor`` (a flux or solar fraction scaling the result).

        Parameters
        ----------
        factor : float

        Returns
        -------
        Sensitivities

        Examples
        --------
        >>> ones = np.ones((1, 7, 3))
        >>> Sensitivities(("a",), ones, ones, np.zeros(3)).scaled(0.5).force_N[0, 0]
        array([0.5, 0.5, 0.5])
        """
        return Sensitivities(
            self.materials, self.force_N * factor, self.torque_Nm * factor, self.reference_point_m
        )

    def to_json(self) -> dict:
        """``{material: {coefficient: {"force_N": [..], "torque_Nm": [..]}}}``.

        Returns
        -------
        dict

        Examples
        --------
        >>> Sensitivities.zeros(["a"], [0, 0, 0]).to_json()["a"]["reflectivity"]
        {'force_N': [0.0, 0.0, 0.0], 'torque_Nm': [0.0, 0.0, 0.0]}
        """
        return {
            material: {
                coefficient: {
                    "force_N": self.force_N[m, k].tolist(),
                    "torque_Nm": self.torque_Nm[m, k].tolist(),
                }
                for k, coefficient in enumerate(COEFFICIENTS)
            }
            for m, material in enumerate(self.materials)
        }

    def to_dataset(self) -> xr.Dataset:
        """The derivatives on ``(material, coefficient, component)``, with units and long names.

        Returns
        -------
        xarray.Dataset

        Examples
        --------
        >>> ds = Sensitivities.zeros(["a"], [0, 0, 0]).to_dataset()
        >>> ds["torque_Nm"].attrs["units"], ds.coefficient.values[:2].tolist()
        ('N m', ['reflectivity', 'specular_fraction'])
        """
        dims = ("material", "coefficient", COMPONENT)
        variables = {
            "force_N": (
                dims,
                self.force_N,
                {"units": "N", "long_name": "d force / d coefficient, body frame"},
            ),
            "torque_Nm": (
                dims,
                self.torque_Nm,
                {
                    "units": "N m",
                    "long_name": "d torque about the reference point / d coefficient, body frame",
                },
            ),
        }
        coords = {
            "material": ("material", list(self.materials)),
            "coefficient": ("coefficient", list(COEFFICIENTS)),
            COMPONENT: (COMPONENT, list(COMPONENTS), COMPONENT_ATTRS),
        }
        attrs = {
            "reference_point_m": list(map(float, self.reference_point_m)),
            "frame": "body frame of the mesh",
        }
        return xr.Dataset(variables, coords=coords, attrs=attrs)


@dataclass(frozen=True)
class Derivative:
    """Derivative of force [N] and torque [N m] with respect to one coefficient, body frame.

    Attributes
    ----------
    force_N, torque_Nm : (3,) float64

    Examples
    --------
    >>> Derivative(np.zeros(3), np.ones(3)).torque_Nm
    array([1., 1., 1.])
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]


def optics_partials(rho: NDArray[np.float64], beta: NDArray[np.float64]) -> NDArray[np.float64]:
    """Partials of the shares ``(absorbed, specular, diffuse, transmitted)`` with respect to the optics
    ``(rho, beta, sigma)``: ``alpha = 1 - rho - sigma``, ``rho_s = rho beta``, ``rho_d = rho (1 - beta)``.

    Parameters
    ----------
    rho, beta : (n,) float64
        Reflectivity and specular fraction.

    Returns
    -------
    (n, 3, 4) float64
        ``[i, coefficient, share]``.

    Examples
    --------
    >>> optics_partials(np.array([0.5]), np.array([0.2]))[0]
    array([[-1. ,  0.2,  0.8,  0. ],
           [ 0. ,  0.5, -0.5,  0. ],
           [-1. ,  0. ,  0. ,  1. ]])
    """
    out = np.zeros((len(rho), 3, 4))
    out[:, 0] = np.stack([-np.ones_like(rho), beta, 1.0 - beta, np.zeros_like(rho)], 1)
    out[:, 1, 1], out[:, 1, 2] = rho, -rho
    out[:, 2, 0], out[:, 2, 3] = -1.0, 1.0
    return out
