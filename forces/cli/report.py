"""What the single-attitude commands print: a text report, or one JSON document with the same facts."""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.error_estimate import ADVICE, ErrorEstimate, ShadowErrorWarning, summed
from sunwind.forces.results import FRAME, VALIDITY, DragResult, SrpResult
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.spacecraft import Spacecraft

#: Loads added to a total: (name, force [N] (3,), torque [N m] (3,)) each.
Terms = Sequence[tuple[str, np.ndarray, np.ndarray]]


def vector(v: np.ndarray, fmt: str = "{:+.6e}") -> str:
    """Write a vector as ``[a  b  c]``.

    Parameters
    ----------
    v : (3,) float ndarray
        The vector (any length is written).
    fmt : str, optional
        Format of each component; signed scientific notation by default.

    Returns
    -------
    str
        The components in brackets, two spaces apart.

    Examples
    --------
    >>> import numpy as np
    >>> vector(np.array([1.0, -2.0, 0.5]))
    '[+1.000000e+00  -2.000000e+00  +5.000000e-01]'
    >>> vector(np.array([1.0, -2.0, 0.5]), "{:+.2f}")
    '[+1.00  -2.00  +0.50]'
    """
    return "[" + "  ".join(fmt.format(x) for x in v) + "]"


def about(point_m: np.ndarray, name: str) -> str:
    """Write the torque reference point and what it is.

    Parameters
    ----------
    point_m : (3,) float ndarray
        The reference point [m], body frame.
    name : str
        What the point is (a result's ``reference_point``); one ending in ``" (default)"`` is a
        default, and the text then says how to give the centre of mass.

    Returns
    -------
    str
        The point to the micrometre and its description in parentheses.

    Examples
    --------
    >>> import numpy as np
    >>> about(np.array([0.0, 0.0, 0.1]), "given")
    '[+0.000000  +0.000000  +0.100000]  (given)'
    >>> about(np.zeros(3), "volume centroid (default)")
    '[+0.000000  +0.000000  +0.000000]  (volume centroid, a default: give the centre of mass with ...)'
    """
    point = vector(point_m, "{:+.6f}")
    if name.endswith(" (default)"):
        what = name.removesuffix(" (default)")
        fix = "give the centre of mass with --ref-point or [model] centre_of_mass_m"
        return f"{point}  ({what}, a default: {fix})"
    return f"{point}  ({name})"


def header(craft: Spacecraft) -> dict:
    """Describe the model for the head of a JSON document.

    Parameters
    ----------
    craft : Spacecraft
        The loaded spacecraft.

    Returns
    -------
    dict
        ``mesh`` (the source), ``unit`` and ``triangles``; with hinges also ``articulation``, their
        angles [deg] by glob.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> header(cube.craft)
    {'mesh': '<box>', 'unit': 'm', 'triangles': 12}
    """
    out = {"mesh": craft.source, "unit": craft.unit, "triangles": craft.n_facets}
    return out | ({"articulation": craft.articulation} if craft.hinges else {})


def print_articulation(craft: Spacecraft) -> None:
    """Print the line of the hinges' angles and laws, when the model has hinges.

    Parameters
    ----------
    craft : Spacecraft
        The posed spacecraft; without hinges nothing is printed.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> print_articulation(cube.craft)  # a box has no hinges: no line
    """
    laws = {"fixed": "fixed", "track": "tracking the Sun", "schedule": "scheduled"}
    angles = [
        f"{hinge.pattern} {angle:+.3f} deg ({laws[hinge.law]})"
        for hinge, angle in zip(craft.hinges, craft.pose_deg, strict=True)
    ]
    if angles:
        print(f"  articulation     {'; '.join(angles)}")


def estimated(estimate: ErrorEstimate | None, without: str = "fixed points per side, --samples") -> str:
    """Write a shadow error estimate, or why there is none.

    Parameters
    ----------
    estimate : ErrorEstimate or None
        The relative force and torque error estimates; None when not estimated.
    without : str, optional
        Why there is no estimate, shown in parentheses (by default: fixed points per side).

    Returns
    -------
    str
        The estimate's text, or ``"not estimated (WITHOUT)"``.

    Examples
    --------
    >>> estimated(ErrorEstimate(2e-4, 5e-4))
    'force 2.0e-04, torque 5.0e-04 (relative, estimated)'
    >>> estimated(None)
    'not estimated (fixed points per side, --samples)'
    """
    return f"not estimated ({without})" if estimate is None else str(estimate)


