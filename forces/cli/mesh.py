"""``sunwind info`` and ``sunwind mesh``: describe a mesh file, or write a parametric one."""

from __future__ import annotations

import inspect
import json
from pathlib import Path

import click
import numpy as np

from sunwind import meshes
from sunwind.forces.cli.options import json_option, model_options, view_factor_options
from sunwind.forces.cli.report import vector
from sunwind.forces.model import ModelSource
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.reflection.views import view_factor_summary
from sunwind.geometry.errors import InputError, SunwindError
from sunwind.geometry.summary import describe


@click.command()
@model_options()
@view_factor_options
@click.option("--no-k-is", is_flag=True, help="Skip the view factors and K_IS (quick look at a large mesh).")
@json_option
def info(source: ModelSource, reflections: ReflectionSettings, no_k_is: bool, as_json: bool) -> None:
    """Describe a mesh: triangles, parts, materials, area, bounds, closed or not, checks, and K_IS."""
    report = describe(source.mesh, source.materials, source.unit, source.uniform, source.two_sided)
    if not no_k_is:
        try:
            craft = source.spacecraft()
        except SunwindError:
            report["k_is"] = "not available until the checks pass"
        else:
            report.update(view_factor_summary(craft, reflections))
    if as_json:
        print(json.dumps(report, indent=2))
        return
    print(f"sunwind info: {report['mesh']}")
    for key in ("unit", "triangles", "area_m2", "volume_m3", "closed", "reference_point", "k_is"):
        if key in report:
            print(f"  {key:<17}{_shown(report[key])}")
    if "view_factors" in report:
        view = report["view_factors"]
        print(
            f"  {'open sky':<17}{view['open_sky_share']:.4f} of diffusely reflected light escapes "
            f"(area-weighted); view factors: {view['rays_per_side']} rays per side, {view['origin']}"
        )
    low, high = report["bounds_m"]
    low, high = (vector(np.array(corner), "{:+.6g}") for corner in (low, high))
    print(f"  {'bounds_m':<17}min {low}  max {high}")
    print("  checks:")
    for line in report["checks"]:
        print(f"    {line}")
    survey = report["survey"]
    print(
        f"  survey of the mesh as read ({survey['facets']} facets; edges by position, corners within "
        f"{survey['weld_m']:.3g} m one):"
    )
    for name, line in _survey_lines(survey):
        print(f"    {name:<15}{line}")
    print("  parts:")
    for part in report["parts"]:
        print(
            f"    {part['name']:<28} {part['triangles']:>7} tri {part['area_m2']:>10.4f} m^2  "
            f"{part['surface']:<16}  {part['materials']}"
        )
    if report["materials"]:
        print(f"  materials:{'':<18}rho    beta   sigma  alpha")
        for m in report["materials"]:
            print(
                f"    {m['name']:<24}{m['reflectivity']:.3f}  {m['specular_fraction']:.3f}  "
                f"{m['transmissivity']:.3f}  {m['absorptivity']:.3f}"
            )


