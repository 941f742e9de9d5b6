"""Hostile model files on the command line (issue 17, model loading): each gives one line and no traceback.

Each case writes its files into a temporary folder and runs ``sunwind`` on them; it checks the exit
code and the key words of the error, warning or notice line.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

#: Eight corners of the unit cube and its six faces, counter-clockwise seen from outside (0-based).
CUBE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def obj_text(parts: dict, points=CUBE_POINTS, scale: float = 1.0, mtl=None, shared: bool = False) -> str:
    """An OBJ with one group per part, each on its own copy of ``points`` 2 m further along x (all on
    the same points when ``shared``); ``mtl`` maps a part to its usemtl key."""
    lines = []
    for k, (part, faces) in enumerate(parts.items()):
        dx = 0 if shared else 2 * k
        if k == 0 or not shared:
            lines += [f"v {(x + dx) * scale:g} {y * scale:g} {z * scale:g}" for x, y, z in points]
        lines.append(f"g {part}")
        if mtl and part in mtl:
            lines.append(f"usemtl {mtl[part]}")
        base = 0 if shared else k * len(points)
        lines += ["f " + " ".join(str(base + i + 1) for i in face) for face in faces]
    return "\n".join(lines) + "\n"


def usda_cube(metadata: str = "metersPerUnit = 1", extra: str = "", scale: str = "") -> str:
    """A USD stage with one cube Mesh (white optics), layer ``metadata`` and ``extra`` prims."""
    points = ", ".join(f"({x}, {y}, {z})" for x, y, z in CUBE_POINTS)
    indices = ", ".join(str(i) for quad in CUBE_QUADS for i in quad)
    op = (
        f'double3 xformOp:scale = {scale}\n        uniform token[] xformOpOrder = ["xformOp:scale"]'
        if scale
        else ""
    )
    return f"""#usda 1.0
(
    {metadata}
)

