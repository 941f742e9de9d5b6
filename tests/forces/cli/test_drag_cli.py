"""``sunwind drag`` and ``sunwind forces``: output contracts and one-line errors for every bad input."""

import json

import numpy as np
import pytest

from sunwind.forces.gas import nrlmsis

SPHERE_ARGS = ["--gsi", "sentman", "--wall-temperature", "300"]
EXPLICIT_AIR = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]


@pytest.fixture(scope="module")
def sphere_mesh(tmp_path_factory):
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import sphere

    path = tmp_path_factory.mktemp("drag") / "sphere.obj"
    save_mesh(sphere(1.0, 24), path)
    return path


def test_drag_json_has_the_documented_keys(run_cli, sphere_mesh):
    code, out, err = run_cli(
        "drag", sphere_mesh, "--velocity", "7600", "0", "0", *EXPLICIT_AIR, *SPHERE_ARGS, "--json"
    )
    assert code == 0, err
    payload = json.loads(out)
    for key in (
        "force_N",
        "torque_Nm",
        "density_kg_m3",
        "temperature_K",
        "speed_m_s",
        "dynamic_pressure_Pa",
        "speed_ratio",
        "CD",
        "CL",
        "CS",
        "CM",
        "reference_area_m2",
        "reference_length_m",
        "reference_point_m",
        "validity",
    ):
        assert key in payload, key
    assert payload["density_kg_m3"] == pytest.approx(3e-12, rel=1e-12)
    assert payload["force_N"][0] < 0  # drag opposes v_rel
    assert 2.0 < payload["CD"] < 3.0  # a sphere in orbit


def test_drag_from_nrlmsis_uses_the_circular_orbit_speed_and_passes_the_atmosphere_through(
    run_cli, sphere_mesh
):
    code, out, err = run_cli(
        "drag", sphere_mesh, "--flow-azel", "-90", "0", "--altitude", "400", *SPHERE_ARGS, "--json"
    )
    assert code == 0, err
    payload = json.loads(out)
    air = nrlmsis(400.0)
    assert payload["density_kg_m3"] == air.density_kg_m3
    assert payload["atmosphere"]["number_density_m3"] == air.number_density_m3
    assert payload["speed_m_s"] == pytest.approx(7668.56, abs=0.05)
    assert payload["force_N"][1] > 0  # v_rel along -y: drag along +y


def test_forces_json_gives_srp_drag_and_their_total(run_cli, sphere_mesh):
    code, out, err = run_cli(
        "forces",
        sphere_mesh,
        "--sun",
        "0",
        "1",
        "0",
        "--velocity",
        "7600",
        "0",
        "0",
        *EXPLICIT_AIR,
        "--reflectivity",
        "0.3",
        "--specular-fraction",
        "0.5",
        "--json",
    )
    assert code == 0, err
    payload = json.loads(out)
    total = np.add(payload["srp"]["force_N"], payload["drag"]["force_N"])
    assert np.allclose(payload["total"]["force_N"], total, rtol=1e-15)
    assert payload["srp"]["force_N"][1] < 0 and payload["drag"]["force_N"][0] < 0


def test_text_output_states_normalisation_and_validity(run_cli, sphere_mesh):
    code, out, err = run_cli("drag", sphere_mesh, "--velocity", "7600", "0", "0", *EXPLICIT_AIR, *SPHERE_ARGS)
    assert code == 0, err
    assert "C = F/(q A_ref)" in out and "free-molecular" in out and "body frame" in out


def test_gas_flags_override_the_materials_file(run_cli, sphere_mesh, tmp_path):
    materials = tmp_path / "m.toml"
    materials.write_text(
        '[materials.al]\nreflectivity = 0.8\nspecular_fraction = 0.9\ngsi = "specular"\n[parts]\n"*" = "al"\n'
    )
    base = ["drag", sphere_mesh, "--velocity", "7600", "0", "0", *EXPLICIT_AIR, "-m", materials, "--json"]
    specular = json.loads(run_cli(*base)[1])["CD"]
    diffuse = json.loads(run_cli(*base, "--gsi", "sentman")[1])["CD"]
    assert specular != pytest.approx(diffuse, rel=1e-3)


