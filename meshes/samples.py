"""The sample spacecraft: a box-wing satellite with dish, boom and engine, its materials and files.

Build it with :func:`sample_spacecraft`; the shipped files in ``meshes/data`` (OBJ + materials
TOML, and USD carrying the optics) are written by :func:`write_sample_files`, which is what
``python -m sunwind.meshes.samples [--triangles N] [-o DIR]`` runs. Regenerate the shipped files after
changing anything here with ``python -m sunwind.meshes.samples``.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.triangles import normals
from sunwind.meshes.arguments import check_triangles
from sunwind.meshes.assembly import label, rotation_matrix, transform
from sunwind.meshes.primitives import box, cone, cylinder, dish, plate

#: Directory of the shipped sample files.
DATA_DIR = Path(__file__).resolve().parent / "data"
#: Base name of the shipped sample files.
SAMPLE_NAME = "sample_spacecraft"

#: Solar-band optics of the sample's materials: reflectivity ``rho``, specular share of the
#: reflected light ``beta`` and transmissivity ``sigma`` (METHOD.md "Surfaces and sides"). Beginning-of-life
#: values; ``rho = 1 - alpha_s`` for an opaque finish, sources and reasoning in
#: :data:`SAMPLE_OPTICS_NOTES`.
SAMPLE_OPTICS: dict[str, dict[str, float]] = {
    "mli": {"reflectivity": 0.60, "specular_fraction": 0.40, "transmissivity": 0.0},
    "osr": {"reflectivity": 0.92, "specular_fraction": 0.95, "transmissivity": 0.0},
    "white_paint": {"reflectivity": 0.80, "specular_fraction": 0.05, "transmissivity": 0.0},
    "reflector_paint": {"reflectivity": 0.76, "specular_fraction": 0.05, "transmissivity": 0.0},
    "solar_cell": {"reflectivity": 0.09, "specular_fraction": 0.80, "transmissivity": 0.0},
    "cfrp": {"reflectivity": 0.08, "specular_fraction": 0.20, "transmissivity": 0.0},
    "aluminium": {"reflectivity": 0.75, "specular_fraction": 0.60, "transmissivity": 0.0},
    "niobium_silicide": {"reflectivity": 0.20, "specular_fraction": 0.10, "transmissivity": 0.0},
}

#: Where each value of :data:`SAMPLE_OPTICS` comes from. "Gilmore" is D. G. Gilmore (ed.),
#: *Spacecraft Thermal Control Handbook*, Vol. I, 2nd ed., The Aerospace Press, 2002, App. A
#: (solar absorptance ``alpha_s`` of finishes); the specular shares are judgements from the finish.
SAMPLE_OPTICS_NOTES: dict[str, str] = {
    "mli": "aluminised Kapton outer layer, Kapton outward: alpha_s 0.38-0.44 (Gilmore), take 0.40;"
    " glossy but wrinkled film, half specular; aluminium backing, opaque",
    "osr": "optical solar reflector, silvered fused silica: alpha_s 0.05-0.08 (Gilmore);"
    " second-surface mirror, almost all specular",
    "white_paint": "white thermal paint (S13G/LO, AZ-93 class): alpha_s 0.15-0.20 (Gilmore);"
    " matte, nearly Lambertian",
    "reflector_paint": "conductive white paint on the dish front (PCB-Z, SG121FD class):"
    " alpha_s 0.20-0.28 (Gilmore), take 0.24; matte",
    "solar_cell": "triple-junction GaAs cells under cover glass: alpha_s 0.88-0.92 (Gilmore);"
    " the reflection is mostly the cover glass's, specular",
    "cfrp": "bare carbon-fibre epoxy (wing backs, yokes): alpha_s 0.90-0.93 (Gilmore);"
    " resin-rich surface, mostly diffuse",
    "aluminium": "machined aluminium alloy (boom): alpha_s 0.10-0.40 with finish (Gilmore),"
    " take 0.25; partly specular",
    "niobium_silicide": "silicide-coated niobium engine nozzle (C103 + R512E class): dark grey,"
    " alpha_s taken 0.80 (estimate, no handbook value); diffuse",
}

#: Hemispherical infrared emissivity ``eps`` of the sample's materials (grey; by Kirchhoff the infrared
#: absorptance), beginning of life; sources in :data:`SAMPLE_EMISSIVITY_NOTES`, written to the materials
#: files and carried by the USD file with the solar optics.
SAMPLE_EMISSIVITY: dict[str, float] = {
    "mli": 0.67,
    "osr": 0.80,
    "white_paint": 0.88,
    "reflector_paint": 0.88,
    "solar_cell": 0.85,
    "cfrp": 0.82,
    "aluminium": 0.08,
    "niobium_silicide": 0.85,
}

#: Where each value of :data:`SAMPLE_EMISSIVITY` comes from (Gilmore as in :data:`SAMPLE_OPTICS_NOTES`;
#: Henninger = NASA RP-1121, 1984; Fortescue = Spacecraft Systems Engineering, 4th ed., Wiley, 2011,
#: Table 11.3).
SAMPLE_EMISSIVITY_NOTES: dict[str, str] = {
    "mli": "aluminised Kapton, Kapton outward: eps 0.67 for 1 mil film (Gilmore; Fortescue 0.63 at alpha_s"
    " 0.40), more for thicker film: take 0.67",
    "osr": "silvered fused silica: eps 0.80 (Gilmore)",
    "white_paint": "S13G/LO eps 0.85, AZ-93 eps 0.91 (Henninger; Gilmore): take 0.88",
    "reflector_paint": "conductive white paints of this class: eps about 0.85-0.90 (Gilmore), take 0.88",
    "solar_cell": "cells under cover glass: eps 0.80-0.85 (Gilmore; Fortescue 0.80), take 0.85, the glass's",
    "cfrp": "graphite-epoxy: eps 0.80-0.85 (Gilmore), take 0.82",
    "aluminium": "bare aluminium alloy: eps 0.03-0.10 with the finish; polished aluminium 0.08 at alpha_s"
    " 0.24 (Fortescue), as this one: take 0.08",
    "niobium_silicide": "silicide coatings are chosen for a high emittance: eps taken 0.85 (estimate, no"
    " handbook value)",
}

#: Part -> (front material, back material) of the two-sided sheets.
SHEETS: dict[str, tuple[str, str]] = {
    "wing_left": ("solar_cell", "cfrp"),
    "wing_right": ("solar_cell", "cfrp"),
    "dish": ("reflector_paint", "mli"),
}


@dataclass(frozen=True)
class Dimensions:
    """Sizes of the sample spacecraft (see :func:`sample_spacecraft`).

    Attributes
    ----------
    bus_size : (3,) tuple of float
        Bus box edges along x, y, z [m].
    clearance : float
        Gap between separately built parts [m]: none touches another.
    yoke_radius, yoke_length : float
        Solar-array yoke cylinders [m].
    panel_span, panel_width, panel_gap : float
        Solar panel length along y, width along z at array angle 0, and gap between panels [m].
    panels_per_wing : int
        Panels in each wing.
    mast_radius, mast_length : float
        Antenna mast cylinder [m].
    dish_diameter : float
        Antenna dish rim diameter [m].
    dish_focal_ratio : float
        Dish ``f / D`` [-].
    boom_radius, boom_length : float
        Magnetometer boom cylinder [m].
    boom_tip_size : (3,) tuple of float
        Magnetometer box edges [m].
    nozzle_exit_radius : float
        Apogee-engine nozzle exit radius [m].
    nozzle_half_angle_deg : float
        Nozzle cone half-angle [deg].

    Examples
    --------
    >>> d = Dimensions()
    >>> round(d.panels_per_wing * d.panel_span + (d.panels_per_wing - 1) * d.panel_gap, 6)
    3.2
    """

    bus_size: tuple[float, float, float] = (1.6, 1.4, 1.2)
    clearance: float = 0.002  # gap between separately built parts: none touches another
    yoke_radius: float = 0.025
    yoke_length: float = 0.8
    panel_span: float = 1.04  # along y; 3 panels and 2 gaps make a 3.2 m wing
    panel_width: float = 1.1  # along z at array angle 0
    panel_gap: float = 0.04
    panels_per_wing: int = 3
    mast_radius: float = 0.05
    mast_length: float = 0.3
    dish_diameter: float = 1.2
    dish_focal_ratio: float = 0.35
    boom_radius: float = 0.03
    boom_length: float = 2.0
    boom_tip_size: tuple[float, float, float] = (0.12, 0.08, 0.08)
    nozzle_exit_radius: float = 0.12
    nozzle_half_angle_deg: float = 20.0


#: The sample's dimensions.
DIMENSIONS = Dimensions()

_MIN_TRIANGLES = 2_000
_MIN_SEGMENTS = 12  # facets round the thinnest struts, whatever the facet size


def sample_spacecraft(triangles: int = 20_000, array_angle_deg: float = 0.0) -> MeshData:
    """A realistic small GEO-style satellite whose triangle count follows ``triangles``.

    Provenance: built here from :mod:`sunwind.meshes.primitives` (no external model); the shipped
    ``meshes/data/sample_spacecraft.*`` are this function at 20 000 triangles and array angle 0.

    Body frame (nadir-pointing, the local-vertical/local-horizontal frame at zero attitude):
    origin at the centre of the bus box; +z toward Earth (the dish side); +y along the solar-array
    axis, toward the negative orbit normal; +x = y x z, along the velocity on a circular orbit.

    Parts (closed bodies are watertight and outward-wound; sheets are zero-thickness, two-sided
    and share no vertex with anything, separated by a 2 mm clearance):

    ============ ========== ===================================================== ==============
    part         kind       geometry [m]                                          material(s)
    ============ ========== ===================================================== ==============
    bus          closed     box 1.6 x 1.4 x 1.2 centred at the origin             mli; osr on the
                                                                                  +-y radiators
    yoke_left/   closed     cylinders r 0.025, 0.8 long on the y axis from the    cfrp
    yoke_right              -y / +y faces
    wing_left/   two-sided  3 panels 1.04 (y) x 1.1 (z) with 0.04 gaps, 3.2 long, front solar_cell,
    wing_right   sheet      in the plane x = 0 beyond the yokes, y ±(1.504-4.704) back cfrp
    mast         closed     cylinder r 0.05, 0.3 long on +z above the bus         white_paint
    dish         two-sided  paraboloid D 1.2, f/D 0.35 (f 0.42, depth 0.214),     front
                 sheet      vertex at z 0.904 on the mast, concave side +z        reflector_paint,
                                                                                  back mli
    boom         closed     cylinder r 0.03, 2.0 long on the -x axis              aluminium
    boom_tip     closed     box 0.12 x 0.08 x 0.08 (magnetometer) at x -2.864     white_paint
    nozzle       closed     cone, exit r 0.12, half-angle 20 deg, apex at the     niobium_silicide
                            -z face (apogee engine), exit plane z -0.932
    ============ ========== ===================================================== ==============

    Extent at array angle 0: y -4.704 to 4.704, x -2.924 to 0.8, z -0.932 to 1.118. Materials
    and their optics are in :data:`SAMPLE_OPTICS` (also carried as ``file_optics``), with sources
    in :data:`SAMPLE_OPTICS_NOTES`, their infrared emissivities (in the materials files only) in
    :data:`SAMPLE_EMISSIVITY`; the back materials of the sheets are in
    ``part_back_material``.

    Triangle count: all parts are meshed at one facet size ``h``, struts with at least 12 facets
    round, and ``h`` is adjusted until the count is within 2 % of ``triangles``: 20 000 gives
    19 984 triangles (h = 4.8 cm), 100 000 gives 100 180 (h = 2.1 cm). The chosen ``h`` is
    ``metadata["facet_size_m"]``.

    Parameters
    ----------
    triangles : int
        Target triangle count, >= 2000.
    array_angle_deg : float
        Solar-array drive angle [deg]: both wings are turned about +y (right-handed) from the
        cells facing +x, so the cell normal is ``(cos a, 0, -sin a)``; 90 deg faces them to -z.

    Returns
    -------
    MeshData
        ``metadata`` holds ``shape``, ``triangles``, ``array_angle_deg``, ``facet_size_m`` and
        ``dimensions_m`` (:data:`DIMENSIONS`).

    Raises
    ------
    InputError
        ``triangles`` below 2000 or ``array_angle_deg`` not finite.

    Examples
    --------
    >>> mesh = sample_spacecraft(2_000)
    >>> len(mesh.part_names), sorted(mesh.two_sided_parts)
    (10, ['dish', 'wing_left', 'wing_right'])
    """
    if isinstance(triangles, bool) or not isinstance(triangles, (int, np.integer)):
        raise InputError(f"triangles = {triangles!r} must be an integer")
    if triangles < _MIN_TRIANGLES:
        raise InputError(
            f"triangles = {triangles} is too few for the sample spacecraft",
            hint=f"ask for at least {_MIN_TRIANGLES}",
        )
    if not math.isfinite(array_angle_deg):
        raise InputError(f"array_angle_deg = {array_angle_deg!r} must be finite")
    check_triangles(triangles, "lower triangles", ("triangles",))
    facet = math.sqrt(2 * 21.0 / triangles)  # two triangles per h^2 over ~21 m^2 of surface
    best: tuple[float, MeshData] | None = None
    for _ in range(12):
        mesh = _assemble(facet, array_angle_deg)
        if best is None or abs(mesh.n_faces - triangles) < abs(best[1].n_faces - triangles):
            best = (facet, mesh)
        if abs(mesh.n_faces / triangles - 1) < 0.02:
            break
        facet *= math.sqrt(mesh.n_faces / triangles)
    facet, mesh = best
    metadata = {
        "shape": "sample_spacecraft",
        "triangles": int(triangles),
        "array_angle_deg": float(array_angle_deg),
        "facet_size_m": facet,
        "dimensions_m": asdict(DIMENSIONS),
    }
    return replace(mesh, metadata=metadata)


def _assemble(facet: float, array_angle_deg: float) -> MeshData:
    """All parts of the sample at facet size ``facet`` [m], joined into one mesh."""
    d = DIMENSIONS
    gap = d.clearance
    half = np.asarray(d.bus_size) / 2

    def cells(*lengths: float) -> tuple[int, ...]:
        return tuple(max(1, math.ceil(length / facet)) for length in lengths)

    def strut(radius: float, length: float) -> MeshData:
        segments = max(_MIN_SEGMENTS, math.ceil(2 * math.pi * radius / facet))
        return cylinder(radius, length, segments=segments, rings=cells(length)[0])

    z_to_y, z_to_x = rotation_matrix("x", -90.0), rotation_matrix("y", 90.0)

    bus = label(box(d.bus_size, cells(*d.bus_size)), "bus", "mli")
    radiator = np.abs(normals(bus.vertices[bus.faces])[:, 1]) > 0.5  # the +-y faces
    bus = replace(bus, material_names=("mli", "osr"), face_material=radiator.astype(np.int32))

    yoke = strut(d.yoke_radius, d.yoke_length)
    yoke_centre = half[1] + gap + d.yoke_length / 2
    root = half[1] + gap + d.yoke_length + gap  # inner edge of the first panel
    span, pitch = d.panel_span, d.panel_span + d.panel_gap
    panel = plate(span, d.panel_width, cells(span, d.panel_width))
    to_body = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])  # front +x, span y
    drive = rotation_matrix("y", array_angle_deg) @ to_body
    panel_centres = root + span / 2 + pitch * np.arange(d.panels_per_wing)

    def place(
        mesh: MeshData, part: str, material: str, at: Sequence[float], rotation: np.ndarray | None = None
    ) -> MeshData:
        return label(transform(mesh, rotation, at), part, material)

    parts = [bus]
    for side, sign in (("left", -1.0), ("right", 1.0)):
        parts.append(place(yoke, f"yoke_{side}", "cfrp", (0, sign * yoke_centre, 0), z_to_y))
        panels = [transform(panel, drive, (0, sign * y, 0)) for y in panel_centres]
        parts.append(label(MeshData.concatenate(panels), f"wing_{side}", SHEETS[f"wing_{side}"][0]))

    mast_base = half[2] + gap
    mast = strut(d.mast_radius, d.mast_length)
    parts.append(place(mast, "mast", "white_paint", (0, 0, mast_base + d.mast_length / 2)))
    rim_segments = max(2 * _MIN_SEGMENTS, math.ceil(math.pi * d.dish_diameter / facet))
    reflector = dish(d.dish_diameter, d.dish_focal_ratio, segments=rim_segments)
    dish_vertex = (0, 0, mast_base + d.mast_length + gap)
    parts.append(place(reflector, "dish", SHEETS["dish"][0], dish_vertex))

    boom_start = half[0] + gap
    boom = strut(d.boom_radius, d.boom_length)
    parts.append(place(boom, "boom", "aluminium", (-(boom_start + d.boom_length / 2), 0, 0), z_to_x))
    tip = box(d.boom_tip_size, cells(*d.boom_tip_size))
    tip_centre = boom_start + d.boom_length + gap + d.boom_tip_size[0] / 2
    parts.append(place(tip, "boom_tip", "white_paint", (-tip_centre, 0, 0)))

    exit_radius, half_angle = d.nozzle_exit_radius, math.radians(d.nozzle_half_angle_deg)
    height = exit_radius / math.tan(half_angle)
    nozzle = cone(
        exit_radius,
        d.nozzle_half_angle_deg,
        segments=max(_MIN_SEGMENTS, math.ceil(2 * math.pi * exit_radius / facet)),
        rings=cells(exit_radius / math.sin(half_angle))[0],
    )
    # The cone's apex (+z) is the throat, at the bus's -z face; the exit plane faces -z.
    parts.append(place(nozzle, "nozzle", "niobium_silicide", (0, 0, -(half[2] + gap + height))))

    mesh = MeshData.concatenate(parts, source=f"<{SAMPLE_NAME}>")
    return replace(
        mesh,
        file_optics=_file_optics(),
        two_sided_parts=frozenset(SHEETS),
        part_back_material={part: back for part, (_, back) in SHEETS.items()},
    )


def _file_optics() -> dict[str, dict[str, float]]:
    """What the sample's USD file carries per material: the solar optics and the emissivity."""
    return {name: {**values, "emissivity": SAMPLE_EMISSIVITY[name]} for name, values in SAMPLE_OPTICS.items()}


