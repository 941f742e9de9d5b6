"""Calibrating the model from flight data: the surface coefficients that make SRP match measured
torque, momentum or acceleration (``sunwind fit``; the guide "Calibrating the model from flight data").

:func:`fit` reads the telemetry (:mod:`.telemetry`), evaluates the model once per distinct geometry
with its sensitivities (:mod:`.forward`), solves the bounded weighted least-squares problem
(:mod:`.solve`) and reports estimates, uncertainties and what the data cannot separate (:mod:`.report`).

>>> from sunwind.forces.fit import FitOptions
>>> FitOptions().reflections
'auto'
"""

from sunwind.forces.fit.report import FitResult, write_materials
from sunwind.forces.fit.solve import FitOptions, fit
from sunwind.forces.fit.telemetry import Telemetry, read_telemetry

__all__ = ["FitOptions", "FitResult", "Telemetry", "fit", "read_telemetry", "write_materials"]
