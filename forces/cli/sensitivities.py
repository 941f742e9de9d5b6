"""``--sensitivities``: the option and the printed table of d force and d torque per material coefficient
(METHOD.md "Sensitivities")."""

from __future__ import annotations

import click
import numpy as np

from sunwind.forces.cli.report import vector
from sunwind.forces.sensitivity import COEFFICIENTS, Sensitivities

sensitivities_option = click.option(
    "--sensitivities",
    is_flag=True,
    help="Also give d force / d coefficient and d torque / d coefficient for every material's coefficients "
    "(reflectivity, specular_fraction, transmissivity, emissivity, accommodations).",
)


def print_sensitivities(sensitivities: Sensitivities) -> None:
    """Print every nonzero derivative, one line per ``MATERIAL.COEFFICIENT``.

    Parameters
    ----------
    sensitivities : Sensitivities
        The result's derivatives.

    Examples
    --------
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.25)
    >>> cube = sw.load(sw.meshes.box(), uniform=grey, threads=1)
    >>> result = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none", sensitivities=True)
    >>> print_sensitivities(result.sensitivities)
      sensitivities    d/d coefficient, body frame, torque about the reference point
        grey.reflectivity            d force  [N]    [-3.404856e-06  +0.000000e+00  +0.000000e+00]
                                     d torque [N m]  [+0.000000e+00  +0.000000e+00  +0.000000e+00]
        grey.specular_fraction       d force  [N]    [-4.539807e-07  +0.000000e+00  +0.000000e+00]
                                     d torque [N m]  [+0.000000e+00  +0.000000e+00  +0.000000e+00]
        grey.transmissivity          d force  [N]    [+4.539807e-06  +0.000000e+00  +0.000000e+00]
                                     d torque [N m]  [+0.000000e+00  +0.000000e+00  +0.000000e+00]
    """
    print("  sensitivities    d/d coefficient, body frame, torque about the reference point")
    for m, material in enumerate(sensitivities.materials):
        for k, coefficient in enumerate(COEFFICIENTS):
            force, torque = sensitivities.force_N[m, k], sensitivities.torque_Nm[m, k]
            if not (np.any(force) or np.any(torque)):
                continue
            name = f"{material}.{coefficient}"
            print(f"    {name:<28} d force  [N]    {vector(force)}")
            print(f"    {'':<28} d torque [N m]  {vector(torque)}")
