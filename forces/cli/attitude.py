"""``sunwind srp``, ``sunwind drag`` and ``sunwind forces``: one attitude, printed as text or JSON."""

from __future__ import annotations

import sys

import click

from sunwind.forces.cli.earth import (
    EarthRequest,
    earth_below,
    earth_document,
    earth_request,
    earth_term_options,
    print_earth,
    radiation,
)
from sunwind.forces.cli.free_stream import FreeStream, flow_options, refuse_without_flow
from sunwind.forces.cli.options import (
    Sun,
    drag_only,
    group,
    json_option,
    loaded,
    model_options,
    posed,
    reference_options,
    reflection_options,
    sampling_options,
    sun_options,
)
from sunwind.forces.cli.report import (
    forces_document,
    print_drag,
    print_forces,
    print_json,
    print_srp,
    warn_results,
)
from sunwind.forces.cli.sensitivities import print_sensitivities, sensitivities_option
from sunwind.forces.drag import drag as drag_of
from sunwind.forces.model import Model, ModelSource
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.results import DragResult
from sunwind.forces.srp import srp as srp_of
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import infrared_optics


@click.command()
@model_options()
@sun_options()
@reference_options()
@sampling_options
@reflection_options("light")
@sensitivities_option
@json_option
def srp(
    source: ModelSource,
    sun: Sun,
    references: dict,
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    sensitivities: bool,
    as_json: bool,
) -> None:
    """Solar-radiation force and torque for one Sun direction, with self-shadowing and inter-reflection."""
    model = posed(loaded(source, **references), sun.vector, "srp")
    result = srp_of(
        model,
        sun.vector,
        flux_W_m2=sun.flux_W_m2,
        reflections=reflections,
        sampling=sampling,
        sensitivities=sensitivities,
    )
    if as_json:
        print_json(model.craft, result.to_json())
    else:
        print_srp(result)
        if result.sensitivities is not None:
            print_sensitivities(result.sensitivities)
    warn_results({"srp": result.error_estimate}, sampling.tolerance)


@click.command()
@model_options(gas=True)
@flow_options(directed=True)
@reference_options(sizes=True)
@sampling_options
@reflection_options("gas")
@sensitivities_option
@json_option
def drag(
    source: ModelSource,
    flow: FreeStream,
    references: dict,
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    sensitivities: bool,
    as_json: bool,
) -> None:
    """Free-molecular force and torque for one flow direction: gas-surface law, shadowing, re-emission."""
    model = posed(loaded(drag_only(source), **references), None, "drag")
    result = _drag(model, flow, reflections, sampling, sensitivities)
    craft = model.craft
    if as_json:
        print_json(craft, result.to_json())
    else:
        print_drag(result, f"sunwind drag: {craft.source} ({craft.n_facets} triangles, unit {craft.unit})")
        if result.sensitivities is not None:
            print_sensitivities(result.sensitivities)
    warn_results({"drag": result.error_estimate}, sampling.tolerance)


@click.command()
@model_options(gas=True)
@sun_options()
@flow_options(directed=True, optional=True)
@reference_options(sizes=True)
@sampling_options
@reflection_options("both")
@group("earth", earth_term_options(place=True), earth_request)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object: srp, drag, total.")
def forces(
    source: ModelSource,
    sun: Sun,
    flow: FreeStream,
    references: dict,
    sampling: ShadowSampling,
    reflections: ReflectionSettings,
    earth: EarthRequest | None,
    as_json: bool,
) -> None:
    """Solar-radiation pressure and free-molecular drag together for one attitude, and their total
    (with --earth-radiation, the Earth's albedo and infrared too, and --thermal the thermal recoil;
    without a flow direction, no drag: SRP and the Earth's terms, as in GEO)."""
    model = posed(loaded(source, **references), sun.vector, "forces")
    below = None
    if earth is not None:  # the place, the cell step and a missing emissivity refused before any work
        below = earth_below(earth, flow)
        infrared_optics(model.craft)
    if flow.velocity_m_s is None:
        refuse_without_flow([key for key, _ in source.gas])
        print(
            "sunwind: notice: no flow direction (--velocity or --flow-azel): no drag; the total is SRP"
            " (and the Earth's terms with --earth-radiation)",
            file=sys.stderr,
        )
    light = srp_of(model, sun.vector, flux_W_m2=sun.flux_W_m2, reflections=reflections, sampling=sampling)
    gas = None if flow.velocity_m_s is None else _drag(model, flow, reflections, sampling)
    estimates = {"srp": light.error_estimate} | ({} if gas is None else {"drag": gas.error_estimate})
    if earth is None:
        if as_json:
            print_json(model.craft, forces_document(light, gas))
        else:
            print_forces(light, gas)
        warn_results(estimates, sampling.tolerance)
        return
    result, state = radiation(model, below, sun, reflections, sampling, thermal=earth.thermal)
    terms = [(band.name, band.force_N, band.torque_Nm) for band in (result.albedo, result.infrared)]
    if state is not None:
        terms.append(("thermal", state.force_N, state.torque_Nm))
    errors = [result.shadow_error]  # the albedo's and the infrared's; the thermal recoil casts no ray
    if as_json:
        document = forces_document(light, gas, terms, errors)
        planet = earth_document(result, state)
        for key in ("albedo", "infrared", "thermal", "parts"):
            if key in planet:
                document[key] = planet.pop(key)
        document["planet"] = planet
        print_json(model.craft, document)
    else:
        print_forces(light, gas, terms, errors)
        print_earth(result, state, title="  planet:")
    warn_results(estimates | {"planet": result.error_estimate}, sampling.tolerance)


def _drag(
    model: Model,
    flow: FreeStream,
    reflections: ReflectionSettings,
    sampling: ShadowSampling,
    sensitivities: bool = False,
) -> DragResult:
    """Drag of ``model`` in the command's ``flow``, with its reflection and shadow sampling settings."""
    return drag_of(
        model,
        flow.velocity_m_s,
        flow.atmosphere,
        reflections=reflections,
        gas_sampling=flow.sampling,
        sampling=sampling,
        sensitivities=sensitivities,
    )
