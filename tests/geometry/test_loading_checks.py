"""Model loading (issue 17): every problem of a load in one error, cracks closed, parts judged alone,
TOML keys quoted in hints, globs that select nothing, the centre of mass, a size that suggests a unit."""

from __future__ import annotations

import numpy as np
import pytest

from helpers import ABSORBER
from sunwind.forces.model import Model, load
from sunwind.geometry.checks import CRACK_TOLERANCE
from sunwind.geometry.errors import InputError, MaterialError, MeshError, combine
from sunwind.geometry.materials import load_materials, parse_materials, toml_key
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import CENTRE_OF_MASS, build_spacecraft
from sunwind.geometry.summary import describe

CUBE = np.array(
    [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], float
)
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def mesh(points, parts: dict[str, list[tuple[int, ...]]]) -> MeshData:
    """Quads (and triangles) per part, fan-split into triangles."""
    faces, part = [], []
    for index, polygons in enumerate(parts.values()):
        for polygon in polygons:
            faces += [(polygon[0], polygon[k], polygon[k + 1]) for k in range(1, len(polygon) - 1)]
            part += [index] * (len(polygon) - 2)
    n = len(faces)
    return MeshData(
        np.asarray(points, float),
        np.array(faces),
        np.array(part, np.int32),
        tuple(parts),
        -np.ones(n, np.int32),
    )


def test_combine_lists_problems_one_line_each_then_distinct_fixes():
    a = MeshError("is open", path="m.obj", part="a", hint="close it")
    b = MaterialError("has no material", path="m.obj", part="b", hint="add one")
    c = MaterialError("unit bad", path="t.toml", hint="add one", parameters=("unit",))
    both = combine([a, b])
    assert isinstance(both, MeshError) and [p.part for p in both.problems] == ["a", "b"]
    assert (
        str(both) == "m.obj: 2 problems:\n  part 'a' is open\n  part 'b' has no material\n"
        "  fix: close it\n  fix: add one"
    )
    three = combine([both, c])  # flattened; the files differ, so each line names its own
    assert len(three.problems) == 3 and three.path is None
    assert str(three).splitlines()[3] == "  t.toml: unit bad" and str(three).count("fix: add one") == 1
    assert "--unit" in str(three.renamed({"unit": "--unit"}))
    assert combine([a]) is a
    assert str(combine([a], hint="one fix")) == "m.obj: part 'a' is open; one fix"


def test_t_junctions_of_a_closed_box_are_closed_with_a_notice():
    # the top split in two along x = 0.5; front and back faces keep one top edge: two T-junctions
    points = np.vstack([CUBE, [(0.5, 0, 1), (0.5, 1, 1)]])
    faces = [q for q in QUADS if q != (4, 5, 6, 7)] + [(4, 8, 9, 7), (8, 5, 6, 9)]
    craft = build_spacecraft(mesh(points, {"box": faces}), uniform=ABSORBER)
    assert craft.is_closed and craft.volume == pytest.approx(1.0)
    assert craft.n_facets == 16 and craft.total_area == pytest.approx(6.0)
    (notice,) = [n for n in craft.notices if "crack" in n]
    assert "split 2 triangles at T-junctions" in notice and "closing 4 m of open edges" in notice


def test_several_t_junctions_on_one_edge_and_a_random_soup_stays_open():
    # the top cut in three strips: two vertices on each of the front and back faces' top edges
    strips = [
        (0, 0, 1),
        (1 / 3, 0, 1),
        (2 / 3, 0, 1),
        (1, 0, 1),
        (1, 1, 1),
        (2 / 3, 1, 1),
        (1 / 3, 1, 1),
        (0, 1, 1),
    ]
    points = np.vstack([CUBE[:4], strips])  # 4..11 around the top
    sides = [(0, 3, 2, 1), (0, 1, 7, 4), (1, 2, 8, 7), (2, 3, 11, 8), (3, 0, 4, 11)]
    top = [(4, 5, 10, 11), (5, 6, 9, 10), (6, 7, 8, 9)]
    craft = build_spacecraft(mesh(points, {"box": sides + top}), uniform=ABSORBER)
    assert craft.is_closed and craft.volume == pytest.approx(1.0)
    assert any("split 4 triangles" in n for n in craft.notices)
    rng = np.random.default_rng(1)
    soup = MeshData(
        rng.random((3000, 3)),
        np.arange(3000).reshape(-1, 3),
        np.zeros(1000, np.int32),
        ("soup",),
        -np.ones(1000, np.int32),
    )
    with pytest.raises(MeshError, match="3000 boundary edges"):
        build_spacecraft(soup, uniform=ABSORBER)