def materials_toml(mesh: MeshData) -> str:
    """Write the materials file (sunwind TOML schema) for a sample mesh saved without its optics, e.g. as OBJ.

    Every material key of the mesh and every back material gets a ``[materials.NAME]`` table from
    :data:`SAMPLE_OPTICS` and :data:`SAMPLE_EMISSIVITY`, commented with their sources; each two-sided
    part gets a ``[parts]`` entry with its front and back. Closed parts are not listed: each face keeps
    the file's material key.

    Parameters
    ----------
    mesh : MeshData
        A mesh whose material keys are keys of :data:`SAMPLE_OPTICS`, e.g. :func:`sample_spacecraft`.

    Returns
    -------
    str
        TOML text.

    Examples
    --------
    >>> from sunwind.geometry.materials import parse_materials
    >>> import tomllib
    >>> spec = parse_materials(tomllib.loads(materials_toml(sample_spacecraft(2_000))))
    >>> spec.rule_for("wing_left").back
    'cfrp'
    """
    names = list(dict.fromkeys([*mesh.material_names, *mesh.part_back_material.values()]))
    lines = [
        f"# Materials for {SAMPLE_NAME}.obj in the sunwind materials schema.",
        "# Generated by `python -m sunwind.meshes.samples` from meshes/samples.py (SAMPLE_OPTICS,",
        "# SAMPLE_EMISSIVITY); do not edit.",
        "# Solar band: reflectivity rho, specular share of the reflected light beta, transmissivity",
        "# sigma; absorptivity alpha = 1 - rho - sigma. Infrared: hemispherical emissivity eps (grey).",
        "# Gilmore = Spacecraft Thermal Control Handbook, Vol. I, 2nd ed. (Aerospace Press, 2002),",
        "# App. A; Henninger = NASA RP-1121 (1984); Fortescue = Spacecraft Systems Engineering, 4th",
        "# ed. (Wiley, 2011), Table 11.3.",
    ]
    for name in names:
        optics = SAMPLE_OPTICS[name]
        lines += [
            "",
            f"# {SAMPLE_OPTICS_NOTES[name]}",
            f"# infrared: {SAMPLE_EMISSIVITY_NOTES[name]}",
            f"[materials.{name}]",
            f"reflectivity = {optics['reflectivity']!r}  # rho",
            f"specular_fraction = {optics['specular_fraction']!r}  # beta",
            f"transmissivity = {optics['transmissivity']!r}  # sigma",
            f"emissivity = {SAMPLE_EMISSIVITY[name]!r}  # eps",
        ]
    lines += [
        "",
        "# Part-name glob -> material; first match wins. A table makes the part a two-sided sheet.",
        "# Parts not listed are closed bodies and use the OBJ usemtl key of each face.",
        "[parts]",
    ]
    for part in sorted(mesh.two_sided_parts):
        front = mesh.material_names[mesh.face_material[mesh.face_part == mesh.part_names.index(part)][0]]
        lines.append(f'"{part}" = {{ front = "{front}", back = "{mesh.part_back_material[part]}" }}')
    return "\n".join(lines) + "\n"