def bad_drag_inputs(tmp_path, mesh):
    """(arguments, words the one-line error must contain)."""
    velocity = ["--velocity", "7600", "0", "0"]
    (tmp_path / "gsi.toml").write_text(
        '[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0\ngsi = "cook"\n'
    )
    (tmp_path / "acc.toml").write_text(
        "[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0\nenergy_accommodation = 1.2\n"
    )
    (tmp_path / "wall.toml").write_text(
        "[materials.a]\nreflectivity = 0.5\nspecular_fraction = 0\nwall_temperature = -3\n"
    )
    return [
        (["drag", mesh, *velocity, *EXPLICIT_AIR, "--gsi", "cook"], ["--gsi", "cook"]),
        (
            ["drag", mesh, *velocity, *EXPLICIT_AIR, "-m", tmp_path / "gsi.toml"],
            ["gsi.toml", "cook", "sentman"],
        ),
        (
            ["drag", mesh, *velocity, *EXPLICIT_AIR, "-m", tmp_path / "acc.toml"],
            ["acc.toml", "energy_accommodation"],
        ),
        (
            ["drag", mesh, *velocity, *EXPLICIT_AIR, "-m", tmp_path / "wall.toml"],
            ["wall.toml", "wall_temperature"],
        ),
        (["drag", mesh, *velocity, *EXPLICIT_AIR, "--tangential-accommodation", "-0.1"], ["tangential"]),
        (
            ["drag", mesh, *velocity, *EXPLICIT_AIR, *SPHERE_ARGS[:2], "--normal-accommodation", "2"],
            ["normal"],
        ),
        (
            [
                "drag",
                mesh,
                *velocity,
                "--density",
                "3e-12",
                "--temperature",
                "900",
                "--composition",
                "O:0.8,Xe:0.2",
            ],
            ["Xe", "N2"],
        ),
        (
            [
                "drag",
                mesh,
                *velocity,
                "--density",
                "3e-12",
                "--temperature",
                "900",
                "--composition",
                "O:0.7,N2:0.2",
            ],
            ["0.9", "--normalise-composition"],
        ),
        (
            ["drag", mesh, *velocity, "--density", "0", "--temperature", "900", "--composition", "O:1"],
            ["--density"],
        ),
        (
            ["drag", mesh, *velocity, "--density", "1e-12", "--temperature", "-5", "--composition", "O:1"],
            ["temperature"],
        ),
        (["drag", mesh, *velocity, "--density", "1e-12"], ["--temperature", "--composition"]),
        (["drag", mesh, *velocity, "--altitude", "3000", *SPHERE_ARGS], ["--altitude", "2000"]),
        (["drag", mesh, *velocity, "--altitude", "-10", *SPHERE_ARGS], ["--altitude"]),
        (
            ["drag", mesh, *velocity, "--altitude", "400", "--epoch", "1850-01-01", *SPHERE_ARGS],
            ["--epoch", "1958"],
        ),
        (["drag", mesh, *velocity, "--altitude", "400", "--epoch", "yesterday", *SPHERE_ARGS], ["--epoch"]),
        (["drag", mesh, "--velocity", "0", "0", "0", *EXPLICIT_AIR, *SPHERE_ARGS], ["velocity", "zero"]),
        (["drag", mesh, *EXPLICIT_AIR, *SPHERE_ARGS], ["--velocity", "--flow-azel"]),
        (["drag", mesh, "--flow-azel", "0", "0", *EXPLICIT_AIR, *SPHERE_ARGS], ["--speed"]),
        (["drag", mesh, *velocity, *SPHERE_ARGS], ["--altitude", "--density"]),
        (["drag", mesh, *velocity, "--corotating", *EXPLICIT_AIR, *SPHERE_ARGS], ["--corotating"]),
        (["drag", mesh, *velocity, *EXPLICIT_AIR, *SPHERE_ARGS, "--ref-area", "0"], ["--ref-area"]),
        (
            ["drag", mesh, *velocity, *EXPLICIT_AIR, *SPHERE_ARGS, "--reflections", "mirror"],
            ["--reflections"],
        ),
        (["forces", mesh, *velocity, *EXPLICIT_AIR, *SPHERE_ARGS], ["--sun"]),
    ]


def test_every_bad_drag_input_gives_one_line_and_a_non_zero_exit(run_cli, sphere_mesh, tmp_path):
    for args, words in bad_drag_inputs(tmp_path, sphere_mesh):
        code, out, err = run_cli(*args)
        line = err.strip()
        assert code != 0, (args, out)
        assert "\n" not in line and "Traceback" not in line, (args, err)
        assert line.startswith("sunwind"), (args, line)
        for word in words:
            assert word in line, (args, word, line)


def test_a_low_speed_ratio_on_a_concave_model_answers_without_a_warning(run_cli, tmp_path):
    """The open-sky integral holds at every speed ratio: nothing to warn of, the speed ratio reported."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box_wing

    concave = tmp_path / "box_wing.usda"
    save_mesh(box_wing(facet_size=0.5), concave)
    slow = ["--velocity", "1500", "0", "0", *EXPLICIT_AIR, *SPHERE_ARGS, "--json"]
    code, out, err = run_cli("drag", concave, *slow)
    assert code == 0 and "warning" not in err
    document = json.loads(out)
    assert document["speed_ratio"] < 3
    assert document["open_sky"]["rays_per_side"] >= 64 and 0 < document["core_half_angle_deg"] <= 17.2


def test_extrapolated_altitude_warns(run_cli, sphere_mesh):
    code, _, err = run_cli("drag", sphere_mesh, "--flow-azel", "0", "0", "--altitude", "1200", *SPHERE_ARGS)
    assert code == 0 and "sunwind: warning:" in err and "1000 km" in err