def test_a_hair_line_gap_is_welded_and_a_wide_one_is_open():
    def box(gap: float) -> MeshData:
        # the top face's own copy of corner 6, off by ``gap``: a crack along two edges
        points = np.vstack([CUBE, [(1 + gap, 1, 1)]])
        faces = [q for q in QUADS if q != (4, 5, 6, 7)] + [(4, 5, 8, 7)]
        return mesh(points, {"box": faces})

    craft = build_spacecraft(box(0.1 * CRACK_TOLERANCE), uniform=ABSORBER)
    assert craft.is_closed and any("welded 1 vertices" in n for n in craft.notices)
    with pytest.raises(MeshError, match="part 'box' is an open surface"):
        build_spacecraft(box(10 * CRACK_TOLERANCE), uniform=ABSORBER)


def test_each_part_is_judged_closed_on_its_own(tmp_path):
    # lid + tub make a closed cube, but neither is closed alone: one body of two parts, said so
    split = mesh(CUBE, {"lid": QUADS[:1], "tub": QUADS[1:]})
    craft = build_spacecraft(split, uniform=ABSORBER)
    assert craft.is_closed and craft.volume == pytest.approx(1.0)
    lines = "".join(f"v {x:g} {y:g} {z:g}\n" for x, y, z in CUBE)
    for name, quads in (("lid", QUADS[:1]), ("tub", QUADS[1:])):
        lines += f"g {name}\n" + "".join(f"f {a + 1} {b + 1} {c + 1} {d + 1}\n" for a, b, c, d in quads)
    (tmp_path / "split.obj").write_text(lines)
    report = describe(tmp_path / "split.obj", uniform=ABSORBER)
    assert {p["name"]: p["surface"] for p in report["parts"]} == {
        "lid": "part of a body",
        "tub": "part of a body",
    }
    assert (
        "part 'lid' is open on its own (4 boundary edges): a closed body only together with 'tub'"
        in report["checks"]
    )
    # a part open on its own and not closed by another is open
    with pytest.raises(MeshError, match="part 'tub' is an open surface"):
        build_spacecraft(mesh(CUBE, {"tub": QUADS[1:]}), uniform=ABSORBER)


def test_all_missing_materials_and_open_parts_in_one_error():
    parts = {f"p{k}": QUADS for k in range(3)} | {"open": QUADS[:5]}
    data = mesh(np.vstack([CUBE + 2 * k for k in range(4)]), {})
    faces = [
        np.array(mesh(CUBE, {name: quads}).faces) + 8 * k for k, (name, quads) in enumerate(parts.items())
    ]
    part = np.concatenate([np.full(len(f), k, np.int32) for k, f in enumerate(faces)])
    data = MeshData(
        data.vertices, np.concatenate(faces), part, tuple(parts), np.minimum(part, 2), ("a.1", "b", "c")
    )
    with pytest.raises(MaterialError) as error:
        build_spacecraft(data)
    text = str(error.value)
    assert text.startswith("<memory>: 5 problems:") and "part 'open' is an open surface" in text
    assert '[materials."a.1"], [materials.b], [materials.c]' in text  # one fix, keys quoted as TOML needs


def test_materials_file_problems_are_all_reported():
    document = {
        "materials": {"x": {"reflectivity": 2, "specular_fraction": 0}, "y": {"shine": 1}},
        "parts": {"a": "z", "b": {"front": "q.1"}},
    }
    with pytest.raises(MaterialError) as error:
        parse_materials(document, "m.toml")
    assert len(error.value.problems) == 4 and '[materials."q.1"]' in str(error.value)


@pytest.mark.parametrize(
    ("key", "written"),
    [
        ("white_paint", "white_paint"),
        ("foil_silver.014", '"foil_silver.014"'),
        ("MLI gold", '"MLI gold"'),
        ('a"b', '"a\\"b"'),
        ("Kapton-1", "Kapton-1"),
    ],
)
def test_toml_key_quotes_what_is_not_a_bare_key(key, written):
    import tomllib

    assert toml_key(key) == written
    assert list(tomllib.loads(f"[materials.{toml_key(key)}]\nx = 1\n")["materials"]) == [key]