def warn_beyond(estimates: Mapping[str, tuple[NDArray, NDArray]], tolerance: float, entries: str) -> None:
    """Warn once when the shadow pass's estimated error exceeds the tolerance.

    One :class:`~sunwind.forces.error_estimate.ShadowErrorWarning` covers every quantity beyond it: with
    one entry per quantity it gives the estimates; with more, how many entries exceed the tolerance
    and the worst. Nothing is said when none does.

    Parameters
    ----------
    estimates : mapping of str to (ndarray, ndarray)
        Per quantity (``"srp"``, ``"drag"``, ...), the relative force and torque error estimates of
        its entries, (n,) each, NaN where there is none.
    tolerance : float
        The relative error allowed (``--tolerance``).
    entries : str
        What the entries are, plural, for the message (``"attitudes"``, ``"steps"``).

    Warns
    -----
    ShadowErrorWarning
        An estimate exceeds ``tolerance``.

    Examples
    --------
    >>> import warnings
    >>> import numpy as np
    >>> estimates = {"srp": (np.array([0.02, np.nan]), np.array([0.001, 0.004]))}
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_beyond(estimates, 0.01, "attitudes")
    >>> print(caught[0].message)
    the shadow pass's estimated error exceeds the tolerance 0.01: srp at 1 of 2 attitudes (worst force ...
    """
    beyond = []
    for name, (force, torque) in estimates.items():
        worst = np.fmax(force, torque)
        over = worst > tolerance
        if not over.any():
            continue
        largest = f"force {np.nanmax(force):.1e}, torque {np.nanmax(torque):.1e}, relative"
        if len(worst) == 1:
            beyond.append(f"{name} {largest}")
        else:
            beyond.append(f"{name} at {int(over.sum())} of {len(worst)} {entries} (worst {largest})")
    if beyond:
        warnings.warn(
            f"the shadow pass's estimated error exceeds the tolerance {tolerance:g}: "
            f"{'; '.join(beyond)}; {ADVICE}",
            ShadowErrorWarning,
            stacklevel=2,
        )


def warn_results(results: Mapping[str, ErrorEstimate | None], tolerance: float) -> None:
    """Warn when the estimated errors of single results exceed the tolerance (:func:`warn_beyond`).

    Parameters
    ----------
    results : mapping of str to ErrorEstimate or None
        Each result's relative error estimate by name (None: not estimated, skipped).
    tolerance : float
        The relative error allowed (``--tolerance``).

    Warns
    -----
    ShadowErrorWarning
        An estimate exceeds ``tolerance``.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_results({"srp": ErrorEstimate(0.05, 0.002), "drag": None}, 0.01)
    >>> print(caught[0].message)
    the shadow pass's estimated error exceeds the tolerance 0.01: srp force 5.0e-02, torque 2.0e-03, ...
    """
    estimates = {
        name: (np.array([estimate.force]), np.array([estimate.torque]))
        for name, estimate in results.items()
        if estimate is not None
    }
    warn_beyond(estimates, tolerance, "attitudes")


def print_json(craft: Spacecraft, document: dict) -> None:
    """Print one JSON object: the model's :func:`header`, the ``document`` and the repair notices.

    Parameters
    ----------
    craft : Spacecraft
        The loaded spacecraft.
    document : dict
        The command's facts, JSON-serialisable; its keys follow the header's.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> print_json(cube.craft, {"k_is": 0.0})
    {
      "mesh": "<box>",
      "unit": "m",
      "triangles": 12,
      "k_is": 0.0,
      "notices": []
    }
    """
    print(json.dumps({**header(craft), **document, "notices": list(craft.notices)}, indent=2))