#: The sample's solar-array drive (``sample_spacecraft_tracking.toml``): both wings turn about the
#: yokes' axis, body y through the origin, with their cells as close to the Sun as it allows.
ARRAY_DRIVE = """
# Solar-array drive: both wings turn about the yokes' axis (body y, through the bus centre), their
# cells (front, +x as drawn) as close to the Sun as the hinge allows.
[articulation."wing_*"]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
track = "sun"
"""


def write_sample_files(directory: str | Path = DATA_DIR, triangles: int = 20_000) -> dict[str, Path]:
    """Build the sample and write its ``.obj``, ``.usda``, ``.toml`` and ``_tracking.toml`` files.

    The files go into ``directory``, named ``sample_spacecraft.*``.

    The OBJ carries geometry, parts (groups) and material keys (``usemtl``); the TOML beside it
    gives the optics and the two-sided sheets, and ``_tracking.toml`` the same with the arrays
    turning to the Sun (:data:`ARRAY_DRIVE`). The USD carries all of the first: optics as
    ``sunwind:*`` material attributes, ``doubleSided`` sheets and their ``sunwind:backMaterial``.

    Returns
    -------
    dict
        ``{"obj": path, "usda": path, "toml": path, "tracking": path}``.

    Parameters
    ----------
    directory : str or Path
        Folder to write into; default the shipped ``meshes/data``.
    triangles : int
        Target triangle count, >= 2000 (see :func:`sample_spacecraft`).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     sorted(write_sample_files(folder, triangles=2_000))
    ['obj', 'toml', 'tracking', 'usda']
    """
    from sunwind.geometry.io import save_mesh

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    mesh = sample_spacecraft(triangles)
    paths = {suffix: directory / f"{SAMPLE_NAME}.{suffix}" for suffix in ("obj", "usda", "toml")}
    save_mesh(mesh, paths["obj"])
    save_mesh(mesh, paths["usda"], optics=_file_optics())
    paths["toml"].write_text(materials_toml(mesh), encoding="utf-8")
    paths["tracking"] = directory / f"{SAMPLE_NAME}_tracking.toml"
    paths["tracking"].write_text(materials_toml(mesh) + ARRAY_DRIVE, encoding="utf-8")
    return paths