def Xform "root"
{{
    def Scope "Looks"
    {{
        def Material "white"
        {{
            custom float sunwind:reflectivity = 0.8
            custom float sunwind:specularFraction = 0.1
            custom float sunwind:transmissivity = 0
        }}
    }}
    def Mesh "box" (prepend apiSchemas = ["MaterialBindingAPI"])
    {{
        {op}
        int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]
        int[] faceVertexIndices = [{indices}]
        point3f[] points = [{points}]
        rel material:binding = </root/Looks/white>
    }}
    {extra}
}}
"""


def gltf_scaled(directory: Path, scale: list[float]) -> None:
    """``m.gltf``: the unit cube as one node with ``scale``."""
    import json

    from sunwind.geometry.io import load_mesh, save_mesh

    (directory / "c.obj").write_text(obj_text({"box": CUBE_QUADS}))
    save_mesh(load_mesh(directory / "c.obj"), directory / "m.gltf")
    document = json.loads((directory / "m.gltf").read_text())
    document["nodes"][0]["scale"] = scale
    (directory / "m.gltf").write_text(json.dumps(document))


def t_junction_box() -> tuple[list, dict]:
    """The unit cube with its top split in two along x = 0.5: the front and back faces keep one edge
    where the top has two (a T-junction at each end), as CAD exporters write. Closed physically."""
    points = [*CUBE_POINTS, (0.5, 0, 1), (0.5, 1, 1)]
    faces = [q for q in CUBE_QUADS if q != (4, 5, 6, 7)] + [(4, 8, 9, 7), (8, 5, 6, 9)]
    return points, {"box": faces}


#: A materials-file table of material ``w``.
WHITE = "[materials.w]\nreflectivity = 0.5\nspecular_fraction = 0\n"
#: A uniform material on the command line.
UNIFORM = ["--reflectivity", "0", "--specular-fraction", "0"]
#: A closed box and a one-sided wing (front -z) beside it, with material ``w``.
WINGED = obj_text({"box": CUBE_QUADS, "wing": CUBE_QUADS[:1]})
WINGED_PARTS = f'{WHITE}[parts]\n"wing" = {{ front = "w" }}\n"box" = "w"\n'
#: A hinge on the wing about ``axis`` through (2, 0, 0), with ``law``.
HINGE = "[articulation.wing]\naxis = {axis}\norigin_m = [2, 0, 0]\n{law}\n"
SUN_X = ["--sun", "1", "0", "0"]


def winged(extra: str, law: str = "angle_deg = 30", axis: str = "[0, 1, 0]") -> Callable[[Path], None]:
    """A builder of the winged box with its materials, the hinge of ``law`` and ``axis``, and ``extra``
    tables."""

    def build(folder: Path) -> None:
        (folder / "m.obj").write_text(WINGED)
        (folder / "m.toml").write_text(WINGED_PARTS + HINGE.format(law=law, axis=axis) + extra)

    return build


#: An explicit atmosphere for drag.
FREE_STREAM = ["--density", "1e-12", "--temperature", "1000", "--composition", "O:1", "--reflections", "none"]

CASES = {
    # item 1: USD composition errors
    "usd-missing-reference": (
        lambda d: (d / "m.usda").write_text(
            usda_cube(extra='def Xform "arm" (references = @missing_arm.usda@) {}')
        ),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "m.usda", "missing_arm.usda"],
    ),
    "usd-missing-sublayer": (
        lambda d: (d / "m.usda").write_text(usda_cube("metersPerUnit = 1\n    subLayers = [@gone.usda@]")),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "m.usda", "gone.usda"],
    ),
    "usd-missing-payload": (
        lambda d: (d / "m.usda").write_text(usda_cube(extra='def Xform "arm" (payload = @lost.usdc@) {}')),
        ["srp", "m.usda", "--sun", "1", "0", "0"],
        1,
        ["error", "m.usda", "lost.usdc"],
    ),
    # item 2: bad stage units and scales
    "usd-metersPerUnit-negative": (
        lambda d: (d / "m.usda").write_text(usda_cube("metersPerUnit = -1")),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "m.usda", "metersPerUnit", "-1"],
    ),
    "usd-metersPerUnit-zero": (
        lambda d: (d / "m.usda").write_text(usda_cube("metersPerUnit = 0")),
        ["srp", "m.usda", "--sun", "1", "0", "0"],
        1,
        ["error", "m.usda", "metersPerUnit", "0"],
    ),
    "usd-metersPerUnit-inf": (
        lambda d: (d / "m.usda").write_text(usda_cube("metersPerUnit = inf")),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "m.usda", "metersPerUnit", "inf"],
    ),
    "usd-scale-zero": (
        lambda d: (d / "m.usda").write_text(usda_cube(scale="(1, 0, 1)")),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "/root/box", "transform", "collapses"],
    ),
    "usd-scale-nan": (
        lambda d: (d / "m.usda").write_text(usda_cube(scale="(1, nan, 1)")),
        ["info", "m.usda", "--no-k-is"],
        1,
        ["error", "/root/box", "transform", "finite"],
    ),
    "gltf-scale-zero": (
        lambda d: gltf_scaled(d, [1, 0, 1]),
        ["info", "m.gltf", "--no-k-is", *UNIFORM],
        1,
        ["error", "m.gltf", "part 'box'", "collapses"],
    ),
    # item 6: a size that suggests the wrong unit
    "size-1000-m": (
        lambda d: (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS}, scale=1000)),
        ["srp", "m.obj", "--sun", "1", "0", "0", *UNIFORM],
        0,
        ["notice", "1000 m", "--unit"],
    ),
    "size-5-mm": (
        lambda d: (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS}, scale=0.005)),
        ["info", "m.obj", "--no-k-is", *UNIFORM],
        0,
        ["0.005 m", "--unit"],
    ),
    # item 10: a materials file nested 5000 tables deep
    "toml-5000-deep": (
        lambda d: (
            (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
            (d / "m.toml").write_text("a = " + "{ b = " * 5000 + "1" + " }" * 5000 + "\n"),
        ),
        ["info", "m.obj", "--no-k-is", "-m", "m.toml"],
        1,
        ["error", "m.toml", "nested"],
    ),
    "toml-5000-deep-arrays": (
        lambda d: (
            (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
            (d / "m.toml").write_text("a = " + "[" * 5000 + "]" * 5000 + "\n"),
        ),
        ["srp", "m.obj", "--sun", "1", "0", "0", "-m", "m.toml"],
        1,
        ["error", "m.toml", "nested"],
    ),
    # item 24: a material key that is not a bare TOML key
    "undefined-dotted-key": (
        lambda d: (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS}, mtl={"box": "foil_silver.014"})),
        ["srp", "m.obj", "--sun", "1", "0", "0"],
        1,
        ["error", "foil_silver.014", '[materials."foil_silver.014"]'],
    ),
    # item 25: every problem of a load at once
    "ten-undefined-keys": (
        lambda d: (d / "m.obj").write_text(
            obj_text({f"p{k}": CUBE_QUADS for k in range(10)}, mtl={f"p{k}": f"paint_{k}" for k in range(10)})
        ),
        ["srp", "m.obj", "--sun", "1", "0", "0"],
        1,
        ["10 problems", *[f"paint_{k}" for k in range(10)]],
    ),
    "three-open-parts": (
        lambda d: (d / "m.obj").write_text(
            obj_text({"a": CUBE_QUADS[:5], "b": CUBE_QUADS[:4], "c": CUBE_QUADS[:3]})
        ),
        ["srp", "m.obj", "--sun", "1", "0", "0", *UNIFORM],
        1,
        ["3 problems", "part 'a'", "part 'b'", "part 'c'", "one-sided", "cavity"],
    ),
    "open-and-unassigned": (
        lambda d: (d / "m.obj").write_text(obj_text({"a": CUBE_QUADS[:5], "b": CUBE_QUADS}, mtl={"b": "x"})),
        ["srp", "m.obj", "--sun", "1", "0", "0"],
        1,
        ["problems", "part 'a' is an open surface", "'x'"],
    ),
    # item 26: a part open on its own, closed only with its neighbour
    "part-open-alone": (
        lambda d: (d / "m.obj").write_text(
            obj_text({"lid": CUBE_QUADS[:1], "tub": CUBE_QUADS[1:]}, shared=True)
        ),
        ["info", "m.obj", "--no-k-is", *UNIFORM],
        0,
        [
            "part 'lid' is open on its own (4 boundary edges): a closed body only together with 'tub'",
            "part 'tub' is open on its own",
            "part of a body",
        ],
    ),
    # item 27: a closed body with T-junctions is closed
    "t-junction-box": (
        lambda d: (d / "m.obj").write_text(obj_text(t_junction_box()[1], points=t_junction_box()[0])),
        ["srp", "m.obj", "--sun", "0", "0", "1", *UNIFORM],
        0,
        ["notice", "closed", "crack"],
    ),
    # item 5: a glob that selects no part
    "two-sided-glob-unmatched": (
        lambda d: (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
        ["srp", "m.obj", "--sun", "1", "0", "0", *UNIFORM, "--two-sided", "wing*"],
        1,
        ["error", "wing*", "box"],
    ),
    "parts-glob-unmatched": (
        lambda d: (
            (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
            (d / "m.toml").write_text(f'{WHITE}[parts]\n"bxo" = "w"\n"box" = "w"\n'),
        ),
        ["srp", "m.obj", "--sun", "1", "0", "0", "-m", "m.toml"],
        0,
        ["warning", "bxo", "box"],
    ),
    # item 16: single-body formats lose the parts of a multi-part model
    "mesh-sample-stl": (
        lambda d: None,
        ["mesh", "sample", "--triangles", "2000", "-o", "s.stl"],
        1,
        ["error", "parts", ".obj"],
    ),
    "mesh-sample-ply": (
        lambda d: None,
        ["mesh", "sample", "--triangles", "2000", "-o", "s.ply"],
        1,
        ["error", "parts", ".obj"],
    ),
    # item 18: the reference point is a default, or the model file's centre of mass
    "ref-point-default": (
        lambda d: (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
        ["srp", "m.obj", "--sun", "1", "0", "0", *UNIFORM],
        0,
        ["(volume centroid, a default: give the centre of mass with --ref-point"],
    ),
    "ref-point-centre-of-mass": (
        lambda d: (
            (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
            (d / "m.toml").write_text(
                "[model]\ncentre_of_mass_m = [0.5, 0.5, 0.25]\n[materials.w]\nreflectivity = 0.5\n"
                'specular_fraction = 0\n[parts]\n"*" = "w"\n'
            ),
        ),
        ["drag", "m.obj", "-m", "m.toml", "--velocity", "7500", "0", "0", *FREE_STREAM],
        0,
        ["centre of mass", "+0.250000"],
    ),
    "ref-point-centre-of-mass-bad": (
        lambda d: (
            (d / "m.obj").write_text(obj_text({"box": CUBE_QUADS})),
            (d / "m.toml").write_text(f'[model]\ncentre_of_mass_m = [0.5, "x"]\n{WHITE}'),
        ),
        ["srp", "m.obj", "-m", "m.toml", "--sun", "1", "0", "0"],
        1,
        ["error", "m.toml", "centre_of_mass_m", "3 numbers"],
    ),
    # issue 20 item 4: articulated parts
    "articulation-unknown-key": (
        winged("", "angle_deg = 30\nspeed = 2"),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", "m.toml", "[articulation] \"wing\" has unknown key 'speed'", "origin_m"],
    ),
    "articulation-axis-zero": (
        winged("", axis="[0, 0, 0]"),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", "m.toml", "axis = [0, 0, 0] is not a direction", "axis = [0, 1, 0]"],
    ),
    "articulation-schedule-backwards": (
        winged("", "schedule = [[0, 0], [600, 10], [300, 20]]"),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", "m.toml", "schedule times do not increase (t = 300 s after t = 600 s)", "time order"],
    ),
    "articulation-two-laws": (
        winged("", 'angle_deg = 3\ntrack = "sun"'),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", "m.toml", "has angle_deg and track", "exactly one of"],
    ),
    "articulation-glob-unmatched": (
        winged(
            HINGE.format(law="angle_deg = 1", axis="[0, 1, 0]").replace(
                "articulation.wing", "articulation.wnig"
            )
        ),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", "m.toml", '"wnig" matches no part of m.obj', "the parts are: box, wing"],
    ),
    "articulation-part-twice": (
        winged(
            HINGE.format(law="angle_deg = 1", axis="[0, 1, 0]").replace(
                "articulation.wing", 'articulation."w*"'
            )
        ),
        ["drag", "m.obj", "-m", "m.toml", "--velocity", "7500", "0", "0", *FREE_STREAM],
        1,
        ["error", "m.toml", "part 'wing' is turned by two hinges", '"wing" and "w*"', "different parts"],
    ),
    "articulation-track-closed-body": (
        lambda d: (
            (d / "m.obj").write_text(WINGED),
            (d / "m.toml").write_text(
                WINGED_PARTS
                + HINGE.format(law='track = "sun"', axis="[0, 1, 0]").replace(
                    "articulation.wing", "articulation.box"
                )
            ),
        ),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        [
            "error",
            "m.toml",
            '"box" tracks the Sun, but the parts it turns have no front',
            "front = [x, y, z]",
        ],
    ),
    "articulation-track-drag": (
        winged("", 'track = "sun"'),
        ["drag", "m.obj", "-m", "m.toml", "--velocity", "7500", "0", "0", *FREE_STREAM],
        1,
        ["error", '"wing" tracks the Sun: sunwind drag has no Sun direction', '--articulate "wing=DEG"'],
    ),
    "articulation-track-drag-sweep": (
        winged("", 'track = "sun"'),
        [
            "sweep",
            "m.obj",
            "-m",
            "m.toml",
            "--drag",
            "--speed",
            "7500",
            *FREE_STREAM,
            "--step",
            "90",
            "-o",
            "t.nc",
        ],
        1,
        ["error", '"wing" tracks the Sun: a drag table has no Sun', '--articulate "wing=DEG"', "SRP alone"],
    ),
    "articulation-schedule-sweep": (
        winged("", "schedule = [[0, 0], [60, 9]]"),
        ["sweep", "m.obj", "-m", "m.toml", "--srp", "--step", "90", "-o", "t.nc"],
        1,
        ["error", '"wing" follows a schedule: a table has no time', "sunwind orbit"],
    ),
    "articulation-schedule-srp": (
        winged("", "schedule = [[0, 0], [60, 9]]"),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X],
        1,
        ["error", '"wing" follows a schedule: sunwind srp has no time', "sunwind orbit"],
    ),
    "articulate-flag-malformed": (
        winged(""),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X, "--articulate", "wing:30"],
        1,
        ["error", "--articulate 'wing:30' is not GLOB=DEG", 'e.g. --articulate "wing_*=30"'],
    ),
    "articulate-flag-not-finite": (
        winged(""),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X, "--articulate", "wing=nan"],
        1,
        ["error", '--articulate "wing" angle nan must be a finite number'],
    ),
    "articulate-flag-undeclared": (
        winged(""),
        ["srp", "m.obj", "-m", "m.toml", *SUN_X, "--articulate", "box=30"],
        1,
        ["error", 'm.toml: --articulate "box" names no hinge', '[articulation."box"] with axis, origin_m'],
    ),
    "articulate-flag-held": (
        winged("", 'track = "sun"'),
        [
            "drag",
            "m.obj",
            "-m",
            "m.toml",
            "--velocity",
            "7500",
            "0",
            "0",
            *FREE_STREAM,
            "--articulate",
            "wing=-15",
        ],
        0,
        ["articulation     wing -15.000 deg (fixed)"],
    ),
}


@pytest.mark.parametrize("name", CASES)
def test_hostile_model_input(name, run_cli, tmp_path, monkeypatch):
    build, args, code, words = CASES[name]
    monkeypatch.chdir(tmp_path)
    build(Path("."))
    got, out, err = run_cli(*args)
    text = out + err
    assert "Traceback" not in text
    assert got == code, text
    for word in words:
        assert word in text, (word, text)