def print_srp(result: SrpResult) -> None:
    """Print the human-readable report of ``sunwind srp``.

    Parameters
    ----------
    result : SrpResult
        The SRP at one attitude.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> light = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> print_srp(light)  # doctest: +ELLIPSIS
    sunwind srp: <box> (12 triangles, 1 parts, unit m)
      frame            body frame of the mesh; SI units
      sun vector       [+1.000000  +0.000000  +0.000000]  az 0.000 deg  el 0.000 deg
      flux             1361 W/m^2   pressure P = 4.539807e-06 Pa
      force   [N]      [-4.539807e-06  +0.000000e+00  +0.000000e+00]  |F| = 4.539807e-06
    ...
      lit area         1.000000 m^2
      projected area   1.000000 m^2
    ...
    """
    craft = result.craft
    az, el = result.azel_deg
    parts = f"{craft.n_facets} triangles, {len(craft.part_names)} parts, unit {craft.unit}"
    print(f"sunwind srp: {craft.source} ({parts})")
    print("  frame            body frame of the mesh; SI units")
    print_articulation(craft)
    print(f"  sun vector       {vector(result.sun_vector, '{:+.6f}')}  az {az:.3f} deg  el {el:.3f} deg")
    print(f"  flux             {result.flux_W_m2:.6g} W/m^2   pressure P = {result.pressure_Pa:.6e} Pa")
    print(f"  force   [N]      {vector(result.force_N)}  |F| = {np.linalg.norm(result.force_N):.6e}")
    print(f"    direct         {vector(result.direct_force_N)}")
    print(f"    reflected      {vector(result.reflected_force_N)}")
    print(f"  torque  [N m]    {vector(result.torque_Nm)}  |M| = {np.linalg.norm(result.torque_Nm):.6e}")
    print(f"    direct         {vector(result.direct_torque_Nm)}")
    print(f"    reflected      {vector(result.reflected_torque_Nm)}")
    print(f"  about   [m]      {about(result.reference_point_m, result.reference_point)}")
    print(f"  lit area         {result.lit_area_m2:.6f} m^2")
    print(f"  projected area   {result.projected_area_m2:.6f} m^2")
    print(f"  shadow rays      {result.rays} ({result.sampling})")
    print(f"  shadow error     {estimated(result.error_estimate)}")
    print(
        f"  reflections      {result.reflections} (asked: {result.settings.mode}); "
        f"K_IS = {_k_is(result.k_is)} (eq. 7; inter-reflection matters from 0.1)"
    )
    power = result.power
    print(
        f"  power   [W]      incident {power.incident_W:.6g}, absorbed {power.absorbed_W:.6g}, "
        f"escaped {power.escaped_W:.6g}, cut off {power.truncated_W:.3g} (imbalance {power.imbalance:.1e})"
    )
    chains, view = result.reflected.chains, result.reflected.view
    if chains is not None:
        print(f"  beam rays        {chains.rays}, chains up to {chains.depth} surfaces")
    if view is not None and result.reflections == "full":
        print(f"  view factors     {view.rays_per_side} rays per side, {view.origin}")


def print_drag(result: DragResult, heading: str, hinges: bool = True) -> None:
    """Print the human-readable drag report under a heading.

    Parameters
    ----------
    result : DragResult
        The drag for one flow.
    heading : str
        The report's first line (``sunwind drag: MESH (...)``, or ``drag:`` within ``forces``).
    hinges : bool, optional
        Print the hinges' angles (off where a report above has them).

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> light = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> fast = sw.GasSampling(sky_rays=16, core_rays=1024)
    >>> gas = sw.drag(cube, [7600.0, 0.0, 0.0], air, reflections="none", gas_sampling=fast)
    >>> print_drag(gas, "drag of a cube:")  # doctest: +ELLIPSIS
    drag of a cube:
      frame            body frame of the mesh; SI units
      v_rel   [m/s]    [+7600.000  +0.000  +0.000]  az 0.000 deg  el 0.000 deg
    ...
      force   [N]      [-7.078358e-05  +0.000000e+00  +0.000000e+00]  |F| = 7.078358e-05
    ...
      coefficients     CD 1.633970  CL +0.000000  CS +0.000000  CM ...
    ...
    """
    air = result.atmosphere
    cd, cs, cl = result.force_coefficients
    az, el = result.azel_deg
    print(heading)
    print("  frame            body frame of the mesh; SI units")
    if hinges:
        print_articulation(result.craft)
    print(f"  v_rel   [m/s]    {vector(result.velocity_m_s, '{:+.3f}')}  az {az:.3f} deg  el {el:.3f} deg")
    print(f"  atmosphere       {air.source}")
    print(
        f"                   rho {air.density_kg_m3:.6e} kg/m^3, T {air.temperature_K:.1f} K, "
        f"q = {result.dynamic_pressure_Pa:.6e} Pa, speed ratio {result.speed_ratio:.3f}"
    )
    print(f"  force   [N]      {vector(result.force_N)}  |F| = {np.linalg.norm(result.force_N):.6e}")
    print(f"    panel law      {vector(result.direct_force_N)}")
    print(f"    re-emission    {vector(result.reflected_force_N)}")
    print(f"  torque  [N m]    {vector(result.torque_Nm)}  |M| = {np.linalg.norm(result.torque_Nm):.6e}")
    print(f"  about   [m]      {about(result.reference_point_m, result.reference_point)}")
    print(f"  coefficients     CD {cd:.6f}  CL {cl:+.6f}  CS {cs:+.6f}  CM {vector(result.CM)}")
    print(
        f"{'':19}A_ref {result.reference_area_m2:.6g} m^2, L_ref {result.reference_length_m:.6g} m; "
        "C = F/(q A_ref), C_M = M/(q A_ref L_ref)"
    )
    print(f"  lit area         {result.lit_area_m2:.6f} m^2 (facing the flow, not shadowed)")
    print(f"  projected area   {result.projected_area_m2:.6f} m^2 (normal to the flow)")
    print(
        f"  re-emission      {result.reflections} (asked: {result.settings.mode}); "
        f"molecular K_IS = {_k_is(result.k_is)}"
    )
    chains = result.reflected.chains
    if chains is not None and chains.packets:
        print(
            f"  chains           {chains.packets} molecules sent on unaccommodated, {chains.rays} rays, "
            f"{chains.truncated:.1e} of their weight cut off"
        )
    sky = result.open_sky
    print(
        f"  rays             {result.rays} (shadow along the flow: {result.sampling}; core cone "
        f"{math.degrees(result.core_half_angle_rad):.1f} deg)"
    )
    print(f"  shadow error     {estimated(result.error_estimate)}")
    print(f"  open sky         {sky.rays_per_side} rays per side, {sky.origin}")
    print(f"  validity         {VALIDITY}")


