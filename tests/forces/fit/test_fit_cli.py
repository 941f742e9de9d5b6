"""``sunwind fit`` on the command line: a fit to a telemetry file, its JSON, fitted materials and plot;
bad telemetry refused in one line naming the file, the line and the column."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sunwind.geometry.io import save_mesh
from sunwind.geometry.materials import load_materials
from sunwind.meshes import box_wing

FREE = ("--free", "cells.reflectivity", "--free", "paint.reflectivity")


@pytest.fixture(scope="module")
def files(tmp_path_factory, twin_module):
    """The box-wing's mesh and materials files, and a torque telemetry of other coefficients."""
    folder = tmp_path_factory.mktemp("fit")
    mesh, materials = folder / "box_wing.obj", folder / "box_wing.toml"
    save_mesh(box_wing(facet_size=0.25), mesh)
    materials.write_text(twin_module.MATERIALS.replace("[materials.paint]", "# the bus\n[materials.paint]"))
    model = twin_module.box_wing_model()
    suns = twin_module.sphere(40, seed=3)
    rng = np.random.default_rng(1)
    truth = {"cells.reflectivity": 0.2, "paint.reflectivity": 0.6}
    telemetry, _ = twin_module.simulate(model, truth, suns, {"torque": 1e-8}, rng)
    data = folder / "telemetry.csv"
    write_csv(
        data,
        {
            "time_s": telemetry.time_s,
            **{f"sun_{a}": suns[:, k] for k, a in enumerate("xyz")},
            **{f"torque_{a}": telemetry.measured["torque"][:, k] for k, a in enumerate("xyz")},
        },
    )
    return folder, mesh, materials, data