@pytest.mark.parametrize(
    "text",
    [
        "a = " + "[" * 5000 + "]" * 5000,
        "a = " + "{ b = " * 5000 + "1" + " }" * 5000,
        ".".join(["a"] * 5000) + " = 1",
    ],
)
def test_deeply_nested_toml_is_one_error(tmp_path, text):
    (tmp_path / "deep.toml").write_text(text + "\n")
    with pytest.raises(MaterialError, match=r"deep\.toml"):
        load_materials(tmp_path / "deep.toml")


def test_a_two_sided_glob_that_matches_no_part_is_refused_and_a_parts_rule_warns():
    box = mesh(CUBE, {"box": QUADS})
    with pytest.raises(InputError, match="two_sided glob 'wing' matches no part; the parts are: box"):
        build_spacecraft(box, uniform=ABSORBER, two_sided=["wing"])
    spec = parse_materials(
        {"materials": {"w": {"reflectivity": 0, "specular_fraction": 0}}, "parts": {"bxo": "w"}}
    )
    with pytest.warns(UserWarning, match='"bxo" matches no part'):
        build_spacecraft(box, spec, uniform=ABSORBER)


def test_centre_of_mass_of_the_materials_file_is_the_reference_point(tmp_path):
    (tmp_path / "box.obj").write_text(
        "".join(f"v {x:g} {y:g} {z:g}\n" for x, y, z in CUBE)
        + "".join(f"f {a + 1} {b + 1} {c + 1} {d + 1}\n" for a, b, c, d in QUADS)
    )
    (tmp_path / "m.toml").write_text(
        "[model]\ncentre_of_mass_m = [0.5, 0.5, 0.2]\n"
        '[materials.w]\nreflectivity = 0\nspecular_fraction = 0\n[parts]\n"*" = "w"\n'
    )
    model = load(tmp_path / "box.obj", tmp_path / "m.toml")
    point, name = model.reference()
    assert name == CENTRE_OF_MASS and np.allclose(point, [0.5, 0.5, 0.2])
    assert model.reference([0, 0, 0])[1] == "user"
    assert Model(model.craft, reference_point_m=(1, 1, 1)).reference()[1] == "user"
    plain = load(tmp_path / "box.obj", uniform=ABSORBER)
    assert plain.reference()[1] == "volume centroid (default)"
    for bad in ("[1, 2]", "[1, 2, nan]", '"centre"', "[1, 2, true]"):
        (tmp_path / "bad.toml").write_text(f"[model]\ncentre_of_mass_m = {bad}\n")
        with pytest.raises(MaterialError, match=r"centre_of_mass_m .* is not 3 numbers"):
            load_materials(tmp_path / "bad.toml")


@pytest.mark.parametrize(
    ("scale", "suggested"),
    [(1.0, None), (100.0, None), (0.03, None), (1000.0, "mm"), (340.0, "mm"), (0.005, "another unit")],
)
def test_a_size_that_suggests_another_unit_gives_a_notice_naming_it(scale, suggested):
    """Sizes of real spacecraft: the ISS is 109 m across, chip satellites 3.5 cm; a 340 mm CubeSat read
    as metres is 340 m. The unit suggested gives a typical size (5 cm to 30 m); read in metres, a 5 mm
    model is in no larger unit of a mesh file, so none is named."""
    craft = build_spacecraft(mesh(CUBE * scale, {"box": QUADS}), uniform=ABSORBER)
    notices = [n for n in craft.notices if "--unit" in n]
    assert bool(notices) == (suggested is not None)
    if suggested:
        assert f"{scale:g} m across" in notices[0] and "(Python: unit=" in notices[0]
        named = (
            f"in {suggested}, give --unit {suggested}"
            if suggested != "another unit"
            else "another unit, give it"
        )
        assert named in notices[0]


def test_the_unit_suggested_is_never_the_one_the_model_was_read_in():
    from sunwind.geometry.checks import size_notice

    corners = np.array([[0.0, 0, 0], [0.34, 0.1, 0.34]])
    assert "give --unit m " in size_notice(corners * 1e-3, "mm (--unit)")  # a metre file read as mm
    assert "--unit mm" not in size_notice(corners * 1e-3, "mm (--unit)")