def sample_path(name: str = f"{SAMPLE_NAME}.obj") -> Path:
    """Find a shipped sample file in ``meshes/data``.

    Parameters
    ----------
    name : str
        The file name; default ``sample_spacecraft.obj``.

    Returns
    -------
    Path
        Its path.

    Raises
    ------
    InputError
        No such file; the message lists the shipped ones.

    Examples
    --------
    >>> sample_path().name
    'sample_spacecraft.obj'
    """
    path = DATA_DIR / name
    if not path.is_file():
        shipped = sorted(p.name for p in DATA_DIR.glob("*") if p.is_file())
        raise InputError(f"no sample file '{name}'", hint=f"shipped: {', '.join(shipped) or 'none'}")
    return path


def sample_materials_path() -> Path:
    """Find the shipped materials file for ``sample_spacecraft.obj``.

    Returns
    -------
    Path
        The path of ``meshes/data/sample_spacecraft.toml``.

    Examples
    --------
    >>> sample_materials_path().name
    'sample_spacecraft.toml'
    """
    return sample_path(f"{SAMPLE_NAME}.toml")


def main(argv: Sequence[str] | None = None) -> None:
    """Run the command line ``python -m sunwind.meshes.samples [--triangles N] [-o DIR]``.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments; default ``sys.argv[1:]``.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:  # doctest: +ELLIPSIS
    ...     main(["--triangles", "2000", "-o", folder])
    /...sample_spacecraft.obj
    ...
    """
    parser = argparse.ArgumentParser(
        prog="python -m sunwind.meshes.samples", description="Write the sample spacecraft files."
    )
    parser.add_argument("--triangles", type=int, default=20_000, help="target triangle count")
    parser.add_argument("-o", "--output", type=Path, default=DATA_DIR, help="output directory")
    args = parser.parse_args(argv)
    for path in write_sample_files(args.output, args.triangles).values():
        print(path)


if __name__ == "__main__":
    main()
