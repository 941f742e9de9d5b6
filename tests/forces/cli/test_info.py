"""``sunwind info``: the survey of what a CAD export did, in JSON and as one text line per finding, also
for a mesh that fails the loading checks."""

import json

import pytest

#: A unit cube ``bus`` written as a CAD export does: each side with its own four vertices. Then an
#: open square ``panel`` (not declared a sheet, so the loading checks fail) at z = 0.5 through the
#: cube, 3 m across: it crosses the cube's four walls along 4 m.
SEAMED = """o bus
v 0 0 0
v 0 1 0
v 1 1 0
v 1 0 0
f 1 2 3 4
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 5 6 7 8
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
f 9 10 11 12
v 1 0 0
v 1 1 0
v 1 1 1
v 1 0 1
f 13 14 15 16
v 1 1 0
v 0 1 0
v 0 1 1
v 1 1 1
f 17 18 19 20
v 0 1 0
v 0 0 0
v 0 0 1
v 0 1 1
f 21 22 23 24
o panel
v -1 -1 0.5
v 2 -1 0.5
v 2 2 0.5
v -1 2 0.5
f 25 26 27 28
"""

UNIFORM = ["--reflectivity", "0.3", "--specular-fraction", "0.5"]


@pytest.fixture
def seamed(tmp_path):
    path = tmp_path / "seamed.obj"
    path.write_text(SEAMED)
    return path


def test_info_json_has_the_survey_of_a_mesh_that_fails_the_checks(run_cli, seamed):
    code, out, _ = run_cli("info", seamed, "--no-k-is", "--json", *UNIFORM)
    assert code == 0
    report = json.loads(out)
    assert "part 'panel' is open (4 boundary edges): declare it a sheet to use it" in report["checks"]
    survey = report["survey"]
    assert survey["facets"] == 14 and survey["corners"] == 12
    assert survey["open_edges"] == {"count": 4, "length_m": pytest.approx(12.0), "parts": {"panel": 4}}
    assert survey["seams"] == {"count": 12, "length_m": pytest.approx(12.0), "parts": {"bus": 12}}
    assert survey["seams_unmerged"] == 0
    assert survey["mixed_winding"]["count"] == 0 and survey["nonmanifold_edges"]["count"] == 0
    assert len(survey["crossings"]) == 1
    crossing = survey["crossings"][0]
    assert crossing["parts"] == ["bus", "panel"] and crossing["length_m"] == pytest.approx(4.0)
    assert survey["shells"] == {"bus": 1, "panel": 1}
    assert survey["coincident"]["facets"] == 0 and survey["layered"]["facets"] == 0
    assert set(survey["slivers"]) >= {"count", "degenerate", "area_min_m2", "area_max_m2", "probe_spacing_m"}


def test_info_prints_one_survey_line_per_finding_with_what_the_methods_do(run_cli, seamed):
    code, out, _ = run_cli("info", seamed, "--no-k-is", *UNIFORM)
    assert code == 0
    printed = out.split("\n")
    start = next(
        k for k, line in enumerate(printed) if line.startswith("  survey of the mesh as read (14 facets")
    )
    block = printed[start + 1 : printed.index("  parts:")]
    lines = {line.split()[0]: line for line in block}
    assert len(block) == len(lines) == 9
    assert "4 edges, 12 m (panel 4)" in lines["open"] and "as silhouette edges" in lines["open"]
    assert "12 edges, 12 m (bus 12)" in lines["seams"] and "by position" in lines["seams"]
    assert "bus x panel 4 m (" in lines["crossings"]
    assert "outline segments of the shadow pass" in lines["crossings"]
    assert "position and fold, not winding" in lines["mixed"]
    assert "the upper layer shades the lower" in lines["duplicates"]
    assert "10th percentile of facet widths" in lines["slivers"]
    assert "every part one piece" in lines["shells"]
    assert set(lines) == {
        *("open", "non-manifold", "mixed", "seams", "gaps", "crossings", "duplicates", "slivers", "shells")
    }
