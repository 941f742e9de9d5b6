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
    """A vector as ``[a  b  c]``."""
    return "[" + "  ".join(fmt.format(x) for x in v) + "]"


def about(point_m: np.ndarray, name: str) -> str:
    """The torque reference point and what it is; a default says how to give the centre of mass."""
    point = vector(point_m, "{:+.6f}")
    if name.endswith(" (default)"):
        what = name.removesuffix(" (default)")
        fix = "give the centre of mass with --ref-point or [model] centre_of_mass_m"
        return f"{point}  ({what}, a default: {fix})"
    return f"{point}  ({name})"


def header(craft: Spacecraft) -> dict:
    """What every JSON document says of the model (and, with hinges, their angles [deg] by glob)."""
    out = {"mesh": craft.source, "unit": craft.unit, "triangles": craft.n_facets}
    return out | ({"articulation": craft.articulation} if craft.hinges else {})


def print_articulation(craft: Spacecraft) -> None:
    """The line of the hinges' angles, when the model has hinges."""
    laws = {"fixed": "fixed", "track": "tracking the Sun", "schedule": "scheduled"}
    angles = [
        f"{hinge.pattern} {angle:+.3f} deg ({laws[hinge.law]})"
        for hinge, angle in zip(craft.hinges, craft.pose_deg, strict=True)
    ]
    if angles:
        print(f"  articulation     {'; '.join(angles)}")


def estimated(estimate: ErrorEstimate | None, without: str = "fixed points per side, --samples") -> str:
    """The text of a shadow error estimate: its relative force and torque, or why there is none
    (``without``)."""
    return f"not estimated ({without})" if estimate is None else str(estimate)


def warn_beyond(estimates: Mapping[str, tuple[NDArray, NDArray]], tolerance: float, entries: str) -> None:
    """One ``sunwind: warning:`` line when the shadow pass's estimated error exceeds ``tolerance``:
    ``estimates`` holds per quantity (srp, drag, ...) the relative force and torque estimates of its
    ``entries`` (attitudes, steps), (n,) each, NaN where there is none. With one entry per quantity the
    line gives the estimates; with more, how many entries exceed it and the worst."""
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
    """:func:`warn_beyond` of single results' estimates, by name (None: not estimated)."""
    estimates = {
        name: (np.array([estimate.force]), np.array([estimate.torque]))
        for name, estimate in results.items()
        if estimate is not None
    }
    warn_beyond(estimates, tolerance, "attitudes")


def print_json(craft: Spacecraft, document: dict) -> None:
    """One JSON object: the model, the ``document``, the repair notices."""
    print(json.dumps({**header(craft), **document, "notices": list(craft.notices)}, indent=2))


def print_srp(result: SrpResult) -> None:
    """The human-readable SRP report."""
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
    """The human-readable drag report under ``heading`` (with the hinges' angles when ``hinges``)."""
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
    """The shadow passes' estimated error of the total of SRP, drag (None: none) and the ``extra``
    terms, relative: the absolute errors of the results and ``errors`` (those of the extra terms that
    have one) added."""
    error = summed([light.shadow_error, None if gas is None else gas.shadow_error, *errors])
    if error is None:
        return None
    force, torque = _total(light, gas, extra)
    return ErrorEstimate.of(error, force, torque, light.craft.diagonal_m)


def forces_document(
    light: SrpResult, gas: DragResult | None, extra: Terms = (), errors: Sequence[LoadsError | None] = ()
) -> dict:
    """The JSON document of ``sunwind forces``: both results (``drag`` null without a flow), the
    ``extra`` terms' loads (name, force [N], torque [N m]) and the total of all, with its
    :func:`total_estimate` (``errors``: the extra terms' absolute shadow errors)."""
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
    """The human-readable report of ``sunwind forces`` (the total with drag unless ``gas`` is None, and
    the ``extra`` terms, whose absolute shadow errors are ``errors``)."""
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