def _survey_lines(survey: dict) -> list[tuple[str, str]]:
    """The survey of ``sunwind info`` (:meth:`sunwind.geometry.survey.Survey.to_json`) as one line per
    finding: what was found, then what loading and the methods do about it."""
    gap, offset = survey["gap_m"], survey["offset_m"]
    crossing = ", ".join(
        f"{' x '.join(c['parts']) if c['parts'][0] != c['parts'][1] else c['parts'][0] + ' with itself'} "
        f"{c['length_m']:.4g} m ({c['facet_pairs']} facet pairs)"
        for c in survey["crossings"][:3]
    ) + (f", {len(survey['crossings']) - 3} more pairs" if len(survey["crossings"]) > 3 else "")
    coincident, layered, slivers = survey["coincident"], survey["layered"], survey["slivers"]
    shells = {part: n for part, n in survey["shells"].items() if n > 1}
    return [
        (
            "open edges",
            f"{_edges(survey['open_edges'])}: one facet each (a sheet's border, an open seam); outlines "
            "cast from them as silhouette edges; refused on closed bodies (checks)",
        ),
        (
            "non-manifold",
            f"{_edges(survey['nonmanifold_edges'])}: three or more facets each; silhouette edges found by "
            "position and fold, not winding",
        ),
        (
            "mixed winding",
            f"{_edges(survey['mixed_winding'])}, {survey['mixed_on_sheets']} on sheets: two facets run "
            "each the same way; closed bodies made consistent on loading; silhouette edges found by "
            "position and fold, not winding; a sheet's front (its material) follows each facet's winding",
        ),
        (
            "seams",
            f"{_edges(survey['seams'])}: coinciding corners that are separate vertices; merged on loading "
            f"within {survey['merge_m']:.3g} m ({survey['seams_unmerged']} edges stay apart: no near-field "
            "view factors across them); the shadow pass joins edges by position",
        ),
        (
            "gaps",
            f"{_edges(survey['gaps'])}: open edges within {gap:.3g} m of another across empty space; light "
            f"passes, their edges cast outlines (closed bodies' cracks under {survey['crack_m']:.3g} m "
            "closed on loading)",
        ),
        (
            "crossings",
            f"{crossing or 'none'}: the lines where parts cross are outline segments of the shadow pass",
        ),
        (
            "duplicates",
            f"{coincident['facets']} facets coincident{_parts(coincident['parts'])}, {layered['facets']} "
            f"layered within {gap:.3g} m{_parts(layered['parts'])}, sharing "
            f"{coincident['area_m2'] + layered['area_m2']:.4g} m^2, of which "
            f"{coincident['coplanar_area_m2'] + layered['coplanar_area_m2']:.4g} m^2 closer than the shadow "
            f"rays' offset ({offset:.3g} m): there the later layer in the file covers the earlier, lit "
            "once, but drag's open-sky integral counts both; farther apart, the upper layer shades the lower",
        ),
        (
            "slivers",
            f"{slivers['count']} facets over 1000 times longer than wide{_parts(slivers['parts'])}, "
            f"{slivers['degenerate']} degenerate (dropped on loading); facet areas "
            f"{slivers['area_min_m2']:.3g} to {slivers['area_max_m2']:.3g} m^2; probe spacing "
            f"{slivers['probe_spacing_m']:.3g} m from the 10th percentile of facet widths "
            f"({slivers['width_p10_m']:.3g} m)",
        ),
        (
            "shells",
            (f"{len(shells)} parts in several pieces{_parts(shells)}" if shells else "every part one piece")
            + ": pieces of a part sharing no corner; each closed piece turned outward on its own on "
            "loading, no connection needed by the shadow pass",
        ),
    ]


def _parts(parts: dict[str, int], most: int = 3) -> str:
    """``" (a 3, b 2, 4 more parts)"``: the parts with the most, or nothing when there are none."""
    ranked = sorted(parts.items(), key=lambda item: -item[1])
    words = [f"{name} {n}" for name, n in ranked[:most]]
    if len(ranked) > most:
        words.append(f"{len(ranked) - most} more parts")
    return f" ({', '.join(words)})" if words else ""


def _edges(tally: dict) -> str:
    """``"12 edges, 3.4 m (a 8, b 4)"``."""
    return f"{tally['count']} edges, {tally['length_m']:.4g} m{_parts(tally['parts'])}"


def builder_params(kind: str, builder, words: list[str]) -> dict:
    """Read the ``--name value`` words after ``sunwind mesh KIND`` as keyword arguments of its builder.

    Types follow the builder's defaults: numbers, ``--flag``/``--no-flag`` for booleans, and several
    numbers for a sequence (``--size 1 2 3``).

    Parameters
    ----------
    kind : str
        The mesh kind, for messages.
    builder : callable
        The kind's builder (:data:`sunwind.meshes.PRIMITIVES` or the sample spacecraft's); its
        signature names the parameters and its defaults type them.
    words : list of str
        The command-line words after the kind.

    Returns
    -------
    dict
        The builder's keyword arguments.

    Raises
    ------
    InputError
        A word that is no ``--name``, a name the builder does not take, or a value that is not of its
        type.

    Examples
    --------
    >>> from sunwind import meshes
    >>> builder_params("cylinder", meshes.cylinder, ["--radius", "0.5", "--no-caps"])
    {'radius': 0.5, 'caps': False}
    >>> builder_params("box", meshes.box, ["--size", "1", "2", "0.5"])
    {'size': (1, 2, 0.5)}
    >>> builder_params("box", meshes.box, ["--radius", "1"])
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: mesh box has no parameter --radius; use --size, --divisions
    """
    signature = inspect.signature(builder).parameters
    params: dict = {}
    i = 0
    while i < len(words):
        word = words[i]
        if not word.startswith("--"):
            raise InputError(f"unexpected '{word}' for mesh {kind}", hint="give parameters as --name value")
        name = word[2:].replace("-", "_")
        negated = name.startswith("no_") and name[3:] in signature
        key = name[3:] if negated else name
        if key not in signature:
            valid = ", ".join("--" + p.replace("_", "-") for p in signature)
            raise InputError(f"mesh {kind} has no parameter --{name.replace('_', '-')}", hint=f"use {valid}")
        values = []
        i += 1
        while i < len(words) and not words[i].startswith("--"):
            values.append(words[i])
            i += 1
        params[key] = _parameter(kind, key, signature[key].default, values, negated)
    return params