def _total(light: SrpResult, gas: DragResult | None, extra: Terms) -> tuple[np.ndarray, np.ndarray]:
    """Force [N] and torque [N m] of SRP, drag (None: none) and the ``extra`` terms together."""
    results = [light] if gas is None else [light, gas]
    force = sum((r.force_N for r in results), np.zeros(3)) + sum((f for _, f, _ in extra), np.zeros(3))
    torque = sum((r.torque_Nm for r in results), np.zeros(3)) + sum((t for _, _, t in extra), np.zeros(3))
    return force, torque


def total_estimate(
    light: SrpResult, gas: DragResult | None, extra: Terms = (), errors: Sequence[LoadsError | None] = ()
) -> ErrorEstimate | None:
    """Estimate the shadow passes' relative error of a total of loads.

    The absolute errors of SRP, drag and the extra terms are added (a bound: they may partly cancel)
    and made relative to the total force and torque.

    Parameters
    ----------
    light : SrpResult
        The SRP.
    gas : DragResult or None
        The drag; None when there is none.
    extra : sequence of (str, ndarray, ndarray), optional
        Further loads in the total: name, force [N] (3,) and torque [N m] (3,) each.
    errors : sequence of LoadsError or None, optional
        The absolute shadow errors of the extra terms that have one.

    Returns
    -------
    ErrorEstimate or None
        The relative force and torque errors of the total; None when a term has no estimate.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> light = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> fast = sw.GasSampling(sky_rays=16, core_rays=1024)
    >>> gas = sw.drag(cube, [7600.0, 0.0, 0.0], air, reflections="none", gas_sampling=fast)
    >>> total_estimate(light, gas)
    ErrorEstimate(force=0.0, torque=0.0)
    >>> total_estimate(light, None) is not None  # SRP alone (no flow): its own estimate
    True
    """
    drag_error = [] if gas is None else [gas.shadow_error]  # no flow: no drag, and nothing to add
    error = summed([light.shadow_error, *drag_error, *errors])
    if error is None:
        return None
    force, torque = _total(light, gas, extra)
    return ErrorEstimate.of(error, force, torque, light.craft.diagonal_m)


