"""The second hostile sweep of issue 33 (every command): an output that is an input, hints that name the
flag to give, messages a person can read, and unit slips of the reference point and sizes."""

import pytest

BOX = ["--reflectivity", "0.3", "--specular-fraction", "0.5", "--emissivity", "0.8"]
LEO = ["--altitude", "500", "--inclination", "51.6", "--epoch", "2025-03-20T00:00:00Z", "--srp"]
BELOW = ["--earth", "0", "0", "-1", "--altitude", "500", "--sun", "1", "0", "0"]
ELEMENTS = ["7000", "0.001", "51.6", "1e308", "0", "0"]  # a RAAN of 1e308 deg
GEO_EARTH = ["--earth-radiation", "--earth", "0", "0", "1", "--altitude", "35786"]


@pytest.fixture(scope="module")
def box(tmp_path_factory):
    """A 1 m box (12 triangles) and a file that is not a law of attitude but an attitude list."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box

    d = tmp_path_factory.mktemp("second-sweep")
    save_mesh(box(), d / "box.obj")
    (d / "q.csv").write_text("time_s,qw,qx,qy,qz\n0,1,0,0,0\n")
    return d


CASES = {
    "earth --sides over the mesh": (["earth", "{d}/box.obj", *BOX, *BELOW, "--sides", "{d}/box.obj"],
                                    "the output is also another file of this run"),
    "sweep with neither --srp nor a flow": (["sweep", "{d}/box.obj", *BOX, "-o", "{d}/t.nc"],
                                            "or tabulate SRP alone with --srp"),
    "orbit --attitude naming a file": (["orbit", "{d}/box.obj", *BOX, *LEO, "--attitude", "{d}/q.csv"],
                                       "give csv:{d}/q.csv"),
    "orbit of 1e308 s": (["orbit", "{d}/box.obj", *BOX, *LEO, "--duration", "1e308", "--step", "60"],
                         "years to"),
    "knocke on the Moon": (["earth", "{d}/box.obj", *BOX, *BELOW, "--planet", "moon", "--albedo-model",
                            "knocke", "--epoch", "2024-01-01", "--pole", "0", "1", "0"],
                           "not that of the Moon"),
    "subnormal reference area": (["drag", "{d}/box.obj", "--flow-azel", "0", "0", "--altitude", "400",
                                  "--ref-area", "1e-320"],
                                 "--ref-area 1e-320 must be a positive number from"),
    "an lvlh angle of 1e308": (["orbit", "{d}/box.obj", *BOX, *LEO, "--attitude", "lvlh:1e308,0,0"],
                               "lvlh angles 1e+308,0,0 must lie within [-360, 360] deg"),
    "a mass of 1e308 kg": (["orbit", "{d}/box.obj", *BOX, *LEO, "--mass", "1e308"],
                           "--mass 1e+308 kg must be from 0.001 kg to 1e7 kg"),
    "a RAAN of 1e308": (["orbit", "{d}/box.obj", *BOX, "--elements", *ELEMENTS, "--epoch", "2025-03-20",
                         "--srp"], "RAAN 1e+308 deg outside [-360, 360]"),
    "forces --earth-step 1e-9, first": (["forces", "{d}/box.obj", *BOX, "--sun", "1", "0", "0", *GEO_EARTH,
                                         "--earth-step", "1e-9"], "--earth-step 1e-09 cuts"),
    "a reference point at 1e308 m": (["srp", "{d}/box.obj", *BOX, "--sun", "1", "0", "0",
                                      "--ref-point", "1e308", "0", "0"], "has a coordinate beyond 1e+07 m"),
    "a cone 57 million km tall": (["mesh", "cone", "--half-angle-deg", "1e-9", "--rings", "3", "-o",
                                   "{d}/c.obj"], "makes the cone 5.73e+10 m tall"),
}  # fmt: skip


@pytest.mark.parametrize("args, message", CASES.values(), ids=CASES.keys())
def test_one_line_naming_the_fix(run_cli, box, args, message):
    before = (box / "box.obj").read_bytes()
    code, out, err = run_cli(*(str(a).format(d=box) for a in args))
    assert code == 1 and out == "", err
    assert err.startswith("sunwind: error:") and err.count("\n") == 1, err
    assert message.format(d=box) in err and len(err) < 400, err
    assert (box / "box.obj").read_bytes() == before  # no input overwritten


def test_a_reference_point_a_thousand_sizes_away_is_said_and_kept(run_cli, box):
    args = ["srp", box / "box.obj", *BOX, "--sun", "1", "0", "0", "--json"]
    code, out, err = run_cli(*args, "--ref-point", "1000", "0", "0")
    assert code == 0, err
    assert "warning: --ref-point (1000, 0, 0) m lies 1e+03 m outside the model" in err
    assert '"reference_point_m": [\n    1000.0' in out  # the torques are about the point as given
    code, _, err = run_cli(*args, "--ref-point", "2", "0", "0")  # beside the model: nothing said
    assert code == 0 and "warning" not in err, err


def test_a_numpy_warning_is_said_as_a_numerical_problem_to_report(run_cli, box, monkeypatch):
    import numpy as np

    from sunwind.forces.cli import attitude
    from sunwind.geometry.errors import InputError

    def overflowing(*args, **kwargs):
        np.array([1e308]) * 10.0  # what an unchecked input would do deep in a kernel
        raise InputError("stopped after the overflow")

    monkeypatch.setattr(attitude, "srp_of", overflowing)
    code, _, err = run_cli("srp", box / "box.obj", *BOX, "--sun", "1", "0", "0")
    assert code == 1 and "sunwind: error: stopped after the overflow" in err
    assert "sunwind: warning: numerical overflow encountered in multiply (test_second_sweep.py:" in err
    assert "check the results for inf or NaN and report the command line" in err


def test_a_slow_sweep_speed_is_said_once(run_cli, box, tmp_path):
    air = ["--density", "1e-12", "--temperature", "900", "--composition", "O:1"]
    code, _, err = run_cli("sweep", box / "box.obj", "--drag", "--speed", "7.6", *air, "--step", "45",
                           "-o", tmp_path / "slow.nc")  # fmt: skip
    assert code == 0, err
    assert err.count("warning") == 1 and "--speed gives a speed of 7.6 m/s: that looks like km/s" in err


BENCH = {
    "both benchmarks": (["bench", "--sweep", "--orbit"], "--sweep, --orbit and --earth are three benchmarks"),
    "places without the earth": (["bench", "--places", "5"], "--places is the place count of --earth"),
    "no places": (["bench", "--earth", "--places", "0"], "--places 0 must be from 1 to 1000"),
    "a hundred million attitudes": (["bench", "--attitudes", "100000000"], "must be from 1 to 10000"),
    "a sweep of a mesh it does not time": (["bench", "--sweep", "--mesh", "{d}/box.obj", "-m", "{d}/q.csv"],
                                           "--sweep times the generated sample"),
    "a step without the sweep": (["bench", "--step", "10"], "--step is the grid step of --sweep"),
    "a mesh without its materials": (["bench", "--mesh", "{d}/box.obj"], "--mesh and its materials -m"),
}  # fmt: skip


@pytest.mark.parametrize("args, message", BENCH.values(), ids=BENCH.keys())
def test_bench_flags_are_checked_together(run_cli, box, args, message):
    code, out, err = run_cli(*(str(a).format(d=box) for a in args))
    assert code == 1 and out == "" and err.count("\n") == 1 and message in err, err