def _parameter(kind: str, key: str, default: object, values: list[str], negated: bool) -> object:
    """One builder parameter from its words, typed as its default."""
    try:
        if isinstance(default, bool):
            if values:
                raise ValueError
            return not negated
        if isinstance(default, tuple | list) or len(values) > 1:
            return tuple(float(v) if "." in v or "e" in v.lower() else int(v) for v in values)
        if len(values) == 1:
            whole = isinstance(default, int) or (default is None and values[0].lstrip("+-").isdigit())
            return int(values[0]) if whole else float(values[0])
        raise ValueError
    except ValueError:
        raise InputError(
            f"mesh {kind}: bad value for --{key.replace('_', '-')}: {' '.join(values)!r}",
            hint="give a number (or several for a size)",
        ) from None


def _shown(value: object) -> str:
    """A value of the info report as text for a person: yes/no, numbers to 6 digits, none as a dash."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if value is None:
        return "-"
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def kind_parameters() -> str:
    r"""List every mesh kind's flags and their defaults, for the epilog of ``sunwind mesh --help``.

    The flags come from the builders' own signatures, so the help cannot drift from them.

    Returns
    -------
    str
        A click epilog: a no-rewrap marker line (``\b``), a title, then one line per kind.

    Examples
    --------
    >>> lines = kind_parameters().splitlines()
    >>> print(lines[1])
    Parameters of each kind (default):
    >>> print(next(line for line in lines if "box " in line))
      box       --size 1 1 1, --divisions 1
    """
    lines = ["\b", "Parameters of each kind (default):"]
    for kind, builder in [*meshes.PRIMITIVES.items(), ("sample", meshes.sample_spacecraft)]:
        flags = []
        for name, parameter in inspect.signature(builder).parameters.items():
            flag, default = "--" + name.replace("_", "-"), parameter.default
            if isinstance(default, bool):
                flags.append(f"--[no-]{flag[2:]} ({'on' if default else 'off'})")
            elif isinstance(default, tuple | list):
                flags.append(f"{flag} {' '.join(f'{v:g}' for v in default)}")
            else:
                flags.append(f"{flag} {'(from the others)' if default is None else default}")
        lines.append(f"  {kind:<9} {', '.join(flags)}")
    return "\n".join(lines)


@click.command(
    context_settings={"ignore_unknown_options": True, "allow_extra_args": True}, epilog=kind_parameters()
)
@click.argument("kind")
@click.option(
    "--output",
    "-o",
    type=click.Path(path_type=Path),
    required=True,
    help="File to write: .obj .stl .ply .glb .gltf .usda .usdc",
)
@click.pass_context
def mesh(ctx: click.Context, kind: str, output: Path) -> None:
    """Write a parametric mesh: plate, sphere, cylinder, cone, dish, box, box_wing, or sample.

    Parameters follow the kind, e.g. `sunwind mesh cylinder --radius 0.5 --length 2 --no-caps -o c.obj`,
    `sunwind mesh sample --triangles 100000 -o big.usda`. Frames: METHOD.md "Frames, units and signs".
    """
    from sunwind.geometry.io import save_mesh  # its readers load trimesh and USD: when a mesh is written
    from sunwind.geometry.io.registry import SINGLE_BODY_SUFFIXES

    builder = meshes.sample_spacecraft if kind == "sample" else meshes.PRIMITIVES.get(kind)
    if builder is None:
        kinds = ", ".join([*meshes.PRIMITIVES, "sample"])
        raise InputError(f"unknown mesh kind '{kind}'", hint=f"choose one of {kinds}")
    params = builder_params(kind, builder, ctx.args)
    try:
        built = builder(**params) if kind == "sample" else meshes.build(kind, **params)
    except SunwindError as error:  # the builder names its parameters: write them as this command's flags
        flags = {name: "--" + name.replace("_", "-") for name in inspect.signature(builder).parameters}
        raise error.renamed(flags) from None
    parts = len(np.unique(built.face_part))
    if output.suffix.lower() in SINGLE_BODY_SUFFIXES and (parts > 1 or len(built.material_names) > 1):
        raise InputError(
            f"mesh {kind} has {parts} parts and {len(built.material_names)} materials, which a "
            f"{output.suffix} file cannot keep (it holds one body: sunwind would read it as one part "
            "without material)",
            path=str(output),
            hint="write .obj (with its .toml), .glb, .gltf, .usda or .usdc",
        )
    save_mesh(built, output)
    print(f"wrote {output}: {built.n_faces} triangles, parts {', '.join(built.part_names)}")
    if kind == "sample" and not output.suffix.lower().startswith(".usd"):
        materials = output.with_suffix(".toml")
        materials.write_text(meshes.materials_toml(built))
        print(f"wrote {materials}: its materials and two-sided sheets (use with --materials)")
    elif built.two_sided_parts:
        print(
            f"two-sided sheets: {', '.join(sorted(built.two_sided_parts))} (declare them, e.g. --two-sided)"
        )