def forces_document(
    light: SrpResult, gas: DragResult | None, extra: Terms = (), errors: Sequence[LoadsError | None] = ()
) -> dict:
    """Make the JSON document of ``sunwind forces``.

    Parameters
    ----------
    light : SrpResult
        The SRP.
    gas : DragResult or None
        The drag; None without a flow (``drag`` is then null).
    extra : sequence of (str, ndarray, ndarray), optional
        Further loads in the total: name, force [N] (3,) and torque [N m] (3,) each.
    errors : sequence of LoadsError or None, optional
        The absolute shadow errors of the extra terms that have one, for :func:`total_estimate`.

    Returns
    -------
    dict
        ``srp`` and ``drag`` (each result's JSON) and ``total``: force [N], torque [N m], the
        reference point, the frame and the total's error estimate.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> light = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> fast = sw.GasSampling(sky_rays=16, core_rays=1024)
    >>> gas = sw.drag(cube, [7600.0, 0.0, 0.0], air, reflections="none", gas_sampling=fast)
    >>> document = forces_document(light, gas)
    >>> sorted(document["total"])
    ['error_estimate', 'force_N', 'frame', 'reference_point', 'reference_point_m', 'torque_Nm']
    >>> print(f"{document['total']['force_N'][0]:.4e}")
    -7.5323e-05
    """
    force, torque = _total(light, gas, extra)
    estimate = total_estimate(light, gas, extra, errors)
    total = {
        "force_N": force.tolist(),
        "torque_Nm": torque.tolist(),
        "reference_point_m": light.reference_point_m.tolist(),
        "reference_point": light.reference_point,
        "frame": FRAME,
        "error_estimate": None if estimate is None else estimate.to_json(),
    }
    return {"srp": light.to_json(), "drag": None if gas is None else gas.to_json(), "total": total}


def print_forces(
    light: SrpResult, gas: DragResult | None, extra: Terms = (), errors: Sequence[LoadsError | None] = ()
) -> None:
    """Print the human-readable report of ``sunwind forces``: the total, then SRP and drag.

    Parameters
    ----------
    light : SrpResult
        The SRP.
    gas : DragResult or None
        The drag, in the total and reported below it; None without a flow.
    extra : sequence of (str, ndarray, ndarray), optional
        Further loads in the total: name, force [N] (3,) and torque [N m] (3,) each.
    errors : sequence of LoadsError or None, optional
        The absolute shadow errors of the extra terms that have one.

    Examples
    --------
    >>> import sunwind as sw
    >>> black = sw.Material("black", reflectivity=0.0, specular_fraction=0.0)
    >>> cube = sw.load(sw.meshes.box(), uniform=black, threads=1)
    >>> light = sw.srp(cube, [1.0, 0.0, 0.0], reflections="none")
    >>> air = sw.explicit_atmosphere(1e-12, 1000.0, "O:1")
    >>> fast = sw.GasSampling(sky_rays=16, core_rays=1024)
    >>> gas = sw.drag(cube, [7600.0, 0.0, 0.0], air, reflections="none", gas_sampling=fast)
    >>> print_forces(light, gas)  # doctest: +ELLIPSIS
    sunwind forces: <box> (12 triangles, unit m)
      total force  [N]    [-7.532338e-05  +0.000000e+00  +0.000000e+00]  |F| = 7.532338e-05
      total torque [N m]  [+0.000000e+00  +0.000000e+00  +0.000000e+00]
    ...
      srp force    [N]    [-4.539807e-06  +0.000000e+00  +0.000000e+00]  (sun [+1.0000  +0.0000  +0.0000])
    ...
      drag:
      frame            body frame of the mesh; SI units
    ...
    """
    craft = light.craft
    force, torque = _total(light, gas, extra)
    print(f"sunwind forces: {craft.source} ({craft.n_facets} triangles, unit {craft.unit})")
    print_articulation(craft)
    print(f"  total force  [N]    {vector(force)}  |F| = {np.linalg.norm(force):.6e}")
    print(f"  total torque [N m]  {vector(torque)}")
    print(f"  about        [m]    {about(light.reference_point_m, light.reference_point)}")
    print(f"  shadow error        {estimated(total_estimate(light, gas, extra, errors))}")
    print(f"  srp force    [N]    {vector(light.force_N)}  (sun {vector(light.sun_vector, '{:+.4f}')})")
    print(f"  srp torque   [N m]  {vector(light.torque_Nm)}")
    print(f"  srp shadow error    {estimated(light.error_estimate)}")
    if gas is None:
        print("  drag:            none (no flow direction: --velocity or --flow-azel)")
    else:
        print_drag(gas, "  drag:", hinges=False)


def _k_is(k_is: float | None) -> str:
    """``K_IS`` to 4 decimals, or why it is not known: the reflections asked for needed no view factors
    (``sunwind info`` computes it)."""
    return (
        "not computed (no view factors asked for; sunwind info gives it)" if k_is is None else f"{k_is:.4f}"
    )