@pytest.fixture(scope="module")
def twin_module():
    import importlib.util
    from pathlib import Path

    spec = importlib.util.spec_from_file_location("fit_conftest", Path(__file__).with_name("conftest.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write_csv(path, columns: dict, comment: str = "") -> None:
    names = list(columns)
    rows = zip(*[np.asarray(columns[n], dtype=object) for n in names], strict=True)
    lines = [comment] if comment else []
    lines += [",".join(names), *[",".join(str(v) for v in row) for row in rows]]
    path.write_text("\n".join(lines) + "\n")


def args(files, data=None, *more):
    _, mesh, materials, default = files
    centre = ("--ref-point", "0.15", "0.1", "-0.2")
    return [
        "fit",
        mesh,
        "-m",
        materials,
        "--data",
        data or default,
        *FREE,
        *centre,
        "--reflections",
        "none",
        *more,
    ]


def test_a_fit_prints_its_estimates_and_writes_materials_and_plot(run_cli, files):
    folder = files[0]
    fitted, picture = folder / "fitted.toml", folder / "fit.png"
    code, out, err = run_cli(
        *args(files, None, "--sigma-torque", "1e-8", "--write-materials", fitted, "--plot", picture)
    )
    assert code == 0, err
    assert "cells.reflectivity" in out and "chi2/dof" in out and "singular values" in out
    spec = load_materials(fitted)
    values = {m.name: m.reflectivity for m in spec.materials.values()}
    assert abs(values["cells"] - 0.2) < 0.01 and abs(values["paint"] - 0.6) < 0.01
    text = fitted.read_text()
    assert "# the bus" in text and "fitted by sunwind fit" in text
    assert picture.stat().st_size > 10_000


def test_the_json_has_the_issues_keys(run_cli, files):
    code, out, err = run_cli(*args(files, None, "--json"))
    assert code == 0, err
    document = json.loads(out)
    for key in ("estimates", "correlation", "singular_values", "residual_rms_before", "residual_rms_after"):
        assert key in document
    assert set(document["estimates"]["cells.reflectivity"]) >= {"value", "sigma"}
    assert document["chi2_dof"] > 0 and isinstance(document["warnings"], list)
    assert "sunwind: notice: no sigma of the torque given" in err


GOOD = {"time_s": [0, 10, 20], "sun_x": [1, 1, 1], "sun_y": [0, 0.1, 0.2], "sun_z": [0, 0, 0]}
TORQUE = {"torque_x": [0, 0, 0], "torque_y": [0, 0, 0], "torque_z": [1e-7, 1e-7, 1e-7]}


@pytest.mark.parametrize(
    ("columns", "extra", "expected"),
    [
        (
            {**GOOD, "time_s": [0, 20, 10], **TORQUE},
            (),
            "line 5: time_s 10 comes before the previous row's 20",
        ),
        ({**GOOD, "time_s": [0, 10, 10], **TORQUE}, (), "line 5: time_s 10 repeats the previous row's 10"),
        (
            {**GOOD, "sun_z": [0, "nan", 0], **TORQUE},
            (),
            "line 4: column sun_z is 'nan', not a finite number",
        ),
        ({**GOOD, "sun_z": [0, "", 0], **TORQUE}, (), "line 4: column sun_z is 'empty'"),
        ({k: v for k, v in GOOD.items() if k != "sun_z"} | TORQUE, (), "column sun_z missing"),
        ({k: v for k, v in GOOD.items() if k != "time_s"} | TORQUE, (), "no column time_s"),
        (GOOD, (), "no measurement columns"),
        (
            {**GOOD, "accel_x": [0] * 3, "accel_y": [0] * 3, "accel_z": [0] * 3},
            (),
            "need the spacecraft mass",
        ),
        (
            {
                "time_s": [0, 10, 20],
                "qw": [1, 1, 1.00001],
                "qx": [0] * 3,
                "qy": [0] * 3,
                "qz": [0] * 3,
                **TORQUE,
            },
            ("--epoch", "2024-03-20T00:00:00Z"),
            "line 5: qw, qx, qy, qz is not a unit quaternion (|q| = 1.00001, more than 1e-06 from 1)",
        ),
        (
            {"time_s": [0, 10, 20], "qw": [1] * 3, "qx": [0] * 3, "qy": [0] * 3, "qz": [0] * 3, **TORQUE},
            (),
            "needs the epoch of time_s = 0",
        ),
        ({**GOOD, **TORQUE, "hinge:mast": [0, 1, 2]}, (), "column hinge:mast names no hinge of the model"),
        ({**GOOD, **TORQUE}, ("--free", "wing.reflectivity"), "the model has no material 'wing'"),
        ({**GOOD, **TORQUE}, ("--free", "cells.albedo"), "unknown coefficient 'albedo'"),
    ],
    ids=[
        "unsorted",
        "repeated",
        "nan",
        "empty",
        "partial-sun",
        "no-time",
        "no-measurement",
        "accel-without-mass",
        "non-unit-quaternion",
        "quaternion-without-epoch",
        "unknown-hinge",
        "unknown-material",
        "unknown-coefficient",
    ],
)
def test_bad_telemetry_gets_one_line(run_cli, files, tmp_path, columns, extra, expected):
    data = tmp_path / "bad.csv"
    write_csv(data, columns, comment="# a comment line, skipped: the header is line 2")
    code, out, err = run_cli(*args(files, data, *extra))
    assert code == 1 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("sunwind: error: "), err
    assert expected in lines[0], lines[0]
    if "--free" not in extra:
        assert str(data) in lines[0]
    assert "Traceback" not in err


def test_a_missing_file_is_one_line(run_cli, files, tmp_path):
    code, _, err = run_cli(*args(files, tmp_path / "none.csv"))
    assert (
        code == 1
        and err.strip()
        == f"sunwind: error: {tmp_path / 'none.csv'}: file not found; check the path and its spelling"
    )


def test_an_output_over_an_input_or_a_plot_not_a_picture_is_one_line_before_any_work(run_cli, files):
    """--write-materials over the materials file it was read from (or the telemetry), --plot that is no
    picture: refused before the model is loaded, and the input is left as it was."""
    _, _, materials, data = files
    before = materials.read_text()
    for more, expected in (
        (("--write-materials", materials), "the output is also another file of this run"),
        (("--write-materials", data), "the output is also another file of this run"),
        (("--plot", data), "a plot is written as a picture"),
    ):
        code, out, err = run_cli(*args(files, None, *more))
        assert code == 1 and err.count("\n") == 1 and expected in err and out == "", err
    assert materials.read_text() == before


def test_a_combination_the_data_cannot_separate_is_a_warning_and_a_null_sigma(run_cli, tmp_path):
    from sunwind.meshes import plate

    mesh = tmp_path / "plate.obj"
    save_mesh(plate(1.0, 1.0, 2), mesh)
    n = 10
    rng = np.random.default_rng(2)
    accel = -9.1e-9 + rng.normal(scale=1e-11, size=n)  # face-on: along -z only
    data = tmp_path / "face_on.csv"
    columns = {"time_s": 10.0 * np.arange(n), "sun_x": [0] * n, "sun_y": [0] * n, "sun_z": [1] * n}
    write_csv(data, columns | {"accel_x": [0.0] * n, "accel_y": [0.0] * n, "accel_z": accel})
    code, out, err = run_cli(
        "fit", mesh, "--reflectivity", "0.5", "--specular-fraction", "0.5", "--two-sided", "*",
        "--data", data, "--free", "uniform.reflectivity", "--free", "uniform.specular_fraction",
        "--mass", "1000", "--reflections", "none", "--json",
    )  # fmt: skip
    assert code == 0, err
    document = json.loads(out)
    assert document["estimates"]["uniform.reflectivity"]["sigma"] is None
    warning = [
        line for line in err.splitlines() if line.startswith("sunwind: warning: the data cannot separate")
    ]
    assert warning and "uniform.reflectivity and uniform.specular_fraction" in warning[0]


def test_momentum_with_quaternions_and_an_epoch(run_cli, files, twin_module, tmp_path):
    """A slowly turning attitude given by quaternions: the Sun from the ephemeris, the momentum in
    the inertial frame, its start fitted."""
    from scipy.integrate import cumulative_trapezoid

    from sunwind.forces import srp
    from sunwind.forces.fit import read_telemetry
    from sunwind.forces.fit.forward import with_optics
    from sunwind.forces.orbit.attitude import quaternion_matrix

    model = twin_module.box_wing_model()
    n = 60
    time = 600.0 * np.arange(n)
    angle = np.linspace(0.0, 1.5, n)  # a slow turn about z
    q = np.stack([np.cos(angle / 2), 0 * angle, 0 * angle, np.sin(angle / 2)], 1)
    data = tmp_path / "q.csv"
    columns = {"time_s": time, "qw": q[:, 0], "qx": q[:, 1], "qy": q[:, 2], "qz": q[:, 3]}
    write_csv(data, columns | {f"momentum_{a}": np.zeros(n) for a in "xyz"})  # for the Sun of each row
    telemetry = read_telemetry(data, "2024-03-20T00:00:00Z")
    truth = twin_module.optics_with(model, {"cells.reflectivity": 0.2, "paint.reflectivity": 0.6})
    batch = srp(with_optics(model, truth), telemetry.sun_body, flux_W_m2=1361.0, reflections="none")
    torque = batch.torque_Nm * (telemetry.flux_W_m2 / 1361.0)[:, None]
    h = cumulative_trapezoid(np.einsum("nij,nj->ni", quaternion_matrix(q), torque), time, axis=0, initial=0.0)
    h += np.random.default_rng(3).normal(scale=1e-6, size=h.shape) + 0.1
    write_csv(data, columns | {f"momentum_{a}": h[:, k] for k, a in enumerate("xyz")})
    code, out, err = run_cli(
        *args(files, data, "--epoch", "2024-03-20T00:00:00Z", "--sigma-momentum", "1e-6", "--json")
    )
    assert code == 0, err
    estimates = json.loads(out)["estimates"]
    for name, value in (("cells.reflectivity", 0.2), ("paint.reflectivity", 0.6)):
        assert abs(estimates[name]["value"] - value) < 3 * estimates[name]["sigma"]
    assert (
        abs(estimates["initial_momentum_Nms.x"]["value"] - 0.1)
        < 3 * estimates["initial_momentum_Nms.x"]["sigma"]
    )
